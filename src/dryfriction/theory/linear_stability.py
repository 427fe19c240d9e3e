"""Linear stability and rate-and-state twin of steady sliding of a :class:`.model.TrapModel`:
the model's entry points (:func:`critical_stiffness`, :func:`effective_rsf`,
:func:`linear_response`), the direct effect included when the model has one (ours).

The population's response and its Nyquist scan live in :mod:`.stability` (which this module
only calls). Units as there: lengths ``a0``, times ``t0``, forces ``F_el``, stiffness
``F_el/a0``.

**Linear response.** With the direct effect (:mod:`.direct`) the friction is
``mu = g(V) mu_age``. Perturbing the slider, ``X = u t + xi``, ``V = u + xi'``; to first order
``delta mu = g(u) delta mu_age + g'(u) mu_d(u) xi'``, so with ``xi = e^{lambda t}``

    Z_A(lambda) = g(u) Z(lambda) + (a_d / u) lambda,    a_d = u g'(u) mu_d(u)  (-> A mu_d),

``Z`` the athermal response of :mod:`.stability`. The new term is the instantaneous,
positive one (the asperity tips re-equilibrate at once): it acts on the spring-slider
``chi = M lambda^2 + eta lambda + K + Z_A`` exactly like a viscous damping ``a_d/u``. As
``Im Z(i omega)`` stays bounded, the crossings ``(eta + a_d/u) omega + g Im Z(i omega) = 0`` stop
at a finite frequency, so ``K_c`` with ``M = eta = 0`` becomes finite (no supremum at
infinity), as in quasi-static rate-and-state, whose ``K_c = (b - a)/Dc`` it parallels.

**Rate-and-state twin.** Matching the Taylor series of ``Z_A`` at 0 as in
:func:`.stability.rsf_from_response`: ``Z_A`` has derivatives ``g Z_1 + a_d/u``, ``g Z_2``,
``g Z_3``, so ``Dc`` is unchanged, ``b -> g b`` and ``a -> g a + a_d``.

A :class:`DirectResponse` has the ``Z`` and ``tau_d`` of a :class:`.stability.SteadyResponse`,
so :func:`.stability.characteristic` and :func:`.stability.rightmost_root` accept it as is.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..validation import check_scalar
from .direct import junction_log_slope, junction_strength
from .model import TrapModel
from .stability import (
    CArray,
    StabilityResult,
    SteadyResponse,
    nyquist_crossings,
    nyquist_stiffness,
    rsf_from_response,
    steady_response,
)
from .steady import steady_friction

__all__ = ["DirectResponse", "linear_response", "critical_stiffness", "effective_rsf"]


@dataclass(frozen=True)
class DirectResponse:
    """``Z_A(lambda) = g Z(lambda) + (a_d/u) lambda`` at one steady state (module docstring).

    Attributes
    ----------
    base : SteadyResponse
        The athermal response ``Z``.
    g : float
        Junction strength ``g(u)``.
    a_direct : float
        ``a_d = u g'(u) mu_d(u)``, units ``F_el``.
    """

    base: SteadyResponse
    g: float
    a_direct: float

    @property
    def u(self) -> float:
        return self.base.u

    @property
    def tau_d(self) -> float:
        return self.base.tau_d

    def Z(self, lam: ArrayLike) -> CArray:
        lam = np.asarray(lam, dtype=complex)
        return self.g * self.base.Z(lam) + (self.a_direct / self.base.u) * lam

    def derivative_at_zero(self, n: int) -> float:
        d = self.g * self.base.derivative_at_zero(n)
        return d + self.a_direct / self.base.u if n == 1 else d

    def im_bound(self) -> float:
        """Upper bound of ``g |Im Z(i omega)|`` over all ``omega`` (sum of the weights)."""
        b = self.base
        return self.g * (float(np.sum(np.abs(b.b))) + abs(b.edge * b.edge_delay)) / b.H0


def linear_response(u: float, model: TrapModel) -> SteadyResponse | DirectResponse:
    """Linear response of the friction in steady sliding at ``u``: the population's
    :class:`.stability.SteadyResponse` for an athermal model (``direct = 0``, the same object
    bit for bit), else ``Z_A = g Z + (a_d/u) lambda`` (module docstring)."""
    base = steady_response(u, model)
    if model.direct == 0.0:
        return base
    mu_d = float(steady_friction(model.athermal, u))
    g = float(junction_strength(u, model.direct, model.v_ref))
    a_d = float(junction_log_slope(u, model.direct, model.v_ref)) * mu_d
    return DirectResponse(base=base, g=g, a_direct=a_d)


def critical_stiffness(
    u: float, model: TrapModel, mass: float = 0.0, damping: float = 0.0,
    omega_max: float | None = None, n_omega: int | None = None,
) -> StabilityResult:
    """Critical stiffness ``K_c`` of a spring-slider of mass ``mass`` (``F_el t0^2/a0``) and
    damping ``damping`` (``F_el t0/a0``) pulled at ``u`` over ``model``, and the frequency at
    onset.

    Athermal model: :func:`.stability.nyquist_stiffness` (``n_omega`` default 4000), where
    ``K_c`` with ``M = eta = 0`` may be a supremum at infinite frequency. With the direct effect
    (module docstring) the scan reaches ``omega_max = max(200/tau_d, 2 u B/(eta u + a_d))``
    (unless given) with ``B`` the bound :meth:`DirectResponse.im_bound`: beyond it
    ``(eta + a_d/u) omega`` exceeds ``|g Im Z|`` and no crossing exists, so the largest
    crossing found is ``K_c`` (finite even with ``M = eta = 0``; ``n_omega`` default 20000).
    """
    mass = check_scalar("mass", mass, 0.0)
    damping = check_scalar("damping", damping, 0.0)
    resp = linear_response(u, model)
    if not isinstance(resp, DirectResponse):
        return nyquist_stiffness(resp, mass, damping, omega_max,
                                 4000 if n_omega is None else n_omega)
    visc = damping + resp.a_direct / resp.u
    if omega_max is None:
        omega_max = 200.0 / resp.tau_d
        if visc > 0.0:
            omega_max = max(omega_max, 2.0 * resp.im_bound() / visc)
    else:
        omega_max = check_scalar("omega_max", omega_max, 0.0, lo_open=True)
    best_K, best_om = nyquist_crossings(resp.Z, mass, damping, omega_max,
                                        20000 if n_omega is None else n_omega)
    h = 1e-6 * max(1.0, 1.0 / resp.tau_d)
    slope = float((resp.Z(h) - resp.Z(-h)).real / (2 * h))
    b = resp.base
    # a sudden forward shift: the population's Z(inf) scaled by g; the direct term is a rate
    # term (infinite at a true jump of position), so it does not enter the shift stiffness
    return StabilityResult(
        u=b.u, eps=b.eps, alpha=b.alpha, mass=mass, damping=damping,
        critical_stiffness=max(best_K, 0.0) if np.isfinite(best_K) else 0.0, omega=best_om,
        forward_stiffness=resp.g * (b.A + b.edge) / b.H0, backward_stiffness=resp.g * b.A / b.H0,
        velocity_slope=slope, supremum_at_infinity=False)


def effective_rsf(u: float, model: TrapModel) -> dict[str, float]:
    """Effective rate-and-state ``a``, ``b`` (units ``F_el``), ``Dc`` (``a0``) of ``model`` at
    ``u``: the Taylor matching of :func:`.stability.rsf_from_response` applied to the friction's
    response, so with the direct effect ``a = g a_0 + a_d``, ``b = g b_0``, ``Dc`` unchanged
    (module docstring); also the direct part ``a_direct = a_d ~ A mu_d`` (0 when athermal)."""
    resp = linear_response(check_scalar("u", u, 0.0, lo_open=True), model)
    out = rsf_from_response(resp)
    return {**out, "a_direct": resp.a_direct if isinstance(resp, DirectResponse) else 0.0}
