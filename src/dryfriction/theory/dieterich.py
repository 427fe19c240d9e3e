"""Static against dynamic friction: Dieterich's memory length (paper §6, docs/model.md §5).

Dieterich's scaling ``mu_d(V) = mu_s(t_w = D0/V)`` with ``D0 = C a0`` (eq. 36) reads, in reduced
units, ``mu_d(u) = mu_s(T = C/u)``. The model satisfies it only asymptotically:

* **asymptotic constant** (ours, from the first-order expansions): for ``u -> inf`` and
  ``T -> 0``, ``mu_d - 1 ~ (eps / 2 u H0) int (4 y + 3) f dy`` (first order of eq. 34) and
  ``mu_s - 1 ~ (eps T / 2 H0) [3 H1 + (y_c - 1) f(y_c - 1)]`` (eq. 28), so
  ``C_inf = int_{-1}^{death} (4 y + 3) f(y) dy / [3 H1 + (y_c - 1) f(y_c - 1)]``;
* **least-squares constant** over a range of ``u`` (the paper's fitting procedure, Fig. 6);
* **local constant** ``C(u)``: the ``C`` for which the two curves meet at ``u``. It is not
  constant: no single ``D0`` fits everywhere.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..validation import (
    Array,
    check_alpha,
    check_broadcast,
    check_choice,
    check_range,
    check_scalar,
)
from .creep import CREEP_LAWS, PER_EPS_CHUNK, per_eps
from .model import TrapModel, takes_model
from .static import static_friction, static_friction_at_radius, static_slope_per_eps
from .steady import steady_friction, steady_friction_over_eps
from .trap import Trap, z_plus

__all__ = [
    "forward_moment",
    "dieterich_constant_asymptotic",
    "dieterich_constant_least_squares",
    "dieterich_constant_local",
    "dieterich_constant_local_over_eps",
]


_ZX, _ZW = np.polynomial.legendre.leggauss(16)


def _forward_moment_loose(k: int, alpha: float = 0.13) -> float:
    """:func:`forward_moment` at a loose ``alpha`` (its old form).
    ``int_{-1}^{death} y^k f(y) dy`` for the forward force profile, exactly (ours).

    On the (+) branch ``y(z) = -(z^2 + (1 - alpha) z)/alpha`` and ``f = -6 z (1 + z)``, so the
    integrand is a polynomial in ``z`` of degree ``2k + 3``; 16-point Gauss-Legendre in ``z`` is
    exact for ``k <= 14``. The (-) part (strong pinning) follows from ``f_-(y) = -f_+(-y)``.
    """
    alpha = check_alpha(alpha)
    if not 0 <= k <= 14:
        raise ValueError(f"k = {k} is out of range: allowed 0 <= k <= 14")
    trap = Trap(alpha)

    def on_plus(z0: float, z1: float, sign: float) -> float:
        z = 0.5 * (z1 - z0) * _ZX + 0.5 * (z1 + z0)
        y = -(z * z + (1.0 - alpha) * z) / alpha
        dy = -(2.0 * z + 1.0 - alpha) / alpha
        return float(0.5 * (z1 - z0) * np.sum(_ZW * (sign * y) ** k * (-6.0 * z * (1.0 + z)) * dy))

    total = on_plus(-1.0, trap.z_c, 1.0)
    if trap.y_c < 1.0:
        # int_{y_c}^{1} y^k f_-(y) dy = -int_{-1}^{-y_c} (-s)^k f_+(s) ds
        total -= on_plus(-1.0, float(z_plus(-trap.y_c, alpha)), -1.0)
    return total


@takes_model(_forward_moment_loose, "forward_moment(k, alpha)", "forward_moment(model, k)")
def forward_moment(model: TrapModel, k: int) -> float:
    """``int_{-1}^{death} y^k f(y) dy`` for the forward force profile of ``model``'s trap,
    exactly (ours; units ``Phi00/a0`` times ``a0^k``), ``0 <= k <= 14``.

    On the (+) branch ``y(z) = -(z^2 + (1 - alpha) z)/alpha`` and ``f = -6 z (1 + z)``, so the
    integrand is a polynomial in ``z`` of degree ``2k + 3``; 16-point Gauss-Legendre in ``z`` is
    exact for ``k <= 14``. The (-) part (strong pinning) follows from ``f_-(y) = -f_+(-y)``.
    Only ``model.alpha`` enters.
    """
    return _forward_moment_loose(k, model.alpha)


def _asymptotic_loose(alpha: float = 0.13) -> float:
    """:func:`dieterich_constant_asymptotic` with ``alpha`` loose (its old form)."""
    alpha = check_alpha(alpha)
    trap = Trap(alpha)
    dyn = 4.0 * _forward_moment_loose(1, alpha) + 3.0 * _forward_moment_loose(0, alpha)
    stat = 2.0 * trap.H0 * static_slope_per_eps(TrapModel(alpha))
    return dyn / stat


def _athermal(model: TrapModel, name: str) -> None:
    if model.direct > 0.0:
        raise ValueError(f"{name} compares the athermal curves mu_d(u) and mu_s(T) (eq. 36); "
                         f"model.direct = {model.direct:g} makes mu_s depend on the pull "
                         "velocity: pass model.athermal")


@takes_model(_asymptotic_loose, "dieterich_constant_asymptotic(alpha)",
             "dieterich_constant_asymptotic(model)")
def dieterich_constant_asymptotic(model: TrapModel) -> float:
    """``C_inf``: Dieterich constant matching ``mu_d`` and ``mu_s`` as ``u -> inf`` (ours;
    module docstring). Only ``model.alpha`` enters (the first orders in ``eps`` of both curves
    are proportional to ``eps``, for either creep law); the athermal model only."""
    _athermal(model, "dieterich_constant_asymptotic")
    return _asymptotic_loose(model.alpha)


def _least_squares_loose(
    eps: float,
    alpha: float = 0.13,
    u_min: float = 0.01,
    u_max: float = 100.0,
    n: int = 81,
    creep: str = "log",
) -> float:
    """:func:`dieterich_constant_least_squares` with the parameters loose (its old form)."""
    eps = check_scalar("eps", eps, 0.0, lo_open=True)
    alpha = check_alpha(alpha)
    u_min = check_scalar("u_min", u_min, 0.0, lo_open=True)
    u_max = check_scalar("u_max", u_max, u_min, lo_open=True)
    check_choice("creep", creep, CREEP_LAWS)
    u = np.logspace(np.log10(u_min), np.log10(u_max), int(n))
    model = TrapModel(alpha, eps, creep)
    mu_d = steady_friction(model, u)

    def cost(log_c: float) -> float:
        return float(np.sum((mu_d - static_friction(model, np.exp(log_c) / u)) ** 2))

    from scipy.optimize import minimize_scalar  # lazily: slow to import

    res = minimize_scalar(cost, bounds=(np.log(1e-3), np.log(1e3)), method="bounded",
                          options={"xatol": 1e-10})
    return float(np.exp(res.x))


@takes_model(_least_squares_loose,
             "dieterich_constant_least_squares(eps, alpha, u_min, u_max, n, creep)",
             "dieterich_constant_least_squares(model, u_min, u_max, n)")
def dieterich_constant_least_squares(model: TrapModel, u_min: float = 0.01,
                                     u_max: float = 100.0, n: int = 81) -> float:
    """``C`` minimising ``sum (mu_d(u_i) - mu_s(C/u_i))^2`` on ``n`` log-spaced ``u`` in
    ``[u_min, u_max]`` (reduced ``a0/t0``) for ``model`` (Fig. 6); ``model.eps > 0``, the
    athermal model only."""
    _athermal(model, "dieterich_constant_least_squares")
    return _least_squares_loose(model.eps, model.alpha, u_min, u_max, n, model.creep)


def _local_loose(
    u: ArrayLike, eps: ArrayLike, alpha: float = 0.13, creep: str = "log"
) -> Array:
    """:func:`dieterich_constant_local` with the parameters loose and ``eps`` broadcast with
    ``u`` (its old form, and the core of :func:`dieterich_constant_local_over_eps`).

    ``mu_s`` depends on ``T`` only through the aged radius ``r = a_r(T)`` and increases with
    it; ``r`` is found by bisection and ``T`` from the creep law's inverse. NaN where
    ``mu_d(u) < 1`` (no waiting time gives a static friction that low).
    """
    alpha = check_alpha(alpha)
    check_choice("creep", creep, CREEP_LAWS)
    u = check_range("u", u, 0.0, lo_open=True)
    eps = check_range("eps", eps, 0.0, lo_open=True)
    check_broadcast(u=u, eps=eps)

    u_b, eps_b = np.broadcast_arrays(u, eps)
    tgt = np.asarray(steady_friction_over_eps(TrapModel(alpha, creep=creep), u_b, eps_b), float)
    # mu_s(r) does not depend on eps: one bisection for every point, in bounded chunks
    flat = np.atleast_1d(tgt).ravel()
    r = np.empty(flat.size)
    for i0 in range(0, flat.size, PER_EPS_CHUNK):
        r[i0:i0 + PER_EPS_CHUNK] = _radius_at_static_friction(flat[i0:i0 + PER_EPS_CHUNK], alpha)
    T = per_eps(lambda law, rr: law.age(law.clock_at_radius(rr)), creep, eps_b,
                r.reshape(tgt.shape))
    return np.where(tgt >= 1.0, u_b * T, np.nan)[()]


@takes_model(_local_loose, "dieterich_constant_local(u, eps, alpha, creep)",
             "dieterich_constant_local(model, u)")
def dieterich_constant_local(model: TrapModel, u: ArrayLike) -> Array:
    """``C(u) = u T`` with ``mu_s(T) = mu_d(u)`` for ``model``: where the two curves meet
    (eq. 36 inverted). ``mu_s`` depends on ``T`` only through the aged radius ``r = a_r(T)``
    and increases with it; ``r`` is found by bisection and ``T`` from the creep law's inverse.
    NaN where ``mu_d(u) < 1`` (no waiting time gives a static friction that low).
    ``model.eps > 0``; the athermal model only."""
    _athermal(model, "dieterich_constant_local")
    return _local_loose(u, model.eps, model.alpha, model.creep)


def dieterich_constant_local_over_eps(model: TrapModel, u: ArrayLike, eps: ArrayLike) -> Array:
    """:func:`dieterich_constant_local` with ``model.eps`` replaced by every value of ``eps``,
    broadcast with ``u``: a sweep over the creep parameter in one vectorised call (a figure);
    ``eps > 0``. At a scalar ``e`` it equals ``dieterich_constant_local(model.replace(eps=e),
    u)``."""
    _athermal(model, "dieterich_constant_local_over_eps")
    return _local_loose(u, eps, model.alpha, model.creep)


def _radius_at_static_friction(tgt: Array, alpha: float) -> Array:
    """Aged radius ratio ``r >= 1`` with ``mu_s(r) = tgt`` (bisection; ``mu_s`` increases
    with ``r``); tends to 1 where ``tgt <= 1``."""
    model = TrapModel(alpha)
    lo = np.ones_like(tgt)
    hi = np.full_like(tgt, 2.0)
    while np.any(static_friction_at_radius(model, hi) < tgt):
        hi = np.where(static_friction_at_radius(model, hi) < tgt, 2.0 * hi, hi)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        below = static_friction_at_radius(model, mid) < tgt
        lo = np.where(below, mid, lo)
        hi = np.where(below, hi, mid)
    return 0.5 * (lo + hi)
