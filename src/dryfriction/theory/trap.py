"""One elastic trap: a pair of touching asperities (paper §3.1, docs/model.md §1).

Reduced units of this module: lengths in the contact radius ``a`` (``y = p/a`` is the
configuration coordinate, ``z = x/a`` the actual relative position), energies in ``Phi0``,
forces in ``Phi0/a``. The single parameter is ``alpha = kappa a^2 / (6 Phi0)``.

The pinning potential is ``psi(z) = 1 - 3 z^2 + 2|z|^3`` for ``|z| <= 1`` (0 outside), the
trap energy ``U = psi(z) + 3 alpha (z - y)^2``, and equilibrium ``psi'(z) + 6 alpha (z - y) = 0``.
The pinning force on the track is ``f = psi'(z) = 6 alpha (y - z)``.

Three regimes (reported by :func:`regime`, never guessed):

* very strong pinning, ``alpha < alpha0 = 3 - 2 sqrt 2``: the (+) spinodal ``y_c > 1``; a trap
  leaving (+) jumps straight out of contact (dies) at ``y_c``;
* strong pinning, ``alpha0 <= alpha < 1``: ``y_c <= 1``; the trap jumps onto the far side of the
  bump, the (-) branch, at ``y_c`` and dies at ``y = 1``;
* no pinning, ``alpha >= 1``: single-valued response, no hysteresis, no friction.

Integrals of the force along the (+) branch are polynomials in ``z`` (ours): with
``y(z) = -(z^2 + (1 - alpha) z)/alpha`` on that branch,
``W(z) = int_{-1}^{y(z)} f_+ dy = (1 + z)^2 (3 z^2/alpha + 1 - 2 z)``. This closed form avoids the
cancellation of the paper's ``H0`` formula (eq. 12 and the line after it) near ``alpha -> 1``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum

import numpy as np
from numpy.typing import ArrayLike

from ..validation import Array, check_scalar

__all__ = [
    "ALPHA0",
    "Regime",
    "regime",
    "psi",
    "dpsi",
    "z_plus",
    "z_minus",
    "z_unstable",
    "force_plus",
    "force_minus",
    "force_forward",
    "branch_work",
    "work_forward",
    "work_minus",
    "Trap",
]

ALPHA0: float = 3.0 - 2.0 * math.sqrt(2.0)
"""Boundary between very strong and strong pinning, where ``y_c = 1`` (ours, from §1)."""


class Regime(StrEnum):
    """Pinning regime of a trap (docs/model.md §1)."""

    VERY_STRONG = "very strong pinning"
    STRONG = "strong pinning"
    NONE = "no pinning"


def regime(alpha: float) -> Regime:
    """Pinning regime for reduced stiffness ``alpha`` (Tomlinson criterion ``alpha < 1``)."""
    alpha = check_scalar("alpha", alpha, 0.0, lo_open=True)
    if alpha >= 1.0:
        return Regime.NONE
    return Regime.VERY_STRONG if alpha < ALPHA0 else Regime.STRONG


def psi(z: ArrayLike) -> Array:
    """Reduced pinning potential ``psi(z) = 1 - 3 z^2 + 2 |z|^3`` for ``|z| <= 1``, else 0."""
    z = np.asarray(z, dtype=float)
    a = np.abs(z)
    return np.where(a <= 1.0, 1.0 - 3.0 * z * z + 2.0 * a**3, 0.0)


def dpsi(z: ArrayLike) -> Array:
    """Derivative ``psi'(z) = 6 z (|z| - 1)`` for ``|z| <= 1``, else 0 (force on the track)."""
    z = np.asarray(z, dtype=float)
    a = np.abs(z)
    return np.where(a <= 1.0, 6.0 * z * (a - 1.0), 0.0)


def _discriminant(y: Array, alpha: float) -> Array:
    # (1 - alpha)^2 - 4 alpha y = 4 alpha (y_c - y); clipped at the spinodal against rounding.
    return np.maximum((1.0 - alpha) ** 2 - 4.0 * alpha * y, 0.0)


def z_plus(y: ArrayLike, alpha: float) -> Array:
    """Stable near-side (+) branch ``z_+(y)``, ``-1 <= y <= y_c`` (docs/model.md §1).

    Root of ``z^2 + (1 - alpha) z + alpha y = 0`` with ``z <= -(1 - alpha)/2``. Outside the
    branch's domain the value is NaN.
    """
    y = np.asarray(y, dtype=float)
    out = -0.5 * ((1.0 - alpha) + np.sqrt(_discriminant(y, alpha)))
    yc = (1.0 - alpha) ** 2 / (4.0 * alpha)
    tol = 8.0 * np.finfo(float).eps * max(1.0, yc)  # y_c itself carries rounding
    return np.where((y >= -1.0 - tol) & (y <= yc + tol), out, np.nan)


def z_minus(y: ArrayLike, alpha: float) -> Array:
    """Stable far-side (-) branch, ``z_-(y) = -z_+(-y)``, ``-y_c <= y <= 1``."""
    return -z_plus(-np.asarray(y, dtype=float), alpha)


def z_unstable(y: ArrayLike, alpha: float) -> Array:
    """Unstable middle branch joining the two spinodals, ``-y_c <= y <= y_c``.

    For ``y >= 0`` it is the other root of the (+) quadratic, ``-(1 - alpha - sqrt(...))/2``;
    for ``y < 0`` it follows by the symmetry ``z(y) = -z(-y)``. ``|z| < (1 - alpha)/2``.
    """
    y = np.asarray(y, dtype=float)
    ay = np.abs(y)
    out = -np.sign(y) * 0.5 * ((1.0 - alpha) - np.sqrt(_discriminant(ay, alpha)))
    yc = (1.0 - alpha) ** 2 / (4.0 * alpha)
    return np.where(ay <= yc + 8.0 * np.finfo(float).eps * max(1.0, yc), out, np.nan)


def force_plus(y: ArrayLike, alpha: float) -> Array:
    """Pinning force on the (+) branch ``f_+(y) = 6 alpha (y - z_+(y))``, units ``Phi0/a``."""
    y = np.asarray(y, dtype=float)
    return 6.0 * alpha * (y - z_plus(y, alpha))


def force_minus(y: ArrayLike, alpha: float) -> Array:
    """Pinning force on the (-) branch ``f_-(y) = -f_+(-y)``."""
    return -force_plus(-np.asarray(y, dtype=float), alpha)


def force_forward(w: ArrayLike, alpha: float) -> Array:
    """Force of a trap that entered contact at ``w = -1`` and was pushed forward to ``w``.

    ``f_+(w)`` up to the spinodal ``y_c``; then, in strong pinning, ``f_-(w)`` up to ``w = 1``;
    zero before contact and after death. This is the integrand of eqs. 12 and 34 (ours: the
    strong-pinning continuation on (-)).
    """
    w = np.asarray(w, dtype=float)
    yc = (1.0 - alpha) ** 2 / (4.0 * alpha)
    on_plus = (w >= -1.0) & (w <= yc)
    on_minus = (w > yc) & (w <= 1.0)
    fp = np.where(on_plus, force_plus(np.where(on_plus, w, -1.0), alpha), 0.0)
    fm = np.where(on_minus, force_minus(np.where(on_minus, w, 1.0), alpha), 0.0)
    return fp + fm


def branch_work(z: ArrayLike, alpha: float) -> Array:
    """``W(z) = int_{-1}^{y(z)} f_+ dy = (1 + z)^2 (3 z^2/alpha + 1 - 2 z)`` (ours).

    ``z`` is a point on the (+) branch, ``-1 <= z <= -(1 - alpha)/2``; ``y(z)`` the
    configuration coordinate there. Exact polynomial, well conditioned for all ``alpha``.
    """
    z = np.asarray(z, dtype=float)
    return (1.0 + z) ** 2 * (3.0 * z * z / alpha + 1.0 - 2.0 * z)


def work_minus(a: ArrayLike, b: ArrayLike, alpha: float) -> Array:
    """``int_a^b f_-(w) dw`` for ``-y_c <= a, b <= 1`` (by the symmetry ``f_-(w) = -f_+(-w)``)."""
    return branch_work(z_plus(-np.asarray(b, float), alpha), alpha) - branch_work(
        z_plus(-np.asarray(a, float), alpha), alpha
    )


def work_forward(x: ArrayLike, alpha: float) -> Array:
    """``Phi(x) = int_{-1}^{x} force_forward(w) dw`` in closed form; equals ``H0`` past death."""
    x = np.asarray(x, dtype=float)
    yc = (1.0 - alpha) ** 2 / (4.0 * alpha)
    w_plus = branch_work(z_plus(np.clip(x, -1.0, yc), alpha), alpha)
    if yc >= 1.0:
        return np.where(x < -1.0, 0.0, w_plus)
    xm = np.clip(x, yc, 1.0)
    return np.where(x < -1.0, 0.0, w_plus + np.where(x > yc, work_minus(yc, xm, alpha), 0.0))


@dataclass(frozen=True)
class Trap:
    """Constants of one trap of reduced stiffness ``alpha`` (docs/model.md §1).

    Parameters
    ----------
    alpha : float
        ``kappa a^2 / (6 Phi0)``, must be ``> 0``. ``alpha >= 1`` is allowed here (it reports
        the no-pinning regime with ``H0 = 0``); friction calculations require ``alpha < 1``.
    """

    alpha: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "alpha", check_scalar("alpha", self.alpha, 0.0, lo_open=True))

    @property
    def regime(self) -> Regime:
        return regime(self.alpha)

    @property
    def pinned(self) -> bool:
        return self.alpha < 1.0

    @property
    def beta(self) -> float:
        """``beta = kappa a^2 / Phi0 = 6 alpha``."""
        return 6.0 * self.alpha

    @property
    def y_c(self) -> float:
        """Spinodal of the (+) branch, ``y_c = (1 - alpha)^2 / (4 alpha)``; NaN without pinning."""
        return (1.0 - self.alpha) ** 2 / (4.0 * self.alpha) if self.pinned else math.nan

    @property
    def z_c(self) -> float:
        """Position at the spinodal, ``z_+(y_c) = -(1 - alpha)/2``."""
        return -(1.0 - self.alpha) / 2.0 if self.pinned else math.nan

    @property
    def f_c(self) -> float:
        """Force at the spinodal, ``f_+(y_c) = 6 alpha (y_c - z_c)``."""
        return 6.0 * self.alpha * (self.y_c - self.z_c) if self.pinned else math.nan

    @property
    def f_max(self) -> float:
        """Largest pinning force on (+): ``max psi' = 3/2``, reached at ``z = -1/2`` (ours).

        ``df_+/dy = 6 alpha (1 - alpha / sqrt((1 - alpha)^2 - 4 alpha y))`` tends to ``-inf`` at
        the spinodal, so the force peaks before it, at ``y_m = (1 - 2 alpha)/(4 alpha) >= -1``.
        """
        return 1.5 if self.pinned else math.nan

    @property
    def death_point(self) -> float:
        """Where a forward-moving trap leaves contact: ``y_c`` (very strong) or ``1`` (strong)."""
        if not self.pinned:
            return math.nan
        return max(self.y_c, 1.0)

    @property
    def maxwell_point(self) -> float:
        """Maxwell plateau ``y_M = 0`` (the potential is even)."""
        return 0.0

    @property
    def maxwell_jump(self) -> float:
        """Force jump across the Maxwell plateau, ``f_+(0) - f_-(0) = 12 alpha (1 - alpha)``."""
        return 12.0 * self.alpha * (1.0 - self.alpha) if self.pinned else 0.0

    @property
    def H0(self) -> float:
        """Work dissipated per trap swept through, in ``Phi0`` (eq. 12).

        Very strong pinning: ``int_{-1}^{y_c} f_+ dy`` (the paper's case); strong pinning
        (ours): the (-) part returns energy, ``H0 = int_{-y_c}^{y_c} f_+ dy``. Zero for
        ``alpha >= 1``.
        """
        if not self.pinned:
            return 0.0
        return float(work_forward(self.death_point, self.alpha))

    @property
    def H0_paper(self) -> float:
        """The paper's closed form of ``int_{-1}^{y_c} f_+ dy`` (line after eq. 12).

        ``6 alpha [(y_c^2 - 1)/2 + (1 - alpha)(y_c + 1)/2 + (1 + alpha)^3/(12 alpha)]``. Equals
        :attr:`H0` in very strong pinning; kept as an independent check.
        """
        a, yc = self.alpha, self.y_c
        return 6 * a * ((yc**2 - 1) / 2 + (1 - a) * (yc + 1) / 2 + (1 + a) ** 3 / (12 * a))

    @property
    def H1(self) -> float:
        """``H1 = int_{y_c - 1}^{death} force_forward dy`` (eq. 28b; strong-pinning form ours)."""
        if not self.pinned:
            return 0.0
        return self.H0 - float(work_forward(self.y_c - 1.0, self.alpha))

    @property
    def contact_stiffness(self) -> float:
        """Contact shear stiffness after recoil to zero load, in units ``F_el/a`` (eqs. 13-14).

        ``kappa_c = N_p (2a)^-1 Delta f Phi0/a`` and ``F_el = N_p (2a)^-1 Phi0 H0``, so
        ``kappa_c a / F_el = Delta f / H0``.
        """
        return self.maxwell_jump / self.H0 if self.pinned else math.inf

    def energy(self, z: ArrayLike, y: ArrayLike) -> Array:
        """Trap energy ``U/Phi0 = psi(z) + 3 alpha (z - y)^2``."""
        z = np.asarray(z, float)
        return psi(z) + 3.0 * self.alpha * (z - np.asarray(y, float)) ** 2

    def summary(self) -> dict[str, float | str]:
        """All single-trap constants, JSON-ready."""
        return {
            "alpha": self.alpha,
            "alpha0": ALPHA0,
            "regime": self.regime.value,
            "y_c": self.y_c,
            "z_c": self.z_c,
            "f_c": self.f_c,
            "f_max": self.f_max,
            "death_point": self.death_point,
            "maxwell_point": self.maxwell_point,
            "maxwell_jump": self.maxwell_jump,
            "H0": self.H0,
            "H1": self.H1,
            "contact_stiffness": self.contact_stiffness,
        }
