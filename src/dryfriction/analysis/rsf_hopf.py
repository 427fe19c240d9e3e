"""The nature of the Hopf bifurcation of steady sliding of a rate-and-state spring slider:
critical stiffness, frequency and first Lyapunov coefficient ``l1`` from the
equations (:func:`dryfriction.theory.hopf.first_lyapunov`), not from simulations.

The slider (:mod:`dryfriction.rsf.driving`): ``k (x_load - x) = mu(V, theta) + eta V + m dV/dt``,
load point at ``V*`` (m/s), one or two state variables with the ageing, slip, PRZ or Nagata law
(:mod:`dryfriction.rsf.law`; the standard friction law: the regularised one differs from it
by ``O((V0/V)^2 exp(-2 Psi/a))``, far below anything here). Reduced variables (ours), time in
``Dc/V*``::

    x = ln(V/V*),  y_i = ln(theta_i V*/Dc_i),  s = (tau - mu_ss(V*) - eta V*)/a  (with mass)
    kappa = k Dc,  e = eta V*,  M = m V*^2/Dc,  delta_i = Dc/Dc_i

    mu - mu_ss(V*) = a x + b y_1 + b2 y_2                                   (Ruina 1983)
    y_i' = delta_i (e^-y_i - e^x)                        ageing (Dieterich 1979)
    y_i' = -delta_i e^x (x + y_i)                        slip (Ruina 1983)
    y_i' = delta_i (e^-y_i - e^(2x + y_i)) / 2           PRZ (Perrin, Rice & Zheng 1995)
    y_1' = e^-y_1 - e^x - (c/b) kappa (1 - e^x)          Nagata (2012), tau' = kappa (1 - e^x)

    quasi-static:  (a + e e^x) x' = kappa (1 - e^x) - b y_1' - b2 y_2'
    with mass:     M e^x x' = a (s - x) - b y_1 - b2 y_2 - e (e^x - 1),  s' = (kappa/a)(1 - e^x)

Steady sliding is the origin for every ``kappa``. ``kappa_c`` is the largest ``kappa`` where
a complex pair of the Jacobian crosses the imaginary axis (found by bisection on the rightmost
real part, checked against Rice & Ruina's closed form in the tests); ``l1`` is taken there in
the coordinates above (dimensionless: ``l1 = Re c1/omega`` does not depend on the time unit).
Its sign is the nature: ``< 0`` supercritical, ``> 0`` subcritical; ``|l1|`` below
``DEGENERATE_TOL`` times the largest of its three terms is *degenerate* (the terms cancel to
the precision of the derivatives, ~1e-13 with the Cauchy circle).

The amplitude prediction (ours, from the normal form): near ``kappa_c`` the critical
eigenvalue's real part is ``beta ~ sigma_k (kappa - kappa_c)``; the cycle's half peak-to-peak
``ln V`` is ``2 |q_x| sqrt(-beta/Re c1)`` (:func:`dryfriction.theory.hopf.cycle_amplitude`),
i.e. ``amp_coef sqrt(|kappa - kappa_c|/kappa_c)`` on the side where it exists.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import brentq

from ..rsf.law import RateState
from ..theory.hopf import HopfPoint, first_lyapunov, jacobian
from ..validation import Array, check_scalar

__all__ = ["RSFHopf", "SliderField", "rsf_hopf", "NATURES", "DEGENERATE_TOL"]

DEGENERATE_TOL = 1e-8
"""``|l1|`` over its largest term below which the bifurcation is reported degenerate (ours:
the Cauchy-circle derivatives are good to ~1e-13 relative, the Jacobian's eigenvectors to
~1e-14; 1e-8 leaves room for ill-conditioned eigenvectors and is far below any l1 found
non-zero here, whose ratios are 1e-3 and above)."""

NATURES = ("supercritical", "subcritical", "degenerate", "none", "undetermined")
"""What :func:`rsf_hopf` reports: ``none`` where steady sliding is stable at every stiffness;
``undetermined`` where the normal form could not be computed (``note`` says why)."""


@dataclass(frozen=True)
class SliderField:
    """The reduced spring-slider vector field (module docstring), holomorphic in its variables.

    Parameters
    ----------
    model : RateState
        Friction law and parameters.
    v : float
        Load-point velocity ``V*``, m/s, ``> 0``.
    damping, mass : float
        ``eta/sigma`` (s/m) and ``m`` (s^2/m), per unit normal force, ``>= 0``.
    """

    model: RateState
    v: float
    damping: float = 0.0
    mass: float = 0.0

    def __post_init__(self) -> None:
        check_scalar("v", self.v, 0.0, lo_open=True)
        check_scalar("damping", self.damping, 0.0)
        check_scalar("mass", self.mass, 0.0)

    @property
    def n(self) -> int:
        """Number of variables: ``x``, the ``y_i`` and, with mass, ``s``."""
        return 1 + self.model.n_state + (self.mass > 0)

    @property
    def kappa_scale(self) -> float:
        """``kappa = k Dc`` per unit of ``k`` (m)."""
        return self.model.dc

    def _state_rates(self, x: Any, ys: list[Any], kappa: float) -> list[Any]:
        m = self.model
        out = []
        for i, y in enumerate(ys):
            delta = 1.0 if i == 0 else m.dc / float(m.dc2)  # type: ignore[arg-type]
            if m.state_law in ("ageing", "nagata"):
                r = delta * (np.exp(-y) - np.exp(x))
                if m.state_law == "nagata":
                    r = r - (m.c / m.b) * kappa * (1.0 - np.exp(x))
            elif m.state_law == "slip":
                r = -delta * np.exp(x) * (x + y)
            else:  # prz
                r = 0.5 * delta * (np.exp(-y) - np.exp(2 * x + y))
            out.append(r)
        return out

    def __call__(self, X: Array, kappa: float) -> Array:
        """``X'`` (per unit time ``Dc/V*``) at the reduced state ``X`` and stiffness ``kappa``."""
        m = self.model
        e = self.damping * self.v
        bs = [m.b] + ([m.b2] if m.dc2 is not None else [])
        ns = len(bs)
        x, ys = X[0], [X[1 + i] for i in range(ns)]
        rates = self._state_rates(x, ys, kappa)
        ex = np.exp(x)
        if self.mass > 0:
            M = self.mass * self.v**2 / m.dc
            s = X[1 + ns]
            mu = m.a * x + sum(b * y for b, y in zip(bs, ys, strict=True))
            xdot = (m.a * s - mu - e * (ex - 1.0)) * np.exp(-x) / M
            sdot = kappa / m.a * (1.0 - ex)
            return np.array([xdot, *rates, sdot])
        xdot = (kappa * (1.0 - ex) - sum(b * r for b, r in zip(bs, rates, strict=True))) / (
            m.a + e * ex)
        return np.array([xdot, *rates])

    def growth(self, kappa: float) -> complex:
        """The rightmost eigenvalue of the Jacobian at steady sliding (1/(Dc/V*))."""
        lam = np.linalg.eigvals(jacobian(lambda X: self(X, kappa), np.zeros(self.n)))
        return complex(lam[np.argmax(lam.real)])


@dataclass(frozen=True)
class RSFHopf:
    """The Hopf point of steady sliding at one load velocity (module docstring).

    Attributes
    ----------
    velocity : float
        Load velocity ``V*``, m/s.
    k_c : float
        Critical stiffness, 1/m per unit normal force (NaN: none, steady sliding stable).
    frequency : float
        Angular frequency at ``k_c``, rad/s.
    l1 : float
        First Lyapunov coefficient in the reduced coordinates (dimensionless).
    relative_l1 : float
        ``l1`` over its largest term (how far from a cancellation).
    nature : str
        One of :data:`NATURES`.
    amp_coef : float
        Half peak-to-peak ``ln V`` of the cycle per ``sqrt(|k - k_c|/k_c)`` (dimensionless),
        on the side where the cycle exists (below ``k_c`` if supercritical, above if
        subcritical); NaN if degenerate or none.
    point : HopfPoint or None
        The normal form (reduced coordinates and time).
    note : str
        What the user must know about this row (an undetermined nature, a ``K_c`` off Rice &
        Ruina's closed form); empty if nothing.
    growth_slope : float
        ``-(k_c/omega) dRe(lambda)/dk`` at ``k_c`` (dimensionless, ``> 0``): the linear
        growth rate per radian is ``growth_slope (k_c - k)/k_c`` near ``k_c``.
    """

    velocity: float
    k_c: float
    frequency: float
    l1: float
    relative_l1: float
    nature: str
    amp_coef: float
    point: HopfPoint | None
    growth_slope: float = math.nan
    note: str = ""

    def as_row(self) -> dict[str, Any]:
        """The CSV/JSON row: ``velocity`` (m/s), ``K_c`` (1/m), ``frequency`` (rad/s), ``l1``,
        ``relative_l1``, ``nature``, ``amp_coef``, ``note``."""
        return {"velocity": self.velocity, "K_c": self.k_c, "frequency": self.frequency,
                "l1": self.l1, "relative_l1": self.relative_l1, "nature": self.nature,
                "amp_coef": self.amp_coef, "note": self.note}


def critical_kappa(field: SliderField) -> float:
    """Largest reduced stiffness ``kappa = k Dc`` where steady sliding loses stability (NaN if
    it is stable at every stiffness): a geometric scan down from a stable stiffness, then
    Brent's method on the rightmost eigenvalue's real part."""
    m = field.model
    # an upper bound: the quasi-static closed form times the inertial factor, or b itself
    hi = 4.0 * max(m.b_total, m.a) * (1.0 + field.mass * field.v**2 / (m.a * m.dc)) + 1e-12
    for _ in range(60):
        if field.growth(hi).real < 0:
            break
        hi *= 4.0
    else:
        return math.nan
    lo = hi
    for _ in range(400):
        lo /= 1.25
        if lo < 1e-9 * hi:
            return math.nan
        if field.growth(lo).real > 0:
            break
    else:
        return math.nan
    return float(brentq(lambda k: field.growth(k).real, lo, lo * 1.25, xtol=1e-15 * hi,
                        rtol=1e-15, maxiter=200))


def rsf_hopf(model: RateState, v: float, damping: float = 0.0, mass: float = 0.0
             ) -> RSFHopf:
    """Critical stiffness, frequency and first Lyapunov coefficient of steady sliding at ``v``.

    Parameters
    ----------
    model : RateState
        Friction law (one or two state variables; ageing, slip, PRZ or Nagata).
    v : float
        Load-point velocity, m/s, ``> 0``.
    damping : float
        Radiation damping ``eta/sigma``, s/m, ``>= 0``.
    mass : float
        Mass per unit normal force, s^2/m, ``>= 0``.

    Returns
    -------
    RSFHopf
        ``k_c = kappa_c/Dc`` (1/m), ``omega = omega_reduced V/Dc`` (rad/s), ``l1`` and the
        nature (module docstring).
    """
    field = SliderField(model, v, damping, mass)
    kc = critical_kappa(field)
    if not math.isfinite(kc):
        return RSFHopf(v, math.nan, math.nan, math.nan, math.nan, "none", math.nan, None)
    note = ""
    if model.n_state == 1 and model.state_law != "nagata":
        ref = model.critical_stiffness(v, damping, mass) * model.dc
        if abs(kc / ref - 1.0) > 1e-6:  # the eigenproblem lost precision (a huge mass)
            note = (f"K_c is {kc / ref - 1.0:+.1e} off Rice & Ruina's closed form: the "
                    "eigenproblem is ill-conditioned here, l1 is not to be trusted")
    try:
        point = first_lyapunov(lambda X: field(X, kc), np.zeros(field.n), residual_max=1e-7)
    except ValueError as exc:
        return RSFHopf(v, kc / model.dc, math.nan, math.nan, math.nan, "undetermined",
                       math.nan, None, note=f"no normal form: {exc}")
    rel = point.relative_l1
    if abs(rel) < DEGENERATE_TOL:
        nature = "degenerate"
    else:
        nature = "supercritical" if point.l1 < 0 else "subcritical"
    amp = math.nan
    dk = 1e-5 * kc
    sigma_k = (field.growth(kc + dk).real - field.growth(kc - dk).real) / (2 * dk)
    if nature != "degenerate":
        # beta = sigma_k (kappa - kappa_c) = -sigma_k kappa_c d on the cycle's side, d = |.|/kc
        amp = 2 * abs(point.q[0]) * math.sqrt(abs(sigma_k * kc / point.c1.real))
    return RSFHopf(velocity=v, k_c=kc / model.dc, frequency=point.omega * v / model.dc,
                   l1=point.l1, relative_l1=rel, nature=nature, amp_coef=amp, point=point,
                   growth_slope=-sigma_k * kc / point.omega, note=note)
