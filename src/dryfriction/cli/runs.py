"""Commands that run a history and write a results folder: reproduce, rsf, simulate,
compare (parse, call one workflow of :mod:`dryfriction.app`, print)."""

from __future__ import annotations

from typing import Annotated, Any

import typer
import typer.core

from ..app.options import OPTIONS
from .common import (
    DPI_HELP,
    FIGURE_HELP,
    FORCE_HELP,
    FORMAT_CHOICES,
    FORMAT_HELP,
    app,
    cli_errors,
    compile_notice,
    emit,
    err,
    lazy_progress_bar,
    many,
    one_of,
    out,
    progress_bar,
    renamed,
    say,
    say_interrupted,
)
from .painter import draw_figure

_REP, _SIM, _CMP = OPTIONS["reproduce"], OPTIONS["simulate"], OPTIONS["compare"]
_RSF = OPTIONS["rsf"]
_STDOUT = out  # the console, for compare, whose --out parameter is named out


@app.command(cls=many())
@cli_errors
def reproduce(
    out_dir: Annotated[str, typer.Option("--out", help="Results folder: new, empty, or one "
                                         "this program wrote before.")],
    force: bool = typer.Option(_REP["force"].default, "--force", help=FORCE_HELP),
    fmt: str = typer.Option(_REP["fmt"].default, "--format", metavar=FORMAT_CHOICES,
                     help=FORMAT_HELP),
    dpi: int = typer.Option(_REP["dpi"].default, "--dpi", help=DPI_HELP),
) -> None:
    """The paper's six figures, three extra figures, the data behind them (CSV), summary.json
    and report.html."""
    from ..app.runs import reproduce as run

    with progress_bar("reproduce", unit="steps") as update:
        done = run(out_dir, force=force, fmt=fmt, dpi=dpi, progress=update, report=say)
    # every file it wrote, in words a reader of the paper knows
    out.print(f"wrote {out_dir}/: {', '.join(done.files)}", highlight=False, soft_wrap=True)
    out.print("fig1-6: the paper's figures; extra_*: loaded waiting, the two creep laws "
              "compared, and the Dieterich constant C over velocity; report.html shows them "
              "all with the key numbers (summary.json)", highlight=False, soft_wrap=True)


@app.command()
@cli_errors
def rsf(
    case: str = typer.Option(_RSF["case"].default, metavar=one_of(_RSF["case"].choices),
                             help="step (v1 for t1, then v2 for t2), shs "
                             "(slide-hold-slide: v1 for t1, a hold of --hold-time, v1 for t2) "
                             "or stick-slip (v1 for t1)."),
    a: float = typer.Option(_RSF["a"].default, help="Direct effect a, dimensionless, > 0."),
    b: float = typer.Option(_RSF["b"].default, help="Evolution effect b, dimensionless, >= 0."),
    dc: float = typer.Option(_RSF["dc"].default, help="Characteristic slip Dc, m, > 0."),
    mu0: float = typer.Option(_RSF["mu0"].default, help="Reference friction at V0, dimensionless, "
                              "-10 to 10."),
    v0: float = typer.Option(_RSF["v0"].default, help="Reference velocity V0, m/s, > 0."),
    state_law: str = typer.Option(_RSF["state_law"].default,
                                  metavar=one_of(_RSF["state_law"].choices),
                                  help="ageing (Dieterich) or slip (Ruina)."),
    regularized: bool = typer.Option(_RSF["regularized"].default, help="Regularised asinh law "
                                     "(needed for holds with --stiffness inf)."),
    stiffness: float = typer.Option(_RSF["stiffness"].default, help="Spring stiffness k per "
                                    "unit normal force, 1/m, > 0; inf for a kinematic "
                                    "machine."),
    damping: float = typer.Option(_RSF["damping"].default, help="Radiation damping eta/sigma, "
                                  "s/m, >= 0."),
    mass: float = typer.Option(_RSF["mass"].default, help="Mass per unit normal force, s^2/m, "
                               ">= 0."),
    v1: float = typer.Option(_RSF["v1"].default, help="Load velocity of the first segment, "
                             "m/s."),
    v2: float = typer.Option(_RSF["v2"].default, help="Load velocity after the step (case "
                             "step), m/s."),
    t1: float = typer.Option(_RSF["t1"].default, help="Duration of the first segment, s."),
    t2: float = typer.Option(_RSF["t2"].default, help="Duration of the last segment, s "
                             "(default: 30 for step; for shs long enough to pass the reload "
                             "peak and slide 10 Dc beyond)."),
    hold: float = typer.Option(_RSF["hold"].default, "--hold-time",
                               help="Hold time (case shs), s, > 0 (was --hold, the name "
                               "static gives its position|force choice)."),
    hold_old: float | None = typer.Option(None, "--hold", hidden=True,
                                          help="Deprecated: --hold-time."),
    v_init: float = typer.Option(_RSF["v_init"].default, help="Initial slip velocity, m/s, "
                                 "with the state at steady state for v_init (default v1; "
                                 "1.01 v1 for stick-slip, since exact steady state never "
                                 "leaves)."),
    rtol: float = typer.Option(_RSF["rtol"].default, help="Local error tolerance, dimensionless "
                               "(relative in V and theta)."),
    out_dir: str = typer.Option(None, "--out", help="Write series.csv, summary.json and "
                                "rsf.png into this folder (whole or not at all; new, empty, or "
                                "written by this program before)."),
    force: bool = typer.Option(_RSF["force"].default, "--force", help=FORCE_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
    fmt: str = typer.Option(_RSF["fmt"].default, "--format", metavar=FORMAT_CHOICES,
                     help=FORMAT_HELP),
    dpi: int = typer.Option(_RSF["dpi"].default, "--dpi", help=DPI_HELP),
    figure: bool = typer.Option(_RSF["figure"].default, "--figure/--no-figure",
                                help=FIGURE_HELP),
) -> None:
    """Rate-and-state friction (SI units) through a velocity step, slide-hold-slide or
    stick-slip, on a spring with optional radiation damping and inertia."""
    from ..app.ratestate import rsf as run

    hold = renamed("--hold", "--hold-time", "seconds; --hold is position|force in static",
                   hold_old, hold, _RSF["hold"].default)
    done = run(case=case, a=a, b=b, dc=dc, mu0=mu0, v0=v0, state_law=state_law,
               regularized=regularized, stiffness=stiffness, damping=damping, mass=mass,
               v1=v1, v2=v2, t1=t1, t2=t2, hold=hold, v_init=v_init, rtol=rtol, out=out_dir,
               force=force, fmt=fmt, dpi=dpi, figure=figure, report=say, draw=draw_figure,
               on_start=lambda: compile_notice(rsf=True))
    summary = done.summary
    brief = {k: v for k, v in summary.items() if not isinstance(v, dict)}
    emit(summary if json_out else brief, json_out, f"rate-and-state, {case}",
         summary["units"])
    for note in done.notes:
        say(note)


@app.command()
@cli_errors
def simulate(
    protocol: str = typer.Argument(..., help="Protocol file (TOML), see dryfriction.io.protocol."),
    out: str = typer.Option(..., "--out", help="Results folder (written whole or not at all; "
                            "new, empty, or written by this program before)."),
    json_out: bool = typer.Option(False, "--json", help="Print the summary as JSON."),
    force: bool = typer.Option(_SIM["force"].default, "--force", help=FORCE_HELP),
    fmt: str = typer.Option(_SIM["fmt"].default, "--format", metavar=FORMAT_CHOICES,
                     help=FORMAT_HELP),
    dpi: int = typer.Option(_SIM["dpi"].default, "--dpi", help=DPI_HELP),
    figure: bool = typer.Option(_SIM["figure"].default, "--figure/--no-figure",
                                help=FIGURE_HELP),
) -> None:
    """Run a protocol file (see dryfriction model, section 6): the trap model's ensemble
    (reduced units), or rate-and-state where the file says model.law = "rsf" (SI units);
    writes timeseries.csv, summary.json and timeseries.png.

    Ctrl-C stops a trap-model run and writes the samples so far as a complete result marked
    "partial": true in summary.json (exit code 130); an interrupt while writing leaves
    nothing.
    """
    from ..app.runs import simulate as run

    def on_start(proto: Any) -> None:
        compile_notice(rsf=type(proto).__name__ == "RSFProtocol")

    with lazy_progress_bar("simulate", 100.0, unit="%") as update:
        done = run(protocol, out, force=force, fmt=fmt, dpi=dpi, figure=figure,
                   progress=update, report=say, draw=draw_figure, on_start=on_start)
    title = (f"simulate {protocol} -> {out}" + (" (rate-and-state, SI: t s, x m, v m/s, "
                                                 "theta s)" if done.units == "SI" else ""))
    brief = {k: v for k, v in done.summary.items() if not isinstance(v, dict)}
    emit(done.summary if json_out else brief, json_out, title, done.summary["units"])
    for note in done.notes:
        say(note)
    if done.partial:
        say_interrupted("partial result written")
        raise typer.Exit(130)


@app.command()
@cli_errors
def compare(
    protocol: str = typer.Argument(..., help="Trap-model protocol file (TOML) with a velocity "
                                   "drive."),
    out: str = typer.Option(..., "--out", help="Results folder: compare.png, compare.json "
                            "(written whole or not at all)."),
    state_law: str = typer.Option(_CMP["state_law"].default, "--state-law",
                                  metavar=one_of(_CMP["state_law"].choices),
                                  help="Twin's state law: ageing or slip."),
    json_out: bool = typer.Option(False, "--json", help="Print compare.json."),
    force: bool = typer.Option(_CMP["force"].default, "--force", help=FORCE_HELP),
    fmt: str = typer.Option(_CMP["fmt"].default, "--format", metavar=FORMAT_CHOICES,
                     help=FORMAT_HELP),
    dpi: int = typer.Option(_CMP["dpi"].default, "--dpi", help=DPI_HELP),
    figure: bool = typer.Option(_CMP["figure"].default, "--figure/--no-figure",
                                help=FIGURE_HELP),
) -> None:
    """Run a trap-model protocol and its fitted rate-and-state twin; draw both on one figure.

    The twin is fitted to the run itself when it starts in steady sliding at its first velocity
    and never holds, otherwise taken from the standard calibration (velocity steps and
    slide-hold-slide at the first sliding velocity). Reduced units.
    """
    from ..app.runs import compare as run

    with progress_bar("compare", 100.0, unit="%") as update:
        done = run(protocol, out, state_law=state_law, force=force, fmt=fmt, dpi=dpi,
                   figure=figure, report=say, draw=draw_figure,
                   on_start=lambda proto: compile_notice(), progress=update)
    report = done.summary
    brief = {k: v for k, v in report.items() if not isinstance(v, (dict, list))}
    brief.update({f"misfit_{k}": v for k, v in done.result.misfit.items()})
    units = {**report["units"], **{f"misfit_{k}": report["units"].get(k)
                                   for k in done.result.misfit}}
    emit(report if json_out else brief, json_out, f"compare {protocol} -> {out}", units)
    # what the table cannot hold, where the user reads it (as fit's notes): the comparison's
    # own notes, then the twin's fit notes (a parameter on its bound, a systematic misfit);
    # whole on a pipe, and on standard error with --json so that standard output stays JSON
    for note in (*report["notes"], *report["fit"]["notes"]):
        (err if json_out else _STDOUT).print(f"- {note}", markup=False, highlight=False,
                                             soft_wrap=True)
