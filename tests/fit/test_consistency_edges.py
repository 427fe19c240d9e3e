"""``fit.statistics.consistency_test``: every branch, both sides of each refusal, the
reported columns written from their definitions here (issue 25, strengthen6B)."""

from __future__ import annotations

import pytest
from scipy import stats

from dryfriction.fit.statistics import consistency_test


def test_refuses_exactly_when_the_joint_fit_has_no_fewer_parameters() -> None:
    # df1 = sep_p - p: 0 refuses, 1 runs (both branches)
    for sigma in (False, True):
        r = consistency_test(cost=3.0, p=5, n=60, sep_cost=2.0, sep_p=5, sigma_given=sigma)
        assert r["test"] == "not run" and "parameters" in r["reason"]
        r = consistency_test(cost=3.0, p=6, n=60, sep_cost=2.0, sep_p=5, sigma_given=sigma)
        assert r["test"] == "not run"
        ok = consistency_test(cost=3.0, p=4, n=60, sep_cost=2.0, sep_p=5, sigma_given=sigma)
        assert ok["test"] != "not run"


def test_f_branch_refuses_exactly_at_no_residual_dof() -> None:
    """``df2 = n - sep_p``: 0 refuses, 1 runs; the chi-square branch needs no df2."""
    r = consistency_test(cost=3.0, p=2, n=7, sep_cost=2.0, sep_p=7, sigma_given=False)
    assert r["test"] == "not run" and "points" in r["reason"]
    r = consistency_test(cost=3.0, p=2, n=8, sep_cost=2.0, sep_p=7, sigma_given=False)
    assert r["test"] == "F" and r["df"] == [5, 1]
    F = (2 * (3.0 - 2.0) / 5) / (2 * 2.0 / 1)
    assert r["F"] == pytest.approx(F, rel=1e-12)
    c = consistency_test(cost=3.0, p=2, n=7, sep_cost=2.0, sep_p=7, sigma_given=True)
    assert c["test"] == "chi-square difference"


def test_reported_columns_from_their_definitions() -> None:
    """RSS = 2 cost (cost is RSS/2), chi2 = 2 cost, delta unclamped, df as integers."""
    r = consistency_test(cost=1.7, p=3, n=90, sep_cost=1.1, sep_p=9, sigma_given=False)
    assert r["separate_rss"] == pytest.approx(2.2, rel=1e-12)
    assert r["joint_rss"] == pytest.approx(3.4, rel=1e-12)
    assert r["df"] == [6, 81]
    c = consistency_test(cost=11.3, p=3, n=90, sep_cost=8.2, sep_p=9, sigma_given=True)
    assert c["delta_chi2"] == pytest.approx(2 * (11.3 - 8.2), rel=1e-12)
    assert c["df"] == 6
    assert c["separate_chi2"] == pytest.approx(16.4, rel=1e-12)
    assert c["p_value"] == pytest.approx(stats.chi2.sf(6.2, 6), rel=1e-10)


def test_a_joint_fit_better_than_the_separate_ones_is_clamped_to_no_evidence() -> None:
    """Round-off can put the joint cost below the separate sum: the statistic is then 0 and
    the p-value 1 (not NaN, not a negative F), while delta_chi2 keeps its sign."""
    r = consistency_test(cost=1.0, p=3, n=90, sep_cost=1.2, sep_p=9, sigma_given=False)
    assert r["F"] == 0.0 and r["p_value"] == pytest.approx(1.0)
    c = consistency_test(cost=1.0, p=3, n=90, sep_cost=1.2, sep_p=9, sigma_given=True)
    assert c["p_value"] == pytest.approx(1.0)
    assert c["delta_chi2"] == pytest.approx(-0.4, rel=1e-12)
