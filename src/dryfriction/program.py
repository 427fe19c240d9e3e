"""Prescribed load-point motion: a sequence of constant-velocity segments.

Shared by every driver (the trap ensemble and rate-and-state) and every unit system: the
numbers are in whatever units the caller works in (reduced ``a0/t0``, ``t0``, ``a0`` for the
trap model; m/s, s, m for rate-and-state). A segment is given by its velocity and either its
duration or the slip it covers (``|velocity| * duration``). Velocity 0 is a hold; negative
velocities move backwards.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .validation import check_scalar

__all__ = ["Segment", "VelocityProgram"]

_RESOLVABLE = 1e-12
"""Smallest segment duration relative to its end time: about 4500 rounding units of the time
variable, so the segment is still resolved."""


@dataclass(frozen=True)
class Segment:
    """One constant-velocity stretch of a program.

    Parameters
    ----------
    velocity : float
        Load-point velocity (0 = hold, negative = backwards).
    duration : float, optional
        Length of the segment in time, ``> 0``.
    slip : float, optional
        Distance covered, ``> 0``; needs ``velocity != 0``. Give exactly one of
        ``duration`` and ``slip``.
    """

    velocity: float
    duration: float | None = None
    slip: float | None = None

    def __post_init__(self) -> None:
        v = check_scalar("velocity", self.velocity)
        object.__setattr__(self, "velocity", v)
        if (self.duration is None) == (self.slip is None):
            raise ValueError("a segment needs exactly one of duration and slip")
        if self.duration is not None:
            d = check_scalar("duration", self.duration, 0.0, lo_open=True)
            object.__setattr__(self, "duration", d)
        else:
            s = check_scalar("slip", self.slip, 0.0, lo_open=True)
            if v == 0.0:
                raise ValueError("slip is given for a segment with velocity = 0: give a duration")
            object.__setattr__(self, "slip", s)

    @property
    def time(self) -> float:
        """Duration of the segment."""
        if self.duration is not None:
            return self.duration
        assert self.slip is not None
        return self.slip / abs(self.velocity)

    @property
    def displacement(self) -> float:
        """Signed displacement of the load point over the segment."""
        return self.velocity * self.time

    @classmethod
    def from_mapping(cls, m: Mapping[str, float]) -> Segment:
        """Build from ``{velocity=…, duration=…}`` or ``{velocity=…, slip=…}``."""
        unknown = set(m) - {"velocity", "duration", "slip"}
        if unknown:
            raise ValueError(
                f"unknown segment key(s) {', '.join(sorted(unknown))}: "
                "allowed velocity, duration, slip"
            )
        if "velocity" not in m:
            raise ValueError("a segment needs a velocity")
        return cls(m["velocity"], m.get("duration"), m.get("slip"))


@dataclass(frozen=True)
class VelocityProgram:
    """A piecewise-constant velocity program starting at time 0 and position ``x0``."""

    segments: tuple[Segment, ...]
    x0: float = 0.0

    def __init__(self, segments: Iterable[Segment | Mapping[str, float]], x0: float = 0.0):
        segs = tuple(s if isinstance(s, Segment) else Segment.from_mapping(s) for s in segments)
        if not segs:
            raise ValueError("a velocity program needs at least one segment")
        start = 0.0
        for i, seg in enumerate(segs, 1):
            # each segment must start at a finite time and last long enough to move the clock:
            # otherwise it would be dropped silently in floating point
            end = start + seg.time
            if not np.isfinite(end) or seg.time < _RESOLVABLE * end:
                what = "duration" if seg.duration is not None else "slip"
                raise ValueError(
                    f"segment {i} ({what} {getattr(seg, what):g}) starts at t = {start:g} and "
                    f"would end at t = {end:g}: every segment must last at least "
                    f"{_RESOLVABLE:g} of its end time and end at a finite time; shorten the "
                    "segments before it"
                )
            start = end
        object.__setattr__(self, "segments", segs)
        object.__setattr__(self, "x0", check_scalar("x0", x0))
        self._derive()

    def _derive(self) -> None:
        """The boundaries' times and positions and the velocities, computed once (read-only):
        a fit's solver runs ask for them a few times a run, on programs of 100-odd segments."""
        segs = self.segments
        times = np.concatenate([[0.0], np.cumsum([s.time for s in segs])])
        positions = self.x0 + np.concatenate([[0.0], np.cumsum([s.displacement for s in segs])])
        velocities = np.array([s.velocity for s in segs])
        for name, a in (("_times", times), ("_positions", positions),
                        ("_velocities", velocities)):
            a.flags.writeable = False
            object.__setattr__(self, name, a)

    def __setstate__(self, state: dict[str, object]) -> None:
        """Unpickled or deep-copied: the segments and ``x0``, the arrays derived again (so
        read-only again; a pickle from before they were kept has none)."""
        for key in ("segments", "x0"):
            object.__setattr__(self, key, state[key])
        self._derive()

    @property
    def times(self) -> NDArray[np.float64]:
        """Segment boundaries in time, length ``n + 1``, starting at 0 (read-only)."""
        return self._times

    @property
    def positions(self) -> NDArray[np.float64]:
        """Load-point positions at the segment boundaries (read-only)."""
        return self._positions

    @property
    def velocities(self) -> NDArray[np.float64]:
        """The segments' velocities (read-only)."""
        return self._velocities

    @property
    def total_time(self) -> float:
        return float(self.times[-1])

    def check_speeds(self, lo: float, hi: float, unit: str) -> None:
        """Refuse a moving segment slower than ``lo`` or faster than ``hi`` (in ``unit``).

        A hold is velocity 0 exactly; a velocity of ``1e-300`` is no hold but below what the
        drivers resolve (the theory's velocities start at ``U_MIN``), so it is refused rather
        than run as a number that means nothing.

        Raises
        ------
        ValueError
            Naming ``segments[i].velocity`` and the allowed range.
        """
        for i, seg in enumerate(self.segments):
            speed = abs(seg.velocity)
            if speed != 0.0 and not lo <= speed <= hi:
                raise ValueError(f"segments[{i}].velocity = {seg.velocity:g} {unit} is out of "
                                 f"range: allowed 0 (a hold) or {lo:g} <= |velocity| <= "
                                 f"{hi:g} {unit}")

    def segment_index(self, t: NDArray[np.float64]) -> NDArray[np.intp]:
        """Index of the segment that holds each time ``t`` (right-continuous at boundaries;
        times outside the program clip to the first or last segment)."""
        i = np.searchsorted(self.times, t, side="right") - 1
        return np.clip(i, 0, len(self.segments) - 1)

    def velocity(self, t: ArrayLike) -> NDArray[np.float64]:
        """Load-point velocity at times ``t`` (right-continuous at boundaries)."""
        t = np.asarray(t, float)
        return self.velocities[self.segment_index(t)]

    def position(self, t: ArrayLike) -> NDArray[np.float64]:
        """Load-point position at times ``t`` (continuous, piecewise linear)."""
        t = np.asarray(t, float)
        i = self.segment_index(t)
        return self.positions[i] + self.velocities[i] * (t - self.times[i])
