"""Parameter sweeps on Dask and the stick-slip phase diagram."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import typer
import typer.core

from .common import (
    DPI_HELP,
    FORMAT_HELP,
    app,
    cli_errors,
    error_line,
    out,
    progress_bar,
    say_interrupted,
)

WORKERS_PER_CORE = 4
"""Most local workers per core (ours): more processes than that only wait for one another
and take memory each; a larger pool is a ``--scheduler``'s."""


def _prepare_sweep(protocol: str, out_dir: str, confirm: bool, workers: int | None,
                   scheduler: str | None = None, linear: bool = False,
                   connect_timeout: float = 10.0) -> Any:
    """Parse a sweep protocol and check every grid point before any worker starts (the
    ``[stickslip]`` table too, and, without ``linear``, everything the stick-slip runner would
    refuse at run time)."""
    import tomllib

    from ..io.files import check_writable_dir
    from ..io.protocol import spring_point
    from ..io.textfile import HEAD_BYTES, check_text
    from ..sweeps.sweep import MAX_POINTS, SWEEP_MODULES, parse_sweep
    from ..validation import require_extra

    require_extra("sweep", SWEEP_MODULES, "a sweep")  # before any work, like bad input
    path = Path(protocol)
    try:
        raw = path.read_bytes()
        check_text(raw[:HEAD_BYTES], str(path))
        text = raw.decode("utf-8")
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
    cores = os.cpu_count() or 1
    if workers is not None and workers > WORKERS_PER_CORE * cores:
        # ours: each local worker is a process of its own (~0.1-0.2 GB with NumPy and Numba);
        # --workers 100000 forked until the machine ran out, silently (issue 24, outside24)
        raise ValueError(f"--workers {workers} is out of range: allowed 1 to "
                         f"{WORKERS_PER_CORE * cores} ({WORKERS_PER_CORE} per core, {cores} "
                         "cores here; each worker is a process)")
    if workers is not None and scheduler is not None:
        raise ValueError("--workers is for the local cluster and --scheduler brings its own "
                         "workers: give one of the two")
    if not connect_timeout > 0:
        raise ValueError(f"--connect-timeout {connect_timeout:g} is out of range: allowed > 0")
    for _, ov in spec.points():
        point = spec.protocol(ov)
        where = f"{path} (point {', '.join(f'{k} = {v}' for k, v in ov.items())})"
        spring_point(point, where, "linear" if linear else "stick-slip")
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
                  protocol_text: str = "", connect_timeout: float = 10.0, resume: str = "",
                  variables: Any = None, outputs: Any = None) -> Any:
    """:func:`~dryfriction.sweeps.sweep.run_sweep` with a progress bar; Ctrl-C prints how many
    points are stored and the command that resumes, and exits with 130."""
    from ..sweeps.sweep import SweepInterrupted, run_sweep

    try:
        with progress_bar("sweep", spec.size, unit="points", delay=0.0) as update:
            return run_sweep(spec, runner, out_dir, scheduler=scheduler, n_workers=workers,
                             confirm=confirm, progress=update, source=source,
                             protocol_text=protocol_text, connect_timeout=connect_timeout,
                             variables=variables, outputs=outputs)
    except SweepInterrupted as exc:
        say_interrupted(f"{exc.stored} of {exc.total} points stored in {out_dir}; resume "
                        f"with: {resume}")
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
                                "(analysis.linear.linear_summary) instead of simulating "
                                "stick-slip."),
    connect_timeout: float = typer.Option(10.0, "--connect-timeout", help=_TIMEOUT_HELP),
) -> None:
    """Run a parameter grid on Dask: stick-slip summaries (default) or linear stability,
    written to OUT/sweep.nc. Re-running the same command resumes; exit code 1 if any point
    failed, 130 on Ctrl-C."""
    from ..analysis import linear as linear_analysis
    from ..analysis import stickslip

    spec = _prepare_sweep(protocol, out_dir, yes, workers, scheduler, linear,
                                connect_timeout)
    runner, variables = (
        (linear_analysis.linear_summary, linear_analysis.SWEEP_VARIABLES) if linear
        else (stickslip.stick_slip_summary, stickslip.SWEEP_VARIABLES))
    resume = _resume_command("sweep", protocol, out_dir, scheduler, workers, yes, linear,
                             connect_timeout)
    ds = _run_with_bar(spec, runner, out_dir, scheduler, workers, yes,
                       source=protocol, protocol_text=_text_of(protocol),
                       connect_timeout=connect_timeout, resume=resume, variables=variables)
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
    fmt: str = typer.Option("png", "--format", help=FORMAT_HELP),
    dpi: int = typer.Option(None, "--dpi", help=DPI_HELP),
) -> None:
    """The (K, V) stick-slip phase diagram: simulated classes over the linear K_c(V) line.
    Exit code 1 if any point failed, 130 on Ctrl-C (re-run to resume)."""
    import io as _io

    from ..analysis.stickslip import CLASSES, SWEEP_VARIABLES, phase_axes, stick_slip_summary
    from ..plots.runs import phase_diagram_figure
    from ..plots.style import save_figure
    from ..validation import check_figure_format

    fmt, dpi = check_figure_format(fmt, dpi)
    spec = _prepare_sweep(protocol, out_dir, yes, workers, scheduler, False,
                                connect_timeout)
    k_key, v_key = phase_axes(spec)  # before any worker starts
    resume = _resume_command("phase-diagram", protocol, out_dir, scheduler, workers, yes,
                             False, connect_timeout)

    def render(ds: Any) -> bytes:
        fig, _ = phase_diagram_figure(ds, spec.base, k_key, v_key)
        buf = _io.BytesIO()
        save_figure(fig, buf, fmt, dpi)
        return buf.getvalue()

    # written by the sweep under its folder's rule (an edited figure is never overwritten)
    ds = _run_with_bar(spec, stick_slip_summary, out_dir, scheduler, workers, yes,
                       source=protocol, protocol_text=_text_of(protocol),
                       connect_timeout=connect_timeout, resume=resume,
                       variables=SWEEP_VARIABLES, outputs={f"phase_diagram.{fmt}": render})
    counts = {}
    for c, name in CLASSES.items():
        n = int((ds["class"].values == c).sum()) if "class" in ds else 0
        if n:
            counts[name] = n
    out.print(f"wrote {out_dir}/sweep.nc, phase_diagram.{fmt}: "
              + ", ".join(f"{k} {v}" for k, v in counts.items())
              + f", failed {ds.attrs['n_failed']}", highlight=False, soft_wrap=True)
    _fail_if_points_failed(ds, out_dir)
