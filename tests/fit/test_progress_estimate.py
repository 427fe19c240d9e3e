"""fit.progress.EvaluationTracker driven by hand (issue 25): the total the progress bar shows,
at each point of a fit, against the estimate written out from its docstrings (a start: ten
forward-difference iterations, 10 (p + 1), until one has run, then the mean of those run; a
Jacobian 2p; the profiles PROFILE_COST times the starts over p each; a running stage at least
one more), with p = 3 and two starts (no symmetric or unit inputs)."""

from __future__ import annotations

import pytest

from dryfriction.fit.progress import PROFILE_COST, EvaluationTracker


def test_the_estimated_total_through_a_fit() -> None:
    seen: list[tuple[int, int, str]] = []
    tr = EvaluationTracker(3, {"start": 2, "jacobian": 1, "profile": 1},
                           lambda d, t, w: seen.append((d, t, w)))
    p, starts = 3, 2
    start0 = 10.0 * (p + 1)
    assert tr.per_stage("start") == start0 and tr.per_stage("jacobian") == 2.0 * p
    assert tr.per_stage("profile") == pytest.approx(PROFILE_COST * starts * start0 / p)
    assert tr.total() == round(starts * start0 + 2 * p + PROFILE_COST * starts * start0 / p)
    # the first start: 25 evaluations
    tr.begin("start", "start 1 of 2")
    for _ in range(25):
        tr.tick()
    assert seen[-1][0] == 25 and seen[-1][2] == "start 1 of 2"
    tr.end()
    prof = PROFILE_COST * starts * 25.0 / p  # now from the measured start
    assert tr.total() == round(25 + 25 + 2 * p + prof)
    # the second start, 5 in: 20 more expected; 31 in: at least one more
    tr.begin("start", "start 2 of 2")
    for _ in range(5):
        tr.tick()
    assert tr.total() == round(30 + 20 + 2 * p + prof)
    for _ in range(26):
        tr.tick()
    assert tr.total() == round(56 + 1 + 2 * p + prof) == seen[-1][1]
    tr.end()
    assert tr.per_stage("start") == pytest.approx((25 + 31) / 2)  # the mean, not the sum
    # two more profiles than planned (a profile restarted the fit)
    tr.add("profile", 2)
    prof = PROFILE_COST * starts * 28.0 / p
    assert tr.total() == round(56 + 2 * p + 3 * prof)


def test_a_nested_fit_counts_each_of_its_evaluations_once() -> None:
    tr = EvaluationTracker(2, {"consistency": 2}, None)
    tr.begin("consistency", "data set 1")
    inner = tr.nested()
    inner(3, 99, "x")
    inner(7, 99, "x")
    inner(7, 7, "done")  # its final report: no evaluation
    tr.end()
    assert tr.done == 7 and tr.used["consistency"] == [7]
    assert tr.total() == 7 + 7  # one more data set, at the measured 7
