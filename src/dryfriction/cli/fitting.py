"""The fit command: measured friction against the trap model or rate-and-state."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

import typer
import typer.core
from rich.table import Table
from rich.text import Text

from ..app.options import OPTIONS
from ..io.files import to_jsonable
from .common import (
    DPI_HELP,
    FIGURE_HELP,
    FORCE_HELP,
    FORMAT_CHOICES,
    FORMAT_HELP,
    app,
    cli_errors,
    compile_notice,
    err,
    lazy_progress_bar,
    one_of,
    out,
    print_whole,
    progress_bar,
    say,
)
from .model import CREEP_HELP
from .record import SEGMENTS_HELP

_FIT = OPTIONS["fit"]


@app.command("fit")
@cli_errors
def fit_command(
    data: Annotated[list[Path], typer.Argument(help="CSV files: t_w,mu_s (static), V,mu_d "
                                               "(steady) or t,v_load,mu (time series); units "
                                               "in the header, e.g. V[um/s]. One file in "
                                               "another format is read as a laboratory "
                                               "record (velocity steps, rsf).")],
    out_dir: Annotated[str, typer.Option("--out", help="Results folder: fit.json, fit.png "
                                          "(written whole or not at all; new, empty, or "
                                          "written by this program before).")],
    model: str | None = typer.Option(_FIT["model"].default, "--model",
                                     metavar=one_of(_FIT["model"].choices),
                                     help="cv (trap model) or rsf (rate-and-state); default "
                                     "chosen by the input: rsf for a laboratory record "
                                     "(--run-cv adds the trap model), cv for the project's "
                                     "CSV files.", show_default=False),
    alpha: float = typer.Option(_FIT["alpha"].default, "--alpha",
                                help="Trap stiffness (cv), dimensionless, fixed."),
    creep: str = typer.Option(_FIT["creep"].default, "--creep",
                              metavar=one_of(_FIT["creep"].choices), help=CREEP_HELP),
    fix: Annotated[list[str] | None, typer.Option(
        "--fix", help="Hold a parameter fixed: --fix t0=0.01 (SI units; repeatable).")] = None,
    v0: float = typer.Option(_FIT["v0"].default, "--v0",
                             help="rsf: reference velocity V0, m/s (for static "
                             "data: the hold tests' sliding velocity; required then)."),
    state_law: str = typer.Option(_FIT["state_law"].default, "--state-law",
                                  metavar=one_of(_FIT["state_law"].choices),
                                  help="rsf: ageing, slip, prz "
                                  "(Perrin-Rice-Zheng), nagata (ageing with a stress-rate "
                                  "term c, fitted) or ageing2 (two state variables: b2, dc2 "
                                  "fitted); record: also auto (every law per step, the least "
                                  "AIC chosen; the comparison in fit.json and the notes)."),
    initial_state: str = typer.Option(_FIT["initial_state"].default, "--initial-state",
                                      metavar=one_of(_FIT["initial_state"].choices),
                                      help="Record: each step's "
                                      "fit starts in steady sliding (steady), from a fitted "
                                      "state ln(theta0 V/Dc) (free), or free only where the "
                                      "step is flagged not_steady_before (auto)."),
    stiffness: str = typer.Option(_FIT["stiffness"].default, "--stiffness",
                                  metavar="[K|inf|fit|slope|record]",
                                  help="rsf time series: machine "
                                  "stiffness per unit normal force: a number (1/m; inf: "
                                  "kinematic, the default for CSV), fit (a free parameter "
                                  "per step), slope (fixed from the loading slope after the "
                                  "change) or record (the default for a record: its one "
                                  "machine, from the steps' free fits and its elastic "
                                  "reloads, then held in every step; each step free where "
                                  "fewer than two estimates exist)."),
    trend: bool = typer.Option(_FIT["trend"].default, "--trend/--no-trend",
                               help="rsf time series: a linear "
                               "trend in load-point displacement (default: on for a record, "
                               "off for CSV)."),
    columns: str = typer.Option(_FIT["columns"].default, "--columns",
                                help="Record: column map, e.g. "
                                "time=Time,disp=LP_disp,friction=Mu."),
    segments: str = typer.Option(_FIT["segments"].default, "--segments",
                                 help="Record: " + SEGMENTS_HELP),
    joint: bool = typer.Option(_FIT["joint"].default, "--joint",
                               help="Record: also fit all steps with one "
                               "a, b, Dc and one stiffness."),
    drive: str = typer.Option(_FIT["drive"].default, "--drive",
                              metavar=one_of(_FIT["drive"].choices),
                              help="Record: what drives the fitted "
                              "machine: measured (default: the record's load-point "
                              "displacement, denoised, its change times placed from it, so "
                              "that the stiffness does not hang on a given change time) or "
                              "program (the idealised piecewise-constant program)."),
    errors: str = typer.Option(_FIT["errors"].default, "--errors",
                               metavar=one_of(_FIT["errors"].choices),
                               help="Record: uncertainties that allow for "
                               "autocorrelated residuals (hac, default) or that assume "
                               "independent noise (white)."),
    run_cv: bool = typer.Option(_FIT["run_cv"].default, "--run-cv",
                                help="Record: also fit the trap model "
                                "(cv) to each step and compare (costly: its estimate is "
                                "printed without this flag)."),
    regularized: bool = typer.Option(_FIT["regularized"].default,
                                     help="rsf: regularised law (holds, kinematic)."),
    traps_per_a0: float | None = typer.Option(_FIT["traps_per_a0"].default, "--traps-per-a0",
                                              help="cv time series: "
                                       "density of the simulated ensemble, traps per a0 "
                                       "(1/a0; accuracy about its inverse; cost grows with "
                                       "it; default 1000, 100 for a record)."),
    direct: float = typer.Option(_FIT["direct"].default, "--direct",
                                 help="cv: fit the direct effect A "
                                 "(dimensionless, 0 <= A <= 1), started from this value; 0: "
                                 "the athermal model. Hold it with --fix direct=A."),
    v_ref: float = typer.Option(_FIT["v_ref"].default, "--v-ref",
                                help="cv with --direct: reference velocity "
                                "of the direct effect, m/s, fixed."),
    profile: bool = typer.Option(_FIT["profile"].default, "--profile/--no-profile",
                                 help="Profile-likelihood "
                                 "intervals and identifiability (for a record: of a, b, Dc "
                                 "per step; default on up to 6 steps, HAC intervals above)."),
    compare: bool = typer.Option(_FIT["compare"].default,
                                 help="Also fit the other model and compare (AIC/BIC)."),
    json_out: bool = typer.Option(False, "--json", help="Print fit.json to standard output."),
    force: bool = typer.Option(_FIT["force"].default, "--force", help=FORCE_HELP),
    fmt: str = typer.Option(_FIT["fmt"].default, "--format", metavar=FORMAT_CHOICES,
                     help=FORMAT_HELP),
    dpi: int = typer.Option(_FIT["dpi"].default, "--dpi", help=DPI_HELP),
    figure: bool = typer.Option(_FIT["figure"].default, "--figure/--no-figure", help=FIGURE_HELP),
) -> None:
    """Fit the trap model (cv) or rate-and-state (rsf) to measured friction; writes fit.json
    (values, uncertainties, correlations, identifiability, goodness of fit, AIC/BIC) and
    fit.png (data, fitted curve, residuals)."""
    from ..app.fitting import fit as run
    from ..io.units import header

    options = dict(model=model, alpha=alpha, creep=creep, fix=fix, v0=v0, state_law=state_law,
                   initial_state=initial_state, stiffness=stiffness, trend=trend,
                   columns=columns, segments=segments, joint=joint, drive=drive, errors=errors,
                   run_cv=run_cv, regularized=regularized, traps_per_a0=traps_per_a0,
                   direct=direct, v_ref=v_ref, profile=profile, compare=compare, force=force,
                   fmt=fmt, dpi=dpi, figure=figure)
    # opened at the first update: a record's fit has bars of its own (``bar``)
    with lazy_progress_bar("fit", unit="evaluations") as update:
        done = run(data, out_dir, progress=update, report=say, on_start=compile_notice,
                   bar=progress_bar, on_program=lambda segs, rec: _print_program(
                       segs, rec, to_stderr=json_out), **options)
    if hasattr(done, "steps"):  # a laboratory record
        from .records import print_record_fit

        print_record_fit(done, json_out=json_out, run_cv=run_cv, fmt=done.fmt,
                         figure=figure)
        return
    result, report = done.result, done.report
    if json_out:
        print(json.dumps(to_jsonable(report), indent=2))
    else:
        words = {"cv": "trap model (cv)", "rsf": "rate-and-state (rsf)"}
        table = Table(title=f"{words.get(done.report.get('model'), 'fit')} fit of "
                            f"{', '.join(str(p) for p in data)}")
        for col in ("parameter", "value", "+-", "95 % interval", "identifiability"):
            table.add_column(col)
        for p in result.parameters:
            iv = p.profile_95 or p.interval_95
            ivs = "" if iv is None else ("[" + ", ".join("open" if x is None else f"{x:.4g}"
                                                          for x in iv) + "]")
            # the +- only where the Wald interval is the one to quote: beside a profile
            # interval it disagrees with ("use profile_95") it would contradict it silently
            # (docs/tutorials/lab-record.md, "Reading the table")
            pm = "" if p.stderr is None or (p.profile_95 is not None
                                            and p.identifiability != "identified") \
                else f"{p.stderr:.2g}"
            cells = (header(p.name, p.unit or "1"), f"{p.value:.6g}", pm, ivs,
                     p.identifiability)
            table.add_row(*(Text(c) for c in cells))  # "[open, 0.2]" is no Rich markup
        print_whole(table)
        for note in result.notes:
            out.print(f"- {note}", highlight=False, soft_wrap=True)
        if "comparison" in report and "verdict" in report["comparison"]:
            out.print(f"comparison: {report['comparison']['verdict']}", highlight=False)
        out.print(f"wrote {out_dir}/" + ", ".join(done.files), highlight=False)
        against = [f.split(":", 1)[1] for f in result.flags if f.startswith("against_model:")]
        if against:  # the last line, where a user looks (as a record's "every step is flagged")
            out.print(f"the data contradict the model ({', '.join(against)}: its trend has "
                      "the sign the model forbids): read the first note before using any "
                      "value", highlight=False, soft_wrap=True)
    if not result.success:
        err.print(f"[bold red]fit did not converge:[/] {result.message}", highlight=False,
                  soft_wrap=True)
        raise typer.Exit(1)


def _print_program(segments: Any, record: Any, *, to_stderr: bool = False) -> None:
    """A record's load program, printed before its fit (the normal load in its own unit):
    whole, whatever the console's width (a pipe's is 80 columns), and on standard error with
    ``--json``, so that standard output stays one JSON document."""
    from ..records import lab

    (err if to_stderr else out).print(lab.segments_table(segments, record.normal_unit),
                                      highlight=False, markup=False, soft_wrap=True)
