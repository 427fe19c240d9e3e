"""What an extended-interface run writes besides its own files: the
space-time fields, the event catalogue, the fronts, the precursor curve and four figures
(:mod:`dryfriction.analysis.fronts`, :mod:`dryfriction.analysis.catalogue`,
:mod:`dryfriction.plots.fronts`).

Files, in the folder given (a results folder being staged by
:func:`dryfriction.io.files.output_directory`):

* ``fields.nc`` (or ``fields.npz`` without xarray, with a one-line note): slip rate, slip,
  stress and load against time, with their units;
* ``events.csv``: the catalogue, one row per event, headers ``name[unit]``;
* ``fronts.csv``: every front's arrival time and local speed at each element it reached;
* ``precursors.csv`` (side loading): arrested-front length against the load-to-normal ratio;
* ``spacetime.{fmt}``, ``front_speed.{fmt}``, ``magnitude_frequency.{fmt}`` and, for side
  loading, ``precursors.{fmt}``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["interface_outputs", "space_time_figure", "front_speed_figure",
           "precursor_figure", "magnitude_frequency_figure"]


# the figures as functions that import matplotlib when called (as app/runs.py's)
def space_time_figure(*args: Any, **kwargs: Any) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.fronts.space_time_figure`."""
    from ..plots.fronts import space_time_figure as build

    return build(*args, **kwargs)


def front_speed_figure(st: Any, events: Any, sound_speed: float = math.nan
                       ) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.fronts.front_speed_figure`, the chain's sound speed drawn where
    it is known."""
    from ..plots.fronts import front_speed_figure as build

    known = math.isfinite(sound_speed) and sound_speed > 0
    return build(st, events, reference_speed=sound_speed if known else None,
                 reference_label=r"sound speed $\sqrt{k_c/m}$")


def precursor_figure(*args: Any, **kwargs: Any) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.fronts.precursor_figure`."""
    from ..plots.fronts import precursor_figure as build

    return build(*args, **kwargs)


def magnitude_frequency_figure(*args: Any, **kwargs: Any) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.fronts.magnitude_frequency_figure`."""
    from ..plots.fronts import magnitude_frequency_figure as build

    return build(*args, **kwargs)


def _draw_here(builder: Callable[..., Any], *args: Any, path: Any, fmt: str,
               dpi: int | None) -> None:
    from ..plots.style import save_figure

    fig, _ = builder(*args)
    save_figure(fig, path, fmt, dpi)


def interface_outputs(result: Any, folder: str | Path, *, threshold: float | None = None,
                      figure: bool = True, fmt: str = "png", dpi: int | None = None,
                      draw: Callable[..., None] | None = None, half_window: int = 3,
                      min_elements: int = 1, transient: float = 0.0, edge_gap: int = 1,
                      fields: bool = True
                      ) -> tuple[list[str], list[str], dict[str, Any]]:
    """Analyse an interface run and write its files into ``folder`` (module doc).

    Parameters
    ----------
    result : InterfaceResult
        The run (:class:`dryfriction.ensemble.interface_result.InterfaceResult`).
    folder : path
        Existing folder to write into (a staged results folder).
    threshold : float, optional
        Slip-rate threshold of the fronts [``a0/t0``] (default
        :func:`~dryfriction.analysis.fronts.default_threshold`: 10 x the loading velocity).
    figure, fmt, dpi, draw : as :func:`dryfriction.app.runs.simulate`.
    half_window : int
        Half-width of the local front-speed fit, in elements.
    min_elements : int
        Smallest event kept, in elements (2 drops the one-element slips of a block ringing
        on its own).
    transient : float
        Events that start before this time [``t0``] are left out of the precursor curve (the
        relaxation of the initial state); the catalogue keeps them.
    edge_gap : int
        Elements next to the loaded edge that may creep below the threshold while an event
        starts beside them (:func:`~dryfriction.analysis.catalogue.precursors`; 1: the edge
        block, which the edge spring keeps creeping).
    fields : bool
        Write ``fields.nc`` (False where the caller writes the fields itself).

    Returns
    -------
    files : list of str
        Names written.
    notes : list of str
        One line each for the user (the fields written as .npz, no event found, ...).
    summary : dict
        Counts and answers for summary.json: events, spanning, threshold, precursor trend,
        front regimes, and a ``units`` object declaring every number's unit.
    """
    from ..analysis.catalogue import (
        catalogue_columns,
        front_regimes,
        magnitude_frequency,
        precursor_trend,
        precursors,
    )
    from ..analysis.fronts import (
        detect_events,
        event_threshold,
        from_result,
        interface_loaded_edge,
        interface_normal_load,
        interface_sound_speed,
        speed_unit,
    )
    from ..io.files import write_csv
    from ..io.spacetime import write_fields
    from ..validation import check_figure_format, check_scalar

    fmt, dpi = check_figure_format(fmt, dpi)
    transient = check_scalar("transient", transient, 0.0)
    thr = event_threshold(result, threshold)
    folder = Path(folder)
    draw = draw or _draw_here
    st = from_result(result)
    u = st.units
    events = detect_events(st, thr, half_window=half_window, min_elements=min_elements)
    files: list[str] = []
    notes: list[str] = []

    if fields:
        arrays = {"slip_rate": result.slip_rate, "slip": result.slip, "stress": result.stress,
                  "load": result.load}
        written = write_fields(folder / "fields.nc", result.t, result.x, arrays,
                               {**u, "stress": u.get("stress", "F_el per element")},
                               attrs={"threshold": thr, "threshold_units": u["slip_rate"]})
        files.append(written.path.name)
        if written.note:
            notes.append(written.note)
    write_csv(folder / "events.csv", *catalogue_columns(events, st, thr))
    files.append("events.csv")
    rows: dict[str, list[float]] = {k: [] for k in ("event", "direction", "x", "t", "speed",
                                                    "low", "high")}
    for e in events:
        for f in e.fronts:
            for k in range(f.x.size):
                for key, val in zip(rows, (e.index, f.direction, f.x[k], f.t[k], f.speed[k],
                                           f.speed_low[k], f.speed_high[k]), strict=True):
                    rows[key].append(val)
    v = speed_unit(u)
    write_csv(folder / "fronts.csv", {
        "event": np.asarray(rows["event"], int), "direction": np.asarray(rows["direction"], int),
        "x": np.asarray(rows["x"]), "t_arrival": np.asarray(rows["t"]),
        "speed": np.asarray(rows["speed"]), "speed_low": np.asarray(rows["low"]),
        "speed_high": np.asarray(rows["high"])},
        {"event": "1 (index)", "direction": "1 (+1 or -1)", "x": u["x"], "t_arrival": u["t"],
         "speed": v, "speed_low": v, "speed_high": v})
    files.append("fronts.csv")

    c_s = interface_sound_speed(result)
    summary: dict[str, Any] = {
        "events": len(events), "spanning": sum(e.spanning for e in events),
        "threshold": thr, "sound_speed": c_s,
        # every number's unit, by key (the JSON convention of dryfriction.io.units)
        "units": {"events": "1", "spanning": "1", "threshold": u["slip_rate"],
                  "sound_speed": v, "slow": "1", "fast": "1", "undetermined": "1",
                  "after": u["t"], "edge_gap": "1", "n": "1", "rho": "1", "p_value": "1",
                  "alpha": "1", "alpha_err": "1"},
    }
    if not events:
        notes.append(f"no slip event: no element's slip rate exceeded the threshold {thr:g} "
                     f"{u['slip_rate']}")
    if math.isfinite(c_s) and c_s > 0:
        reg = front_regimes(events, c_s)
        summary["fronts"] = {r: reg.count(r) for r in ("slow", "fast", "undetermined")}
    edge = interface_loaded_edge(result)
    pre = trend = None
    if edge is not None:
        pre = precursors(events, st, interface_normal_load(result), edge=edge,
                         edge_gap=edge_gap, after=transient)
        write_csv(folder / "precursors.csv",
                  {"event": pre.events, "load_ratio": pre.ratio, "length": pre.length,
                   "t_arrest": pre.t_arrest},
                  {"event": "1 (index)", "load_ratio": "1", "length": u["x"],
                   "t_arrest": u["t"]})
        files.append("precursors.csv")
        trend = precursor_trend(pre)
        summary["precursors"] = {"after": transient, "edge_gap": edge_gap, "n": trend.n,
                                 "rho": trend.rho, "p_value": trend.p_value,
                                 "grow_with_load": trend.grows}
    mf = magnitude_frequency([e.moment for e in events])
    summary["moment_exponent"] = {"alpha": mf.alpha, "alpha_err": mf.alpha_err, "n": mf.n_fit}
    if figure:
        jobs: list[tuple[str, Callable[..., Any], tuple[Any, ...]]] = [
            ("spacetime", space_time_figure, (st, events, thr)),
            ("front_speed", front_speed_figure, (st, events, c_s)),
            ("magnitude_frequency", magnitude_frequency_figure, (mf, st)),
        ]
        if pre is not None:
            jobs.append(("precursors", precursor_figure, (pre, st, trend)))
        for name, builder, args in jobs:
            draw(builder, *args, path=folder / f"{name}.{fmt}", fmt=fmt, dpi=dpi)
            files.append(f"{name}.{fmt}")
    return files, notes, summary
