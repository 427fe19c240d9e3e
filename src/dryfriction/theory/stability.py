"""Linear stability of steady sliding against stick-slip (docs/model.md §6 "Stability"; ours).

The paper's §7 is not in the seed; this module rebuilds the linear analysis from the model.
Reduced units: lengths ``a0``, times ``t0``, forces ``F_el``; stiffness ``K`` in ``F_el/a0``,
mass ``M`` in ``F_el t0^2/a0``, damping ``eta`` in ``F_el t0/a0``.

**Linear response of the steady population.** Label the traps of the steady state at velocity
``u`` by their age ``tau`` (position ``y = u tau - 1``, eq. 29). Perturb the slider,
``X(t) = u t + xi(t)``. To first order every trap is shifted by ``xi(t)``, it is older by
``xi(t - tau)/u`` (it entered contact earlier or later), and the edge where traps leave the
(+) branch (``y/r = y_c``, eq. 32) moves. With ``g(y, theta) = r(theta)^2 f(y/r)`` the force
per trap (eq. 31) and ``xi = e^{lambda t}``, the friction changes by ``delta mu = Z(lambda) xi``,

    H0 Z(lambda) = int_0^{tau_end} [u g_y + g_theta e^{-lambda tau}] dtau
                   - u Delta g_d [1 - (y_c r'_d/u) e^{-lambda tau_d}] / (u - y_c r'_d),

where ``tau_d`` is the age at the spinodal, ``r'_d = dr/dtheta`` there and ``Delta g_d`` the
force lost there per trap (``r_d^2 f_+(y_c)`` in very strong pinning, ``r_d^2 [f_+ - f_-](y_c)``
in strong pinning). Checks: ``Z(0) = 0`` (a constant shift is a relabelling) and
``Z'(0) = d mu_d / du`` (the slope of :func:`dryfriction.steady.steady_friction`).

**The non-smooth part.** ``Z(lambda -> inf)`` along the real axis is the response to a sudden
forward shift at frozen ages: the stiffening of all traps (``int u g_y dtau``, which alone is
the stiffness met by a *backward* shift, where no trap dies) minus the force of the traps
killed at the edge. Without ageing the two cancel; with ageing the edge traps are the oldest
and strongest and the forward response is *negative* (:func:`shift_stiffness`). The linear
analysis holds as long as the slider keeps moving forward (``|xi'| < u``): then the edge always
advances and the forward branch applies. A finite-amplitude slip that stops or reverses the
slider meets the large backward stiffness instead, so the bifurcation cannot be smooth: the
linear growth or decay says nothing about the amplitude of stick-slip, which must come from
direct simulation.

**Spring-slider.** ``M X'' = K (u t - X) - mu - eta X'`` gives the characteristic function
``chi(lambda) = M lambda^2 + eta lambda + K + Z(lambda)``; steady sliding is linearly stable
when every root has ``Re lambda < 0``. Roots cross the imaginary axis at ``lambda = i omega``
where ``eta omega + Im Z(i omega) = 0``, at the stiffness ``K = M omega^2 - Re Z(i omega)``;
``K_c`` is the largest such ``K``. With ``M = 0`` and ``eta = 0`` the delay term makes the
Nyquist curve circle forever at high frequency (no inertia or damping filters it); then the
supremum over frequencies is reported (it is approached as ``omega -> inf``) and a real root
arrives from infinity once ``K < -Z(inf)``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from ..validation import Array, check_choice, check_scalar
from .creep import CREEP_LAWS, CreepLaw, creep_law
from .steady import death_clock
from .trap import Trap, force_minus, force_plus

__all__ = [
    "SteadyResponse",
    "steady_response",
    "shift_stiffness",
    "characteristic",
    "StabilityResult",
    "critical_stiffness",
    "rightmost_root",
    "effective_rsf",
    "nyquist_crossings",
]

CArray = NDArray[np.complex128]

_S, _SW = np.polynomial.legendre.leggauss(96)
_S = 0.5 * (_S + 1.0)
_SW = 0.5 * _SW


def _dforce_plus(w: Array, alpha: float) -> Array:
    """``f_+'(w) = 6 alpha (1 - alpha / sqrt((1-alpha)^2 - 4 alpha w))`` (from docs/model.md §1)."""
    disc = np.maximum((1.0 - alpha) ** 2 - 4.0 * alpha * w, 1e-300)
    return 6.0 * alpha * (1.0 - alpha / np.sqrt(disc))


def _dforce_minus(w: Array, alpha: float) -> Array:
    """``f_-'(w) = f_+'(-w)`` (symmetry ``f_-(w) = -f_+(-w)``)."""
    return _dforce_plus(-w, alpha)


@dataclass(frozen=True)
class SteadyResponse:
    """Quadrature nodes of the steady population at one ``(u, eps, alpha)``, ready for ``Z``.

    Attributes are arrays over the nodes (ages ``T`` in ``t0``): the static part ``A`` of
    ``H0 Z`` (``int u g_y dtau``), the weights ``b`` of ``e^{-lambda T}`` in ``H0 Z``, and the
    spinodal-edge terms.
    """

    u: float
    eps: float
    alpha: float
    H0: float
    A: float
    T: Array
    b: Array
    tau_d: float
    edge: float
    edge_delay: float

    def derivative_at_zero(self, n: int) -> float:
        """``d^n Z / d lambda^n`` at ``lambda = 0``: moments of the age distribution (ours)."""
        edge = -self.edge * self.edge_delay * (-self.tau_d) ** n
        return float((np.sum(self.b * (-self.T) ** n) + edge) / self.H0)

    def Z(self, lam: ArrayLike) -> CArray:
        """``Z(lambda)``: friction change (units ``F_el``) per unit slip perturbation (``a0``)."""
        lam = np.asarray(lam, dtype=complex)
        # far in the left half-plane e^{-lambda T} overflows: the value is then inf/nan,
        # which the root search discards
        with np.errstate(over="ignore", invalid="ignore"):
            memory = np.exp(-lam[..., None] * self.T) @ self.b
            edge = self.edge * (1.0 - self.edge_delay * np.exp(-lam * self.tau_d))
        return (self.A + memory + edge) / self.H0


def _pieces(law: CreepLaw, u: float, alpha: float) -> SteadyResponse:
    trap = Trap(alpha)
    yc = trap.y_c
    uu = np.array([u])
    c_d = float(death_clock(law, uu, yc)[0])
    # (+) branch: c = c_d (1 - s^2) removes the 1/sqrt of f_+' at the spinodal
    c = c_d * (1.0 - _S**2)
    wts = 2.0 * c_d * _S * _SW
    branches = [(c, wts, force_plus, _dforce_plus)]
    if yc < 1.0:  # strong pinning: (-) branch up to w = 1
        c_e = float(death_clock(law, uu, 1.0)[0])
        branches.append((c_d + (c_e - c_d) * _S, (c_e - c_d) * _SW, force_minus, _dforce_minus))
    A = 0.0
    Ts, bs = [], []
    for cc, ww, f, df in branches:
        R = law.radius_sq(cc)
        r = np.sqrt(R)
        T = law.age(cc)
        w = np.clip((-1.0 + u * T) / r, -1.0, yc if f is force_plus else 1.0)
        fv, dfv = f(w, alpha), df(w, alpha)
        # u g_y dtau = u r f'(w) T'(c) dc ;  g_theta dtau = (R'(c)/2) [2 f - w f'] dc
        A += float(np.sum(u * r * dfv * law.dage(cc) * ww))
        Ts.append(T)
        bs.append(0.5 * law.dradius_sq(cc) * (2.0 * fv - w * dfv) * ww)
    R_d = float(law.radius_sq(c_d))
    r_d = np.sqrt(R_d)
    tau_d = float(law.age(c_d))
    rp_d = float(law.dradius_sq(c_d)) / (2.0 * r_d * float(law.dage(c_d)))
    # f_+(y_c) from its closed form: evaluating f_+ at a rounded y_c costs sqrt(ulp)
    jump = trap.f_c - (float(force_minus(yc, alpha)) if yc < 1.0 else 0.0)
    dg = R_d * jump
    edge = -u * dg / (u - yc * rp_d)
    return SteadyResponse(u=u, eps=law.eps, alpha=alpha, H0=trap.H0, A=A,
                          T=np.concatenate(Ts), b=np.concatenate(bs), tau_d=tau_d, edge=edge,
                          edge_delay=yc * rp_d / u)


def steady_response(
    u: float, eps: float, alpha: float = 0.13, creep: str = "log"
) -> SteadyResponse:
    """Linear response ``Z(lambda)`` of steady sliding at reduced velocity ``u`` (module doc).

    Parameters
    ----------
    u : float
        Reduced velocity ``V t0 / a0``, ``> 0``.
    eps : float
        Creep parameter, ``>= 0``.
    alpha : float
        Reduced trap stiffness, ``0 < alpha < 1``.
    creep : {"log", "eyring-nabarro"}
        Ageing law.
    """
    u = check_scalar("u", u, 0.0, lo_open=True)
    eps = check_scalar("eps", eps, 0.0)
    alpha = check_scalar("alpha", alpha, 0.0, 1.0, lo_open=True, hi_open=True)
    check_choice("creep", creep, CREEP_LAWS)
    return _pieces(creep_law(creep, eps), u, alpha)


def shift_stiffness(
    u: float, eps: float, alpha: float = 0.13, creep: str = "log"
) -> tuple[float, float]:
    """Stiffness (units ``F_el/a0``) met by a sudden small shift of the steady population.

    Returns ``(forward, backward)``: ``forward = Z(inf)``, where the traps killed at the edge
    offset the stiffening of the others (zero without ageing, negative with it);
    ``backward = int u g_y dtau / H0``, the full elastic stiffness (no trap dies).
    """
    resp = steady_response(u, eps, alpha, creep)
    return (resp.A + resp.edge) / resp.H0, resp.A / resp.H0


def characteristic(
    lam: ArrayLike, resp: SteadyResponse, stiffness: float, mass: float = 0.0,
    damping: float = 0.0,
) -> CArray:
    """``chi(lambda) = M lambda^2 + eta lambda + K + Z(lambda)`` of the spring-slider."""
    lam = np.asarray(lam, dtype=complex)
    return mass * lam**2 + damping * lam + stiffness + resp.Z(lam)


@dataclass(frozen=True)
class StabilityResult:
    """Critical stiffness ``K_c`` (``F_el/a0``) and onset angular frequency (``1/t0``)."""

    u: float
    eps: float
    alpha: float
    mass: float
    damping: float
    critical_stiffness: float
    omega: float
    forward_stiffness: float
    backward_stiffness: float
    velocity_slope: float
    supremum_at_infinity: bool

    def to_dict(self) -> dict[str, float | bool]:
        return dict(self.__dict__)


def nyquist_crossings(
    Z: Callable[[ArrayLike], CArray],
    mass: float,
    damping: float,
    omega_max: float,
    n_omega: int = 4000,
) -> tuple[float, float]:
    """Largest stiffness at which ``M lambda^2 + eta lambda + K + Z(lambda)`` has a root on the
    imaginary axis, and that root's frequency: ``(K, omega)``; ``(-inf, nan)`` if none.

    Scans ``omega`` on a log grid over ``[1e-7, 1] * omega_max``, brackets the zeros of
    ``eta omega + Im Z(i omega)`` and evaluates ``K = M omega^2 - Re Z(i omega)`` there. Any
    linear response ``Z`` (units of ``K``) can be given.
    """
    omega_max = check_scalar("omega_max", omega_max, 0.0, lo_open=True)
    om = np.geomspace(omega_max * 1e-7, omega_max, int(n_omega))

    def im(o: float) -> float:
        return float(damping * o + Z(1j * o).imag)

    vals = damping * om + Z(1j * om).imag
    best_K, best_om = -np.inf, np.nan
    for i in np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)[0]:
        o = brentq(im, om[i], om[i + 1], xtol=1e-14 * om[i], maxiter=200)
        K = mass * o**2 - float(Z(1j * o).real)
        if K > best_K:
            best_K, best_om = K, o
    return best_K, best_om


def critical_stiffness(
    u: float,
    eps: float,
    alpha: float = 0.13,
    creep: str = "log",
    mass: float = 0.0,
    damping: float = 0.0,
    omega_max: float | None = None,
    n_omega: int = 4000,
) -> StabilityResult:
    """Critical stiffness ``K_c(u; eps, alpha, M, eta)`` and the frequency at onset.

    Scans ``omega`` on a log grid up to ``omega_max`` (default ``200/tau_d``, ``tau_d`` the
    age at which traps die), finds the zeros of ``eta omega + Im Z(i omega)`` by bracketing,
    and returns the largest ``K = M omega^2 - Re Z(i omega)`` among them. When ``M = eta = 0``
    the crossings never stop (module doc): the largest value found up to ``omega_max`` is
    returned with ``supremum_at_infinity = True``.
    """
    mass = check_scalar("mass", mass, 0.0)
    damping = check_scalar("damping", damping, 0.0)
    resp = steady_response(u, eps, alpha, creep)
    if omega_max is None:
        omega_max = 200.0 / resp.tau_d
    best_K, best_om = nyquist_crossings(resp.Z, mass, damping, omega_max, n_omega)
    fwd, bwd = (resp.A + resp.edge) / resp.H0, resp.A / resp.H0
    at_inf = False
    if mass == 0.0 and damping == 0.0 and -fwd > best_K:
        best_K, best_om, at_inf = -fwd, np.inf, True
    h = 1e-6 * max(1.0, 1.0 / resp.tau_d)
    slope = float((resp.Z(h) - resp.Z(-h)).real / (2 * h))
    return StabilityResult(u=resp.u, eps=resp.eps, alpha=resp.alpha, mass=mass, damping=damping,
                           critical_stiffness=max(best_K, 0.0) if np.isfinite(best_K) else 0.0,
                           omega=best_om, forward_stiffness=fwd, backward_stiffness=bwd,
                           velocity_slope=slope, supremum_at_infinity=at_inf)


def rightmost_root(
    resp: SteadyResponse, stiffness: float, mass: float = 0.0, damping: float = 0.0,
    n_seeds: int = 24,
) -> complex:
    """Root of ``chi`` with the largest real part found by Newton from seeds (growth rate).

    Seeds lie on ``lambda = s (cos phi + i sin phi) / tau_d`` over a grid of ``s`` and
    ``phi in [-pi/2, pi/2]``; each Newton run uses the derivative of ``chi`` by complex-step
    differences. A positive real part means an unstable mode growing as ``e^{Re lambda t}``.
    """
    stiffness = check_scalar("stiffness", stiffness, 0.0, lo_open=True)
    scale = 1.0 / resp.tau_d
    seeds = [s * scale * np.exp(1j * p) for s in np.geomspace(0.05, 50.0, n_seeds // 4)
             for p in (-1.2, -0.4, 0.4, 1.2)]
    best = complex(-np.inf, 0.0)
    # a Newton run may wander off to |lambda| ~ 1e200, where chi overflows: that seed is
    # dropped (no warning, no OverflowError), the others still find the root
    with np.errstate(all="ignore"):
        for z in seeds:
            for _ in range(60):
                h = 1e-7 * max(abs(z), scale)
                f = complex(characteristic(z, resp, stiffness, mass, damping))
                df = (complex(characteristic(z + h, resp, stiffness, mass, damping)) - f) / h
                if df == 0 or not (np.isfinite(df) and np.isfinite(f)):
                    break
                step = f / df
                z = z - step
                if not np.isfinite(z):
                    break
                if abs(step) < 1e-13 * max(abs(z), scale):
                    break
            else:
                continue
            if not np.isfinite(z):
                continue
            residual = np.abs(np.complex128(characteristic(z, resp, stiffness, mass, damping)))
            if residual < 1e-8 and z.real > best.real:
                best = z
    return best


def effective_rsf(
    u: float, eps: float, alpha: float = 0.13, creep: str = "log"
) -> dict[str, float]:
    """Rate-and-state parameters that reproduce the model's slow linear response (ours).

    Linearised rate-and-state friction (ageing or slip law, Ruina 1983; Rice & Ruina 1983)
    responds to a slip perturbation ``xi ~ e^{lambda t}`` at velocity ``V`` with
    ``delta mu = (lambda/V) [a - b V/(V + lambda Dc)] xi``. Matching its Taylor series at
    ``lambda = 0`` to that of ``Z(lambda)`` up to third order, with ``Z_n`` the n-th
    derivative at 0, gives ``Dc = -u Z_3 / (3 Z_2)``, ``b = u^2 Z_2 / (2 Dc)`` and
    ``a = u Z_1 + b``. Units: ``a``, ``b`` in ``F_el`` (multiply by ``mu_el`` for a friction
    coefficient), ``Dc`` in ``a0``. They describe slow perturbations only: at high frequency
    the model's response tends to the finite, negative ``Z(inf)`` (:func:`shift_stiffness`),
    not to rate-and-state's ``a lambda / V``.
    """
    resp = steady_response(u, eps, alpha, creep)
    z1, z2, z3 = (resp.derivative_at_zero(n) for n in (1, 2, 3))
    if z2 == 0.0:
        raise ValueError("eps = 0: the response vanishes, no rate-and-state parameters")
    dc = -u * z3 / (3.0 * z2)
    b = u * u * z2 / (2.0 * dc)
    return {"a": u * z1 + b, "b": b, "dc": dc, "u": u}
