"""The stick-slip bifurcation of the quasi-static spring-slider with the direct effect (every
definition here is ours).

Reduced units as in :mod:`.stickslip`: lengths ``a0``, times ``t0``, velocities ``a0/t0``,
forces ``F_el`` (the spring force is reported as friction, ``mu_el = 1``), stiffness
``F_el/a0``. The slider is quasi-static (``M = eta = 0``), where ``K_c`` is finite only with
the direct effect (:func:`~dryfriction.theory.linear_stability.critical_stiffness`).

The perturbation: a *state kick*
---------------------------------
Steady sliding is perturbed by starting from the steady population of a slightly different
velocity, ``Initial("steady", velocity=(1 + state_kick) u)``, with the spring balancing that
population's friction at ``g(u)``. This puts the perturbation into the slow (ageing) degree of
freedom that carries the oscillatory mode. A kick of the spring force instead mostly relaxes
through the fast mode of the direct effect (the slider creeps onto the contacts over a slip
``~ A mu / k_c``, a few hundredths of ``a0``): what is left in the slow mode is then
comparable with the force steps of single trap deaths, and on a regular track the
lattice-periodic sliding captures it (this is why a 1e-3 force kick did not grow at ``u = 1``,
0.7 ``K_c``, in the earlier scans, while a state kick grows at the linear rate).

Growth check (:func:`growth_check`)
-----------------------------------
The spring force ``K (X_pull - X)`` after a state kick is fitted by
``A e^{sigma t} cos(omega t + phi) + c`` (:func:`.stickslip.fit_growth`) over the periods whose
peak-to-peak force stays below ``linear_limit`` times the force of a velocity oscillation of
amplitude ``u`` (the linear window), and ``sigma + i omega`` is compared with
:func:`~dryfriction.theory.stability.rightmost_root` of the direct response at the same ``K``.

Continuation (:func:`continuation`)
-----------------------------------
One ensemble is pulled at ``u`` through a list of stiffnesses ``K = K_c (1 - d)``, ``d`` the
distance ``(K_c - K)/K_c``: down from the first (largest ``K``) to the last, then back up,
each run continuing the previous one's end state (population, position, spring force;
:func:`~dryfriction.ensemble.driving.continue_spring`). Each run lasts ``periods`` linear
periods ``2 pi / omega`` (``omega`` of the rightmost root, or the onset frequency when the
root is real or stable); the **amplitude** is the peak-to-peak spring force over its last
``measure`` periods. The **noise floor** is that amplitude in the first run, above ``K_c``,
where the kick decays: what the lattice and the discretisation leave in steady sliding.
The same capture keeps steady sliding alive on the way down well below ``K_c`` (to 0.7
``K_c`` at ``eps = 0.04``, ``A = 0.02``, 100 traps/``a0``): the way down does not locate the
onset, and the amplitude curve is read on the way up, where each run starts from a cycle.
Classification (:func:`classify`): *subcritical* when on the way up a cycle of amplitude above
``5 x`` the floor survives, not decaying, at some ``K >= K_c`` (hysteresis); otherwise
*supercritical* when the amplitude goes to the floor continuously: the fit
``amplitude = c d^beta`` over the smallest distances gives ``beta`` (1/2 is the Hopf normal
form, ``amplitude^2 ∝ K_c - K``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..ensemble.driving import Output, SpringDrive, continue_spring
from ..ensemble.population import Ensemble, Initial, Track, TrapModel
from ..program import Segment, VelocityProgram
from ..theory.direct import junction_strength
from ..theory.linear_stability import critical_stiffness, linear_response
from ..theory.model import TRAPS_PER_A0, TRAPS_PER_A0_COARSE
from ..theory.stability import rightmost_root
from ..validation import check_scalar
from .stickslip import fit_growth

__all__ = ["kicked_ensemble", "growth_check", "continuation", "classify"]

_SAMPLES = 50  # samples per linear period (ours: resolves the oscillation, cheap to analyse)


def kicked_ensemble(u: float, model: TrapModel, traps_per_a0: float, state_kick: float,
                    horizon: float) -> tuple[Ensemble, float]:
    """Steady population of velocity ``(1 + state_kick) u`` (module docstring) and the spring
    force that balances its friction at ``g(u)``, ``F_el``."""
    ens = Ensemble(model, Track(traps_per_a0), Initial("steady", velocity=(1 + state_kick) * u),
                   age_horizon=horizon)
    return ens, ens.observe().force * float(junction_strength(u, model.direct, model.v_ref))


def _checked(u: float, model: TrapModel, traps_per_a0: float, state_kick: float) -> None:
    # the model was checked when built; what this analysis needs beyond that:
    check_scalar("u", u, 0.0, lo_open=True)
    if model.eps == 0.0:
        raise ValueError("eps = 0 is not allowed here: without ageing there is no instability; "
                         "allowed 0 < eps <= 1")
    TRAPS_PER_A0.check(traps_per_a0)
    check_scalar("state_kick", state_kick, -0.5, 0.5)
    if model.direct == 0.0:
        raise ValueError("direct = 0 is not allowed here: K_c of the quasi-static slider is "
                         "finite only with the direct effect; allowed 0 < direct <= 1")


def growth_check(
    u: float, model: TrapModel, stiffness_factor: float, *,
    traps_per_a0: float = TRAPS_PER_A0_COARSE, state_kick: float = 0.03, periods: float = 4.0,
    linear_limit: float = 1.0,
) -> dict[str, Any]:
    """Simulated growth rate of a state kick at ``K = stiffness_factor K_c`` against the
    linear theory's rightmost root (module docstring).

    Parameters
    ----------
    u : float
        Pulling velocity (``a0/t0``, ``> 0``).
    model : TrapModel
        The trap model, with ``eps > 0`` and the direct effect ``0 < A <= 1`` (``v_ref`` in
        ``a0/t0``).
    stiffness_factor : float
        ``K/K_c``, ``> 0``.
    traps_per_a0 : float
        Density of the regular track.
    state_kick : float
        Relative velocity offset of the initial population, ``|.| <= 0.5``.
    periods : float
        Run length in linear periods ``2 pi/omega``, ``>= 2``.
    linear_limit : float
        The fit stops after the first period whose peak-to-peak spring force exceeds
        ``linear_limit x 2 K u / omega`` (a velocity oscillation of amplitude
        ``linear_limit u``).

    Returns
    -------
    dict
        ``K``, ``K_c``, ``sigma_linear``, ``omega_linear``, ``sigma_sim``, ``omega_sim`` and
        the fit window ``fit_t0``, ``fit_t1`` (``t0``; NaN rates when the fit finds fewer
        than two oscillations, as in a fast decay); ``ptp``, the peak-to-peak spring force
        of each period.
    """
    _checked(u, model, traps_per_a0, state_kick)
    check_scalar("stiffness_factor", stiffness_factor, 0.0, lo_open=True)
    check_scalar("periods", periods, 2.0)
    Kc = critical_stiffness(u, model).critical_stiffness
    K = stiffness_factor * Kc
    lam = rightmost_root(linear_response(u, model), K)
    if lam.imag == 0.0:
        raise ValueError(f"stiffness_factor = {stiffness_factor:g}: the rightmost root is real "
                         "(no oscillation to fit); allowed a K with an oscillatory mode")
    period = 2 * math.pi / abs(lam.imag)
    ens, f0 = kicked_ensemble(u, model, traps_per_a0, state_kick, 4 * periods * period)
    r = continue_spring(ens, SpringDrive(K, 0.0, VelocityProgram(
        [Segment(u, duration=periods * period)])), Output(every=period / _SAMPLES),
        spring_force=f0)
    # the first sample is the start, before any creep step
    y, t = K * (r.x_pull - r.x)[1:], r.t[1:]
    ptp = np.array([np.ptp(y[i:i + _SAMPLES]) for i in range(0, y.size - _SAMPLES + 1,
                                                               _SAMPLES)])
    big = np.flatnonzero(ptp > linear_limit * 2 * K * u / abs(lam.imag))
    # the period that first exceeds the limit is kept: it starts in the linear range
    end = _SAMPLES * (int(big[0]) + 1) if big.size else y.size
    start = _SAMPLES // 5  # the fast relaxation onto the contacts is long over by then
    try:
        s, w = fit_growth(t[start:end], y[start:end])
    except ValueError:  # a decay into the lattice's own force steps: no clean oscillation
        s = w = math.nan
    return {"K": K, "K_c": Kc, "sigma_linear": lam.real, "omega_linear": abs(lam.imag),
            "sigma_sim": s, "omega_sim": w, "fit_t0": float(t[start]),
            "fit_t1": float(t[end - 1]), "ptp": [float(p) for p in ptp]}


def continuation(
    u: float, model: TrapModel, distances: Sequence[float], *,
    traps_per_a0: float = TRAPS_PER_A0_COARSE, state_kick: float = 0.05, periods: float = 15.0,
    measure: float = 4.0, rekick: bool = False,
) -> dict[str, Any]:
    """Continuation in ``K = K_c (1 - d)`` down then up, the amplitude at each ``d`` (module
    docstring).

    Parameters
    ----------
    u, model, traps_per_a0, state_kick
        As :func:`growth_check`.
    distances : sequence of float
        ``d = (K_c - K)/K_c`` of the way down, in increasing order (decreasing ``K``), each
        ``< 1``; the first should be negative (above ``K_c``: it measures the noise floor) and
        the way up runs them in reverse from the end of the way down.
    periods, measure : float
        Run length per stiffness and the final stretch analysed, in linear periods.
    rekick : bool
        On the way down, a run whose predecessor ended in steady sliding (amplitude below
        5x the floor) starts from a fresh state-kicked steady population instead, so that
        the lattice capture of small perturbations does not hide the instability (the
        previous end state *is* steady sliding then; the kick is the only change). The way
        up is always a pure continuation.

    Returns
    -------
    dict
        ``K_c``, ``omega_c``, ``u``, ``floor`` and, for ``"down"`` and ``"up"``, lists of
        ``{"d", "K", "amplitude", "trend", "mean_force", "v_min"}`` (``trend`` the
        peak-to-peak force of the second half of the measured stretch over the first's:
        below 1 the oscillation is still decaying; ``v_min`` the smallest sampled slider
        velocity of the measured stretch, in units of ``u``: near 0 means stick-slip).
    """
    _checked(u, model, traps_per_a0, state_kick)
    ds = [check_scalar("distance", d, -1.0, 1.0, hi_open=True) for d in distances]
    if len(ds) < 2 or any(b <= a for a, b in zip(ds, ds[1:], strict=False)):
        raise ValueError("distances must hold at least two values in increasing order")
    if not 0 < measure < periods:
        raise ValueError(f"measure = {measure:g} is not allowed: 0 < measure < periods "
                         f"= {periods:g}")
    lin = critical_stiffness(u, model)
    Kc = lin.critical_stiffness
    resp = linear_response(u, model)

    def period(K: float) -> float:
        lam = rightmost_root(resp, K)
        om = abs(lam.imag) if lam.imag != 0.0 and lam.real > -abs(lam.imag) else lin.omega
        return 2 * math.pi / om

    total = 2 * len(ds) * periods * max(period(Kc * (1 - d)) for d in ds)
    ens, force = kicked_ensemble(u, model, traps_per_a0, state_kick, 2 * total)
    out: dict[str, Any] = {"K_c": Kc, "omega_c": lin.omega, "u": u, "direct": model.direct,
                           "traps_per_a0": traps_per_a0, "rekick": rekick, "down": [],
                           "up": []}
    for leg, order in (("down", ds), ("up", ds[::-1][1:])):
        for d in order:
            K = Kc * (1 - d)
            p = period(K)
            if rekick and leg == "down" and out["down"] and (
                    out["down"][-1]["amplitude"] < 5.0 * out["down"][0]["amplitude"]):
                ens, force = kicked_ensemble(u, model, traps_per_a0, state_kick, 2 * total)
            r = continue_spring(ens, SpringDrive(K, 0.0, VelocityProgram(
                [Segment(u, duration=periods * p)])), Output(every=p / _SAMPLES),
                spring_force=force)
            y = K * (r.x_pull - r.x)
            tail = r.t >= r.t[-1] - measure * p
            late = r.t >= r.t[-1] - 0.5 * measure * p
            early = tail & ~late
            out[leg].append({"d": d, "K": K, "amplitude": float(np.ptp(y[tail])),
                             "trend": float(np.ptp(y[late]) / max(np.ptp(y[early]), 1e-300)),
                             "mean_force": float(np.mean(y[tail])),
                             "v_min": float(np.min(r.v[tail]) / u)})
            force = float(y[-1])
    out["floor"] = out["down"][0]["amplitude"]
    out.update(classify(out))
    return out


def classify(scan: dict[str, Any], factor: float = 5.0, n_fit: int = 4,
             decaying: float = 0.9) -> dict[str, Any]:
    """Bifurcation type of a :func:`continuation` result (module docstring).

    Returns ``{"type": "subcritical" | "supercritical" | "undetermined", "exponent": beta,
    "hysteresis_d": [...]}``: ``beta`` fitted (log-log least squares) over the ``n_fit``
    smallest positive distances of the way up whose amplitude exceeds ``factor x`` floor,
    NaN when fewer than two; ``hysteresis_d`` the distances ``<= 0`` (``K >= K_c``) where the
    way up still oscillates above ``factor x`` floor without decaying (``trend``, where
    given, above ``decaying``: a linearly stable state close to ``K_c`` decays slowly, over
    more periods than a run lasts).
    """
    thr = factor * scan["floor"]
    hyst = [r["d"] for r in scan["up"] if r["d"] <= 0.0 and r["amplitude"] > thr
            and r.get("trend", 1.0) > decaying]
    pts = sorted((r["d"], r["amplitude"]) for r in scan["up"]
                 if r["d"] > 0.0 and r["amplitude"] > thr)[:n_fit]
    beta = math.nan
    if len(pts) >= 2:
        d, a = np.log(np.array(pts)).T
        beta = float(np.polyfit(d, a, 1)[0])
    if hyst:
        kind = "subcritical"
    elif len(pts) >= 2:
        kind = "supercritical"
    else:
        kind = "undetermined"
    return {"type": kind, "exponent": beta, "hysteresis_d": hyst}
