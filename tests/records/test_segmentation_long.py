"""A long record is searched on block means (hinge_segments): the noise of a block mean is
the samples' noise over sqrt(block), so a slope change that the sample-by-sample search finds
is found in the long record too. Written for the survivors of the second blind mutant review
(benchmarks/blind_mutants2.py: seg_block_noise_floor, the block means' noise floor not divided
by sqrt(block), so that small changes are missed in big files only)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.records.segmentation import hinge_segments, noise_level


@pytest.mark.parametrize("seed", [3, 7])
def test_small_slope_change_found_in_a_long_record(seed: int) -> None:
    """60 000 samples (blocks of 12), unit white noise, slope 0.37 -> 0.3714 per s at t = 613 s
    of 1000 s: a change the sample-by-sample search (max_points = n) finds."""
    n = 60_000
    t = np.linspace(0.0, 1000.0, n)
    x = 0.37 * t + 0.0014 * np.maximum(t - 613.0, 0.0)
    x = x + np.random.default_rng(seed).normal(0.0, 1.0, n)
    sigma = noise_level(x)
    assert sigma == pytest.approx(1.0, rel=0.05)
    one_by_one = hinge_segments(t, x, sigma, max_points=n)
    assert len(one_by_one) == 3  # the independent route: one change
    blocked = hinge_segments(t, x, sigma)  # default max_points 5000: block means
    assert len(blocked) == 3, blocked
    true_k = int(np.searchsorted(t, 613.0))
    assert abs(blocked[1] - true_k) < 0.05 * n
    assert abs(blocked[1] - one_by_one[1]) < 0.02 * n
