"""Rate-and-state friction (RSF): the laws, their steady state and linear stability.

SI units throughout: slip and ``dc`` in m, velocities in m/s, times in s; friction and the
constitutive parameters ``a``, ``b``, ``mu0`` are dimensionless. Stiffness ``k`` (1/m), damping
``eta`` (s/m) and mass ``m`` (s^2/m) are per unit normal force (the rsfmodel convention); see
:mod:`dryfriction.rsf.driving` for the spring-slider driver.

Laws (``theta`` in s):

* friction (Dieterich 1979; Ruina 1983), with an optional second state variable
  (Ruina 1983; Gu, Rice, Ruina & Tse 1984)::

      mu = mu0 + a ln(V/V0) + b ln(V0 theta/Dc) + b2 ln(V0 theta2/Dc2)

* the regularised form, valid down to ``V = 0`` and odd in ``V`` (Rice & Ben-Zion 1996;
  Lapusta, Rice, Ben-Zion & Zheng 2000; Rice, Lapusta & Ranjith 2001)::

      mu = a asinh( V/(2 V0) exp(Psi/a) ),  Psi = mu0 + b ln(V0 theta/Dc) + b2 ln(V0 theta2/Dc2)

  It equals the standard form up to a relative ``O((V0/V)^2 exp(-2 Psi/a))`` once
  ``V >> 2 V0 exp(-Psi/a)``;

* the Dieterich ("ageing") law ``dtheta/dt = 1 - |V| theta/Dc`` (Dieterich 1979; named by
  Ruina 1983) and the Ruina ("slip") law ``dtheta/dt = -(|V| theta/Dc) ln(|V| theta/Dc)``
  (Ruina 1983). Each state variable follows the same law with its own ``Dc``;
* the Perrin-Rice-Zheng ("prz") law ``dtheta'/dt = 1 - (|V| theta'/(2 Dc))^2`` (Perrin, Rice
  & Zheng 1995, *J. Mech. Phys. Solids* 43, 1461), written here for ``theta = theta'/2`` so
  that every law has ``theta_ss = Dc/V`` and the same ``mu0`` (PRZ's own ``theta'`` would
  shift ``mu0`` by ``b ln 2``): ``dtheta/dt = (1 - (|V| theta/Dc)^2)/2``, i.e. ``d ln
  theta/dt = (|V|/Dc) sinh(-ln(|V| theta/Dc))``, odd in ``ln(V theta/Dc)`` like the slip law
  (ours, by the substitution); it heals at rest as ``theta' = t``;
* the Nagata ("nagata") law ``dtheta/dt = 1 - |V| theta/Dc - (c/b) theta dtau/dt`` (Nagata,
  Nakatani & Yoshida 2012, *J. Geophys. Res.* 117, B02314: the ageing law plus a weakening by
  the rate of shear stress ``tau`` over normal stress, ``c >= 0``, about 2 in their fits).
  Here ``tau`` is the stress the spring applies, ``k (x_load - x)`` (what the apparatus
  measures; equal to friction without damping or mass), so it needs a finite spring; with a
  fast change of ``tau`` the state drops by ``(c/b) Delta tau`` and the direct effect of a
  step on a stiff machine is ``a ln(V2/V1)/(1 + c)`` (ours, from the law). One state
  variable. The paper's own text (and its equation number) was not at hand: the form and the
  sign are those restated by Bhattacharya & Rubin 2014 (*J. Geophys. Res.* 119, 2272; ``c =
  0`` is the ageing law) and by Kame et al. (13th Int. Conf. Fracture, 2013, whose
  nondimensional equation for ``d ln V/dt`` carries the factor ``1 + c`` on ``dtau/dt`` that
  this form gives).

Steady state: ``theta_ss = Dc/V`` and ``mu_ss = mu0 + (a - b - b2) ln(V/V0)`` (Ruina 1983),
for every law.

Linear stability of steady sliding of a spring slider (one state variable, either law, both
laws have the same linearisation about steady state; Ruina 1983; Rice & Ruina 1983): the
critical stiffness is ``k_c = (b - a)/Dc`` quasi-statically and
``k_c = (b - a)/Dc (1 + m V^2/(a Dc))`` with inertia (Rice & Ruina 1983); at ``k = k_c`` the
slider oscillates at ``omega = (V/Dc) sqrt((b - a)/a)`` (Rice & Ruina 1983; Gu et al. 1984;
independent of the mass, ours by the same algebra). Quasi-dynamic radiation damping ``eta``
enters the linearisation only through ``a -> a + eta V`` (ours, same algebra).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from ..validation import (
    FRICTION_MAX,
    REQUIRED,
    Array,
    Parameter,
    check_range,
    check_scalar,
    declared,
)

__all__ = ["RateState", "RateStateModel", "RATE_STATE_PARAMETERS", "STATE_LAWS", "V_MAX",
           "V_MIN"]

V_MAX: float = 1e3
"""Largest reference or load velocity accepted, m/s: far above seismic slip rates (~1 m/s);
``ln(V0 theta/Dc)`` and the integration stay finite below it."""

V_MIN: float = 1e-30
"""Slowest moving load point accepted, m/s (0 is a hold): it covers a picometre in the age of
the universe; the trap model's velocities start at the same number (``U_MIN``, a0/t0)."""

StateLaw = Literal["ageing", "slip", "prz", "nagata"]
STATE_LAWS: tuple[str, ...] = ("ageing", "slip", "prz", "nagata")

MU_MAX: float = 1e3
"""Largest ``a``, ``b``, ``b2`` accepted (``|mu0|``: ``validation.FRICTION_MAX``): friction
coefficients and their rate and state parameters are of order 1 (``a, b ~ 0.01``); beyond
this the friction times the stiffness overflows long before a run could mean anything
(``a = 1e308`` ran to garbage)."""

# Above this ln z, asinh(z) = ln(2z) + 1/(4 z^2) to double precision (next term ~ z^-4).
_ASINH_LARGE = 20.0


def asinh_exp(lnz: ArrayLike) -> Array:
    """``asinh(exp(lnz))`` without overflow for large ``lnz``."""
    lnz = np.asarray(lnz, float)
    big = lnz > _ASINH_LARGE
    safe = np.where(big, 0.0, lnz)
    return np.where(
        big, lnz + math.log(2.0) + 0.25 * np.exp(-2.0 * np.where(big, lnz, 0.0)),
        np.arcsinh(np.exp(safe)),
    )


RATE_STATE_PARAMETERS: dict[str, Parameter] = {p.name: p for p in (
    Parameter("a", lo=0.0, hi=MU_MAX, lo_open=True, meaning="direct-effect coefficient"),
    Parameter("b", lo=0.0, hi=MU_MAX, meaning="evolution coefficient, first state variable"),
    Parameter("dc", lo=0.0, lo_open=True, meaning="characteristic slip, first state variable, m"),
    Parameter("mu0", lo=-FRICTION_MAX, hi=FRICTION_MAX, meaning="friction at V0 in steady state"),
    Parameter("v0", lo=0.0, hi=V_MAX, lo_open=True, meaning="reference velocity, m/s"),
    Parameter("state_law", "ageing", choices=STATE_LAWS, meaning="evolution law of the state"),
    Parameter("b2", 0.0, 0.0, MU_MAX, meaning="evolution coefficient, second state variable"),
    Parameter("dc2", None, 0.0, lo_open=True,
              meaning="characteristic slip of the second state variable, m (None: one state "
                      "variable)"),
    Parameter("regularized", False, boolean=True, meaning="the asinh form, defined at V <= 0"),
    Parameter("c", 0.0, 0.0, MU_MAX, meaning="Nagata's stress-rate coefficient (nagata only)"),
)}
"""Rate-and-state parameters, in :class:`RateState`'s field order: every default and range
declared once (the fields and :meth:`RateState.from_mapping` read them from here)."""


def _default(name: str) -> Any:
    return declared(RATE_STATE_PARAMETERS, name)


@dataclass(frozen=True)
class RateState:
    """Rate-and-state friction parameters (validated at construction).

    Parameters
    ----------
    a : float
        Direct-effect coefficient, ``> 0`` (dimensionless).
    b : float
        Evolution-effect coefficient of the first state variable, ``>= 0``.
    dc : float
        Characteristic slip of the first state variable, m, ``> 0``.
    mu0 : float
        Reference friction at ``V = V0`` in steady state, ``|mu0| <= FRICTION_MAX`` (10).
    v0 : float
        Reference velocity, m/s, ``> 0``.
    state_law : {"ageing", "slip", "prz", "nagata"}
        Dieterich ageing law, Ruina slip law, Perrin-Rice-Zheng or Nagata law (module
        docstring; used for every state variable; Nagata's for one only).
    b2 : float
        Evolution coefficient of the optional second state variable, ``>= 0``.
    dc2 : float or None
        Characteristic slip of the second state variable, m, ``> 0``; ``None`` means one
        state variable (then ``b2`` must be 0).
    regularized : bool
        Use the regularised (``asinh``) friction law, defined for ``V <= 0`` too.
    c : float
        Nagata's stress-rate coefficient, ``>= 0`` (dimensionless); only with
        ``state_law = "nagata"`` (which needs ``b > 0``).
    """

    a: float = _default("a")
    b: float = _default("b")
    dc: float = _default("dc")
    mu0: float = _default("mu0")
    v0: float = _default("v0")
    state_law: StateLaw = _default("state_law")
    b2: float = _default("b2")
    dc2: float | None = _default("dc2")
    regularized: bool = _default("regularized")
    c: float = _default("c")

    def __post_init__(self) -> None:
        # every field against its declared range, once (RATE_STATE_PARAMETERS)
        for name, p in RATE_STATE_PARAMETERS.items():
            object.__setattr__(self, name, p.check(getattr(self, name)))
        if self.dc2 is None and self.b2 != 0.0:
            raise ValueError(f"b2 = {self.b2:g} needs dc2 (a second state variable)")
        if self.state_law != "nagata" and self.c != 0.0:
            raise ValueError(f"c = {self.c:g} is Nagata's stress-rate coefficient: it needs "
                             "state_law = 'nagata'")
        if self.state_law == "nagata" and (self.b == 0.0 or self.dc2 is not None):
            raise ValueError("state_law = 'nagata' needs b > 0 (its term is c/b) and one "
                             "state variable (no dc2)")

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_mapping(cls, m: Mapping[str, Any]) -> RateState:
        """Build from a mapping such as a protocol file's ``[model]`` table.

        Keys are the field names (``a``, ``b``, ``dc``, ``mu0``, ``v0``, ``state_law``, ``b2``,
        ``dc2``, ``regularized``); ``law = "rsf"`` is accepted and ignored. Unknown keys and
        missing required keys are errors.
        """
        allowed = {*RATE_STATE_PARAMETERS, "law"}
        unknown = set(m) - allowed
        if unknown:
            raise ValueError(
                f"unknown rate-and-state key(s) {', '.join(sorted(map(str, unknown)))}: "
                f"allowed {', '.join(sorted(allowed))}"
            )
        if "law" in m and m["law"] != "rsf":
            raise ValueError(f"law = {m['law']!r} is not allowed here: rate-and-state needs 'rsf'")
        missing = [k for k, p in RATE_STATE_PARAMETERS.items()
                   if p.default is REQUIRED and k not in m]
        if missing:
            raise ValueError(f"missing rate-and-state key(s): {', '.join(missing)}")
        kwargs = {k: v for k, v in m.items() if k != "law"}
        return cls(**kwargs)

    def to_dict(self) -> dict[str, Any]:
        """Plain mapping of the parameters (``from_mapping`` round-trips it)."""
        return asdict(self)

    # ------------------------------------------------------------------ the laws
    @property
    def n_state(self) -> int:
        """Number of state variables (1 or 2)."""
        return 1 if self.dc2 is None else 2

    @property
    def b_total(self) -> float:
        """``b + b2``: the steady-state evolution effect."""
        return self.b + self.b2

    def _psi(self, theta: Array, theta2: Array | None) -> Array:
        """``Psi = mu0 + b ln(V0 theta/Dc) (+ b2 ln(V0 theta2/Dc2))``."""
        psi = self.mu0 + self.b * np.log(self.v0 * theta / self.dc)
        if self.dc2 is not None:
            if theta2 is None:
                raise ValueError("theta2 is needed: these parameters have two state variables")
            psi = psi + self.b2 * np.log(self.v0 * np.asarray(theta2, float) / self.dc2)
        return psi

    def friction(self, v: ArrayLike, theta: ArrayLike, theta2: ArrayLike | None = None) -> Array:
        """Friction coefficient ``mu(V, theta[, theta2])``.

        Parameters
        ----------
        v : array_like
            Slip velocity, m/s; ``> 0`` for the standard law, any real for the regularised one.
        theta, theta2 : array_like
            State variables, s, ``> 0``.

        Returns
        -------
        ndarray
            Friction coefficient (dimensionless).
        """
        theta = check_range("theta", theta, 0.0, lo_open=True)
        if theta2 is not None:
            theta2 = check_range("theta2", theta2, 0.0, lo_open=True)
        if self.regularized:
            v = check_range("v", v)
            psi = self._psi(theta, theta2)
            av = np.abs(v)
            with np.errstate(divide="ignore"):
                lnz = np.log(av / (2.0 * self.v0)) + psi / self.a
            return np.sign(v) * self.a * np.where(av > 0, asinh_exp(lnz), 0.0)
        v = check_range("v", v, 0.0, lo_open=True)
        return self._psi(theta, theta2) + self.a * np.log(v / self.v0)

    def state_rate(self, v: ArrayLike, theta: ArrayLike, dc: float | None = None) -> Array:
        """``dtheta/dt`` (s/s) of the chosen state law at slip velocity ``v`` (m/s).

        ``dc`` defaults to the first state variable's; pass ``self.dc2`` for the second. For
        Nagata's law, at a constant shear stress (its term ``-(c/b) theta dtau/dt`` needs the
        stress rate, which the driver supplies).
        """
        v = np.abs(check_range("v", v))
        theta = check_range("theta", theta, 0.0, lo_open=True)
        dc = self.dc if dc is None else dc
        omega = v * theta / dc
        if self.state_law in ("ageing", "nagata"):
            return 1.0 - omega
        if self.state_law == "prz":
            return 0.5 * (1.0 - omega * omega)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(omega > 0, -omega * np.log(omega), 0.0)

    def steady_state_theta(self, v: ArrayLike) -> Array:
        """``theta_ss = Dc/V`` (s) for the first state variable (Ruina 1983)."""
        v = check_range("v", v, 0.0, lo_open=True)
        return self.dc / v

    def steady_state_friction(self, v: ArrayLike) -> Array:
        """Steady-state friction ``mu_ss(V)`` (Ruina 1983).

        ``mu0 + (a - b - b2) ln(V/V0)`` for the standard law; the regularised law evaluated at
        ``theta_i = Dc_i/V``.
        """
        v = check_range("v", v, 0.0, lo_open=True)
        if not self.regularized:
            return self.mu0 + (self.a - self.b_total) * np.log(v / self.v0)
        th2 = None if self.dc2 is None else self.dc2 / v
        return self.friction(v, self.dc / v, th2)

    def hold_peak_friction(self, t_hold: ArrayLike, v: float) -> Array:
        """Peak friction on reloading at ``v`` after a hold of ``t_hold`` (static friction).

        Protocol: steady sliding at ``v`` (``theta_i = Dc_i/v``), a truly stationary hold of
        ``t_hold`` s, then an infinitely stiff (kinematic) reload at ``v``: the peak is the
        friction at the first instant of reloading, ``mu(v, theta_i + t_hold)`` with the ageing
        law (``dtheta/dt = 1`` at rest; Dieterich 1979). For one state variable and the standard
        law this is ``mu_ss(v) + b ln(1 + v t_hold/Dc)`` (Beeler, Tullis & Weeks 1994; Marone
        1998, *Annu. Rev. Earth Planet. Sci.* 26, 643, the healing law with ``d mu_s/d ln t -> b``
        at long holds). The slip law does not evolve at rest, so it gives ``mu_ss(v)`` for every
        hold. With a finite machine stiffness the measured peak is lower (the slider creeps
        during reloading); that case needs :func:`dryfriction.rsf.driving.simulate`.

        Parameters
        ----------
        t_hold : array_like
            Hold times, s, ``>= 0``.
        v : float
            Sliding velocity before the hold and on reloading, m/s, ``> 0``.

        Returns
        -------
        ndarray
            Peak friction coefficient.
        """
        t_hold = check_range("t_hold", t_hold, 0.0)
        v = check_scalar("v", v, 0.0, lo_open=True)
        if self.state_law == "nagata":
            raise ValueError("hold_peak_friction is for a truly stationary contact on a "
                             "kinematic machine; Nagata's law needs the spring's stress rate: "
                             "use dryfriction.simulate on a spring")
        heal = {"ageing": 1.0, "prz": 0.5, "slip": 0.0}[self.state_law] * t_hold
        th2 = None if self.dc2 is None else self.dc2 / v + heal
        return self.friction(v, self.dc / v + heal, th2)

    # ------------------------------------------------------------------ stability
    def _one_state_standard(self, what: str) -> None:
        if self.dc2 is not None or self.regularized or self.state_law == "nagata":
            raise ValueError(
                f"the closed-form {what} is for one state variable, the standard law and "
                "the ageing, slip or PRZ law (their linearisations agree): "
                "use dryfriction.rsf.stability.linear_stability for these parameters"
            )

    def critical_stiffness(self, v: float = 1.0, damping: float = 0.0, mass: float = 0.0) -> float:
        """Critical spring stiffness ``k_c`` (1/m, per unit normal force) of steady sliding.

        ``k_c = (b - a')/Dc * (1 + m V^2/(a' Dc))`` with ``a' = a + eta V``: Rice & Ruina
        (1983) for ``eta = 0`` (``k_c = (b - a)/Dc`` quasi-statically); the ``eta`` term is
        ours (same algebra). Negative when steady sliding is stable at any stiffness.

        Parameters
        ----------
        v : float
            Steady sliding velocity, m/s (irrelevant when ``damping = mass = 0``).
        damping : float
            Radiation damping ``eta/sigma``, s/m, ``>= 0``.
        mass : float
            Slider mass per unit normal force, s^2/m, ``>= 0``.
        """
        v = check_scalar("v", v, 0.0, lo_open=True)
        damping = check_scalar("damping", damping, 0.0)
        mass = check_scalar("mass", mass, 0.0)
        self._one_state_standard("critical stiffness")
        ap = self.a + damping * v
        return (self.b - ap) / self.dc * (1.0 + mass * v * v / (ap * self.dc))

    def hopf_frequency(self, v: float, damping: float = 0.0) -> float:
        """Angular frequency (rad/s) of the oscillation at ``k = k_c``.

        ``omega = (V/Dc) sqrt((b - a')/a')``, ``a' = a + eta V`` (Rice & Ruina 1983 for
        ``eta = 0``; the ``eta`` term is ours); independent of the mass. Needs ``b > a'``.
        """
        v = check_scalar("v", v, 0.0, lo_open=True)
        damping = check_scalar("damping", damping, 0.0)
        self._one_state_standard("Hopf frequency")
        ap = self.a + damping * v
        if self.b <= ap:
            raise ValueError(
                f"b = {self.b:g} <= a + eta V = {ap:g}: steady sliding is stable at any "
                "stiffness and there is no Hopf bifurcation"
            )
        return v / self.dc * math.sqrt((self.b - ap) / ap)


RateStateModel = RateState
"""The rate-and-state model object: :class:`RateState` is it, frozen and checked
once at construction against :data:`RATE_STATE_PARAMETERS`; the two names are one class.
Not to be confused with :class:`dryfriction.fit.models.RSFModel`, a fit's parameter spec."""
