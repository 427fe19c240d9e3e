"""What a workflow of :mod:`dryfriction.app` returns: the results folder, the files it holds,
the numbers written and what the command line prints from them."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

__all__ = ["RunOutcome", "FitOutcome", "RecordFitOutcome"]


@dataclass
class RunOutcome:
    """A run written to a results folder (``simulate``, ``compare``, ``reproduce``).

    Attributes
    ----------
    out : Path
        The results folder.
    files : list of str
        The files written into it, by name.
    summary : dict
        What summary.json (compare.json for ``compare``) holds.
    result : Any
        The library's result object (the run, the comparison); ``None`` for ``reproduce``.
    notes : list of str
        Lines for the user (a snapshot not reached, a reload that ended before its peak).
    partial : bool
        The run was interrupted and the samples so far were written (``"partial": true``).
    units : str
        ``"reduced"`` (the trap model: a0, t0, F_el) or ``"SI"`` (rate-and-state).
    """

    out: Path
    files: list[str]
    summary: dict[str, Any]
    result: Any = None
    notes: list[str] = field(default_factory=list)
    partial: bool = False
    units: str = "reduced"


@dataclass
class FitOutcome:
    """A fit of the project's CSV files (``fit DATA.csv ...``).

    Attributes
    ----------
    out, files : as :class:`RunOutcome`
    report : dict
        What fit.json holds (the fit, and ``comparison`` with the other model).
    result : dryfriction.fit.FitResult
        The fit; ``result.success`` False: it did not converge (the command exits 1).
    datasets : list
        The data read.
    """

    out: Path
    files: list[str]
    report: dict[str, Any]
    result: Any
    datasets: list[Any]

    @property
    def success(self) -> bool:
        return bool(self.result.success)


@dataclass
class RecordFitOutcome:
    """A fit of one laboratory record, step by step (``fit RECORD.txt ...``).

    Attributes
    ----------
    out, files : as :class:`RunOutcome`
    report : dict
        What fit.json holds.
    steps : dryfriction.fit.steps.StepsResult
        The steps' fits (``steps.rows``: steps.csv).
    record, segments, detection : the record read, its load program, the step finder's
        result (``None`` where ``segments`` was given).
    apparatus_note : str or None
        A note on the record's units or apparatus, said before the fit.
    fmt : str
        The figures' format.
    """

    out: Path
    files: list[str]
    report: dict[str, Any]
    steps: Any
    record: Any
    segments: list[Any]
    detection: Any = None
    apparatus_note: str | None = None
    fmt: str = "png"

    @property
    def success(self) -> bool:
        return bool(self.steps.success)
