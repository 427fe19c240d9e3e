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

With ``Phi`` the closed-form cumulative work of :func:`dryfriction.theory.trap.work_forward`, the
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
from dataclasses import dataclass

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
from .creep import CREEP_LAWS, check_age, per_eps, radius
from .direct import junction_strength
from .model import TrapModel, takes_model
from .trap import Trap, force_forward, work_forward, work_minus

__all__ = [
    "loaded_edge",
    "fresh_force",
    "pull_force",
    "threshold_shift",
    "static_friction",
    "static_friction_over_eps",
    "force_hold_shift",
    "HOLDS",
    "static_friction_at_radius",
    "static_friction_first_order",
    "static_slope_per_eps",
]


def _fresh_force_loose(d: ArrayLike, alpha: float = 0.13) -> Array:
    """:func:`fresh_force` at a loose ``alpha`` (its old form).
    Force (units ``F_el``) of a fresh rest population shifted by ``d`` (units ``a0``).

    ``[Phi(d) + int_d^1 f_-] / H0`` for ``0 <= d <= y_c``: 0 at ``d = 0`` (forces cancel, eq. 25)
    and 1 at ``d = y_c`` (the elastic threshold equals ``F_el``). Its slope at 0 is the contact
    stiffness ``Delta f / H0`` (eqs. 13-14).
    """
    alpha = check_alpha(alpha)
    trap = Trap(alpha)
    d = check_range("d", d, 0.0, trap.y_c)
    dm = np.minimum(d, 1.0)
    return (work_forward(d, alpha) + work_minus(dm, 1.0, alpha)) / trap.H0


@takes_model(_fresh_force_loose, "fresh_force(d, alpha)", "fresh_force(model, d)")
def fresh_force(model: TrapModel, d: ArrayLike) -> Array:
    """Force (units ``F_el``) of a fresh rest population of ``model`` shifted by ``d`` (units
    ``a0``, ``0 <= d <= y_c``).

    ``[Phi(d) + int_d^1 f_-] / H0``: 0 at ``d = 0`` (forces cancel, eq. 25) and 1 at
    ``d = y_c`` (the elastic threshold equals ``F_el``). Its slope at 0 is the contact
    stiffness ``Delta f / H0`` (eqs. 13-14). Only ``model.alpha`` enters (a fresh population
    has not aged; the direct effect multiplies forces in sliding only).
    """
    return _fresh_force_loose(d, model.alpha)


def _loaded_edge_loose(f_w: float, alpha: float = 0.13) -> float:
    """:func:`loaded_edge` at a loose ``alpha`` (its old form).
    Population edge ``d_w`` (units ``a0``) at which a fresh contact carries force ``f_w``.

    Parameters
    ----------
    f_w : float
        Tangential force during the wait, units ``F_el``, ``-1 < f_w < 1``; a negative (reversed)
        load gives the mirror image, ``d_w(-f) = -d_w(f)``.
    alpha : float
        Reduced trap stiffness, ``0 < alpha < 1``.
    """
    f_w = check_scalar("load", f_w, -1.0, 1.0, lo_open=True, hi_open=True)
    alpha = check_alpha(alpha)
    if f_w == 0.0:
        return 0.0
    if f_w < 0.0:  # mirror symmetry p -> -p of the rest population
        return -_loaded_edge_loose(-f_w, alpha)
    yc = Trap(alpha).y_c
    from scipy.optimize import brentq  # lazily: SciPy's optimizers are slow to import

    return float(brentq(lambda d: float(_fresh_force_loose(d, alpha)) - f_w, 0.0, yc,
                        xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200))


@takes_model(_loaded_edge_loose, "loaded_edge(f_w, alpha)", "loaded_edge(model, load)")
def loaded_edge(model: TrapModel, load: float) -> float:
    """Population edge ``d_w`` (units ``a0``) at which a fresh contact of ``model`` carries the
    tangential force ``load`` (ours, module docstring): the root of
    ``fresh_force(model, d_w) = load``.

    Parameters
    ----------
    model : TrapModel
        Only ``alpha`` enters (see :func:`fresh_force`).
    load : float
        Tangential force during the wait, units ``F_el``, ``-1 < load < 1``; a negative
        (reversed) load gives the mirror image, ``d_w(-f) = -d_w(f)``.

    Returns
    -------
    float
        ``d_w`` in ``a0``.
    """
    return _loaded_edge_loose(load, model.alpha)


def _pull_force_loose(d: ArrayLike, r: ArrayLike, alpha: float = 0.13, d_w: float = 0.0
                      ) -> Array:
    """:func:`pull_force` at a loose ``alpha`` (its old form).
    Force ``mu(d)`` (units ``F_el``) during the pull, after a shift ``d >= 0`` (units ``a0``).

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
    d_w = check_scalar("d_w", d_w, -min(1.0, trap.y_c), trap.y_c, lo_open=True, hi_open=True)
    fresh = work_forward(-1.0 + d, alpha)
    aged_plus = work_forward((d_w + d) / r, alpha) - work_forward((d - 1.0) / r, alpha)
    lo = np.minimum((d_w + d) / r, 1.0)
    hi = np.minimum((1.0 + d) / r, 1.0)
    aged_minus = work_minus(lo, hi, alpha)
    return (fresh + r**3 * (aged_plus + aged_minus)) / trap.H0


@takes_model(_pull_force_loose, "pull_force(d, r, alpha, d_w)", "pull_force(model, d, r, d_w)")
def pull_force(model: TrapModel, d: ArrayLike, r: ArrayLike, d_w: float = 0.0) -> Array:
    """Force ``mu(d)`` (units ``F_el``) of ``model``'s population during the pull, after a
    shift ``d >= 0`` (units ``a0``; module docstring, eqs. 25-27).

    Parameters
    ----------
    model : TrapModel
        Only ``alpha`` enters: the ageing is in ``r``, and the direct effect's factor
        ``g(pull_velocity)`` is applied by :func:`static_friction`.
    d : array_like
        Shift of the slider since the end of the wait, units ``a0``.
    r : array_like
        Radius ratio ``a_r(t_w)`` of the aged contacts (broadcast with ``d``), ``>= 1``.
    d_w : float
        Population edge during the wait (0: waiting at zero load; see :func:`loaded_edge`).
    """
    return _pull_force_loose(d, r, model.alpha, d_w)


def _threshold_shift_loose(r: ArrayLike, alpha: float = 0.13, d_w: float = 0.0) -> Array:
    """:func:`threshold_shift` at a loose ``alpha`` (its old form)."""
    return np.asarray(r, float) * Trap(check_alpha(alpha)).y_c - d_w


@takes_model(_threshold_shift_loose, "threshold_shift(r, alpha, d_w)",
             "threshold_shift(model, r, d_w)")
def threshold_shift(model: TrapModel, r: ArrayLike, d_w: float = 0.0) -> Array:
    """Shift ``d* = r y_c - d_w`` (units ``a0``) at which the aged (+) edge of ``model``'s
    population, radius ratio ``r``, reaches its spinodal (eq. 26). Only ``model.alpha``
    enters (through ``y_c``)."""
    return _threshold_shift_loose(r, model.alpha, d_w)


def _interior_maximum(r: Array, alpha: float, d_w: float, n: int = 64) -> Array:
    """Largest ``mu(d)`` on ``[0, d*]``: grid, then golden-section search around the best node.

    Needed in strong pinning, where the aged (-) traps still carry force at ``d*`` and the
    force can peak before the aged edge reaches its spinodal (``f_+`` turns over before
    ``y_c``: its slope tends to ``-inf`` there).
    """
    dstar = _threshold_shift_loose(r, alpha, d_w)[..., None]
    grid = dstar * np.linspace(0.0, 1.0, n)
    vals = _pull_force_loose(grid, r[..., None], alpha, d_w)
    k = np.argmax(vals, axis=-1)[..., None]
    lo = np.take_along_axis(grid, np.maximum(k - 1, 0), axis=-1)[..., 0]
    hi = np.take_along_axis(grid, np.minimum(k + 1, n - 1), axis=-1)[..., 0]
    g = (math.sqrt(5.0) - 1.0) / 2.0
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = _pull_force_loose(x1, r, alpha, d_w), _pull_force_loose(x2, r, alpha, d_w)
    for _ in range(60):
        left = f1 >= f2
        hi = np.where(left, x2, hi)
        lo = np.where(left, lo, x1)
        x2n = np.where(left, x1, lo + g * (hi - lo))
        x1n = np.where(left, hi - g * (hi - lo), x2)
        f2 = np.where(left, f1, np.nan)
        f1 = np.where(left, np.nan, f2)
        x1, x2 = x1n, x2n
        f1 = np.where(np.isnan(f1), _pull_force_loose(x1, r, alpha, d_w), f1)
        f2 = np.where(np.isnan(f2), _pull_force_loose(x2, r, alpha, d_w), f2)
    return np.maximum(vals.max(axis=-1), np.maximum(f1, f2))


def _at_radius_loose(r: ArrayLike, alpha: float = 0.13, d_w: float = 0.0) -> Array:
    """:func:`static_friction_at_radius` with ``alpha`` loose (its old form, and the core of
    :func:`static_friction`). Static threshold ``mu_s`` (units ``F_el``) as a function of the
    aged radius ratio ``r``.

    The maximum of ``mu(d)`` over the pull. In very strong pinning it is the largest of
    ``mu(d*)`` (the eq. 27 reading), ``mu(1 + y_c)`` (fresh edge at its spinodal) and the
    plateau ``mu = 1`` reached once every aged trap is gone. In strong pinning (ours) the held
    force ``mu(0)`` and an interior maximum before ``d*`` are candidates too. The tests check
    the result against a dense scan of ``mu(d)`` over both regimes.
    """
    alpha = check_alpha(alpha)
    r = check_range("r", r, 1.0)
    trap = Trap(alpha)
    best = np.maximum(_pull_force_loose(_threshold_shift_loose(r, alpha, d_w), r, alpha, d_w),
                      1.0)
    best = np.maximum(best, _pull_force_loose(np.full_like(r, 1.0 + trap.y_c), r, alpha, d_w))
    if trap.y_c < 1.0:
        best = np.maximum(best, _interior_maximum(np.atleast_1d(r), alpha, d_w).reshape(r.shape))
    return best


def _athermal_only(model: TrapModel, name: str) -> None:
    if model.direct > 0.0:
        raise ValueError(f"{name} is the threshold of the aged population, without the direct "
                         f"effect (model.direct = {model.direct:g}): pass model.athermal, or use "
                         "static_friction(model, T, pull_velocity=...)")


@takes_model(_at_radius_loose, "static_friction_at_radius(r, alpha, d_w)",
             "static_friction_at_radius(model, r, d_w)")
def static_friction_at_radius(model: TrapModel, r: ArrayLike, d_w: float = 0.0) -> Array:
    """Static threshold ``mu_s`` (units ``F_el``) of ``model``'s traps as a function of the aged
    radius ratio ``r = a_r(T)`` (``>= 1``), contact made with the population edge at ``d_w``
    (``a0``; 0: zero load, :func:`loaded_edge`).

    The maximum of ``mu(d)`` over the pull (module docstring); only ``model.alpha`` enters (the
    creep law and ``eps`` are in ``r``). The athermal threshold: a model with the direct effect
    is refused (its threshold depends on the pull velocity: :func:`static_friction`).
    """
    _athermal_only(model, "static_friction_at_radius")
    return _at_radius_loose(r, model.alpha, d_w)


def _static_friction_loose(
    T: ArrayLike,
    eps: ArrayLike,
    alpha: float = 0.13,
    creep: str = "log",
    load: float = 0.0,
    direct: float = 0.0,
    v_ref: float = 1.0,
    pull_velocity: float | None = None,
    hold: str = "position",
) -> Array:
    """:func:`static_friction` with the parameters loose and ``eps`` broadcast with ``T`` (its
    old form, and the vectorised core of :func:`static_friction_over_eps`). Static friction
    ``mu_s = F_s/F_el`` after a wait ``T = t_w/t0`` (eq. 27, our reading).

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
        Tangential force at contact formation, units ``F_el``, ``-1 < load < 1``. 0 is the
        paper's protocol; ``load != 0`` the loaded protocol (ours, module docstring).
    hold : {"position", "force"}
        How the loaded contact is held during the wait (no difference at ``load = 0``):
        ``"position"``, the slider stays where the load put it and the force grows as the
        contacts age (the population does not move, as in §4); ``"force"``, the tangential
        force stays ``load`` and the slider creeps (back, for ``load > 0``) as the contacts
        age (module docstring). Experiments use both; a constant-force hold is the common one.
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
    pull_velocity = _checked_pull(direct, pull_velocity)
    T = check_range("T", T, 0.0, T_MAX)
    eps = check_range("eps", eps, 0.0, EPS_MAX)
    check_broadcast(T=T, eps=eps)
    check_age(T, eps, creep)
    check_choice("hold", hold, HOLDS)
    d_w = _loaded_edge_loose(load, alpha)
    if hold == "position" and d_w <= -1.0:
        # the held population's pull (pull_force) needs the edge above -a0; a second new
        # user's --load -0.7 was refused there as "d_w = -1.04", a name no user gave: the
        # load's own range instead (a force hold creeps the edge back: no such limit)
        lim = float(_fresh_force_loose(1.0, alpha))
        raise ValueError(f"load = {load:g} is out of range: allowed {-lim:.4g} < load < 1 "
                         f"at alpha = {alpha:g} with the position held (a reversed load beyond "
                         f"{lim:.4g} F_el puts the population's edge at or past -a0, where the "
                         "pull is not defined; hold = 'force' takes -1 < load < 1)")
    if hold == "force" and load != 0.0:
        Tb, eb = np.broadcast_arrays(T, eps)
        mu = np.array([_force_hold(float(t), float(e), alpha, creep, float(load))[0]
                       for t, e in zip(Tb.ravel(), eb.ravel(), strict=True)]).reshape(Tb.shape)
    else:
        # radius and threshold together, chunk by chunk: the threshold's temporaries (~80
        # bytes a point) would otherwise be held for the whole array at once
        mu = per_eps(lambda law, t: _at_radius_loose(law.radius(t), alpha, d_w),
                     creep, eps, T)
    if direct > 0.0:
        mu = mu * junction_strength(pull_velocity, direct, v_ref)
    return check_finite_result("mu_s", mu, T=T, eps=eps)


def _checked_pull(direct: float, pull_velocity: float | None) -> float | None:
    """The pull's slip rate, required (and checked) when the model has the direct effect."""
    if direct == 0.0:
        return pull_velocity
    if pull_velocity is None:
        raise ValueError("pull_velocity is required when direct > 0 (the threshold depends "
                         "on how fast it is pulled): "
                         f"allowed {U_MIN:g} <= pull_velocity <= {U_MAX:g} (a0/t0)")
    return check_scalar("pull_velocity", pull_velocity, U_MIN, U_MAX)


@takes_model(_static_friction_loose,
             "static_friction(T, eps, alpha, creep, load, direct, v_ref, pull_velocity, hold)",
             "static_friction(model, T, load=..., pull_velocity=..., hold=...)")
def static_friction(model: TrapModel, T: ArrayLike, *, load: float = 0.0,
                    pull_velocity: float | None = None, hold: str = "position") -> Array:
    """Static friction ``mu_s = F_s/F_el`` of ``model`` after a wait ``T = t_w/t0`` (eq. 27, our
    reading).

    Parameters
    ----------
    model : TrapModel
        ``alpha``, ``eps``, ``creep`` (eq. 17 or the exact eqs. 15-16), ``direct`` and
        ``v_ref`` (reduced ``a0/t0``). ``model.mu_el`` does not enter: the result is ``F/F_el``.
    T : array_like
        Reduced waiting time ``t_w/t0``, ``>= 0``.
    load : float
        Tangential force at contact formation, units ``F_el``, ``-1 < load < 1``. 0 is the
        paper's protocol; ``load != 0`` the loaded protocol (ours, module docstring).
    pull_velocity : float, optional
        Slip rate of the pull, reduced ``a0/t0``, ``> 0``; required when ``model.direct > 0``
        (the threshold then scales with ``g(pull_velocity)``), ignored otherwise.
    hold : {"position", "force"}
        How the loaded contact is held during the wait (no difference at ``load = 0``):
        ``"position"``, the slider stays where the load put it and the force grows as the
        contacts age (the population does not move, as in §4); ``"force"``, the tangential
        force stays ``load`` and the slider creeps (back, for ``load > 0``) as the contacts
        age (module docstring).

    Returns
    -------
    ndarray
        ``mu_s``, the shape of ``T``; ``mu_s(T = 0) = 1`` (times ``g(pull_velocity)``). For a
        sweep over ``eps`` in one call see :func:`static_friction_over_eps`.
    """
    return _static_friction_loose(T, model.eps, model.alpha, model.creep, load, model.direct,
                                  model.v_ref, pull_velocity, hold)


def static_friction_over_eps(model: TrapModel, T: ArrayLike, eps: ArrayLike, *,
                             load: float = 0.0, pull_velocity: float | None = None,
                             hold: str = "position") -> Array:
    """:func:`static_friction` of ``model`` with its ``eps`` replaced by every value of ``eps``,
    broadcast with ``T``: a sweep over the creep parameter in one vectorised call (the paper's
    figures). ``eps`` is checked like ``model.eps`` (``0 <= eps <= 1``); ``model.eps`` is not
    used. At a scalar ``e`` it equals ``static_friction(model.replace(eps=e), T, ...)``.
    """
    return _static_friction_loose(T, eps, model.alpha, model.creep, load, model.direct,
                                  model.v_ref, pull_velocity, hold)


# ---------------------------------------------------------------- the constant-force hold
HOLDS: tuple[str, ...] = ("position", "force")
_HOLD_STEPS = 120  # log-spaced steps of the hold (the slabs of new contacts)
_PULL_GRID = 401


@dataclass
class _Slabs:
    """Pairs that entered contact during the hold: original positions ``[lo, hi]``, branch
    (True: entered at ``-1`` moving forward, on (+)), entry time."""

    lo: list[float]
    hi: list[float]
    plus: list[bool]
    t: list[float]

    def add(self, lo: float, hi: float, plus: bool, t: float) -> None:
        self.lo.append(lo)
        self.hi.append(hi)
        self.plus.append(plus)
        self.t.append(t)

    def arrays(self) -> tuple[Array, Array, Array, Array]:
        return (np.array(self.lo), np.array(self.hi), np.array(self.plus, bool),
                np.array(self.t))


def _population(s: Array, r: float, alpha: float, d_w: float,
                slabs: tuple[Array, Array, Array, Array], radii: Array, top: float,
                rear: float = -1.0) -> Array:
    """``mu H0`` of the held population after total shifts ``s`` (any sign) from the
    contact position: the aged initial population (radius ``r``) from its rear ``rear``
    (``> -1`` once the hold pushed the rearmost aged traps out of contact, ``w < -1``), the
    slabs of pairs that entered during the hold (radius ``radii``), and fresh pairs entering
    at ``-1``: those behind the rearmost pair ever met, ``-1 - top`` (``top``: the largest
    forward shift of the hold), or the aged pairs that left at the rear."""
    yc = Trap(alpha).y_c
    s = np.asarray(s, float)[..., None]
    fresh_edge = rear if rear > -1.0 else -1.0 - top
    fresh = work_forward(fresh_edge + s[..., 0], alpha)
    plus = work_forward((d_w + s[..., 0]) / r, alpha) - work_forward((s[..., 0] + rear) / r, alpha)
    lo = np.clip((d_w + s[..., 0]) / r, -yc, 1.0)
    hi = np.clip((1.0 + s[..., 0]) / r, -yc, 1.0)
    total = fresh + r**3 * (plus + np.where(lo < hi, work_minus(lo, np.maximum(lo, hi), alpha),
                                            0.0))
    sl_lo, sl_hi, sl_plus, _ = slabs
    if sl_lo.size:
        a, b = (sl_lo + s) / radii, (sl_hi + s) / radii
        fwd = work_forward(b, alpha) - work_forward(a, alpha)
        am, bm = np.clip(a, -yc, 1.0), np.clip(b, -yc, 1.0)
        back = np.where(am < bm, work_minus(am, np.maximum(am, bm), alpha), 0.0)
        total = total + np.sum(radii**3 * np.where(sl_plus, fwd, back), axis=-1)
    return total


def _force_hold(T: float, eps: float, alpha: float, creep: str, f_w: float
                ) -> tuple[float, float]:
    """Static threshold and final slider shift after a hold at constant force ``f_w``.

    The hold is followed on a log grid of ages: at each, the shift that balances ``f_w``;
    pairs met for the first time enter fresh (at ``-1`` moving forward, at ``+1`` moving
    back, as in the ensemble) and age from then on. Then the pull from the held position.
    """
    from scipy.optimize import brentq  # lazily: SciPy's optimizers are slow to import

    trap = Trap(alpha)
    H0, yc = trap.H0, trap.y_c
    d_w = _loaded_edge_loose(f_w, alpha)
    slabs = _Slabs([], [], [], [])
    s, low, top, rear = 0.0, 0.0, 0.0, -1.0
    times = np.geomspace(min(1e-6, T), T, _HOLD_STEPS) if T > 0 else np.zeros(0)
    t_prev = 0.0
    for t in times:
        r = float(radius(t, eps, creep))
        # pairs met during this step entered, on average, half-way through it (in ln t)
        t_in, t_prev = math.sqrt(t_prev * t) if t_prev > 0 else 0.5 * t, t
        lo_, hi_, pl_, tt = slabs.arrays()
        radii = radius(t - tt, eps, creep) if tt.size else np.zeros(0)

        def balance(x: float, r: float = r, radii: Array = radii,
                    base: tuple[Array, Array, Array, Array] = (lo_, hi_, pl_, tt),
                    low: float = low, top: float = top, rear: float = rear) -> float:
            lo, hi, pl, rr = list(base[0]), list(base[1]), list(base[2]), list(radii)
            if x < low:  # the pairs this step's motion brings into contact (fresh)
                lo, hi, pl, rr = lo + [1.0 - low], hi + [1.0 - x], pl + [False], rr + [1.0]
            if x > top:
                lo, hi, pl, rr = lo + [-1.0 - x], hi + [-1.0 - top], pl + [True], rr + [1.0]
            sl = (np.array(lo), np.array(hi), np.array(pl, bool), np.zeros(len(lo)))
            back = max(rear, -r - x)  # aged (+) traps pushed past w = -1 have left
            return float(_population(x, r, alpha, d_w, sl, np.array(rr), max(top, x),
                                     back)) / H0 - f_w

        s = float(brentq(balance, s - 0.5, s + 0.5, xtol=1e-14, maxiter=200))
        if s < low:
            slabs.add(1.0 - low, 1.0 - s, False, t_in)
            low = s
        if s > top:
            slabs.add(-1.0 - s, -1.0 - top, True, t_in)
            top = s
        rear = max(rear, -r - s)
    r = float(radius(T, eps, creep))
    final = slabs.arrays()
    radii = radius(T - final[3], eps, creep) if final[3].size else np.zeros(0)

    def pull(d: ArrayLike) -> Array:
        return _population(s + np.asarray(d, float), r, alpha, d_w, final, radii, top,
                           rear) / H0

    # the threshold: the aged edge at its spinodal (eq. 26 from the held position), the
    # fresh edge at its own, then a grid and a golden-section refinement of the best node
    reach = max(r * yc - d_w - s, 0.0) + 1.0 + yc + abs(s)
    cand = [float(pull(max(r * yc - d_w - s, 0.0))), float(pull(1.0 + yc + top - s)), 1.0]
    grid = np.linspace(0.0, reach, _PULL_GRID)
    vals = pull(grid)
    k = int(np.argmax(vals))
    lo, hi = float(grid[max(k - 1, 0)]), float(grid[min(k + 1, grid.size - 1)])
    g = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(60):
        x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if float(pull(x1)) >= float(pull(x2)):
            hi = x2
        else:
            lo = x1
    cand += [float(vals[k]), float(pull(0.5 * (lo + hi)))]
    return max(cand), s


def _force_hold_shift_loose(T: float, eps: float, alpha: float = 0.13, creep: str = "log",
                            load: float = 0.0) -> float:
    """:func:`force_hold_shift` with the parameters loose (its old form)."""
    T = check_scalar("T", T, 0.0, T_MAX)
    eps = check_scalar("eps", eps, 0.0, EPS_MAX)
    alpha = check_alpha(alpha)
    check_choice("creep", creep, CREEP_LAWS)
    check_age(np.asarray(T), np.asarray(eps), creep)
    _loaded_edge_loose(load, alpha)
    return _force_hold(T, eps, alpha, creep, float(load))[1]


@takes_model(_force_hold_shift_loose, "force_hold_shift(T, eps, alpha, creep, load)",
             "force_hold_shift(model, T, load=...)")
def force_hold_shift(model: TrapModel, T: float, *, load: float = 0.0) -> float:
    """Slider displacement (``a0``) of ``model`` during a hold of reduced duration ``T`` at
    constant tangential force ``load`` (units ``F_el``, ``-1 < load < 1``; ours, module
    docstring).

    Negative: under a positive load the slider creeps back as the contacts age (their force
    at fixed position grows, so the force balance moves them back); positive for a reversed
    load. See :func:`static_friction` (``hold = "force"``). Uses ``model.alpha``, ``eps`` and
    ``creep``; as in :func:`static_friction`, the hold is the population's, so ``direct`` and
    ``v_ref`` do not enter.
    """
    return _force_hold_shift_loose(T, model.eps, model.alpha, model.creep, load)


def _static_slope_per_eps_loose(alpha: float = 0.13) -> float:
    """:func:`static_slope_per_eps` at a loose ``alpha`` (its old form).
    ``(1/eps) d mu_s / d ln T`` at first order in ``eps`` and large ``T`` (eq. 28a).

    ``[3 H1 + (y_c - 1) f(y_c - 1)] / (2 H0)``, with ``f`` the forward force (``f_+`` in the
    paper's regime) and ``H1`` of eq. 28b.
    """
    trap = Trap(check_alpha(alpha))
    f1 = float(force_forward(trap.y_c - 1.0, alpha))
    return (3.0 * trap.H1 + (trap.y_c - 1.0) * f1) / (2.0 * trap.H0)


@takes_model(_static_slope_per_eps_loose, "static_slope_per_eps(alpha)",
             "static_slope_per_eps(model)")
def static_slope_per_eps(model: TrapModel) -> float:
    """``(1/eps) d mu_s / d ln T`` of ``model`` at first order in ``eps`` and large ``T``
    (eq. 28a): ``[3 H1 + (y_c - 1) f(y_c - 1)] / (2 H0)``, with ``f`` the forward force
    (``f_+`` in the paper's regime) and ``H1`` of eq. 28b.

    A property of the trap: only ``model.alpha`` enters (``eps`` is the expansion's parameter,
    both creep laws agree to this order; the direct effect multiplies ``mu_s`` by
    ``g(pull_velocity)``, see :func:`static_friction_first_order`).
    """
    return _static_slope_per_eps_loose(model.alpha)


def _static_first_order_loose(T: ArrayLike, eps: ArrayLike, alpha: float = 0.13) -> Array:
    """:func:`static_friction_first_order` with its parameters loose (its old form)."""
    T = check_range("T", T, 0.0, T_MAX)
    eps = check_range("eps", eps, 0.0, EPS_MAX)
    check_broadcast(T=T, eps=eps)
    return 1.0 + eps * np.log1p(T) * _static_slope_per_eps_loose(alpha)


@takes_model(_static_first_order_loose, "static_friction_first_order(T, eps, alpha)",
             "static_friction_first_order(model, T, pull_velocity=...)")
def static_friction_first_order(model: TrapModel, T: ArrayLike, *,
                                pull_velocity: float | None = None) -> Array:
    """First order in ``model.eps`` of :func:`static_friction` at zero load (eq. 28a).

    ``mu_s ~ 1 + eps ln(1 + T) [3 H1 + (y_c - 1) f_+(y_c - 1)] / (2 H0)`` (both creep laws:
    eq. 17 is eqs. 15-16 to first order in ``eps``); times ``g(pull_velocity)`` with the
    direct effect, where ``pull_velocity`` (reduced ``a0/t0``) is required, as in
    :func:`static_friction`.
    """
    pull_velocity = _checked_pull(model.direct, pull_velocity)
    mu = _static_first_order_loose(T, model.eps, model.alpha)
    if model.direct == 0.0:
        return mu
    return mu * junction_strength(pull_velocity, model.direct, model.v_ref)
