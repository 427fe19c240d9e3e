"""Estimators against their definitions (issue 25 item 2).

Each estimator is fed a signal whose answer is known from its construction, not from the code:
white noise of a given standard deviation, AR(1), AR(2) and MA(1) noise whose autocovariances
are written here from the textbook formulas (Box & Jenkins, *Time Series Analysis*, §3.2-3.4),
and linear least squares, whose exact estimate covariance under any stationary noise is
``(X^T X)^-1 X^T Sigma X (X^T X)^-1``. The Newey–West and Andrews–Monahan steps are written
out again here, in loops, from the papers, and compared with the package on a generic input.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.fit.statistics import (
    covariance,
    hac_bandwidth,
    hac_covariance,
    lag1_autocorrelation,
)
from dryfriction.fit.steps import steady_noise, white_noise
from dryfriction.records.segmentation import noise_level

N = 3000


# ------------------------------------------------------------------ noises of known spectrum
def _ma1(rng: np.random.Generator, n: int, th: float) -> np.ndarray:
    w = rng.normal(size=n + 1)
    return w[1:] + th * w[:-1]


def _ma1_acov(th: float) -> np.ndarray:
    return np.array([1.0 + th * th, th])


def _ar2(rng: np.random.Generator, n: int, p1: float, p2: float) -> np.ndarray:
    burn = 500
    w = rng.normal(size=n + burn)
    x = np.zeros(n + burn)
    for i in range(2, n + burn):
        x[i] = p1 * x[i - 1] + p2 * x[i - 2] + w[i]
    return x[burn:]


def _ar2_acov(p1: float, p2: float, lags: int = 400) -> np.ndarray:
    """Yule–Walker: ``rho_1 = p1/(1 - p2)``, ``rho_k = p1 rho_{k-1} + p2 rho_{k-2}``, and
    ``gamma_0 = (1 - p2) / ((1 + p2) ((1 - p2)^2 - p1^2))`` (unit innovations)."""
    g0 = (1.0 - p2) / ((1.0 + p2) * ((1.0 - p2) ** 2 - p1 * p1))
    r = [1.0, p1 / (1.0 - p2)]
    for _ in range(2, lags):
        r.append(p1 * r[-1] + p2 * r[-2])
    return g0 * np.array(r)


def _ar1(rng: np.random.Generator, n: int, rho: float) -> np.ndarray:
    e = rng.normal(size=n)
    x = np.empty(n)
    x[0] = e[0] / math.sqrt(1.0 - rho * rho)
    for i in range(1, n):
        x[i] = rho * x[i - 1] + e[i]
    return x


def _design(n: int = N) -> np.ndarray:
    t = np.linspace(0.0, 1.0, n)
    return np.column_stack([np.ones(n), t, np.sin(6 * np.pi * t)])


def _exact_stderr(X: np.ndarray, acov: np.ndarray) -> np.ndarray:
    """Exact standard errors of OLS under stationary noise with autocovariances ``acov``."""
    n = len(X)
    lag = np.abs(np.arange(n)[:, None] - np.arange(n)[None, :])
    sigma = np.where(lag < len(acov), np.asarray(acov)[np.minimum(lag, len(acov) - 1)], 0.0)
    bread = np.linalg.inv(X.T @ X)
    return np.sqrt(np.diag(bread @ X.T @ sigma @ X @ bread))


# ------------------------------------------------------------------ noise levels
@pytest.mark.parametrize("sigma", [3.7e-4, 2.2])
def test_noise_level_recovers_a_known_white_noise_on_a_smooth_signal(sigma: float) -> None:
    """Mistake: ``var(x[i+1] - 2x[i] + x[i-1])`` taken as ``2 sigma^2`` (``/sqrt 2``, the
    first-difference factor) instead of ``6 sigma^2``: sigma off by sqrt 3."""
    rng = np.random.default_rng(11)
    t = np.linspace(0.0, 40.0, 20000)
    x = 5.0 * sigma * np.sin(0.3 * t) + 0.1 * t + rng.normal(0.0, sigma, t.size)
    assert noise_level(x) == pytest.approx(sigma, rel=0.05)


def test_white_noise_and_steady_noise_recover_a_known_sigma() -> None:
    """``white_noise`` (first differences, ``/sqrt 2``) and ``steady_noise`` (about a line,
    ``n - 2`` dof) on white noise of sigma 4.1e-4 riding on a line with a generic slope.
    Mistakes: ``/sqrt 6`` or no ``/sqrt 2`` in ``white_noise``; the line not removed."""
    rng = np.random.default_rng(12)
    s = 4.1e-4
    t = np.linspace(3.0, 900.0, 8000)
    mu = 0.63 - 2.3e-5 * t + rng.normal(0.0, s, t.size)
    assert white_noise(mu) == pytest.approx(s, rel=0.05)
    assert steady_noise(t, mu) == pytest.approx(s, rel=0.03)


@pytest.mark.parametrize("kind", ["ar1", "ma1"])
def test_steady_noise_is_the_stationary_std_of_correlated_noise(kind: str) -> None:
    """``steady_noise`` holds slower fluctuations too: on AR(1) (rho 0.7) its value is the
    stationary ``1/sqrt(1 - rho^2)``, on MA(1) (theta -0.6) ``sqrt(1 + theta^2)``; and
    ``white_noise`` of MA(1) noise is ``sqrt(1 + theta^2 - theta)``, half the variance of its
    first differences, ``2 gamma_0 - 2 gamma_1`` (Box & Jenkins)."""
    rng = np.random.default_rng(13)
    t = np.arange(20000) * 0.25
    if kind == "ar1":
        x, std = _ar1(rng, t.size, 0.7), 1.0 / math.sqrt(1.0 - 0.49)
    else:
        x, std = _ma1(rng, t.size, -0.6), math.sqrt(1.36)
        # var(x_t - x_{t-1}) = 2 gamma_0 - 2 gamma_1; the MAD of a Gaussian is exact
        assert white_noise(x) == pytest.approx(math.sqrt(1.36 + 0.6), rel=0.04)
    assert steady_noise(t, 0.5 + x * 1e-3) == pytest.approx(std * 1e-3, rel=0.04)


@pytest.mark.parametrize(("kind", "expected"), [
    ("ar1", 0.83), ("ma1", 0.7 / 1.49), ("ar2", 1.2 / 1.5)])
def test_lag1_autocorrelation_of_known_processes(kind: str, expected: float) -> None:
    """AR(1): rho; MA(1): theta/(1 + theta^2); AR(2): p1/(1 - p2) (Yule–Walker)."""
    rng = np.random.default_rng(14)
    x = {"ar1": lambda: _ar1(rng, 40000, 0.83), "ma1": lambda: _ma1(rng, 40000, 0.7),
         "ar2": lambda: _ar2(rng, 40000, 1.2, -0.5)}[kind]()
    assert float(lag1_autocorrelation(x + 7.0)[0]) == pytest.approx(expected, abs=0.02)


def test_hac_bandwidth_is_andrews_plug_in() -> None:
    """``1.1447 (alpha n)^(1/3)``, ``alpha = 4 rho^2/((1 - rho)^2 (1 + rho)^2)`` written here
    (Andrews 1991, eqs. 5.3 and 6.4), ``rho`` the lag-1 autocorrelation computed here."""
    rng = np.random.default_rng(15)
    for rho_true in (0.3, 0.8, 0.95):
        x = _ar1(rng, 2500, rho_true)
        xc = x - x.mean()
        rho = float(xc[1:] @ xc[:-1] / (xc @ xc))
        alpha = 4 * rho**2 / ((1 - rho) ** 2 * (1 + rho) ** 2)
        want = min(max(math.ceil(1.1447 * (alpha * 2500) ** (1 / 3)), 1), 1250)
        assert hac_bandwidth(x) == want


# ------------------------------------------------------------------ covariances
def test_white_covariance_is_s2_times_the_inverse_normal_matrix() -> None:
    """``covariance(J, s2) = s2 (J^T J)^-1`` at a generic J and s2 (no factor 2, no sqrt)."""
    rng = np.random.default_rng(16)
    J = rng.normal(size=(50, 3)) @ np.array([[1.0, 0.3, 0.0], [0.0, 2.0, -0.4], [0.0, 0.0, 0.7]])
    c = covariance(J, 3.3e-5)
    want = 3.3e-5 * np.linalg.inv(J.T @ J)
    np.testing.assert_allclose(c.matrix, want, rtol=1e-10)
    np.testing.assert_allclose(c.stderr, np.sqrt(np.diag(want)), rtol=1e-10)


def _hac_by_definition(J: np.ndarray, r: np.ndarray, lags: int, cap: float) -> np.ndarray:
    """Andrews & Monahan (1992) prewhitened Newey–West, written out with explicit loops:
    scores ``u_t = J_t r_t``; VAR(1) ``u_t = A u_{t-1} + e_t`` by least squares, singular values
    of ``A`` capped; ``Omega_e = sum_{|l|<=L} (1 - |l|/(L+1)) sum_t e_t e_{t-l}^T`` (both signs of
    ``l``: for ``l < 0`` the transpose), times ``n/(n - 1)``; recoloured
    ``(I - A)^-1 Omega_e (I - A)^-T``; sandwich with ``(J^T J)^-1`` times ``n/(n - p)``."""
    n, p = J.shape
    u = J * r[:, None]
    A = np.linalg.lstsq(u[:-1], u[1:], rcond=None)[0].T  # u_t = A u_{t-1}
    U, S, Vt = np.linalg.svd(A)
    A = (U * np.minimum(S, cap)) @ Vt
    e = np.array([u[t] - A @ u[t - 1] for t in range(1, n)])
    m = len(e)
    omega = np.zeros((p, p))
    for lag in range(-lags, lags + 1):
        w = 1.0 - abs(lag) / (lags + 1.0)
        for t in range(max(0, lag), min(m, m + lag)):
            omega += w * np.outer(e[t], e[t - lag])
    omega *= n / (n - 1.0)
    color = np.linalg.inv(np.eye(p) - A)
    omega = color @ omega @ color.T
    bread = np.linalg.inv(J.T @ J)
    return bread @ omega @ bread * (n / (n - p))


def test_hac_covariance_matches_its_definition_at_a_generic_point() -> None:
    """Mistakes: the Bartlett sum without its transpose term (``g`` instead of ``g + g^T``),
    weights ``1 - l/L``, the recolouring on the wrong side, the ``n/(n - p)`` dropped. The
    scores have cross-correlations at lags of both signs (MA(1) residuals on three regressors,
    not AR(1)), so ``sum_t e_t e_{t-l}^T`` is not symmetric."""
    rng = np.random.default_rng(17)
    n = 400
    X = _design(n)
    X[:, 2] = np.roll(X[:, 2], 3) + 0.2 * rng.normal(size=n)
    r = _ma1(rng, n, -0.55) * (1.0 + 0.5 * X[:, 1])
    for lags in (1, 4, 9):
        c, used = hac_covariance(-X, r, lags=lags)
        assert used == lags
        want = _hac_by_definition(-X, r, lags, 0.99)
        np.testing.assert_allclose(c.matrix, want, rtol=1e-9, atol=1e-12 * np.abs(want).max())


@pytest.mark.parametrize(("name", "lo", "hi"), [
    ("ma1+", 0.9, 1.15), ("ma1-", 0.9, 1.22), ("ar2", 0.75, 1.15)])
def test_hac_stderr_against_the_exact_covariance_of_non_ar1_noise(name: str, lo: float,
                                                                  hi: float) -> None:
    """Mean HAC standard error over 30 records / exact, for MA(1) (theta 0.8 and -0.5) and AR(2)
    (0.5, 0.3) noise, where VAR(1) prewhitening leaves correlated ``e_t`` and the Bartlett sum
    has to carry them (measured 1.06, 1.13, 0.80; without the transpose term 1.13, 1.31,
    0.77). The bounds take the estimator's own small-bandwidth bias; the white covariance is
    checked to be off by the known long-run factor, so the comparison can fail."""
    rng = np.random.default_rng(18)
    X = _design()
    gen, acov = {
        "ma1+": (lambda: _ma1(rng, N, 0.8), _ma1_acov(0.8)),
        "ma1-": (lambda: _ma1(rng, N, -0.5), _ma1_acov(-0.5)),
        "ar2": (lambda: _ar2(rng, N, 0.5, 0.3), _ar2_acov(0.5, 0.3)),
    }[name]
    exact = _exact_stderr(X, acov)
    hac, white = [], []
    for _ in range(30):
        y = X @ np.array([0.6, -0.01, 0.002]) + gen()
        b = np.linalg.lstsq(X, y, rcond=None)[0]
        res = y - X @ b
        hac.append(hac_covariance(-X, res)[0].stderr)
        white.append(covariance(-X, float(res @ res) / (N - 3)).stderr)
    ratio = np.mean(hac, axis=0) / exact
    print(f"REPORT {name}: HAC/exact {ratio}")
    assert np.all((ratio > lo) & (ratio < hi)), ratio
    # long-run over short-run variance: sum of acov (both sides) / gamma_0
    lrv = (acov[0] + 2 * acov[1:].sum()) / acov[0]
    np.testing.assert_allclose(np.mean(white, axis=0) / exact, 1 / math.sqrt(lrv), rtol=0.12)


def test_hac_equals_white_on_white_noise() -> None:
    """On white noise the robust and the white standard errors agree (inflation about 1),
    and both are the exact ``sigma sqrt((X^T X)^-1_jj)``: a white covariance off by 2, or
    a robust one that counts the lags twice, fails."""
    rng = np.random.default_rng(19)
    X = _design()
    s = 0.37
    exact = s * np.sqrt(np.diag(np.linalg.inv(X.T @ X)))
    ratios, whites = [], []
    for _ in range(20):
        y = X @ np.array([0.6, -0.01, 0.002]) + rng.normal(0.0, s, N)
        b = np.linalg.lstsq(X, y, rcond=None)[0]
        res = y - X @ b
        w = covariance(-X, float(res @ res) / (N - 3)).stderr
        ratios.append(hac_covariance(-X, res)[0].stderr / w)
        whites.append(w / exact)
    np.testing.assert_allclose(np.mean(ratios, axis=0), 1.0, atol=0.06)
    np.testing.assert_allclose(np.mean(whites, axis=0), 1.0, atol=0.02)


def test_steady_noise_uses_n_minus_2_degrees_of_freedom() -> None:
    """Five samples whose residual about the least-squares line is ``(1, -2, 0, 2, -1)`` (it is
    orthogonal to 1 and t): ``sqrt(10 / 3)``. Mistake: dividing by ``n`` or ``n - 1``."""
    t = np.array([2.0, 3.0, 4.0, 5.0, 6.0])
    r = np.array([1.0, -2.0, 0.0, 2.0, -1.0])
    assert steady_noise(t, 0.41 + 0.03 * t + r) == pytest.approx(math.sqrt(10.0 / 3.0), rel=1e-12)


def test_step_white_covariance_is_the_engines_and_robust_is_about_it_on_white_noise() -> None:
    """A velocity step (independent Radau solver, ``tests/lab_synth.py``) with white noise:
    the white covariance of :func:`step_covariance` gives the engine's standard errors exactly
    (delta method for log parameters), and the robust one is about the white one for the
    parameters the whole window informs (``mu0``, ``trend``: inflation measured 1.02-1.07;
    the transient's ``a``, ``b``, ``Dc``, ``k`` come out lower, 0.6-0.95, the sandwich's
    small-sample bias where a few samples carry the information). Mistakes: the white
    covariance with ``s^2 = RSS/(2 dof)`` or ``RSS/n``; a robust estimate that double counts."""
    import sys
    from pathlib import Path

    from dryfriction.fit.steps import fit_steps, step_covariance
    from dryfriction.records.data import SeriesData

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from lab_synth import Truth, synth_record

    t, v, mu, _ = synth_record(Truth(), [1e-6, 3e-6], duration_slip=300e-6, dt_per_um=0.5,
                               seed=3)
    res = fit_steps(SeriesData(t, v, mu))
    r, d = res.fits[0], res.data[0]
    sc = step_covariance(r, d)
    engine = {p.name: p.stderr for p in r.parameters}
    for j, s in enumerate(sc.specs):
        se = float(sc.white.stderr[j])
        want = s.from_internal(sc.theta[j]) * se if s.log else se
        assert want == pytest.approx(engine[s.name], rel=1e-6), s.name
    names = [s.name for s in sc.specs]
    for name in ("mu0", "trend"):
        assert 0.85 < sc.inflation(names.index(name)) < 1.2, name
    for name in ("a", "b", "dc", "stiffness"):
        assert 0.4 < sc.inflation(names.index(name)) < 1.3, name


# ------------------------------------------------------------------ tests and criteria
def test_runs_test_is_wald_wolfowitz() -> None:
    """Signs ``++-+--+++-`` (n1 = 6, n2 = 4, R = 6 runs): ``E R = 2 n1 n2/n + 1 = 5.8``,
    ``var R = 2 n1 n2 (2 n1 n2 - n)/(n^2 (n - 1)) = 2.1333``, two-sided normal p-value."""
    from scipy.stats import norm

    from dryfriction.fit.statistics import runs_test

    r = np.array([0.3, 1.1, -0.2, 0.7, -0.4, -0.9, 0.1, 0.2, 0.5, -0.6])
    mean, var = 2 * 6 * 4 / 10 + 1, 2 * 6 * 4 * (2 * 6 * 4 - 10) / (100 * 9)
    want = 2 * norm.sf(abs(6 - mean) / math.sqrt(var))
    assert runs_test(r) == pytest.approx(want, rel=1e-12)


def test_information_criteria_are_the_gaussian_definitions() -> None:
    """Estimated noise: ``-2 ln L = n ln(RSS/n)`` (+ const), ``k = p + 1``; AIC ``+ 2k``, AICc
    ``+ 2k(k+1)/(n-k-1)``, BIC ``+ k ln n``. Given noise: ``chi^2 = 2 cost``, ``k = p``."""
    from dryfriction.fit.statistics import information_criteria

    cost, n, p = 0.0137, 83, 4
    ic = information_criteria(cost, n, p, sigma_given=False)
    m2 = n * math.log(2 * cost / n)
    k = p + 1
    assert ic["aic"] == pytest.approx(m2 + 2 * k, rel=1e-12)
    assert ic["aicc"] == pytest.approx(m2 + 2 * k + 2 * k * (k + 1) / (n - k - 1), rel=1e-12)
    assert ic["bic"] == pytest.approx(m2 + k * math.log(n), rel=1e-12)
    given = information_criteria(41.0, n, p, sigma_given=True)
    assert given["aic"] == pytest.approx(82.0 + 2 * p, rel=1e-12)


def test_consistency_test_is_the_chow_f_and_chi2_difference() -> None:
    """F = ``((RSS_joint - RSS_sep)/(p_sep - p)) / (RSS_sep/(n - p_sep))`` and the chi-square
    difference with ``p_sep - p`` dof (written here with SciPy's distributions)."""
    from scipy import stats

    from dryfriction.fit.statistics import consistency_test

    r = consistency_test(cost=0.61, p=3, n=140, sep_cost=0.52, sep_p=7, sigma_given=False)
    F = (2 * (0.61 - 0.52) / 4) / (2 * 0.52 / 133)
    assert r["F"] == pytest.approx(F, rel=1e-12)
    assert r["p_value"] == pytest.approx(stats.f.sf(F, 4, 133), rel=1e-10)
    c = consistency_test(cost=9.1, p=3, n=140, sep_cost=6.3, sep_p=7, sigma_given=True)
    assert c["p_value"] == pytest.approx(stats.chi2.sf(2 * (9.1 - 6.3), 4), rel=1e-10)
