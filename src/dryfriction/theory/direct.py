"""The direct effect: thermally activated junction rheology on top of creep ageing.

**[reading]** Baumberger & Caroli (Adv. Phys. 55, 279 (2006)): the interfacial junctions yield
by thermally activated (Eyring) plasticity, so their shear strength depends on the present slip
rate, ``sigma_s(V) = sigma_s0 [1 + A ln(V/V_ref)]`` with ``A = kT/(sigma_s0 v*)`` (``v*`` an
activation volume), and friction is (real contact area, aged by creep) x (junction strength at
the present slip rate).

**Regularisation (reading).** ``g(V) = A asinh(V e^{1/A} / (2 V_ref))``. For
``V >> V_ref e^{-1/A}``, ``asinh(x) = ln(2x) + O(x^-2)`` gives ``g = 1 + A ln(V/V_ref)``; the
form is odd and finite at ``V = 0`` (``g(0) = 0``: a junction under any stress creeps, so at
exactly zero slip rate it carries no stress). The crossover velocity ``V_ref e^{-1/A}`` is
astronomically small for ``A ~ 0.01`` (``e^{-100}``), so ``g`` is computed from ``ln x``
without forming ``x`` (``e^{1/A}`` overflows for ``A < 1/709``).

**How g enters a trap (ours).** The junction strength sets the pinning amplitude,
``Phi0 -> Phi0 g(V)``. Two readings:

* *prefactor only* (chosen): the whole trap force is scaled, ``f -> g(V) f``, with
  ``alpha = kappa a^2/(6 Phi0)`` and so the spinodal ``y_c`` unchanged. Friction is then exactly
  the product ``mu = g(V) mu_age`` (the population of the athermal model times the strength),
  which is Baumberger-Caroli's form, keeps eq. 22's rate- and age-independent ``alpha``, and
  makes ``A = 0`` the athermal model exactly;
* *spinodal moves*: ``kappa`` fixed, ``alpha -> alpha/g``. Then ``mu = g H0(alpha/g)/H0(alpha)
  mu_age``, whose direct coefficient is ``A (1 - d ln H0/d ln alpha)`` = ``1.70 A`` at
  ``alpha = 0.13`` (``d ln H0/d ln alpha = -0.70``), and ``y_c`` shifts by ``(1 + alpha)/
  (1 - alpha) y_c A ln(V2/V1)`` at a step (``1.30 y_c`` per unit ``A ln``), so a step down
  kills the traps between the two spinodals: the jump is then not purely instantaneous.

Both are ``O(A)`` on the force: the second only renormalises the fitted ``A`` by 1.70 at leading
order and adds an ``O(A y_c)`` change of the memory length. We take the first: it is the
physical product form, its ``A`` is the measured ``a/mu`` directly, and the population dynamics
(the compiled kernel) are untouched, so the ensemble force is ``g(V) x`` the athermal force.

**Instantaneous response.** The asperity tips re-equilibrate instantly, so a velocity jump
``V1 -> V2`` multiplies the force at once by ``g(V2)/g(V1)``: ``delta mu = mu (g2/g1 - 1)``,
``~ A mu ln(V2/V1)`` -- the rate-and-state ``a = A mu`` (``mu`` the friction level, units
``F_el``).

Reduced units: velocities in ``a0/t0`` (``v_ref`` too); the SI forms live in :mod:`.units`.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..validation import Array, check_direct

__all__ = ["junction_strength", "junction_log_slope", "instantaneous_jump", "strength_ratio"]


def _log_x(v: Array, direct: float, v_ref: float) -> Array:
    # ln x, x = |V| e^{1/A} / (2 V_ref): never forms e^{1/A}
    with np.errstate(divide="ignore"):
        return np.log(np.abs(v) / (2.0 * v_ref)) + 1.0 / direct


def junction_strength(v: ArrayLike, direct: float, v_ref: float = 1.0) -> Array:
    """Junction strength ratio ``g(V) = A asinh(V e^{1/A} / (2 V_ref))`` (module docstring).

    Parameters
    ----------
    v : array_like
        Slip rate, reduced ``a0/t0`` (any sign; ``g`` is odd).
    direct : float
        ``A``, ``0 <= A <= 1``. ``A = 0`` gives ``g = 1`` everywhere (the athermal model;
        callers skip the factor then, keeping their results bit for bit).
    v_ref : float
        Reference velocity where ``g = 1`` (in the large-``V`` form), reduced, ``> 0``.

    Returns
    -------
    ndarray
        ``g``; ``1 + A ln(V/V_ref)`` up to ``A (2x)^-2`` for ``x >> 1``; 0 at ``V = 0``.
    """
    direct, v_ref = check_direct(direct, v_ref)
    v = np.asarray(v, dtype=float)
    if direct == 0.0:
        return np.ones_like(v)
    lx = _log_x(v, direct, v_ref)
    big = lx > 0.0
    # x > 1: asinh x = ln x + ln(1 + sqrt(1 + x^-2)), and A ln x = A ln(V/2V_ref) + 1
    lb = np.where(big, lx, 0.0)
    g_big = direct * (lb + np.log1p(np.sqrt(1.0 + np.exp(-2.0 * lb))))
    g_small = direct * np.arcsinh(np.exp(np.minimum(lx, 0.0)))
    return np.sign(v) * np.where(big, g_big, g_small)


def strength_ratio(v: float, direct: float, v_ref: float) -> float:
    """:func:`junction_strength` for one checked ``direct > 0`` and ``v_ref``, without the
    checks or arrays: the ensemble's force-balance solvers call it at every iteration."""
    if v == 0.0:
        return 0.0
    lx = math.log(abs(v) / (2.0 * v_ref)) + 1.0 / direct
    if lx > 0.0:
        g = direct * (lx + math.log1p(math.sqrt(1.0 + math.exp(-2.0 * lx))))
    else:
        g = direct * math.asinh(math.exp(lx))
    return math.copysign(g, v)


def strength_slope(v: float, direct: float, v_ref: float) -> float:
    """``g'(V) = A / sqrt(V^2 + V_c^2)``, ``V_c = 2 V_ref e^{-1/A}``: the derivative of
    :func:`strength_ratio` (ours; the same checks skipped), from logarithms where ``V_c``
    underflows; ``inf`` at ``V = 0`` when ``A / V_c`` overflows."""
    log_vc = math.log(2.0 * v_ref) - 1.0 / direct
    if v == 0.0:
        return direct * math.exp(-log_vc) if log_vc > -700.0 else math.inf
    lx = math.log(abs(v)) - log_vc  # ln(|V| / V_c)
    if lx < -350.0:  # V << V_c: g' = A / V_c
        return direct * math.exp(-log_vc) if log_vc > -700.0 else math.inf
    return direct / (abs(v) * math.sqrt(1.0 + math.exp(-2.0 * lx)))


def junction_log_slope(v: ArrayLike, direct: float, v_ref: float = 1.0) -> Array:
    """``V g'(V) = A x / sqrt(1 + x^2)``: the direct coefficient at ``V`` (``-> A`` for
    ``x >> 1``, ``-> 0`` as ``V -> 0``)."""
    direct, v_ref = check_direct(direct, v_ref)
    v = np.asarray(v, dtype=float)
    if direct == 0.0:
        return np.zeros_like(v)
    lx = _log_x(v, direct, v_ref)
    return direct / np.sqrt(1.0 + np.exp(-2.0 * lx))


def instantaneous_jump(v1: ArrayLike, v2: ArrayLike, mu: ArrayLike, direct: float,
                       v_ref: float = 1.0) -> Array:
    """Friction jump at a velocity step ``v1 -> v2`` from the level ``mu`` (units of ``mu``):
    ``mu (g(v2)/g(v1) - 1)``, ``~ A mu ln(v2/v1)``."""
    g1 = junction_strength(v1, direct, v_ref)
    g2 = junction_strength(v2, direct, v_ref)
    return np.asarray(mu, float) * (g2 / g1 - 1.0)
