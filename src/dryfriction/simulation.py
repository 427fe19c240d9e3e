"""One simulator shape for both laws: ``simulate(model, drive, initial, output)``.

A run is one call that composes four frozen objects, validated when made, and returns a
:class:`Result` - the shape diffrax gives ``diffeqsolve(terms, solver, ..., saveat=SaveAt(...))``
and the one :class:`~dryfriction.program.VelocityProgram` already has (shared by both laws)::

    dryfriction.simulate(model, drive, initial, output) -> Result

=======  =========================================  =========================================
part     trap model (``law = "cv"``, reduced)         rate-and-state (``law = "rsf"``, SI)
=======  =========================================  =========================================
model    ``TrapModel``                              ``RateState``
drive    ``VelocityDrive``, ``ForceDrive``,         ``SpringSlider`` (``stiffness = inf``:
         ``SpringDrive``                            the kinematic machine)
initial  ``Initial``: the contact population at     ``RSFInitial``: slip velocity and state
         ``t = 0`` (kind) and where its pairs sit
         (``track``)
output   ``Output``: ``every`` / ``every_slip``,    ``RSFOutput``: ``every`` / ``t_eval``,
         snapshots                                  ``rtol``, ``max_steps``
result   ``SimulationResult``                       ``RSFResult``
=======  =========================================  =========================================

The classes here are what the two laws share: every part names its law (``law``, the
``"cv"`` / ``"rsf"`` of the results' summary) and with it the units its numbers are in
(:data:`LAW_UNITS`). The fields stay law-specific where they must differ: a trap population
is not a state variable, and a solver tolerance means nothing to the trap model's exact
steps. :func:`check_parts` refuses a part of the other law before any work: a trap-model
drive in ``a0/t0`` handed to rate-and-state would otherwise be read in m/s.

The old forms (``simulate(model, track, initial, drive, output)`` and ``simulate_rsf``) warn
with :class:`OldSimulatorFormWarning` for one release (CHANGELOG.md).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Any, ClassVar

from .results import records, to_dataframe
from .validation import Array

__all__ = ["LAW_UNITS", "Drive", "Initial", "OldSimulatorFormWarning", "Output", "Part",
           "Result", "check_parts"]

LAW_UNITS: dict[str, str] = {
    "cv": "reduced units (a0, t0, a0/t0)",
    "rsf": "SI units (m, s, m/s)",
}
"""The units every number of a law's parts and results is in (the trap model's core is
reduced, rate-and-state is SI: docs/model.md, :mod:`dryfriction.theory.units`)."""

_OWNERS = {"cv": "the trap model's", "rsf": "rate-and-state's"}
_MODELS = {"cv": "a TrapModel", "rsf": "a RateState"}


class OldSimulatorFormWarning(DeprecationWarning):
    """An old form of a simulator call: it still works, for one release.

    A ``DeprecationWarning``; its own class so that the test suite can turn exactly this one
    into an error (pyproject.toml) and no internal code path can use an old form unnoticed."""


class Part:
    """Base of the frozen objects a run is made of (its drive, initial state and output)."""

    __slots__ = ()
    law: ClassVar[str]
    """``"cv"`` (trap model, reduced units) or ``"rsf"`` (rate-and-state, SI)."""

    @property
    def units(self) -> str:
        """The units of this part's numbers, in words (:data:`LAW_UNITS`)."""
        return LAW_UNITS[self.law]


class Drive(Part):
    """What moves the slider: a load-point program, a force ramp, a spring."""

    __slots__ = ()


class Initial(Part):
    """The state a run starts from."""

    __slots__ = ()


class Output(Part):
    """What a run records and when."""

    __slots__ = ()


class Result(ABC):
    """What a run returns: the time series and its summary (the schema of
    :mod:`dryfriction.results`, in the units of :attr:`law`).

    Attributes
    ----------
    t, x, v, mu : ndarray
        Time, slider position, slider velocity and friction coefficient, one entry a sample
        (units: :data:`LAW_UNITS` of :attr:`law`; ``summary()["units"]`` names each column's).
    """

    __slots__ = ()
    law: ClassVar[str]
    t: Array
    x: Array
    v: Array
    mu: Array

    @property
    @abstractmethod
    def partial(self) -> bool:
        """The run was interrupted: the samples stop early."""

    @abstractmethod
    def columns(self) -> dict[str, Array]:
        """The time series as ``{column: array}``, starting with ``t, x, v, mu``."""

    @abstractmethod
    def summary(self) -> dict[str, Any]:
        """The shared summary (:func:`dryfriction.results.summarize`), then the law's own."""

    def to_records(self) -> Any:
        """The time series (:meth:`columns`) as a NumPy structured array, a record a sample."""
        return records(self.columns())

    def to_dataframe(self) -> Any:
        """A ``pandas.DataFrame`` of :meth:`columns` (needs pandas, not a dependency)."""
        return to_dataframe(self.columns())


def check_parts(law: str, **parts: Any) -> None:
    """Refuse a part of the other law, in one line naming the parameter and both units.

    Parameters
    ----------
    law : {"cv", "rsf"}
        The model's law.
    **parts
        ``drive=..., initial=..., output=...``: a part that is no :class:`Part` is left to
        the law's own check (which names the classes it allows).

    Raises
    ------
    ValueError
        A part of the other law: its numbers are in the other units.
    """
    for name, part in parts.items():
        other = getattr(part, "law", None) if isinstance(part, Part) else None
        if other is not None and other != law:
            raise ValueError(
                f"{name} = {type(part).__name__}(...) is {_OWNERS.get(other, other)}, in "
                f"{LAW_UNITS.get(other, other)}: not allowed with {_MODELS[law]}, whose {name} "
                f"is in {LAW_UNITS[law]}")
