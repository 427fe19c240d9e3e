"""The step judge's statistics (fit/identify.py) against their definitions written here, at a
generic residual correlation (issue 25: an estimator checked only at rho = 0 hides a factor
(1 + rho)/(1 - rho) turned over). Each test names the mistake it is for; each was seen failing
with it applied."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from dryfriction.fit.identify import MISFIT_RMS, misfit_words, transient_test
from dryfriction.fit.machine import load_point_displacement
from dryfriction.records.data import SeriesData


def _step(n: int = 300, seed: int = 3) -> tuple[SeriesData, np.ndarray]:
    """A 1.1 -> 3.3 um/s step at 0.25 s sampling: friction a line in load-point displacement
    plus AR(1) noise (rho 0.6, 2e-4)."""
    rng = np.random.default_rng(seed)
    t = 4.0 + 0.25 * np.arange(n)
    v = np.where(np.arange(n) < n // 3, 1.1e-6, 3.3e-6)
    e = np.zeros(n)
    for i in range(1, n):
        e[i] = 0.6 * e[i - 1] + rng.normal(0.0, 2e-4 * math.sqrt(1 - 0.36))
    d0 = SeriesData(t, v, np.zeros(n))
    x = load_point_displacement(d0)
    return SeriesData(t, v, 0.613 + 37.0 * x + e), x


def test_transient_f_test_is_its_definition() -> None:
    # mistakes: F without the factor (1 - rho)/(1 + rho); the denominator's degrees of
    # freedom n - p instead of n_eff - p; the numerator's p instead of p - 2
    d, x = _step()
    p, rho = 6, 0.43
    X = np.column_stack([np.ones(len(d)), x - x[0]])
    r0 = d.mu - X @ np.linalg.lstsq(X, d.mu, rcond=None)[0]
    model = d.mu - 0.97 * r0  # a fit a little better than the line
    r1 = d.mu - model
    shrink = (1 - rho) / (1 + rho)
    n_eff = len(d) * shrink
    F = (r0 @ r0 - r1 @ r1) / (p - 2) / (r1 @ r1 / (len(d) - p)) * shrink
    pv = float(stats.f.sf(F, p - 2, n_eff - p))
    assert 0.01 < pv < 0.99  # a p-value the message prints, neither end
    msg = transient_test(d, model, p, rho)
    assert f"p = {pv:.2g})" in msg
    # a real transient: the model explains a decay the line cannot
    bump = 4e-3 * np.exp(-np.maximum(x - x[100], 0.0) / 20e-6) * (np.arange(len(d)) >= 100)
    assert transient_test(SeriesData(d.t, d.v_load, d.mu + bump), model + bump, p, rho) == ""


def test_peak_residual_allowance_counts_the_tail_correlation() -> None:
    # mistakes: the allowance's factor (1 + rho)/(1 - rho) turned over; the correlation of the
    # whole window instead of its detrended last third; peak_samples ignored
    d, _ = _step()
    tail = slice(len(d) * 2 // 3, len(d))
    tt = d.t[tail] - d.t[tail][0]
    calm = d.mu[tail] - np.polyval(np.polyfit(tt, d.mu[tail], 1), tt)
    rho = float(np.clip(np.corrcoef(calm[1:], calm[:-1])[0, 1], 0.0, 0.999))
    assert 0.45 < rho < 0.75
    noise, k = 2.1e-4, 12
    allow = 3.0 * noise * min(1.0, math.sqrt((1 + rho) / ((1 - rho) * k)))
    model = d.mu + np.where(np.arange(len(d)) % 2 == 0, 1e-5, -1e-5)  # a white misfit
    for factor, flagged in ((0.98, False), (1.02, True)):
        row = {"noise": noise, "rms": 1e-5, "peak_residual": -factor * allow}
        words = misfit_words(d, model, row, k)
        assert any("peak residual" in w for w in words) is flagged, (factor, words)
    row = {"noise": noise, "rms": 1.01 * MISFIT_RMS * noise, "peak_residual": 0.0}
    assert any("rms residual" in w for w in misfit_words(d, model, row, k))
    row["rms"] = 0.99 * MISFIT_RMS * noise
    assert not any("rms residual" in w for w in misfit_words(d, model, row, k))


def test_record_stiffness_is_the_inverse_variance_mean_of_ln_k_by_its_definition() -> None:
    # mistake (blind set 5, record_stiffness_halfwidth_as_se): the standard error of ln k_i
    # taken as ln(hi/lo)/z (the whole 95 % width) instead of ln(hi/lo)/(2 z): the weighted
    # mean is unchanged (every weight scales alike) but the record's interval is twice as wide
    from dryfriction.fit.identify import record_stiffness

    z = 1.96
    # three consistent steps, asymmetric intervals of different widths (in 1/m)
    ks = [(2.71e4, 2.2e4, 3.5e4), (3.02e4, 2.9e4, 3.2e4), (2.88e4, 2.5e4, 3.4e4)]
    rows = [{"stiffness": k, "stiffness_lo": lo, "stiffness_hi": hi, "flags": ""}
            for k, lo, hi in ks]
    rec = record_stiffness(rows, z=z)
    assert rec is not None and rec["steps"] == [0, 1, 2] and rec["unit"] == "1/m"
    se = np.array([math.log(hi / lo) / (2.0 * z) for _, lo, hi in ks])
    w = 1.0 / se**2
    m = float(w @ np.log([k for k, _, _ in ks]) / w.sum())
    s = 1.0 / math.sqrt(w.sum())
    assert rec["value"] == pytest.approx(math.exp(m), rel=1e-12)
    assert rec["lo"] == pytest.approx(math.exp(m - z * s), rel=1e-12)
    assert rec["hi"] == pytest.approx(math.exp(m + z * s), rel=1e-12)
    assert all(r["flags"] == "" for r in rows)


def test_two_disagreeing_steps_are_kept_and_the_method_says_so() -> None:
    # the mistake (a second new user): two steps flagged k_inconsistent, both kept in the
    # record's k (nothing says which is right), while the method said "over the steps where
    # k is identified and consistent"
    from dryfriction.fit.identify import record_stiffness

    rows = [{"stiffness": k, "stiffness_lo": 0.9 * k, "stiffness_hi": 1.1 * k, "flags": ""}
            for k in (2.3e3, 4.1e3)]
    rec = record_stiffness(rows)
    assert rec is not None and rec["steps"] == [0, 1] and rec["consistent"] is False
    assert all("k_inconsistent" in r["flags"] for r in rows)
    assert "the two steps disagree (both flagged k_inconsistent)" in rec["method"]
    assert "identified and consistent" not in rec["method"]
    agree = [{"stiffness": k, "stiffness_lo": 0.9 * k, "stiffness_hi": 1.1 * k, "flags": ""}
             for k in (3.1e3, 3.2e3)]
    rec = record_stiffness(agree)
    assert rec is not None and rec["consistent"] is True
    assert "identified and consistent" in rec["method"]
