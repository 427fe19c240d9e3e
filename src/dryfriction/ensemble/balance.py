"""The quasi-static slider's force balance: jumps between equilibria, creep steps with the
direct effect (:mod:`dryfriction.ensemble.driving`'s module docstring says when each is used).

:func:`equilibrate` moves the slider, ages frozen, to the next stable root of
``A - K X - g F(X) = 0`` stretch by stretch between the population's events (spinodals,
births, exits), where ``F`` is continuous; :func:`root_in_bracket` polishes the root inside a
stretch by Newton steps with the slope the kernel returns (``dF/dX``) and the strength's
``g'`` (:mod:`.thermal`), each kept inside the bracket (ours).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from .population import Ensemble, Observables
from .thermal import VelocityScale

__all__ = ["TINY", "add_events", "equilibrate", "events", "root_in_bracket"]

TINY = 1e-10
"""How far past a spinodal the slider is moved to kill the trap, ``a0`` (ours)."""

EPS = float(np.finfo(float).eps)


def events(o: Observables) -> tuple[int, int, int]:
    return (o.births, o.spinodal, o.exits)


def add_events(a: tuple[int, int, int], b: tuple[int, int, int]) -> tuple[int, int, int]:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def equilibrate(
    ens: Ensemble, A: float, K: float, max_slip: float,
    scale: VelocityScale | None = None,
) -> tuple[float, bool, tuple[int, int, int]]:
    """Jump, ages frozen, to the next stable root of ``A - K X - F(X) = 0``.

    With ``scale`` (direct effect) the force is ``scale(X) F(X)``: the root is then the end of
    a creep step rather than of a jump (module docstring). Between two events the root is
    polished by :func:`root_in_bracket` with the slope ``dF/dX`` the kernel returns.

    Returns
    -------
    extreme : float
        The largest (forward jump) or smallest (backward) force met on the way: at the
        spinodals passed (left limits) and at the end. The exact peak of a forward jump.
    runaway : bool
        True if no root lies within ``max_slip``; the slider is then left at the end of the
        search.
    events : tuple of int
        (births, spinodal, exits) during the jump.
    """
    def eff(f: float, x: float) -> float:
        return f if scale is None else scale(x) * f

    def balance(o: Observables, x: float) -> tuple[float, float]:
        """``G(X) = A - K X - g F`` and ``dG/dX`` from the observables at ``X``."""
        if scale is None:
            return A - K * x - o.force, -K - o.stiffness
        g = scale(x)
        slope = scale.slope(x) * o.force if o.force != 0.0 else 0.0
        return A - K * x - g * o.force, -K - g * o.stiffness - slope

    o = ens.observe(1, stiffness=True)
    G0 = A - K * ens.x - eff(o.force, ens.x)
    tol = 1e-13 * max(1.0, abs(A))
    if abs(G0) <= tol:
        return eff(o.force, ens.x), False, (0, 0, 0)
    d = 1 if G0 > 0 else -1
    start = ens.x
    extreme = eff(o.force, ens.x)
    ev = (0, 0, 0)
    if d < 0:  # the next event backwards (the force is the same)
        o = ens.observe(d, stiffness=True)
    while True:
        xe = o.next_event
        capped = abs(xe - start) > max_slip
        if capped:
            xe = start + d * max_slip
        xb = xe - d * TINY
        if (xb - ens.x) * d <= 0.0:  # the event is within rounding of here: step past it
            xb = ens.x
        pb = ens.probe(xb, d, stiffness=True)
        fb = eff(pb.force, xb)
        Gb = A - K * xb - fb
        if math.isnan(Gb):  # no root can be bracketed: the search would walk max_slip
            # (1e9 a0 for the spring) event by event without a line (issue 24)
            raise ValueError(f"the trap force is not a number at t = {ens.t:.6g} t0, x = "
                             f"{xb:.6g} a0: the quasi-static jump cannot find its equilibrium")
        if Gb * d <= 0.0:
            xa = ens.x
            ga, sa = balance(o, xa)
            if xb == xa or ga * d <= 0.0:
                root = xa
            else:
                root = root_in_bracket(
                    lambda x: balance(ens.probe(x, d, stiffness=True), x),
                    xa, (ga, sa), xb, balance(pb, xb), tol)
            ob = ens.advance(root, ens.t)
            fr = eff(ob.force, root)
            extreme = max(extreme, fr) if d > 0 else min(extreme, fr)
            return extreme, False, add_events(ev, events(ob))
        # the slider passes this stretch: its end (the spinodal's left limit) is a local extreme
        extreme = max(extreme, fb) if d > 0 else min(extreme, fb)
        if capped:
            ob = ens.advance(xb, ens.t)
            return extreme, True, add_events(ev, events(ob))
        ev = add_events(ev, events(ens.advance(xe + d * TINY, ens.t)))
        o = ens.observe(d, stiffness=True)


def root_in_bracket(h: Callable[[float], tuple[float, float]], xa: float,
                     ha: tuple[float, float], xb: float, hb: tuple[float, float],
                     g_tol: float = 0.0) -> float:
    """The root of ``G`` between ``xa`` and ``xb`` (``G(xa)``, ``G(xb)`` of opposite signs or
    ``G(xb) = 0``), ``h(x) = (G(x), G'(x))``: Newton steps from the end nearer the root, each
    kept inside the shrinking bracket, a bisection where a step would leave it or would not
    halve the step before (ours; a safeguarded Newton iteration).

    It ends when ``G`` changes sign across a step under ``tol = 1e-13`` absolute and 4 ulps
    relative, the tolerance Brent's method was given before, in about a third of its
    evaluations (each one is a pass of the kernel over the pairs in contact). A small step
    alone proves nothing: at the start of a creep step the strength's slope ``g'(0)/dt`` is
    huge, and the Newton step is tiny however far the root is; so a small step is confirmed by
    one evaluation just past it, unless ``|G|`` is already within ``g_tol`` there.
    """
    (ga, sa), (gb, sb) = ha, hb
    if gb == 0.0:
        return xb
    lo, hi = (xa, xb) if ga < 0.0 else (xb, xa)  # G(lo) < 0 < G(hi)
    x, g, s = (xa, ga, sa) if abs(ga) < abs(gb) else (xb, gb, sb)
    step_old = step = abs(xb - xa)
    for _ in range(200):
        if abs(hi - lo) <= 2e-13 + 8.0 * EPS * abs(x):
            return 0.5 * (lo + hi)
        newton_ok = (math.isfinite(s) and s != 0.0
                     and ((x - hi) * s - g) * ((x - lo) * s - g) < 0.0
                     and abs(2.0 * g) <= abs(step_old * s))
        step_old = step
        if newton_ok:
            step = g / s
            x_new = x - step
        else:
            step = 0.5 * (hi - lo)
            x_new = lo + step
        tol = 1e-13 + 4.0 * EPS * abs(x_new)
        if newton_ok and abs(step) <= tol and abs(g) <= g_tol:
            return x_new
        if newton_ok and abs(step) <= tol:
            # confirm: the root lies within tol of x_new if G changes sign just past it
            beyond = x_new - math.copysign(tol, step)
            gc, sc = h(beyond)
            if gc == 0.0 or (gc < 0.0) != (g < 0.0):
                return x_new
            x, g, s = beyond, gc, sc  # not there yet: go on from the point just past
        else:
            x = x_new
            g, s = h(x)
            if g == 0.0:
                return x
        if g < 0.0:
            lo = x
        else:
            hi = x
    return x
