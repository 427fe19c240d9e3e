"""The ``dryfriction`` command line: thin wrappers that parse, call one library function, print.

Bad input (any ``ValueError`` from the library's checks, a bad path) becomes one line on
standard error and exit code 2.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, TypeVar

import numpy as np
import typer
import typer.core
from rich.console import Console
from rich.table import Table

from .io.files import to_jsonable

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="The Caroli-Velicky elasto-plastic model of dry friction (reduced units: a0, t0, F_el).",
)
err = Console(stderr=True)
out = Console()

F = TypeVar("F", bound=Callable[..., Any])


@app.callback()
def _root() -> None:
    """The Caroli-Velicky elasto-plastic model of dry friction (reduced units: a0, t0, F_el)."""


def error_line(message: str) -> None:
    """Print ``error: message`` as one line; the message is plain text (``[drive]`` is not
    Rich markup)."""
    err.print("[bold red]error:[/] ", end="", highlight=False)
    err.print(message, markup=False, highlight=False, soft_wrap=True)


def cli_errors(fn: F) -> F:
    """Turn the library's ``ValueError``/``OSError`` into one line and exit code 2."""

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return fn(*args, **kwargs)
        except (ValueError, OSError) as exc:
            error_line(str(exc))
            raise typer.Exit(2) from None

    return wrapper  # type: ignore[return-value]


_FORCE_HELP = ("Write into a folder that holds other files too: they are kept (one whose name "
               "collides with a result is renamed NAME.~1~); nothing is deleted.")


def say(line: str) -> None:
    """One plain-text line on standard error (what was done to files already there)."""
    err.print(line, markup=False, highlight=False, soft_wrap=True)


def emit(result: dict[str, Any], as_json: bool, title: str) -> None:
    """Print ``result`` as JSON (``--json``) or as a table."""
    if as_json:
        print(json.dumps(to_jsonable(result), indent=2))
        return
    table = Table(title=title, show_header=False)
    for k, v in result.items():
        table.add_row(k, f"{v:.10g}" if isinstance(v, float) else str(v))
    out.print(table)


def write_summary(path: Any, result: Any, context: dict[str, Any]) -> dict[str, Any]:
    """Write ``result.summary()`` plus the run's ``context`` (protocol, wall time, ...) as
    ``path`` (JSON): the one summary.json writer of ``rsf`` and ``simulate`` (both laws).
    Returns what was written."""
    from .io.files import write_json

    summary = {**result.summary(), **context}
    write_json(path, summary)
    return summary


@app.command()
@cli_errors
def trap(
    alpha: float = typer.Option(0.13, help="Reduced trap stiffness kappa a^2/(6 Phi0), > 0."),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """All single-trap constants and the pinning regime (spec §1)."""
    from .theory.trap import Trap

    emit(Trap(alpha).summary(), json_out, f"trap, alpha = {alpha:g}")


# --------------------------------------------------------------------------------------------
# static, steady, reproduce
# --------------------------------------------------------------------------------------------


class _ManyValues(typer.core.TyperCommand):
    """A command whose list options take several values after one flag: ``--T 1 10 100``.

    Before Click parses, ``--T 1 10 100`` is rewritten to ``--T 1 --T 10 --T 100``: every token
    after a listed flag that reads as a number (``-1``, ``1e3``, ``nan`` included, so that the
    library's range checks see it) is taken as another value. Repeating the flag also works.
    Click's own usage errors (missing option, not a number) are printed as one line, exit 2.
    """

    many: tuple[str, ...] = ()

    def parse_args(self, ctx: Any, args: list[str]) -> list[str]:
        expanded: list[str] = []
        i = 0
        while i < len(args):
            tok = args[i]
            expanded.append(tok)
            i += 1
            if tok == "--":
                expanded += args[i:]
                break
            if tok in self.many and i < len(args):
                expanded.append(args[i])  # the first value, whatever it is: Click checks it
                i += 1
                while i < len(args) and _is_number(args[i]):
                    expanded += [tok, args[i]]
                    i += 1
        try:
            return super().parse_args(ctx, expanded)
        except typer.TyperException as exc:  # Click's UsageError and its kin (exit code 2)
            if getattr(exc, "exit_code", None) != 2:
                raise
            message = exc.format_message()  # type: ignore[attr-defined]
            error_line(message)
            raise typer.Exit(2) from None


def _is_number(tok: str) -> bool:
    try:
        float(tok)
    except ValueError:
        return False
    return True


def _many(*flags: str) -> type[_ManyValues]:
    return type("ManyValues", (_ManyValues,), {"many": flags})


def _columns(title: str, params: dict[str, Any], cols: dict[str, Any]) -> None:
    out.print(f"{title}: " + ", ".join(f"{k} = {v}" for k, v in params.items()), highlight=False)
    table = Table()
    for name in cols:
        table.add_column(name, justify="right")
    for row in zip(*cols.values(), strict=True):
        table.add_row(*(f"{float(v):.10g}" for v in row))
    out.print(table)


_CREEP_HELP = "Creep law: log (eq. 17) or eyring-nabarro (exact, eqs. 15-16)."


@app.command(cls=_many("--T"))
@cli_errors
def static(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, >= 0.")],
    T: Annotated[list[float], typer.Option(
        "--T", help="Waiting times t_w/t0, >= 0: --T 1 10 100 (or --T 1 --T 10)."
    )],
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness, 0 < alpha < 1."),
    load: float = typer.Option(
        0.0, "--load", help="Tangential force during the wait, units F_el, 0 <= f_w < 1."
    ),
    creep: str = typer.Option("log", "--creep", help=_CREEP_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Static friction mu_s = F_s/F_el after waiting T = t_w/t0 (eq. 27, our reading)."""
    from .theory.static import static_friction

    mu = static_friction(np.asarray(T, float), eps, alpha, creep, load)
    params = {"eps": eps, "alpha": alpha, "load": load, "creep": creep}
    if json_out:
        emit({**params, "T": list(T), "mu_s": mu}, True, "static")
    else:
        _columns("static friction", params, {"T": T, "mu_s": mu})


@app.command(cls=_many("--u"))
@cli_errors
def steady(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, >= 0.")],
    u: Annotated[list[float], typer.Option(
        "--u", help="Reduced velocities V t0/a0, > 0: --u 0.1 1 10 (or --u 0.1 --u 1)."
    )],
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness, 0 < alpha < 1."),
    creep: str = typer.Option("log", "--creep", help=_CREEP_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Steady dynamic friction mu_d = F_d/F_el at reduced velocity u = V/V* (eq. 34)."""
    from .theory.steady import steady_friction

    mu = steady_friction(np.asarray(u, float), eps, alpha, creep)
    params = {"eps": eps, "alpha": alpha, "creep": creep}
    if json_out:
        emit({**params, "u": list(u), "mu_d": mu}, True, "steady")
    else:
        _columns("steady friction", params, {"u": u, "mu_d": mu})


@app.command(cls=_many())
@cli_errors
def reproduce(
    out_dir: Annotated[Path, typer.Option("--out", help="Results folder: new, empty, or one "
                                          "this program wrote before.")],
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
) -> None:
    """The paper's six figures, the data behind them, summary.json and report.html."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    from .io.files import check_output_dir
    from .plots.report import reproduce as run

    check_output_dir(out_dir, force=force)  # fail on a bad --out before importing matplotlib
    with Progress(
        TextColumn("{task.description}"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
        TimeElapsedColumn(), console=err, disable=not err.is_terminal, transient=True,
    ) as bar:
        task = bar.add_task("reproduce", total=None)

        def progress(done: int, total: int, what: str) -> None:
            bar.update(task, completed=done, total=total, description=what)

        summary = run(out_dir, progress, force=force, report=say)
    out.print(
        f"wrote {out_dir}/: fig1-6.png, static_friction.csv, steady_friction.csv, "
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
    mu0: float = typer.Option(0.6, help="Reference friction at V0."),
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
    t2: float = typer.Option(30.0, help="Duration of the last segment, s."),
    hold: float = typer.Option(100.0, help="Hold time (case shs), s."),
    v_init: float = typer.Option(None, help="Initial slip velocity, m/s, with the state at "
                                 "steady state for v_init (default v1; 1.01 v1 for "
                                 "stick-slip, since exact steady state never leaves)."),
    rtol: float = typer.Option(1e-7, help="Local error tolerance (relative in V and theta)."),
    out_dir: str = typer.Option(None, "--out", help="Write series.csv, summary.json and "
                                "rsf.png into this folder (whole or not at all; new, empty, or "
                                "written by this program before)."),
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Rate-and-state friction (SI units) through a velocity step, slide-hold-slide or
    stick-slip, on a spring with optional radiation damping and inertia."""
    import time

    from .io.files import check_output_dir, output_directory, write_csv
    from .program import Segment
    from .rsf.driving import RSFInitial, RSFOutput, SolverError, SpringSlider, simulate_rsf
    from .rsf.law import RateState
    from .validation import check_choice, check_scalar

    check_choice("case", case, ("step", "shs", "stick-slip"))
    from .rsf.law import V_MAX

    # durations and velocities a run can reach in floating point (a 1e308 s first segment
    # would leave the later ones at t = inf, silently dropped)
    for name, value in (("--t1", t1), ("--t2", t2), ("--hold", hold)):
        check_scalar(name, value, 0.0, _LOAD_MAX, lo_open=True)
    for name, value in (("--v1", v1), ("--v2", v2)):
        check_scalar(name, value, -V_MAX, V_MAX)
    if v_init is not None:
        check_scalar("--v-init", v_init, 0.0, V_MAX, lo_open=True)
    check_scalar("--damping", damping, 0.0, _LOAD_MAX)
    check_scalar("--mass", mass, 0.0, _LOAD_MAX)
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
    start = time.perf_counter()
    try:
        res = simulate_rsf(params, drive, init, output)
    except SolverError as exc:
        raise ValueError(str(exc)) from None
    context = {"case": case, "wall_s": time.perf_counter() - start}
    summary = {**res.summary(), **context}
    if out_dir is not None:
        from .plots.runs import rsf_figure
        from .plots.style import save_png

        with output_directory(out_dir, command="rsf", force=force, report=say) as tmp:
            write_csv(tmp / "series.csv", res.columns())
            summary = write_summary(tmp / "summary.json", res, context)
            fig, _ = rsf_figure(res, f"{case}, {state_law} law")
            save_png(fig, tmp / "rsf.png")
    brief = {k: v for k, v in summary.items() if not isinstance(v, dict)}
    emit(summary if json_out else brief, json_out, f"rate-and-state, {case}")


_LOAD_MAX = 1e12
"""Largest mass, damping (reduced units) or duration (s) the commands accept: far beyond any
experiment, and small enough that products with the other inputs stay finite."""


@app.command(cls=_many("--u"))
@cli_errors
def stability(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, >= 0.")],
    u: Annotated[list[float], typer.Option(
        "--u", help="Reduced velocities V t0/a0, > 0: --u 0.1 1 10 (or --u 0.1 --u 1)."
    )],
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness, 0 < alpha < 1."),
    mass: float = typer.Option(0.0, "--mass", help="Slider mass M, F_el t0^2/a0, >= 0."),
    damping: float = typer.Option(0.0, "--damping", help="Viscous damping eta, F_el t0/a0."),
    creep: str = typer.Option("log", "--creep", help=_CREEP_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Critical stiffness K_c (F_el/a0) and onset frequency (1/t0) of steady sliding."""
    from .analysis.rsf_stability import rsf_stability_prediction
    from .theory.stability import critical_stiffness
    from .theory.steady import check_steady_inputs
    from .validation import check_scalar

    check_steady_inputs(np.asarray(u, float), eps, alpha, creep)
    check_scalar("mass", mass, 0.0, _LOAD_MAX)
    check_scalar("damping", damping, 0.0, _LOAD_MAX)
    res = [critical_stiffness(v, eps, alpha, creep, mass, damping) for v in u]
    twins = ([rsf_stability_prediction(v, eps, alpha, creep, mass, damping) for v in u]
             if eps > 0 else [])
    params = {"eps": eps, "alpha": alpha, "mass": mass, "damping": damping, "creep": creep}
    cols = {
        "u": list(u),
        "K_c": [r.critical_stiffness for r in res],
        "omega_c": [r.omega for r in res],
        "forward_stiffness": [r.forward_stiffness for r in res],
        "backward_stiffness": [r.backward_stiffness for r in res],
        "dmu_d_du": [r.velocity_slope for r in res],
    }
    if twins:  # rate-and-state with the model's effective a, b, Dc (Rice & Ruina 1983)
        cols["K_c_rsf"] = [t["K_c"] for t in twins]
    if json_out:
        emit({**params, **cols}, True, "stability")
    else:
        _columns("linear stability of steady sliding", params, cols)
@app.command("fit")
@cli_errors
def fit_command(
    data: Annotated[list[Path], typer.Argument(help="CSV files: t_w,mu_s (static), V,mu_d "
                                               "(steady) or t,v_load,mu (time series); units "
                                               "in the header, e.g. V[um/s].")],
    out_dir: Annotated[Path, typer.Option("--out", help="Results folder: fit.json, fit.png "
                                          "(written whole or not at all; new, empty, or "
                                          "written by this program before).")],
    model: str = typer.Option("cv", "--model", help="cv (trap model) or rsf (rate-and-state)."),
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness (cv), fixed."),
    creep: str = typer.Option("log", "--creep", help=_CREEP_HELP),
    fix: Annotated[list[str] | None, typer.Option(
        "--fix", help="Hold a parameter fixed: --fix t0=0.01 (SI units; repeatable).")] = None,
    v0: float = typer.Option(None, "--v0", help="rsf: reference velocity V0, m/s (for static "
                             "data: the hold tests' sliding velocity; required then)."),
    state_law: str = typer.Option("ageing", "--state-law", help="rsf: ageing or slip."),
    stiffness: float = typer.Option(float("inf"), "--stiffness", help="rsf time series: "
                                    "machine stiffness per unit normal force, 1/m; inf: "
                                    "kinematic."),
    regularized: bool = typer.Option(False, help="rsf: regularised law (holds, kinematic)."),
    traps_per_a0: float = typer.Option(1000.0, "--traps-per-a0", help="cv time series: "
                                       "density of the simulated ensemble (accuracy about its "
                                       "inverse; cost grows with it)."),
    profile: bool = typer.Option(True, help="Profile-likelihood intervals and identifiability."),
    compare: bool = typer.Option(True, help="Also fit the other model and compare (AIC/BIC)."),
    json_out: bool = typer.Option(False, "--json", help="Print fit.json to standard output."),
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
) -> None:
    """Fit the trap model (cv) or rate-and-state (rsf) to measured friction; writes fit.json
    (values, uncertainties, correlations, identifiability, goodness of fit, AIC/BIC) and
    fit.png (data, fitted curve, residuals)."""
    from .fit import compare_models, fit
    from .io.data import read_csv
    from .io.files import check_output_dir, output_directory, write_json
    from .plots.fits import plot_fit
    from .validation import check_choice

    check_choice("model", model, ("cv", "rsf"))
    check_output_dir(out_dir, force=force, inputs=data)
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
                                stiffness=stiffness, regularized=regularized)
    from .fit import CVModel

    chosen: Any = CVModel(alpha, creep, traps_per_a0=traps_per_a0) if model == "cv" else model
    try:
        result = fit(datasets, chosen, fix=fixed, profile=profile, **opts)
    except NotImplementedError as exc:
        raise ValueError(str(exc)) from None
    report = result.to_dict()
    if compare:
        other = "rsf" if model == "cv" else "cv"
        try:
            alt = fit(datasets, other, profile=False, consistency=False, **opts)
            report["comparison"] = compare_models([result, alt])
        except (ValueError, NotImplementedError) as exc:
            report["comparison"] = {"not_run": f"{other}: {exc}"}
    with output_directory(out_dir, command="fit", force=force, inputs=data,
                          report=say) as tmp:
        write_json(tmp / "fit.json", report)
        plot_fit(result, datasets, tmp / "fit.png")
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
            table.add_row(f"{p.name} ({p.unit})" if p.unit else p.name, f"{p.value:.6g}",
                          "" if p.stderr is None else f"{p.stderr:.2g}", ivs, p.identifiability)
        out.print(table)
        for note in result.notes:
            out.print(f"- {note}", highlight=False, soft_wrap=True)
        if "comparison" in report and "verdict" in report["comparison"]:
            out.print(f"comparison: {report['comparison']['verdict']}", highlight=False)
        out.print(f"wrote {out_dir}/fit.json, fit.png", highlight=False)
    if not result.success:
        err.print(f"[bold red]fit did not converge:[/] {result.message}", highlight=False,
                  soft_wrap=True)
        raise typer.Exit(1)


@app.command()
@cli_errors
def simulate(
    protocol: str = typer.Argument(..., help="Protocol file (TOML), see dryfriction.protocol."),
    out: str = typer.Option(..., "--out", help="Results folder (written whole or not at all; "
                            "new, empty, or written by this program before)."),
    json_out: bool = typer.Option(False, "--json", help="Print the summary as JSON."),
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
) -> None:
    """Run a protocol (trap ensemble, spec §6, or rate-and-state with ``model.law = "rsf"``):
    timeseries.csv, summary.json, timeseries.png.

    Ctrl-C stops a trap-model run and writes the samples so far as a complete result marked
    ``"partial": true`` in summary.json (exit code 130); an interrupt while writing leaves
    nothing.
    """
    import time
    from pathlib import Path

    from .io.files import check_output_dir, output_directory, write_csv
    from .io.protocol import RSFProtocol, load_protocol

    proto = load_protocol(protocol)  # every check before any work
    check_output_dir(out, force=force, inputs=[protocol])
    if isinstance(proto, RSFProtocol):
        _simulate_rsf_protocol(proto, protocol, out, json_out, force)
        return

    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    started = time.monotonic()
    bar: dict[str, Any] = {}

    def progress(fraction: float) -> None:
        if not err.is_terminal or time.monotonic() - started < 1.0:
            return
        if not bar:
            p = Progress(TextColumn("simulate"), BarColumn(), TimeElapsedColumn(),
                         console=err, transient=True)
            p.start()
            bar["p"], bar["task"] = p, p.add_task("simulate", total=1.0)
        bar["p"].update(bar["task"], completed=fraction)

    try:
        result = proto.run(progress=progress, on_interrupt="partial")
    finally:
        if bar:
            bar["p"].stop()
    from .plots.runs import timeseries_figure
    from .plots.style import save_png

    with output_directory(out, command="simulate", force=force, inputs=[protocol],
                          report=say) as tmp:
        write_csv(tmp / "timeseries.csv", result.columns())
        summary = write_summary(tmp / "summary.json", result,
                                {"protocol": str(Path(protocol))})
        fig, _ = timeseries_figure(result)
        save_png(fig, tmp / "timeseries.png")
        for i, snap in enumerate(result.snapshots):
            cols = {k: v for k, v in snap.items() if k not in ("t", "x")}
            write_csv(tmp / f"snapshot_{i:03d}_t{snap['t']:.6g}.csv", cols)
    brief = {k: v for k, v in summary.items() if not isinstance(v, dict)}
    emit(brief if not json_out else summary, json_out, f"simulate {protocol} -> {out}")
    if result.partial:
        err.print("[bold yellow]interrupted:[/] partial result written", highlight=False)
        raise typer.Exit(130)


# --------------------------------------------------------------------------------------------
# sweep, phase-diagram (issue 5)
# --------------------------------------------------------------------------------------------


def _prepare_sweep(protocol: str, out_dir: str, confirm: bool, workers: int | None,
                   scheduler: str | None = None, linear: bool = False,
                   connect_timeout: float = 10.0) -> Any:
    """Parse a sweep protocol and check every grid point before any worker starts (the
    ``[stickslip]`` table too, and, without ``linear``, everything the stick-slip runner would
    refuse at run time)."""
    import tomllib

    from .analysis.stickslip import analysis_options, stick_slip_point
    from .io.files import check_writable_dir
    from .io.protocol import protocol_from_dict
    from .io.sweep import MAX_POINTS, parse_sweep

    path = Path(protocol)
    try:
        text = path.read_bytes().decode("utf-8")
        doc = tomllib.loads(text)
    except OSError as exc:
        raise ValueError(f"{path}: cannot read the protocol: {exc.strerror}") from None
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise ValueError(f"{path}: malformed TOML: {exc}") from None
    spec = parse_sweep(doc, str(path))
    if spec.size > MAX_POINTS and not confirm:
        raise ValueError(f"{path}: the grid has {spec.size} points, more than {MAX_POINTS}: "
                         "confirm with --yes")
    if workers is not None and workers < 1:
        raise ValueError(f"--workers {workers} is out of range: allowed >= 1")
    if workers is not None and scheduler is not None:
        raise ValueError("--workers is for the local cluster and --scheduler brings its own "
                         "workers: give one of the two")
    if not connect_timeout > 0:
        raise ValueError(f"--connect-timeout {connect_timeout:g} is out of range: allowed > 0")
    for _, ov in spec.points():
        point = spec.protocol(ov)
        where = f"{path} (point {', '.join(f'{k} = {v}' for k, v in ov.items())})"
        if linear:
            analysis_options(point.get("stickslip"), where)
            model = point.get("model", {})
            if isinstance(model, dict) and model.get("law", "cv") == "rsf":
                raise ValueError(f"{where}: model.law = 'rsf': sweeps of rate-and-state "
                                 "protocols are not supported yet (--linear needs the trap "
                                 "model)")
            protocol_from_dict({k: v for k, v in point.items() if k != "stickslip"}, where)
        else:
            stick_slip_point(point, where)
    check_writable_dir(out_dir)
    return spec


def _text_of(protocol: str) -> str:
    """The protocol file's text, for the results folder's ``sweep.json`` (informative only:
    the sweep's identity is the hash of the parsed protocol)."""
    try:
        return Path(protocol).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return ""


def _resume_command(command: str, protocol: str, out_dir: str, scheduler: str | None,
                    workers: int | None, yes: bool, linear: bool,
                    connect_timeout: float) -> str:
    """The command line that resumes this sweep (the same options, shell-quoted)."""
    import shlex

    args = ["dryfriction", command, protocol, "--out", out_dir]
    if scheduler is not None:
        args += ["--scheduler", scheduler]
    if workers is not None:
        args += ["--workers", str(workers)]
    if connect_timeout != 10.0:
        args += ["--connect-timeout", f"{connect_timeout:g}"]
    args += ["--yes"] * yes + ["--linear"] * linear
    return shlex.join(args)


def _run_with_bar(spec: Any, runner: Any, out_dir: str, scheduler: str | None,
                  workers: int | None, confirm: bool, *, source: str = "",
                  protocol_text: str = "", connect_timeout: float = 10.0, resume: str = "") -> Any:
    """:func:`~dryfriction.sweep.run_sweep` with a progress bar; Ctrl-C prints how many points
    are stored and the command that resumes, and exits with 130."""
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
    )

    from .io.sweep import SweepInterrupted, run_sweep

    try:
        with Progress(TextColumn("sweep"), BarColumn(), MofNCompleteColumn(),
                      TimeElapsedColumn(), console=err, disable=not err.is_terminal,
                      transient=True) as bar:
            task = bar.add_task("sweep", total=spec.size)

            def progress(done: int, total: int) -> None:
                bar.update(task, completed=done, total=total)

            return run_sweep(spec, runner, out_dir, scheduler=scheduler, n_workers=workers,
                             confirm=confirm, progress=progress, source=source,
                             protocol_text=protocol_text, connect_timeout=connect_timeout)
    except SweepInterrupted as exc:
        err.print(f"[bold yellow]interrupted:[/] {exc.stored} of {exc.total} points stored in "
                  f"{out_dir}; resume with: {resume}", highlight=False, soft_wrap=True)
        raise typer.Exit(130) from None


def _fail_if_points_failed(ds: Any, out_dir: str) -> None:
    """Exit 1 with one line when any point failed (sweep.nc is written, failures included)."""
    n_failed = int(ds.attrs["n_failed"])
    if not n_failed:
        return
    size = int(ds["error"].size)
    first = next(e for e in ds["error"].values.ravel() if e)
    what = "all" if n_failed == size else f"{n_failed} of"
    error_line(f"{what} {size} points failed (first: {first}); the errors are in "
               f"{out_dir}/sweep.nc (variable 'error', NaN results) and the tracebacks in "
               f"{out_dir}/points/*.json; re-running the command retries them")
    raise typer.Exit(1)


_SCHED_HELP = "Address of a running Dask scheduler (default: a local cluster)."
_TIMEOUT_HELP = "Seconds to wait for --scheduler to answer, > 0."
_OUT_HELP = ("Results folder: sweep.json, points/ (resumable) and sweep.nc; it belongs to one "
             "sweep (a different protocol is refused).")


@app.command()
@cli_errors
def sweep(
    protocol: str = typer.Argument(..., help="Protocol (TOML) with a [sweep] table of dotted "
                                   "keys and values (lists, {log = [a, b, n]}, {lin = ...})."),
    out_dir: str = typer.Option(..., "--out", help=_OUT_HELP),
    scheduler: str = typer.Option(None, "--scheduler", help=_SCHED_HELP),
    workers: int = typer.Option(None, "--workers", help="Local workers (default: one per core)."),
    yes: bool = typer.Option(False, "--yes", help="Allow grids larger than the stated limit."),
    linear: bool = typer.Option(False, "--linear", help="Linear stability per point "
                                "(stability.linear_summary) instead of simulating stick-slip."),
    connect_timeout: float = typer.Option(10.0, "--connect-timeout", help=_TIMEOUT_HELP),
) -> None:
    """Run a parameter grid on Dask: stick-slip summaries (default) or linear stability,
    written to OUT/sweep.nc. Re-running the same command resumes; exit code 1 if any point
    failed, 130 on Ctrl-C."""
    from .analysis.stickslip import stick_slip_summary
    from .theory.stability import linear_summary

    spec = _prepare_sweep(protocol, out_dir, yes, workers, scheduler, linear,
                                connect_timeout)
    runner = linear_summary if linear else stick_slip_summary
    resume = _resume_command("sweep", protocol, out_dir, scheduler, workers, yes, linear,
                             connect_timeout)
    ds = _run_with_bar(spec, runner, out_dir, scheduler, workers, yes,
                       source=protocol, protocol_text=_text_of(protocol),
                       connect_timeout=connect_timeout, resume=resume)
    out.print(f"wrote {out_dir}/sweep.nc: {spec.size} points, {ds.attrs['n_failed']} failed; "
              f"variables {', '.join(v for v in ds.data_vars if v != 'error')}",
              highlight=False, soft_wrap=True)
    _fail_if_points_failed(ds, out_dir)


@app.command("phase-diagram")
@cli_errors
def phase_diagram(
    protocol: str = typer.Argument(..., help="Spring protocol (TOML) whose [sweep] table "
                                   "sweeps drive.stiffness and drive.segments.<last>.velocity."),
    out_dir: str = typer.Option(..., "--out", help="Results folder: sweep.nc, "
                                "phase_diagram.png."),
    scheduler: str = typer.Option(None, "--scheduler", help=_SCHED_HELP),
    workers: int = typer.Option(None, "--workers", help="Local workers (default: one per core)."),
    yes: bool = typer.Option(False, "--yes", help="Allow grids larger than the stated limit."),
    connect_timeout: float = typer.Option(10.0, "--connect-timeout", help=_TIMEOUT_HELP),
) -> None:
    """The (K, V) stick-slip phase diagram: simulated classes over the linear K_c(V) line.
    Exit code 1 if any point failed, 130 on Ctrl-C (re-run to resume)."""
    import io as _io

    from .analysis.stickslip import CLASSES, phase_axes, stick_slip_summary
    from .io.files import atomic_write_bytes
    from .plots.runs import phase_diagram_figure
    from .plots.style import save_png

    spec = _prepare_sweep(protocol, out_dir, yes, workers, scheduler, False,
                                connect_timeout)
    k_key, v_key = phase_axes(spec)  # before any worker starts
    resume = _resume_command("phase-diagram", protocol, out_dir, scheduler, workers, yes,
                             False, connect_timeout)
    ds = _run_with_bar(spec, stick_slip_summary, out_dir, scheduler, workers, yes,
                       source=protocol, protocol_text=_text_of(protocol),
                       connect_timeout=connect_timeout, resume=resume)
    fig, _ = phase_diagram_figure(ds, spec.base, k_key, v_key)
    buf = _io.BytesIO()
    save_png(fig, buf)
    atomic_write_bytes(Path(out_dir) / "phase_diagram.png", buf.getvalue())
    counts = {}
    for c, name in CLASSES.items():
        n = int((ds["class"].values == c).sum()) if "class" in ds else 0
        if n:
            counts[name] = n
    out.print(f"wrote {out_dir}/sweep.nc, phase_diagram.png: "
              + ", ".join(f"{k} {v}" for k, v in counts.items())
              + f", failed {ds.attrs['n_failed']}", highlight=False, soft_wrap=True)
    _fail_if_points_failed(ds, out_dir)


@app.command()
@cli_errors
def compare(
    protocol: str = typer.Argument(..., help="Trap-model protocol file (TOML) with a velocity "
                                   "drive."),
    out: str = typer.Option(..., "--out", help="Results folder: compare.png, compare.json "
                            "(written whole or not at all)."),
    state_law: str = typer.Option("ageing", "--state-law", help="Twin's state law: ageing or "
                                  "slip."),
    json_out: bool = typer.Option(False, "--json", help="Print compare.json."),
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
) -> None:
    """Run a trap-model protocol and its fitted rate-and-state twin; draw both on one figure.

    The twin is fitted to the run itself when it starts in steady sliding at its first velocity
    and never holds, otherwise taken from the standard calibration (velocity steps and
    slide-hold-slide at the first sliding velocity). Reduced units.
    """
    from .analysis.rsf_view import compare_protocol
    from .io.files import check_output_dir, output_directory, write_json
    from .io.protocol import load_protocol
    from .plots.runs import comparison_figure
    from .plots.style import save_png
    from .validation import check_choice

    check_choice("state_law", state_law, ("ageing", "slip"))
    proto = load_protocol(protocol)
    check_output_dir(out, force=force, inputs=[protocol])
    c = compare_protocol(proto, state_law)
    report = {"protocol": protocol, **c.to_dict()}

    with output_directory(out, command="compare", force=force, inputs=[protocol],
                          report=say) as tmp:
        write_json(tmp / "compare.json", report)
        fig, _ = comparison_figure(c, Path(protocol).name)
        save_png(fig, tmp / "compare.png")
    brief = {k: v for k, v in report.items() if not isinstance(v, (dict, list))}
    brief.update({f"misfit_{k}": v for k, v in c.misfit.items()})
    emit(report if json_out else brief, json_out, f"compare {protocol} -> {out}")


def _simulate_rsf_protocol(proto: Any, protocol: str, out: str, json_out: bool,
                           force: bool) -> None:
    """``simulate`` for ``model.law = "rsf"``: the same three files, SI units."""
    import time
    from pathlib import Path

    from .io.files import output_directory, write_csv

    start = time.perf_counter()
    res = proto.run()
    context = {"wall_s": time.perf_counter() - start, "protocol": str(Path(protocol))}

    from .plots.runs import rsf_timeseries_figure
    from .plots.style import save_png

    with output_directory(out, command="simulate", force=force, inputs=[protocol],
                          report=say) as tmp:
        write_csv(tmp / "timeseries.csv", res.columns())
        summary = write_summary(tmp / "summary.json", res, context)
        fig, _ = rsf_timeseries_figure(res)
        save_png(fig, tmp / "timeseries.png")
    brief = {k2: v2 for k2, v2 in summary.items() if not isinstance(v2, dict)}
    emit(brief if not json_out else summary, json_out, f"simulate {protocol} -> {out} "
         "(rate-and-state, SI: t s, x m, v m/s, theta s)")


def main(argv: list[str] | None = None) -> int:
    """Console-script entry point: runs the app and returns the exit status.

    Click's usage errors (unknown option or command, missing or ill-typed value) become one
    line ``error: ...`` on standard error and status 2, like the library's own errors (Click
    would print a usage box). ``--help`` and a bare ``dryfriction`` still print the help.

    Ctrl-C and SIGTERM become exceptions, so every temporary file and folder is removed on the
    way out (status 130 and 143). An interrupt is never swallowed: one that a library swallowed
    (raised inside a finaliser, say) still turns a finished run's status 0 into 130.

    Parameters
    ----------
    argv : list of str, optional
        Arguments without the program name; default ``sys.argv[1:]``.
    """
    import signal

    interrupted: list[int] = []

    def on_sigint(signum: int, frame: Any) -> None:
        interrupted.append(signum)
        raise KeyboardInterrupt

    def on_sigterm(signum: int, frame: Any) -> None:
        interrupted.append(signum)
        raise SystemExit(128 + signum)

    signal.signal(signal.SIGINT, on_sigint)
    signal.signal(signal.SIGTERM, on_sigterm)
    try:
        code = _run(argv)
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else int(exc.code is not None)
    except KeyboardInterrupt:
        error_line("interrupted (Ctrl-C)")
        code = 130
    last = interrupted[-1] if interrupted else None
    if last == signal.SIGTERM or (last == signal.SIGINT and code == 0):
        error_line(f"interrupted ({'Ctrl-C' if last == signal.SIGINT else 'SIGTERM'})")
        code = 128 + last
    return code


def _run(argv: list[str] | None) -> int:
    """The app without Click's standalone mode: usage errors become one line."""
    try:
        rv = app(args=argv, prog_name="dryfriction", standalone_mode=False)
    except typer.Abort:  # Ctrl-C, as Click reports it
        error_line("interrupted (Ctrl-C)")
        return 130
    except typer.TyperException as exc:  # Click's exceptions (Typer vendors Click)
        ctx = getattr(exc, "ctx", None)
        if type(exc).__name__ == "NoArgsIsHelpError" and ctx is not None:
            print(ctx.get_help())
            return 2
        message = exc.format_message()  # type: ignore[attr-defined]
        if ctx is not None and getattr(exc, "exit_code", 1) == 2:
            message += f" (see {ctx.command_path} --help)"
        error_line(message)
        return int(getattr(exc, "exit_code", 1))
    # without standalone mode a command's typer.Exit(code) comes back as its code
    return rv if isinstance(rv, int) else 0


if __name__ == "__main__":
    raise SystemExit(main())
