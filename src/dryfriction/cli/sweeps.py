"""Parameter sweeps on Dask and the stick-slip phase diagram."""

from __future__ import annotations

from typing import Any

import typer
import typer.core

from ..app.options import FIGURE, OPTIONS
from ..app.options import SWEEP as _SW
from .common import (
    DPI_HELP,
    FORMAT_CHOICES,
    FORMAT_HELP,
    app,
    cli_errors,
    error_line,
    out,
    progress_bar,
    say_interrupted,
)


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
    if connect_timeout != _SW["connect_timeout"].default:
        args += ["--connect-timeout", f"{connect_timeout:g}"]
    args += ["--yes"] * yes + ["--linear"] * linear
    return shlex.join(args)


def _interrupted(exc: Any, out_dir: str, resume: str) -> None:
    """Ctrl-C in a sweep: how many points are stored and the command that resumes; exit 130."""
    say_interrupted(f"{exc.stored} of {exc.total} points stored in {out_dir}; resume "
                    f"with: {resume}")
    raise typer.Exit(130) from None


def _bar(label: str, total: float | None = None, unit: str = "") -> Any:
    return progress_bar(label, total, unit=unit, delay=0.0)


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
    scheduler: str = typer.Option(_SW["scheduler"].default, "--scheduler", help=_SCHED_HELP),
    workers: int = typer.Option(_SW["workers"].default, "--workers",
                                help="Local workers (default: one per core)."),
    yes: bool = typer.Option(_SW["yes"].default, "--yes",
                             help="Allow grids larger than the stated limit."),
    linear: bool = typer.Option(OPTIONS["sweep"]["linear"].default, "--linear",
                                help="Linear stability per point "
                                "(analysis.linear.linear_summary) instead of simulating "
                                "stick-slip."),
    connect_timeout: float = typer.Option(_SW["connect_timeout"].default,
                                         "--connect-timeout", help=_TIMEOUT_HELP),
) -> None:
    """Run a parameter grid on Dask: stick-slip summaries (default) or linear stability,
    written to OUT/sweep.nc. Re-running the same command resumes; exit code 1 if any point
    failed, 130 on Ctrl-C."""
    from ..app.sweeps import sweep as run
    from ..sweeps.sweep import SweepInterrupted

    try:
        done = run(protocol, out_dir, scheduler=scheduler, workers=workers, yes=yes,
                   linear=linear, connect_timeout=connect_timeout, bar=_bar)
    except SweepInterrupted as exc:
        _interrupted(exc, out_dir, _resume_command("sweep", protocol, out_dir, scheduler,
                                                   workers, yes, linear, connect_timeout))
    ds = done.dataset
    out.print(f"wrote {out_dir}/sweep.nc: {done.size} points, {done.failed} failed; "
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
    scheduler: str = typer.Option(_SW["scheduler"].default, "--scheduler", help=_SCHED_HELP),
    workers: int = typer.Option(_SW["workers"].default, "--workers",
                                help="Local workers (default: one per core)."),
    yes: bool = typer.Option(_SW["yes"].default, "--yes",
                             help="Allow grids larger than the stated limit."),
    connect_timeout: float = typer.Option(_SW["connect_timeout"].default,
                                         "--connect-timeout", help=_TIMEOUT_HELP),
    fmt: str = typer.Option(FIGURE["fmt"].default, "--format", metavar=FORMAT_CHOICES,
                            help=FORMAT_HELP),
    dpi: int = typer.Option(FIGURE["dpi"].default, "--dpi", help=DPI_HELP),
) -> None:
    """The (K, V) stick-slip phase diagram: simulated classes over the linear K_c(V) line.
    Exit code 1 if any point failed, 130 on Ctrl-C (re-run to resume)."""
    from ..app.sweeps import phase_diagram as run
    from ..sweeps.sweep import SweepInterrupted

    try:
        done = run(protocol, out_dir, scheduler=scheduler, workers=workers, yes=yes,
                   connect_timeout=connect_timeout, fmt=fmt, dpi=dpi, bar=_bar)
    except SweepInterrupted as exc:
        _interrupted(exc, out_dir, _resume_command("phase-diagram", protocol, out_dir,
                                                   scheduler, workers, yes, False,
                                                   connect_timeout))
    ds = done.dataset
    out.print(f"wrote {out_dir}/" + ", ".join(done.files) + ": "
              + ", ".join(f"{k} {v}" for k, v in done.classes.items())
              + f", failed {done.failed}", highlight=False, soft_wrap=True)
    _fail_if_points_failed(ds, out_dir)
