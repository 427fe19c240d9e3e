"""Autocorrelation-robust (Newey–West) covariance of fitted parameters.

Checked on linear least squares with AR(1) noise, where the exact covariance of the estimates is
known in closed form, ``(X^T X)^-1 X^T Sigma X (X^T X)^-1`` with
``Sigma_ij = s^2 rho^|i-j| / (1 - rho^2)``, independently of the code under test.
"""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.fit.statistics import covariance, hac_bandwidth, hac_covariance

N = 3000


def _design(n: int = N) -> np.ndarray:
    t = np.linspace(0.0, 1.0, n)
    return np.column_stack([np.ones(n), t, np.sin(6 * np.pi * t)])


def _ar1(rng: np.random.Generator, n: int, rho: float, s: float = 1.0) -> np.ndarray:
    e = rng.normal(0.0, s, n)
    out = np.empty(n)
    out[0] = e[0] / np.sqrt(1.0 - rho**2)
    for i in range(1, n):
        out[i] = rho * out[i - 1] + e[i]
    return out


def _exact_stderr(X: np.ndarray, rho: float, s: float = 1.0) -> np.ndarray:
    n = len(X)
    idx = np.arange(n)
    sigma = s**2 * rho ** np.abs(idx[:, None] - idx[None, :]) / (1.0 - rho**2)
    bread = np.linalg.inv(X.T @ X)
    return np.sqrt(np.diag(bread @ X.T @ sigma @ X @ bread))


@pytest.mark.parametrize("rho", [0.0, 0.9])
def test_hac_stderr_matches_the_exact_covariance(rho: float):
    """Mean HAC standard error within 15 % of the exact one for white and AR(1) noise; the
    white-noise covariance is right for rho = 0 and ~sqrt((1+rho)/(1-rho)) too small for 0.9
    (so a HAC that ignored the lags, or used them with the wrong weight, fails)."""
    rng = np.random.default_rng(1)
    X = _design()
    exact = _exact_stderr(X, rho)
    beta = np.array([0.6, -0.01, 0.002])
    hac, naive, hits_hac, hits_naive = [], [], 0, 0
    reps = 60
    for _ in range(reps):
        y = X @ beta + _ar1(rng, N, rho)
        b, *_ = np.linalg.lstsq(X, y, rcond=None)
        r = y - X @ b
        J = -X
        h = hac_covariance(J, r)[0]
        w = covariance(J, float(r @ r) / (N - 3))
        hac.append(h.stderr)
        naive.append(w.stderr)
        hits_hac += int(np.all(np.abs(b - beta) <= 1.96 * h.stderr))
        hits_naive += int(np.all(np.abs(b - beta) <= 1.96 * w.stderr))
    ratio = np.mean(hac, axis=0) / exact
    assert np.all(np.abs(ratio - 1.0) < 0.15), ratio
    naive_ratio = np.mean(naive, axis=0) / exact
    if rho == 0.0:
        assert np.all(np.abs(naive_ratio - 1.0) < 0.1), naive_ratio
    else:
        assert naive_ratio[0] < 0.35, naive_ratio  # sqrt(0.1/1.9) = 0.23
        assert hits_hac / reps >= 0.7 and hits_naive / reps <= 0.4, (hits_hac, hits_naive)


def test_bandwidth_grows_with_the_correlation_time():
    rng = np.random.default_rng(2)
    lags = [hac_bandwidth(_ar1(rng, N, rho)) for rho in (0.0, 0.5, 0.9, 0.99)]
    assert lags[0] <= 3 and lags == sorted(lags) and lags[-1] > 100, lags


def test_singular_jacobian_is_flagged():
    X = _design()
    J = np.column_stack([X, X[:, :1]])
    c, lags = hac_covariance(J, np.random.default_rng(3).normal(size=N))
    assert c.singular and np.all(np.isinf(c.stderr)) and lags == 0
