"""The best hinge of a stretch (records/hinge_kernel.py ``hinge_scan`` and its NumPy twin
``segmentation.best_hinge(compiled=False)``) against an independent route: for every allowed
sample ``k`` a least-squares fit of ``x = c + v1 min(t - t_k, 0) + v2 max(t - t_k, 0)`` by
``numpy.linalg.lstsq``, and the RSS it saves over one straight line. A non-uniform grid that
does not start at 0, a kink, seeded noise; both edges of the allowed range (``m``, and
``min_dur`` met exactly)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.records.segmentation import best_hinge


def _rss(A: np.ndarray, x: np.ndarray) -> float:
    coef = np.linalg.lstsq(A, x, rcond=None)[0]
    r = x - A @ coef
    return float(r @ r)


def _brute(t: np.ndarray, x: np.ndarray, m: int, min_dur: float) -> tuple[int, float]:
    n = t.size
    line = _rss(np.column_stack([np.ones(n), t]), x)
    best = (-1, 0.0)
    for k in range(m, n - m + 1):
        if not (t[k] - t[0] >= min_dur and t[-1] - t[k] >= min_dur):
            continue
        d = t - t[k]
        g = line - _rss(np.column_stack([np.ones(n), np.minimum(d, 0), np.maximum(d, 0)]), x)
        if best[0] < 0 or g > best[1]:
            best = (k, g)
    return best


def _stretch(seed: int, kink: float) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    t = 731.0 + np.cumsum(rng.uniform(0.2, 1.7, 60))  # non-uniform, starting far from 0
    x = 3e-6 * (t - t[0]) + 9e-6 * np.maximum(t - kink, 0.0) + rng.normal(0, 2e-6, t.size)
    return t, x / 1e-6  # um: the kernels' sums in the data's own scale


@pytest.mark.parametrize("compiled", [True, False])
def test_best_hinge_is_the_brute_force_least_squares_one(compiled) -> None:
    # mistakes: a sum's cross term dropped (2 tk st), the left count k + 1, the RSS saved
    # with one of its three terms missing, the scan stopping at n - m - 1
    for seed, kink_at in ((3, 0.3), (11, 0.75), (29, 0.5)):
        t, x = _stretch(seed, 0.0)
        kink = t[0] + kink_at * (t[-1] - t[0])
        x = x + 9.0 * np.maximum(t - kink, 0.0)
        for m in (2, 5):
            k, g = best_hinge(t, x, m, 0.0, compiled=compiled)
            kb, gb = _brute(t, x, m, 0.0)
            assert k == kb, (seed, m)
            assert g == pytest.approx(gb, rel=1e-8)
    # noise alone: still the brute-force optimum (a small saving, wherever it is)
    t, x = _stretch(5, 0.0)
    assert best_hinge(t, x, 3, 0.0, compiled=compiled) == pytest.approx(_brute(t, x, 3, 0.0),
                                                                        rel=1e-8)


@pytest.mark.parametrize("compiled", [True, False])
def test_allowed_range_both_edges(compiled) -> None:
    t, x = _stretch(7, 0.0)
    x = x + 9.0 * np.maximum(t - t[4], 0.0)  # the kink at sample 4
    # m = 4: sample 4 allowed (k >= m); m = 5: not
    assert best_hinge(t, x, 4, 0.0, compiled=compiled)[0] == _brute(t, x, 4, 0.0)[0] == 4
    assert best_hinge(t, x, 5, 0.0, compiled=compiled)[0] == _brute(t, x, 5, 0.0)[0] != 4
    # min_dur equal to t[4] - t[0] exactly: allowed (">="); a hair more: not
    d = float(t[4] - t[0])
    assert best_hinge(t, x, 2, d, compiled=compiled)[0] == 4
    assert best_hinge(t, x, 2, np.nextafter(d, np.inf), compiled=compiled)[0] != 4
    # the right edge the same way: a kink at n - m is allowed
    n = t.size
    y = x - 9.0 * np.maximum(t - t[4], 0.0) + 9.0 * np.maximum(t - t[n - 4], 0.0)
    assert best_hinge(t, y, 4, 0.0, compiled=compiled)[0] == n - 4
    # too short a stretch: n < 2 m + 1
    assert best_hinge(t[:8], x[:8], 4, 0.0, compiled=compiled) == (-1, 0.0)
    assert best_hinge(t[:9], x[:9], 4, 0.0, compiled=compiled)[0] == 4
