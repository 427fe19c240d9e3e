"""Steady sliding: the dynamic friction force (paper §5, docs/model.md §4).

At reduced velocity ``u = V/V*``, ``V* = a0/t0``, a trap born at ``y = p/a0 = -1`` has age
``(y + 1)/u`` (eq. 29), radius ratio ``r(y) = a_r((y + 1)/u)`` (eq. 30) and force
``r^2 f(y/r)`` in units ``Phi00/a0`` (eq. 31); it dies where ``y/r(y) = y_c`` (eq. 32) in very
strong pinning. In strong pinning (ours) it jumps there onto the (-) branch and dies where
``y/r(y) = 1``. States are filled uniformly with density ``1/(2 a0)`` (eq. 33), so

    mu_d(u) = (1/H0) int_{-1}^{y_d} r(y)^2 f(y / r(y)) dy            (eq. 34)

**Quadrature (ours).** The integral is taken in the creep law's clock ``c`` (``c = ln(1 + T)``
for the log law), in which ``r^2`` is smooth and the boundary layer of width ``u`` at ``y = -1``
disappears: ``dy = u T'(c) dc``. The force has a square-root singularity where the trap reaches
its spinodal; the substitution ``c = c_d (1 - tau^2)`` removes it. Fixed Gauss-Legendre rules
then give close to rounding accuracy at a fixed cost, vectorised over ``u``.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike

from ..validation import (
    EPS_MAX,
    U_MAX,
    U_MIN,
    Array,
    check_alpha,
    check_broadcast,
    check_choice,
    check_direct,
    check_finite_result,
    check_range,
    check_scalar,
)
from .creep import CREEP_LAWS, CreepLaw, EyringNabarroCreep, per_eps
from .direct import junction_log_slope, junction_strength
from .model import TrapModel, takes_model
from .trap import Trap, force_forward, force_minus, force_plus

__all__ = [
    "steady_friction",
    "steady_friction_over_eps",
    "min_velocity",
    "check_steady_inputs",
    "steady_death_point",
    "death_clock",
    "steady_profile",
    "steady_friction_first_order",
    "steady_friction_low_velocity",
    "steady_log_slope",
    "steady_log_slope_low_velocity",
    "low_velocity_constant",
    "DYNAMIC_SLOPE_PER_EPS",
    "athermal_steady_weakens",
]


DYNAMIC_SLOPE_PER_EPS: float = -1.5
"""``(1/eps) d mu_d / d ln u`` for ``u << 1`` (eq. 35 reading): ``-3/2``, independent of alpha."""


def _rule(n: int) -> tuple[Array, Array]:
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


_TAU, _TAU_W = _rule(48)  # piece up to the (+) spinodal, in tau
_ETA, _ETA_W = _rule(32)  # (-) branch piece, strong pinning


def _graded(L: Array, delta: Array) -> tuple[Array, Array]:
    """Nodes ``x`` in ``[0, L]`` and weights for a function with a branch point at ``x = -delta``.

    ``x = delta (exp(eta ln(1 + L/delta)) - 1)``: uniform in ``ln(x + delta)``, which makes
    ``sqrt(x + delta)`` smooth however small ``delta/L`` is (ours).
    """
    lam = np.log1p(L / delta)
    e = np.exp(lam * _ETA)
    return delta * (e - 1.0), delta * lam * e * _ETA_W


def _minus_branch_nodes(c_d: Array, c_e: Array, yc: float) -> tuple[Array, Array]:
    # f_- has its branch point at w = -y_c, a distance 2 y_c before the piece [y_c, 1]; in the
    # clock the piece has length c_e - c_d for a change of w of 1 - y_c.
    L = c_e - c_d
    x, wts = _graded(L, L * 2.0 * yc / (1.0 - yc))
    return c_d + x, wts


def _min_velocity_loose(eps: float, alpha: float = 0.13, creep: str = "eyring-nabarro"
                        ) -> float:
    """:func:`min_velocity` with the parameters loose (its old form; note its default creep
    law, Eyring-Nabarro, where :class:`TrapModel`'s is the log law).
    Smallest ``u`` at which steady sliding stays inside the creep law's range (ours).

    A trap dies where ``-1 + u T = w_d a_r(T)`` (eq. 32; ``w_d`` = :attr:`Trap.death_point`).
    The Eyring-Nabarro law holds up to the age ``T_v`` where ``a_r^2 = 1/eps``
    (:func:`dryfriction.theory.creep.max_age`). On the clock interval ``[0, Q_v]``,
    ``g(Q) = -1 + u T(Q) - w a_r(Q)`` has ``g' = (u e^Q - w eps / (2 sqrt(b)))/b``, ``b = 1 - eps
    Q``, and ``ln(u e^Q 2 sqrt(b) / (w eps))`` has slope ``1 - eps/(2b) > 0`` there: ``g``
    falls, then rises, so the death lies inside the range exactly when ``g(Q_v) >= 0``, i.e.

        u >= u_min = (1 + w_d / sqrt(eps)) / T_v(eps).

    The log law has no such limit (0 is returned).
    """
    check_choice("creep", creep, CREEP_LAWS)
    eps = check_scalar("eps", eps, 0.0, EPS_MAX)
    if creep == "log" or eps == 0.0:
        return 0.0
    w_d = Trap(check_alpha(alpha)).death_point
    t_v = EyringNabarroCreep(eps).max_age
    return (1.0 + w_d / math.sqrt(eps)) / t_v if t_v > 0 else math.inf


@takes_model(_min_velocity_loose, "min_velocity(eps, alpha, creep)", "min_velocity(model)")
def min_velocity(model: TrapModel) -> float:
    """Smallest reduced velocity ``u`` at which steady sliding of ``model`` stays inside its
    creep law's range (ours).

    A trap dies where ``-1 + u T = w_d a_r(T)`` (eq. 32; ``w_d`` = :attr:`Trap.death_point`);
    the Eyring-Nabarro law holds up to the age ``T_v`` where ``a_r^2 = 1/eps``, so (see the
    derivation in :func:`_min_velocity_loose`)

        u_min = (1 + w_d / sqrt(eps)) / T_v(eps).

    Uses ``model.alpha``, ``eps`` and ``creep``; the log law has no such limit (0 is
    returned), nor has ``eps = 0``. ``direct`` and ``v_ref`` do not enter (the direct effect
    leaves the trap dynamics alone).

    Returns
    -------
    float
        ``u_min`` in ``a0/t0`` (``inf`` if the law has no range left).
    """
    return _min_velocity_loose(model.eps, model.alpha, model.creep)


def _check_velocity(u: Array, eps: Array, alpha: float, creep: str) -> None:
    """Refuse velocities whose traps die beyond the creep law's range (:func:`min_velocity`)."""
    if creep == "log":
        return
    u_b, eps_b = np.broadcast_arrays(u, eps)
    for e in np.unique(eps_b):
        u_min = _min_velocity_loose(float(e), alpha, creep)
        low = (eps_b == e) & (u_b < u_min)
        if np.any(low):
            t_v = EyringNabarroCreep(float(e)).max_age
            raise ValueError(
                f"u = {float(u_b[low].flat[0]):g} is beyond the Eyring-Nabarro law's range at "
                f"eps = {float(e):g}: its traps would die older than T = {t_v:.4g}, where the "
                "contact stress has relaxed to S (a_r^2 = 1/eps) and the contact runs away; "
                f"use u >= {u_min:.4g} or creep = log (--creep log)"
            )


def check_steady_inputs(u: ArrayLike, eps: ArrayLike, alpha: float, creep: str
                  ) -> tuple[float, Array, Array]:
    """Every check of the steady-sliding entry points, before any work.

    Returns ``(alpha, u, eps)`` as floats and arrays; raises ``ValueError`` naming the
    parameter and its allowed range (also used by the ``stability`` command).
    """
    alpha = check_alpha(alpha)
    check_choice("creep", creep, CREEP_LAWS)
    u_a = check_range("u", u, U_MIN, U_MAX)
    eps_a = check_range("eps", eps, 0.0, EPS_MAX)
    check_broadcast(u=u_a, eps=eps_a)
    _check_velocity(u_a, eps_a, alpha, creep)
    return alpha, u_a, eps_a


def death_clock(law: CreepLaw, u: Array, w_end: float) -> Array:
    """Clock ``c`` at which ``y(c)/r(c) = w_end``, ``y(c) = -1 + u T(c)`` (eq. 32).

    ``g(c) = -1 + u T(c) - w_end r(c)`` is increasing and convex in ``c`` for the log law, and
    falls then rises up to the end ``Q_v`` of the Eyring-Nabarro law's range
    (:func:`min_velocity`); Newton's method from the lower bound ``c(T = (w_end + 1)/u)`` with
    a bisection safeguard, each point iterated until it alone has converged.
    """
    c_max = law.valid_clock if isinstance(law, EyringNabarroCreep) else math.inf
    lo = law.clock((w_end + 1.0) / u)
    hi = np.full_like(lo, c_max)
    if math.isfinite(c_max):
        g_hi = -1.0 + u * law.age(hi) - w_end * np.sqrt(law.radius_sq(hi))
        # rounding may put g(Q_v) a hair below 0 at u = u_min: the root is then Q_v itself
        if np.any(g_hi < -1e-9 * (1.0 + u * law.age(hi))):
            raise ValueError(
                f"u = {float(u[np.argmax(g_hi < 0)]):g} is beyond the Eyring-Nabarro law's "
                f"range at eps = {law.eps:g}: its traps would die after the contact runs away; "
                "use a larger u or creep = log"
            )
    c = lo.copy()
    # a converged point must not move while its neighbours still iterate (alone or in an
    # array: the same answer), so only the active points are updated
    act = np.arange(c.size)
    for _ in range(200):
        ca, ua, lo_a, hi_a = c[act], u[act], lo[act], hi[act]
        R = law.radius_sq(ca)
        g = -1.0 + ua * law.age(ca) - w_end * np.sqrt(R)
        lo_a = np.where(g <= 0, ca, lo_a)
        hi_a = np.where(g >= 0, ca, hi_a)
        dg = ua * law.dage(ca) - w_end * law.dradius_sq(ca) / (2.0 * np.sqrt(R))
        with np.errstate(divide="ignore", invalid="ignore"):
            cn = ca - g / dg
        bad = ~np.isfinite(cn) | (cn < lo_a) | (cn > hi_a)
        mid = np.where(np.isfinite(hi_a), 0.5 * (lo_a + hi_a), 2.0 * lo_a + 1.0)
        cn = np.where(bad, mid, cn)
        # a bracket a few ulps wide is converged too: Newton can hop between two floats either
        # side of the root for ever (seen at u = 0.3121... with the Eyring-Nabarro law)
        done = ((np.abs(cn - ca) <= 4e-16 * np.maximum(1.0, np.abs(ca)))
                | (hi_a - lo_a <= 4.0 * np.spacing(np.abs(ca))))
        c[act], lo[act], hi[act] = cn, lo_a, hi_a
        act = act[~done]
        if act.size == 0:
            return c
    raise RuntimeError("steady sliding: the death point did not converge")  # pragma: no cover


def _steady_one_law(law: CreepLaw, u: Array, alpha: float) -> Array:
    trap = Trap(alpha)
    yc = trap.y_c
    c_d = death_clock(law, u, yc)[:, None]
    # piece 1: (+) branch, c = c_d (1 - tau^2), smooth in tau despite the spinodal singularity
    c = c_d * (1.0 - _TAU**2)
    R = law.radius_sq(c)
    y = -1.0 + u[:, None] * law.age(c)
    w = np.minimum(y / np.sqrt(R), yc)
    integrand = u[:, None] * law.dage(c) * R * force_plus(w, alpha) * 2.0 * c_d * _TAU
    # a sum along the rule, not a matrix product: each u summed alike whatever the batch
    total = np.sum(integrand * _TAU_W, axis=-1)
    if yc < 1.0:  # strong pinning: continue on the (-) branch up to w = 1
        c_e = death_clock(law, u, 1.0)[:, None]
        c, wts = _minus_branch_nodes(c_d, c_e, yc)
        R = law.radius_sq(c)
        y = -1.0 + u[:, None] * law.age(c)
        w = np.clip(y / np.sqrt(R), yc, 1.0)
        integrand = u[:, None] * law.dage(c) * R * force_minus(w, alpha) * wts
        total = total + integrand.sum(axis=-1)
    return total / trap.H0


def _steady_friction_loose(
    u: ArrayLike, eps: ArrayLike, alpha: float = 0.13, creep: str = "log",
    direct: float = 0.0, v_ref: float = 1.0,
) -> Array:
    """:func:`steady_friction` with the parameters loose and ``eps`` broadcast with ``u`` (its
    old form, and the vectorised core of :func:`steady_friction_over_eps`). Steady dynamic
    friction ``mu_d = F_d/F_el`` at reduced velocity ``u = V t0/a0`` (eq. 34).

    With the direct effect (``direct = A > 0``, :mod:`.direct`, ours) the junction strength at
    the sliding velocity multiplies the aged population's force: ``mu = g(u) mu_d(u)``.

    Parameters
    ----------
    u : array_like
        Reduced sliding velocity ``V/V*``, ``V* = a0/t0``; ``> 0``.
    eps : array_like
        Creep parameter ``S/Y``, ``>= 0`` (broadcast with ``u``).
    alpha : float
        Reduced trap stiffness, ``0 < alpha < 1`` (0.13 in the paper).
    creep : {"log", "eyring-nabarro"}
        Ageing law (eq. 17 or eqs. 15-16).
    direct : float
        Direct-effect coefficient ``A``, ``0 <= A <= 1`` (0: the athermal model, same code path).
    v_ref : float
        Reference velocity of the junction rheology, reduced ``a0/t0``, ``> 0``.

    Returns
    -------
    ndarray
        ``mu_d``; tends to 1 for ``u -> inf`` and grows like ``-(3/2) eps ln u`` for ``u -> 0``
        (times ``g(u)`` when ``direct > 0``).
    """
    direct, v_ref = check_direct(direct, v_ref)
    alpha, u, eps = check_steady_inputs(u, eps, alpha, creep)
    mu = per_eps(
        lambda law, x: _steady_one_law(law, np.atleast_1d(x), alpha).reshape(x.shape),
        creep,
        eps,
        u,
    )
    if direct != 0.0:
        mu = mu * junction_strength(u, direct, v_ref)
    return check_finite_result("mu_d", mu, u=u, eps=eps)


@takes_model(_steady_friction_loose, "steady_friction(u, eps, alpha, creep, direct, v_ref)",
             "steady_friction(model, u)")
def steady_friction(model: TrapModel, u: ArrayLike) -> Array:
    """Steady dynamic friction ``mu_d = F_d/F_el`` of ``model`` at reduced velocity
    ``u = V t0/a0`` (eq. 34).

    With the direct effect (``model.direct = A > 0``, :mod:`.direct`, ours) the junction
    strength at the sliding velocity multiplies the aged population's force:
    ``mu = g(u) mu_d(u)``. ``model.mu_el`` does not enter: the result is ``F/F_el``.

    Parameters
    ----------
    model : TrapModel
        ``alpha``, ``eps``, ``creep``, ``direct`` and ``v_ref`` (reduced ``a0/t0``).
    u : array_like
        Reduced sliding velocity ``V/V*``, ``V* = a0/t0``; ``> 0``.

    Returns
    -------
    ndarray
        ``mu_d``, the shape of ``u``; tends to 1 for ``u -> inf`` and grows like
        ``-(3/2) eps ln u`` for ``u -> 0`` (times ``g(u)`` when ``direct > 0``). For a sweep
        over ``eps`` in one call see :func:`steady_friction_over_eps`.
    """
    return _steady_friction_loose(u, model.eps, model.alpha, model.creep, model.direct,
                                  model.v_ref)


def steady_friction_over_eps(model: TrapModel, u: ArrayLike, eps: ArrayLike) -> Array:
    """:func:`steady_friction` of ``model`` with its ``eps`` replaced by every value of ``eps``,
    broadcast with ``u``: a sweep over the creep parameter in one vectorised call (the paper's
    figures; the quadrature is batched by value of ``eps``, as for one model). ``eps`` is
    checked like ``model.eps`` (``0 <= eps <= 1``); ``model.eps`` is not used.

    ``steady_friction_over_eps(model, u, e)`` at a scalar ``e`` equals
    ``steady_friction(model.replace(eps=e), u)``.
    """
    return _steady_friction_loose(u, eps, model.alpha, model.creep, model.direct, model.v_ref)


def _steady_log_slope_loose(
    u: ArrayLike, eps: ArrayLike, alpha: float = 0.13, creep: str = "log",
    direct: float = 0.0, v_ref: float = 1.0,
) -> Array:
    """:func:`steady_log_slope` with the parameters loose, ``eps`` broadcast with ``u`` (its
    old form). ``d mu / d ln u`` of :func:`steady_friction` (ours).

    ``u g'(u) mu_d + g(u) d mu_d/d ln u``: the direct term (``-> A mu_d`` above the rheology's
    crossover) plus the ageing term (``-> -(3/2) eps`` for ``u << 1``, eq. 35). The ageing
    slope is a central difference in ``ln u`` (step 1e-4; the quadrature is smooth in ``u``).
    """
    direct, v_ref = check_direct(direct, v_ref)
    alpha, u, eps = check_steady_inputs(u, eps, alpha, creep)
    h = 1e-4
    up = _steady_friction_loose(u * np.exp(h), eps, alpha, creep)
    dn = _steady_friction_loose(u * np.exp(-h), eps, alpha, creep)
    slope = (up - dn) / (2.0 * h)
    if direct == 0.0:
        return slope
    mu = _steady_friction_loose(u, eps, alpha, creep)
    return junction_log_slope(u, direct, v_ref) * mu + junction_strength(u, direct, v_ref) * slope


@takes_model(_steady_log_slope_loose, "steady_log_slope(u, eps, alpha, creep, direct, v_ref)",
             "steady_log_slope(model, u)")
def steady_log_slope(model: TrapModel, u: ArrayLike) -> Array:
    """``d mu / d ln u`` of :func:`steady_friction` of ``model`` at reduced velocity ``u`` (ours).

    ``u g'(u) mu_d + g(u) d mu_d/d ln u``: the direct term (``-> A mu_d`` above the rheology's
    crossover) plus the ageing term (``-> -(3/2) eps`` for ``u << 1``, eq. 35). The ageing
    slope is a central difference in ``ln u`` (step 1e-4; the quadrature is smooth in ``u``).

    Parameters
    ----------
    model : TrapModel
        ``alpha``, ``eps``, ``creep``, ``direct`` and ``v_ref`` (reduced ``a0/t0``).
    u : array_like
        Reduced sliding velocity ``V t0/a0``, ``> 0``.

    Returns
    -------
    ndarray
        ``d mu/d ln u`` (friction in ``F_el``), the shape of ``u``.
    """
    return _steady_log_slope_loose(u, model.eps, model.alpha, model.creep, model.direct,
                                   model.v_ref)


@lru_cache(maxsize=64)
def athermal_steady_weakens(alpha: float, creep: str = "log") -> bool:
    """Whether the athermal model's steady friction (eq. 34, ``direct = 0``) at trap stiffness
    ``alpha`` falls with velocity everywhere: ``d mu_d/d ln u <= 0`` at every ``eps`` and ``u``
    (ours, numerical: :func:`steady_log_slope` on ``eps`` = 1e-4 .. 1, 13 values, and ``u`` =
    1e-20 .. 1e20, 81 values, within the creep law's range, :func:`min_velocity`; a slope above
    ``1e-6 eps`` counts as growth, the rest is the central difference's rounding).

    The traps of faster sliding die younger (eq. 29), less aged (eq. 17): ``-(3/2) eps`` at
    ``u << 1`` (eq. 35). It holds for ``alpha <= 0.3`` with both creep laws; from about 0.35
    (0.4 with the log law) ``mu_d`` rises over some velocities, so data that rise do not
    contradict the model there. Steady data whose friction grows with velocity contradict the
    first kind (:meth:`dryfriction.fit.models.CVModel.allowed_trend`).

    Parameters
    ----------
    alpha : float
        Trap stiffness.
    creep : str
        Creep law (:data:`CREEP_LAWS`).
    """
    u = np.logspace(-20.0, 20.0, 81)
    for eps in np.logspace(-4.0, 0.0, 13):
        model = TrapModel(alpha, float(eps), creep)
        lo = min_velocity(model) * 1.01  # the Eyring-Nabarro law's range
        inside = u[u > lo]
        if not inside.size:
            continue
        # the exact law's exponentials overflow at the range's far end: not a slope there
        with np.errstate(over="ignore", invalid="ignore"):
            slope = steady_log_slope(model, inside)
        if np.any(slope[np.isfinite(slope)] > 1e-6 * eps):
            return False
    return True


def _steady_death_point_loose(
    u: ArrayLike, eps: ArrayLike, alpha: float = 0.13, creep: str = "log"
) -> Array:
    """:func:`steady_death_point` with the parameters loose, ``eps`` broadcast with ``u`` (its
    old form)."""
    alpha, u, eps = check_steady_inputs(u, eps, alpha, creep)
    yc = Trap(alpha).y_c

    def one(law: CreepLaw, x: Array) -> Array:
        x1 = np.atleast_1d(x)
        return (-1.0 + x1 * law.age(death_clock(law, x1, yc))).reshape(x.shape)

    return per_eps(one, creep, eps, u)


@takes_model(_steady_death_point_loose, "steady_death_point(u, eps, alpha, creep)",
             "steady_death_point(model, u)")
def steady_death_point(model: TrapModel, u: ArrayLike) -> Array:
    """Where a trap of ``model`` sliding steadily at reduced velocity ``u`` leaves the (+)
    branch, ``p_d/a0`` with ``p_d/a(p_d) = y_c`` (eq. 32).

    Uses ``model.alpha``, ``eps`` and ``creep``; the direct effect scales the friction force,
    not the trap dynamics (:mod:`.direct`), so ``direct`` and ``v_ref`` do not enter.

    Returns
    -------
    ndarray
        ``p_d/a0``, the shape of ``u``.
    """
    return _steady_death_point_loose(u, model.eps, model.alpha, model.creep)


def _steady_profile_loose(
    y: ArrayLike, u: float, eps: float, alpha: float = 0.13, creep: str = "log"
) -> Array:
    """:func:`steady_profile` with the parameters loose (its old form)."""
    alpha = check_alpha(alpha)
    check_choice("creep", creep, CREEP_LAWS)
    u = check_scalar("u", u, U_MIN, U_MAX)
    eps = check_scalar("eps", eps, 0.0, EPS_MAX)
    _check_velocity(np.asarray(u), np.asarray(eps), alpha, creep)
    y = check_range("y", y)
    from .creep import creep_law

    law = creep_law(creep, eps)
    r = law.radius(np.maximum(y + 1.0, 0.0) / u)
    w = y / r
    # the death point in y: once passed, the trap is gone even if w falls back below it
    y_end = -1.0 + u * float(law.age(death_clock(law, np.array([u]), Trap(alpha).death_point))[0])
    f = r**2 * force_forward(w, alpha)
    return np.where((y >= -1.0) & (y <= y_end), f, 0.0)


@takes_model(_steady_profile_loose, "steady_profile(y, u, eps, alpha, creep)",
             "steady_profile(model, y, u)")
def steady_profile(model: TrapModel, y: ArrayLike, u: float) -> Array:
    """Force of a trap of ``model`` at ``y = p/a0`` in steady sliding at reduced velocity ``u``,
    units ``Phi00/a0`` (eq. 31, Fig. 4).

    ``r(y)^2 f(y/r(y))`` for traps in contact, 0 before contact (``y < -1``) and after death.
    Uses ``model.alpha``, ``eps`` and ``creep``: the population's force, before the direct
    effect's factor ``g(u)`` (:mod:`.direct`), which does not change the trap dynamics.
    """
    return _steady_profile_loose(y, u, model.eps, model.alpha, model.creep)


def _steady_first_order_loose(u: ArrayLike, eps: ArrayLike, alpha: float = 0.13) -> Array:
    """First order in ``eps`` of eq. 34 for any ``u`` (ours), parameters loose, ``eps``
    broadcast with ``u`` (the old form of :func:`steady_friction_first_order`).

    Expanding ``r^2 f(y/r)`` and the moving death point to first order and integrating by parts
    (the boundary terms cancel): ``mu_d ~ 1 + (eps / 2 H0) int_{-1}^{death}
    [3 ln(1 + (y + 1)/u) + y/(u + y + 1)] f(y) dy``. Tends to eq. 35 as ``u -> 0`` and to
    ``1 + (eps / 2 u H0) int (4 y + 3) f dy`` as ``u -> inf``.
    """
    alpha, u, eps = check_steady_inputs(u, eps, alpha, "log")
    trap = Trap(alpha)
    ub = np.atleast_1d(u)[..., None].astype(float)

    def piece(w_lo: float, w_hi: float, sing: bool) -> Array:
        # clock c = ln(1 + (y+1)/u); y = -1 + u (e^c - 1); dy = u e^c dc
        c0 = np.log1p((w_lo + 1.0) / ub)
        c1 = np.log1p((w_hi + 1.0) / ub)
        if sing:
            c = c1 - (c1 - c0) * _TAU**2
            wts = 2.0 * (c1 - c0) * _TAU * _TAU_W
        else:
            c, wts = _minus_branch_nodes(c0, c1, trap.y_c)
        y = np.minimum(-1.0 + ub * np.expm1(c), trap.death_point)
        g = 3.0 * c * ub * np.exp(c) + y
        return (g * force_forward(y, alpha) * wts).sum(axis=-1)

    total = piece(-1.0, trap.y_c, True)
    if trap.y_c < 1.0:
        total = total + piece(trap.y_c, 1.0, False)
    out = 1.0 + eps * total.reshape(np.shape(u)) / (2.0 * trap.H0)
    return out


@takes_model(_steady_first_order_loose, "steady_friction_first_order(u, eps, alpha)",
             "steady_friction_first_order(model, u)")
def steady_friction_first_order(model: TrapModel, u: ArrayLike) -> Array:
    """First order in ``model.eps`` of eq. 34 for any ``u`` (ours), times ``g(u)`` with the
    direct effect (``model.direct > 0``).

    ``mu_d ~ 1 + (eps / 2 H0) int_{-1}^{death} [3 ln(1 + (y + 1)/u) + y/(u + y + 1)] f(y) dy``
    (expanding ``r^2 f(y/r)`` and the moving death point to first order and integrating by
    parts; the boundary terms cancel). Tends to eq. 35 as ``u -> 0`` and to
    ``1 + (eps / 2 u H0) int (4 y + 3) f dy`` as ``u -> inf``. Both creep laws give it: eq. 17
    is eqs. 15-16 to first order in ``eps``.
    """
    mu = _steady_first_order_loose(u, model.eps, model.alpha)
    if model.direct == 0.0:
        return mu
    return mu * junction_strength(np.asarray(u, float), model.direct, model.v_ref)


@lru_cache(maxsize=256)
def _low_velocity_constant_loose(alpha: float = 0.13) -> float:
    """:func:`low_velocity_constant` at a loose ``alpha`` (its old form; cached)."""
    alpha = check_alpha(alpha)
    trap = Trap(alpha)

    def g(y: float) -> float:
        return (3.0 * math.log1p(y) + y / (1.0 + y)) * float(force_forward(y, alpha))

    pts = [trap.y_c] if trap.y_c < 1.0 else None
    from scipy.integrate import quad  # lazily: scipy.integrate imports SciPy's optimizers

    val, _ = quad(g, -1.0, trap.death_point, points=pts, limit=400, epsabs=1e-13, epsrel=1e-13)
    return val / trap.H0


@takes_model(_low_velocity_constant_loose, "low_velocity_constant(alpha)",
             "low_velocity_constant(model)")
def low_velocity_constant(model: TrapModel) -> float:
    """``K1 = (1/H0) int_{-1}^{death} [3 ln(1 + y) + y/(1 + y)] f(y) dy`` of ``model`` (ours,
    eq. 35's order-``eps`` constant, :func:`steady_friction_low_velocity`).

    A property of the trap alone: only ``model.alpha`` enters (``eps`` is the expansion's
    parameter; both creep laws agree to this order; the direct effect multiplies the result).
    """
    return _low_velocity_constant_loose(model.alpha)


def _steady_low_velocity_loose(u: ArrayLike, eps: ArrayLike, alpha: float = 0.13,
                               direct: float = 0.0, v_ref: float = 1.0) -> Array:
    """:func:`steady_friction_low_velocity` with its parameters loose (its old form):
    ``mu_d ~ 1 + (eps/2) (-3 ln u + K1)``, valid for ``u << 1`` and ``eps << 1``; times
    ``g(u)`` with the direct effect."""
    direct, v_ref = check_direct(direct, v_ref)
    alpha, u, eps = check_steady_inputs(u, eps, alpha, "log")
    mu = 1.0 + 0.5 * eps * (-3.0 * np.log(u) + _low_velocity_constant_loose(alpha))
    return mu if direct == 0.0 else mu * junction_strength(u, direct, v_ref)


@takes_model(_steady_low_velocity_loose,
             "steady_friction_low_velocity(u, eps, alpha, direct, v_ref)",
             "steady_friction_low_velocity(model, u)")
def steady_friction_low_velocity(model: TrapModel, u: ArrayLike) -> Array:
    """Low-velocity expansion of eq. 34 for ``model`` (eq. 35 with its constant ``K1``,
    :func:`low_velocity_constant`): ``mu_d ~ 1 + (eps/2) (-3 ln u + K1)``, valid for
    ``u << 1`` and ``eps << 1`` (both creep laws: eq. 17 is eqs. 15-16 to first order in
    ``eps``); times ``g(u)`` with the direct effect (``model.direct > 0``)."""
    return _steady_low_velocity_loose(u, model.eps, model.alpha, model.direct, model.v_ref)


def _steady_log_slope_low_velocity_loose(u: ArrayLike, eps: ArrayLike, alpha: float = 0.13,
                                         direct: float = 0.0, v_ref: float = 1.0) -> Array:
    """:func:`steady_log_slope_low_velocity` with the parameters loose (its old form).
    ``d mu/d ln u`` of :func:`steady_friction_low_velocity` (ours, derived):
    ``A_u mu_d - (3/2) eps g(u)``, ``A_u = u g'(u)``; ``-> A mu_d - 3 eps/2`` when
    ``u >> v_ref e^{-1/A}`` and ``A ln(u/v_ref) << 1``. Velocity strengthening at low ``u``
    exactly when ``A mu_d > 3 eps g/2``."""
    direct, v_ref = check_direct(direct, v_ref)
    alpha, u, eps = check_steady_inputs(u, eps, alpha, "log")
    mu = 1.0 + 0.5 * eps * (-3.0 * np.log(u) + _low_velocity_constant_loose(alpha))
    if direct == 0.0:
        return -1.5 * eps * np.ones_like(mu)
    return (junction_log_slope(u, direct, v_ref) * mu
            - 1.5 * eps * junction_strength(u, direct, v_ref))


@takes_model(_steady_log_slope_low_velocity_loose,
             "steady_log_slope_low_velocity(u, eps, alpha, direct, v_ref)",
             "steady_log_slope_low_velocity(model, u)")
def steady_log_slope_low_velocity(model: TrapModel, u: ArrayLike) -> Array:
    """``d mu/d ln u`` of :func:`steady_friction_low_velocity` of ``model`` (ours, derived):
    ``A_u mu_d - (3/2) eps g(u)``, ``A_u = u g'(u)``; ``-> A mu_d - 3 eps/2`` when
    ``u >> v_ref e^{-1/A}`` and ``A ln(u/v_ref) << 1``. Velocity strengthening at low ``u``
    exactly when ``A mu_d > 3 eps g/2``. Uses ``alpha`` (through ``mu_d``'s constant ``K1``),
    ``eps``, ``direct`` and ``v_ref``; both creep laws give it (eq. 17 is eqs. 15-16 to first
    order in ``eps``)."""
    return _steady_log_slope_low_velocity_loose(u, model.eps, model.alpha, model.direct,
                                                model.v_ref)
