"""The testing machine seen from a record (fit/machine.py) at generic points (issue 25): no
velocity, friction parameter or sampling interval at 1, a hold between two different
velocities, up and down steps, against the definitions written here. Each test names the
mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.fit.machine import hold_remnant, load_point_displacement, loading_slope_stiffness
from dryfriction.records.data import SeriesData


def _times(n: int) -> np.ndarray:
    """Irregular sampling: intervals 0.31..0.69 s."""
    return 2.7 + np.concatenate([[0.0], np.cumsum(0.5 + 0.19 * np.sin(0.9 * np.arange(n - 1)))])


def test_load_point_displacement_integrates_the_program_forwards() -> None:
    # mistakes: each stretch at the velocity of the sample that ends it (a right Riemann sum);
    # the displacement from zero time, not from t[0]
    t = _times(40)
    v = np.r_[np.full(11, 2.3e-6), np.zeros(9), np.full(12, 0.7e-6), np.full(8, 4.1e-6)]
    x = load_point_displacement(SeriesData(t, v, np.full(40, 0.6)))
    want = np.concatenate([[0.0], np.cumsum(v[:-1] * np.diff(t))])  # the definition
    np.testing.assert_allclose(x, want, rtol=1e-12, atol=1e-18)


def test_hold_remnant_between_two_different_velocities() -> None:
    # mistakes: the healing from the reslide's velocity, not the one before the hold (equal in
    # the hand test at 1 m/s); the hold one sample short; b or Dc left out (1 there); the slip
    # counted from the hold's start in time, not in load-point travel
    t = _times(90)
    v = np.r_[np.full(20, 2.3e-6), np.zeros(30), np.full(40, 0.7e-6)]
    d = SeriesData(t, v, np.full(90, 0.6))
    b, dc, i = 0.013, 4.1e-6, 75
    rem, hold, slip = hold_remnant(d, i, b, dc)
    assert hold == pytest.approx(t[50] - t[20], rel=1e-14)
    assert slip == pytest.approx(0.7e-6 * (t[i] - t[50]), rel=1e-12)
    want = b * math.log1p(hold * 2.3e-6 / dc) * math.exp(-slip / dc)
    assert rem == pytest.approx(want, rel=1e-12)
    assert 1e-4 < rem < b  # a visible remnant (the test can fail)


def _slope_by_definition(x: np.ndarray, mu: np.ndarray, i0: int, end: int, up: bool,
                         fraction: float) -> float:
    """The docstring's recipe: the least-squares line of ``mu`` against ``x`` from the change
    until ``mu`` has covered ``fraction`` of its way from the mean of the last 10 samples to
    the extreme after the change (at least 5 samples)."""
    base = float(np.mean(mu[i0 - 10:i0]))
    after = mu[i0:end]
    ext = float(after.max() if up else after.min())
    n = 5
    for k, m in enumerate(after):
        if abs(m - base) >= fraction * abs(ext - base):
            n = max(5, k + 1)
            break
    A = np.column_stack([x[i0:i0 + n], np.ones(n)])
    return float(np.linalg.lstsq(A, mu[i0:i0 + n], rcond=None)[0][0])


@pytest.mark.parametrize("vb, va", [(0.9e-6, 3.4e-6), (3.4e-6, 1.3e-6)])
def test_loading_slope_stiffness_up_and_down(vb: float, va: float) -> None:
    # mistakes: the extreme after a decrease taken as the maximum (the window cut at 5
    # samples); the level before the change from its last sample, not the mean of ten; the
    # velocity factor 1 - v_after/v_before
    t = _times(120)
    v = np.r_[np.full(40, vb), np.full(60, va), np.full(20, 0.5 * va)]
    k, L = 2.7e3, 9.7e-6  # a curved approach to the new level over L of load-point travel
    x = load_point_displacement(SeriesData(t, v, np.zeros(120)))
    rel = np.maximum(x - x[40], 0.0)
    S = k * (1.0 - vb / va)  # the elastic slope against load-point displacement
    mu = 0.61 + 0.004 * np.sin(1.3 * np.arange(120)) * (np.arange(120) < 40) \
        + S * L * (1.0 - np.exp(-rel / L))
    fraction = 0.45
    got = loading_slope_stiffness(SeriesData(t, v, mu), fraction=fraction)
    want = _slope_by_definition(x, mu, 40, 100, va > vb, fraction) / (1.0 - vb / va)
    assert got == pytest.approx(want, rel=1e-9)
    assert 0.5 * k < got < k  # low, as the slider accelerates (the test can fail)
