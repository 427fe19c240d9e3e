"""The joint fit's autocorrelation-robust covariance: each window its own block
(:func:`dryfriction.fit.statistics.blocked_meats`, :func:`dryfriction.fit.steps.robust_joint`).

Mistakes these are for: the joint fit's engine covariance (white noise) kept, many times too
narrow with a record's correlated residuals; one window's long-run covariance left out of the
sum (each window carries its share of a shared parameter's information); the robust numbers
computed but not put where the user reads them (the joint's parameters, ``a - b``)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.signal import lfilter

from dryfriction.fit.statistics import blocked_meats, covariance, local_covariance
from dryfriction.fit.steps import fit_steps, step_covariance
from dryfriction.records.data import SeriesData

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def _ar1(rng: np.random.Generator, n: int, rho: float, sd: float) -> np.ndarray:
    e = rng.normal(0.0, sd, n)
    e[1:] = lfilter([np.sqrt(1.0 - rho**2)], [1.0, -rho], e[1:], zi=[rho * e[0]])[0]
    return e


@pytest.mark.slow
def test_blocked_sandwich_matches_the_spread_of_a_shared_slope() -> None:
    """Two windows apart in time, sampled at 10 and 40 Hz, each with its own AR(1) noise
    (lag-1 0.85, sd 1.0; 0.9, sd 0.35) and intercept, one shared slope whose information
    comes about half from each: the blocked sandwiches' variance of the slope against its
    Monte Carlo spread over 200 draws, each of the two (score HAC, time-lag) and the floored
    one the steps use. The HAC's known bias at these correlations is low by a few tens of per
    cent (0.71, 0.62 and 0.73 measured); the white covariance is ~16 times too small."""
    rng = np.random.default_rng(7)
    na, nb = 400, 900
    ta, tb = 3.7 + 0.1 * np.arange(na), 250.0 + 0.025 * np.arange(nb)
    X = np.zeros((na + nb, 3))
    X[:na, 0], X[na:, 0] = 1.3 * (ta - ta.mean()), 2.5 * (tb - tb.mean())
    X[:na, 1], X[na:, 2] = 1.0, 1.0
    t, blocks = np.concatenate([ta, tb]), [slice(0, na), slice(na, na + nb)]
    est, robust, white, score, lag = [], [], [], [], []
    for _ in range(200):
        y = np.concatenate([_ar1(rng, na, 0.85, 1.0), _ar1(rng, nb, 0.9, 0.35)])
        beta = np.linalg.lstsq(X, y, rcond=None)[0]
        r = y - X @ beta
        est.append(beta[0])
        robust.append(local_covariance(-X, r, t, blocks)[0].matrix[0, 0])
        by_score, _, by_lag = blocked_meats(-X, r, t, blocks)
        score.append(by_score.matrix[0, 0])
        lag.append(by_lag.matrix[0, 0])
        white.append(covariance(X, float(r @ r) / (len(r) - 3)).matrix[0, 0])
    spread = float(np.var(est))
    for var in (robust, score, lag):
        assert 0.5 < np.mean(var) / spread < 1.35
    assert np.mean(white) / spread < 0.2


@pytest.fixture(scope="module")
def red_joint() -> tuple:
    from lab_synth import Truth, synth_record

    tr = Truth(rho=0.98)
    t, v, mu, _ = synth_record(tr, [1.3e-6, 4.1e-6, 1.3e-6, 4.1e-6], duration_slip=300e-6,
                               dt_per_um=0.5, seed=211)
    return fit_steps(SeriesData(t, v, mu, source="red"), joint=True), tr


@pytest.mark.slow
@pytest.mark.ci
def test_joint_intervals_are_the_robust_ones(red_joint: tuple) -> None:
    """On a record with AR(1) friction noise (lag-1 0.98) the joint fit's ``+-``, its 95 %
    intervals and ``a - b``'s error are the blocked sandwich's, several times the white
    ones, and say so; the intervals hold the truth of this record."""
    res, tr = red_joint
    sc = step_covariance(res.joint, res.data)
    names = [s.name for s in sc.specs]
    est = {p.name: p for p in res.joint.parameters}
    for name in ("a", "b", "dc"):
        j = names.index(name)
        assert sc.inflation(j) > 3.0
        p = est[name]
        assert p.stderr == pytest.approx(p.value * sc.robust.stderr[j], rel=1e-9)
        lo, hi = p.interval_95
        assert lo < getattr(tr, name) < hi
        assert lo < p.value < hi
    ia, ib = names.index("a"), names.index("b")
    a, b = est["a"].value, est["b"].value
    C = sc.robust.matrix
    want = np.sqrt(a * a * C[ia, ia] + b * b * C[ib, ib] - 2 * a * b * C[ia, ib])
    assert res.joint.derived["a_minus_b"]["stderr"] == pytest.approx(want, rel=1e-3)
    assert any("autocorrelation-robust" in n for n in res.joint.notes)
    assert not any("white-noise ones" in n for n in res.joint.notes)
