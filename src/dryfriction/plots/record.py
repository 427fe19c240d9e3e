"""The figure of a laboratory record as the step finder read it (``record.png``):
the load-point velocity (a smoothed estimate, light) with the load program drawn on it, friction
and normal stress against time below; each step and hold shaded and numbered as in the table,
sampling-rate changes, gaps, resets and normal-stress changes marked."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.figure import Figure

from .style import FRICTION_SI

if TYPE_CHECKING:
    from ..records.detection import Detection
    from ..records.lab import LabRecord, Segment

__all__ = ["RecordFigure", "plot_record", "smoothed_velocity"]

TITLE_WIDTH = 0.92
"""The widest title line of ``record.png``, a fraction of the figure's width (ours: the
text's measured width runs about 4 % under what Agg draws)."""

LABEL_LINES = 4
"""The lines the segments' numbers stand on below the top of the velocity panel (ours: 9 pt
apart, four take 37 pt of the panel's 165)."""

LABEL_EM = 0.64
"""A label's width per character, in ems (ours: DejaVu Sans' digits are 0.636 em, its
letters and space narrower): what the line a label takes is judged by, before drawing."""

MARGINS = {"left": 0.09, "right": 0.98}
"""The panels' left and right edges, figure fractions: set before the labels are placed (their
widths in data units depend on the panel's width) and again with the title's room."""

TITLE_LINES = 6
"""The most lines ``record.png``'s title takes (ours: six lines, 1.3 in of a figure of at
least 5.4 in, leave each panel its room)."""


def _wrap(text: str, fontsize: float, width: float) -> list[str]:
    """``text``'s lines, each cut where it is wider than ``width`` points at ``fontsize`` (its
    width measured on the font, :class:`matplotlib.textpath.TextToPath`): after the last
    space or ``/`` that leaves at least half of the line, else within a word (a long path has
    no space)."""
    from matplotlib.font_manager import FontProperties
    from matplotlib.textpath import TextToPath

    prop, measure = FontProperties(size=fontsize), TextToPath()

    def wide(part: str) -> float:
        return measure.get_text_width_height_descent(part, prop, ismath=False)[0]

    out: list[str] = []
    for line in text.split("\n"):
        while line and wide(line) > width:
            lo, hi = 1, len(line)  # the longest head that fits: lo fits, hi does not
            while hi - lo > 1:
                mid = (lo + hi) // 2
                lo, hi = (mid, hi) if wide(line[:mid]) <= width else (lo, mid)
            cut = max(line.rfind(" ", 0, lo + 1), line.rfind("/", 0, lo) + 1)
            cut = cut if cut >= max(lo // 2, 1) else lo  # never an empty head
            out.append(line[:cut].rstrip())
            line = line[cut:].lstrip()
        out.append(line)
    return out


@dataclass
class RecordFigure:
    """What :func:`plot_record` drew, for a reader (or a test) to check.

    Attributes
    ----------
    panels : list of str
        The panels' names, top to bottom (``velocity``, ``friction``, ``normal``).
    shaded : list of int
        The table's segment numbers that were shaded (each step and hold).
    marks : dict
        Kind (``rate change``, ``gap``, ``reset``, ``normal change``) -> times marked, s.
    artists : dict
        Panel -> the matplotlib artists of the shading.
    unplaced : list of int
        The segments whose start the record does not place within the larger of one sample
        and 0.5 s (95 %): numbered with a ``*``, as in the table, and said in the title.
    """

    panels: list[str]
    shaded: list[int]
    marks: dict[str, list[float]] = field(default_factory=dict)
    artists: dict[str, list[Any]] = field(default_factory=dict)
    unplaced: list[int] = field(default_factory=list)


def smoothed_velocity(t: np.ndarray, x: np.ndarray, width: float, breaks: bool = False
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Load-point velocity (m/s) as the slope of ``x`` over consecutive windows of ``width``
    s (least squares in each: the sampling may vary), at the windows' mean times; windows of
    fewer than 3 samples left out. With ``breaks``, a NaN (time and velocity) stands between
    the windows either side of each gap (no sample for longer than ``width``), so that a line
    drawn through them breaks where the record has no velocity to show, instead of a
    straight line across."""
    w = np.floor((t - t[0]) / width).astype(np.int64)
    nw = int(w[-1]) + 1
    n = np.bincount(w, minlength=nw).astype(float)
    tc = t - t[0]
    st, sx = np.bincount(w, tc, nw), np.bincount(w, x - x[0], nw)
    stt, stx = np.bincount(w, tc * tc, nw), np.bincount(w, tc * (x - x[0]), nw)
    with np.errstate(divide="ignore", invalid="ignore"):
        var = stt / n - (st / n) ** 2
        v = (stx / n - st * sx / n**2) / var
    ok = (n >= 3) & (var > 0)
    tv, vv = t[0] + st[ok] / n[ok], v[ok]
    if breaks:
        # a gap: no sample for longer than a window (a window dropped for want of samples
        # in jittered sampling is none, and drew a dashed line: found by review)
        gap = np.flatnonzero(np.diff(t) > width)
        at = np.unique(np.searchsorted(tv, 0.5 * (t[gap] + t[gap + 1])))
        at = at[(at > 0) & (at < tv.size)]
        tv, vv = np.insert(tv, at, np.nan), np.insert(vv, at, np.nan)
    return tv, vv


def _unassessed(s: object) -> bool:
    """Whether a segment not placed has no interval (its change's time not assessed)."""
    return not np.isfinite(getattr(s, "start_lo", 0.0))


def plot_record(record: LabRecord, segments: tuple[Segment, ...] | list[Segment],
                detection: Detection | None = None, x: np.ndarray | None = None,
                given: bool = False, note: str | None = None) -> tuple[Figure, RecordFigure]:
    """Draw the record and its load program.

    Parameters
    ----------
    record : LabRecord
        The record (SI).
    segments : sequence of Segment
        Its load program, numbered as in the table
        (:func:`~dryfriction.records.lab.segments_table`).
    detection : Detection, optional
        What the detector found besides (marks); ``None`` for a program given by hand.
    x : array, optional
        Load-point displacement, m (resets taken out); default from the record, its resets
        taken out by :func:`~dryfriction.records.detection.find_resets`.
    given : bool
        The program was given with ``--segments`` (said in the title).
    note : str, optional
        One more line for the title (a unit assumed for want of one in the header).

    Returns
    -------
    Figure, RecordFigure
    """
    from ..records.artifacts import gap_intervals
    from ..records.detection import displacement, find_resets

    t = np.asarray(record.time, float)
    t0 = float(t[0])
    if x is None:
        # a displacement transducer's resets taken out as the detector takes them out: a
        # re-zeroing is no velocity, and its jump drew a spike the user would read as one
        x = displacement(record)
        if record.load_point is not None:
            x = find_resets(t, x)[0]
    has_normal = record.normal_stress is not None
    names = ["velocity", "friction"] + (["normal"] if has_normal else [])
    fig = Figure(figsize=(10.0, 2.3 * len(names) + 0.8))
    axes = fig.subplots(len(names), 1, sharex=True)
    info = RecordFigure(panels=names, shaded=[], artists={n: [] for n in names})
    span = float(t[-1] - t0)
    # three of the slower samples to a window (ours): with the median interval, the slow side
    # of a sampling-rate change (zoo 44052: 0.2 s jittered before, 0.02 s after) had windows of
    # fewer than 3 samples, left out, and no velocity drawn there; the 99th percentile leaves
    # out gaps as long as they are under 1 % of the intervals
    width = max(span / 400.0, 3.0 * float(np.quantile(np.diff(t), 0.99)))
    tv, v = smoothed_velocity(t, x, width, breaks=True)  # no line across a gap
    ax = axes[0]
    ax.plot(tv - t0, v * 1e6, color="0.6", lw=0.8, alpha=0.7,
            label=f"load-point velocity (slope over {width:.3g} s)")
    for s in segments:
        ax.plot([s.t_start - t0, s.t_end - t0], [s.velocity * 1e6] * 2, color="C3", lw=1.8)
    ax.plot([], [], color="C3", lw=1.8, label="load program" + (" (--segments)" if given
                                                                  else " (detected)"))
    ax.set_ylabel("velocity  [µm/s]")
    speeds = [abs(s.velocity) for s in segments if s.velocity != 0.0]
    if speeds and max(speeds) / min(speeds) > 30.0:
        # the linear range to the decade at or below the slowest speed: the ticks are 0 and
        # whole decades, one decade's height apart (at the slowest speed itself, 0.008 um/s,
        # the labels 1e-3, 0 and -1e-3 fell inside it and were drawn over each other)
        ax.set_yscale("symlog", linthresh=10.0 ** np.floor(np.log10(min(speeds) * 1e6)))
    vmax = max(speeds or [1e-6]) * 1e6
    if ax.get_yscale() == "linear":  # the smoothed velocity's spikes do not set the scale
        ax.set_ylim(-0.15 * vmax, 1.5 * vmax)
    axes[1].scatter(t - t0, record.friction, s=1.0, color="0.35", linewidths=0,
                    rasterized=True)
    axes[1].set_ylabel(FRICTION_SI)
    if has_normal:
        unit, scale = ("MPa", 1e-6) if record.normal_unit == "Pa" else ("kN", 1e-3)
        # no line across a gap, as the velocity above (an outside user's records)
        dt = np.diff(t)
        cut = np.flatnonzero((dt > width) | gap_intervals(dt, float(np.median(dt)))) + 1
        axes[2].plot(np.insert(t - t0, cut, np.nan),
                     np.insert(np.asarray(record.normal_stress, float) * scale, cut, np.nan),
                     color="C0", lw=0.8)
        axes[2].set_ylabel(f"normal {'stress' if unit == 'MPa' else 'force'}  [{unit}]")
        axes[2].ticklabel_format(axis="y", useOffset=False)  # 30.002, not +3e1 and 0.002
    # each step and hold shaded and numbered as in the table (segment 0 is where it starts);
    # a label goes on the highest of LABEL_LINES lines where the last label ends before it
    # starts, so that short segments' labels do not print over each other; with every line
    # taken, on the line whose last label ends first (ours: the first forms cycled through
    # three lines, or took a label's width for 3 % of the span: "1 hold" is twice that)
    fig.subplots_adjust(**MARGINS)  # the final widths (below), for per_pt
    lo_x, hi_x = ax.get_xlim()
    per_pt = (hi_x - lo_x) / (ax.get_position().width * fig.get_figwidth() * 72.0)
    ends = np.full(LABEL_LINES, -np.inf)
    for j, s in enumerate(segments):
        if j == 0 and s.velocity != 0.0:
            continue
        prev = segments[j - 1].velocity if j else None
        if prev is not None and prev == s.velocity:
            continue  # a boundary set by the normal stress alone
        hold = s.velocity == 0.0
        info.shaded.append(j)
        end, k = s.t_end, j + 1
        while hold and k < len(segments) and segments[k].velocity == 0.0:
            end, k = segments[k].t_end, k + 1  # a hold split by a normal change: one hold
        for name, a in zip(names, axes, strict=True):
            info.artists[name].append(a.axvspan(s.t_start - t0, end - t0,
                                                color="C0" if hold else "C2",
                                                alpha=0.12 if hold else 0.08, lw=0))
        if not s.start_placed:
            info.unplaced.append(j)
        mark = "" if s.start_placed else "?" if _unassessed(s) else "*"
        text = f"{j}{mark}" + (" hold" if hold else "")
        x0 = s.t_start - t0 + 2.0 * per_pt  # the label's left edge (2 pt right of its change)
        free = np.flatnonzero(ends <= x0)
        level = int(free[0]) if free.size else int(np.argmin(ends))
        ends[level] = x0 + (LABEL_EM * 8.0 * len(text) + 2.0) * per_pt
        ax.annotate(text, (s.t_start - t0, 1.0),
                    xycoords=("data", "axes fraction"), xytext=(2, -10 - 9 * level),
                    textcoords="offset points", fontsize=8)
    marks = {"rate change": list(detection.rate_changes) if detection else [],
             "gap": list(detection.gaps) if detection else [],
             "reset": list(detection.resets) if detection else [],
             "normal change": list(detection.normal_changes) if detection else []}
    styles = {"rate change": ("C1", ":"), "gap": ("k", "--"), "reset": ("C4", "-."),
              "normal change": ("C0", "--")}
    for kind, times in marks.items():
        color, ls = styles[kind]
        for k, tm in enumerate(times):
            for a in axes:
                a.axvline(tm - t0, color=color, ls=ls, lw=0.9,
                          label=kind if (k == 0 and a is ax) else None)
    info.marks = {k: [float(v) for v in vs] for k, vs in marks.items() if vs}
    # above the top panel, not in it: inside, it hid the number of a step starting early
    # in the record (a new user's segment 1 at 60 s of 200 s)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), fontsize=7, ncol=6,
              frameon=False, borderaxespad=0.1)
    axes[-1].set_xlabel(f"time from the first sample  [s]  (t0 = {t0:g} s)")
    n_steps = sum(1 for j in info.shaded if segments[j].velocity != 0.0)
    n_holds = len(info.shaded) - n_steps
    unassessed = [j for j in info.unplaced if _unassessed(segments[j])]
    placed_not = [j for j in info.unplaced if j not in unassessed]
    # the notes (a sign changed, a unit assumed) before the lists of segments: a cut title
    # keeps its first lines, and the lists are whole in the table (review helper-89)
    title = (f"{record.source}: {len(segments)} segments, {n_steps} velocity change(s), "
             f"{n_holds} hold(s); shaded and numbered as in segments.csv"
             + (f"\n{note}" if note else "")
             + ("\n* change time not placed within max(0.5 s, one sample) (95 % interval "
                f"in segments.csv): segment(s) {', '.join(map(str, placed_not))}"
                if placed_not else "")
             + ("\n? change time not assessed (no interval: too few samples beside it): "
                f"segment(s) {', '.join(map(str, unassessed))}" if unassessed else ""))
    # each line wrapped to the figure's width (a long path was cut at its edges), the
    # panels lowered by the lines it takes
    lines = _wrap(title, 9.0, TITLE_WIDTH * 72.0 * fig.get_figwidth())
    if len(lines) > TITLE_LINES:  # the panels keep their room (800 unplaced segments
        # listed took it all: found by review); the table has them all
        lines = lines[:TITLE_LINES - 1] + ["... (title cut: the table and segments.csv "
                                           "list every segment)"]
    fig.suptitle("\n".join(lines), fontsize=9)
    top = 1.0 - (0.62 + 0.14 + 0.16 * (len(lines) - 1)) / fig.get_figheight()
    fig.subplots_adjust(**MARGINS, bottom=0.08, top=top, hspace=0.08)
    return fig, info
