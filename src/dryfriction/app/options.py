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

from ..rsf.law import RATE_STATE_PARAMETERS as _RSF
from ..theory.model import TRAP_PARAMETERS, TRAPS_PER_A0

__all__ = ["Option", "OPTIONS", "FIGURE", "SWEEP", "defaults"]

_TRAP = TRAP_PARAMETERS
"""The trap model's own declared defaults (:data:`dryfriction.theory.model.TRAP_PARAMETERS`):
an option that sets one of its parameters takes the default from there, not a copy."""


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
    choices : tuple of str
        The values of an option that takes one of a few words (shown in ``--help``; the
        library's own tuple is the reference, ``tests/cli/test_help.py`` keeps them equal).
    """

    flag: str
    default: Any
    allowed: str = ""
    choices: tuple[str, ...] = ()


FIGURE: dict[str, Option] = {
    "fmt": Option("--format", "png", "png, pdf or svg", ("png", "pdf", "svg")),
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

_THEORY: dict[str, Option] = {
    "alpha": Option("--alpha", _TRAP["alpha"].default, "ALPHA_MIN <= alpha < 1"),
    "creep": Option("--creep", _TRAP["creep"].default, "log or eyring-nabarro",
                    ("log", "eyring-nabarro")),
    "direct": Option("--direct", _TRAP["direct"].default, "0 <= A <= DIRECT_MAX"),
    # --u-ref, reduced as --u is: --v-ref is m/s (fit); the old --v-ref here warns
    "v_ref": Option("--u-ref", _TRAP["v_ref"].default, "U_MIN to U_MAX a0/t0"),
}
"""The trap model's options of the closed-form workflows (``static``, ``steady``,
``stability``), defaults from the model's own table."""

_SI: dict[str, Option] = {
    "a0": Option("--a0", None, "> 0 m; with --t0, velocities in m/s"),
    "t0": Option("--t0", None, "> 0 s; with it, times in seconds"),
    "mu_el": Option("--mu-el", None, "0 < mu_el <= 10; with it, friction is F/W"),
}
"""The SI scales of the closed-form workflows (none: reduced units)."""

OPTIONS: dict[str, dict[str, Option]] = {
    "simulate": {**FIGURE},
    "compare": {**FIGURE, "state_law": Option("--state-law", "ageing", "ageing or slip",
                                              ("ageing", "slip"))},
    "reproduce": {k: FIGURE[k] for k in ("fmt", "dpi", "force")},
    "sweep": {**SWEEP, "linear": Option("--linear", False, "linear stability per point "
                                        "instead of simulating stick-slip")},
    "phase-diagram": {**SWEEP, "fmt": FIGURE["fmt"], "dpi": FIGURE["dpi"]},
    "fit": {
        **FIGURE,
        "model": Option("--model", None, "cv (trap model) or rsf (rate-and-state); default "
                        "chosen by the input: rsf for a laboratory record (--run-cv adds the "
                        "trap model), cv for the project's CSV files", ("cv", "rsf")),
        "alpha": Option("--alpha", _TRAP["alpha"].default,
                        "ALPHA_MIN <= alpha < 1 (trap stiffness, fixed)"),
        "creep": Option("--creep", _TRAP["creep"].default,
                        "a creep law of dryfriction.theory.creep", ("log", "eyring-nabarro")),
        "fix": Option("--fix", None, "name=value pairs (SI), CSV files only"),
        "v0": Option("--v0", None, "V_MIN to V_MAX m/s; required for static rsf data"),
        "state_law": Option("--state-law", "ageing", "a fitted law, or auto (record)",
                            ("ageing", "slip", "prz", "nagata", "ageing2", "auto")),
        "initial_state": Option("--initial-state", "auto", "steady, free or auto (record)",
                                ("auto", "steady", "free")),
        "stiffness": Option("--stiffness", None, "> 0 1/m, inf, fit, slope or record; "
                            "default inf for CSV files, record for a record"),
        "trend": Option("--trend/--no-trend", None, "default on for a record, off for CSV"),
        "columns": Option("--columns", None, "a column map (record)"),
        "segments": Option("--segments", None, "the load program (record)"),
        "joint": Option("--joint", False, "also one a, b, Dc, k for all steps (record)"),
        "drive": Option("--drive", "measured", "measured or program (record)",
                        ("measured", "program")),
        "errors": Option("--errors", "hac", "hac or white (record)", ("hac", "white")),
        "run_cv": Option("--run-cv", False, "also fit the trap model per step (record)"),
        "regularized": Option("--regularized", False, "the regularised rsf law"),
        "traps_per_a0": Option("--traps-per-a0", None, ">= TRAPS_PER_A0_MIN; default 1000 "
                               "for CSV files, RECORD_TRAPS_PER_A0 (100) for a record"),
        "direct": Option("--direct", _TRAP["direct"].default,
                         "0 <= A <= DIRECT_MAX (start of the fit)"),
        "v_ref": Option("--v-ref", 1e-6, "V_MIN to V_MAX m/s"),
        "profile": Option("--profile/--no-profile", None, "default on, for a record up to "
                          "6 steps"),
        "compare": Option("--compare/--no-compare", True, "also fit the other model (CSV)"),
    },
    "trap": {"alpha": Option("--alpha", _TRAP["alpha"].default, "ALPHA_MIN <= alpha "
                             "(>= 1: no pinning)")},
    "static": {**_THEORY, "load": Option("--load", 0.0, "-1 < f_w < 1 (F_el)"),
               "hold": Option("--hold", "position", "position or force",
                              ("position", "force")),
               "t0": _SI["t0"], "mu_el": _SI["mu_el"],
               "pull_velocity": Option("--pull-velocity", None, "> 0 a0/t0; required with "
                                       "--direct > 0")},
    "steady": {**_THEORY, **_SI},
    # --M and --eta, reduced (as --u, --T): --mass and --damping are SI in rsf; the old
    # --mass and --damping here warn
    "stability": {**_THEORY, "mass": Option("--M", 0.0, "0 to LOAD_MAX F_el t0^2/a0"),
                  "damping": Option("--eta", 0.0, "0 to LOAD_MAX F_el t0/a0")},
    "rsf": {
        **FIGURE,
        "case": Option("--case", "step", "step, shs or stick-slip",
                       ("step", "shs", "stick-slip")),
        "a": Option("--a", 0.005, "> 0"), "b": Option("--b", 0.01, ">= 0"),
        "dc": Option("--dc", 1e-5, "> 0 m"), "mu0": Option("--mu0", 0.6, "-10 to 10"),
        "v0": Option("--v0", 1e-6, "> 0 m/s"),
        "state_law": Option("--state-law", _RSF["state_law"].default, "ageing or slip",
                            ("ageing", "slip")),
        "regularized": Option("--regularized", _RSF["regularized"].default,
                              "the regularised asinh law"),
        "stiffness": Option("--stiffness", 1e3, "> 0 1/m, or inf"),
        "damping": Option("--damping", 0.0, "0 to LOAD_MAX s/m"),
        "mass": Option("--mass", 0.0, "0 to LOAD_MAX s^2/m"),
        "v1": Option("--v1", 1e-6, "0 or V_MIN <= |v1| <= V_MAX m/s"),
        "v2": Option("--v2", 1e-5, "0 or V_MIN <= |v2| <= V_MAX m/s"),
        "t1": Option("--t1", 10.0, "0 < t1 <= LOAD_MAX s"),
        "t2": Option("--t2", None, "0 < t2 <= LOAD_MAX s; default 30 s for step, past the "
                     "reload peak for shs"),
        # --hold-time, s: --hold is static's position|force; the old --hold here warns
        "hold": Option("--hold-time", 100.0, "0 < hold <= LOAD_MAX s"),
        "v_init": Option("--v-init", None, "0 < v_init <= V_MAX m/s; default v1 (1.01 v1 "
                         "for stick-slip)"),
        "rtol": Option("--rtol", 1e-7, "1e-13 <= rtol <= 0.01"),
    },
    "record": {"columns": Option("--columns", None, "a column map"),
               "segments": Option("--segments", None, "the load program; default detected"),
               "out": Option("--out", None, "a folder for record.png and segments.csv"),
               "force": FIGURE["force"]},
    "bifurcation": {"check": Option("--check", False, "check each nature by simulation "
                                    "(at most MAX_CHECKED velocities)"),
                    "figure": FIGURE["figure"], "force": FIGURE["force"]},
}
"""Workflow -> option name (the keyword of its function) -> :class:`Option`."""

CSV_TRAPS_PER_A0: float = TRAPS_PER_A0.default
"""``--traps-per-a0`` of a trap-model fit of the project's CSV files when not given: the trap
model's own default (:data:`dryfriction.theory.model.TRAPS_PER_A0`)."""


def defaults(workflow: str) -> dict[str, Any]:
    """The default value of every option of ``workflow`` (a key of :data:`OPTIONS`)."""
    return {k: o.default for k, o in OPTIONS[workflow].items()}
