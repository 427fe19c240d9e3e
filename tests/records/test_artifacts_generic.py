"""The artifacts of a record (records/artifacts.py) on signals built to know them (issue 25):
sampling that slows down as well as speeds up, each criterion just inside and just outside its
threshold, a re-zeroing's jump against its true size, a normal-stress change up and down. Each
test names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.records.artifacts import jump_excursions, normal_changes, sampling_changes


def _times(*pieces: tuple[float, int]) -> np.ndarray:
    """Sample times from (interval, count) pieces, from t = 3.7 s."""
    dt = np.concatenate([np.full(n, d) for d, n in pieces])
    return 3.7 + np.concatenate([[0.0], np.cumsum(dt)])


@pytest.mark.parametrize("before, after", [(0.05, 0.2), (0.2, 0.05)])
def test_sampling_rate_change_both_ways(before: float, after: float) -> None:
    # mistakes: only a faster sampling looked for (a slower one missed); the change placed at
    # the block's start, not at the first interval at the new rate
    t = _times((before, 300), (after, 300))
    changes, gaps = sampling_changes(t)
    assert changes == pytest.approx([t[300]], abs=1e-12) and gaps == []


@pytest.mark.parametrize("factor, found", [(1.4, False), (1.6, True)])
def test_sampling_rate_change_threshold(factor: float, found: bool) -> None:
    # mistake: the factor 1.5 taken as 2 (or as 1.2): a change by 1.6 missed or one by 1.4 kept
    t = _times((0.1, 320), (0.1 * factor, 320))
    assert (len(sampling_changes(t)[0]) == 1) is found


@pytest.mark.parametrize("gap, found", [(1.9, False), (2.1, True)])
def test_gap_threshold_and_start_time(gap: float, found: bool) -> None:
    # mistakes: a gap reported at the sample after it (its end); a gap over 5 intervals, or
    # over 20, instead of 10
    t = _times((0.2, 200), (gap, 1), (0.2, 200))
    _, gaps = sampling_changes(t)
    assert gaps == ([pytest.approx(t[200], abs=1e-12)] if found else [])


def test_a_re_zeroing_inside_an_excursion_is_a_jump_of_its_size() -> None:
    # mistakes: the step not projected off the line's slope (its size biased by the slope
    # times the step's lever arm); the first sample after the jump off by one; its sign
    t = _times((0.2, 599))
    v = 1.7e-6
    x = 2.1e-3 + v * (t - t[0])
    x[313:] -= 3.1e-6  # the transducer re-zeroed between samples 312 and 313
    bounds = [0, 290, 330, 600]
    speeds = np.array([v, 0.4 * v, v])  # what a velocity fit would make of the stretch
    (found,) = jump_excursions(t, x, bounds, speeds, rel_tol=0.1, m=10)
    j, k, jump = found
    assert (j, k) == (1, 313)
    assert jump == pytest.approx(-3.1e-6, rel=1e-6)
    # a true excursion (a ramp at 0.4 v, no jump) is not one
    ramp = 2.1e-3 + np.concatenate([[0.0], np.cumsum(np.diff(t) * np.r_[
        np.full(290, v), np.full(40, 0.4 * v), np.full(269, v)])])
    assert jump_excursions(t, ramp, bounds, speeds, rel_tol=0.1, m=10) == []


@pytest.mark.parametrize("level_after", [6.1e6, 4.7e6])
def test_normal_stress_change_up_and_down(level_after: float) -> None:
    # mistake: the half-way crossing looked for upwards only (a decrease placed at the
    # cluster's first sample)
    rng = np.random.default_rng(19)
    t = _times((0.1, 3999))
    sn = np.where(np.arange(t.size) < 1234, 5.3e6, level_after) + rng.normal(0, 2e3, t.size)
    (i,) = normal_changes(t, sn)
    assert i == 1234


@pytest.mark.parametrize("ramp", [20.0, 30.0])
def test_normal_stress_ramp_in_slow_sampling_is_one_change(ramp: float) -> None:
    # mistake (detect8): split points of one ramp merged only when within 30 s (or ten blocks
    # at the record's median interval): after a 10-fold slower sampling a block of 18 samples
    # spans 18 s, the ramp's split points two blocks (36 s) apart were two changes, both
    # placed at the same half-way crossing (zoo records 7049, 7186, 8125)
    rng = np.random.default_rng(23)
    t = _times((0.1, 30000), (1.0, 6000))
    start = 6141.3
    sn = 30e6 - 18e6 * np.clip((t - start) / ramp, 0.0, 1.0) + rng.normal(0, 1e3, t.size)
    (i,) = normal_changes(t, sn)
    # the half-way crossing, to the sample (1 s here)
    assert t[i] == pytest.approx(start + 0.5 * ramp, abs=1.01)


@pytest.mark.parametrize("level_after, lead", [(11.3e6, 0.004), (47.0e6, 0.031)])
def test_normal_stress_ramp_cut_by_a_gap_just_after_half_way(level_after: float,
                                                             lead: float) -> None:
    """A gap of 6.3 s opening ``lead`` s after a ramp's half-way time (down and up): the
    change is the sample before the gap, nearest the crossing interpolated across it, not the
    first sample after the gap (zoo 12014: the change reported 6.3 s late). Mistake: the
    first sample past the level taken across a gap."""
    rng = np.random.default_rng(31)
    t = _times((0.02, 3000))
    start, ramp = 31.4, 8.5
    half = start + 0.5 * ramp
    t = t[(t < half + lead) | (t > half + lead + 6.3)]
    sn = 29.6e6 + (level_after - 29.6e6) * np.clip((t - start) / ramp, 0.0, 1.0)
    sn = sn + rng.normal(0, 1e3, t.size)
    (i,) = normal_changes(t, sn)
    assert t[i] == pytest.approx(half, abs=0.05)
    assert t[i + 1] - t[i] > 6.0  # the gap follows it
