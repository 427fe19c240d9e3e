"""The commanded load program of a laboratory record, told from the apparatus' fluctuations.

A record's load-point displacement is the commanded program (constant velocities and holds)
plus the machine's own fluctuations: white transducer noise, quantisation, and red noise (a
servo's oscillation of seconds, a gear's wobble, drift). A test that assumes independent samples
takes every wobble for a step. Here a change is a step only when the velocities on its two sides
differ by more than the scatter that the fluctuations give the slopes of stretches of those
durations.

The fluctuations are measured on the record itself, at every time scale ``T`` (ours; the
model is :class:`Fluctuations`): the residuals about the current broken line are cut into
adjacent windows of duration ``T`` and the slopes of neighbouring windows differ by ``Delta``.
``var(slope_T) = sum_ij w_i w_j gamma(t_i - t_j)`` (``w`` the least-squares weights, ``gamma``
the displacement's autocovariance), so the spread of ``Delta / sqrt 2`` is the long-run,
autocorrelation-aware error of a slope over ``T``, estimated without a model of ``gamma``
(robustly: medians, so the odd pair across a real change does not count). It is split into a
part proportional to the velocity (a servo's wander: on the shared record 6 % of the velocity
over 10-s windows at both 0.2 and 2 um/s) and one that is not (a wobble or a drift, seen in a
hold), beside the white noise of the transducer. Beyond the longest scale measured they fall as
``T**-0.5`` (a random-walk wander; conservative for a bounded one), the relative part at most
``sqrt(12) lag / T`` (:meth:`Fluctuations.relative_at`: no wander of the measured rms
position error can tilt a longer stretch more).

Steps (:func:`detect_program`): candidates are the slope changes of a continuous broken line
(:func:`.segmentation.hinge_segments`, white-noise criterion, the 80 largest gains: too many
under red noise, by design); each boundary gets the confidence ``z = |v2 - v1| / sqrt(e1**2 +
e2**2)`` (the stretches' OLS slopes and their errors ``e`` from the fluctuations), and must
also carry slip beyond the servo's position error (``SLIP_MIN``, :func:`_slip_ratio`: the
settling of the load point after a large change is no step); every weak boundary (below
``z_min``, below ``SLIP_MIN``, or with a relative change below ``rel_tol``) that is weaker than
both its neighbours is removed, their neighbours re-placed, and the fluctuations measured
again, until every boundary stands. An
excursion that returns to the same velocity must differ from it by ``EXCURSION_REL`` too; a
stretch of fewer than ``2 min_samples`` samples between its neighbours' velocities is a
transition (a change between two samples), not a step. Before that, displacement resets (a
jump in one sample that neither neighbouring velocity explains: a transducer re-zeroed) are
taken out, and after it a normal-stress change splits a stretch (a segment boundary,
reported). Sampling-rate changes and gaps are found and reported; they create no change, the
fit being against time. A record longer than ``MAX_POINTS`` samples is searched on block
means and each change then moved to the best hinge on the samples between its neighbours
(the hinge search is compiled: :mod:`.hinge_kernel`); a change of confidence below
``LOCAL_Z`` is finally placed by the maximum-likelihood hinge under the record's own wander
(:mod:`.placement`: a slow wander bends the kink of the whole stretches), with the periods of
a machine oscillation found in the record as free regressors. Each change as placed must
still reach ``z_min`` over the two segments it joins (:data:`FINAL_JUDGE`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from ..validation import Array
from .artifacts import (
    find_resets,
    jump_excursions,
    normal_changes,
    same_velocity,
    sampling_changes,
    trapezoid_displacement,
)
from .labsteps import Segment, example_segments, make_segments
from .placement import (
    FINE_RATIO,
    HOLD_RATIO,
    OSC_RATIO,
    RELAX_STOP,
    RELAX_TAUS,
    oscillation_periods,
    place_changes,
    placed_at,
    sample_intervals,
)
from .reading import reading_step
from .record import LabRecord
from .segmentation import best_hinge, hinge_segments, kernel_input, median, noise_level

__all__ = ["Detection", "Fluctuations", "detect_program", "detect_segments", "find_resets",
           "displacement", "backwards_message", "held_back_message", "no_change_message",
           "PLACE_TOL", "Z_MIN"]

Z_MIN = 6.5
"""Confidence (velocity change over its fluctuation scatter) a detected change must reach. From
the null distribution (``python -m benchmarks bench_detect_null``: 150 seeded no-step zoo
records, searched at 2): on the first zoo (a velocity random walk) the largest ``z`` per record
reached 6.5 on 2.0 % of them (7.5, 10.4 and 34: excursions of 20-30 % in short records with
every artifact), and the tuning records (zoo 0-149) lost no change between 6 and 6.5, one at
7.6; on the zoo whose wander is a servo's position error, with the slip test, the largest is
4.35 (a change found on 3 % of the records at 2, none at 6.5)."""
ABS_BY_LAG = True
"""Whether the absolute part ``a(T)`` of a *moving* stretch's scatter is bounded, beyond the
longest scale measured, by the position error measured on the moving samples, as the
relative part is: ``a(T) <= sqrt(12) lag lag_speed / T`` (:meth:`Fluctuations.absolute_at`;
ours, the Cauchy-Schwarz bound of :meth:`Fluctuations.relative_at` applied to the
velocity-independent part; ``False``: ``a(T)`` falls as ``T**-0.5`` alone).

Why: where a record's speeds are only 1.3 times apart, the split of the measured scatter into
a relative and an absolute part (:func:`measure_fluctuations`: ``r`` from the faster half of
the window pairs, ``a`` from the slower half) is set by which stretch wanders more, and the
absolute part took most of it (1.5-2.8 times the relative part at 60 s); extrapolated as a
random walk it held ratio-1.3 steps of 60-s stretches at confidence 5.3-6.4 against
:data:`Z_MIN` (zoo 12013, 13105, 26184, 44052).
Whatever its split, the wander of a moving load point is in the residuals ``lag`` measures,
rms ``lag`` times the speed there (``lag_speed``, their median). Only stretches at least
``lag_floor`` fast (the speed above which ``lag`` was measured) are bounded: a hold's or a
creep's drift is no slide's error (with every stretch bounded, zoo 14257's creep of 0.008
um/s after a ratio-30 down-step was split in two). The split itself was tried otherwise and
dropped (docs/performance.md, "the absolute part of the wander")."""

Z_HOLD = 3.0
"""A stretch whose speed is below this many times its slope scatter is a hold."""


@dataclass(frozen=True)
class Fluctuations:
    """The scatter of a stretch's velocity from the apparatus' fluctuations (ours).

    ``e(T, v, Sxx)**2 = sigma**2 / Sxx + a(T)**2 + (r(T) v)**2``: the transducer's white
    noise (and quantum) ``sigma`` gives a least-squares slope the variance ``sigma**2 / Sxx``
    (``Sxx = sum (t - mean t)**2`` of the stretch's samples); the load point's own wander (a
    servo's oscillation, bursts) is mostly *relative*: the same fraction ``r(T)`` of the
    velocity at 0.2 and at 2 um/s on the shared record (6 % over 10-s windows at both); a
    wander that does not scale with the velocity (a gear's wobble, a drift, seen in a hold
    too) is ``a(T)``.

    Attributes
    ----------
    sigma : float
        White noise of the displacement, m.
    scales : Array
        Window durations ``T``, s, at which ``r`` was measured (increasing).
    relative : Array
        ``r(T)``, non-increasing in ``T``.
    absolute : Array
        ``a(T)``, m/s, non-increasing in ``T``.
    lag : float
        The load point's position error per unit speed, s (a servo's error: the robust rms of
        the displacement about the broken line over the speed, white noise taken out; inf
        where not measured): what a stretch carries into its neighbours (:func:`_slip_ratio`).
    lag_speed : float
        The median speed, m/s, of the samples ``lag`` was measured on (0: not measured).
    lag_floor : float
        The speed, m/s, those samples move at least (5 % of the fastest; inf: not measured):
        a stretch at least this fast has its absolute wander bounded (:data:`ABS_BY_LAG`).
    """

    sigma: float
    scales: Array
    relative: Array
    absolute: Array
    lag: float = float("inf")
    lag_speed: float = 0.0
    lag_floor: float = float("inf")

    @cached_property
    def _logs(self) -> tuple[Array, Array, Array]:
        """``log T``, ``log r`` and ``log a`` (each at least 1e-300), once per object: the
        pruning reads the model a dozen times a pass, each on a few stretches."""
        return (np.log(self.scales), np.log(np.maximum(self.relative, 1e-300)),
                np.log(np.maximum(self.absolute, 1e-300)))

    def _at(self, q: Array, log_q: Array, durations: Array) -> Array:
        """``q(T)`` interpolated in log-log (``log_q`` its logarithm, :attr:`_logs`);
        ``T**-0.5`` beyond the longest scale (a random-walk wander: conservative for a bounded
        one), constant below the shortest."""
        T = self.scales
        d = np.maximum(np.asarray(durations, float), 1e-300)
        out = np.exp(np.interp(np.log(d), self._logs[0], log_q))
        out = np.where(q.max() > 0, out, 0.0)
        return np.where(d >= T[-1], q[-1] * np.sqrt(T[-1] / d), out)

    def relative_at(self, durations: Array) -> Array:
        """``r(T)`` (1) at these durations (s); beyond the longest scale measured, at most
        ``sqrt(12) lag / T``.

        The bound (ours, Cauchy-Schwarz): a least-squares slope over ``T`` of a wander ``e``
        is ``sum (t - tbar) e / Sxx``, so ``slope**2 <= sum e**2 / Sxx = 12 rms(e)**2 / T**2``
        for samples spread evenly over ``T``; a servo's position error of rms ``lag`` times the
        speed can tilt a stretch by no more, whatever its spectrum (a machine oscillation of
        22-45 s, which the ``T**-0.5`` extrapolation takes for a random walk, included)."""
        d = np.maximum(np.asarray(durations, float), 1e-300)
        out = self._at(self.relative, self._logs[1], d)
        if np.isfinite(self.lag):
            out = np.where(d > self.scales[-1], np.minimum(out, np.sqrt(12.0) * self.lag / d),
                           out)
        return out

    def absolute_at(self, durations: Array, velocities: Array | None = None) -> Array:
        """``a(T)`` (m/s) at these durations (s); with :data:`ABS_BY_LAG`, for stretches of
        these ``velocities`` (m/s) at least ``lag_floor``, beyond the longest scale measured at
        most ``sqrt(12) lag lag_speed / T``."""
        d = np.maximum(np.asarray(durations, float), 1e-300)
        return self._bounded(self._at(self.absolute, self._logs[2], d), d, velocities)

    def _bounded(self, out: Array, d: Array, velocities: Array | None) -> Array:
        """``a(T)`` as :meth:`absolute_at` returns it, from its interpolation ``out`` at the
        durations ``d`` (s, at least 1e-300)."""
        if (ABS_BY_LAG and velocities is not None and np.isfinite(self.lag)
                and self.lag_speed > 0.0):
            moving = np.abs(np.asarray(velocities, float)) >= self.lag_floor
            out = np.where(moving & (d > self.scales[-1]),
                           np.minimum(out, np.sqrt(12.0) * self.lag * self.lag_speed / d), out)
        return out

    def levels(self, durations: Array) -> tuple[Array, Array]:
        """``r(T)`` as :meth:`relative_at` gives it and ``a(T)`` as :meth:`absolute_at` gives
        it without velocities (m/s), at these durations (s): the two interpolations that
        :meth:`scatter` and :func:`_slip_ratio` read, done once for a table of stretches
        (the pruning scores each table three ways)."""
        d = np.maximum(np.asarray(durations, float), 1e-300)
        return self.relative_at(d), self._at(self.absolute, self._logs[2], d)

    def scatter(self, durations: Array, velocities: Array, sxx: Array,
                levels: tuple[Array, Array] | None = None) -> Array:
        """``e``, m/s, of stretches of these durations (s), velocities (m/s) and ``Sxx``
        (s^2); ``levels``: :meth:`levels` at these durations, where already computed."""
        v = np.asarray(velocities, float)
        if levels is None:
            levels = self.levels(durations)
        d = np.maximum(np.asarray(durations, float), 1e-300)
        return np.sqrt(self.sigma**2 / np.maximum(sxx, 1e-300)
                       + self._bounded(levels[1], d, v) ** 2
                       + (levels[0] * v) ** 2)


@dataclass(frozen=True)
class Detection:
    """What the detector decided about a record, to show and to report.

    Attributes
    ----------
    segments : tuple of Segment
        The load program, each with the confidence of the change at its start.
    fluctuations : Fluctuations
        The velocity scatter against stretch duration it judged by.
    resets : tuple of float
        Times, s, of displacement resets taken out (a jump with no slip).
    rate_changes : tuple of float
        Times, s, where the sampling interval changes by more than a factor 1.5.
    gaps : tuple of float
        Start times, s, of gaps in the sampling (an interval 10 times its neighbours').
    normal_changes : tuple of float
        Times, s, of normal-stress changes (segment boundaries).
    held_back : tuple of (float, float)
        Stretches read moving backwards faster than a hold's drift and reported as holds
        (:data:`BACK_HELD`): the time each starts, s, and the velocity read, m/s.
    """

    segments: tuple[Segment, ...]
    fluctuations: Fluctuations
    resets: tuple[float, ...] = ()
    rate_changes: tuple[float, ...] = ()
    gaps: tuple[float, ...] = ()
    normal_changes: tuple[float, ...] = ()
    held_back: tuple[tuple[float, float], ...] = ()


def displacement(record: LabRecord) -> Array:
    """The load-point displacement, m (a velocity column integrated by trapezoids)."""
    if record.load_point is not None:
        return np.asarray(record.load_point, float)
    return trapezoid_displacement(np.asarray(record.time), record.load_velocity)


# ------------------------------------------------------------------------------ fluctuations
def _window_pairs(t: Array, x: Array, speed: Array, width: float, offset: float,
                  half_s2: float) -> tuple[Array, Array]:
    """For each pair of adjacent usable windows ``[offset + m width, offset + (m+1) width)``:
    ``(s2 - s1)**2 / 2 - half_s2 (1/Sxx1 + 1/Sxx2)`` (``s`` the windows' OLS slopes of
    ``x(t)``, ``Sxx`` their times' sums of squares) and the mean of the two windows' mean
    ``speed``. A window is usable with >= 3 samples spread over at least half of it (a uniform
    spread over ``width / 2`` has the time variance ``width**2 / 48``) and a finite slope.
    Compiled (:func:`.hinge_kernel.window_pairs`: each window's sums over its samples, times
    from the window's start, in one pass)."""
    from .hinge_kernel import window_pairs  # Numba: imported on first use only

    return window_pairs(kernel_input(t), kernel_input(x), kernel_input(speed), float(width),
                        float(offset), float(half_s2), width**2 / 48.0)


MOVING_Z = 3.0
"""The relative wander ``r(T)`` is measured on the faster half of the window pairs whose speed
``u`` is at least this many times the slower half's slope scatter, ``sqrt(2.198 median y)``
over the slower half (ours; 0: the whole faster half, as before stop 53): a pair moves when
its speed is told from the wander.

Why: ``y = a**2 + r**2 u**2`` is split by rank, ``r`` from the faster half of the pairs. In a
record that is mostly hold (a slide-hold-slide with a hold of 1000 s against 200 s of slides)
the faster half holds hold pairs, whose ``y`` is the absolute wander (a drift of nm/s) and
whose ``u`` is the hold's fitted creep (nm/s): ``y / u**2`` of order 1, so ``r`` read 1.7
(170 % of any speed) and every change was pruned, the whole record one segment at 0.036
um/s (``bench_detect_holds`` B8: 1 um/s, 0.056 um/s for 40 s, a 1000-s hold, 1 um/s). A share
of the top speed instead (5 %, as ``lag``'s) mended that but dropped the slow slides of
ratio-10 records too (zoo 3165: 0.127 um/s beside 12.7), whose pairs the rank had used, and
moved a change 0.65 s off."""
MOVING_SHARE = 1e-3
"""And at least this share of the record's top stretch speed (ours): at the longest durations
the slower half's scatter is a fraction of a nm/s, below a hold's fitted creep of a nm/s, and
:data:`MOVING_Z` alone let a 2600-s hold's pairs in (an independent review's record: 14.5
um/s slides of 39 and 140 s about the hold, ``r`` 16 % at 242 s and so at every shorter
duration, the record one segment). A thousandth keeps the slower speed of any step of the
issue's ratios (1.3-30; zoo 3165's 0.127 um/s beside 12.7 is a hundredth); in a program that
spans more than a thousandfold, the slowest slides' pairs are left out and ``r`` is the faster
ones'. With ``MOVING_Z = 0`` neither criterion applies (the whole faster half, as before)."""
MOVING_MIN = 6
"""Fewer moving pairs than this at a duration: ``r`` there is the shorter duration's (0 at the
shortest; the non-increasing envelope is taken after)."""


COMPILED_SCALES = True
"""Whether :func:`measure_fluctuations` takes its loop over the durations in one compiled call
(:func:`.hinge_kernel.fluctuation_scales`) rather than a dozen NumPy calls per duration and
offset: the same operations, the same numbers (a speed change only; the NumPy loop is kept as
the reference the tests compare with)."""


def measure_fluctuations(t: Array, x: Array, sigma: float, bounds: list[int],
                         velocity: Array) -> Fluctuations:
    """``r(T)`` of the displacement ``x(t)`` about a broken line (:class:`Fluctuations`).

    The residuals of ``x`` about a line fitted to each stretch between ``bounds`` (so that
    the record's changes do not count as fluctuations) are cut into adjacent windows of
    duration ``T``; for a pair with residual slopes ``s1, s2``, white parts ``w**2 = sigma**2
    (1/Sxx1 + 1/Sxx2) / 2`` and stretch speed ``u``: ``r**2 = ((s2 - s1)**2 / 2 - w**2) /
    u**2`` (0 where negative). ``r(T)`` is 1.4826 times the median over the faster half of the
    pairs that move (``u`` at least :data:`MOVING_Z` times the slower half's slope scatter
    and :data:`MOVING_SHARE` of the top stretch speed; fewer than :data:`MOVING_MIN` such
    pairs: the shorter duration's ``r``): a Gaussian's MAD, blind to the odd pair across a
    missed change. A line absorbs the wander at its own duration only, so a boundary too
    many hides little of it; :func:`detect_program` measures again as boundaries go.

    Parameters
    ----------
    t, x : Array
        Times, s (increasing), and load-point displacement, m (resets taken out).
    sigma : float
        White noise of ``x``, m.
    bounds : list of int
        Stretch boundaries (samples, from 0 to ``len(t)``).
    velocity : Array
        Fitted velocity of each stretch, m/s.
    """
    from .hinge_kernel import stretch_residuals  # Numba: imported on first use only

    n = len(t)
    if len(velocity) != len(bounds) - 1:
        raise ValueError(f"{len(bounds) - 1} stretches but {len(velocity)} velocities")
    t, x = kernel_input(t), kernel_input(x)  # once here, not per window (a read-only record)
    # each stretch's residuals about its line (segmentation.line_fit's, to the last bit) and
    # its speed, compiled: one Python call, not a dozen NumPy calls per stretch
    res, speed = stretch_residuals(t, x, np.array(bounds, np.int64), kernel_input(velocity))
    # the position error per unit speed, from the samples moving at least 5 % of the top
    # speed (ours): the median of (res**2 - sigma**2) / speed**2, 2.198 times (a Gaussian's
    # median of squares); unmeasured (inf) where the white noise hides it
    fast = speed >= 0.05 * float(speed.max())
    lag = float("inf")
    lag_speed, lag_floor = 0.0, float("inf")
    if fast.sum() >= 24 and speed.max() > 0:
        q = (res[fast] ** 2 - sigma**2) / speed[fast] ** 2
        lag2 = 2.198 * median(q)
        lag = float(np.sqrt(lag2)) if lag2 > 0 else float("inf")
        lag_speed, lag_floor = float(median(speed[fast])), 0.05 * float(speed.max())
    if n > 200_000:  # time-averaged blocks: windows of >= 5 blocks see the same slopes
        bl = n // 100_000
        m = n // bl
        t, res, speed = (q[: m * bl].reshape(m, bl).mean(axis=1) for q in (t, res, speed))
        sigma = sigma / np.sqrt(bl)
    top = float(speed.max())  # the fastest stretch's speed, m/s (MOVING_SHARE)
    span = float(t[-1] - t[0])
    dt = median(np.diff(t))
    scales: list[float] = []
    rel: list[float] = []
    ab: list[float] = []
    # ours: windows of at least 5 samples, and never more windows than 10 per sample, so that
    # a gap of years between two samples (span >> n dt) cannot ask for span/T ~ 1e9 windows
    # and exhaust the memory in bincount (issue 24, outside24: a silent hang)
    T = max(5.0 * dt, span / (10.0 * len(t)))
    if not (T > 0.0 and span < float("inf")):
        # times all equal (or infinite): no duration to double (a caller's record; a
        # LabRecord's times increase), so none measured, not a loop without end
        T = float("inf")
    if COMPILED_SCALES:
        from .hinge_kernel import fluctuation_scales  # Numba: imported on first use only

        # the loop below in one compiled call (the same numbers): its durations, and the
        # numbers it computes with Python's powers, computed here as it computes them
        widths = []
        while T <= span / 3.0:
            widths.append(T)
            T *= 2.0
        sc, rl, ab_ = fluctuation_scales(
            kernel_input(t), kernel_input(res), kernel_input(speed), np.asarray(widths, float),
            np.asarray([q**2 / 48.0 for q in widths], float), 0.5 * sigma**2, top,
            float(MOVING_Z), float(MOVING_SHARE), int(MOVING_MIN), 2.0)
        scales, rel, ab = sc.tolist(), rl.tolist(), ab_.tolist()
    else:
        while T <= span / 3.0:
            ys, us = [], []
            for off in (0.0, 0.5 * T, 0.25 * T, 0.75 * T):
                if off in (0.25 * T, 0.75 * T) and sum(len(q) for q in ys) >= 100:
                    break  # pairs enough from two offsets (the other two only for long T)
                # each pair's (s2 - s1)**2 / 2 less its white part w**2, and its mean speed
                y_off, u_off = _window_pairs(t, res, speed, T, float(t[0]) - off, 0.5 * sigma**2)
                ys.append(y_off)
                us.append(u_off)
            y, u = np.concatenate(ys), np.concatenate(us)
            if y.size >= 24:
                # y = a**2 + r**2 u**2: r from the faster half of the pairs, then a from the
                # slower half less r's part; 2.198 = 1.4826**2 turns a median of squares of a
                # Gaussian into its variance
                fast = np.zeros(y.size, bool)
                fast[np.argsort(u, kind="stable")[y.size // 2:]] = True  # by rank: ties split
                # r from the pairs that move (MOVING_Z), not from a hold's creep
                a0 = np.sqrt(max(2.198 * median(y[~fast]), 0.0))
                moving = (fast & (u >= MOVING_Z * a0) & (u >= MOVING_SHARE * top)
                          if MOVING_Z > 0.0 else fast)
                uf = u[moving]
                if MOVING_Z > 0.0 and moving.sum() < MOVING_MIN:
                    r2 = rel[-1] ** 2 if rel else 0.0  # too few: the shorter scale's
                else:
                    r2 = 2.198 * median(y[moving] / uf**2) if (uf > 0).all() else 0.0
                r2 = max(r2, 0.0)
                a2 = max(2.198 * median((y - r2 * u**2)[~fast]), 0.0)
                scales.append(T)
                rel.append(np.sqrt(r2))
                ab.append(np.sqrt(a2))
            T *= 2.0
    if not scales:  # too short a record to measure a wander: none assumed
        scales, rel, ab = [max(span, 1e-300)], [0.0], [0.0]
    # never less at a shorter scale than at a longer one
    r_arr = np.maximum.accumulate(np.asarray(rel)[::-1])[::-1]
    a_arr = np.maximum.accumulate(np.asarray(ab)[::-1])[::-1]
    return Fluctuations(float(sigma), np.asarray(scales), r_arr, a_arr, lag, lag_speed,
                        lag_floor)


# ------------------------------------------------------------------------------ the program
class _Fits:
    """OLS line of each stretch between boundaries, all stretches at once (a few passes over
    their samples, not one Python call per stretch)."""

    def __init__(self, t: Array, x: Array) -> None:
        self.t, self.x = t, x
        # the tables asked for, by their bounds: the pruning asks for the same bounds several
        # times (its scores, their confidences, the reach); read-only, as they are shared
        self._memo: dict[tuple[int, ...], tuple[Array, Array, Array]] = {}

    def table(self, bounds: list[int]) -> tuple[Array, Array, Array]:
        """Velocities (m/s), durations (s) and ``Sxx`` (s^2) of the stretches between
        ``bounds`` (increasing sample indices; only the samples between the first and the last
        are read); read-only arrays, computed once for each ``bounds``."""
        key = tuple(bounds)
        got = self._memo.get(key)
        if got is None:
            got = self._table(bounds)
            for q in got:
                q.flags.writeable = False
            if len(self._memo) >= 256:
                self._memo.clear()
            self._memo[key] = got
        return got

    def _table(self, bounds: list[int]) -> tuple[Array, Array, Array]:
        """:meth:`table`, computed."""
        b = np.asarray(bounds, np.int64)
        lo = int(b[0])
        t, x = self.t[lo:b[-1]], self.x[lo:b[-1]]
        a = b[:-1] - lo
        cnt = np.diff(b)
        seg = np.repeat(np.arange(a.size), cnt)
        tc = t - (np.add.reduceat(t, a) / cnt)[seg]  # centred in each stretch: no cancellation
        xc = x - (np.add.reduceat(x, a) / cnt)[seg]
        sxx = np.add.reduceat(tc * tc, a)
        with np.errstate(divide="ignore", invalid="ignore"):
            v = np.where(sxx > 0, np.add.reduceat(tc * xc, a) / sxx, 0.0)
        return v, self.t[b[1:] - 1] - self.t[b[:-1]], sxx


def _is_hold(v: Array, d: Array, sxx: Array, fl: Fluctuations, floor: float,
             given: bool, levels: tuple[Array, Array] | None = None) -> Array:
    """A hold: slower than ``floor`` (given), or than ``Z_HOLD`` slope errors of a still load point
    (white noise and absolute wander; and 1e-4 of the fastest velocity, ``floor``);
    ``levels``: :meth:`Fluctuations.levels` at ``d``, where already computed."""
    v = np.asarray(v, float)
    return np.abs(v) <= (floor if given else np.maximum(
        Z_HOLD * fl.scatter(d, 0.0 * v, sxx, levels), floor))


def _z(fits: _Fits, fl: Fluctuations, bounds: list[int],
       levels: tuple[Array, Array] | None = None) -> Array:
    """Confidence of each inner boundary: ``|v2 - v1| / sqrt(e1**2 + e2**2)``; ``levels``:
    :meth:`Fluctuations.levels` at the stretches' durations, where already computed."""
    v, d, sxx = fits.table(bounds)
    e = fl.scatter(d, v, sxx, levels)
    return np.abs(np.diff(v)) / np.hypot(e[1:], e[:-1])


SLIP_MIN = 3.0
"""The slip a change carries over the shorter of its two stretches, against the position
error a servo may carry there (:func:`_slip_ratio`), must reach this (ours; set a priori
between the tuning records' transients, below 1.1, and their weakest true changes, above 5)."""


SETTLE = True
"""A moving stretch between a faster one and a hold (a stop's settling, :func:`_settling`) is
no stretch of its own where the servo's relaxation explains it as well as a stretch does
(:func:`_relaxation_explains`; ours; ``False``: off).

Why: the position error a servo carries at a stop relaxes whole in the hold (the zoo's
servo, ``de/dt = -e / tau``, as a loop with no integral term does), so the load point moves
on after the stop by the error it had, a draw of rms ``lag`` times the fast speed. Beyond
:data:`SLIP_MIN` rms (about one stop in 400; more where ``lag``, measured about a broken line
that takes up part of the wander, is low) that settling passes the slip test as a slow
stretch of its own: zoo 21022 (4.55 um/s, then 0.097 um/s for 8.4 s, then held) and 23206
(46.8, then 2.5 um/s for 4.7 s), slip ratios 3.6 and 3.6. A higher slip threshold at a stop
(5, tried first) fixes both but drops true slow stretches before a hold that carry 4-5
``lag`` of slip (a 31 -> 3.1 um/s step held after 12 s, 37 um: lost in 4 of 5 seeds with the
zoo's servo and wobble). The shape tells them apart where the size cannot: a settling's
velocity decays from the stop as ``exp(-t / tau)``, a commanded stretch keeps its velocity and
stops at once. Measured (``bench_detect``): on the 4650 used zoo records the same records right
and wrong; on the 4500 examined (17000-31299) 21022, 23206 and 26206 fixed, none broken; on an
independent generator (``tests/records/test_count_causes.py``) commanded stretches of 6-16 s
before a hold found as often as without the rule, and settlings of 1.3 s of the fast speed
taken for stretches in 4 of 5 seeds without it, in none with it."""


def _settling(v: Array, hold: Array) -> Array:
    """Per inner boundary: the boundary between a moving stretch and a held one after it (a
    hold, or slower than :data:`.placement.HOLD_RATIO` of the fast stretch before the moving
    one: a hold read with its drift), the speeds falling through the three (:data:`SETTLE`)."""
    u = np.abs(np.asarray(v, float))
    out = np.zeros(len(u) - 1, bool)
    # boundary j lies between stretches j and j + 1; the stretch before is j - 1
    held = hold[2:] | (u[2:] <= HOLD_RATIO * u[:-2])
    out[1:] = held & ~hold[1:-1] & (u[:-2] > u[1:-1]) & (u[1:-1] > u[2:])
    return out


SETTLE_MOST = 3.0
"""A settling (:data:`SETTLE`) is looked for only where the slip ratio (:func:`_slip_ratio`) is
below this many times :data:`SLIP_MIN` (nine ``lag``; ours): a Gaussian error beyond nine of
its rms does not happen, even with the rms measured low by half; a commanded stretch that
carries more is kept without its shape compared (and a stretch of minutes costs no fit)."""


SETTLE_AFTER = 30.0
"""The seconds of the hold after the settling stretch that :func:`_relaxation_explains` fits
(ours: the longest relaxation time of :data:`.placement.RELAX_TAUS` three times over, and
more; a hold's own drift is a line of its own over minutes)."""


def _relaxation_explains(t: Array, x: Array, b0: int, b1: int, b2: int, b3: int,
                         v_after: float = 0.0) -> bool:
    """Whether the servo's relaxation after a stop near sample ``b1`` fits the displacement at
    least as well as a stretch to ``b2`` of its own velocity, then held (:data:`SETTLE`; ours).

    The samples from half the stretch's duration before ``t[b1]`` (not before ``b0``) to
    :data:`SETTLE_AFTER` s after ``t[b2]`` (not past ``b3``), less ``v_after (t - t2)+`` (the
    held stretch's own measured velocity, m/s: a slow slide after it is not taken for a
    relaxation's tail). Two least-squares models of three parameters each, with the stop
    ``t_s`` profiled over (at most 25 samples) within that half duration of ``t[b1]``: the
    stretch, ``c + v_F (t - t_s)- + v_S clip(t - t_s, 0, t2 - t_s)``; the relaxation, ``c + v_F
    (t - t_s)- + A (1 - exp(-(t - t_s)+ / tau))``, ``tau`` the best of
    :data:`.placement.RELAX_TAUS`. ``True`` where the relaxation's least residual sum of
    squares is at most the stretch's. Why the stop is profiled: ``b1`` is where the pruning
    has it, not yet placed (up to a second early: the relaxation's start then takes the fast
    slide's last samples, which a stretch's ramp cannot); why only half the stretch before it:
    the fast stretch's wander over longer (a machine oscillation of micrometres at tens of
    um/s) would outweigh the shapes compared.
    """
    t1, t2 = float(t[b1]), float(t[b2])
    half = 0.5 * (t2 - t1)
    lo = max(b0, int(np.searchsorted(t, t1 - half)))
    hi = min(b3, int(np.searchsorted(t, t2 + SETTLE_AFTER)))
    stops = np.arange(lo + 2, min(int(np.searchsorted(t, t1 + half)), b2 - 2))
    if hi - lo < 12 or stops.size == 0:
        return False
    stops = stops[np.linspace(0, stops.size - 1, min(25, stops.size)).astype(int)]
    tt = np.asarray(t[lo:hi], float)
    y = np.asarray(x[lo:hi], float) - v_after * np.maximum(tt - t2, 0.0)
    y = y - y.mean()

    taus = np.asarray(RELAX_TAUS, float)
    stretch = relax = np.inf
    for ts in t[stops]:
        u = tt - float(ts)
        after = np.maximum(u, 0.0)
        shapes = np.column_stack([np.minimum(after, t2 - float(ts)),
                                  -np.expm1(-after[:, None] / taus[None, :])])
        got = _shape_rss(u, y, shapes)
        stretch, relax = min(stretch, float(got[0])), min(relax, float(got[1:].min()))
    return relax <= stretch


def _shape_rss(u: Array, y: Array, shapes: Array) -> Array:
    """The residual sum of squares of ``y`` fitted by ``c + a min(u, 0) + b s_k`` for each
    column ``s_k`` of ``shapes`` (least squares, one fit per column; ours): the base ``[1,
    min(u, 0)]`` projected out once, then each column's gain over it (Frisch-Waugh-Lovell),
    in place of a fit per column."""
    base = np.column_stack([np.ones_like(u), np.minimum(u, 0.0)])
    q, _ = np.linalg.qr(base)
    yp = y - q @ (q.T @ y)
    sp = shapes - q @ (q.T @ shapes)
    norm = np.einsum("ij,ij->j", sp, sp)
    with np.errstate(divide="ignore", invalid="ignore"):
        gain = np.where(norm > 1e-12 * len(u), (sp.T @ yp) ** 2 / norm, 0.0)
    return float(yp @ yp) - gain


def _slip_ratio(v: Array, d: Array, fl: Fluctuations,
                levels: tuple[Array, Array] | None = None) -> Array:
    """The slip ``|v2 - v1| d`` of each inner boundary over the shorter stretch ``d`` beside
    it, over the position error a servo may carry there, ``D U`` (ours).

    The load point's wander is a servo's position error, a displacement ``D`` (s) times the
    speed it was made at, ``D = min(r(d) d, lag)`` (the wander over ``d``, at most the
    record's measured position error, :class:`Fluctuations`). The error left by a fast stretch
    relaxes through the next ones, so a short stretch just after a fast one drifts by the
    *fast* stretch's error: ``U`` is the largest speed of the two stretches and their outer
    neighbours. A true change carries far more slip than that; the servo's settling after a
    large change does not.
    """
    u = np.abs(np.asarray(v, float))
    nb = np.maximum(u[1:], u[:-1])  # the two stretches beside each boundary
    big = nb.copy()
    big[1:] = np.maximum(big[1:], u[:-2])  # the stretch before the left one
    big[:-1] = np.maximum(big[:-1], u[2:])  # the one after the right one
    dmin = np.minimum(d[1:], d[:-1])
    if levels is None:
        r, a = fl.relative_at(dmin), fl.absolute_at(dmin)
    else:
        # the shorter stretch's levels, read off those of each stretch (``levels``, at ``d``)
        right = d[1:] < d[:-1]
        r = np.where(right, levels[0][1:], levels[0][:-1])
        a = np.where(right, levels[1][1:], levels[1][:-1])
    lag = np.minimum(r * dmin, fl.lag)
    scale = np.hypot(lag * big, a * dmin)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.abs(np.diff(v)) * dmin / scale
    return np.where(scale > 0, out, np.inf)


EXCURSION_REL = 0.2
"""A stretch between two of the same velocity (an excursion that returns) is a change only
when it differs from them by this fraction too (a ratio of 1.25; the steps are >= 1.3)."""


EXCURSION_TWO = True
"""Two stretches between two of the same velocity (an excursion in two parts that returns)
are judged as one stretch there is (:data:`EXCURSION_REL`; ours): the three boundaries about
them are changes only where they differ by that fraction too, neither of the two a hold.

Why: two servo bursts side by side, one up and one down, are an excursion of two velocities;
each of its boundaries differs from the next stretch by 10-11 %, over ``rel_tol`` (10 %),
while no stretch lies between two of one velocity, so the rule for one stretch did not
apply: zoo 83599 (3.97 um/s, then +12 % for 2.5 s and -12 % for 2.5 s, then 3.97 again,
bursts drawn at 181.4 and 184.8 s) read three false changes of confidence 7-13."""


EDGE_BURSTS = True
"""A servo burst at the edge of a commanded stretch, beside a change, must differ from the
stretch by ``EXCURSION_REL`` too (:func:`_edge_bursts`; ours, detect11). The excursion rule
asks it of a stretch between two of the same velocity; a burst (+-12 % for 0.5-3 s in the
zoo, as in the issue's records) that lies against a change has the change on one side, so it
was judged by ``rel_tol`` (10 %) and stood at confidence 10-47: a short step read as three
(zoo 272, 5294, 9128, 10256: 11-15 % beside steps of ratio 3 and 10)."""


EDGE_TWO = True
"""The burst at an edge (:data:`EDGE_BURSTS`) is looked for also where the record has only two
stretches (ours): a burst at the record's end (or start) with no change in the record is one
change against its record's end, the case the rule counts the record's ends for; it was asked
only of three stretches and more, and a +12 % burst in a record's last 2 s read as a change
of 14 % (zoo 21083, a record with no change). Only where the shorter stretch lasts less than
:data:`EDGE_TWO_SHARE` of the longer: a burst is short beside a commanded stretch, and two
stretches of about one length are a step measured small by the wander (zoo 12156, a ratio-1.3
up-step read as 22 %: 59 s against 60 s). And only where it lasts less than
:data:`EDGE_TWO_MOST` s: a burst lasts seconds (0.5-3 s in the issue's records and the zoo;
7253's slower end, 10.7 s), and a commanded last stretch of minutes is no burst whatever the
record's length (a review's clean 1.0 -> 1.15 um/s step, 1200 s then 250 s, lost its change
without this)."""
EDGE_TWO_SHARE = 0.25
EDGE_TWO_MOST = 20.0

EDGE_ENDS = True
"""A stretch at the record's start or end is a burst at the edge of the next (the record's
end counting as its change, :data:`EDGE_BURSTS`) only where it lasts less than
:data:`EDGE_TWO_MOST` s, in a record of any number of stretches (ours; :data:`EDGE_TWO` asks
it of two). Why: a staircase 1.0 -> 1.15 -> 1.32 um/s of 600, 600 and 1200 s under a 1 %
wander read as one change 160 s before the second step in 4 of 6 seeds: its first 600-s
stretch, shorter than the next as measured, was taken for a burst at the record's start.
Only at the ends: between two changes, a long stretch within ``EXCURSION_REL`` of a longer
one is mostly the wander of a slow slide (``bench_detect_holds`` A 39 and C 14 read changes
too many with the limit there too)."""

EDGE_PAIRS = True
"""Two servo bursts side by side at the edge of a commanded stretch, beside a change, are one
burst in two parts (ours; :data:`EXCURSION_TWO` is the same for an excursion that returns):
the two boundaries between them and the stretch are judged by ``EXCURSION_REL`` where both
are shorter than the stretch and than :data:`EDGE_TWO_MOST` (a burst lasts seconds), one
faster and one slower than the stretch (an excursion about it, as bursts up and down), and
neither is a hold, as one burst's (:data:`EDGE_BURSTS`).

Why: zoo 89828, a short step of 8 s at 362 um/s whose last 1.3 s held a +12 % and a -10 %
burst side by side, read as three changes (the boundaries 10.6 % and 19.5 %, confidence 14
and 26): neither burst lies between the stretch and the change alone. (That reading came
with a rule since dropped, every change re-placed within its reach; without it 89828 reads
right with this rule off too, and no zoo record measured needs it: it is the edge's
counterpart of :data:`EXCURSION_TWO`.) Without the duration and the two sides, a clean
staircase 1.0 -> 1.15 -> 1.32 um/s of 600, 600 and 1200 s (an independent review's) read
one change 164 s before either: its first two stretches, beside the record's start, were
taken for a pair of bursts at the third's edge."""


def _edge_bursts(v: Array, d: Array, rel: Array, hold: Array) -> Array:
    """Whether each inner boundary is a burst's at the edge of a commanded stretch (ours):
    between a stretch ``k`` with a change beyond ``EXCURSION_REL`` (or the record's start or
    end) on its other side and a longer stretch within ``EXCURSION_REL`` of it, neither a
    hold; with :data:`EDGE_PAIRS`, the two boundaries of two such stretches side by side.

    Parameters
    ----------
    v : Array
        Velocity of each stretch, m/s.
    d : Array
        Duration of each stretch, s.
    rel : Array
        Each inner boundary's velocity change over the faster of its two velocities (1).
    hold : Array
        Whether each stretch is a hold.

    Returns
    -------
    Array
        One flag per inner boundary: judged by ``EXCURSION_REL`` instead of ``rel_tol``.
    """
    # big[k] and big[k + 1]: the changes on either side of stretch k; the record's ends count
    # as changes (a burst at its start has no history before it)
    big = np.concatenate([[True], rel > EXCURSION_REL, [True]])
    out = np.zeros(len(rel), bool)
    for k in range(len(v)):
        if hold[k]:
            continue
        # at the record's start or end (its own "change"), a burst lasts seconds (EDGE_ENDS)
        brief = not EDGE_ENDS or d[k] < EDGE_TWO_MOST
        if (k + 1 < len(v) and big[k] and not big[k + 1] and d[k] < d[k + 1] and not hold[k + 1]
                and (k > 0 or brief)):
            out[k] = True
        if (k > 0 and big[k + 1] and not big[k] and d[k] < d[k - 1] and not hold[k - 1]
                and (k + 1 < len(v) or brief)):
            out[k - 1] = True
        if not EDGE_PAIRS:
            continue
        # two bursts side by side at the edge (EDGE_PAIRS): stretches k and k + 1 after the
        # change at k's start, or k - 1 and k before the change at k's end
        if (k + 2 < len(v) and big[k] and not big[k + 1] and not big[k + 2]
                and max(d[k], d[k + 1]) < min(d[k + 2], EDGE_TWO_MOST)
                and (v[k] - v[k + 2]) * (v[k + 1] - v[k + 2]) < 0.0
                and not (hold[k + 1] or hold[k + 2])):
            out[k] = out[k + 1] = True
        if (k > 1 and big[k + 1] and not big[k] and not big[k - 1]
                and max(d[k], d[k - 1]) < min(d[k - 2], EDGE_TWO_MOST)
                and (v[k] - v[k - 2]) * (v[k - 1] - v[k - 2]) < 0.0
                and not (hold[k - 1] or hold[k - 2])):
            out[k - 2] = out[k - 1] = True
    return out


def _scores(fits: _Fits, fl: Fluctuations, bounds: list[int], rel_tol: float, z_min: float,
            floor: float, given: bool, m: int = 0) -> Array:
    """Each inner boundary's standing: ``min(z / z_min, rel / rel_tol)`` (< 1: remove), 0
    between two holds, ``z / z_min`` between a hold and a slide."""
    v, d, sxx = fits.table(bounds)
    lv = fl.levels(d)  # read three ways below: the holds, the confidences, the slips
    hold = _is_hold(v, d, sxx, fl, floor, given, lv)
    dv = np.abs(np.diff(v))
    z = _z(fits, fl, bounds, lv)
    rel = dv / np.maximum(np.maximum(np.abs(v[1:]), np.abs(v[:-1])), 1e-300)
    # an excursion: the stretches on either side of this one's two boundaries agree
    tol = np.full(len(dv), rel_tol)
    if len(v) >= 3:
        back = np.abs(v[2:] - v[:-2]) <= rel_tol * np.maximum(np.abs(v[2:]), np.abs(v[:-2]))
        exc = np.zeros(len(v), bool)
        exc[1:-1] = back & ~hold[1:-1]
        tol = np.where(exc[1:] | exc[:-1], max(rel_tol, EXCURSION_REL), tol)
        if EXCURSION_TWO and len(v) >= 4:
            # stretches i and i + 1 between i - 1 and i + 2 of one velocity: the boundaries
            # i - 1, i and i + 1 (boundary k lies between stretches k and k + 1)
            two = (np.abs(v[3:] - v[:-3])
                   <= rel_tol * np.maximum(np.abs(v[3:]), np.abs(v[:-3])))
            two &= ~hold[1:-2] & ~hold[2:-1]
            run = np.zeros(len(dv), bool)
            run[:-2] |= two
            run[1:-1] |= two
            run[2:] |= two
            tol = np.where(run, max(rel_tol, EXCURSION_REL), tol)
    if EDGE_BURSTS and (len(v) >= 3 or EDGE_TWO and d.min() < min(EDGE_TWO_SHARE * d.max(),
                                                                    EDGE_TWO_MOST)):
        tol = np.where(_edge_bursts(v, d, rel, hold), max(rel_tol, EXCURSION_REL), tol)
    slip = _slip_ratio(v, d, fl, lv) / SLIP_MIN
    if SETTLE and len(v) >= 3:
        # only where the slip passes SLIP_MIN but not SETTLE_MOST times it: below, the boundary
        # goes anyway; above, no servo's settling carries it (and the fits cost nothing)
        for j in np.flatnonzero(_settling(v, hold) & (slip >= 1.0) & (slip < SETTLE_MOST)):
            if _relaxation_explains(fits.t, fits.x, *bounds[j - 1:j + 3], float(v[j + 1])):
                slip[j] = 0.0
    score = np.minimum(np.minimum(z / z_min, rel / tol), slip)
    one = hold[1:] ^ hold[:-1]
    score = np.where(one, np.minimum(z / z_min, slip), score)
    score = np.where(hold[1:] & hold[:-1], 0.0, score)
    if len(v) >= 3 and m > 0:
        # a transition: a stretch of < 2m samples between its neighbours' velocities (a
        # change between two samples, which a kink at a sample cannot follow): its weaker
        # boundary goes
        size = np.diff(np.asarray(bounds))
        mono = (v[1:-1] - v[:-2]) * (v[2:] - v[1:-1]) > 0
        for j in np.flatnonzero(mono & (size[1:-1] < 2 * m)) + 1:
            k = j - 1 if score[j - 1] <= score[j] else j
            score[k] = min(score[k], 0.0)
    return score


def _prune(t: Array, x: Array, xs: Array, bounds: list[int], fl: Fluctuations, fits: _Fits,
           rel_tol: float, z_min: float, floor: float, given: bool, m: int) -> list[int]:
    """Remove the weakest boundary until each stands (module docstring)."""
    while len(bounds) > 2:
        score = _scores(fits, fl, bounds, rel_tol, z_min, floor, given, m)
        weak = score < 1.0
        if not weak.any():
            break
        # every weak boundary weaker than both its neighbours goes at once (never two
        # neighbours: each removal touches only its own two stretches), its neighbours
        # re-placed; the weakest first in each neighbourhood, as one by one, in a few passes
        # (the cost of one by one is a pass per candidate)
        s = np.concatenate([[np.inf], score, [np.inf]])
        go = set((np.flatnonzero(weak & (score <= s[:-2]) & (score < s[2:])) + 1).tolist())
        near = {bounds[j + d] for j in go for d in (-1, 1)} - {0, len(t)}
        bounds = [q for j, q in enumerate(bounds) if j not in go]
        # a large change re-placed within its shorter stretch as it now stands (REPLACE_REACH)
        reach = _reach(bounds, fits.table(bounds)[0]) if REPLACE_REACH else {}
        bounds = _replace(t, xs, bounds, {q: reach.get(q, len(t)) for q in near}, m)
    return bounds


REPLACE_REACH = True
"""Whether a boundary of a large change (velocities more than :data:`.placement.FINE_RATIO`
apart, a hold, a reversal: :func:`_reach`) that the re-placement would move beyond the
length of its shorter stretch is placed by the best hinge within that reach instead
(:func:`_replace`): in the pruning, once a weak neighbour is removed, and when the changes
found on block means are moved to the samples (ours; detect12). A move within the reach is
kept as before.

Why: removing a weak boundary merges two stretches, and the best hinge between the new
neighbours of the boundary beside it may then be another feature of the merged, longer
stretch (a servo's wobble over hundreds of seconds outweighs the kink of a short hold), so
a short stretch lost one end and, its other end alone no longer a change, the whole of it.
Zoo 3112: a 19-s hold's end (confidence 21.5) moved 300 s into the slide when a weak
boundary beyond it went, and the hold was lost; 278 (a short step) and 9000 the same
(docs/performance.md). A re-placement corrects a kink's place for the change of its
stretch; a move beyond its shorter stretch is no longer that kink, and a change there stays
a candidate of the search. Small changes (a servo burst read at 26-34 %) move as before:
with the reach for every change (in an earlier form, every change placed within its reach),
zoo 4278, 5145, 5170, 5177, 7018 and 7262 read one or more changes too many. Placing every
large change within its reach, not only those moved beyond it, fixed 11290 and 7058 too but
moved nine records' times off (short steps' starts 2.7-3.4 s) and widened a change's
interval (``tests/records/test_change_interval.py``)"""


def _reach(bounds: list[int], v: Array) -> dict[int, int]:
    """How far each inner boundary of a large change may be re-placed (:data:`REPLACE_REACH`):
    the length of its shorter stretch, samples; a change is large when its two velocities
    (``v``, m/s, one per stretch) are more than :data:`.placement.FINE_RATIO` apart or of
    opposite signs or one is zero (a hold). Boundaries of small changes are not listed."""
    u = np.asarray(v, float)
    lo = np.minimum(np.abs(u[1:]), np.abs(u[:-1]))
    hi = np.maximum(np.abs(u[1:]), np.abs(u[:-1]))
    large = (hi > FINE_RATIO * lo) | (u[1:] * u[:-1] <= 0.0)
    return {bounds[j]: min(bounds[j] - bounds[j - 1], bounds[j + 1] - bounds[j])
            for j in np.flatnonzero(large) + 1}


def _replace(t: Array, xs: Array, bounds: list[int], reach: dict[int, int], m: int
             ) -> list[int]:
    """Each inner boundary found in ``reach`` (sample index -> samples) moved to the best hinge
    (:func:`.segmentation.best_hinge`) between its neighbours, or, where that lies beyond
    ``reach`` of where it stands, to the best hinge on the samples within reach; one pass in
    order (:data:`REPLACE_REACH`).

    Parameters
    ----------
    t, xs : Array
        Times (s) and the displacement in units of the white noise.
    bounds : list[int]
        Sample indices of the boundaries, the ends included.
    reach : dict[int, int]
        Boundaries to re-place and how far each may move, samples.
    m : int
        Shortest stretch, samples.

    Returns
    -------
    list[int]
        The boundaries re-placed.
    """
    out = list(bounds)
    for j in range(1, len(out) - 1):
        q = out[j]
        if q not in reach:
            continue
        a, b = out[j - 1], out[j + 1]
        k, _ = best_hinge(t[a:b], xs[a:b], m, 0.0)
        if k > 0 and abs(a + k - q) > reach[q]:
            # moved beyond its reach: the hinge on the samples within reach instead (the
            # stretches' lines over them only)
            a, b = max(a, q - reach[q]), min(b, q + reach[q])
            k, _ = best_hinge(t[a:b], xs[a:b], m, 0.0)
        if k > 0:
            out[j] = a + k
    return out


def detect_program(
    record: LabRecord,
    *,
    rel_tol: float = 0.1,
    z_min: float = Z_MIN,
    hold_velocity: float | None = None,
    min_samples: int = 10,
) -> Detection:
    """The commanded load program of a record, judged against its own fluctuations.

    Parameters
    ----------
    record : LabRecord
        With a load-point displacement or velocity.
    rel_tol : float
        A change smaller than this fraction of the faster velocity is no change, and velocities
        within it anywhere in the record get one plateau value, ``0 < rel_tol < 1``.
    z_min : float
        Confidence a change must reach: velocity difference over the scatter of the two
        stretches' slopes (module docstring), ``> 0``.
    hold_velocity : float, optional
        Speed (m/s) below which a stretch is a hold; default ``Z_HOLD`` times its slope
        scatter, at least 1e-4 of the fastest velocity.
    min_samples : int
        Shortest stretch, samples (``>= 3``).

    Returns
    -------
    Detection
    """
    if not 0.0 < rel_tol < 1.0:
        raise ValueError(f"rel_tol = {rel_tol:g} is out of range: allowed > 0 and < 1")
    if not z_min > 0.0:
        raise ValueError(f"z_min = {z_min:g} is out of range: allowed > 0")
    if min_samples < 3:
        raise ValueError(f"min_samples = {min_samples} is out of range: allowed >= 3")
    if hold_velocity is not None and not hold_velocity >= 0.0:
        raise ValueError(f"hold_velocity = {hold_velocity:g} is out of range: allowed >= 0")
    t_all = np.asarray(record.time, float)
    # a reset is a displacement transducer's (re-zeroed): a velocity column integrated has
    # none, and its noisy increments would only be taken for some
    x_all, resets = (find_resets(t_all, displacement(record)) if record.load_point is not None
                     else (displacement(record), []))
    n = len(t_all)
    # a long record is searched on the means of blocks (<= MAX_POINTS), each change then
    # placed on the samples near it: the cost stays linear in the length
    blk = max(1, -(-n // MAX_POINTS))
    t, x = _blocks(t_all, x_all, blk)
    span = float(np.ptp(x))
    sigma = max(noise_level(x), 1e-9 * span, 1e-300)
    m = max(3, -(-min_samples // blk))
    bounds = hinge_segments(t, x, sigma, min_samples=m, penalty=10.0,
                            max_segments=MAX_CANDIDATES, max_points=len(t), tidy=False)
    xs = (x - x[0]) / sigma
    fits = _Fits(t, x)
    given = hold_velocity is not None
    jumps: list[int] = []
    for _ in range(2):
        for _ in range(6):  # the wander about the boundaries left, until they settle
            v_now = fits.table(bounds)[0]
            # the wander measured about the broken line less its drift-sized boundaries
            # (DRIFT_SIZED): a boundary must not hide the fluctuation it is judged by
            mb = _drift_bounds(bounds, v_now) if DRIFT_SIZED else bounds
            fl = measure_fluctuations(t, x, sigma, mb,
                                      v_now if mb == bounds else fits.table(mb)[0])
            vmax = float(np.max(np.abs(v_now)))
            floor = hold_velocity if given else 1e-4 * vmax
            new = _prune(t, x, xs, bounds, fl, fits, rel_tol, z_min, floor, given, m)
            if new == bounds:
                break
            bounds = new
        # an excursion that a jump of the displacement explains as well is a reset too small
        # for find_resets (a few quanta): taken out, and the boundaries searched again
        # (on the samples: a block mean smears a jump into a ramp)
        full = [b * blk for b in bounds[:-1]] + [n]
        off = jump_excursions(t_all, x_all, full, fits.table(bounds)[0], rel_tol, m * blk,
                              HOLD_RATIO if DRIFT_SIZED else 0.0,
                              2 * blk if blk > 1 else 0) if (
            record.load_point is not None) else []
        if not off:
            break
        x_all = x_all.copy()
        for _j, k, step in off:
            x_all[k:] -= step
            jumps.append(k - 1)
        _, x = _blocks(t_all, x_all, blk)
        drop = {j for j, _, _ in off} | {j + 1 for j, _, _ in off}
        # a jump between two different velocities (JUMP_BETWEEN) leaves one change between
        # its neighbours: at the best hinge there once the jump is out
        v_off = fits.table(bounds)[0]
        between = [(bounds[j - 1], bounds[j + 2]) for j, _, _ in off if not same_velocity(
            v_off, j, rel_tol, HOLD_RATIO if DRIFT_SIZED else 0.0)]
        bounds = [q for i, q in enumerate(bounds) if i not in drop]
        xs = (x - x[0]) / sigma
        fits = _Fits(t, x)
        for lo, hi in between:
            k, _ = best_hinge(t[lo:hi], xs[lo:hi], m, 0.0)
            if k > 0:
                bounds = sorted({*bounds, lo + k})
    resets = sorted(resets + jumps)
    # the oscillation's periods on the searched signal (block means of a long record): only
    # where some change is placed by the hinge under the wander
    weak_now = _z(fits, fl, bounds) < LOCAL_Z
    periods = _periods(t, x, bounds, fits) if weak_now.any() else ()
    if blk > 1:
        # each change found on block means moved to the best hinge on the samples between
        # its neighbours (one vectorised pass per change: O(n) each, few changes)
        sigma_all = max(noise_level(x_all), 1e-9 * span, 1e-300)
        full = [b * blk for b in bounds[:-1]] + [n]
        xs_all = (x_all - x_all[0]) / sigma_all
        # a large change within its shorter stretch (REPLACE_REACH), the others between
        # their neighbours
        reach = _reach(full, fits.table(bounds)[0]) if REPLACE_REACH else {}
        bounds = _replace(t_all, xs_all, full, {q: reach.get(q, n) for q in full[1:-1]},
                          max(3, min_samples))
        fl = replace(fl, sigma=sigma_all)
        t, x = t_all, x_all
        fits = _Fits(t, x)
        if SHORT_SEARCH:
            # the stretches shorter than the blocks let the search hold, looked for on finer
            # blocks stretch by stretch and judged as the others were
            m_s = max(3, min_samples)
            held = _is_hold(*fits.table(bounds), fl, floor, given)

            def judge(q: list[int]) -> tuple[Array, Array]:
                return _stop_scores(fits, fl, q, rel_tol, z_min, floor, given, m_s)

            bounds = _short_stretches(t, x, bounds, held, blk, m, judge)
    # a change to or from a hold (or a speed below RELAX_STOP of the other side's) is placed
    # by the hinge under the wander whatever its confidence (the servo's relaxation after a
    # stop bends the whole stretches' kink: HOLD_PLACED)
    v_now, d_now, sxx_now = fits.table(bounds)
    hold_now = _is_hold(v_now, d_now, sxx_now, fl, floor, given)
    weak = _z(fits, fl, bounds) < LOCAL_Z
    by_rule = np.zeros_like(weak)
    if HOLD_PLACED and _wanders(fl):
        u = np.abs(v_now)
        stop = np.minimum(u[1:], u[:-1]) <= RELAX_STOP * np.maximum(u[1:], u[:-1])
        by_rule = ~weak & (hold_now[1:] | hold_now[:-1] | stop)
        weak = weak | by_rule
    if (weak.any() or OSC_PLACED) and not periods and not weak_now.any():
        periods = _periods(t, x, bounds, fits)
    if OSC_PLACED and periods:
        u = np.abs(v_now)
        weak = weak | (np.maximum(u[1:], u[:-1]) > OSC_RATIO * np.minimum(u[1:], u[:-1]))
    sig_place = sigma if blk == 1 else fl.sigma
    guess = bounds
    bounds, places = place_changes(t, x, bounds, v_now, sig_place, fl.scales, fl.relative,
                                   fl.absolute, m, weak=weak, periods=periods,
                                   tol=PLACE_TOL if TOL_PLACED else 0.0, holds=hold_now,
                                   lag=fl.lag)
    # each sample's interval, a gap's sample given the one after it (once per record)
    one = sample_intervals(t, np.arange(1, t.size)) if t.size > 1 else np.zeros(0)
    if P_MOVE > 0.0 and _wanders(fl):
        # a confident change left where the whole stretches put it, whose own profile gives
        # that place less than P_MOVE of lying within the tolerance: placed by the profile
        # (NaN, never below it, where there is no interval or the profile is cut by the
        # times searched: :func:`.placement.placed_at`)
        p_at = np.array([placed_at(pl, t, PLACE_TOL, float(one[pl.index - 1]))[1]
                         for pl in places])
        far = ~weak & (p_at < P_MOVE)
        for j in np.flatnonzero(far) + 1:  # each between its neighbours as placed
            sub = [bounds[j - 1], bounds[j], bounds[j + 1]]
            (_, bj, _), (pl,) = place_changes(
                t, x, sub, v_now[j - 1:j + 1], sig_place, fl.scales, fl.relative,
                fl.absolute, m, weak=np.array([True]), periods=periods,
                tol=PLACE_TOL if TOL_PLACED else 0.0, holds=hold_now[j - 1:j + 1],
                lag=fl.lag)
            bounds[j], places[j - 1] = bj, pl
        weak = weak | far
    if HOLD_PLACED:
        bounds, places = _keep_holds(t, x, guess, bounds, places, hold_now, by_rule, v_now,
                                     fits, fl, floor, given, sig_place, m, periods)
    if READING and record.load_point is None and record.load_velocity is not None:
        bounds, places = _on_reading(t, np.asarray(record.load_velocity, float), bounds,
                                     places, v_now)
    while True:
        v_arr, d_arr, sxx_arr = fits.table(bounds)
        vel = [float(v) for v in v_arr]
        hold_end = _is_hold(v_arr, d_arr, sxx_arr, fl, floor, given)
        if HOLD_BACK and not given:
            hold_end |= _held_back(v_arr)
        back = np.zeros(len(vel), bool)
        top = float(np.max(v_arr)) if len(vel) else 0.0
        if BACK_HELD and not given and top > 0.0 and top >= float(np.max(np.abs(v_arr))):
            # a program whose fastest stretch moves forward: a slow backward stretch is a hold
            back = ~hold_end & (v_arr < 0.0) & (np.abs(v_arr) <= BACK_RATIO * top)
            hold_end |= back
        hold = [bool(h) for h in hold_end]
        plateau = _plateaus(t, bounds, vel, hold, rel_tol)
        keep = [0] + [bounds[j] for j in range(1, len(plateau)) if plateau[j] != plateau[j - 1]]
        keep.append(len(t))
        if not FINAL_JUDGE or len(keep) <= 2:
            break
        # each change as it is reported (over the two segments it joins, placed) must stand
        # as the pruning judged it: the weakest below z_min goes, and the program is read again
        # (by the pruning's whole standing, FINAL_SCORES: confidence, size, slip; on the
        # samples, whose shortest stretch is max(3, min_samples), whatever the blocks were)
        stand = (_scores(fits, fl, keep, rel_tol, z_min, floor, given, max(3, min_samples))
                 if FINAL_SCORES else _z(fits, fl, keep) / z_min)
        stand = np.where(np.isnan(stand), np.inf, stand)  # 0/0: nothing to judge it by
        k = int(np.argmin(stand))
        if not stand[k] < 1.0:
            break
        gone = keep[k + 1]
        places = [pl for q, pl in zip(bounds[1:-1], places, strict=True) if q != gone]
        bounds = [q for q in bounds if q != gone]
    where = {pl.index: pl for pl in places}
    # a normal-stress change is a boundary too (the velocity may stay)
    nchg = normal_changes(t, record.normal_stress, min_samples)
    cuts = sorted(set(keep) | {i for i in nchg if 0 < i < len(t)})
    vals = [plateau[int(np.searchsorted(bounds, a, side="right")) - 1] for a in cuts[:-1]]
    segs = list(make_segments(t, cuts, vals))
    sn = None if record.normal_stress is None else np.asarray(record.normal_stress, float)
    out = []
    for j, s in enumerate(segs):
        conf = float("nan")
        if j > 0 and s.i_start in keep:
            # over the two stretches the change joins (a normal-stress change or a gap within
            # either cuts a segment, not the stretch the change was judged on)
            k = keep.index(s.i_start)
            conf = float(_z(fits, fl, keep[k - 1:k + 2])[0])
        normal = float(np.mean(sn[s.i_start:s.i_end])) if sn is not None else float("nan")
        pl = where.get(s.i_start) if np.isfinite(conf) else None
        if pl is None or not np.isfinite(pl.lo):
            # a velocity change whose time could not be assessed (too few samples beside it
            # to compute an interval) is not said to be placed (an outside user's holds cut
            # by a gap: such changes read as placed, 5 s off)
            moved = j > 0 and s.velocity != segs[j - 1].velocity
            out.append(replace(s, confidence=conf, normal=normal, start_placed=not moved))
            continue
        # placed: probably (PLACED_P) within the larger of one sample (the interval before
        # the change, not a gap: sample_intervals) and PLACE_TOL of the reported time, by the
        # widened profile; a change whose profile reaches the end of the times searched is not
        placed, p_in = placed_at(pl, t, PLACE_TOL, float(one[s.i_start - 1]))
        out.append(replace(s, confidence=conf, normal=normal, start_lo=pl.lo, start_hi=pl.hi,
                           start_edge=pl.edge, start_placed=placed, start_p=p_in))
    rate, gaps = sampling_changes(t)
    held_back = tuple((float(t[bounds[j]]), float(v_arr[j])) for j in np.flatnonzero(back))
    return Detection(tuple(out), fl, tuple(float(t[i + 1]) for i in resets), tuple(rate),
                     tuple(gaps), tuple(float(t[i]) for i in nchg), held_back)


FINAL_JUDGE = True
"""Each change as reported, over the two segments it joins at its placed time, must reach
``z_min`` (ours): the weakest below goes and the program is read again, until each stands.

Why: the pruning judges each boundary where the search put it; the placement then moves it
(seconds, under the servo's wander), and the confidence the table reports is computed
there. A change kept at 1.01 times ``z_min`` and moved 2.6 s by its placement was reported
at 4.7: the settling after a ratio-10 down-step read as a 5-s step (zoo 87801), a servo burst
as a change (507: confidence 2.9; 7058: 3.9). On zoo 0-899 no true change is reported below
7.9."""


FINAL_SCORES = True
"""With :data:`FINAL_JUDGE`, each change as reported must stand by the pruning's whole
standing (:func:`_scores`: its confidence, its size against ``rel_tol`` or, for an excursion
or a burst at an edge, ``EXCURSION_REL``, and its slip), not by its confidence alone (ours).
``False``: by the confidence alone."""


READING = True
"""In a record that gives the servo's velocity reading (no displacement transducer), each
change is placed again on the reading, as its step (:func:`.reading.reading_step`), where the
reading shows it as one (ours): integrated to a displacement, the reading's white noise is a
random walk the hinge's wander model does not have, and small steps were placed seconds off
(the zoo's velocity records: 13 of the changes off the tolerance on the used ranges and
17000-19299, 3.6-4.9 s on 14004, 16009, 19044)."""


def _on_reading(t: Array, v: Array, bounds: list[int], places: list, vel: Array
                ) -> tuple[list[int], list]:
    """``bounds`` and ``places`` with each inner boundary placed on the velocity reading ``v``
    (m/s) where :func:`.reading.reading_step` places it (:data:`READING`); ``vel``: each
    stretch's velocity, m/s."""
    bounds, places = list(bounds), list(places)
    for j in range(1, len(bounds) - 1):
        pl = reading_step(t, v, bounds[j], bounds[j - 1], bounds[j + 1], float(vel[j - 1]),
                          float(vel[j]))
        if pl is not None:
            bounds[j], places[j - 1] = pl.index, pl
    return bounds, places


HOLD_SIGN = True
"""A hold is lost to a placement (:func:`_keep_holds`) only where it now reads as moving the
way a slide beside it moves (ours): the guard is against a slide's slope taken into the hold.
A hold that reads as moving backwards beyond its scatter got no slope from the slide; what
shows there is the record's own drift, which the slide's samples at a late guess had hidden
(zoo 14026 and 16252: a restart at a sampling-rate change placed within 0.1 s of the truth,
sent back 1.9 and 2.7 s late, the hold reading -0.8 and -1.5 nm/s against a scatter of 0.2
and 0.1 nm/s). Such a hold is reported as one by :data:`HOLD_BACK`."""


PLACE_TOL = 0.5
"""A change is *placed* (:class:`.labsteps.Segment`'s ``start_placed``) when the probability
that it lies within the larger of one sample and this many seconds of its time is at least
:data:`.labsteps.PLACED_P`, s: the tolerance the detection is measured against on the
artifact zoo (``benchmarks/bench_detect.py``)."""

TOL_PLACED = True
"""Whether a change placed by the hinge under the wander is put at the time most probably
within ``PLACE_TOL`` of it (the largest ``start_p``: :func:`.placement._most_probable`),
not at the profile's mode (ours)."""

P_MOVE = 0.01
"""A change confident enough to stay where the whole stretches put it (``LOCAL_Z``) is placed
by the hinge under the wander after all where its own profile gives that place less than
this probability of lying within its tolerance (``start_p``), the profile is not cut by the
times searched, and the record's load point wanders (:func:`_wanders`) (ours). The
whole stretches' kink of a confident step is biased by a wander the stretches share: zoo
records 123, 3027, 3267, 6051 (ratio-3 and ratio-10 steps of a many-step run, z 500-640),
1.1-1.7 tolerances off with ``start_p`` < 1e-3, within 0.1 after. 0.01, not 0.05: the shared
sepiolite record's change (z ~ 1960) has 0.033 and must stay at sample 16451 (with 0.05 it
moved 3 samples, 0.41 s, earlier; that record's program is to stay as it is). Without
the edge guard, zoo 4088 (a white record sampled 10 times faster from the step on) moved
1.5 tolerances off."""

HOLD_PLACED = True
"""Whether changes to and from a hold, or between speeds in a ratio beyond ``1 / RELAX_STOP``
(:data:`.placement.RELAX_STOP`), are placed by the hinge under the wander at any confidence
(ours): the servo's position error relaxes after a stop with nothing driving it, which bends
the kink of the whole stretches, however confident the change. Two guards: only in a record
whose load point wanders (:func:`_wanders`: in a white one the whole stretches' hinge is the
maximum-likelihood one), and a placement that makes a hold read as a motion goes back
(:func:`_keep_holds`: before them the rule moved the hold starts of ``tests/fit/test_shs.py``'s
slide-hold-slide records into the slide, a hold read as 4e-8 m/s, and their fits failed)."""

HOLD_SHRUNK = True
"""Whether a placement that leaves a hold beside it no longer a hold goes back (the guard of
:data:`HOLD_PLACED`, :func:`_keep_holds`) only where it lengthened that hold (a stop moved
earlier, a restart later), the moves that shortened it kept, unless no move lengthened it
(ours; ``holdfix``).

Why: the guard is there for a hinge that takes samples of the slide into the hold and so
gives the hold the slide's slope. A move that shortens the hold takes samples out of it and
cannot give it a slope of the slide's; where such a move makes the hold fail the hold test,
it took slide samples *out* of the hold that had hidden its drift (zoo 4132: a restart
guessed 0.94 s late, placed 0.12 s late, and the hold, without 0.8 s of the 0.19-um/s slide
at its end, read as a drift of -9e-4 um/s beyond its scatter; sent back to the guess).
The stop beside it, moved 0.08 s earlier into the slide, still goes back, and then the hold
reads as a hold. Where no move lengthened a hold that is lost, every moved change beside it
goes back as before, so every hold stays a hold. Measured: docs/performance.md
(holdfix)."""

LOCAL_Z = 500.0
"""Below this confidence a change is placed by the generalised-least-squares hinge under the
record's wander (:func:`.placement.place_changes`); a larger one is placed as well by the whole
stretches (the shared record's, z ~ 760, stays at sample 16451)."""


OSC_PLACED = True
"""Where the record's periodogram finds a machine oscillation (:func:`_periods`), a change
between speeds more than ``OSC_RATIO`` apart is placed by the hinge with the oscillation's
regressors (:func:`.placement.change_profile`) whatever its confidence (ours): the whole
stretches' kink, where a change above ``LOCAL_Z`` stays otherwise, models no oscillation, and
a velocity oscillation of the zoo's 22 and 45 s bends a long stretch's line near its ends
(zoo records 7245 and 3165, steps of ratio 3 and 10, confidence 545-1067: 1.13-1.30
tolerances off there, within 0.3 placed). Not for the small steps (``OSC_RATIO``), whose
window already holds two periods each side: on ``bench_detect_oracle``'s ratio-1.3 records
with the oscillation, placing them too put 17 of 27 within the tolerance against 20 left
(``tests/records/test_detect.py``). Measured on the zoo (``bench_detect A:B --no-stress``):
docs/performance.md."""

MAX_POINTS = 2_000
"""Longest signal searched sample by sample; a longer one is searched on block means."""
MAX_CANDIDATES = 80
"""Most candidate stretches (the largest white-noise gains) judged against the fluctuations."""


DRIFT_SIZED = True
"""Whether the fluctuations are measured about the broken line less its drift-sized
boundaries (a velocity change below :data:`.placement.HOLD_RATIO`, 1/100, of the fastest
speed around it: :func:`_drift_sized`), and two stretches so close are the same velocity
for an excursion that a jump explains (:func:`.artifacts.jump_excursions`) (ours; detect11).

Why: the displacement transducer's drift (the zoo's: 2 um over the record) moves a hold or
a slow stretch by 0.002-0.02 um/s and bends it, and a boundary that splits the stretch
hides it from the measurement it is judged by: each piece's line takes up the curvature
(zoo 5050: ``a(T) = 0`` at every scale with the split, 1.8e-3 um/s about the true program),
so the split stood at confidence 7-13 (a hold read as a hold and a creep: 5050, 8110, 9238;
a slow stretch after a ratio-30 down-step read as two: 10165, 11245), and a reset's small
excursion in a hold was not taken for a jump, the hold's two pieces reading 25-40 % apart
(11140, 11218). Measured without the split, every pair of windows in the stretch sees the
drift's curvature, and the median takes it; a genuine change so left out is seen only by
the few pairs across it, which the median ignores (``tests/records/test_lab.py``'s 300 ->
0.1 um/s record with a hold, 1/3000 of the speed around, keeps its program; removing such
boundaries outright broke it)."""


def _drift_bounds(bounds: list[int], v: Array) -> list[int]:
    """``bounds`` (sample indices, the ends included) less the inner ones whose change is
    drift-sized (:func:`_drift_sized`; ``v`` the stretches' velocities, m/s)."""
    small = _drift_sized(v)
    return [bounds[0]] + [b for j, b in enumerate(bounds[1:-1]) if not small[j]] + [bounds[-1]]


def _drift_sized(v: Array) -> Array:
    """Whether each inner boundary's velocity change is below :data:`.placement.HOLD_RATIO`
    of the fastest speed around it: its two stretches and their outer neighbours, as the
    speed a servo's error comes from in :func:`_slip_ratio` (ours, :data:`DRIFT_SIZED`).

    Parameters
    ----------
    v : Array
        Velocity of each stretch, m/s.

    Returns
    -------
    Array
        One flag per inner boundary.
    """
    u = np.abs(np.asarray(v, float))
    big = np.maximum(u[1:], u[:-1])
    big[1:] = np.maximum(big[1:], u[:-2])
    big[:-1] = np.maximum(big[:-1], u[2:])
    return np.abs(np.diff(np.asarray(v, float))) < HOLD_RATIO * big


def _wanders(fl: Fluctuations) -> bool:
    """Whether the record's load point wanders (a relative or an absolute part measured at
    some scale, :class:`Fluctuations`): only then is a change at a hold placed by the hinge
    under the wander whatever its confidence (:data:`HOLD_PLACED`). In a record whose
    fluctuations are white the whole stretches' hinge is the maximum-likelihood one, on every
    sample; the placement's window and block means only lose information there (zoo record
    40, a slide-hold-slide with gaps: a restart 1.9 tolerances off with the rule; ours)."""
    return bool(np.any(fl.relative > 0) or np.any(fl.absolute > 0))


def _keep_holds(t: Array, x: Array, guess: list[int], bounds: list[int], places: list,
                hold_before: Array, by_rule: Array, v_guess: Array, fits: _Fits,
                fl: Fluctuations, floor: float, given: bool, sigma: float, m: int,
                periods: tuple[float, ...]) -> tuple[list[int], list]:
    """The changes placed by the hold rule (``by_rule``, :data:`HOLD_PLACED`) that leave each
    hold beside them a hold (:func:`_is_hold`); one whose move made a hold read as a motion
    goes back where the whole stretches put it (its interval computed about that place).

    Why (ours): a hold is a commanded velocity of zero, so its stretch must read as one. A
    hinge that takes samples of the slide into the hold (a relaxation regressor or a wander
    model fitted to a record without either: the slide-hold-slide records of
    ``tests/fit/test_shs.py``, a hold start placed 0.1-0.2 s into the slide) leaves the hold a
    slope the slide gave it, beyond the hold's own scatter; a move within the hold's or the
    slide's own fluctuations does not change what either reads as. The check is the same
    test that called the stretch a hold, so it needs no threshold of its own.
    """
    bounds = list(bounds)
    back: set[int] = set()
    while True:  # a change sent back alters its neighbours' stretches too: until none is
        v_after, d_after, sxx_after = fits.table(bounds)
        hold_after = _is_hold(v_after, d_after, sxx_after, fl, floor, given)
        lost = hold_before & ~hold_after
        if HOLD_SIGN:  # lost to a slide's slope: moving the way a slide beside it moves
            lost &= _slide_way(v_after)
        moved = [j for j in range(1, len(bounds) - 1)
                 if by_rule[j - 1] and bounds[j] != guess[j] and (lost[j - 1] or lost[j])]
        # first the moves that lengthened a hold lost (HOLD_SHRUNK: a stop moved earlier, a
        # restart later); the others only where none did
        bad = [j for j in moved if (lost[j - 1] and bounds[j] > guess[j])
               or (lost[j] and bounds[j] < guess[j])] if HOLD_SHRUNK else moved
        bad = bad or moved
        if not bad:
            break
        for j in bad:
            bounds[j] = guess[j]
        back.update(bad)
    places = list(places)
    for j in sorted(back):  # its interval about the guess (its neighbours as placed)
        sub = [bounds[j - 1], bounds[j], bounds[j + 1]]
        _, (pl,) = place_changes(t, x, sub, v_guess[j - 1:j + 1], sigma, fl.scales,
                                 fl.relative, fl.absolute, m, weak=np.array([False]),
                                 periods=periods)
        places[j - 1] = pl
    return bounds, places


def _slide_way(v: Array) -> Array:
    """Whether each stretch moves the way a stretch beside it moves (``v_k v_(k+-1) > 0``)."""
    v = np.asarray(v, float)
    out = np.zeros(v.size, bool)
    out[1:] |= v[1:] * v[:-1] > 0.0
    out[:-1] |= v[:-1] * v[1:] > 0.0
    return out


HOLD_BACK = True
"""A stretch that moves against the stretches beside it at no more than
:data:`.placement.HOLD_RATIO` of the faster one's speed is reported as a hold (ours;
:func:`_held_back`)."""


BACK_HELD = True
"""In a program whose fastest stretch moves forward, a stretch read moving backwards faster
than :func:`_held_back` allows a hold's drift but at most :data:`BACK_RATIO` of that fastest
speed is reported as a hold too, and listed (:class:`Detection`'s ``held_back``) so that the
user is told (ours; stop 50). Why: a load program moves forward or holds (the range
:func:`.lab.parse_segments` and the fits take), and a slow backward reading is a hold seen
through a drift or a position wander. Reported at its speed, it made a program that
``--segments`` refused and that ``fit`` refused with an array index (an outside user's
records: a 190-s hold between slides at 0.03 um/s, read at -0.51 nm/s under a wander of 80
nm). A fast one (a reversal, a reset the detector did not take out) stays as read and is
said (:func:`backwards_message`): called a hold, it hid a step in a slide-hold-slide window
(an independent review's 200-um reset spread over 3 s at a step)."""
BACK_RATIO = 0.2
"""The largest backward speed, as a fraction of the program's fastest forward one, that
:data:`BACK_HELD` takes for a hold (ours: a drift or a wander is far slower than the slides;
a reversal or a reset left in is as fast or faster)."""


def _held_back(v: Array) -> Array:
    """Whether each stretch is a hold read through the record's drift (ours): it moves the way
    no stretch beside it moves, at most :data:`.placement.HOLD_RATIO` of the faster
    neighbour's speed.

    Why: a hold is a commanded velocity of zero; its slope is the apparatus' drift (thermal,
    a transducer's creep), nanometres per second over a hold of minutes: beyond the white
    noise's slope scatter of a densely sampled stretch, and not in the wander measured from
    the slopes of adjacent windows, which a steady drift leaves alike. Of the 450 holds of the
    slide-hold-slides of zoo 0-449, 3000-3299, 7000-7299 and 14000-14299 (a drift of 2 um
    over the record), 142 were reported as slides at -0.1 to -317 nm/s, and a slide-hold-slide
    was then cut as two velocity steps, one to a speed below zero; 140 are holds by this. A
    commanded reversal is as fast as the slides beside it, not 1/100 of them (the bound by
    which the placement reads a hold). A hold that drifts the slides' way is left to
    :func:`_is_hold`: its speed alone does not tell it from a slow stretch (0.1 um/s between
    slides at 300 um/s is a commanded speed).
    """
    u = np.abs(np.asarray(v, float))
    nb = np.zeros(u.size)
    nb[1:] = np.maximum(nb[1:], u[:-1])
    nb[:-1] = np.maximum(nb[:-1], u[1:])
    return ~_slide_way(v) & (u <= HOLD_RATIO * nb)


def _periods(t: Array, x: Array, bounds: list[int], fits: _Fits) -> tuple[float, ...]:
    """Periods (s) of a machine oscillation in the displacement about the broken line
    (:func:`.placement.oscillation_periods`)."""
    v = fits.table(bounds)[0]
    cnt = np.diff(np.asarray(bounds))
    seg = np.repeat(np.arange(len(cnt)), cnt)
    b0 = np.asarray(bounds[:-1])
    tc = t - (np.add.reduceat(t, b0) / cnt)[seg]
    res = x - (np.add.reduceat(x, b0) / cnt)[seg] - v[seg] * tc
    return oscillation_periods(t, res, np.abs(v)[seg])


def _blocks(t: Array, x: Array, blk: int) -> tuple[Array, Array]:
    """Means of ``blk`` consecutive samples of ``t`` and ``x`` (the last block may be short)."""
    if blk == 1:
        return t, x
    idx = np.arange(0, len(t), blk)
    cnt = np.diff(np.append(idx, len(t)))
    return np.add.reduceat(t, idx) / cnt, np.add.reduceat(x, idx) / cnt


SHORT_SEARCH = True
"""A record searched on block means (longer than :data:`MAX_POINTS` samples) is searched
again, stretch by stretch, on blocks :data:`SHORT_SPLIT` times shorter, for the stretches
too short for the block search to hold (:func:`_short_stretches`; ours). ``False``: off.

Why: the block search's shortest stretch is three blocks, and a block lasts the record's
duration over :data:`MAX_POINTS`: 2.7 s in a slide-hold-slide of 5344 s at 100 Hz, so its
1-s hold at 10 um/s (10 um of slip withheld, confidence 500 where a shorter record of the
same program finds it) was not found at 100 or 1000 Hz, nor a 3-s or 10-s hold in two of
four such records at 100 Hz (``tests/records/test_short_stretches.py``). On
``bench_detect_holds`` H (such series at 10-200 Hz, seeds 0-299) the records with the
right number of segments went from 41 to 278 of 300; its families A-G and the zoo's
fresh ranges were read as before (docs/performance.md)."""
SHORT_SPLIT = 8
"""How many times shorter the blocks of :data:`SHORT_SEARCH` are than the record's."""
SHORT_STOPPED = 0.5
"""A short stretch :data:`SHORT_SEARCH` adds is one slower than this fraction of the speeds
beside it: nearer a stop than the slide (ours)."""
SHORT_SPLITS = 3
"""The places searched in each stretch by :data:`SHORT_SEARCH`: where the displacement about
the stretch's line steps most (a missed hold withholds its slip there; the servo's wander
gives the others, which the scores then remove). 3, not 6: on ``bench_detect_holds`` H
(seeds 0-59, the search's first form) 54 records right against 53, in 0.78 of the CPU."""


def _stop_scores(fits: _Fits, fl: Fluctuations, bounds: list[int], rel_tol: float,
                 z_min: float, floor: float, given: bool, m: int) -> tuple[Array, Array]:
    """The scores :data:`SHORT_SEARCH` judges its stops by, and each stretch's velocity (m/s):
    the detector's (:func:`_scores`), and each stretch's confidence with its scatter taken at
    the faster speed beside it, over ``z_min`` (ours): a stop is judged in the wander of the
    slide around it. Its own scatter, the relative part at its own speed (near 0), took a
    load point wandering by a position, not a fraction of its speed, for 4.5-s stops in a
    slow slide (``bench_detect_holds`` G 8, 33 and 280 in the search's first form,
    confidence 8.7-10)."""
    v, d, sxx = fits.table(bounds)
    u = np.abs(v)
    beside = np.maximum(np.append(u[1:], 0.0), np.insert(u[:-1], 0, 0.0))
    e = fl.scatter(d, np.maximum(u, beside), sxx)
    z_slide = np.abs(np.diff(v)) / np.hypot(e[1:], e[:-1])
    return (np.minimum(_scores(fits, fl, bounds, rel_tol, z_min, floor, given, m),
                       z_slide / z_min), v)


def _two_hinges(t: Array, xs: Array, threshold: float) -> tuple[int, int] | None:
    """The first two splits of the white-noise binary segmentation of ``xs(t)`` (``xs`` in
    units of its white noise; each hinge at least 3 samples from the ends and the other),
    each kept where it lowers the residual sum of squares by more than ``threshold``
    (:func:`.segmentation.hinge_segments` with ``max_segments=3``, in compiled scans only),
    each then moved to the best hinge between its neighbours; ``None`` where there are not
    two."""
    k, gain = best_hinge(t, xs, 3, 0.0)
    if k <= 0 or not gain > threshold:
        return None
    kl, gl = best_hinge(t[:k], xs[:k], 3, 0.0)
    kr, gr = best_hinge(t[k:], xs[k:], 3, 0.0)
    gl = gl if kl > 0 else -np.inf
    gr = gr if kr > 0 else -np.inf
    if max(gl, gr) <= threshold:
        return None
    p, q = (kl, k) if gl >= gr else (k, k + kr)
    # each moved to the best hinge between its neighbours (the first split lies at an
    # excursion's middle): as the segmentation's own refinement, one pass
    kp, _ = best_hinge(t[:q], xs[:q], 3, 0.0)
    p = kp if kp > 0 else p
    kq, _ = best_hinge(t[p:], xs[p:], 3, 0.0)
    return p, (p + kq if kq > 0 else q)


def _short_stretches(t: Array, x: Array, bounds: list[int], held: Array, blk: int,
                     m_blk: int, judge: Callable[[list[int]], tuple[Array, Array]]
                     ) -> list[int]:
    """``bounds`` (sample indices, the ends included) with the boundaries of the stretches
    the block search could not hold, where they stand (:data:`SHORT_SEARCH`; ours).

    Each moving stretch is searched on its own block means, ``blk // SHORT_SPLIT`` samples
    each, about the :data:`SHORT_SPLITS` places where the displacement about its line steps
    most (a missed hold withholds its slip there): the step over half a short stretch and
    over its halves down to two blocks, each scale's steps over their median, the largest
    across the scales taken. About each, a hold's two ends are found two ways, the run of
    blocks slower than :data:`SHORT_STOPPED` of the stretch about the step and the
    white-noise hinge's first two splits (:func:`_two_hinges`), each end moved to the best
    hinge on the samples, and the slower pair kept. It is a candidate where it is shorter
    than ``2 m_blk`` of the record's blocks (``blk`` samples, and their duration at the
    stretch's median sampling interval; a longer one the block search holds) and lies
    :data:`SETTLE_AFTER` (or that duration, if longer) from both ends. A stretch's
    candidates are judged within the stretch by ``judge`` (the detector's scores, the
    stretch's ends changes: ``< 1`` falls), the weakest pair falling first until every one
    stands; a pair whose stretch is not slower than :data:`SHORT_STOPPED` of the speeds
    beside it falls (a short hold is what a slide-hold-slide program has and the blocks
    lose; a short excursion at a speed is a servo's burst as often: zoo 80389, a velocity
    reading, read eight 29 % dips of 3-5 s as changes when any excursion was asked). The
    boundaries found before are kept as they were.

    Parameters
    ----------
    t, x : Array
        Times, s, and displacement, m, of every sample.
    bounds : list of int
        The boundaries found, the ends included.
    held : Array of bool
        Which stretches are holds: not searched (a short stop within a hold is no change:
        its pieces, holds both, would fall by their scores; the search is saved).
    blk : int
        Samples per block of the record's search (``> 1``).
    m_blk : int
        Shortest stretch of that search, blocks.
    judge : callable
        Of a list of boundaries: the scores of its inner boundaries (one each; the caller's
        judge a stop in the wander of the slide around it too) and the velocity of each
        stretch, m/s.

    Returns
    -------
    list of int
        The boundaries, increasing, the ends included.
    """
    fb = max(1, blk // SHORT_SPLIT)
    short = 2 * m_blk * blk
    w = max(1, short // (2 * fb))  # half a short stretch, fine blocks
    out = list(bounds)
    for j in range(len(bounds) - 1):
        a, b = bounds[j], bounds[j + 1]
        if held[j] or b - a < 3 * short:
            continue
        tb, xb = _blocks(t[a:b], x[a:b], fb)
        # a short stretch in time, at the stretch's median sampling interval
        short_time = short * float(median(np.diff(tb))) / fb
        # where the displacement about the stretch's line steps most (a missed hold
        # withholds its slip there): over half a short stretch and its halves down to two
        # blocks, each scale's steps over their median, the largest first
        tc, xm = tb - tb.mean(), xb.mean()
        num, den = tc @ (xb - xm), tc @ tc  # the stretch's line: slope num / den
        r = xb - xm - tc * num / den
        sig = None  # the stretch's white noise, once, where a window needs it
        c = np.concatenate([[0.0], np.cumsum(r)])
        # the stretch's speed, and each fine block's over three blocks (to the next's end)
        speed = abs(float(num / den))
        vb = np.full(r.size, np.inf)
        if r.size > 3:
            vb[:-3] = np.abs(xb[3:] - xb[:-3]) / np.maximum(tb[3:] - tb[:-3], 1e-300)
        k = np.arange(w, r.size - w + 1)
        step = np.zeros(k.size)
        ws = w
        while ws >= 2:
            d = np.abs((c[k + ws] - c[k]) - (c[k] - c[k - ws]))
            spread = median(d[::4]) if d.size else 0.0  # every fourth: as robust, cheaper
            if spread > 0.0:
                step = np.maximum(step, d / spread)
            ws //= 2
        pairs: list[tuple[int, int]] = []
        for _ in range(SHORT_SPLITS):
            if not step.size or not np.isfinite(step.max()):
                break
            i = int(np.argmax(step))
            centre = int(k[i])
            step[max(0, i - 2 * w):i + 2 * w] = -np.inf
            lo, hi = max(0, centre - 2 * w), min(r.size, centre + 2 * w)
            if hi - lo < 9:
                continue
            # the hold's two ends, two ways: the run of fine blocks about the step whose speed
            # (over three blocks) is under SHORT_STOPPED of the stretch's (exact where the
            # blocks' noise is well under that speed), and the white-noise hinge's first two
            # splits of the window (:func:`_two_hinges`: where it is not); each pair's ends
            # moved to the best hinges on the samples, the slower pair kept
            found = []
            slow = np.flatnonzero(vb[lo:hi - 1] < SHORT_STOPPED * speed) + lo
            if slow.size:
                i = int(np.argmin(np.abs(slow - centre)))  # the run holding the nearest
                cut = np.flatnonzero(np.diff(slow) > 1)  # a run ends at each
                j0 = int(np.searchsorted(cut, i))
                first = int(slow[cut[j0 - 1] + 1]) if j0 > 0 else int(slow[0])
                last = int(slow[cut[j0]]) if j0 < cut.size else int(slow[-1])
                found.append((first, last + 2))
            if sig is None:
                sig = max(noise_level(xb), 1e-9 * float(np.ptp(xb)), 1e-300)
            two = _two_hinges(tb[lo:hi], xb[lo:hi] / sig, 10.0 * np.log(hi - lo))
            if two is not None:
                found.append((lo + two[0], lo + two[1]))
            best = None
            for p0, q0 in found:
                # (the last block may be short: an end past it is the stretch's last sample)
                p, q = a + p0 * fb, min(a + q0 * fb, b - 1)
                w0, w1 = max(a, p - 2 * fb), min(b, q + 2 * fb)
                kp, _ = best_hinge(t[w0:q], x[w0:q], 3, 0.0)
                p = w0 + kp if kp > 0 else p
                kq, _ = best_hinge(t[p:w1], x[p:w1], 3, 0.0)
                q = p + kq if kq > 0 else q
                if q - p < 2:
                    continue
                u = abs(float(x[q] - x[p])) / max(float(t[q] - t[p]), 1e-300)
                if best is None or u < best[0]:
                    best = (u, p, q)
            # nearer a stop than the slide (judged again below on the pair's own line: this
            # spares the judging of the wander's pairs)
            if best is None or not best[0] < SHORT_STOPPED * speed:
                continue
            _, p, q = best
            # a short stretch in samples and in time (one across a gap is no hold the blocks
            # lost: zoo 80689, a velocity reading integrated over a gap), clear of the
            # stretch's ends by SETTLE_AFTER (beside a change found before, a short slow
            # piece is the servo's settling after it: zoo 80654, 0.2 s at 1.1 s after a
            # 13.6 -> 1.4 um/s step, its boundary not yet placed)
            if (q - p < short and t[q] - t[p] < short_time
                    and t[p] - t[a] >= max(SETTLE_AFTER, short_time)
                    and t[b - 1] - t[q] >= max(SETTLE_AFTER, short_time)
                    and all(q < p0 or p > q0 for p0, q0 in pairs)):
                pairs.append((p, q))
        pairs.sort()
        while pairs:
            local = [a, *(q for pq in pairs for q in pq), b]
            scores, v = judge(local)
            score = dict(zip(local[1:-1], scores, strict=True))
            # nearer a stop than the speed around it (its ends not yet placed, a short hold
            # reads faster than a hold: a 1-s hold at 10 um/s bracketed 0.15 s early, 0.54)
            u = np.abs(v)
            stopped = u[1:-1:2] < SHORT_STOPPED * np.minimum(u[:-2:2], u[2::2])
            weakest = [min(score[p], score[q]) if h else 0.0
                       for (p, q), h in zip(pairs, stopped, strict=True)]
            k = int(np.argmin(weakest))
            if weakest[k] >= 1.0:
                break
            del pairs[k]
        out.extend(q for pq in pairs for q in pq)
    return sorted(out)


def _plateaus(t: Array, bounds: list[int], vel: list[float], hold: list[bool],
              rel_tol: float) -> list[float]:
    """One plateau value for the velocities within ``rel_tol`` of each other (same sign), the
    duration-weighted mean; holds are 0: a record that returns to 0.2 um/s gives 0.2 um/s each
    time."""
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
    return plateau


def detect_segments(record: LabRecord, **kwargs: float) -> tuple[Segment, ...]:
    """The load program of a record (:func:`detect_program`'s segments)."""
    return detect_program(record, **kwargs).segments  # type: ignore[arg-type]


def held_back_message(det: Detection, t0: float = 0.0) -> str | None:
    """One line on the stretches :data:`BACK_HELD` reported as holds (``None`` if none), each
    by its start (s from ``t0``) and the velocity read (um/s)."""
    if not det.held_back:
        return None
    what = ", ".join(f"{t - t0:.6g} s ({v * 1e6:.3g} um/s)" for t, v in det.held_back)
    return (f"read moving backwards and reported as holds: the stretch(es) from {what}; a "
            "load program moves forward or holds, and a backward reading this slow (at most "
            f"{BACK_RATIO:g} of the fastest slide) is a hold seen through a drift or a "
            "position wander: check it in record.png, and give the program with --segments "
            "if it is not a hold")


def backwards_message(segments: tuple[Segment, ...] | list[Segment], t0: float = 0.0
                      ) -> str | None:
    """One line on the segments that move backwards (``None`` if none), each by its start (s
    from ``t0``) and velocity (um/s): the fits refuse them (ours)."""
    back = [s for s in segments if s.velocity < 0.0]
    if not back:
        return None
    what = ", ".join(f"{s.t_start - t0:.6g} s ({s.velocity * 1e6:.3g} um/s)" for s in back)
    return (f"moving backwards: the segment(s) from {what}; a load program moves forward or "
            "holds and the fits refuse it: a reversal, or a displacement reset the detector "
            "did not take out (check record.png); to fit the rest, give the program with "
            "--segments, such a stretch as a hold (0), or cut the record before it")


def no_change_message(record: LabRecord, det: Detection) -> str:
    """The one line for a record in which no velocity change stands above the fluctuations:
    the smallest change the two halves of the record would show at confidence ``Z_MIN``."""
    t = np.asarray(record.time)
    x = displacement(record)
    h = len(t) // 2
    fits = _Fits(t, x)
    v, d, sxx = fits.table([0, h, len(t)])
    e = det.fluctuations.scatter(d, v, sxx)
    lim = Z_MIN * float(np.hypot(e[0], e[1]))
    speed = det.segments[0].velocity if det.segments else 0.0
    # the example from the record's own times and speed (a fixed one lay outside short records)
    return (f"{record.source}: no velocity change found above the apparatus' fluctuations of "
            f"{lim * 1e6:.3g} um/s ({Z_MIN:g} times the scatter of the velocities of the "
            f"record's two halves): it moves at {speed * 1e6:.3g} um/s throughout, and a "
            "one-velocity record has no velocity step to fit; if its speed did change, give the "
            f"program with --segments, e.g. {example_segments(record, speed)}")
