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


def _basalt_times() -> np.ndarray:
    """10 Hz for 30 s, then 100 Hz for 20 s (the sampling of issue 30's basalt record)."""
    return np.concatenate([np.arange(0.0, 30.0, 0.1), np.arange(30.01, 50.0, 0.01)])


def _local_design(t: np.ndarray) -> np.ndarray:
    """A constant, a ramp, a regressor confined to ~0.2 s after 30 s, as the machine
    stiffness is in a velocity-step window (it is fixed by the first instants after the
    change), and one confined to 20-22 s, in the 10 Hz part."""
    u = t - 30.0
    return np.column_stack([np.ones(t.size), u / 20.0, np.where(u >= 0, np.exp(-u / 0.1), 0),
                            ((t > 20.0) & (t < 22.0)).astype(float)])


@pytest.mark.slow
def test_time_lag_kernel_holds_a_local_parameter_under_red_noise():
    """White (0.5) plus Ornstein-Uhlenbeck (0.6, 0.5 s) noise on the irregular sampling:
    the exact covariance ``B X^T Sigma X B`` with ``Sigma = 0.25 I + 0.36 exp(-|dt|/0.5)``
    is independent of the code. The local coefficients' standard errors from
    :func:`time_hac_covariance` are within 20 % of it (RMS over 150 draws; measured 0.94 for
    the 0.2 s one, 0.87 for the 2 s one at 10 Hz, which the Bartlett taper shortens) and
    their 95 % intervals hold the truth in >= 90 % (>= 85 %) of the draws (measured 141 and
    135 of 150); :func:`hac_covariance` (a Bartlett kernel on the scores, bandwidth a lag
    count) gives 0.32 of it for the 0.2 s one, the interval issue 30's machine stiffness had.
    Caught: ``rho`` from the lag-1 autocorrelation (white part kept: 133 of 150), lags
    counted in samples rather than time (1.23 for the 10 Hz one)."""
    from dryfriction.fit.statistics import time_hac_covariance

    t = _basalt_times()
    X = _local_design(t)
    sigma = 0.25 * np.eye(t.size) + 0.36 * np.exp(-np.abs(t[:, None] - t[None, :]) / 0.5)
    bread = np.linalg.inv(X.T @ X)
    exact = np.sqrt(np.diag(bread @ X.T @ sigma @ X @ bread))[2:]
    chol = np.linalg.cholesky(sigma)
    rng = np.random.default_rng(11)
    new, old, hits = [], [], np.zeros(2)
    draws = 150
    for _ in range(draws):
        y = chol @ rng.normal(size=t.size)  # the true coefficients are 0
        beta = bread @ X.T @ y
        r = y - X @ beta
        se = time_hac_covariance(X, r, t)[0].stderr[2:]
        new.append(se)
        old.append(hac_covariance(X, r)[0].stderr[2:])
        hits += np.abs(beta[2:]) <= 1.96 * se
    rms_new, rms_old = (np.sqrt(np.mean(np.square(v), axis=0)) / exact for v in (new, old))
    assert np.all(np.abs(rms_new - 1.0) < 0.2) and hits[0] >= 0.9 * draws \
        and hits[1] >= 0.85 * draws, (rms_new, hits)
    assert rms_old[0] < 0.75, rms_old


def test_time_lag_kernel_is_the_white_covariance_for_white_noise():
    """Independent noise: the estimate is within 10 % of ``s^2 (X^T X)^-1``'s (RMS over 40
    draws), for every coefficient."""
    from dryfriction.fit.statistics import time_hac_covariance

    t = _basalt_times()
    X = _local_design(t)
    rng = np.random.default_rng(5)
    ratios = []
    for _ in range(40):
        y = rng.normal(0.0, 0.7, t.size)
        beta = np.linalg.lstsq(X, y, rcond=None)[0]
        r = y - X @ beta
        white = covariance(X, float(r @ r) / (t.size - 3)).stderr
        ratios.append(time_hac_covariance(X, r, t)[0].stderr / white)
    rms = np.sqrt(np.mean(np.square(ratios), axis=0))
    assert np.all(np.abs(rms - 1.0) < 0.1), rms


def _window(t: np.ndarray, t0: float, tau: float) -> np.ndarray:
    """A step window's design: a constant, a ramp, a transient after ``t0`` (the 'others')
    and a shorter one (the held parameter, as k is: fixed by the first instants)."""
    u = t - t0
    after = u >= 0
    return np.column_stack([np.ones(t.size), u / 7.0, np.where(after, 1 - np.exp(-u / tau), 0),
                            np.where(after, np.exp(-u / 0.13), 0)])


def test_held_parameter_covariance_is_the_two_step_estimators():
    """Two windows share the last coefficient (the machine stiffness of a record). Step one
    fits each window freely and takes the inverse-variance mean of that coefficient; step two
    refits window 1 with it held. Everything is linear in the noise, so the covariance of
    window 1's other coefficients is exactly ``L_1 Sigma_1 L_1^T + L_2 Sigma_2 L_2^T``
    (``L_s`` the maps from each window's noise; white plus Ornstein-Uhlenbeck noise, the two
    windows independent): the held fit's own covariance plus
    :func:`held_parameter_covariance` equals it to rounding. Caught: the cross term left out
    (``share = 0``, Murphy-Topel's ``C V1 C^T`` alone: 4.1 % off on one variance, measured),
    ``G``'s sign flipped in ``x``. With white noise the cross term vanishes."""
    from dryfriction.fit.statistics import held_parameter_covariance

    t1 = np.concatenate([np.arange(0.0, 5.0, 0.1), np.arange(5.01, 12.0, 0.01)])
    t2 = np.arange(0.0, 9.0, 0.02)
    X1, X2 = _window(t1, 5.0, 0.7), _window(t2, 3.3, 1.1)

    def sigma(t: np.ndarray, red: float) -> np.ndarray:
        return 0.3**2 * np.eye(t.size) + red**2 * np.exp(-np.abs(t[:, None] - t) / 0.4)

    for red, cross_matters in ((0.5, True), (0.0, False)):
        S1, S2 = sigma(t1, red), sigma(t2, red)
        A1, A2 = (np.linalg.pinv(X) for X in (X1, X2))  # (X^T X)^-1 X^T
        C1, C2 = (A @ S @ A.T for A, S in ((A1, S1), (A2, S2)))  # exact free covariances
        w1, w2 = 1.0 / C1[3, 3], 1.0 / C2[3, 3]
        W = w1 + w2
        Ao = np.linalg.pinv(X1[:, :3])  # the held fit of window 1
        L1 = Ao - np.outer(Ao @ X1[:, 3], A1[3]) * w1 / W
        L2 = -np.outer(Ao @ X1[:, 3], A2[3]) * w2 / W
        exact = L1 @ S1 @ L1.T + L2 @ S2 @ L2.T
        held_only = Ao @ S1 @ Ao.T
        full = held_only + held_parameter_covariance(-X1, C1, 3, 1.0 / W, w1 / W)
        np.testing.assert_allclose(full, exact, rtol=1e-9, atol=1e-12 * np.abs(exact).max())
        no_cross = held_only + held_parameter_covariance(-X1, C1, 3, 1.0 / W, 0.0)
        gap = np.max(np.abs(np.diag(no_cross) / np.diag(exact) - 1.0))
        assert (gap > 0.02) if cross_matters else (gap < 1e-9), (red, gap)
        assert np.all(np.diag(full) > np.diag(held_only) * 1.01), (red, full, held_only)


def test_local_covariance_is_a_covariance_where_the_time_lag_one_is_not():
    """userfixA (a new user's record of pure noise: the step's stiffness printed as
    ``150.1 [150.1, 150.1]``). The time-lag sandwich averages each lag's products over its
    pairs, so it need not be positive semidefinite: on these 60 samples of AR(1) noise (rho
    0.95, steps of 0.5 and 1 s; found by a seeded search) it gives a negative variance for
    the third coefficient. :func:`local_covariance` must then return the score HAC, which is
    a covariance (Bartlett weights), not a matrix whose ``sqrt|C_ii|`` hides the sign.
    Mistake caught: the positive-semidefinite check left out (the negative variance kept)."""
    from dryfriction.fit.statistics import (
        local_covariance,
        positive_semidefinite,
        time_hac_covariance,
    )

    rng = np.random.default_rng(8)
    n = 60
    t = np.cumsum(rng.choice([0.5, 1.0], n))
    e = rng.normal(size=n)
    r = np.zeros(n)
    for i in range(n):
        r[i] = 0.95 * (r[i - 1] if i else 0.0) + e[i]
    J = np.column_stack([np.ones(n), np.exp(-(t - t[0]) / 3.0),
                         rng.normal(size=n) * np.exp(-(t - t[0]) / 5.0)])
    lag = time_hac_covariance(J, r, t)[0]
    assert not lag.singular and np.diag(lag.matrix)[2] < 0  # the case this test is for
    assert not positive_semidefinite(lag.matrix)
    got, lags = local_covariance(J, r, t)
    score, score_lags = hac_covariance(J, r)
    assert positive_semidefinite(got.matrix) and np.all(np.diag(got.matrix) > 0)
    assert np.array_equal(got.matrix, score.matrix) and lags == score_lags
    # round-off is allowed: a covariance with a -1e-14 eigenvalue is still one
    assert positive_semidefinite(np.diag([1.0, 2.0, -1e-14]))
    assert not positive_semidefinite(np.diag([1.0, 2.0, -1e-6]))


def test_an_indefinite_sandwich_is_singular_not_a_number(monkeypatch):
    """userfixA: on a noise record's slide-hold-slide window the score HAC gave ``ln a``,
    ``ln b``, ``ln Dc``, ``ln k`` and the trend negative variances (``Omega``'s round-off,
    1e-16 of its largest eigenvalue, times the bread's largest eigenvalue squared); the
    standard errors ``sqrt|C_ii|`` hid it and the row printed k as ``150.1 [150.1, 150.1]``.
    Here ``Omega`` gets a negative eigenvalue of 1e-3 of its largest (the case in
    miniature): the result must be singular (no interval), and on a well-conditioned problem
    the same code is untouched (mistake caught: the check left out)."""
    import dryfriction.fit.statistics as st

    rng = np.random.default_rng(5)
    X = _design(400)
    r = _ar1(rng, 400, 0.5)
    good, L = hac_covariance(X, r)
    assert not good.singular and L > 0 and st.positive_semidefinite(good.matrix)
    orig = st._bartlett

    def indefinite(u, lags):
        om = orig(u, lags)
        w, v = np.linalg.eigh(om)
        w[0] = -1e-3 * w[-1]
        return (v * w) @ v.T

    monkeypatch.setattr(st, "_bartlett", indefinite)
    bad, L = hac_covariance(X, r)
    assert bad.singular and L == 0 and np.all(np.isinf(bad.stderr))
