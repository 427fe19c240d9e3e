"""Static ageing and the static friction threshold (paper §4, docs/model.md §3).

Protocol: contact made at ``t = 0``, held for ``t_w``, then a fast tangential pull. Reduced
units: lengths in ``a0``, times in ``t0`` (``T = t_w/t0``), forces in ``F_el`` (eq. 12).

During the pull the slider shifts the whole population rigidly by ``d`` (in ``a0``). Three
groups of pairs carry force (Fig. 2b):

* *fresh* pairs pulled into contact during the pull, on ``[-1, -1 + d]``, radius ``a0``;
* the aged (+) traps, which started on ``[-1, d_w]`` and now sit at ``w = p/r`` in their own
  radius ``r = a_r(T)``, each carrying ``r^2 f(w)`` (eq. 23);
* the aged (-) traps, which started on ``[d_w, 1]``, alive while ``w <= 1``.

``d_w = 0`` is the paper's protocol (waiting under zero tangential load, eq. 25). ``d_w > 0`` is
the loaded protocol the paper describes but does not compute (ours): contact is made under a
tangential force ``f_w`` (units ``F_el``) that places the population edge at ``d_w``, where the
fresh force equals ``f_w`` (:func:`loaded_edge`); the slider is then held in place during the
wait (the distribution does not move, as in §4) and pulled.

With ``Phi`` the closed-form cumulative work of :func:`dryfriction.trap.work_forward`, the
force after a shift ``d`` is (ours; eq. 27 is its value at ``d*``)::

    mu(d) H0 = Phi(-1 + d) + r^3 [Phi((d_w + d)/r) - Phi((d - 1)/r)]
               + r^3 int_{(d_w + d)/r}^{(1 + d)/r} f_-(w) 1[w <= 1] dw

**[reading] of eq. 27**: sliding starts when the aged (+) edge reaches the aged spinodal,
``d* = r y_c - d_w``; at ``d_w = 0`` this gives
``mu_s = {int_{-1}^{-1 + r y_c} f_+ + r^3 int_{y_c - 1/r}^{y_c} f_+} / H0``.
The threshold returned by :func:`static_friction` is the maximum of ``mu(d)`` over the pull
(:func:`static_friction_at_radius` lists the candidates). It equals the eq. 27 reading for
all of the paper's parameters.

**Direct effect (ours, :mod:`.direct`).** With ``direct = A > 0`` the threshold depends on how
fast it is pulled: a pull at the constant slip rate ``pull_velocity`` (reduced ``a0/t0``) scales
every trap force by the junction strength ``g(pull_velocity)``, so ``mu_s = g mu_s(A = 0)`` --
``d mu_s/d ln V_pull = A_V mu_s``, ``A_V = V g'(V)``. The pull is still fast against ageing (no
ageing during it, as in §4); a force-controlled pull is the ensemble's :class:`ForceDrive`.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..validation import (
    EPS_MAX,
    T_MAX,
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
from .creep import CREEP_LAWS, check_age, per_eps
from .direct import junction_strength
from .trap import Trap, force_forward, work_forward, work_minus

__all__ = [
    "loaded_edge",
    "fresh_force",
    "pull_force",
    "threshold_shift",
    "static_friction",
    "static_friction_at_radius",
    "static_friction_first_order",
    "static_slope_per_eps",
]


def fresh_force(d: ArrayLike, alpha: float = 0.13) -> Array:
    """Force (units ``F_el``) of a fresh rest population shifted by ``d`` (units ``a0``).

    ``[Phi(d) + int_d^1 f_-] / H0`` for ``0 <= d <= y_c``: 0 at ``d = 0`` (forces cancel, eq. 25)
    and 1 at ``d = y_c`` (the elastic threshold equals ``F_el``). Its slope at 0 is the contact
    stiffness ``Delta f / H0`` (eqs. 13-14).
    """
    alpha = check_alpha(alpha)
    trap = Trap(alpha)
    d = check_range("d", d, 0.0, trap.y_c)
    dm = np.minimum(d, 1.0)
    return (work_forward(d, alpha) + work_minus(dm, 1.0, alpha)) / trap.H0


def loaded_edge(f_w: float, alpha: float = 0.13) -> float:
    """Population edge ``d_w`` (units ``a0``) at which a fresh contact carries force ``f_w``.

    Parameters
    ----------
    f_w : float
        Tangential force during the wait, units ``F_el``, ``0 <= f_w < 1``.
    alpha : float
        Reduced trap stiffness, ``0 < alpha < 1``.
    """
    f_w = check_scalar("load", f_w, 0.0, 1.0, hi_open=True)
    alpha = check_alpha(alpha)
    if f_w == 0.0:
        return 0.0
    yc = Trap(alpha).y_c
    from scipy.optimize import brentq  # lazily: SciPy's optimizers are slow to import

    return float(brentq(lambda d: float(fresh_force(d, alpha)) - f_w, 0.0, yc, xtol=1e-15,
                        rtol=4 * np.finfo(float).eps, maxiter=200))


def pull_force(d: ArrayLike, r: ArrayLike, alpha: float = 0.13, d_w: float = 0.0) -> Array:
    """Force ``mu(d)`` (units ``F_el``) during the pull, after a shift ``d >= 0`` (units ``a0``).

    Parameters
    ----------
    d : array_like
        Shift of the slider since the end of the wait, units ``a0``.
    r : array_like
        Radius ratio ``a_r(t_w)`` of the aged contacts (broadcast with ``d``).
    alpha : float
        Reduced trap stiffness, ``0 < alpha < 1``.
    d_w : float
        Population edge during the wait (0: waiting at zero load; see :func:`loaded_edge`).
    """
    alpha = check_alpha(alpha)
    trap = Trap(alpha)
    d = check_range("d", d, 0.0)
    r = check_range("r", r, 1.0)
    d_w = check_scalar("d_w", d_w, 0.0, trap.y_c, hi_open=True)
    fresh = work_forward(-1.0 + d, alpha)
    aged_plus = work_forward((d_w + d) / r, alpha) - work_forward((d - 1.0) / r, alpha)
    lo = np.minimum((d_w + d) / r, 1.0)
    hi = np.minimum((1.0 + d) / r, 1.0)
    aged_minus = work_minus(lo, hi, alpha)
    return (fresh + r**3 * (aged_plus + aged_minus)) / trap.H0


def threshold_shift(r: ArrayLike, alpha: float = 0.13, d_w: float = 0.0) -> Array:
    """Shift ``d* = r y_c - d_w`` at which the aged (+) edge reaches its spinodal (eq. 26)."""
    return np.asarray(r, float) * Trap(check_alpha(alpha)).y_c - d_w


def _interior_maximum(r: Array, alpha: float, d_w: float, n: int = 64) -> Array:
    """Largest ``mu(d)`` on ``[0, d*]``: grid, then golden-section search around the best node.

    Needed in strong pinning, where the aged (-) traps still carry force at ``d*`` and the
    force can peak before the aged edge reaches its spinodal (``f_+`` turns over before
    ``y_c``: its slope tends to ``-inf`` there).
    """
    dstar = threshold_shift(r, alpha, d_w)[..., None]
    grid = dstar * np.linspace(0.0, 1.0, n)
    vals = pull_force(grid, r[..., None], alpha, d_w)
    k = np.argmax(vals, axis=-1)[..., None]
    lo = np.take_along_axis(grid, np.maximum(k - 1, 0), axis=-1)[..., 0]
    hi = np.take_along_axis(grid, np.minimum(k + 1, n - 1), axis=-1)[..., 0]
    g = (math.sqrt(5.0) - 1.0) / 2.0
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = pull_force(x1, r, alpha, d_w), pull_force(x2, r, alpha, d_w)
    for _ in range(60):
        left = f1 >= f2
        hi = np.where(left, x2, hi)
        lo = np.where(left, lo, x1)
        x2n = np.where(left, x1, lo + g * (hi - lo))
        x1n = np.where(left, hi - g * (hi - lo), x2)
        f2 = np.where(left, f1, np.nan)
        f1 = np.where(left, np.nan, f2)
        x1, x2 = x1n, x2n
        f1 = np.where(np.isnan(f1), pull_force(x1, r, alpha, d_w), f1)
        f2 = np.where(np.isnan(f2), pull_force(x2, r, alpha, d_w), f2)
    return np.maximum(vals.max(axis=-1), np.maximum(f1, f2))


def static_friction_at_radius(r: ArrayLike, alpha: float = 0.13, d_w: float = 0.0) -> Array:
    """Static threshold ``mu_s`` (units ``F_el``) as a function of the aged radius ratio ``r``.

    The maximum of ``mu(d)`` over the pull. In very strong pinning it is the largest of
    ``mu(d*)`` (the eq. 27 reading), ``mu(1 + y_c)`` (fresh edge at its spinodal) and the
    plateau ``mu = 1`` reached once every aged trap is gone. In strong pinning (ours) the held
    force ``mu(0)`` and an interior maximum before ``d*`` are candidates too. The tests check
    the result against a dense scan of ``mu(d)`` over both regimes.
    """
    alpha = check_alpha(alpha)
    r = check_range("r", r, 1.0)
    trap = Trap(alpha)
    best = np.maximum(pull_force(threshold_shift(r, alpha, d_w), r, alpha, d_w), 1.0)
    best = np.maximum(best, pull_force(np.full_like(r, 1.0 + trap.y_c), r, alpha, d_w))
    if trap.y_c < 1.0:
        best = np.maximum(best, _interior_maximum(np.atleast_1d(r), alpha, d_w).reshape(r.shape))
    return best


def static_friction(
    T: ArrayLike,
    eps: ArrayLike,
    alpha: float = 0.13,
    creep: str = "log",
    load: float = 0.0,
    direct: float = 0.0,
    v_ref: float = 1.0,
    pull_velocity: float | None = None,
) -> Array:
    """Static friction ``mu_s = F_s/F_el`` after a wait ``T = t_w/t0`` (eq. 27, our reading).

    Parameters
    ----------
    T : array_like
        Reduced waiting time ``t_w/t0``, ``>= 0``.
    eps : array_like
        Creep parameter ``S/Y``, ``>= 0`` (broadcast with ``T``).
    alpha : float
        Reduced trap stiffness, ``0 < alpha < 1`` (0.13 in the paper).
    creep : {"log", "eyring-nabarro"}
        Ageing law: eq. 17 or the exact eqs. 15-16.
    load : float
        Tangential force during the wait, units ``F_el``, ``0 <= load < 1``. 0 is the paper's
        protocol; ``load > 0`` the loaded protocol (ours, module docstring).
    direct, v_ref : float
        Direct-effect coefficient ``0 <= A <= 1`` and its reference velocity (reduced, ``> 0``).
    pull_velocity : float, optional
        Slip rate of the pull, reduced ``a0/t0``, ``> 0``; required when ``direct > 0`` (the
        threshold then scales with ``g(pull_velocity)``), ignored otherwise.

    Returns
    -------
    ndarray
        ``mu_s``, same broadcast shape as ``(T, eps)``; ``mu_s(T = 0) = 1``.
    """
    alpha = check_alpha(alpha)
    check_choice("creep", creep, CREEP_LAWS)
    direct, v_ref = check_direct(direct, v_ref)
    if direct > 0.0:
        if pull_velocity is None:
            raise ValueError("pull_velocity is required when direct > 0 (the threshold depends "
                             "on how fast it is pulled): "
                             f"allowed {U_MIN:g} <= pull_velocity <= {U_MAX:g} (a0/t0)")
        pull_velocity = check_scalar("pull_velocity", pull_velocity, U_MIN, U_MAX)
    T = check_range("T", T, 0.0, T_MAX)
    eps = check_range("eps", eps, 0.0, EPS_MAX)
    check_broadcast(T=T, eps=eps)
    check_age(T, eps, creep)
    d_w = loaded_edge(load, alpha)
    # radius and threshold together, chunk by chunk: the threshold's temporaries (~80 bytes a
    # point) would otherwise be held for the whole array at once
    mu = per_eps(lambda law, t: static_friction_at_radius(law.radius(t), alpha, d_w), creep,
                 eps, T)
    if direct > 0.0:
        mu = mu * junction_strength(pull_velocity, direct, v_ref)
    return check_finite_result("mu_s", mu, T=T, eps=eps)


def static_slope_per_eps(alpha: float = 0.13) -> float:
    """``(1/eps) d mu_s / d ln T`` at first order in ``eps`` and large ``T`` (eq. 28a).

    ``[3 H1 + (y_c - 1) f(y_c - 1)] / (2 H0)``, with ``f`` the forward force (``f_+`` in the
    paper's regime) and ``H1`` of eq. 28b.
    """
    trap = Trap(check_alpha(alpha))
    f1 = float(force_forward(trap.y_c - 1.0, alpha))
    return (3.0 * trap.H1 + (trap.y_c - 1.0) * f1) / (2.0 * trap.H0)


def static_friction_first_order(T: ArrayLike, eps: ArrayLike, alpha: float = 0.13) -> Array:
    """First order in ``eps`` of :func:`static_friction` at zero load (eq. 28a).

    ``mu_s ~ 1 + eps ln(1 + T) [3 H1 + (y_c - 1) f_+(y_c - 1)] / (2 H0)``.
    """
    T = check_range("T", T, 0.0, T_MAX)
    eps = check_range("eps", eps, 0.0, EPS_MAX)
    check_broadcast(T=T, eps=eps)
    return 1.0 + eps * np.log1p(T) * static_slope_per_eps(alpha)
