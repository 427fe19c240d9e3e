"""Commands that run a history and write a results folder: reproduce, rsf, simulate,
compare."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any

import typer
import typer.core

from ..app.options import OPTIONS
from . import figures
from .common import (
    DPI_HELP,
    FIGURE_HELP,
    FORCE_HELP,
    FORMAT_HELP,
    app,
    cli_errors,
    compile_notice,
    emit,
    lazy_progress_bar,
    many,
    out,
    progress_bar,
    say,
    say_interrupted,
    write_summary,
)
from .model import LOAD_MAX
from .painter import draw_figure

_REP, _SIM, _CMP = OPTIONS["reproduce"], OPTIONS["simulate"], OPTIONS["compare"]


@app.command(cls=many())
@cli_errors
def reproduce(
    out_dir: Annotated[Path, typer.Option("--out", help="Results folder: new, empty, or one "
                                          "this program wrote before.")],
    force: bool = typer.Option(_REP["force"].default, "--force", help=FORCE_HELP),
    fmt: str = typer.Option(_REP["fmt"].default, "--format", help=FORMAT_HELP),
    dpi: int = typer.Option(_REP["dpi"].default, "--dpi", help=DPI_HELP),
) -> None:
    """The paper's six figures, the data behind them, summary.json and report.html."""
    from ..app.runs import reproduce as run

    with progress_bar("reproduce", unit="steps") as update:
        summary = run(out_dir, force=force, fmt=fmt, dpi=dpi, progress=update,
                      report=say).summary
    out.print(
        f"wrote {out_dir}/: fig1-6.{fmt}, static_friction.csv, steady_friction.csv, "
        f"summary.json, report.html (C_inf = {summary['dieterich_C_asymptotic']:.4f}, "
        f"C_LS = {summary['dieterich_C_least_squares']:.4f})",
        highlight=False, soft_wrap=True,
    )


@app.command()
@cli_errors
def rsf(
    case: str = typer.Option("step", help="step (v1 for t1, then v2 for t2), shs (slide-hold-"
                             "slide: v1 for t1, hold for --hold, v1 for t2) or stick-slip "
                             "(v1 for t1)."),
    a: float = typer.Option(0.005, help="Direct effect a, > 0."),
    b: float = typer.Option(0.01, help="Evolution effect b, >= 0."),
    dc: float = typer.Option(1e-5, help="Characteristic slip Dc, m, > 0."),
    mu0: float = typer.Option(0.6, help="Reference friction at V0, -10 to 10."),
    v0: float = typer.Option(1e-6, help="Reference velocity V0, m/s, > 0."),
    state_law: str = typer.Option("ageing", help="ageing (Dieterich) or slip (Ruina)."),
    regularized: bool = typer.Option(False, help="Regularised asinh law (needed for holds "
                                     "with --stiffness inf)."),
    stiffness: float = typer.Option(1e3, help="Spring stiffness k per unit normal force, 1/m, "
                                    "> 0; inf for a kinematic machine."),
    damping: float = typer.Option(0.0, help="Radiation damping eta/sigma, s/m, >= 0."),
    mass: float = typer.Option(0.0, help="Mass per unit normal force, s^2/m, >= 0."),
    v1: float = typer.Option(1e-6, help="Load velocity of the first segment, m/s."),
    v2: float = typer.Option(1e-5, help="Load velocity after the step (case step), m/s."),
    t1: float = typer.Option(10.0, help="Duration of the first segment, s."),
    t2: float = typer.Option(None, help="Duration of the last segment, s (default: 30 for "
                             "step; for shs long enough to pass the reload peak and slide "
                             "10 Dc beyond)."),
    hold: float = typer.Option(100.0, help="Hold time (case shs), s."),
    v_init: float = typer.Option(None, help="Initial slip velocity, m/s, with the state at "
                                 "steady state for v_init (default v1; 1.01 v1 for "
                                 "stick-slip, since exact steady state never leaves)."),
    rtol: float = typer.Option(1e-7, help="Local error tolerance (relative in V and theta)."),
    out_dir: str = typer.Option(None, "--out", help="Write series.csv, summary.json and "
                                "rsf.png into this folder (whole or not at all; new, empty, or "
                                "written by this program before)."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
    fmt: str = typer.Option("png", "--format", help=FORMAT_HELP),
    dpi: int = typer.Option(None, "--dpi", help=DPI_HELP),
    figure: bool = typer.Option(True, "--figure/--no-figure", help=FIGURE_HELP),
) -> None:
    """Rate-and-state friction (SI units) through a velocity step, slide-hold-slide or
    stick-slip, on a spring with optional radiation damping and inertia."""
    import time

    from ..io.files import check_output_dir, output_directory, write_csv
    from ..program import Segment
    from ..rsf.driving import RSFInitial, RSFOutput, SolverError, SpringSlider, simulate
    from ..rsf.law import RateState
    from ..validation import check_choice, check_figure_format, check_scalar

    check_choice("case", case, ("step", "shs", "stick-slip"))
    fmt, dpi = check_figure_format(fmt, dpi)
    if t2 is None:
        t2 = _reload_time(a, b, dc, v1, hold, stiffness) if case == "shs" else 30.0
    from ..rsf.law import V_MAX, V_MIN

    # durations and velocities a run can reach in floating point (a 1e308 s first segment
    # would leave the later ones at t = inf, silently dropped)
    for name, value in (("--t1", t1), ("--t2", t2), ("--hold", hold)):
        check_scalar(name, value, 0.0, LOAD_MAX, lo_open=True)
    for name, value in (("--v1", v1), ("--v2", v2)):
        check_scalar(name, value, -V_MAX, V_MAX)
        if value != 0.0 and abs(value) < V_MIN:  # named as typed, not as segments[0]
            raise ValueError(f"{name} {value:g} is out of range: allowed 0 (a hold) or "
                             f"{V_MIN:g} <= |{name[2:]}| <= {V_MAX:g} m/s")
        if value < 0.0 and not (math.isinf(stiffness) and regularized):
            # the spring driver integrates ln V and the standard law needs V > 0: the
            # driver's own check would name segments[i], which the user never typed
            raise ValueError(f"{name} {value:g} is out of range: allowed 0 to {V_MAX:g} m/s "
                             "(sliding back needs --stiffness inf --regularized)")
    if v_init is not None:
        check_scalar("--v-init", v_init, 0.0, V_MAX, lo_open=True)
    elif v1 <= 0.0:  # the library would ask for v_init, a name the user never typed
        raise ValueError(f"--v-init is needed when --v1 is {v1:g} m/s: the initial slip "
                         f"velocity, > 0 and <= {V_MAX:g} m/s (the state starts steady for it)")
    check_scalar("--damping", damping, 0.0, LOAD_MAX)
    check_scalar("--mass", mass, 0.0, LOAD_MAX)
    check_scalar("--rtol", rtol, 0.0, 0.1, lo_open=True)
    params = RateState(a, b, dc, mu0, v0, state_law=state_law,  # type: ignore[arg-type]
                       regularized=regularized)
    if case == "step":
        segs = [Segment(v1, t1), Segment(v2, t2)]
    elif case == "shs":
        segs = [Segment(v1, t1), Segment(0.0, hold), Segment(v1, t2)]
    else:
        segs = [Segment(v1, t1)]
        if v_init is None:
            v_init = 1.01 * v1
    drive = SpringSlider(segs, stiffness, damping, mass)  # every check before any work
    init, output = RSFInitial(v=v_init), RSFOutput(rtol=rtol)
    drive.check_model(params)
    init.resolve(params, drive)
    if out_dir is not None:
        check_output_dir(out_dir, force=force)
    compile_notice(rsf=True)
    start = time.perf_counter()
    try:
        res = simulate(params, drive, init, output)
    except SolverError as exc:
        raise ValueError(str(exc)) from None
    context = {"case": case, "wall_s": time.perf_counter() - start}
    summary = {**res.summary(), **context}
    if out_dir is not None:
        with output_directory(out_dir, command="rsf", force=force, report=say) as tmp:
            write_csv(tmp / "series.csv", res.columns())
            summary = write_summary(tmp / "summary.json", res, context)
            if figure:
                draw_figure(figures.rsf_figure, res,
                            f"{case}, {state_law} law", path=tmp / f"rsf.{fmt}", fmt=fmt,
                            dpi=dpi)
    brief = {k: v for k, v in summary.items() if not isinstance(v, dict)}
    emit(summary if json_out else brief, json_out, f"rate-and-state, {case}")
    if case == "shs" and _peak_at_end(res, t1 + hold):
        say(f"note: the reload had not reached its peak when the run ended (t2 = {t2:g} s): "
            "raise --t2")


def _reload_time(a: float, b: float, dc: float, v: float, hold: float,
                 stiffness: float) -> float:
    """Duration (s) of the reload of a slide-hold-slide at load velocity ``v`` that passes the
    peak: the spring takes up the friction the contact healed during the hold (about
    ``b ln(1 + hold v/dc)`` plus the direct effect ``a``, over ``stiffness``), then the slider
    slides ``10 dc`` (the evolution back to steady state). At least 30 s."""
    import math

    if not (a > 0 and dc > 0 and v != 0 and math.isfinite(a + b + dc + v + hold)):
        return 30.0  # the law's own checks reject these, with their own message
    speed = abs(v)
    heal = max(b, 0.0) * math.log1p(hold * speed / dc) + 2.0 * a
    load = heal / (stiffness * speed) if math.isfinite(stiffness) and stiffness > 0 else 0.0
    return max(30.0, min(load + 10.0 * dc / speed, LOAD_MAX))


def _peak_at_end(res: Any, reload_start: float) -> bool:
    """Whether the friction of the reload (after ``reload_start``) is still at its maximum at
    the last sample: the run ended before the peak."""
    import numpy as np

    sel = np.asarray(res.t) >= reload_start
    mu = np.asarray(res.mu)[sel]
    return bool(mu.size > 1 and int(np.argmax(mu)) == mu.size - 1)


@app.command()
@cli_errors
def simulate(
    protocol: str = typer.Argument(..., help="Protocol file (TOML), see dryfriction.io.protocol."),
    out: str = typer.Option(..., "--out", help="Results folder (written whole or not at all; "
                            "new, empty, or written by this program before)."),
    json_out: bool = typer.Option(False, "--json", help="Print the summary as JSON."),
    force: bool = typer.Option(_SIM["force"].default, "--force", help=FORCE_HELP),
    fmt: str = typer.Option(_SIM["fmt"].default, "--format", help=FORMAT_HELP),
    dpi: int = typer.Option(_SIM["dpi"].default, "--dpi", help=DPI_HELP),
    figure: bool = typer.Option(_SIM["figure"].default, "--figure/--no-figure",
                                help=FIGURE_HELP),
) -> None:
    """Run a protocol (trap ensemble, §6 of `dryfriction model`, or rate-and-state with
    ``model.law = "rsf"``):
    timeseries.csv, summary.json, timeseries.png.

    Ctrl-C stops a trap-model run and writes the samples so far as a complete result marked
    ``"partial": true`` in summary.json (exit code 130); an interrupt while writing leaves
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
    emit(done.summary if json_out else brief, json_out, title)
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
                                  help="Twin's state law: ageing or slip."),
    json_out: bool = typer.Option(False, "--json", help="Print compare.json."),
    force: bool = typer.Option(_CMP["force"].default, "--force", help=FORCE_HELP),
    fmt: str = typer.Option(_CMP["fmt"].default, "--format", help=FORMAT_HELP),
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

    done = run(protocol, out, state_law=state_law, force=force, fmt=fmt, dpi=dpi,
               figure=figure, report=say, draw=draw_figure,
               on_start=lambda proto: compile_notice())
    report = done.summary
    brief = {k: v for k, v in report.items() if not isinstance(v, (dict, list))}
    brief.update({f"misfit_{k}": v for k, v in done.result.misfit.items()})
    emit(report if json_out else brief, json_out, f"compare {protocol} -> {out}")
