"""Compressive creep of a contact: the radius ratio ``a_r = a/a0`` against its age
(docs/model.md §2).

Times are reduced, ``T = theta / t0``. Two laws, one interface:

* :class:`LogCreep`, the first-order law ``a_r^2 = 1 + eps ln(1 + T)`` (eqs. 17, 19);
* :class:`EyringNabarroCreep`, the exact Eyring-Nabarro law (eqs. 15-16),
  ``(2/a) da/dt = edot0 exp(sigma/S)``, ``sigma = Y (a0/a)^2``, written with ``eps = S/Y`` and
  ``1/t0 = edot0 (Y/S) exp(Y/S)`` (eq. 18). For ``s = a_r^2`` it reads (ours)
  ``ds/dT = eps s exp((1/s - 1)/eps)``.

Both laws are described through a *clock* variable ``c`` in which ``a_r^2`` is smooth, so that
quadratures over the age of traps (eq. 34) need no special care at short ages:

* log law: ``c = ln(1 + T)``, ``T = e^c - 1``, ``a_r^2 = 1 + eps c``;
* Eyring-Nabarro (ours): ``c = Q = (1 - 1/s)/eps``, ``a_r^2 = 1/(1 - eps Q)`` and
  ``T(Q) = int_0^Q e^q / (1 - eps q) dq`` (separation of variables in the ODE above).
  To first order in ``eps``, ``T = e^Q - 1`` and the two laws coincide.

The exact law grows without bound at long times (``s`` grows exponentially once the stress
has relaxed, at the rate ``eps e^{-1/eps}``); it departs from the log law when
``T ~ e^{1/eps}``. :func:`creep_law_difference` measures the departure.

**Range of the Eyring-Nabarro law (ours).** With ``v = 1/eps - q`` the age integral is an
exponential integral, ``T(Q) = (e^{1/eps}/eps) [E1(b/eps) - E1(1/eps)]``, ``b = 1 - eps Q =
1/s``. As ``b -> 0``, ``E1(x) ~ -gamma - ln x``: ``s ~ (1/eps) exp(T eps e^{-1/eps} - gamma)``,
so the area grows without bound, exponentially with time constant ``e^{1/eps}/eps``, and never
saturates: the contact runs away. It happens because eq. 15's creep rate ``edot0 exp(sigma/S)``
stays finite as the contact stress ``sigma = Y/s`` (eq. 16) relaxes to zero; Eyring's form is the
forward-jump half of ``sinh(sigma/S)`` and holds only while ``sigma >> S``. We accept the law up
to ``sigma = S``, i.e. ``a_r^2 = 1/eps``, ``Q_v = (1 - eps)/eps``, reached at

    T_v(eps) = (e^{1/eps}/eps) [E1(1) - E1(1/eps)]         (E1(1) = 0.2194)

(:func:`max_age`; ``T_v = 2.1e9`` at ``eps = 0.05``, ``4.8e4`` at ``eps = 0.1``). Ages beyond it
are refused (:func:`check_age`) rather than computed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..validation import EPS_MAX, Array, check_broadcast, check_choice, check_range, check_scalar

__all__ = [
    "CreepLaw",
    "LogCreep",
    "EyringNabarroCreep",
    "creep_law",
    "CREEP_LAWS",
    "CreepMaterial",
    "creep_law_difference",
    "radius",
    "per_eps",
    "max_age",
    "check_age",
]

CreepName = Literal["log", "eyring-nabarro"]
CREEP_LAWS: tuple[str, ...] = ("log", "eyring-nabarro")


class CreepLaw(Protocol):
    """What the friction calculations need from an ageing law."""

    eps: float
    name: str

    def radius(self, T: ArrayLike) -> Array:
        """``a_r(T) = a/a0`` at reduced age ``T``."""
        ...

    def clock(self, T: ArrayLike) -> Array:
        """Clock variable ``c(T)``."""
        ...

    def age(self, c: ArrayLike) -> Array:
        """Reduced age ``T(c)``."""
        ...

    def dage(self, c: ArrayLike) -> Array:
        """``dT/dc``."""
        ...

    def radius_sq(self, c: ArrayLike) -> Array:
        """``a_r^2`` as a function of the clock."""
        ...

    def dradius_sq(self, c: ArrayLike) -> Array:
        """``d(a_r^2)/dc``."""
        ...

    def clock_at_radius(self, r: ArrayLike) -> Array:
        """Inverse of ``radius_sq``: the clock at which ``a_r = r``."""
        ...


@dataclass(frozen=True)
class LogCreep:
    """Logarithmic ageing ``a_r(T) = sqrt(1 + eps ln(1 + T))`` (eqs. 17 and 19).

    Parameters
    ----------
    eps : float
        Creep parameter ``S/Y`` (dimensionless, ``>= 0``; typically ~0.01).
    """

    eps: float
    name: str = "log"

    def __post_init__(self) -> None:
        object.__setattr__(self, "eps", check_scalar("eps", self.eps, 0.0))

    def clock(self, T: ArrayLike) -> Array:
        return np.log1p(np.asarray(T, float))

    def age(self, c: ArrayLike) -> Array:
        return np.expm1(np.asarray(c, float))

    def dage(self, c: ArrayLike) -> Array:
        return np.exp(np.asarray(c, float))

    def radius_sq(self, c: ArrayLike) -> Array:
        return 1.0 + self.eps * np.asarray(c, float)

    def dradius_sq(self, c: ArrayLike) -> Array:
        return np.full_like(np.asarray(c, float), self.eps)

    def clock_at_radius(self, r: ArrayLike) -> Array:
        return (np.asarray(r, float) ** 2 - 1.0) / self.eps

    def radius(self, T: ArrayLike) -> Array:
        return np.sqrt(self.radius_sq(self.clock(T)))


# Gauss-Legendre rule on [0, 1] for the Eyring-Nabarro age integral.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(64)
_GL_X = 0.5 * (_GL_X + 1.0)
_GL_W = 0.5 * _GL_W
# Beyond this exponent the integrand of T(Q) is below e^-40 relative: cut there.
_EN_CUT = 40.0
_EN_BLOCK = 4096  # clocks per block of EyringNabarroCreep.age: 2 MB a temporary


@dataclass(frozen=True)
class EyringNabarroCreep:
    """Exact Eyring-Nabarro creep (eqs. 15-16) in reduced form ``ds/dT = eps s e^{(1/s-1)/eps}``.

    ``s = a_r^2``; ``eps = S/Y`` and ``t0`` as in eq. 18. Clock ``Q = (1 - 1/s)/eps``.

    Parameters
    ----------
    eps : float
        Creep parameter ``S/Y`` (``>= 0``). ``eps = 0`` means no ageing.
    """

    eps: float
    name: str = "eyring-nabarro"

    def __post_init__(self) -> None:
        object.__setattr__(self, "eps", check_scalar("eps", self.eps, 0.0))

    def radius_sq(self, c: ArrayLike) -> Array:
        return 1.0 / (1.0 - self.eps * np.asarray(c, float))

    def dradius_sq(self, c: ArrayLike) -> Array:
        return self.eps / (1.0 - self.eps * np.asarray(c, float)) ** 2

    def clock_at_radius(self, r: ArrayLike) -> Array:
        return (1.0 - 1.0 / np.asarray(r, float) ** 2) / self.eps

    def dage(self, c: ArrayLike) -> Array:
        c = np.asarray(c, float)
        return np.exp(c) / (1.0 - self.eps * c)

    def age(self, c: ArrayLike) -> Array:
        """``T(Q) = int_0^Q e^q/(1 - eps q) dq``.

        With ``b = 1 - eps Q`` and ``v = Q - q = (b/eps)(e^t - 1)`` (ours) the integral becomes
        ``T = (e^Q/eps) int_0^{ln(1/b)} exp(-(b/eps)(e^t - 1)) dt``, an entire integrand that a
        fixed Gauss-Legendre rule resolves to rounding for any ``eps > 0`` and ``b > 0``.
        """
        Q = np.asarray(c, float)
        eps = self.eps
        if eps == 0.0:
            return np.expm1(Q)
        flat = Q.ravel()
        out = np.empty(flat.size)
        # the rule's temporaries hold 64 values per point: in blocks, so that their memory is
        # bounded whatever the size of c (the steady integral asks for 48 clocks per velocity)
        for i0 in range(0, flat.size, _EN_BLOCK):
            out[i0:i0 + _EN_BLOCK] = self._age_block(flat[i0:i0 + _EN_BLOCK])
        return out.reshape(Q.shape)[()]

    def _age_block(self, Q: Array) -> Array:
        eps = self.eps
        b = 1.0 - eps * Q
        # upper limit: ln(1/b), cut where (b/eps)(e^t - 1) exceeds _EN_CUT
        t_hi = np.minimum(-np.log1p(-eps * Q), np.log1p(_EN_CUT * eps / b))
        t = t_hi[..., None] * _GL_X
        integrand = np.exp(-(b[..., None] / eps) * np.expm1(t))
        # an elementwise product and a sum along the rule: each row is summed the same way
        # whatever the batch (a matrix product need not be), so one T alone or in an array
        # gives the same bits
        integral = t_hi * np.sum(integrand * _GL_W, axis=-1)
        return np.exp(Q) * integral / eps

    def clock(self, T: ArrayLike) -> Array:
        """Invert ``T(Q)`` by safeguarded Newton iteration on ``ln T(Q)``."""
        T = np.asarray(T, float)
        if self.eps == 0.0:
            return np.log1p(T)
        Tf = np.atleast_1d(T).astype(float)
        out = np.zeros_like(Tf)
        pos = Tf > 0
        Tp = Tf[pos]
        # T(Q) >= e^Q - 1, so Q <= ln(1 + T); and Q < 1/eps.
        hi = np.minimum(np.log1p(Tp), (1.0 - 1e-15) / self.eps)
        lo = np.zeros_like(hi)
        q = hi.copy()
        # iterate only the points not yet converged: a converged point must not move while
        # its neighbours in the array still iterate (alone or in an array: the same answer)
        act = np.arange(q.size)
        for _ in range(200):
            qa = q[act]
            Fq = self.age(qa)
            g = np.log(Fq) - np.log(Tp[act])
            lo[act] = np.where(g < 0, qa, lo[act])
            hi[act] = np.where(g > 0, qa, hi[act])
            qn = qa - g * Fq / self.dage(qa)
            outside = (qn <= lo[act]) | (qn >= hi[act])
            qn = np.where(outside, 0.5 * (lo[act] + hi[act]), qn)
            done = np.abs(qn - qa) <= 1e-15 * np.maximum(1.0, np.abs(qa))
            q[act] = qn
            act = act[~done]
            if act.size == 0:
                break
        out[pos] = q
        return out.reshape(T.shape)

    def radius(self, T: ArrayLike) -> Array:
        return np.sqrt(self.radius_sq(self.clock(T)))

    @property
    def valid_clock(self) -> float:
        """Clock ``Q_v = (1 - eps)/eps`` at which ``a_r^2 = 1/eps``: the contact stress has
        relaxed to ``S``, the end of the law's range (module docstring)."""
        return math.inf if self.eps == 0.0 else (1.0 - self.eps) / self.eps

    @property
    def max_age(self) -> float:
        """Age ``T_v = (e^{1/eps}/eps) [E1(1) - E1(1/eps)]`` at the end of the law's range.

        Evaluated in logarithms: ``inf`` once it exceeds the largest float (``eps < 0.0014``).
        """
        eps = self.eps
        if eps == 0.0:
            return math.inf
        if eps >= 1.0:
            return 0.0
        # imported here: scipy.special costs ~0.3 s of CPU, and the command line's start
        # reads this module (app.options -> theory.model -> creep) for its defaults
        from scipy.special import exp1

        gap = float(exp1(1.0) - exp1(1.0 / eps))
        log_t = 1.0 / eps - math.log(eps) + math.log(gap)
        return math.exp(log_t) if log_t < 709.0 else math.inf


def max_age(eps: float, creep: str = "eyring-nabarro") -> float:
    """Largest reduced age ``T`` a creep law is used for: ``inf`` for the log law, ``T_v(eps)``
    (module docstring) for the Eyring-Nabarro law."""
    check_choice("creep", creep, CREEP_LAWS)
    eps = check_scalar("eps", eps, 0.0, EPS_MAX)
    return math.inf if creep == "log" else EyringNabarroCreep(eps).max_age


def check_age(T: ArrayLike, eps: ArrayLike, creep: str, name: str = "T") -> None:
    """Refuse ages beyond the Eyring-Nabarro law's range (:func:`max_age`), naming ``name``.

    ``T`` and ``eps`` are broadcast; the log law accepts every age.
    """
    if creep == "log":
        return
    T_b, eps_b = np.broadcast_arrays(np.asarray(T, float), np.asarray(eps, float))
    for e in np.unique(eps_b):
        t_v = EyringNabarroCreep(float(e)).max_age
        over = (eps_b == e) & (T_b > t_v)
        if np.any(over):
            raise ValueError(
                f"{name} = {float(T_b[over].flat[0]):g} is beyond the Eyring-Nabarro law's range "
                f"at eps = {float(e):g}: by T = {t_v:.4g} the contact stress has relaxed to S "
                f"(a_r^2 = 1/eps) and the contact runs away; use {name} <= {t_v:.4g} or "
                "creep = log (--creep log)"
            )


def creep_law(name: str, eps: float) -> LogCreep | EyringNabarroCreep:
    """Build a creep law by name: ``"log"`` (eq. 17) or ``"eyring-nabarro"`` (eqs. 15-16)."""
    check_choice("creep", name, CREEP_LAWS)
    return LogCreep(eps) if name == "log" else EyringNabarroCreep(eps)


@dataclass(frozen=True)
class CreepMaterial:
    """Material constants of Eyring-Nabarro creep (eqs. 15-16) and their reduced form (eq. 18).

    Parameters
    ----------
    Y : float
        Yield (hardness) stress, Pa.
    S : float
        Stress scale of the Eyring activation, Pa (``S << Y``).
    edot0 : float
        Strain-rate prefactor, 1/s.
    """

    Y: float
    S: float
    edot0: float

    def __post_init__(self) -> None:
        check_scalar("Y", self.Y, 0.0, lo_open=True)
        check_scalar("S", self.S, 0.0, lo_open=True)
        check_scalar("edot0", self.edot0, 0.0, lo_open=True)

    @property
    def eps(self) -> float:
        """``eps = S/Y`` (eq. 18)."""
        return self.S / self.Y

    @property
    def t0(self) -> float:
        """``t0 = 1 / (edot0 (Y/S) exp(Y/S))`` in seconds (eq. 18), computed in logs."""
        x = self.Y / self.S
        return math.exp(-x - math.log(self.edot0) - math.log(x))

    @classmethod
    def from_reduced(cls, eps: float, t0: float, Y: float) -> CreepMaterial:
        """Material with given ``eps``, ``t0`` (s) and hardness ``Y`` (Pa): inverts eq. 18."""
        eps = check_scalar("eps", eps, 0.0, lo_open=True)
        t0 = check_scalar("t0", t0, 0.0, lo_open=True)
        x = 1.0 / eps
        return cls(Y=Y, S=eps * Y, edot0=math.exp(-x - math.log(t0) - math.log(x)))


PER_EPS_CHUNK = 8192
"""Points evaluated at once by :func:`per_eps`: the quadratures hold a few kB of temporaries
per point, so this bounds their memory (tens of MB) for any array size, at no cost in speed."""


def per_eps(
    fn: Callable[[CreepLaw, NDArray[np.float64]], NDArray[np.float64]],
    creep: str,
    eps: NDArray[np.float64],
    x: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Broadcast ``fn(law, x)`` over arrays of ``eps``, building one law per distinct ``eps``.

    The creep laws carry a scalar ``eps``; this groups the points of a grid by ``eps`` (one
    sort, so many distinct values cost no more than one each) so that every public function
    broadcasts over ``(eps, x)`` like a NumPy ufunc, and evaluates ``fn`` on at most
    :data:`PER_EPS_CHUNK` points at a time (every point is independent of the others, so the
    result does not depend on the chunking).
    """
    eps_b, x_b = np.broadcast_arrays(eps, x)
    flat_e, flat_x = eps_b.ravel(), x_b.ravel()
    out = np.empty(flat_e.size)
    order = np.argsort(flat_e, kind="stable")
    e_sorted = flat_e[order]
    starts = np.flatnonzero(np.r_[True, e_sorted[1:] != e_sorted[:-1]])
    for i0, i1 in zip(starts, np.r_[starts[1:], e_sorted.size], strict=True):
        law = creep_law(creep, float(e_sorted[i0]))
        for j in range(i0, i1, PER_EPS_CHUNK):
            idx = order[j:min(j + PER_EPS_CHUNK, i1)]
            out[idx] = fn(law, flat_x[idx])
    return out.reshape(eps_b.shape) if eps_b.ndim else out[0]


def radius(T: ArrayLike, eps: ArrayLike, creep: str = "log") -> NDArray[np.float64]:
    """``a_r(T)`` for arrays of age ``T`` (in ``t0``) and ``eps``, broadcast (eqs. 17, 15-16)."""
    check_choice("creep", creep, CREEP_LAWS)
    T_a = check_range("T", T, 0.0)
    eps_a = check_range("eps", eps, 0.0, EPS_MAX)
    check_broadcast(T=T_a, eps=eps_a)
    check_age(T_a, eps_a, creep)
    return per_eps(lambda law, t: law.radius(t), creep, eps_a, T_a)


def creep_law_difference(eps: ArrayLike, T: ArrayLike) -> Array:
    """``a_r`` of the Eyring-Nabarro law minus that of the log law, broadcast over (eps, T)."""
    return radius(T, eps, "eyring-nabarro") - radius(T, eps, "log")
