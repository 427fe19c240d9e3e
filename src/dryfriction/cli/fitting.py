"""The fit command: measured friction against the trap model or rate-and-state."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

import typer
import typer.core
from rich.table import Table
from rich.text import Text

from ..io.files import to_jsonable
from .common import (
    DPI_HELP,
    FIGURE_HELP,
    FORCE_HELP,
    FORMAT_HELP,
    app,
    cli_errors,
    compile_notice,
    err,
    out,
    print_whole,
    progress_bar,
    say,
)
from .model import CREEP_HELP
from .record import SEGMENTS_HELP
from .records import is_project_csv, parse_stiffness


def _csv_stiffness(text: str | None) -> float | str:
    """``--stiffness`` for the project's CSV files (``record`` is for a laboratory record)."""
    k = parse_stiffness("inf" if text is None else text)
    if k == "record":
        raise ValueError("--stiffness record is for a laboratory record (its steps' one "
                         "machine), not the project's CSV files: fit, slope or a number (1/m)")
    return k


@app.command("fit")
@cli_errors
def fit_command(
    data: Annotated[list[Path], typer.Argument(help="CSV files: t_w,mu_s (static), V,mu_d "
                                               "(steady) or t,v_load,mu (time series); units "
                                               "in the header, e.g. V[um/s]. One file in "
                                               "another format is read as a laboratory "
                                               "record (velocity steps, rsf).")],
    out_dir: Annotated[Path, typer.Option("--out", help="Results folder: fit.json, fit.png "
                                          "(written whole or not at all; new, empty, or "
                                          "written by this program before).")],
    model: str = typer.Option("cv", "--model", help="cv (trap model) or rsf (rate-and-state)."),
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness (cv), fixed."),
    creep: str = typer.Option("log", "--creep", help=CREEP_HELP),
    fix: Annotated[list[str] | None, typer.Option(
        "--fix", help="Hold a parameter fixed: --fix t0=0.01 (SI units; repeatable).")] = None,
    v0: float = typer.Option(None, "--v0", help="rsf: reference velocity V0, m/s (for static "
                             "data: the hold tests' sliding velocity; required then)."),
    state_law: str = typer.Option("ageing", "--state-law", help="rsf: ageing, slip, prz "
                                  "(Perrin-Rice-Zheng), nagata (ageing with a stress-rate "
                                  "term c, fitted) or ageing2 (two state variables: b2, dc2 "
                                  "fitted); record: also auto (every law per step, the least "
                                  "AIC chosen; the comparison in fit.json and the notes)."),
    initial_state: str = typer.Option("auto", "--initial-state", help="Record: each step's "
                                      "fit starts in steady sliding (steady), from a fitted "
                                      "state ln(theta0 V/Dc) (free), or free only where the "
                                      "step is flagged not_steady_before (auto)."),
    stiffness: str = typer.Option(None, "--stiffness", help="rsf time series: machine "
                                  "stiffness per unit normal force: a number (1/m; inf: "
                                  "kinematic, the default for CSV), fit (a free parameter "
                                  "per step), slope (fixed from the loading slope after the "
                                  "change) or record (the default for a record: its one "
                                  "machine, from the steps' free fits and its elastic "
                                  "reloads, then held in every step; each step free where "
                                  "fewer than two estimates exist)."),
    trend: bool = typer.Option(None, "--trend/--no-trend", help="rsf time series: a linear "
                               "trend in load-point displacement (default: on for a record, "
                               "off for CSV)."),
    columns: str = typer.Option(None, "--columns", help="Record: column map, e.g. "
                                "time=Time,disp=LP_disp,friction=Mu."),
    segments: str = typer.Option(None, "--segments", help="Record: " + SEGMENTS_HELP),
    joint: bool = typer.Option(False, "--joint", help="Record: also fit all steps with one "
                               "a, b, Dc and one stiffness."),
    drive: str = typer.Option("measured", "--drive", help="Record: what drives the fitted "
                              "machine: measured (default: the record's load-point "
                              "displacement, denoised, its change times placed from it, so "
                              "that the stiffness does not hang on a given change time) or "
                              "program (the idealised piecewise-constant program)."),
    errors: str = typer.Option("hac", "--errors", help="Record: uncertainties that allow for "
                               "autocorrelated residuals (hac, default) or that assume "
                               "independent noise (white)."),
    run_cv: bool = typer.Option(False, "--run-cv", help="Record: also fit the trap model "
                                "(cv) to each step and compare (costly: its estimate is "
                                "printed without this flag)."),
    regularized: bool = typer.Option(False, help="rsf: regularised law (holds, kinematic)."),
    traps_per_a0: float | None = typer.Option(None, "--traps-per-a0", help="cv time series: "
                                       "density of the simulated ensemble (accuracy about its "
                                       "inverse; cost grows with it; default 1000, 100 for a "
                                       "record)."),
    direct: float = typer.Option(0.0, "--direct", help="cv: fit the direct effect A "
                                 "(0 <= A <= 1), started from this value; 0: the athermal "
                                 "model. Hold it with --fix direct=A."),
    v_ref: float = typer.Option(1e-6, "--v-ref", help="cv with --direct: reference velocity "
                                "of the direct effect, m/s, fixed."),
    profile: bool = typer.Option(None, "--profile/--no-profile", help="Profile-likelihood "
                                 "intervals and identifiability (for a record: of a, b, Dc "
                                 "per step; default on up to 6 steps, HAC intervals above)."),
    compare: bool = typer.Option(True, help="Also fit the other model and compare (AIC/BIC)."),
    json_out: bool = typer.Option(False, "--json", help="Print fit.json to standard output."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
    fmt: str = typer.Option("png", "--format", help=FORMAT_HELP),
    dpi: int = typer.Option(None, "--dpi", help=DPI_HELP),
    figure: bool = typer.Option(True, "--figure/--no-figure", help=FIGURE_HELP),
) -> None:
    """Fit the trap model (cv) or rate-and-state (rsf) to measured friction; writes fit.json
    (values, uncertainties, correlations, identifiability, goodness of fit, AIC/BIC) and
    fit.png (data, fitted curve, residuals)."""
    from ..fit import compare_models, fit
    from ..io.files import check_output_dir, output_directory, write_json
    from ..records.data import read_csv
    from ..validation import check_choice, check_figure_format

    check_choice("model", model, ("cv", "rsf"))
    from ..fit.loadpoint import check_drive

    check_drive(drive)
    fmt, dpi = check_figure_format(fmt, dpi)
    check_fit_options(alpha=alpha, creep=creep, v0=v0, state_law=state_law, errors=errors,
                      traps_per_a0=traps_per_a0, direct=direct, v_ref=v_ref)
    record = len(data) == 1 and not is_project_csv(data[0])
    if record:
        # the mirror of the CSV files' refusal of the record's options below: a record's fit
        # reads neither, and an option silently ignored looks obeyed (outside24: --fix a=nan
        # and --fix zz=1 fitted the record free, exit 0)
        for flag, given in (("--fix", fix or None), ("--v0", v0)):
            if given is not None:
                raise ValueError(f"{flag} is for the project's CSV files, not a laboratory "
                                 "record (its steps are fitted free; --stiffness K holds "
                                 "the machine)")
    check_output_dir(out_dir, force=force)
    compile_notice()
    if record:
        from .records import fit_record

        fit_record(data[0], out_dir, model=model, columns=columns, segments=segments,
                   stiffness=parse_stiffness("record" if stiffness is None else stiffness),
                   trend=True if trend is None else trend, law=state_law, joint=joint,
                   initial=initial_state, profile=profile, run_cv=run_cv, alpha=alpha,
                   creep=creep, errors=errors, direct=direct, v_ref=v_ref,
                   traps_per_a0=traps_per_a0, drive=drive,
                   json_out=json_out, force=force, fmt=fmt, dpi=dpi, figure=figure)
        return
    for flag, given in (("--columns", columns), ("--segments", segments),
                        ("--joint", joint or None), ("--run-cv", run_cv or None),
                        ("--errors", None if errors == "hac" else errors),
                        ("--drive", None if drive == "measured" else drive),
                        ("--state-law auto", None if state_law != "auto" else state_law),
                        ("--initial-state", None if initial_state == "auto" else initial_state)):
        if given is not None:
            raise ValueError(f"{flag} is for a laboratory record, not the project's CSV files")
    profile = True if profile is None else profile
    fixed: dict[str, float] = {}
    for item in fix or []:
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise ValueError(f"--fix {item!r}: expected name=value, e.g. --fix t0=0.01")
        try:
            fixed[name.strip()] = float(value)
        except ValueError:
            raise ValueError(f"--fix {item!r}: {value!r} is not a number") from None
    datasets = [read_csv(p) for p in data]
    opts: dict[str, Any] = dict(alpha=alpha, creep=creep, v0=v0, state_law=state_law,
                                stiffness=_csv_stiffness(stiffness),
                                regularized=regularized, trend=bool(trend))
    from ..fit import CVModel

    chosen: Any = (CVModel(alpha, creep, traps_per_a0=1000.0 if traps_per_a0 is None
                           else traps_per_a0, direct=direct,
                           v_ref=v_ref) if model == "cv" else model)
    with progress_bar("fit", unit="evaluations") as update:
        done = [0]

        def fit_progress(n: int, total: int, what: str) -> None:
            done[0] = n
            update(n, total, f"{model} {what}")

        try:
            result = fit(datasets, chosen, fix=fixed, profile=profile, progress=fit_progress,
                         **opts)
        except NotImplementedError as exc:
            raise ValueError(str(exc)) from None
        report = result.to_dict()
        if compare:
            other = "rsf" if model == "cv" else "cv"
            before = done[0]

            def compare_progress(n: int, total: int, what: str) -> None:
                # the count goes on; the total grows by the comparison's, unknown before
                update(before + n, before + total, f"{other} comparison {what}")

            try:
                alt = fit(datasets, other, profile=False, consistency=False, **opts,
                          progress=compare_progress)
                report["comparison"] = compare_models([result, alt])
            except (ValueError, NotImplementedError) as exc:
                report["comparison"] = {"not_run": f"{other}: {exc}"}
    with output_directory(out_dir, command="fit", force=force, inputs=data,
                          report=say) as tmp:
        write_json(tmp / "fit.json", report)
        if figure:
            from ..plots.fits import plot_fit
            from ..plots.style import save_figure

            fig, _ = plot_fit(result, datasets)
            save_figure(fig, tmp / f"fit.{fmt}", fmt, dpi)
    if json_out:
        print(json.dumps(to_jsonable(report), indent=2))
    else:
        table = Table(title=f"{model} fit of {', '.join(str(p) for p in data)}")
        for col in ("parameter", "value", "+-", "95 % interval", "identifiability"):
            table.add_column(col)
        for p in result.parameters:
            iv = p.profile_95 or p.interval_95
            ivs = "" if iv is None else ("[" + ", ".join("open" if x is None else f"{x:.4g}"
                                                          for x in iv) + "]")
            cells = (f"{p.name} [{p.unit}]" if p.unit else p.name, f"{p.value:.6g}",
                     "" if p.stderr is None else f"{p.stderr:.2g}", ivs, p.identifiability)
            table.add_row(*(Text(c) for c in cells))  # "[open, 0.2]" is no Rich markup
        print_whole(table)
        for note in result.notes:
            out.print(f"- {note}", highlight=False, soft_wrap=True)
        if "comparison" in report and "verdict" in report["comparison"]:
            out.print(f"comparison: {report['comparison']['verdict']}", highlight=False)
        out.print(f"wrote {out_dir}/fit.json" + (f", fit.{fmt}" if figure else ""),
                  highlight=False)
    if not result.success:
        err.print(f"[bold red]fit did not converge:[/] {result.message}", highlight=False,
                  soft_wrap=True)
        raise typer.Exit(1)


def check_fit_options(*, alpha: float, creep: str, v0: float | None, state_law: str,
                      errors: str, traps_per_a0: float | None, direct: float,
                      v_ref: float) -> None:
    """Every value option of ``fit`` in its range, named as typed, before any work (issue 24:
    ``--run-cv --direct -1`` fitted rsf for 6 s and reported the refusal inside fit.json).

    Raises
    ------
    ValueError
        ``--OPTION VALUE is out of range: allowed ...``.
    """
    from ..ensemble.population import TRAPS_PER_A0_MIN
    from ..ensemble.resources import BYTES_PER_TRAP
    from ..fit.laws import FIT_LAWS
    from ..fit.steps import ERRORS
    from ..rsf.law import V_MAX, V_MIN
    from ..theory.creep import CREEP_LAWS
    from ..validation import ALPHA_MIN, DIRECT_MAX, check_choice, check_memory, check_scalar

    check_scalar("--alpha", alpha, ALPHA_MIN, 1.0, hi_open=True)
    check_choice("--creep", creep, CREEP_LAWS)
    check_choice("--state-law", state_law, (*FIT_LAWS, "auto"))
    check_choice("--errors", errors, ERRORS)
    check_scalar("--direct", direct, 0.0, DIRECT_MAX)
    check_scalar("--v-ref", v_ref, V_MIN, V_MAX)
    if v0 is not None:
        check_scalar("--v0", v0, V_MIN, V_MAX)
    if traps_per_a0 is not None:
        lam = check_scalar("--traps-per-a0", traps_per_a0, TRAPS_PER_A0_MIN)
        # every forward run keeps at least the pairs of 2 (reach + margin + 2) >= 28 a0 around
        # the slider (ensemble.resources.estimate_run): refused here, in the option's name,
        # rather than as a failed evaluation at every trial of the fit
        check_memory(f"--traps-per-a0 {lam:g} keeps at least {28.0 * lam:.1e} pairs around "
                     "the slider in every run of the trap model", 28.0 * lam * BYTES_PER_TRAP,
                     "lower --traps-per-a0")
