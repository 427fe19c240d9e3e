"""The state laws a rate-and-state fit of a time series can use, and its initial state: the
extra parameters each brings and the
:class:`~dryfriction.rsf.RateState` and :class:`~dryfriction.rsf.driving.RSFInitial` of a set
of fitted values. :class:`.models.RSFModel` reads them; nothing here fits.

Laws (:mod:`dryfriction.rsf.law` for the equations and their sources):

* ``ageing``, ``slip``: Dieterich (1979), Ruina (1983), as before;
* ``prz``: Perrin, Rice & Zheng (1995), ``theta_ss = Dc/V`` (the same ``mu0`` as the others);
* ``nagata``: Nagata, Nakatani & Yoshida (2012), the ageing law with the stress-rate term
  ``-(c/b) theta dtau/dt``; ``c`` (dimensionless, ``0 <= c <= C_MAX``) is fitted; ``c = 0`` is
  the ageing law;
* ``ageing2``: two state variables (Ruina 1983; Gu, Rice, Ruina & Tse 1984), both with the
  ageing law: ``b2`` and ``dc2`` fitted besides ``b`` and ``dc`` (the ageing law for both,
  because the slide-hold-slide records this program fits need healing at rest, which the slip
  law lacks); ``mu_ss = mu0 + (a - b - b2) ln(V/V0)``.

Initial state (ours): ``"steady"`` starts the window in steady sliding at its first load
velocity (as before). ``"free"`` starts it at that velocity with the state ``theta0 = (Dc/V)
exp(state0)``, ``state0 = ln(theta0 V/Dc)`` a fitted parameter (dimensionless; ``> 0``:
friction above steady sliding by ``b state0``, the remnant of an earlier hold or step); the
slider's velocity is set to the load point's (the spring then adjusts within a slip of about
``a/k``, which the model follows). A second state variable starts steady.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from ..rsf.law import RateState
from ..rsf.spring import RSFInitial

__all__ = ["FIT_LAWS", "INITIAL_STATES", "C_MAX", "law_specs", "initial_specs",
           "rate_state", "initial_state", "law_guess"]

FIT_LAWS: tuple[str, ...] = ("ageing", "slip", "prz", "nagata", "ageing2")
"""State laws of a time-series fit (module docstring)."""

INITIAL_STATES: tuple[str, ...] = ("steady", "free")
"""Initial states of a time-series fit (module docstring)."""

C_MAX = 50.0
"""Upper search bound of Nagata's ``c`` (they report c of about 2 for granite; ours)."""

STATE0_MAX = 20.0
"""Search bound of ``|state0|``: ``b state0`` then spans friction far beyond any remnant."""

Spec = tuple[str, str, bool, float, float]  # ParamSpec's fields: name, unit, log, lo, hi


def law_specs(law: str) -> tuple[Spec, ...]:
    """The parameters ``law`` adds to ``mu0, a, b, dc`` (as :class:`.models.ParamSpec`
    fields)."""
    if law == "nagata":
        return (("c", "", False, 0.0, C_MAX),)
    if law == "ageing2":
        return (("b2", "", True, 1e-6, 1.0), ("dc2", "m", True, 1e-12, 1.0))
    return ()


def initial_specs(initial: str) -> tuple[Spec, ...]:
    """The parameter of the free initial state (module docstring)."""
    return (("state0", "", False, -STATE0_MAX, STATE0_MAX),) if initial == "free" else ()


def rate_state(law: str, values: Mapping[str, float], v0: float, regularized: bool
               ) -> RateState:
    """The friction law of a fit's values (``a``, ``b``, ``dc``, ``mu0`` and the law's own)."""
    two = law == "ageing2"
    return RateState(values["a"], values["b"], values["dc"], values["mu0"], v0,
                     state_law="ageing" if two else law,  # type: ignore[arg-type]
                     b2=values["b2"] if two else 0.0, dc2=values["dc2"] if two else None,
                     regularized=regularized, c=values["c"] if law == "nagata" else 0.0)


def initial_state(initial: str, values: Mapping[str, float], v_first: float
                  ) -> RSFInitial | None:
    """The slider's start for ``initial`` (``None``: steady sliding at ``v_first``)."""
    if initial != "free" or not v_first > 0.0:
        return None
    theta0 = values["dc"] / v_first * math.exp(values["state0"])
    return RSFInitial(v_first, theta0)


def law_guess(law: str, initial: str, guess: Mapping[str, float]) -> dict[str, float]:
    """Starting values of the extra parameters, from a start of ``a, b, dc`` (ours: ``c = 1``
    between the ageing law and Nagata's 2; a second state variable a third of ``b`` at ten
    times ``Dc``; the free state at steady sliding)."""
    out: dict[str, float] = {}
    if law == "nagata":
        out["c"] = 1.0
    if law == "ageing2":
        out["b2"] = max(guess.get("b", 0.01) / 3.0, 1e-5)
        out["dc2"] = 10.0 * guess.get("dc", 1e-5)
    if initial == "free":
        out["state0"] = 0.0
    return out
