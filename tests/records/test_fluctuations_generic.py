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
