"""The load program of a laboratory record and its velocity steps (used through :mod:`.lab`).

:func:`.detection.detect_segments` finds the piecewise-constant load-point velocities and holds
from the displacement, :func:`parse_segments` reads them from the ``--segments`` form, and
:func:`slice_steps` cuts the record into the windows of its velocity steps and slide-hold-slide
cycles, as one would choose them by hand.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..rsf.law import V_MAX, V_MIN
from ..validation import Array
from .record import LabRecord

__all__ = [
    "PLACED_P",
    "Segment",
    "StepWindow",
    "make_segments",
    "parse_segments",
    "segments_table",
    "write_segments_csv",
    "SEGMENTS_SYNTAX",
    "load_velocity_series",
    "slice_steps",
    "no_steps_message",
    "example_segments",
    "normal_change_values",
    "normal_change_text",
]

PLACED_P = 0.9
"""A change is *placed* when the probability that it lies within its tolerance of its reported time
(:func:`.placement.placed_probability`: the profile likelihood widened by
:data:`.placement.WIDEN`, as the interval) is at least this (ours; chosen on zoo records
150-449: 0.9 marked all 13 times off by more than their tolerance and 85 of the 537 within it,
where the interval's width marked 165; on records 5000-5299, run once, 18 of the 19 off and 91
of the 528 within, the width 19 and 172: ``python -m benchmarks bench_detect_bound``). Zoo
record 5230, a restart after a hold sampled at 0.8 Hz, placed 2.6 s early with its interval on
the other side, was marked placed at this level."""


@dataclass(frozen=True)
class Segment:
    """One stretch of the load program at a constant load-point velocity.

    Attributes
    ----------
    t_start, t_end : float
        Start and end, s, in the record's own time.
    velocity : float
        Load-point velocity, m/s (``0``: a hold).
    i_start, i_end : int
        The samples ``[i_start, i_end)`` of the record it covers.
    confidence : float
        Of the change at its start: the velocity difference over the scatter the apparatus'
        fluctuations give it (:mod:`.detection`); NaN for the first segment, one given by
        ``--segments``, or a boundary set by a normal-stress change alone.
    normal : float
        Mean normal stress (Pa) or force (N) over it; NaN without a normal column.
    start_lo, start_hi : float
        95 % interval of the time of the change at its start, s, in the record's own time
        (:func:`.placement.change_profile`); NaN where none was computed (as ``confidence``).
    start_edge : bool
        That interval reaches the end of the times searched for the change: the record does
        not place it there (the interval is a lower bound on the uncertainty).
    start_placed : bool
        The record places the change: the probability ``start_p`` is at least
        :data:`PLACED_P` (and the interval is not at the edge). ``False``: the time
        is uncertain beyond the tolerance (the table and segments.csv say so); ``False``
        too for a detected velocity change whose interval could not be computed (not
        assessed: ``start_lo`` NaN). True at the first segment, at a boundary set by a
        normal-stress change alone, and for a program given with ``--segments``.
    start_p : float
        The probability that the change lies within the larger of one sample and
        :data:`.detection.PLACE_TOL` of ``t_start`` (:func:`.placement.placed_probability`);
        NaN where no interval was computed, and where it reaches the end of the times
        searched (``start_edge``: the probability over those times alone overstates it).
    """

    t_start: float
    t_end: float
    velocity: float
    i_start: int
    i_end: int
    confidence: float = float("nan")
    normal: float = float("nan")
    start_lo: float = float("nan")
    start_hi: float = float("nan")
    start_edge: bool = False
    start_placed: bool = True
    start_p: float = float("nan")

    @property
    def duration(self) -> float:
        """``t_end - t_start``, s."""
        return self.t_end - self.t_start


def make_segments(t: Array, bounds: list[int], vel: list[float]) -> tuple[Segment, ...]:
    """Segments over the samples ``bounds[j]:bounds[j+1]`` with velocities ``vel`` (m/s)."""
    n = len(t)
    return tuple(Segment(float(t[a]), float(t[b]) if b < n else float(t[-1]), float(v), a, b)
                 for a, b, v in zip(bounds[:-1], bounds[1:], vel, strict=True))


def parse_segments(text: str, record: LabRecord) -> tuple[Segment, ...]:
    """The load program given by hand: ``"0:2e-7,1200:2e-6,2400:0,2500:2e-7"``.

    Each item is ``start:velocity``: the start in seconds *from the record's first sample*
    (so the first item starts at 0) and the load-point velocity in m/s from there until the
    next start (0: a hold). Starts must increase and lie within the record.

    Raises
    ------
    ValueError
        Naming the item and the file.
    """
    if not text.strip(" ,"):  # an empty option is no program, not "detect it"
        raise ValueError("--segments is empty: give the load program as start:velocity items "
                         "(s from the record's start : m/s), e.g. 0:2e-7,1200:2e-6, or leave "
                         "the option out to detect it")
    t = np.asarray(record.time)
    src, dur = record.source, float(t[-1] - t[0])
    starts: list[float] = []
    vel: list[float] = []
    items = [s.strip() for s in text.split(",")]
    if len(items) > 1 and not items[-1]:
        items.pop()  # one trailing comma: nothing lost
    for item in items:
        if not item:  # a comma with no item before it: an item lost in editing, not nothing
            raise ValueError(f"--segments {text!r}: an empty item (a comma with nothing "
                             "before it, or two in a row): give start:velocity items "
                             "separated by single commas, e.g. 0:2e-7,1200:2e-6")
        a, sep, b = item.partition(":")
        try:
            s, v = float(a), float(b)
        except ValueError:
            s = v = float("nan")
        if not sep or not (np.isfinite(s) and np.isfinite(v)):
            raise ValueError(f"--segments {item!r}: expected start:velocity (s from the "
                             "record's start : m/s), e.g. 0:2e-7,1200:2e-6")
        # the fits' own ranges (SeriesData: v_load >= 0; RateState: V0 <= V_MAX), here so
        # that record shows what fit would refuse, before any work
        if v != 0.0 and not V_MIN <= v <= V_MAX:
            raise ValueError(f"--segments {item!r}: velocity {v:g} m/s is out of range: allowed "
                             f"0 (a hold) or {V_MIN:g} to {V_MAX:g} m/s (the load point moves "
                             "forward)")
        if not 0.0 <= s < dur:
            raise ValueError(f"--segments {item!r}: start {s:g} s is outside {src} (0 to "
                             f"{dur:g} s from its first sample)")
        if starts and s <= starts[-1]:
            raise ValueError(f"--segments {item!r}: starts must increase (previous "
                             f"{starts[-1]:g} s)")
        starts.append(s)
        vel.append(v)
    if not starts or starts[0] != 0.0:
        raise ValueError(f"--segments {text!r}: the first segment must start at 0 (the "
                         f"record's first sample, t = {t[0]:g} s in {src})")
    idx = [int(i) for i in np.searchsorted(t - t[0], starts, side="left")] + [len(t)]
    for j in range(1, len(starts)):
        if idx[j] == idx[j + 1] or idx[j] == idx[j - 1]:
            raise ValueError(f"--segments: the segment starting at {starts[j]:g} s holds no "
                             f"sample of {src}")
    segs = list(make_segments(t, idx, vel))
    # the normal load over each segment, as detection reports it (segments.csv, the table)
    sn = None if record.normal_stress is None else np.asarray(record.normal_stress, float)
    # a given start falls between samples: keep the time the user wrote
    segs = [Segment(float(t[0]) + s, g.t_end if j == len(segs) - 1 else float(t[0]) +
                    starts[j + 1], g.velocity, g.i_start, g.i_end,
                    normal=float(np.mean(sn[g.i_start:g.i_end])) if sn is not None
                    else float("nan"))
            for j, (s, g) in enumerate(zip(starts, segs, strict=True))]
    return tuple(segs)


def _normal_column(normal_unit: str) -> tuple[str, str, float]:
    """What the normal column holds, its unit and the factor from the record's SI value:
    stress in Pa -> MPa, force in N -> kN (the record's ``normal_unit``, "Pa" or "N")."""
    if normal_unit == "N":
        return "normal force", "kN", 1e-3
    return "normal stress", "MPa", 1e-6


def normal_change_values(segments: tuple[Segment, ...] | list[Segment],
                         times: tuple[float, ...] | list[float]
                         ) -> tuple[tuple[float, float, float], ...]:
    """``(time, before, after)`` of each normal-stress change at ``times`` (s, record time; a
    segment boundary, :class:`.detection.Detection`'s ``normal_changes``): the mean normal
    stress (Pa) or force (N) of the segments either side of the boundary there."""
    starts = np.array([s.t_start for s in segments])
    out = []
    for tc in times:
        k = int(np.argmin(np.abs(starts - tc))) if len(starts) else 0
        if k > 0:
            out.append((float(tc), segments[k - 1].normal, segments[k].normal))
    return tuple(out)


def normal_change_text(changes: tuple[tuple[float, float, float], ...] | list[
                       tuple[float, float, float]], normal_unit: str = "Pa") -> str:
    """``"t = 70 s: 5 -> 7 MPa"`` for each ``(time, before, after)``, in the unit of the
    segments table (MPa for a stress, kN for a force: ``normal_unit`` "Pa" or "N")."""
    _, nu, scale = _normal_column(normal_unit)
    return "; ".join(f"t = {t:g} s: {b * scale:.4g} -> {a * scale:.4g} {nu}"
                     for t, b, a in changes)


def segments_table(segments: tuple[Segment, ...] | list[Segment],
                   normal_unit: str = "Pa") -> str:
    """The load program as a fixed-width table (times in s, velocities in m/s and um/s, the
    confidence of the change at each start, the mean normal stress in MPa or, for a record
    whose ``normal_unit`` is "N", the normal force in kN)."""
    what, nu, scale = _normal_column(normal_unit)
    lines = [f"{'#':>3} {'t_start (s)':>13} {'95 % (s)':>15} {'t_end (s)':>13} "
             f"{'duration (s)':>12} {'velocity (m/s)':>14} {'(um/s)':>10} {'samples':>8} "
             f"{'confidence':>10} {'normal (' + nu + ')':>12}"]
    unplaced, unassessed, edge = [], [], []
    for j, s in enumerate(segments):
        kind = "  hold" if s.velocity == 0.0 else ""
        conf = "-" if not np.isfinite(s.confidence) else f"{s.confidence:.3g}"
        normal = "-" if not np.isfinite(s.normal) else f"{s.normal * scale:.4g}"
        iv = ("-" if s.start_placed else "?") if not np.isfinite(s.start_lo) else (
            f"-{s.t_start - s.start_lo:.2g}/+{s.start_hi - s.t_start:.2g}"
            + ("" if s.start_placed else "*"))
        if not s.start_placed:
            (unassessed if not np.isfinite(s.start_lo) else edge if s.start_edge
             else unplaced).append(str(j))
        lines.append(f"{j:>3} {s.t_start:>13.6g} {iv:>15} {s.t_end:>13.6g} "
                     f"{s.duration:>12.6g} {s.velocity:>14.4e} {s.velocity * 1e6:>10.4g} "
                     f"{s.i_end - s.i_start:>8d} {conf:>10} {normal:>12}{kind}")
    lines.append("confidence: the velocity change at the segment's start over the scatter the "
                 f"apparatus' fluctuations give it; 95 %: the interval of its time about "
                 f"t_start; normal: mean {what}, {nu}")
    if unplaced:
        lines.append(f"* segment(s) {', '.join(unplaced)}: the record does not place the "
                     "change within the larger of one sample and 0.5 s (probability below "
                     f"{100 * PLACED_P:.0f} %, t_start_p in segments.csv); its time is "
                     "uncertain by the interval shown: give it with --segments if known")
    if edge:
        lines.append(f"* segment(s) {', '.join(edge)}: the likelihood of the change's time "
                     "reaches the end of the times searched for it, so the record does not "
                     "place it (its interval is at least the times searched; no t_start_p in "
                     "segments.csv): give it with --segments if known")
    if unassessed:
        lines.append(f"? segment(s) {', '.join(unassessed)}: the time of the change was not "
                     "assessed (too few samples beside it, e.g. at a gap, to compute an "
                     "interval): check it in record.png and give it with --segments if known")
    return "\n".join(lines)


SEGMENTS_SYNTAX = (
    "The load program as comma-separated START:VELOCITY items: START in s from the record's "
    "first sample (the first item starts at 0; starts increase and lie inside the record), "
    "VELOCITY the load-point velocity in m/s from there to the next START (0: a "
    f"hold, or {V_MIN:g} to {V_MAX:g}: the load point moves forward; a record whose "
    "displacement decreases is read with its sign changed). E.g. 0:2e-7,1200:2e-6 (0.2 "
    "um/s, then 2 um/s from 1200 s); "
    "0:1e-5,100:0,130:1e-5 (a 30-s hold). The table of the 'record' command and its "
    "segments.csv give the detected program in this form to edit.")
"""The full syntax of ``--segments`` (its CLI help)."""


def segments_spec(segments: tuple[Segment, ...] | list[Segment], t0: float,
                  time: Array | None = None) -> str:
    """The program in the ``--segments`` form (starts in s from ``t0``, the first sample).

    With the record's ``time``, each start is the shortest decimal that
    :func:`parse_segments` maps back to the same first sample: at most the sample's own time
    and above the sample before it (a new user was given ``139.99998`` for a change at a
    sample 2e-5 s before 140 s; rounding up to 140 would move it one sample later)."""
    def start(s: Segment) -> str:
        x = s.t_start - t0
        if time is None or not 0 < s.i_start < len(time):
            return f"{x:.10g}"
        x = float(time[s.i_start]) - t0
        prev = float(time[s.i_start - 1]) - t0
        for d in range(11):
            y = math.floor(x * 10**d) / 10**d
            if prev < y <= x:
                return f"{y:.{d}f}".rstrip("0").rstrip(".") if d else f"{y:.0f}"
        return f"{x:.10g}"

    return ",".join(f"{start(s)}:{s.velocity:.6g}" for s in segments)


def write_segments_csv(path: object, segments: tuple[Segment, ...] | list[Segment], t0: float,
                       normal_unit: str = "Pa", time: Array | None = None,
                       notes: Sequence[str] = ()) -> None:
    """Write the load program as CSV, one row per segment, units in the headers
    (``name[unit]``, :mod:`dryfriction.io.units`); the ``--segments`` form of the whole
    program in a comment line on top. ``t_start_lo[s]`` and ``t_start_hi[s]`` are the 95 %
    interval of the change at the segment's start (record time; empty where none was
    computed), ``t_start_p`` the probability that the change lies within the larger of one
    sample and 0.5 s of ``t_start`` (empty too where the interval reaches the end of the times
    searched: :attr:`Segment.start_edge`) and ``t_start_placed`` whether that is at least
    :data:`PLACED_P` (:class:`Segment`; "not assessed" for a detected change with no
    interval). With the record's ``time``, the ``--segments`` line
    gives each start as its shortest decimal (:func:`segments_spec`). Each of ``notes`` (e.g.
    a unit assumed for want of one in the header) is a comment line under it."""
    from ..io.units import SEGMENT_UNITS, header

    what, _, scale = _normal_column(normal_unit)
    names = ("segment", "kind", "t_start", "t_end", "t_from_first", "duration", "velocity",
             "velocity_um", "i_start", "i_end", "samples", "confidence", "t_start_lo",
             "t_start_hi", "t_start_placed", "t_start_p", what.replace(" ", "_"))
    rows = [f"# --segments {segments_spec(segments, t0, time)}",
            *(f"# {n}" for n in notes), ",".join(header(n, SEGMENT_UNITS[n]) for n in names)]
    for j, s in enumerate(segments):
        prev = segments[j - 1].velocity if j else None
        kind = ("hold" if s.velocity == 0.0 else "start" if j == 0 else
                "normal change" if prev == s.velocity else "step")
        conf = "" if not np.isfinite(s.confidence) else f"{s.confidence:.4g}"
        normal = "" if not np.isfinite(s.normal) else f"{s.normal * scale:.6g}"
        has = np.isfinite(s.start_lo)
        p = f"{s.start_p:.3f}" if np.isfinite(s.start_p) else ""
        iv = (f"{s.start_lo:.9g},{s.start_hi:.9g},{'yes' if s.start_placed else 'no'},{p}"
              if has else ",,," if s.start_placed else ",,not assessed,")
        rows.append(f"{j},{kind},{s.t_start:.9g},{s.t_end:.9g},{s.t_start - t0:.9g},"
                    f"{s.duration:.9g},{s.velocity:.6e},{s.velocity * 1e6:.6g},{s.i_start},"
                    f"{s.i_end},{s.i_end - s.i_start},{conf},{iv},{normal}")
    with open(path, "w", encoding="utf-8") as fh:  # type: ignore[call-overload]
        fh.write("\n".join(rows) + "\n")


def load_velocity_series(record: LabRecord, segments: tuple[Segment, ...]) -> Array:
    """The load-point velocity at each sample (m/s), from the segments, for ``SeriesData``.

    Raises
    ------
    ValueError
        If the segments do not cover the record's samples exactly once, in order.
    """
    n = len(record.time)
    v = np.empty(n)
    i = 0
    for s in segments:
        if s.i_start != i or s.i_end <= s.i_start:
            raise ValueError(f"{record.source}: the segments do not cover the record in order "
                             f"(a segment starts at sample {s.i_start}, expected {i})")
        v[s.i_start:s.i_end] = s.velocity
        i = s.i_end
    if i != n:
        raise ValueError(f"{record.source}: the segments end at sample {i}, the record has {n}")
    return v


# ------------------------------------------------------------------------------ steps
@dataclass(frozen=True)
class StepWindow:
    """The samples of one velocity step or slide-hold-slide cycle, as one would cut it by hand.

    Attributes
    ----------
    index : int
        Position in the record (0, 1, ...).
    kind : str
        ``"step"`` (a velocity change) or ``"shs"`` (slide, hold, slide).
    i_start, i_end : int
        The record's samples ``[i_start, i_end)``: steady sliding before the change, up to
        the next change after it.
    t_change : float
        Time of the change (the start of the hold for ``"shs"``), s, record time.
    v_before, v_after : float
        Load-point velocities before and after (after the hold for ``"shs"``), m/s.
    hold : float
        Hold duration, s (0 for a step).
    t_change_lo, t_change_hi : float
        95 % interval of ``t_change``, s (:class:`Segment`'s ``start_lo``, ``start_hi``); NaN
        where none was computed.
    normal_changes : tuple of (float, float, float)
        The normal-stress changes inside the hold of an ``"shs"`` window (a segment boundary
        at which the load point stays at rest): ``(time, before, after)``, s and the record's
        normal unit (Pa, or N for a force; the segments' means either side). The hold runs
        across them: ``hold`` is the whole time at rest.
    """

    index: int
    kind: str
    i_start: int
    i_end: int
    t_change: float
    v_before: float
    v_after: float
    hold: float
    t_change_lo: float = float("nan")
    t_change_hi: float = float("nan")
    normal_changes: tuple[tuple[float, float, float], ...] = ()


def slice_steps(
    record: LabRecord,
    segments: tuple[Segment, ...],
    *,
    pre_slip: float = 50e-6,
    pre_fraction: float = 0.5,
    given: bool = False,
) -> tuple[StepWindow, ...]:
    """Cut a record into its velocity steps and slide-hold-slide cycles.

    Each window starts before the change by ``pre_slip`` of load-point travel at the velocity
    before (enough steady sliding to pin the level), but by no more than ``pre_fraction`` of
    the segment before, and ends at the next change after it. A hold at the start or at the
    end of the record (no sliding before it, or none after) gives no window. Consecutive
    segments at rest are one hold (a normal-stress change during a hold is a segment
    boundary): its duration is the whole time at rest, the time a contact ages, and
    the window runs on to the end of the reslide; the changes are in ``normal_changes``.

    Parameters
    ----------
    record : LabRecord
        The record the segments describe.
    segments : tuple of Segment
        Its load program (:func:`detect_segments` or :func:`parse_segments`).
    pre_slip : float
        Load-point displacement before the change, m, ``> 0``.
    pre_fraction : float
        Largest part of the segment before the change to include, ``0 < pre_fraction <= 1``.
    given : bool
        The program was given by hand (``--segments``): the refusal does not send the user
        back to ``--segments`` (:func:`no_steps_message`).

    Raises
    ------
    ValueError
        If the load program holds no step and no hold (naming the file).
    """
    if not (np.isfinite(pre_slip) and pre_slip > 0.0):
        raise ValueError(f"pre_slip = {pre_slip:g} is out of range: allowed finite and > 0")
    if not 0.0 < pre_fraction <= 1.0:
        raise ValueError(f"pre_fraction = {pre_fraction:g} is out of range: allowed > 0 and "
                         "<= 1")
    t = np.asarray(record.time)
    segs = list(segments)
    out: list[StepWindow] = []
    j = 1
    while j < len(segs):
        prev, cur = segs[j - 1], segs[j]
        if prev.velocity == 0.0 or cur.velocity == prev.velocity:
            j += 1
            continue
        lead = min(pre_fraction * prev.duration, pre_slip / abs(prev.velocity))
        i0 = min(int(np.searchsorted(t, cur.t_start - lead, side="left")), cur.i_start - 1)
        i0 = max(i0, prev.i_start)
        if cur.velocity != 0.0:
            out.append(StepWindow(len(out), "step", i0, cur.i_end, cur.t_start, prev.velocity,
                                  cur.velocity, 0.0, cur.start_lo, cur.start_hi))
            j += 1
        else:
            m = j + 1  # the hold runs on across boundaries at rest (normal-stress changes)
            while m < len(segs) and segs[m].velocity == 0.0:
                m += 1
            if m == len(segs):
                break  # a final hold: nothing slides after it
            after = segs[m]
            changes = tuple((segs[k].t_start, segs[k - 1].normal, segs[k].normal)
                            for k in range(j + 1, m))
            out.append(StepWindow(len(out), "shs", i0, after.i_end, cur.t_start,
                                  prev.velocity, after.velocity, after.t_start - cur.t_start,
                                  cur.start_lo, cur.start_hi, changes))
            j = m + 1
    if not out:
        raise ValueError(no_steps_message(record, segs, given=given))
    return tuple(out)


def no_steps_message(record: LabRecord, segments: tuple[Segment, ...] | list[Segment], *,
                     given: bool = False) -> str:
    """The one line for a load program with no velocity step and no hold followed by sliding
    (:func:`slice_steps`): what the program is, and, for a detected one, the ``--segments``
    that would give a step, built from the record's own times and speed
    (:func:`example_segments`); a program given by hand is not sent back to ``--segments``."""
    segs = list(segments)
    vs = ", ".join(f"{s.velocity:.3g}" for s in segs)
    # no window leaves at most one sliding velocity (two differ: a step, or a hold between)
    what = ("a one-velocity record has no velocity step to fit"
            if all(s.velocity != 0.0 for s in segs) else
            "the load point does not move (a hold throughout): no step to fit"
            if all(s.velocity == 0.0 for s in segs) else
            "one sliding velocity and a hold with no sliding on one side: no step to fit")
    head = (f"{record.source}: no velocity step or hold in the load program"
            f"{' given with --segments' if given else ''} ({len(segs)} segment(s), "
            f"velocities {vs} m/s): {what}")
    if given:
        return head
    return (head + "; if its program did change, give it with --segments, e.g. "
            + example_segments(record, segs[0].velocity if segs else 0.0))


def example_segments(record: LabRecord, velocity: float) -> str:
    """An example ``--segments`` value for ``record`` that :func:`parse_segments` accepts: its
    own speed ``velocity`` (m/s; 1 um/s if it is 0 or out of range) from its first sample,
    then ten times that from about half-way (ours: a form to edit, inside the record's own
    time, not a guess at its program)."""
    t = np.asarray(record.time, float)
    v = abs(float(velocity))
    if not (V_MIN <= v and 10.0 * v <= V_MAX):
        v = 1e-6
    half = float(f"{0.5 * float(t[-1] - t[0]):.3g}")  # rounded: a value a user types
    return (f"0:{v:.3g},{half:g}:{10.0 * v:.3g} ({v * 1e6:.3g} um/s, then "
            f"{10.0 * v * 1e6:.3g} um/s from {half:g} s after the first sample)")
