"""The load program of a laboratory record and its velocity steps (used through :mod:`.lab`).

:func:`detect_segments` finds the piecewise-constant load-point velocities and holds from the
displacement, :func:`parse_segments` reads them from the ``--segments`` form, and
:func:`slice_steps` cuts the record into the windows of its velocity steps and slide-hold-slide
cycles, as one would choose them by hand.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..rsf.law import V_MAX, V_MIN
from ..validation import Array
from .segmentation import hinge_segments, line_fit, noise_level, refine, rss

if TYPE_CHECKING:
    from .lab import LabRecord

__all__ = [
    "Segment",
    "StepWindow",
    "detect_segments",
    "parse_segments",
    "segments_table",
    "load_velocity_series",
    "slice_steps",
]

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
    """

    t_start: float
    t_end: float
    velocity: float
    i_start: int
    i_end: int

    @property
    def duration(self) -> float:
        """``t_end - t_start``, s."""
        return self.t_end - self.t_start


def _make_segments(t: Array, bounds: list[int], vel: list[float]) -> tuple[Segment, ...]:
    n = len(t)
    return tuple(Segment(float(t[a]), float(t[b]) if b < n else float(t[-1]), float(v), a, b)
                 for a, b, v in zip(bounds[:-1], bounds[1:], vel, strict=True))


def _displacement(record: LabRecord) -> Array:
    if record.load_point is not None:
        return np.asarray(record.load_point)
    v, t = np.asarray(record.load_velocity), record.time
    # a velocity column becomes a displacement (trapezoids): the same detection then applies
    return np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])


def detect_segments(
    record: LabRecord,
    *,
    rel_tol: float = 0.1,
    hold_velocity: float | None = None,
    min_samples: int = 10,
    min_duration: float = 0.0,
    penalty: float = 10.0,
) -> tuple[Segment, ...]:
    """The load program of a record: constant load velocities and holds, from the displacement.

    The displacement is cut where its slope changes (:func:`.segmentation.hinge_segments`: a
    continuous broken line against *time*, so noise and sampling-rate changes do not matter;
    a change starts at the sample where the two lines meet); neighbours whose velocities
    differ by less than ``rel_tol``, or by less than their noise, are joined, and velocities
    within ``rel_tol`` of each other anywhere in the record are set to their common
    (duration-weighted) plateau value: a record that returns to 0.2 um/s gives 0.2 um/s each
    time. A stretch slower than the hold velocity is a hold (velocity 0).

    A stretch's velocity noise is the larger of 4 standard errors from the white noise of
    the displacement and ``2 sqrt(12) w / T``, with ``w`` the slow wander of the displacement
    about the broken line (a motor's wobble; RMS beyond the white noise) and ``T`` the
    stretch's duration.

    Parameters
    ----------
    record : LabRecord
        With a load-point displacement or velocity.
    rel_tol : float
        Relative difference below which two velocities are one, ``0 < rel_tol < 1``.
    hold_velocity : float, optional
        Speed (m/s) below which a stretch is a hold. Default: the larger of the stretch's
        velocity noise and 1e-4 of the fastest velocity in the record.
    min_samples, min_duration : int, float
        Shortest stretch, in samples (``>= 3``) and in seconds.
    penalty : float
        Strictness of a new change point (``> 0``; larger finds fewer).

    Returns
    -------
    tuple of Segment
        Covering every sample, in time order.
    """
    if not 0.0 < rel_tol < 1.0:
        raise ValueError(f"rel_tol = {rel_tol:g} is out of range: allowed > 0 and < 1")
    if min_samples < 3:
        raise ValueError(f"min_samples = {min_samples} is out of range: allowed >= 3")
    if not penalty > 0.0:
        raise ValueError(f"penalty = {penalty:g} is out of range: allowed > 0")
    if hold_velocity is not None and not hold_velocity >= 0.0:
        raise ValueError(f"hold_velocity = {hold_velocity:g} is out of range: allowed >= 0")
    t = np.asarray(record.time)
    x = _displacement(record)
    span = float(np.ptp(x))
    sigma = max(noise_level(x), 1e-9 * span, 1e-300)
    bounds = hinge_segments(t, x, sigma, min_samples=min_samples, min_duration=min_duration,
                            penalty=penalty)
    xs = (x - x[0]) / sigma
    wander = _wander(t, xs, bounds) * sigma
    while True:
        fits = [line_fit(t[a:b], x[a:b]) for a, b in zip(bounds[:-1], bounds[1:], strict=True)]
        vel = [f[0] for f in fits]
        vmax = max(abs(v) for v in vel)
        # a velocity is known to within white noise over the stretch's samples, and to within
        # the slow wander (a motor's wobble) over its duration: 2 sqrt(12) w / T at most
        noise = [max(4.0 * sigma / np.sqrt(f[2]),
                     2.0 * np.sqrt(12.0) * wander / max(t[b - 1] - t[a], 1e-300))
                 for f, a, b in zip(fits, bounds[:-1], bounds[1:], strict=True)]
        hold = [abs(v) <= (hold_velocity if hold_velocity is not None else max(e, 1e-4 * vmax))
                for v, e in zip(vel, noise, strict=True)]
        join = [j for j in range(1, len(vel)) if (hold[j] and hold[j - 1]) or (
            not hold[j] and not hold[j - 1] and abs(vel[j] - vel[j - 1]) <= max(
                rel_tol * max(abs(vel[j]), abs(vel[j - 1])), noise[j] + noise[j - 1]))]
        if not join:
            break
        gone = set(join)
        near = {bounds[i] for j in join for i in (j - 1, j + 1) if i not in gone}
        bounds = refine(t, xs, [b for j, b in enumerate(bounds) if j not in gone],
                        min_samples, min_duration, only=near)
    # one plateau value for the velocities within rel_tol of each other (same sign)
    plateau = [0.0] * len(vel)
    order = sorted((j for j in range(len(vel)) if not hold[j]), key=lambda j: vel[j])
    groups: list[list[int]] = []
    for j in order:
        p = groups[-1][-1] if groups else None
        if p is not None and vel[p] * vel[j] > 0 and (
                abs(vel[j] - vel[p]) <= rel_tol * max(abs(vel[j]), abs(vel[p]))):
            groups[-1].append(j)
        else:
            groups.append([j])
    for g in groups:
        w = np.array([t[bounds[j + 1] - 1] - t[bounds[j]] for j in g])
        v = float(np.average([vel[j] for j in g], weights=w if w.sum() > 0 else None))
        for j in g:
            plateau[j] = v
    # neighbours that now share a value are one stretch
    keep = [0] + [bounds[j] for j in range(1, len(plateau)) if plateau[j] != plateau[j - 1]]
    vals = [plateau[0]] + [plateau[j] for j in range(1, len(plateau))
                           if plateau[j] != plateau[j - 1]]
    return _make_segments(t, keep + [len(t)], vals)


def _wander(t: Array, xs: Array, bounds: list[int]) -> float:
    """RMS of the residuals about the broken line beyond the white noise (``xs`` in units of
    the noise): the slow part that makes short stretches' slopes scatter."""
    return float(np.sqrt(max(rss(t, xs, bounds) / len(t) - 1.0, 0.0)))


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
    t = np.asarray(record.time)
    src, dur = record.source, float(t[-1] - t[0])
    starts: list[float] = []
    vel: list[float] = []
    for item in (s.strip() for s in text.split(",")):
        if not item:
            continue
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
    segs = list(_make_segments(t, idx, vel))
    # a given start falls between samples: keep the time the user wrote
    segs = [Segment(float(t[0]) + s, g.t_end if j == len(segs) - 1 else float(t[0]) +
                    starts[j + 1], g.velocity, g.i_start, g.i_end)
            for j, (s, g) in enumerate(zip(starts, segs, strict=True))]
    return tuple(segs)


def segments_table(segments: tuple[Segment, ...] | list[Segment]) -> str:
    """The load program as a fixed-width table (times in s, velocities in m/s and um/s)."""
    lines = [f"{'#':>3} {'t_start (s)':>13} {'t_end (s)':>13} {'duration (s)':>12} "
             f"{'velocity (m/s)':>14} {'(um/s)':>10} {'samples':>8}"]
    for j, s in enumerate(segments):
        kind = "  hold" if s.velocity == 0.0 else ""
        lines.append(f"{j:>3} {s.t_start:>13.6g} {s.t_end:>13.6g} {s.duration:>12.6g} "
                     f"{s.velocity:>14.4e} {s.velocity * 1e6:>10.4g} "
                     f"{s.i_end - s.i_start:>8d}{kind}")
    return "\n".join(lines)


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
    """

    index: int
    kind: str
    i_start: int
    i_end: int
    t_change: float
    v_before: float
    v_after: float
    hold: float


def slice_steps(
    record: LabRecord,
    segments: tuple[Segment, ...],
    *,
    pre_slip: float = 50e-6,
    pre_fraction: float = 0.5,
) -> tuple[StepWindow, ...]:
    """Cut a record into its velocity steps and slide-hold-slide cycles.

    Each window starts before the change by ``pre_slip`` of load-point travel at the velocity
    before (enough steady sliding to pin the level), but by no more than ``pre_fraction`` of
    the segment before, and ends at the next change after it. A hold at the start or at the
    end of the record (no sliding before it, or none after) gives no window.

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
                                  cur.velocity, 0.0))
            j += 1
        elif j + 1 < len(segs):
            after = segs[j + 1]
            out.append(StepWindow(len(out), "shs", i0, after.i_end, cur.t_start,
                                  prev.velocity, after.velocity, cur.duration))
            j += 2
        else:
            break  # a final hold: nothing slides after it
    if not out:
        vs = ", ".join(f"{s.velocity:.3g}" for s in segs)
        raise ValueError(f"{record.source}: no velocity step or hold in the load program "
                         f"({len(segs)} segment(s), velocities {vs} m/s): give the program "
                         "with --segments if it was missed")
    return tuple(out)
