"""The nature of the Hopf bifurcation of steady sliding of the trap model with the direct
effect: a finite-dimensional reduction of the population, ``l1`` on it, refined until it
settles (every formula here is ours unless cited; results in docs/hopf.md).

**The slider as a delay equation.** In steady forward sliding (very strong pinning,
``alpha < alpha0``, docs/model.md §1) a trap is labelled by its age ``tau``; the slip since its
birth is ``sigma(tau, t) = X(t) - X(t - tau)`` (``X`` the slider position, ``a0``), its
reduced coordinate ``w = (sigma - 1)/r(tau)`` (eq. 29-31 with ``y = sigma - 1``), and the
traps born in ``dtau`` cover ``X'(t - tau) dtau = d sigma/d tau dtau`` of track (density 1 per
``a0``, eq. 33). The population's friction is therefore the functional

    mu_age(t) = (1/H0) int_0^{tau_end(t)} sigma_tau R(tau) f_+((sigma - 1)/sqrt(R)) dtau,
    sigma(tau_end) - 1 = y_c r(tau_end)                               (the spinodal, eq. 32)

with ``R = r^2 = a_r^2`` the creep law (eq. 19); at ``sigma = u tau`` it is eq. 34's
``mu_d(u)``. ``sigma`` obeys the transport equation ``sigma_t + sigma_tau = V(t)``,
``sigma(0, t) = 0``: the history enters linearly, all the nonlinearity is in ``mu_age``
(through ``tau_end`` and ``f_+``), and the functional is smooth as long as the slider keeps
moving forward (``sigma_tau > 0``; the backward branch of
:mod:`dryfriction.theory.stability` is not met by a small cycle). The friction is
``mu = g(V) mu_age`` (:mod:`dryfriction.theory.direct`) and the slider
``M V' = F - g(V) mu_age - eta V``, ``F' = K (u - V)`` (``F`` the spring force); with
``M = 0``, ``F = g(V) mu_age`` gives ``V`` explicitly,
``V = v_ref [e^{(g - 1)/A} - e^{-(g + 1)/A}]`` (the inverse of ``g = A asinh(V e^{1/A}/2 v_ref)``).

**The reduction.** ``sigma`` is represented by its values at ``n`` Chebyshev-Gauss-Lobatto
nodes on ``[0, L]`` (``sigma(0) = 0`` removed), ``L = stretch x tau_d`` beyond the death age,
the transport by the Chebyshev differentiation matrix: the pseudospectral discretisation of a
delay equation of Breda, Diekmann, Gyllenberg, Scarabel & Vermiglio (SIAM J. Appl. Dyn. Syst.
15, 1 (2016)), whose Hopf points and normal-form coefficients converge with ``n``. ``tau_end``
is found by Newton's method on the interpolant; the integral by composite Gauss-Legendre in
``s``, ``tau = tau_end (1 - (1 - s)^2)`` (which removes the square root of ``f_+`` at the
spinodal), panels graded towards ``tau = 0`` where ``ln(1 + tau)`` varies. The field is
holomorphic in the state for the log creep law (so :func:`.theory.hopf.first_lyapunov`'s
Cauchy circle applies); with the Eyring-Nabarro law the radius comes from its real routines
and the derivatives are real differences.

**Checks built in.** The steady state is an exact equilibrium of the discrete field; its
``mu_age`` equals :func:`dryfriction.theory.steady.steady_friction` to the quadrature's
precision; the Jacobian's critical stiffness and frequency converge to
:func:`dryfriction.theory.linear_stability.critical_stiffness` (the population's linear
response ``Z`` by a different route, the characteristic integrals) as ``n`` grows.

**Normalisation of l1.** The state is ``(xi, [ln(V/u)], sigma_1..sigma_n)`` with
``xi = (F - F_ss)/K`` (``a0``: the spring's stretch from steady sliding, ``xi' = u - V``), so
that every component is a slip or a log-velocity of order one at any ``K`` (a spring-force
coordinate made the eigenvector all force in the inertial regime, where the cubic term was
then lost in rounding). :func:`.theory.hopf.first_lyapunov` normalises ``|q| = 1`` over all
components, which changes with ``n``; the value reported, ``l1_x = l1/|q_xi|^2``, is the
coefficient where the slip component of the eigenvector has unit modulus (:mod:`.theory.hopf`:
``l1 -> l1/|T q|^2``), comparable across ``n``, in ``1/a0^2``. The cycle's half peak-to-peak
slip is ``2 sqrt(-beta/(omega l1_x))`` (``a0``) and its spring force ``K`` times that,
``beta = (d Re lambda/dK)(K - K_c)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import brentq

from ..theory.creep import LogCreep
from ..theory.direct import junction_log_slope, junction_strength
from ..theory.hopf import HopfPoint, first_lyapunov
from ..theory.linear_stability import critical_stiffness
from ..theory.model import TrapModel
from ..theory.steady import death_clock, steady_friction
from ..theory.trap import Trap
from ..validation import Array, check_scalar

__all__ = ["TrapField", "TrapHopf", "trap_hopf", "ALPHA0"]

ALPHA0 = 3.0 - 2.0 * math.sqrt(2.0)
"""Very strong pinning bound (docs/model.md §1): below it a trap dies at the spinodal."""

_GX, _GW = np.polynomial.legendre.leggauss(16)
_GX, _GW = 0.5 * (_GX + 1.0), 0.5 * _GW


def _cheb(n: int) -> tuple[Array, Array]:
    """Chebyshev-Gauss-Lobatto points ``x_j = cos(j pi/n)`` and the differentiation matrix
    (Trefethen, *Spectral Methods in MATLAB*, 2000, program ``cheb``)."""
    x = np.cos(np.pi * np.arange(n + 1) / n)
    c = np.r_[2.0, np.ones(n - 1), 2.0] * (-1.0) ** np.arange(n + 1)
    dx = x[:, None] - x[None, :]
    D = np.outer(c, 1.0 / c) / (dx + np.eye(n + 1))
    D -= np.diag(D.sum(axis=1))
    return x, D


def _fplus(w: Any, alpha: float) -> Any:
    """``f_+(w) = 6 alpha (w - z_+(w))`` (docs/model.md §1) written holomorphically."""
    z = -0.5 * ((1.0 - alpha) + np.sqrt((1.0 - alpha) ** 2 - 4.0 * alpha * w))
    return 6.0 * alpha * (w - z)


@dataclass
class TrapField:
    """The reduced spring-slider of the trap model (module docstring).

    Parameters
    ----------
    u : float
        Pulling velocity, ``a0/t0``.
    model : TrapModel
        With ``0 < direct`` and ``alpha < ALPHA0`` (very strong pinning).
    mass, damping : float
        ``M`` (``F_el t0^2/a0``) and ``eta`` (``F_el t0/a0``); ``damping`` only with mass.
    n : int
        Chebyshev nodes of the age profile.
    stretch : float
        ``L / tau_d``, the age domain beyond the death age (``> 1``).
    panels : int
        Gauss-Legendre panels (16 points each) of the friction integral.
    direct_form : {"asinh", "linear"}
        The junction strength ``g(V)``: the package's (:mod:`.theory.direct`), or its tangent
        at ``u``, ``g(u) + g'(u) (V - u)`` (an ingredient switch, docs/hopf.md: the same
        linear response, no curvature of the direct effect).
    """

    u: float
    model: TrapModel
    mass: float = 0.0
    damping: float = 0.0
    n: int = 32
    stretch: float = 1.25
    panels: int = 24
    direct_form: str = "asinh"
    _cache: dict[str, Any] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        check_scalar("u", self.u, 0.0, lo_open=True)
        check_scalar("mass", self.mass, 0.0)
        check_scalar("damping", self.damping, 0.0)
        if int(self.n) != self.n or self.n < 4:
            raise ValueError(f"n = {self.n} is not allowed: an integer >= 4")
        check_scalar("stretch", self.stretch, 1.0, lo_open=True)
        if int(self.panels) != self.panels or self.panels < 1:
            raise ValueError(f"panels = {self.panels} is not allowed: an integer >= 1")
        if self.model.direct == 0.0:
            raise ValueError("direct = 0 is not allowed here: the quasi-static slider has no "
                             "finite K_c without the direct effect; allowed 0 < direct <= 1")
        if self.model.alpha >= ALPHA0:
            raise ValueError(f"alpha = {self.model.alpha:g} is not allowed here: the reduction "
                             f"is written for very strong pinning, alpha < {ALPHA0:.4f}")
        if self.direct_form not in ("asinh", "linear"):
            raise ValueError(f"direct_form = {self.direct_form!r} is not allowed: 'asinh' or "
                             "'linear'")
        if self.mass == 0.0 and self.damping != 0.0:
            raise ValueError("damping is allowed only with mass > 0")
        m, u = self.model, self.u
        law = m.law
        self.trap = Trap(m.alpha)
        self.yc = self.trap.y_c
        c_d = float(death_clock(law, np.array([u]), self.yc)[0])
        self.tau_d = float(law.age(c_d))
        self.L = self.stretch * self.tau_d
        x, D = _cheb(self.n)
        # tau = L (1 - x)/2: node 0 at tau = 0 (the inflow), node n at tau = L
        self.tau = 0.5 * self.L * (1.0 - x)
        self.Dt = -2.0 / self.L * D  # d/dtau at the nodes
        self.bary = np.r_[0.5, np.ones(self.n - 1), 0.5] * (-1.0) ** np.arange(self.n + 1)
        self.holomorphic = isinstance(law, LogCreep)
        # panels in s (tau = tau_end (1 - (1 - s)^2)), graded: edges at the steady ages 0, 1/2,
        # 1, 2, ... doubled up to tau_d, then split evenly to reach `panels`
        edges_tau = [0.0] + [0.5 * 2.0**j for j in range(60) if 0.5 * 2.0**j < 0.5 * self.tau_d]
        edges = list(1.0 - np.sqrt(1.0 - np.array(edges_tau) / self.tau_d)) + [1.0]
        while len(edges) - 1 < self.panels:
            k = int(np.argmax(np.diff(edges)))
            edges.insert(k + 1, 0.5 * (edges[k] + edges[k + 1]))
        e = np.array(edges)
        self.s = (e[:-1, None] + np.diff(e)[:, None] * _GX).ravel()
        self.ws = (np.diff(e)[:, None] * _GW).ravel()
        self.g_u = float(junction_strength(u, m.direct, m.v_ref))
        self.g_slope = float(junction_log_slope(u, m.direct, m.v_ref)) / u  # g'(u)
        self.sigma_ss = u * self.tau[1:]
        self.mu_age_ss = float(np.real(self.mu_age(self.sigma_ss.astype(complex))))
        self.mu_d = float(steady_friction(m.athermal, u))  # the aged population alone
        self.F_ss = self.g_u * self.mu_age_ss + self.damping * u

    # -- the population ------------------------------------------------------------------
    def _radius_sq(self, tau: Any) -> Any:
        if self.holomorphic:
            return 1.0 + self.model.eps * np.log(1.0 + tau)
        return self.model.law.radius(np.real(tau)) ** 2

    def _dradius_sq(self, tau: Any) -> Any:
        if self.holomorphic:
            return self.model.eps / (1.0 + tau)
        h = 1e-6 * (1.0 + np.real(tau))
        return (self._radius_sq(tau + h) - self._radius_sq(tau - h)) / (2 * h)

    def _interp(self, t: Any) -> Any:
        """Barycentric interpolation matrix from the nodes to the ages ``t`` (Berrut &
        Trefethen, SIAM Rev. 46, 501 (2004), eq. 4.2; weights of the Lobatto points)."""
        d = np.asarray(t)[..., None] - self.tau
        c = self.bary / d
        return c / c.sum(axis=-1, keepdims=True)

    def death_age(self, vals: Any, dvals: Any) -> Any:
        """``tau_end``: ``sigma(tau) - 1 - y_c r(tau) = 0`` on the interpolant (Newton from
        the steady death age; ``vals``, ``dvals``: sigma and its derivative at the nodes)."""
        t = self.tau_d + 0j if np.iscomplexobj(vals) else self.tau_d
        for _ in range(30):
            P = self._interp(t)
            R = self._radius_sq(t)
            h = P @ vals - 1.0 - self.yc * np.sqrt(R)
            dh = P @ dvals - self.yc * self._dradius_sq(t) / (2.0 * np.sqrt(R))
            step = h / dh
            t = t - step
            if abs(step) < 1e-14 * self.tau_d:
                break
        return t

    def mu_age(self, sigma: Any) -> Any:
        """The population's friction (``F_el``) of the age profile at the nodes ``1..n``."""
        vals = np.concatenate([[0.0], sigma])
        dvals = self.Dt @ vals
        t_end = self.death_age(vals, dvals)
        phi = 1.0 - (1.0 - self.s) ** 2
        tq = t_end * phi
        wq = t_end * 2.0 * (1.0 - self.s) * self.ws
        P = self._interp(tq)
        sig = P @ vals
        dsig = P @ dvals
        R = self._radius_sq(tq)
        wv = (sig - 1.0) / np.sqrt(R)
        return np.sum(wq * dsig * R * _fplus(wv, self.model.alpha)) / self.trap.H0

    # -- the slider ----------------------------------------------------------------------
    @property
    def size(self) -> int:
        return self.n + 1 + (self.mass > 0)

    def strength(self, V: Any) -> Any:
        """``g(V) = A asinh(V e^{1/A}/(2 v_ref))`` without overflow (holomorphic, Re V > 0)."""
        A, vr = self.model.direct, self.model.v_ref
        if self.direct_form == "linear":
            return self.g_u + self.g_slope * (V - self.u)
        return A * (np.log(V / (2 * vr)) + 1.0 / A
                    + np.log1p(np.sqrt(1.0 + (2 * vr / V) ** 2 * math.exp(-2.0 / A))))

    def velocity(self, g: Any) -> Any:
        """The inverse of :meth:`strength`: ``V = v_ref [e^{(g-1)/A} - e^{-(g+1)/A}]``."""
        A, vr = self.model.direct, self.model.v_ref
        if self.direct_form == "linear":
            return self.u + (g - self.g_u) / self.g_slope
        return vr * (np.exp((g - 1.0) / A) - np.exp(-(g + 1.0) / A))

    def steady(self) -> Array:
        """Steady sliding: ``xi = 0``, ``ln(V/u) = 0``, ``sigma = u tau``."""
        return np.concatenate([[0.0], [0.0] * (self.mass > 0), self.sigma_ss])

    def __call__(self, X: Array, K: float) -> Array:
        """``X'`` (per ``t0``) at the state ``X`` and stiffness ``K`` (``F_el/a0``)."""
        F = self.F_ss + K * X[0]
        sigma = X[-self.n:]
        mu = self.mu_age(sigma)
        if self.mass > 0:
            V = self.u * np.exp(X[1])
            ldot = (F - self.strength(V) * mu - self.damping * V) / (self.mass * V)
            head = [self.u - V, ldot]
        else:
            V = self.velocity(F / mu)
            head = [self.u - V]
        vals = np.concatenate([[0.0], sigma])
        sdot = V - (self.Dt @ vals)[1:]  # sigma_t + sigma_tau = V
        return np.concatenate([np.array(head), sdot])

    def jacobian(self, K: float) -> Array:
        """``Df`` at steady sliding, by the complex step (log law) or central differences;
        the field depends on ``xi`` only through ``K xi``, so ``K`` scales the first column
        (one Jacobian at ``K = 1``, cached)."""
        if "J1" not in self._cache:
            x0 = self.steady()
            n = x0.size
            J1 = np.empty((n, n))
            for j in range(n):
                if self.holomorphic:
                    h = 1e-20
                    xp = x0.astype(complex)
                    xp[j] += 1j * h
                    J1[:, j] = np.imag(self(xp, 1.0)) / h
                else:
                    h = 1e-6 * max(1.0, abs(x0[j]))
                    xp, xm = x0.copy(), x0.copy()
                    xp[j] += h
                    xm[j] -= h
                    J1[:, j] = (self(xp, 1.0) - self(xm, 1.0)) / (2 * h)
            self._cache["J1"] = J1
        J = self._cache["J1"].copy()
        J[:, 0] *= K
        return J

    def summary(self) -> dict[str, float]:
        return {"u": self.u, "n": self.n, "tau_d": self.tau_d, "L": self.L,
                "mu_age_ss": self.mu_age_ss, "mu_d": self.mu_d}


@dataclass(frozen=True)
class TrapHopf:
    """``K_c`` (``F_el/a0``), ``omega_c`` (``1/t0``) and the normalised ``l1_x`` (``1/a0^2``) of one
    reduction (module docstring)."""

    u: float
    n: int
    K_c: float
    omega: float
    l1_x: float
    relative_l1: float
    dbeta_dK: float
    K_c_nyquist: float
    omega_nyquist: float
    mu_error: float
    point: HopfPoint | None

    @property
    def nature(self) -> str:
        """``supercritical`` (``l1 < 0``), ``subcritical``, ``degenerate`` (``|l1|`` below
        1e-8 of its largest term) or ``none`` (no oscillatory instability at any ``K``)."""
        if not math.isfinite(self.K_c):
            return "none"
        if abs(self.relative_l1) < 1e-8:
            return "degenerate"
        return "supercritical" if self.l1_x < 0 else "subcritical"

    def slip_amplitude(self, K: float) -> float:
        """Predicted half peak-to-peak slip (``a0``) of the cycle at ``K`` (NaN on the side
        without one): ``2 sqrt(-beta/(omega l1_x))``."""
        beta = self.dbeta_dK * (K - self.K_c)
        r = -beta / (self.omega * self.l1_x)
        return 2.0 * math.sqrt(r) if r > 0 else math.nan

    def force_amplitude(self, K: float) -> float:
        """Predicted half peak-to-peak spring force (``F_el``): ``K`` x the slip's."""
        return K * self.slip_amplitude(K)


def _pick(lam: Array, omega_hint: float) -> complex:
    """The eigenvalue continuing the physical critical pair: ``Im > 0``, nearest to
    ``i omega_hint`` (the Nyquist frequency)."""
    c = lam[lam.imag > 0]
    return complex(c[np.argmin(np.abs(c - 1j * omega_hint))])


def trap_hopf(u: float, model: TrapModel, mass: float = 0.0, damping: float = 0.0, *,
              n: int = 32, stretch: float = 1.25, panels: int = 24,
              method: str | None = None, scale: float | None = None,
              direct_form: str = "asinh") -> TrapHopf:
    """The Hopf point of the reduction of :class:`TrapField` and its ``l1_x``.

    ``K_c`` is the stiffness where the pair continuing the Nyquist crossing
    (:func:`~dryfriction.theory.linear_stability.critical_stiffness`) meets the imaginary
    axis (bisection, relative ``1e-13``); ``l1`` by :func:`.theory.hopf.first_lyapunov`
    (Cauchy circle for the log law, real differences otherwise; ``scale`` in the state's
    units, ``a0`` for the stretch and the slips, 1 for ``ln V``; default 0.05 for the circle,
    1 for differences, whose third differences are rounding-limited below ~0.5).

    Parameters
    ----------
    u : float
        Pulling velocity, ``a0/t0``.
    model : TrapModel
        With the direct effect and very strong pinning (:class:`TrapField`).
    mass, damping : float
        ``M`` (``F_el t0^2/a0``) and ``eta`` (``F_el t0/a0``).
    n, stretch, panels, direct_form
        As :class:`TrapField`.
    method : {"complex", "fd"}, optional
        How the second and third derivatives are taken.
    scale : float, optional
        As above.

    Returns
    -------
    TrapHopf
        ``nature == "none"`` (NaN values) when no stiffness destabilises steady sliding.
    """
    fld = TrapField(u, model, mass, damping, n, stretch, panels, direct_form)
    lin = critical_stiffness(u, model, mass=mass, damping=damping)
    K0, om0 = lin.critical_stiffness, lin.omega
    if not (K0 > 0 and math.isfinite(om0)):  # stable at every stiffness
        nan = math.nan
        return TrapHopf(u=u, n=n, K_c=nan, omega=nan, l1_x=nan, relative_l1=nan,
                        dbeta_dK=nan, K_c_nyquist=K0, omega_nyquist=om0, mu_error=nan,
                        point=None)

    def re(K: float) -> float:
        return _pick(np.linalg.eigvals(fld.jacobian(K)), om0).real

    lo, hi = 0.8 * K0, 1.25 * K0
    for _ in range(20):
        if re(lo) > 0 > re(hi):
            break
        lo, hi = 0.8 * lo, 1.25 * hi
    Kc = brentq(re, lo, hi, xtol=1e-14 * K0, rtol=1e-13, maxiter=200)
    lam = _pick(np.linalg.eigvals(fld.jacobian(Kc)), om0)
    h = 1e-6 * Kc
    dbeta = (re(Kc + h) - re(Kc - h)) / (2 * h)
    meth = method or ("complex" if fld.holomorphic else "fd")
    if scale is None:  # the fd stencils need a wider step (third derivatives, rounding)
        scale = 0.05 if meth == "complex" else 1.0
    J = fld.jacobian(Kc)
    pt = first_lyapunov(lambda X: fld(X, Kc), fld.steady(), jac=J, method=meth,  # type: ignore[arg-type]
                        scale=scale, residual_max=1e-6)
    if abs(pt.omega - lam.imag) > 1e-6 * lam.imag:
        raise RuntimeError(f"first_lyapunov took the pair at omega = {pt.omega:g}, not the "
                           f"critical one at {lam.imag:g}")
    l1x = pt.l1 / abs(pt.q[0]) ** 2
    return TrapHopf(u=u, n=n, K_c=Kc, omega=lam.imag, l1_x=l1x, relative_l1=pt.relative_l1,
                    dbeta_dK=dbeta, K_c_nyquist=K0, omega_nyquist=om0,
                    mu_error=fld.mu_age_ss / fld.mu_d - 1.0, point=pt)


def simulate(fld: TrapField, K: float, x_start: Array, t_end: float, *,
             samples: int = 4000, rtol: float = 1e-7) -> tuple[Array, Array]:
    """Integrate the reduced field (Radau, the Jacobian of steady sliding) from ``x_start``
    to ``t_end`` (``t0``): times and states."""
    from scipy.integrate import solve_ivp

    J = fld.jacobian(K)
    sol = solve_ivp(lambda t, x: np.real(fld(x, K)), (0.0, t_end), x_start, method="Radau",
                    t_eval=np.linspace(0.0, t_end, samples), rtol=rtol, atol=1e-11,
                    jac=lambda t, x: J)
    if not sol.success:
        raise RuntimeError(sol.message)
    return sol.t, sol.y

