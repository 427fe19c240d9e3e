"""The trap model as one object: its parameters, their defaults and allowed ranges.

Every default and every range of the model's parameters is declared once, as data, in
:data:`TRAP_PARAMETERS` (and :data:`TRAPS_PER_A0` for the track density, which belongs to the
track, not to the physics of one trap), in the manner of scikit-learn's declared parameter
constraints. :class:`TrapModel` reads its defaults from there and checks every field against it
once, at construction; the theory functions, simulators, analyses and fits take the object and
check nothing again. Reduced units: velocities in ``a0/t0``, friction in ``F_el`` (eq. 12).
"""

from __future__ import annotations

import dataclasses
import functools
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

from ..validation import (
    ALPHA_MIN,
    DIRECT_MAX,
    EPS_MAX,
    FRICTION_MAX,
    U_MAX,
    U_MIN,
    Parameter,
    check_direct,
    declared,
)
from .creep import CREEP_LAWS, CreepLaw, creep_law
from .trap import Trap

__all__ = ["OldTheoryFormWarning", "Parameter", "TRAP_PARAMETERS", "TRAPS_PER_A0",
           "TRAPS_PER_A0_COARSE", "TrapModel", "takes_model"]


TRAP_PARAMETERS: dict[str, Parameter] = {p.name: p for p in (
    Parameter("alpha", 0.13, ALPHA_MIN, 1.0, hi_open=True,
              meaning="reduced trap stiffness kappa a^2/(6 Phi0) (0.13 in the paper; >= 1: no "
                      "pinning, no friction)"),
    Parameter("eps", 0.0, 0.0, EPS_MAX,
              meaning="creep parameter S/Y (0: no ageing; S < Y)"),
    Parameter("creep", "log", choices=CREEP_LAWS,
              meaning="ageing law: eq. 17 (log) or eqs. 15-16 (eyring-nabarro)"),
    Parameter("mu_el", 1.0, 0.0, FRICTION_MAX, lo_open=True,
              meaning="friction coefficient of the purely elastic model, F_el/N"),
    Parameter("direct", 0.0, 0.0, DIRECT_MAX,
              meaning="direct-effect coefficient A (theory/direct.py; 0: the athermal model)"),
    Parameter("v_ref", 1.0, U_MIN, U_MAX,
              meaning="reference velocity of the junction rheology, a0/t0"),
)}
"""The trap model's parameters, in :class:`TrapModel`'s field order."""

TRAPS_PER_A0 = Parameter(
    "traps_per_a0", 1000.0, 1e-6,
    meaning="density of asperity pairs per a0 of track (a sparser track has no pair within any "
            "run's reach, and its spacing overflows the index arithmetic)")
"""The track density: its one default (1000 pairs per ``a0``: the fits' and the protocol
files' value) and its one minimum, for every route that builds a track."""

TRAPS_PER_A0_COARSE: float = 100.0
"""The coarse track of the routes that run the model many times (a record's step fit, the
stick-slip and bifurcation checks), named here so that no signature carries its own number:
on the shared sepiolite step its rms difference from a 1000-trap track was 1.0e-3 with
``A = 0`` and 2.8e-4 with ``A = 0.03``, below the record's steady noise 1.5e-3
(:mod:`dryfriction.fit.cvsteps`)."""


def _default(name: str) -> Any:
    return declared(TRAP_PARAMETERS, name)


@dataclass(frozen=True)
class TrapModel:
    """Physical parameters of the trap model, checked once (:data:`TRAP_PARAMETERS`).

    Parameters
    ----------
    alpha : float
        Reduced trap stiffness ``kappa a^2 / (6 Phi0)``, ``0 < alpha < 1`` (0.13 in the paper).
    eps : float
        Creep parameter ``S/Y``, ``0 <= eps <= 1`` (0: no ageing).
    creep : {"log", "eyring-nabarro"}
        Ageing law (eq. 17 or eqs. 15-16).
    mu_el : float
        Friction coefficient of the purely elastic model, ``F_el / N``: the reported
        ``mu = mu_el F/F_el``. ``0 < mu_el <= FRICTION_MAX`` (10), default 1.
    direct : float
        Direct-effect coefficient ``A``, ``0 <= A <= 1`` (:mod:`dryfriction.theory.direct`):
        the friction force is ``g(V) x`` the population's force, ``V`` the slider's present
        velocity (ours: the trap dynamics are unchanged). 0: the athermal model.
    v_ref : float
        Reference velocity of the junction rheology, ``a0/t0``, ``> 0``.
    """

    alpha: float = _default("alpha")
    eps: float = _default("eps")
    creep: str = _default("creep")
    mu_el: float = _default("mu_el")
    direct: float = _default("direct")
    v_ref: float = _default("v_ref")

    def __post_init__(self) -> None:
        for name in ("alpha", "eps", "creep", "mu_el"):
            object.__setattr__(self, name, TRAP_PARAMETERS[name].check(getattr(self, name)))
        # the one check of the direct effect in the package: every route takes this object
        direct, v_ref = check_direct(self.direct, self.v_ref)
        object.__setattr__(self, "direct", direct)
        object.__setattr__(self, "v_ref", v_ref)

    @property
    def trap(self) -> Trap:
        """The single trap of stiffness ``alpha`` (eqs. 20-23)."""
        return Trap(self.alpha)

    @property
    def law(self) -> CreepLaw:
        """The creep law ``a_r(T)`` at this ``eps`` (eq. 17 or eqs. 15-16)."""
        return creep_law(self.creep, self.eps)

    @property
    def athermal(self) -> TrapModel:
        """The same model without the direct effect (``direct = 0``)."""
        return dataclasses.replace(self, direct=0.0)

    def replace(self, **changes: Any) -> TrapModel:
        """A copy with ``changes`` (checked like a new model)."""
        return dataclasses.replace(self, **changes)


# ---------------------------------------------------------------- the old loose forms

class OldTheoryFormWarning(FutureWarning):
    """A theory, analysis or fit function called in its old form, with the trap model's
    parameters loose (``steady_friction(u, eps, alpha, creep, direct, v_ref)``) instead of a
    :class:`TrapModel` first. The old form still works, for one release
    (CHANGELOG.md).

    A ``FutureWarning`` (shown to every user, not only to developers); its own class so that the
    test suite turns exactly this one into an error (pyproject.toml): no internal code path may
    use an old form unnoticed."""


_F = TypeVar("_F", bound=Callable[..., Any])


def takes_model(old: Callable[..., Any], old_form: str, new_form: str) -> Callable[[_F], _F]:
    """Decorate a function whose first argument is a :class:`TrapModel` so that its old loose
    form keeps working for one release.

    A call whose first argument (or keyword ``model``) is a :class:`TrapModel` goes to the
    decorated function; any other call is the old form: it warns
    (:class:`OldTheoryFormWarning`, naming ``old_form`` and ``new_form``) and is passed, as
    given, to ``old``, the loose implementation (so the old form computes exactly what it
    did: no mapping of its arguments that could swap two of them)."""

    def wrap(new: _F) -> _F:
        @functools.wraps(new)
        def dispatch(*args: Any, **kwargs: Any) -> Any:
            if (args and isinstance(args[0], TrapModel)) or "model" in kwargs:
                return new(*args, **kwargs)
            warnings.warn(f"{old_form} is the old form (one more release): use {new_form}, "
                          "with a dryfriction.TrapModel", OldTheoryFormWarning, stacklevel=2)
            return old(*args, **kwargs)

        return dispatch  # type: ignore[return-value]

    return wrap
