"""The workflows that run a history and write a results folder: :func:`simulate`,
:func:`compare`, :func:`reproduce` (the commands of the same names)."""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from .options import OPTIONS
from .outcome import RunOutcome

__all__ = ["simulate", "compare", "reproduce", "draw_here", "Draw", "Progress"]

Draw = Callable[..., None]
"""A figure drawer. ``draw(builder, *args, path=path, fmt=fmt, dpi=dpi)`` builds a figure
with ``builder(*args)`` (a function returning ``(fig, axes)``) and saves it; the command line
passes its painter's (:func:`dryfriction.cli.painter.draw_figure`), which draws in a process forked
before the command's imports."""
Progress = Callable[..., None]
Report = Callable[[str], None]

_SIM = OPTIONS["simulate"]
_CMP = OPTIONS["compare"]
_REP = OPTIONS["reproduce"]


def draw_here(builder: Callable[..., Any], *args: Any, path: Any, fmt: str,
              dpi: int | None) -> None:
    """The default :data:`Draw`: build and save the figure in this process."""
    from ..plots.style import save_figure

    fig, _ = builder(*args)
    save_figure(fig, path, fmt, dpi)


# the figures as functions that import matplotlib when called (a painter, forked before the
# command's imports, receives them by module and name: cli.painter)
def timeseries_figure(result: Any) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.runs.timeseries_figure` (a trap-model run)."""
    from ..plots.runs import timeseries_figure as build

    return build(result)


def rsf_timeseries_figure(result: Any) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.runs.rsf_timeseries_figure` (a rate-and-state protocol)."""
    from ..plots.runs import rsf_timeseries_figure as build

    return build(result)


def comparison_figure(c: Any, title: str = "") -> tuple[Any, Any]:
    """:func:`dryfriction.plots.runs.comparison_figure` (``compare``)."""
    from ..plots.runs import comparison_figure as build

    return build(c, title)


def _summary(result: Any, context: dict[str, Any]) -> dict[str, Any]:
    """What summary.json holds: the run's own summary plus its context (protocol, wall time),
    its ``units`` declaring every number (:mod:`dryfriction.io.units`)."""
    from ..io.units import SUMMARY_UNITS, with_units

    summary = {**result.summary(), **context}
    return with_units(summary, SUMMARY_UNITS[summary["law"]])


def simulate(protocol: str | Path, out: str | Path, *, force: bool = _SIM["force"].default,
             fmt: str = _SIM["fmt"].default, dpi: int | None = _SIM["dpi"].default,
             figure: bool = _SIM["figure"].default, progress: Progress | None = None,
             report: Report | None = None, draw: Draw | None = None,
             on_start: Callable[[Any], None] | None = None) -> RunOutcome:
    """Run a protocol file and write its results folder (``dryfriction simulate``).

    A trap-model protocol writes timeseries.csv, summary.json, timeseries.{fmt} and one
    ``snapshot_*.csv`` per snapshot (reduced units); a rate-and-state one (``model.law =
    "rsf"``) the first three, in SI units. Every check (protocol, folder, figure format) runs
    before any work; the folder is written whole or not at all
    (:func:`dryfriction.io.files.output_directory`).

    Parameters
    ----------
    protocol : path
        The protocol file (TOML, :mod:`dryfriction.io.protocol`).
    out : path
        Results folder: new, empty, or written by this program before.
    force, fmt, dpi, figure : as the command's ``--force``, ``--format``, ``--dpi``,
        ``--figure/--no-figure`` (defaults :data:`.options.FIGURE`).
    progress : callable, optional
        ``progress(percent)`` during a trap-model run.
    report : callable, optional
        ``report(line)`` for what was done to files already in ``out``.
    draw : callable, optional
        How figures are drawn (:data:`Draw`); default in this process.
    on_start : callable, optional
        ``on_start(protocol)`` after every check, before the run (the command line's notice
        that the solvers compile first).

    Returns
    -------
    RunOutcome
        ``partial`` True where Ctrl-C stopped a trap-model run: the samples so far were
        written, marked ``"partial": true`` in summary.json.
    """
    from ..io.files import check_output_dir, output_directory, write_csv, write_json
    from ..io.protocol import InterfaceProtocol, RSFProtocol, load_protocol
    from ..io.units import SNAPSHOT_UNITS
    from ..validation import check_figure_format

    fmt, dpi = check_figure_format(fmt, dpi)
    proto = load_protocol(protocol)  # every check before any work
    check_output_dir(out, force=force, command="simulate")
    if on_start is not None:
        on_start(proto)
    if isinstance(proto, InterfaceProtocol):
        return _simulate_interface(proto, protocol, out, force=force, report=report,
                                   fmt=fmt, dpi=dpi, figure=figure, draw=draw)
    draw = draw or draw_here
    context: dict[str, Any] = {"protocol": str(Path(protocol))}
    notes: list[str] = []
    if isinstance(proto, RSFProtocol):
        start = time.perf_counter()
        result = proto.run()
        context = {"wall_s": time.perf_counter() - start, **context}
        builder: Callable[..., Any] = rsf_timeseries_figure
    else:
        def step(fraction: float) -> None:
            if progress is not None:
                progress(100.0 * fraction)

        result = proto.run(progress=step, on_interrupt="partial")
        builder = timeseries_figure
    files = ["timeseries.csv", "summary.json"]
    summary = _summary(result, context)
    with output_directory(out, command="simulate", force=force, inputs=[protocol],
                          report=report) as tmp:
        write_csv(tmp / "timeseries.csv", result.columns(), summary["units"])
        write_json(tmp / "summary.json", summary)
        if figure:
            draw(builder, result, path=tmp / f"timeseries.{fmt}", fmt=fmt, dpi=dpi)
            files.append(f"timeseries.{fmt}")
        for i, snap in enumerate(getattr(result, "snapshots", ())):
            cols = {k: v for k, v in snap.items() if k not in ("t", "x")}
            name = f"snapshot_{i:03d}_t{snap['t']:.6g}.csv"
            write_csv(tmp / name, cols, SNAPSHOT_UNITS)
            files.append(name)
    late = getattr(result, "info", {}).get("snapshots_not_reached")
    if late:
        notes.append(f"note: the run ended at t = {float(result.t[-1]):g} t0 (runaway), "
                     f"before the snapshot time(s) {', '.join(f'{s:g}' for s in late)}: "
                     "not written")
    return RunOutcome(Path(out), files, summary, result, notes,
                      partial=bool(getattr(result, "partial", False)),
                      units="SI" if isinstance(proto, RSFProtocol) else "reduced")


INTERFACE_FILES: tuple[str, ...] = ("fields.npz", "load.csv", "summary.json")
"""What ``simulate`` writes for an ``[interface]`` protocol besides the catalogue and the
figures of :func:`dryfriction.app.interface_outputs.interface_outputs` (``events.csv``,
``fronts.csv``, ``precursors.csv`` under side loading, the space-time map and the other
figures): the space-time fields (``t``, ``x``, ``slip``, ``slip_rate``, ``stress``, ``load``,
``load_point`` and the energy terms, NumPy's ``.npz``), the loading and the energy balance over
time as CSV, and the summary (units of every field in ``summary.json``'s ``units``; the
catalogue's counts and answers under ``fronts``)."""


def _simulate_interface(proto: Any, protocol: str | Path, out: str | Path, *, force: bool,
                        report: Report | None, fmt: str, dpi: int | None, figure: bool,
                        draw: Draw | None) -> RunOutcome:
    """The ``simulate`` workflow of an ``[interface]`` protocol (:data:`INTERFACE_FILES`)."""
    import numpy as np

    from ..io.files import output_directory, write_csv, write_json
    from ..io.units import INTERFACE_LOAD_UNITS, INTERFACE_SUMMARY_UNITS, with_units
    from .interface_outputs import interface_outputs

    start = time.perf_counter()
    result = proto.run(on_interrupt="partial")
    context = {"wall_s": time.perf_counter() - start, "protocol": str(Path(protocol))}
    summary = with_units({**result.summary(), **context}, INTERFACE_SUMMARY_UNITS)
    files = list(INTERFACE_FILES)
    with output_directory(out, command="simulate", force=force, inputs=[protocol],
                          report=report) as tmp:
        with open(tmp / "fields.npz", "wb") as fh:
            np.savez_compressed(fh, t=result.t, x=result.x, slip=result.slip,
                                slip_rate=result.slip_rate, stress=result.stress,
                                load=result.load, load_point=result.load_point,
                                **result.energy)
        write_csv(tmp / "load.csv", {"t": result.t, "load": result.load,
                                     "load_point": result.load_point,
                                     "mean_slip": result.slip.mean(axis=1),
                                     "max_slip_rate": result.slip_rate.max(axis=1),
                                     **result.energy,
                                     "energy_residual": result.energy_residual()},
                  INTERFACE_LOAD_UNITS)
        more, notes, fronts = interface_outputs(result, tmp, fmt=fmt, dpi=dpi, figure=figure,
                                                draw=draw, fields=False)
        files += more
        # the catalogue's counts and answers, their units declared beside the run's own
        summary = {**summary, "fronts": {k: v for k, v in fronts.items() if k != "units"},
                   "units": {**fronts.get("units", {}), **summary["units"]}}
        write_json(tmp / "summary.json", summary)
    notes = ["note: the fields are in fields.npz (units in summary.json)", *notes]
    return RunOutcome(Path(out), files, summary, result, notes, partial=result.partial,
                      units="reduced")


def compare(protocol: str | Path, out: str | Path, *,
            state_law: str = _CMP["state_law"].default, force: bool = _CMP["force"].default,
            fmt: str = _CMP["fmt"].default, dpi: int | None = _CMP["dpi"].default,
            figure: bool = _CMP["figure"].default, report: Report | None = None,
            draw: Draw | None = None, on_start: Callable[[Any], None] | None = None,
            progress: Progress | None = None) -> RunOutcome:
    """Run a trap-model protocol and its fitted rate-and-state twin; write compare.json and
    compare.{fmt} (``dryfriction compare``;
    :func:`dryfriction.analysis.rsf_view.compare_protocol`).

    Parameters
    ----------
    protocol : path
        Trap-model protocol file (TOML) with a velocity drive.
    out : path
        Results folder (written whole or not at all).
    state_law : str
        The twin's state law: ageing or slip (``--state-law``).
    force, fmt, dpi, figure, report, draw, on_start : as :func:`simulate`.
    progress : callable, optional
        ``progress(percent, 100, stage)``: the trap model's run, then its twin.

    Returns
    -------
    RunOutcome
        ``summary``: what compare.json holds; ``result``: the comparison.
    """
    from ..analysis.rsf_view import compare_protocol
    from ..io.files import check_output_dir, output_directory, write_json
    from ..io.protocol import load_protocol
    from ..io.units import COMPARE_UNITS, with_units
    from ..validation import check_choice, check_figure_format

    check_choice("--state-law", state_law, ("ageing", "slip"))
    fmt, dpi = check_figure_format(fmt, dpi)
    proto = load_protocol(protocol)
    check_output_dir(out, force=force, command="compare")
    if on_start is not None:
        on_start(proto)
    c = compare_protocol(proto, state_law, progress=progress)
    comparison = c.to_dict()
    # the words of the unit system beside the units object (dryfriction.io.units)
    summary = with_units({"protocol": str(protocol), "unit_system": comparison.pop("units"),
                          **comparison}, COMPARE_UNITS)
    files = ["compare.json"]
    with output_directory(out, command="compare", force=force, inputs=[protocol],
                          report=report) as tmp:
        write_json(tmp / "compare.json", summary)
        if figure:
            (draw or draw_here)(comparison_figure, c,
                                Path(protocol).name, path=tmp / f"compare.{fmt}", fmt=fmt,
                                dpi=dpi)
            files.append(f"compare.{fmt}")
    return RunOutcome(Path(out), files, summary, c)


def reproduce(out: str | Path, *, force: bool = _REP["force"].default,
              fmt: str = _REP["fmt"].default, dpi: int | None = _REP["dpi"].default,
              progress: Callable[[int, int, str], None] | None = None,
              report: Report | None = None) -> RunOutcome:
    """The paper's six figures, three extra panels, the data behind them, summary.json and
    report.html (``dryfriction reproduce``; :func:`dryfriction.plots.report.reproduce`, which
    draws them in a pool of processes).

    Parameters
    ----------
    out : path
        Results folder: new, empty, or written by this program before; checked before
        matplotlib is imported.
    force, fmt, dpi, report : as :func:`simulate`.
    progress : callable, optional
        ``progress(done, total, what)`` after each file.

    Returns
    -------
    RunOutcome
        ``summary``: what summary.json holds (``dieterich_C_asymptotic``, ...).
    """
    from ..io.files import check_output_dir
    from ..validation import check_figure_format

    fmt, dpi = check_figure_format(fmt, dpi)
    # a bad --out fails before matplotlib is imported
    check_output_dir(out, force=force, command="reproduce")
    from ..plots.report import DATA_FILES, EXTRA_FILES, FIGURE_FILES
    from ..plots.report import reproduce as run

    summary = run(out, progress, force=force, report=report, fmt=fmt, dpi=dpi)
    files = [f.replace(".png", f".{fmt}") for f in (*FIGURE_FILES, *EXTRA_FILES)]
    return RunOutcome(Path(out), [*files, *DATA_FILES], summary)
