"""Every default and allowed value of the workflows (:mod:`dryfriction.app`), declared once, as
data: the library functions take their defaults from here, and the command line its option
defaults (``typer.Option(OPTIONS["fit"]["alpha"].default, "--alpha", ...)``), so that a Python
call and a command line without the option run the same workflow.

A default of ``None`` means "chosen by the workflow from its input", and :attr:`Option.allowed`
says how (``traps_per_a0``: 1000 for the project's CSV files, 100 for a laboratory record).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..theory.model import TRAPS_PER_A0

__all__ = ["Option", "OPTIONS", "FIGURE", "SWEEP", "defaults"]


@dataclass(frozen=True)
class Option:
    """One option of a workflow.

    Attributes
    ----------
    flag : str
        The option as the command line spells it (``--traps-per-a0``): the name every refusal
        uses, from Python as from the shell.
    default : Any
        The value when the option is not given.
    allowed : str
        The allowed values or range, in words (with the unit).
    """

    flag: str
    default: Any
    allowed: str = ""


FIGURE: dict[str, Option] = {
    "fmt": Option("--format", "png", "png, pdf or svg"),
    "dpi": Option("--dpi", None, "72 to 1200 (PNG only; default the style's)"),
    "figure": Option("--figure/--no-figure", True, "draw the figure(s) or not"),
    "force": Option("--force", False, "write beside files not ours (kept)"),
}
"""The options every workflow that writes a results folder shares."""

SWEEP: dict[str, Option] = {
    "scheduler": Option("--scheduler", None, "a running Dask scheduler's address; default a "
                        "local cluster"),
    "workers": Option("--workers", None, "1 to WORKERS_PER_CORE per core; default one per "
                      "core"),
    "yes": Option("--yes", False, "allow grids larger than sweeps.sweep.MAX_POINTS"),
    "connect_timeout": Option("--connect-timeout", 10.0, "> 0 s"),
}
"""The options both sweeps share."""

OPTIONS: dict[str, dict[str, Option]] = {
    "simulate": {**FIGURE},
    "compare": {**FIGURE, "state_law": Option("--state-law", "ageing", "ageing or slip")},
    "reproduce": {k: FIGURE[k] for k in ("fmt", "dpi", "force")},
    "sweep": {**SWEEP, "linear": Option("--linear", False, "linear stability per point "
                                        "instead of simulating stick-slip")},
    "phase-diagram": {**SWEEP, "fmt": FIGURE["fmt"], "dpi": FIGURE["dpi"]},
    "fit": {
        **FIGURE,
        "model": Option("--model", "cv", "cv (trap model) or rsf (rate-and-state)"),
        "alpha": Option("--alpha", 0.13, "ALPHA_MIN <= alpha < 1 (trap stiffness, fixed)"),
        "creep": Option("--creep", "log", "a creep law of dryfriction.theory.creep"),
        "fix": Option("--fix", None, "name=value pairs (SI), CSV files only"),
        "v0": Option("--v0", None, "V_MIN to V_MAX m/s; required for static rsf data"),
        "state_law": Option("--state-law", "ageing", "a fitted law, or auto (record)"),
        "initial_state": Option("--initial-state", "auto", "steady, free or auto (record)"),
        "stiffness": Option("--stiffness", None, "> 0 1/m, inf, fit, slope or record; "
                            "default inf for CSV files, record for a record"),
        "trend": Option("--trend/--no-trend", None, "default on for a record, off for CSV"),
        "columns": Option("--columns", None, "a column map (record)"),
        "segments": Option("--segments", None, "the load program (record)"),
        "joint": Option("--joint", False, "also one a, b, Dc, k for all steps (record)"),
        "drive": Option("--drive", "measured", "measured or program (record)"),
        "errors": Option("--errors", "hac", "hac or white (record)"),
        "run_cv": Option("--run-cv", False, "also fit the trap model per step (record)"),
        "regularized": Option("--regularized", False, "the regularised rsf law"),
        "traps_per_a0": Option("--traps-per-a0", None, ">= TRAPS_PER_A0_MIN; default 1000 "
                               "for CSV files, RECORD_TRAPS_PER_A0 (100) for a record"),
        "direct": Option("--direct", 0.0, "0 <= A <= DIRECT_MAX (start of the fit)"),
        "v_ref": Option("--v-ref", 1e-6, "V_MIN to V_MAX m/s"),
        "profile": Option("--profile/--no-profile", None, "default on, for a record up to "
                          "6 steps"),
        "compare": Option("--compare/--no-compare", True, "also fit the other model (CSV)"),
    },
}
"""Workflow -> option name (the keyword of its function) -> :class:`Option`."""

CSV_TRAPS_PER_A0: float = TRAPS_PER_A0.default
"""``--traps-per-a0`` of a trap-model fit of the project's CSV files when not given: the trap
model's own default (:data:`dryfriction.theory.model.TRAPS_PER_A0`)."""


def defaults(workflow: str) -> dict[str, Any]:
    """The default value of every option of ``workflow`` (a key of :data:`OPTIONS`)."""
    return {k: o.default for k, o in OPTIONS[workflow].items()}
