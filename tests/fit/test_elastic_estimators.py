"""The estimators of fit/elastic.py against their definitions on signals of known spectrum:
the noise of white noise (a robust scale of the differences, over sqrt 2) and the loading
slope's 95 % interval: ordinary least squares' standard error (``numpy.polyfit``'s covariance,
another route) times the AR(1) inflation ``sqrt((1 + rho)/(1 - rho))`` with ``rho`` the steady
part's lag-1 autocorrelation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.fit.elastic import _noise, _slope


def test_noise_of_white_noise_is_its_standard_deviation() -> None:
    # mistakes: the differences' scale not divided by sqrt 2 (sigma sqrt 2), the MAD without
    # its 1.4826 (sigma / 1.48); a level and a trend do not enter (differences)
    rng = np.random.default_rng(41)
    sigma = 1.7e-3
    mu = 0.61 + 2e-5 * np.arange(40000) + rng.normal(0.0, sigma, 40000)
    assert _noise(mu) == pytest.approx(sigma, rel=0.02)
    assert math.isnan(_noise(mu[:3]))


def _ar1(rng, n, rho, s):
    e = rng.normal(0.0, s, n)
    out = np.empty(n)
    out[0] = e[0] / math.sqrt(1 - rho**2)
    for i in range(1, n):
        out[i] = rho * out[i - 1] + e[i]
    return out


def test_slope_interval_is_ols_times_the_ar1_inflation() -> None:
    # mistakes: the inflation inverted ((1 - rho)/(1 + rho)), the residual variance over n
    # instead of n - 2, z ignored (a 1-sigma interval)
    rng = np.random.default_rng(8)
    x = 2.1e-6 + np.cumsum(rng.uniform(0.5e-7, 1.5e-7, 24))  # a non-uniform displacement
    mu = 0.58 + 3100.0 * (x - x[0]) + rng.normal(0.0, 4e-4, x.size)
    # white steady part, smaller than the residuals: OLS's own error
    calm = rng.normal(0.0, 1e-5, 400)
    k, lo, hi = _slope(x, mu, 1.96, calm)
    p, cov = np.polyfit(x, mu, 1, cov="unscaled")
    r = mu - np.polyval(p, x)
    se_ols = math.sqrt(float(r @ r) / (x.size - 2) * cov[0, 0])
    rho = min(max(float(np.corrcoef(calm[1:], calm[:-1])[0, 1]), 0.0), 0.99)
    assert k == pytest.approx(p[0], rel=1e-10)
    se = (hi - lo) / (2 * 1.96)
    assert se == pytest.approx(se_ols * math.sqrt((1 + rho) / (1 - rho)), rel=1e-9)
    assert (hi - k) == pytest.approx(k - lo, rel=1e-12)
    # an AR(1) steady part with rho = 0.8, larger than the residuals: its variance and rho
    calm = _ar1(rng, 4000, 0.8, 2e-3)
    k2, lo2, hi2 = _slope(x, mu, 2.5, calm)
    rho = float(np.corrcoef(calm[1:], calm[:-1])[0, 1])
    assert rho == pytest.approx(0.8, abs=0.03)
    s2 = float(calm @ calm) / (calm.size - 2)
    want = math.sqrt(s2 * cov[0, 0] * (1 + rho) / (1 - rho))
    assert (hi2 - lo2) / (2 * 2.5) == pytest.approx(want, rel=1e-9)
    assert _slope(x[:5], mu[:5], 1.96, calm) is None  # fewer than MIN_SAMPLES = 6
    assert _slope(x[:6], mu[:6], 1.96, calm) is not None
