"""Parameter sweeps on Dask and the stick-slip phase diagram (``dryfriction sweep``,
``dryfriction phase-diagram``): the grid parsed and every point checked before any worker
starts, then :func:`dryfriction.sweeps.sweep.run_sweep` (resumable: the same call again goes on
where it stopped)."""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .options import FIGURE, OPTIONS, SWEEP

__all__ = ["sweep", "phase_diagram", "prepare_sweep", "protocol_text", "SweepOutcome",
           "WORKERS_PER_CORE"]

WORKERS_PER_CORE = 4
"""Most local workers per core (ours): more processes than that only wait for one another
and take memory each; a larger pool is a ``--scheduler``'s."""

@dataclass
class SweepOutcome:
    """A sweep written to its results folder.

    Attributes
    ----------
    out : Path
        The results folder (sweep.json, points/, sweep.nc, and the figure).
    files : list of str
        The results written at its top (sweep.nc, phase_diagram.{fmt}).
    dataset : xarray.Dataset
        What sweep.nc holds (failed points included: ``error``, NaN results).
    size, failed : int
        Points in the grid; points that failed (their errors in the dataset).
    classes : dict
        Phase diagram: class name -> number of points of that class.
    """

    out: Path
    files: list[str]
    dataset: Any
    size: int
    failed: int
    classes: dict[str, int] = field(default_factory=dict)


def _no_bar(label: str, total: float | None = None, unit: str = "", **kw: Any) -> Any:
    import contextlib

    return contextlib.nullcontext(lambda done, total=None, what=None: None)


def _run_sweep(spec: Any, runner: Any, out: str, bar: Callable[..., Any] | None, *,
               scheduler: str | None, workers: int | None, confirm: bool, source: str,
               connect_timeout: float, variables: Any, outputs: Any = None) -> Any:
    """:func:`~dryfriction.sweeps.sweep.run_sweep` under the progress bar ``bar``; Ctrl-C raises
    :class:`dryfriction.sweeps.sweep.SweepInterrupted` (how many points are stored)."""
    from ..sweeps.sweep import run_sweep

    with (bar or _no_bar)("sweep", spec.size, unit="points") as update:
        return run_sweep(spec, runner, out, scheduler=scheduler, n_workers=workers,
                         confirm=confirm, progress=update, source=source,
                         protocol_text=protocol_text(source),
                         connect_timeout=connect_timeout, variables=variables,
                         outputs=outputs)


def prepare_sweep(protocol: str, out_dir: str, confirm: bool, workers: int | None,
                  scheduler: str | None = None, linear: bool = False,
                  connect_timeout: float = 10.0) -> Any:
    """Parse a sweep protocol and check every grid point before any worker starts (the
    ``[stickslip]`` table too, and, without ``linear``, everything the stick-slip runner would
    refuse at run time)."""
    import tomllib

    from ..analysis.interface_sweep import interface_point
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
    interface = is_interface(spec)
    if interface and linear:
        raise ValueError(f"{path}: --linear is for spring protocols: an [interface] protocol's "
                         "sweep runs the chain and summarises its event catalogue")
    for _, ov in spec.points():
        point = spec.protocol(ov)
        where = f"{path} (point {', '.join(f'{k} = {v}' for k, v in ov.items())})"
        if interface:  # its refusals and its memory and time estimate, per point
            interface_point(point, where)
        else:
            spring_point(point, where, "linear" if linear else "stick-slip")
    check_writable_dir(out_dir)
    return spec


def is_interface(spec: Any) -> bool:
    """Whether a sweep's base protocol is an extended interface's (an ``[interface]`` table):
    its points run :func:`dryfriction.analysis.interface_sweep.interface_summary`."""
    return "interface" in spec.base


def protocol_text(protocol: str) -> str:
    """The protocol file's text, for the results folder's ``sweep.json`` (informative only:
    the sweep's identity is the hash of the parsed protocol)."""
    try:
        return Path(protocol).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return ""


def sweep(protocol: str | Path, out: str | Path, *,
          scheduler: str | None = SWEEP["scheduler"].default,
          workers: int | None = SWEEP["workers"].default, yes: bool = SWEEP["yes"].default,
          linear: bool = OPTIONS["sweep"]["linear"].default,
          connect_timeout: float = SWEEP["connect_timeout"].default,
          bar: Callable[..., Any] | None = None) -> SweepOutcome:
    """Run a protocol's ``[sweep]`` grid on Dask: stick-slip summaries
    (:func:`dryfriction.analysis.stickslip.stick_slip_summary`) or, with ``linear``, linear
    stability (:func:`dryfriction.analysis.linear.linear_summary`); for an ``[interface]``
    protocol, the statistics of each point's event catalogue
    (:func:`dryfriction.analysis.interface_sweep.interface_summary`). Written to
    ``out``/sweep.nc.

    Parameters
    ----------
    protocol : path
        Protocol (TOML) with a ``[sweep]`` table.
    out : path
        Results folder: it belongs to one sweep (a different protocol is refused); the same
        call again resumes.
    scheduler, workers, yes, connect_timeout : as ``--scheduler``, ``--workers``, ``--yes``,
        ``--connect-timeout`` (:data:`dryfriction.app.options.SWEEP`).
    linear : bool
        Linear stability per point instead of simulating stick-slip.
    bar : callable, optional
        A progress-bar factory ``bar(label, total, unit=...)`` (as
        :func:`dryfriction.app.records.fit_record`'s).

    Returns
    -------
    SweepOutcome
        ``failed`` > 0: some points failed (the command exits 1).

    Raises
    ------
    dryfriction.sweeps.sweep.SweepInterrupted
        Ctrl-C: the points computed so far are stored.
    """
    from ..analysis import interface_sweep, stickslip
    from ..analysis import linear as linear_analysis

    spec = prepare_sweep(str(protocol), str(out), yes, workers, scheduler, linear,
                         connect_timeout)
    runner, variables = (
        (interface_sweep.interface_summary, interface_sweep.SWEEP_VARIABLES)
        if is_interface(spec)
        else (linear_analysis.linear_summary, linear_analysis.SWEEP_VARIABLES) if linear
        else (stickslip.stick_slip_summary, stickslip.SWEEP_VARIABLES))
    ds = _run_sweep(spec, runner, str(out), bar, scheduler=scheduler, workers=workers,
                    confirm=yes, source=str(protocol), connect_timeout=connect_timeout,
                    variables=variables)
    return SweepOutcome(Path(out), ["sweep.nc"], ds, spec.size, int(ds.attrs["n_failed"]))


def phase_diagram(protocol: str | Path, out: str | Path, *,
                  scheduler: str | None = SWEEP["scheduler"].default,
                  workers: int | None = SWEEP["workers"].default,
                  yes: bool = SWEEP["yes"].default,
                  connect_timeout: float = SWEEP["connect_timeout"].default,
                  fmt: str = FIGURE["fmt"].default, dpi: int | None = FIGURE["dpi"].default,
                  bar: Callable[..., Any] | None = None) -> SweepOutcome:
    """The (K, V) stick-slip phase diagram: the sweep of a spring protocol over
    ``drive.stiffness`` and ``drive.segments.<last>.velocity``, its simulated classes drawn
    over the linear K_c(V) line (phase_diagram.{fmt}, written with sweep.nc under the sweep's
    rule: an edited figure is never overwritten).

    Parameters
    ----------
    protocol, out, scheduler, workers, yes, connect_timeout, bar : as :func:`sweep`.
    fmt, dpi : the figure's format and resolution (``--format``, ``--dpi``).

    Returns
    -------
    SweepOutcome
        ``classes``: how many points fell in each class.
    """
    import io

    from ..analysis.stickslip import CLASSES, SWEEP_VARIABLES, phase_axes, stick_slip_summary
    from ..plots.runs import phase_diagram_figure
    from ..plots.style import save_figure
    from ..validation import check_figure_format

    fmt, dpi = check_figure_format(fmt, dpi)
    spec = prepare_sweep(str(protocol), str(out), yes, workers, scheduler, False,
                         connect_timeout)
    if is_interface(spec):
        raise ValueError(f"{protocol}: the phase diagram is the spring slider's (K, V) plane: "
                         "sweep an [interface] protocol with 'dryfriction sweep'")
    k_key, v_key = phase_axes(spec)  # before any worker starts

    def render(ds: Any) -> bytes:
        fig, _ = phase_diagram_figure(ds, spec.base, k_key, v_key)
        buf = io.BytesIO()
        save_figure(fig, buf, fmt, dpi)
        return buf.getvalue()

    figure = f"phase_diagram.{fmt}"
    ds = _run_sweep(spec, stick_slip_summary, str(out), bar, scheduler=scheduler,
                    workers=workers, confirm=yes, source=str(protocol),
                    connect_timeout=connect_timeout, variables=SWEEP_VARIABLES,
                    outputs={figure: render})
    counts = {}
    for c, name in CLASSES.items():
        n = int((ds["class"].values == c).sum()) if "class" in ds else 0
        if n:
            counts[name] = n
    return SweepOutcome(Path(out), ["sweep.nc", figure], ds, spec.size,
                        int(ds.attrs["n_failed"]), counts)
