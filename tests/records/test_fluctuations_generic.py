"""The apparatus' fluctuation model (records/detection.py :class:`Fluctuations`) against its
definition at generic scales (issue 25: nothing read it directly). Each test names the mistake
it is for; each was seen failing with it applied."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.records.detection import Fluctuations

FL = Fluctuations(sigma=0.17e-6, scales=np.array([2.5, 10.0, 40.0]),
                  relative=np.array([0.12, 0.06, 0.03]),
                  absolute=np.array([4e-8, 2e-8, 1e-8]), lag=0.9)


def test_scatter_levels_interpolated_in_log_log_and_extrapolated() -> None:
    # mistakes: a linear interpolation in T (not log-log); beyond the longest scale the last
    # value kept (no T^-1/2); the servo bound sqrt(12) lag/T as a lower bound (max for min)
    assert float(FL.relative_at(5.0)) == pytest.approx(0.12 * 2.0**-0.5, rel=1e-12)
    assert float(FL.relative_at(1.0)) == pytest.approx(0.12, rel=1e-12)  # flat below
    assert float(FL.absolute_at(20.0)) == pytest.approx(2e-8 * 2.0**-0.5, rel=1e-12)
    # beyond 40 s: 0.03 sqrt(40/T), at most sqrt(12) 0.9/T (binding at 400 s, not at 160 s)
    assert float(FL.relative_at(160.0)) == pytest.approx(0.015, rel=1e-12)
    assert float(FL.relative_at(400.0)) == pytest.approx(math.sqrt(12) * 0.9 / 400, rel=1e-12)
    assert float(FL.absolute_at(160.0)) == pytest.approx(0.5e-8, rel=1e-12)


def test_scatter_adds_the_three_variances() -> None:
    # mistakes: the white noise's variance over sqrt(Sxx); the relative part not times the
    # velocity; standard deviations added instead of variances
    T, v, sxx = np.array([5.0, 20.0]), np.array([2.3e-6, 0.4e-6]), np.array([83.0, 1.3e3])
    r = np.array([0.12 * 2.0**-0.5, 0.06 * 2.0**-0.5])
    a = np.array([4e-8 * 2.0**-0.5, 2e-8 * 2.0**-0.5])
    want = np.sqrt(0.17e-6**2 / sxx + a**2 + (r * v) ** 2)
    np.testing.assert_allclose(FL.scatter(T, v, sxx), want, rtol=1e-12)


def test_absolute_wander_of_a_slide_bounded_by_the_position_error() -> None:
    """``ABS_BY_LAG``: beyond the longest scale (40 s), a stretch moving at least ``lag_floor``
    (0.35 um/s) has its absolute wander at most ``sqrt(12) lag lag_speed / T`` (lag 0.41 s
    measured at a median 6.3 um/s: 8.947e-8 m/s at 100 s, 1.789e-8 at 500 s), the
    velocity-independent part of the position error the servo's bound covers as the relative
    part's; a hold or a creep below the floor keeps ``a(T)`` (its drift is no slide's error),
    as does a call without velocities (the slip ratio's) and every duration within the
    scales measured. Mistakes: the bound on holds too (a hold's drift bounded by a slide's
    error: zoo 14257's creep after a ratio-30 down-step split in two); the bound within the
    measured scales; the bound as a lower bound (max for min); ``lag_speed`` left out; the
    scatter not passing the velocities."""
    fl = Fluctuations(sigma=0.17e-6, scales=np.array([2.5, 10.0, 40.0]),
                      relative=np.array([0.12, 0.06, 0.03]),
                      absolute=np.array([9e-7, 6e-7, 4e-7]), lag=0.41, lag_speed=6.3e-6,
                      lag_floor=0.35e-6)
    T = np.array([20.0, 100.0, 500.0, 100.0, 500.0])
    v = np.array([2.1e-6, 2.1e-6, -7.7e-6, 0.2e-6, 0.0])
    free = 4e-7 * np.sqrt(40.0 / T)
    bound = math.sqrt(12.0) * 0.41 * 6.3e-6 / T
    want = np.where((T > 40.0) & (np.abs(v) >= 0.35e-6), np.minimum(free, bound), free)
    want[0] = 6e-7 * (4.0 / 6.0) ** 0.5  # 20 s: within the scales, log-log over 10-40 s
    np.testing.assert_allclose(fl.absolute_at(T, v), want, rtol=1e-12)
    assert want[1] == pytest.approx(8.947e-8, rel=1e-3) and want[3] > 1e-7
    unbounded = free.copy()
    unbounded[0] = want[0]
    np.testing.assert_allclose(fl.absolute_at(T), unbounded, rtol=1e-12)
    sxx = np.full(5, 1e3)
    r = fl.relative_at(T)
    np.testing.assert_allclose(fl.scatter(T, v, sxx),
                               np.sqrt(0.17e-6**2 / sxx + want**2 + (r * v) ** 2), rtol=1e-12)
    # unmeasured position error: no bound
    inf = Fluctuations(0.17e-6, fl.scales, fl.relative, fl.absolute, float("inf"), 6.3e-6,
                       0.35e-6)
    np.testing.assert_allclose(inf.absolute_at(T, v), unbounded, rtol=1e-12)


def test_the_bound_is_the_least_squares_slope_of_a_ramp_and_no_wander_exceeds_it() -> None:
    """The bound ``sqrt(12) lag lag_speed / T`` against least squares done independently
    (``np.polyfit``): a displacement error of rms ``lag * lag_speed`` (0.41 s at 6.3 um/s,
    2.583 um) tilts a 230-s stretch of 4601 even samples by at most the bound, and a ramp of
    that rms (the worst case, Cauchy-Schwarz's equality) by the bound itself to 1e-3; a random
    walk, an oscillation of 1.7 times the stretch and white noise of that rms, by less.
    Mistakes: ``sqrt(3)`` or ``12`` for ``sqrt(12)`` (the ramp's slope above, or far below,
    the bound)."""
    fl = Fluctuations(sigma=0.17e-6, scales=np.array([2.5, 10.0, 40.0]),
                      relative=np.array([0.12, 0.06, 0.03]),
                      absolute=np.array([9e-4, 6e-4, 4e-4]), lag=0.41, lag_speed=6.3e-6,
                      lag_floor=0.35e-6)
    T = 230.0
    t = np.linspace(0.0, T, 4601)
    rms = 0.41 * 6.3e-6
    bound = float(fl.absolute_at(np.array([T]), np.array([2.1e-6]))[0])
    assert bound < 4e-4 * math.sqrt(40.0 / T)  # the bound, not the random walk, is read here

    def slope(e: np.ndarray) -> float:
        e = (e - e.mean()) * rms / np.sqrt(np.mean((e - e.mean()) ** 2))
        return abs(float(np.polyfit(t, e, 1)[0]))

    assert slope(t) == pytest.approx(bound, rel=1e-3)
    rng = np.random.default_rng(47)
    for e in (np.cumsum(rng.normal(size=t.size)), np.sin(2 * np.pi * t / (1.7 * T) + 0.4),
              rng.normal(size=t.size)):
        assert slope(e) < bound


def test_levels_computed_once_give_what_each_reading_computes() -> None:
    """The pruning reads the levels of a table of stretches once (:meth:`Fluctuations.levels`)
    for its holds, confidences and slips; each must equal its own reading bit for bit, at
    generic durations either side of the longest scale (40 s), the lag bounds binding on some:
    the scatter with and without velocities, and the slip ratio, whose shorter stretch's
    levels are read off the table's. Mistakes: the longer stretch's levels read for the slip
    (``<`` for ``>``); the scatter's absolute part without its lag bound (levels unbounded)."""
    from dryfriction.records.detection import _slip_ratio

    fl = Fluctuations(sigma=0.17e-6, scales=np.array([2.5, 10.0, 40.0]),
                      relative=np.array([0.12, 0.06, 0.03]),
                      absolute=np.array([9e-7, 6e-7, 4e-7]), lag=0.41, lag_speed=6.3e-6,
                      lag_floor=0.35e-6)
    d = np.array([3.7, 230.0, 17.3, 520.0, 61.0, 1.3])
    v = np.array([2.1e-6, 7.7e-6, 0.2e-6, 2.9e-6, 0.0, 11.3e-6])
    sxx = np.array([4.1, 9.9e4, 420.0, 2.2e6, 1.9e4, 0.6])
    lv = fl.levels(d)
    # the scatter as it was computed before the levels, operation for operation
    for u in (v, 0.0 * v):
        before = np.sqrt(fl.sigma**2 / np.maximum(sxx, 1e-300) + fl.absolute_at(d, u) ** 2
                         + (fl.relative_at(d) * u) ** 2)
        assert np.array_equal(fl.scatter(d, u, sxx, lv), before)
    own = _slip_ratio(v, d, fl)
    assert np.array_equal(_slip_ratio(v, d, fl, lv), own)
    # the shorter stretch's levels, computed independently for each boundary
    dmin = np.minimum(d[1:], d[:-1])
    u = np.abs(v)
    big = np.array([max(u[max(j - 1, 0):j + 3]) for j in range(len(d) - 1)])
    lag = np.minimum(fl.relative_at(dmin) * dmin, fl.lag)
    want = np.abs(np.diff(v)) * dmin / np.hypot(lag * big, fl.absolute_at(dmin) * dmin)
    np.testing.assert_allclose(own, want, rtol=1e-14)
