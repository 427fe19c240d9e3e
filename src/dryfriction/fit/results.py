"""What a fit returns: :class:`ParameterEstimate` per parameter and the whole
:class:`FitResult` (everything that goes into ``fit.json``)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..records.data import Dataset
from ..results import records, to_dataframe
from ..validation import Array
from .models import Model

__all__ = ["ParameterEstimate", "FitResult"]


@dataclass(frozen=True)
class ParameterEstimate:
    """One parameter of a fit.

    Attributes
    ----------
    name, unit : str
    value : float
        Best-fit value (or the fixed value). Where ``identifiability`` is not "identified" it is
        one point of a flat valley and means little: read ``profile_95``.
    fixed : bool
        Held fixed by the user.
    stderr : float or None
        Standard error from the Jacobian (delta method for log parameters); ``None`` when the
        parameter is fixed, not identified or at a bound. Quote it only where
        ``identifiability`` is "identified"; where it says "use profile_95", the profile
        interval is the one to quote (the table then prints no ``+-``).
    interval_95 : tuple or None
        Wald 95 % interval (``theta +- q se`` in the fitted variable, mapped back; ``q`` the
        normal 97.5 % quantile with given uncertainties, Student t with ``n - p`` otherwise).
    profile_95 : tuple or None
        95 % profile-likelihood interval; ``None`` on a side the data do not bound within the
        search range (then ``search_bounds`` says how far it was searched).
    identifiability : str
        "identified", "identified (nonlinear: use profile_95)", "bounded above only",
        "bounded below only", "not identified", "poorly determined (Jacobian; no profile)",
        "at lower bound (<bound> <unit>)" / "at upper bound (...)" (the value is its search
        bound: no error bar), or "fixed". A profile limit reached while another parameter
        sat on its search bound counts as open (the note quotes it).
    note : str
        A sentence saying the same in words.
    """

    name: str
    unit: str
    value: float
    fixed: bool = False
    stderr: float | None = None
    interval_95: tuple[float, float] | None = None
    profile_95: tuple[float | None, float | None] | None = None
    search_bounds: tuple[float, float] | None = None
    identifiability: str = "identified"
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)

    def row(self) -> dict[str, Any]:
        """One flat row of the parameter table (intervals split into ``_lo``/``_hi``; a bound
        the data do not give, or a missing error, is ``None``)."""
        wald = self.interval_95 or (None, None)
        prof = self.profile_95 or (None, None)
        return {
            "name": self.name, "unit": self.unit, "value": self.value, "fixed": self.fixed,
            "stderr": self.stderr, "interval_95_lo": wald[0], "interval_95_hi": wald[1],
            "profile_95_lo": prof[0], "profile_95_hi": prof[1],
            "identifiability": self.identifiability,
        }


@dataclass(frozen=True)
class FitResult:
    """The outcome of :func:`fit` (every field but ``theta`` and ``jacobian`` is also in
    :meth:`to_dict` / ``fit.json``).

    ``success`` is False when the optimiser did not converge (``message`` says why) or a
    parameter sits on its search bound; the values are then not to be trusted.

    ``flags`` (the words of a record's ``flags`` column, where they apply):
    ``against_model:<source>`` (the data's own trend has the sign the model forbids, e.g.
    static friction falling with hold time: the per-data-set ``trend`` in
    ``per_dataset``), ``at_bound:<name>`` (the value is its search bound),
    ``not_identified:<name>`` (bounded on one side only, or not at all); the notes say why.

    ``theta`` and ``jacobian``: the free parameters (``free``, in the fit's internal
    variables) at the optimum and the central-difference Jacobian of the residuals there, as
    the fit computed them for its covariance (``None`` where the profiles computed it, or
    nothing is free); for a caller that needs the same Jacobian again
    (:func:`.steps.step_covariance`).
    """

    model: str
    options: dict[str, Any]
    parameters: tuple[ParameterEstimate, ...]
    free: tuple[str, ...]
    correlation: Array
    derived: dict[str, dict[str, Any]]
    success: bool
    status: int
    message: str
    nfev: int
    starts: tuple[dict[str, Any], ...]
    sigma_given: bool
    goodness: dict[str, Any]
    per_dataset: tuple[dict[str, Any], ...]
    information: dict[str, float]
    consistency: dict[str, Any] | None
    notes: tuple[str, ...]
    sources: tuple[str, ...]
    fitted_model: Model = field(repr=False)
    flags: tuple[str, ...] = ()
    theta: Array | None = field(default=None, repr=False, compare=False)
    jacobian: Array | None = field(default=None, repr=False, compare=False)

    @property
    def values(self) -> dict[str, float]:
        """Best-fit (and fixed) values by name."""
        return {p.name: p.value for p in self.parameters}

    def __getitem__(self, name: str) -> ParameterEstimate:
        for p in self.parameters:
            if p.name == name:
                return p
        raise KeyError(name)

    def predict(self, data: Dataset, x: Array | None = None) -> Array:
        """The fitted model at the data's abscissae (or at ``x``, not for time series)."""
        return self.fitted_model.predict(self.values, data, x)

    def to_records(self) -> np.ndarray:
        """The parameter table as a NumPy structured array, one record per parameter.

        Fields: ``name, unit, value, fixed, stderr, interval_95_lo, interval_95_hi,
        profile_95_lo, profile_95_hi, identifiability``; a missing error or interval bound is NaN.
        """
        return records([p.row() for p in self.parameters])

    def to_dataframe(self) -> Any:
        """The parameter table of :meth:`to_records` as a ``pandas.DataFrame`` indexed by
        ``name`` (needs pandas, not a dependency)."""
        return to_dataframe(self.to_records()).set_index("name")

    def to_dict(self) -> dict[str, Any]:
        return {
            "model": self.model,
            "options": self.options,
            "success": self.success,
            "status": self.status,
            "message": self.message,
            "nfev": self.nfev,
            "parameters": {p.name: {k: v for k, v in p.to_dict().items() if k != "name"}
                           for p in self.parameters},
            "correlation": {"names": list(self.free), "matrix": self.correlation},
            "derived": self.derived,
            "uncertainties_given": self.sigma_given,
            "goodness_of_fit": self.goodness,
            "per_dataset": list(self.per_dataset),
            "information_criteria": self.information,
            "consistency": self.consistency,
            "identifiability_notes": list(self.notes),
            "flags": list(self.flags),
            "data_files": list(self.sources),
            "starts": list(self.starts),
        }

