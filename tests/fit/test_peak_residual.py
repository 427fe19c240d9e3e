"""The peak residual of a step (fit/steps.py ``_peak_residual``, module docstring: the mean
residual over PEAK_SAMPLES samples at the data's peak after the change) against that
definition written here, for an up step, a down step and a reslide after a hold (issue 25: up
steps only hide an extreme looked for on one side). Each test names the mistake it is for;
each was seen failing with it applied."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.fit.steps import PEAK_SAMPLES, _peak_residual
from dryfriction.records.data import SeriesData


def _by_definition(mu: np.ndarray, resid: np.ndarray, i0: int, up: bool) -> tuple[float, int]:
    m = PEAK_SAMPLES
    means = np.array([mu[i0 + j:i0 + j + m].mean() for j in range(len(mu) - i0 - m + 1)])
    j = int(np.argmax(means) if up else np.argmin(means))
    return float(resid[i0 + j:i0 + j + m].mean()), i0 + j + m // 2


@pytest.mark.parametrize("before, after", [(1.1e-6, 3.4e-6), (3.4e-6, 0.9e-6), (0.0, 1.3e-6)])
def test_peak_residual_is_its_definition(before: float, after: float) -> None:
    # mistakes: the extreme looked for as a maximum after a down step too; the change found
    # as the first change of velocity (a hold's start) rather than the last to sliding; the
    # residual of the peak's one sample instead of the mean of PEAK_SAMPLES
    n, i_ch = 260, 90
    t = 5.0 + 0.3 * np.arange(n)
    v = np.r_[np.full(30, 2.0e-6), np.full(i_ch - 30, before), np.full(n - i_ch, after)]
    k = np.arange(n)
    sign = 1.0 if after > before else -1.0
    bump = sign * 4e-3 * np.exp(-np.abs(k - (i_ch + 40)) / 9.0) * (k >= i_ch)
    mu = 0.62 + bump + 3e-4 * np.sin(0.7 * k)
    resid = 1e-4 * np.cos(0.31 * k) + 2e-6 * (k - i_ch)  # differs from sample to sample
    got = _peak_residual(SeriesData(t, v, mu), mu - resid)
    want = _by_definition(mu, resid, i_ch, after > before)
    assert got[1] == want[1]
    assert got[0] == pytest.approx(want[0], rel=1e-12)
    assert abs(got[1] - (i_ch + 40)) <= PEAK_SAMPLES  # at the bump (the test can fail)
