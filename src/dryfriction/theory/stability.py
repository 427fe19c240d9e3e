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
``Z'(0) = d mu_d / du`` (the slope of :func:`dryfriction.theory.steady.steady_friction`).

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

**What a simulation sees at the supremum.** At high frequency ``K + Z = 0`` reads
``(K + Z(inf)) xi(t) = -|D| xi(t - tau_d)`` (``|D|`` = ``delay_amplitude``): a sharp forward
jump of the slider returns one death age later, when the pairs born during it reach the
spinodal together, as an echo ``c = -|D| / (K + Z(inf))`` times the jump, so sharp features grow
for ``-Z(inf) < K < K_c`` and decay above ``K_c``. Direct simulation of the quasi-static spring
(u = 0.01, eps = 0.04, 1000 pairs/a0; tests/theory/test_stability.py) shows the first jump
``kick / (K + Z(inf))`` to ~10 % and the echoes sustained at 0.978 ``K_c`` and decaying at
1.04 ``K_c``: it brackets ``K_c = 0.07515`` but cannot resolve it closer (a finite-width echo is
damped by the memory term as well, and the best finite crossing is only 0.15 % lower).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import gamma

from ..validation import Array, check_scalar
from .creep import CreepLaw
from .direct import junction_strength
from .model import TrapModel
from .steady import death_clock
from .trap import Trap, force_minus, force_plus

__all__ = [
    "SteadyResponse",
    "steady_response",
    "shift_stiffness",
    "characteristic",
    "StabilityResult",
    "nyquist_stiffness",
    "rightmost_root",
    "delay_chain_limit",
    "rsf_from_response",
    "nyquist_crossings",
]

CArray = NDArray[np.complex128]

# composite Gauss-Legendre: panels of 16 nodes, at least 6 of them; a panel spans a phase
# change of at most _PHASE radians of e^{-lambda T}, so Z stays exact as |lambda| grows
_GX, _GW = np.polynomial.legendre.leggauss(16)
_GX, _GW = 0.5 * (_GX + 1.0), 0.5 * _GW
_MIN_PANELS = 6
_PHASE = 10.0
# above |lambda| min(tau_d, 1) = _ASYMPTOTE the memory integral is its endpoint expansion
# (module doc); the first neglected terms, O(|lambda|^{-4}) at the young end and
# O((|lambda| tau_d)^{-5/2}) at the spinodal, are below ~1e-7 there
_ASYMPTOTE = 200.0
_MAX_LEVEL = 12
# largest node x frequency block evaluated at once (memory of the e^{-lambda T} matrix)
_BLOCK = 2_000_000


def _dforce_plus(w: Array, alpha: float) -> Array:
    """``f_+'(w) = 6 alpha (1 - alpha / sqrt((1-alpha)^2 - 4 alpha w))`` (from docs/model.md §1)."""
    disc = np.maximum((1.0 - alpha) ** 2 - 4.0 * alpha * w, 1e-300)
    return 6.0 * alpha * (1.0 - alpha / np.sqrt(disc))


def _dforce_minus(w: Array, alpha: float) -> Array:
    """``f_-'(w) = f_+'(-w)`` (symmetry ``f_-(w) = -f_+(-w)``)."""
    return _dforce_plus(-w, alpha)


@dataclass(frozen=True)
class _Branch:
    """One branch of the steady population: clock range ``c = c0 + (c1 - c0) m(s)``."""

    c0: float
    c1: float
    plus: bool
    slope: float  # max |dT/ds| over the branch: sets the panels needed at a given |lambda|


@dataclass(frozen=True)
class SteadyResponse:
    """Quadrature nodes of the steady population at one ``(u, eps, alpha)``, ready for ``Z``.

    Attributes are arrays over the nodes (ages ``T`` in ``t0``): the static part ``A`` of
    ``H0 Z`` (``int u g_y dtau``), the weights ``b`` of ``e^{-lambda T}`` in ``H0 Z``, and the
    spinodal-edge terms. ``T``, ``b`` are the coarsest nodes; :meth:`Z` refines them with
    ``|lambda|`` and uses the endpoint expansion of the memory integral at large ``|lambda|``
    (``tail``: its coefficients, module doc).
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
    law: CreepLaw | None = field(default=None, repr=False, compare=False)
    branches: tuple[_Branch, ...] = field(default=(), repr=False, compare=False)
    tail: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)
    node_cache: dict[int, tuple[Array, Array]] = field(default_factory=dict, repr=False,
                                                   compare=False)

    def derivative_at_zero(self, n: int) -> float:
        """``d^n Z / d lambda^n`` at ``lambda = 0``: moments of the age distribution (ours)."""
        edge = -self.edge * self.edge_delay * (-self.tau_d) ** n
        return float((np.sum(self.b * (-self.T) ** n) + edge) / self.H0)

    @property
    def Z_inf(self) -> float:
        """``lim Z`` without the delay term: ``(A + edge) / H0`` (:func:`shift_stiffness`)."""
        return (self.A + self.edge) / self.H0

    @property
    def delay_amplitude(self) -> float:
        """``|edge * edge_delay| / H0``: radius of the Nyquist circles at high frequency."""
        return abs(self.edge * self.edge_delay) / self.H0

    def nodes(self, level: int) -> tuple[Array, Array]:
        """Ages and weights with ``_MIN_PANELS * 2**level`` panels per branch (cached)."""
        if level not in self.node_cache:
            assert self.law is not None
            Ts, bs = [], []
            for br in self.branches:
                T, b, _ = _branch_nodes(self.law, self.u, self.alpha, br,
                                        _MIN_PANELS * 2**level)
                Ts.append(T)
                bs.append(b)
            self.node_cache[level] = (np.concatenate(Ts), np.concatenate(bs))
        return self.node_cache[level]

    def memory(self, lam: ArrayLike) -> CArray:
        """``int g_theta e^{-lambda tau} dtau`` (units ``F_el``, times ``H0``) at each ``lam``."""
        lam = np.asarray(lam, dtype=complex)
        flat = lam.ravel()
        out = np.zeros(flat.size, complex)
        if not self.branches:  # a response built by hand: its fixed nodes only
            with np.errstate(over="ignore", invalid="ignore"):
                return (np.exp(-lam[..., None] * self.T) @ self.b).astype(complex)
        size = np.abs(flat)
        # the expansion needs |lambda| large on both scales of the integrand: tau_d at the
        # spinodal, and the clock's unit scale (t0) at the young end
        far = size * min(self.tau_d, 1.0) > _ASYMPTOTE
        if np.any(far):
            out[far] = self._memory_far(flat[far])
        slope = max(br.slope for br in self.branches)
        need = np.maximum(size * slope / (_PHASE * _MIN_PANELS), 1.0)
        # past _MAX_LEVEL (6 * 4096 panels) the expansion is used even if not yet that exact:
        # a very old population (tiny u) would otherwise need millions of nodes
        big = ~far & ~(need <= 2.0**_MAX_LEVEL)
        if np.any(big):
            out[big] = self._memory_far(flat[big])
            far = far | big
        level = np.ceil(np.log2(np.where(far, 1.0, need))).astype(int)
        for lv in np.unique(level[~far]):
            idx = np.flatnonzero((level == lv) & ~far)
            T, b = self.nodes(int(lv))
            step = max(1, _BLOCK // T.size)
            for k in range(0, idx.size, step):
                sel = idx[k:k + step]
                # far in the left half-plane e^{-lambda T} overflows: the value is then
                # inf/nan, which the root search discards
                with np.errstate(over="ignore", invalid="ignore"):
                    out[sel] = np.exp(-flat[sel, None] * T) @ b
        return out.reshape(lam.shape)

    def _memory_far(self, lam: CArray) -> CArray:
        """Endpoint expansion of the memory integral (module doc), ``|lambda| tau_d >> 1``."""
        t = self.tail
        with np.errstate(over="ignore", invalid="ignore"):
            out = t["h0"][0] / lam + t["h0"][1] / lam**2 + t["h0"][2] / lam**3
            log_m = np.log(-lam)
            sing = sum(g * gamma(0.5 * (k + 1)) * np.exp(-0.5 * (k + 1) * log_m)
                       for k, g in enumerate(t["spinodal"]))
            out = out + np.exp(-lam * self.tau_d) * sing
            for tau, hs, sign in t["ends"]:
                out = out + sign * np.exp(-lam * tau) * (
                    hs[0] / lam + hs[1] / lam**2 + hs[2] / lam**3)
        return out

    def Z(self, lam: ArrayLike) -> CArray:
        """``Z(lambda)``: friction change (units ``F_el``) per unit slip perturbation (``a0``)."""
        lam = np.asarray(lam, dtype=complex)
        with np.errstate(over="ignore", invalid="ignore"):
            edge = self.edge * (1.0 - self.edge_delay * np.exp(-lam * self.tau_d))
        return (self.A + self.memory(lam) + edge) / self.H0


def _g_theta(law: CreepLaw, u: float, alpha: float, c: Array, plus: bool) -> Array:
    """``g_theta`` per unit clock ``c``: ``(R'(c)/2) [2 f - w f']`` at the steady age."""
    R = law.radius_sq(c)
    w = np.clip((-1.0 + u * law.age(c)) / np.sqrt(R), -1.0, Trap(alpha).y_c if plus else 1.0)
    f, df = (force_plus, _dforce_plus) if plus else (force_minus, _dforce_minus)
    return 0.5 * law.dradius_sq(c) * (2.0 * f(w, alpha) - w * df(w, alpha))


def _branch_nodes(
    law: CreepLaw, u: float, alpha: float, br: _Branch, panels: int
) -> tuple[Array, Array, float]:
    """Ages, ``e^{-lambda T}`` weights and static part ``int u g_y dtau`` of one branch."""
    s = ((np.arange(panels)[:, None] + _GX) / panels).ravel()
    ws = np.tile(_GW, panels) / panels
    dc = br.c1 - br.c0
    if br.plus:  # c = c_d (1 - s^2) removes the 1/sqrt of f_+' at the spinodal
        c, wts = br.c1 - dc * s**2, 2.0 * dc * s * ws
    else:
        c, wts = br.c0 + dc * s, dc * ws
    R = law.radius_sq(c)
    r = np.sqrt(R)
    T = law.age(c)
    w = np.clip((-1.0 + u * T) / r, -1.0, Trap(alpha).y_c if br.plus else 1.0)
    df = _dforce_plus if br.plus else _dforce_minus
    # u g_y dtau = u r f'(w) T'(c) dc ;  g_theta dtau = (R'(c)/2) [2 f - w f'] dc
    A = float(np.sum(u * r * df(w, alpha) * law.dage(c) * wts))
    return T, _g_theta(law, u, alpha, c, br.plus) * wts, A


def _per_age(law: CreepLaw, u: float, alpha: float, T: Array, plus: bool) -> Array:
    """``g_theta`` per unit age ``T`` (the integrand of the memory term)."""
    c = law.clock(T)
    return _g_theta(law, u, alpha, c, plus) / law.dage(c)


def _end_derivatives(h: Callable[[Array], Array], T0: float, step: float) -> list[float]:
    """``h``, ``h'``, ``h''`` at ``T0`` from one-sided differences (``step`` signed)."""
    v = h(T0 + step * np.arange(4.0))
    d1 = (-11 * v[0] + 18 * v[1] - 9 * v[2] + 2 * v[3]) / (6 * step)
    d2 = (2 * v[0] - 5 * v[1] + 4 * v[2] - v[3]) / step**2
    return [float(v[0]), float(d1), float(d2)]


def _tail(law: CreepLaw, u: float, alpha: float, tau_d: float, tau_e: float | None
          ) -> dict[str, Any]:
    """Coefficients of the memory integral's expansion at large ``|lambda|`` (module doc)."""
    plus = lambda T: _per_age(law, u, alpha, np.asarray(T, float), True)  # noqa: E731
    # near the spinodal h(tau_d - q^2) q is smooth in q: a cubic through q = 1..4 dq gives
    # h = sum_k g_k v^{(k-1)/2}, v = tau_d - T (Watson's lemma, k = 0..3)
    dq = 2e-3 * np.sqrt(tau_d)
    q = dq * np.arange(1.0, 5.0)
    S = plus(tau_d - q**2) * q
    g = np.linalg.solve(np.vander(q, 4, increasing=True), S)
    ends = []
    if tau_e is not None:
        minus = lambda T: _per_age(law, u, alpha, np.asarray(T, float), False)  # noqa: E731
        step = 1e-4 * (tau_e - tau_d)
        ends = [(tau_d, _end_derivatives(minus, tau_d, step), 1.0),
                (tau_e, _end_derivatives(minus, tau_e, -step), -1.0)]
    return {"h0": _end_derivatives(plus, 0.0, 1e-3 * min(1.0, tau_d)),
            "spinodal": [float(x) for x in g], "ends": ends}


def _pieces(law: CreepLaw, u: float, alpha: float) -> SteadyResponse:
    trap = Trap(alpha)
    yc = trap.y_c
    uu = np.array([u])
    c_d = float(death_clock(law, uu, yc)[0])
    fine = np.linspace(0.0, 1.0, 2001)
    branches = [_Branch(0.0, c_d, True,
                        float(np.max(law.dage(c_d * (1 - fine**2)) * 2 * c_d * fine)))]
    tau_e = None
    if yc < 1.0:  # strong pinning: (-) branch up to w = 1
        c_e = float(death_clock(law, uu, 1.0)[0])
        branches.append(_Branch(c_d, c_e, False, float(law.dage(c_e)) * (c_e - c_d)))
        tau_e = float(law.age(c_e))
    A = 0.0
    Ts, bs = [], []
    for br in branches:
        T, b, a = _branch_nodes(law, u, alpha, br, _MIN_PANELS)
        A += a
        Ts.append(T)
        bs.append(b)
    R_d = float(law.radius_sq(c_d))
    r_d = np.sqrt(R_d)
    tau_d = float(law.age(c_d))
    rp_d = float(law.dradius_sq(c_d)) / (2.0 * r_d * float(law.dage(c_d)))
    # f_+(y_c) from its closed form: evaluating f_+ at a rounded y_c costs sqrt(ulp)
    jump = trap.f_c - (float(force_minus(yc, alpha)) if yc < 1.0 else 0.0)
    dg = R_d * jump
    edge = -u * dg / (u - yc * rp_d)
    T0, b0 = np.concatenate(Ts), np.concatenate(bs)
    resp = SteadyResponse(u=u, eps=law.eps, alpha=alpha, H0=trap.H0, A=A, T=T0, b=b0,
                          tau_d=tau_d, edge=edge, edge_delay=yc * rp_d / u, law=law,
                          branches=tuple(branches), tail=_tail(law, u, alpha, tau_d, tau_e))
    resp.node_cache[0] = (T0, b0)
    return resp


def steady_response(u: float, model: TrapModel) -> SteadyResponse:
    """Linear response ``Z(lambda)`` of the trap population in steady sliding at reduced
    velocity ``u`` (module doc): the ageing part only; the friction's response, with the
    direct effect of ``model``, is :func:`dryfriction.theory.linear_stability.linear_response`.

    Parameters
    ----------
    u : float
        Reduced velocity ``V t0 / a0``, ``> 0``.
    model : TrapModel
        ``eps``, ``alpha`` and the creep law (checked when the model was built).
    """
    u = check_scalar("u", u, 0.0, lo_open=True)
    return _pieces(model.law, u, model.alpha)


def shift_stiffness(
    u: float, model: TrapModel
) -> tuple[float, float]:
    """Stiffness (units ``F_el/a0``) met by a sudden small shift of the steady population.

    Returns ``(forward, backward)``: ``forward = Z(inf)``, where the traps killed at the edge
    offset the stiffening of the others (zero without ageing, negative with it);
    ``backward = int u g_y dtau / H0``, the full elastic stiffness (no trap dies). Both times
    the junction strength ``g(u)`` of ``model``'s direct effect (a shift is no slip rate).
    """
    resp = steady_response(u, model)
    g = float(junction_strength(u, model.direct, model.v_ref)) if model.direct else 1.0
    return g * (resp.A + resp.edge) / resp.H0, g * resp.A / resp.H0


def characteristic(
    lam: ArrayLike, resp: SteadyResponse, stiffness: float, mass: float = 0.0,
    damping: float = 0.0,
) -> CArray:
    """``chi(lambda) = M lambda^2 + eta lambda + K + Z(lambda)`` of the spring-slider."""
    lam = np.asarray(lam, dtype=complex)
    return mass * lam**2 + damping * lam + stiffness + resp.Z(lam)


@dataclass(frozen=True)
class StabilityResult:
    """Critical stiffness ``K_c`` (``F_el/a0``) and onset angular frequency (``rad/t0``)."""

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


def _grid_crossings(
    Z: Callable[[ArrayLike], CArray], mass: float, damping: float, om: Array,
    candidates: int = 24,
) -> tuple[float, float]:
    """Largest ``K`` among the zeros of ``eta omega + Im Z(i omega)`` bracketed on ``om``.

    Every bracket gets a linear estimate of its ``K``; only the ``candidates`` largest are
    refined (brentq), since at high frequency there are thousands of crossings.
    """
    z = Z(1j * om)
    vals = damping * om + z.imag
    idx = np.flatnonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)
    if idx.size == 0:
        return -np.inf, np.nan
    frac = vals[idx] / (vals[idx] - vals[idx + 1])
    k_lin = mass * om[idx] ** 2 - (z.real[idx] + frac * (z.real[idx + 1] - z.real[idx]))
    keep = idx[np.argsort(k_lin)[::-1][:candidates]]

    def im(o: float) -> float:
        return float(damping * o + Z(np.array([1j * o]))[0].imag)

    from scipy.optimize import brentq  # lazily: SciPy's optimizers are slow to import

    best_K, best_om = -np.inf, np.nan
    for i in keep:
        o = brentq(im, om[i], om[i + 1], xtol=1e-14 * om[i], maxiter=200)
        K = mass * o**2 - float(Z(np.array([1j * o]))[0].real)
        if K > best_K:
            best_K, best_om = K, o
    return best_K, best_om


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
    return _grid_crossings(Z, mass, damping, om)


# the scan: a log grid up to _LOG_TOP / tau_d, then a linear one resolving the delay term's
# period 2 pi / tau (8 points a period) up to _FREE_TOP / tau_d when M = eta = 0, where the
# crossings have settled on circles about -Z(inf) (module doc)
_LOG_TOP = 20.0
_FREE_TOP = 2000.0
_MAX_POINTS = 400_000


def _high_scan(
    resp: SteadyResponse, mass: float, damping: float, lo: float, hi: float,
) -> tuple[float, float]:
    """Crossings on a linear grid over ``[lo, hi]``, in doubling chunks; with damping and no
    mass, stops once no later crossing can beat the best one found (module doc)."""
    tau = resp.tau_d if len(resp.branches) < 2 else float(np.max(resp.T))
    d_om = np.pi / (4.0 * tau)
    best_K, best_om = -np.inf, np.nan
    used = 0
    a = lo
    while a < hi and used < _MAX_POINTS:
        b = min(hi, max(2.0 * a, a + 64 * d_om))
        om = np.arange(a, b + d_om, d_om)
        used += om.size
        K, o = _grid_crossings(resp.Z, mass, damping, om)
        if K > best_K:
            best_K, best_om = K, o
        if damping > 0 and mass == 0.0:
            # beyond b: |Im H0 Z| <= |E| + |memory|, and the damping must be balanced by it
            mem = float(np.max(np.abs(resp.memory(1j * om[-8:])))) * 1.5 / resp.H0
            amp = resp.delay_amplitude + mem
            lean = max(0.0, damping * b - mem)
            bound = -resp.Z_inf + np.sqrt(max(0.0, amp**2 - lean**2)) + mem
            if bound < best_K:
                break
        a = b
    return best_K, best_om


def nyquist_stiffness(
    resp: SteadyResponse,
    mass: float = 0.0,
    damping: float = 0.0,
    omega_max: float | None = None,
    n_omega: int = 4000,
) -> StabilityResult:
    """Critical stiffness ``K_c(u; eps, alpha, M, eta)`` of one population response ``resp``
    and the frequency at onset (the athermal analysis; the model's entry point, which adds the
    direct effect, is :func:`dryfriction.theory.linear_stability.critical_stiffness`).

    Finds the zeros of ``eta omega + Im Z(i omega)`` by bracketing and returns the largest
    ``K = M omega^2 - Re Z(i omega)`` among them. The grid is logarithmic (``n_omega``
    points) up to ``20/tau_d`` (``tau_d`` the age at which traps die), then linear, resolving
    the delay term's period, up to: ``omega_max`` if given; else, with damping, the frequency
    beyond which ``eta omega`` exceeds every ``|Im Z|`` (or no later crossing can beat the
    best: module doc); with ``M = eta = 0``, ``2000/tau_d``, after which the crossings
    circle about ``-Z(inf)`` with radius ``delay_amplitude``. Then the supremum
    ``K_inf = -Z(inf) + delay_amplitude`` is compared with the best crossing found: if it
    is larger, it is returned with ``omega = inf`` and ``supremum_at_infinity = True`` (it
    is approached only as ``omega -> inf``). With mass and no damping the crossings never
    stop and their ``K`` grows as ``M omega^2``: the value up to ``omega_max`` (default
    ``200/tau_d``) is returned.
    """
    mass = check_scalar("mass", mass, 0.0)
    damping = check_scalar("damping", damping, 0.0)
    top_log = _LOG_TOP / resp.tau_d
    if omega_max is not None:
        top = check_scalar("omega_max", omega_max, 0.0, lo_open=True)
    elif damping > 0:
        reach = resp.delay_amplitude + float(np.sum(np.abs(resp.b))) / resp.H0
        # reach 0 (eps = 0: Z is real, no Im Z for eta omega to meet): no crossing at any
        # omega > 0, and the log grid finds none; the scan up to 0 was refused as
        # "omega_max = 0", a name no user gave (outside24: --eps 0 --mass 1 --damping 0.1)
        top = 1.05 * reach / damping if reach > 0 else top_log
    elif mass > 0:
        top = 200.0 / resp.tau_d
    else:
        top = _FREE_TOP / resp.tau_d
    best_K, best_om = nyquist_crossings(resp.Z, mass, damping, min(top, top_log), n_omega)
    if top > top_log:
        K, o = _high_scan(resp, mass, damping, top_log, top)
        if K > best_K:
            best_K, best_om = K, o
    fwd, bwd = resp.Z_inf, resp.A / resp.H0
    at_inf = False
    k_inf = -fwd + resp.delay_amplitude
    if mass == 0.0 and damping == 0.0 and k_inf > best_K:
        best_K, best_om, at_inf = k_inf, np.inf, True
    h = 1e-6 * max(1.0, 1.0 / resp.tau_d)
    slope = float((resp.Z(h) - resp.Z(-h)).real / (2 * h))
    return StabilityResult(u=resp.u, eps=resp.eps, alpha=resp.alpha, mass=mass, damping=damping,
                           critical_stiffness=max(best_K, 0.0) if np.isfinite(best_K) else 0.0,
                           omega=best_om, forward_stiffness=fwd, backward_stiffness=bwd,
                           velocity_slope=slope, supremum_at_infinity=at_inf)


def delay_chain_limit(resp: SteadyResponse, stiffness: float, mass: float = 0.0,
                      damping: float = 0.0) -> float:
    """Where the real parts of the delay term's chain of roots accumulate (ours).

    With ``M = eta = 0``, at high frequency ``chi -> K + Z(inf) - E e^{-lambda tau_d}``
    (``E = edge * edge_delay / H0``), whose roots ``lambda_k = -(Log c + 2 pi i k) / tau_d``,
    ``c = (K + Z(inf)) / E``, have ``Re lambda_k = -ln|c| / tau_d`` for every ``k``: the roots
    of ``chi`` approach them as ``k -> inf``, so the spectrum's supremum is at least this
    (not attained when the chain approaches it from below). ``+inf`` when ``K = -Z(inf)``
    (every frequency grows: ill posed); ``-inf`` with mass or damping, whose ``M lambda^2``
    or ``eta lambda`` outgrows the delay term, without a delay term, or for a response that
    is not a :class:`SteadyResponse` (the direct effect's ``(a_d/u) lambda`` damps it).
    """
    amp = _delay_weight(resp)
    if mass > 0 or damping > 0 or amp == 0:
        return -np.inf
    c = abs((stiffness + resp.Z_inf) / amp)
    return np.inf if c == 0 else float(-np.log(c) / resp.tau_d)


def _delay_weight(resp: Any) -> float:
    """``E = edge * edge_delay / H0``, the weight of ``e^{-lambda tau_d}`` in ``Z`` (0 for a
    response without that form)."""
    if not isinstance(resp, SteadyResponse):
        return 0.0
    return float(resp.edge * resp.edge_delay / resp.H0)


def _seeds(resp: SteadyResponse, stiffness: float, mass: float, damping: float,
           n_seeds: int) -> list[complex]:
    """Newton starts: a polar grid in the right half-plane (``|lambda| tau_d`` 0.05-50) and,
    with ``M = eta = 0``, the delay chain's asymptotic roots (:func:`delay_chain_limit`) up to
    ``k = 10^4``: the rightmost roots there lie far beyond the polar grid (``|lambda| tau_d``
    in the hundreds to thousands) and Newton from it does not reach them; from the chain's
    own asymptotics it converges in a few steps."""
    scale = 1.0 / resp.tau_d
    seeds = [s * scale * np.exp(1j * p) for s in np.geomspace(0.05, 50.0, n_seeds // 4)
             for p in (-1.2, -0.4, 0.4, 1.2)]
    amp = _delay_weight(resp)
    if mass == 0 and damping == 0 and amp != 0 and stiffness + resp.Z_inf != 0:
        log_c = np.log(complex((stiffness + resp.Z_inf) / amp))
        seeds += [complex(-(log_c + 2j * np.pi * k) * scale)
                  for k in np.unique(np.r_[0:4, np.geomspace(4, 1e4, 18).round()])]
    return seeds


def rightmost_root(
    resp: SteadyResponse, stiffness: float, mass: float = 0.0, damping: float = 0.0,
    n_seeds: int = 24,
) -> complex:
    """Root of ``chi`` with the largest real part found by Newton from seeds (growth rate).

    Seeds (:func:`_seeds`): a polar grid ``lambda = s (cos phi + i sin phi) / tau_d`` and the
    delay chain; each Newton run uses the derivative of ``chi`` by complex-step
    differences. A positive real part means an unstable mode growing
    as ``e^{Re lambda t}``. ``-inf`` when no seed converged. With ``M = eta = 0`` the
    spectrum's supremum may be the chain's limit instead (:func:`delay_chain_limit`).
    """
    stiffness = check_scalar("stiffness", stiffness, 0.0, lo_open=True)
    scale = 1.0 / resp.tau_d
    best = complex(-np.inf, 0.0)
    # a Newton run may wander off to |lambda| ~ 1e200, where chi overflows: that seed is
    # dropped (no warning, no OverflowError), the others still find the root
    with np.errstate(all="ignore"):
        for z in _seeds(resp, stiffness, mass, damping, n_seeds):
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


def rsf_from_response(resp: Any) -> dict[str, float]:
    """Rate-and-state parameters that reproduce a linear response ``resp`` at small ``lambda``
    (ours; ``resp`` a :class:`SteadyResponse` or any object with its ``u`` and
    ``derivative_at_zero``).

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
    u = resp.u
    z1, z2, z3 = (resp.derivative_at_zero(n) for n in (1, 2, 3))
    if z2 == 0.0:
        raise ValueError("eps = 0: the response vanishes, no rate-and-state parameters")
    dc = -u * z3 / (3.0 * z2)
    b = u * u * z2 / (2.0 * dc)
    return {"a": u * z1 + b, "b": b, "dc": dc, "u": u}
