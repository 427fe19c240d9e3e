"""The steady-tail test of the trap model's series (fit/cvtail.py ``steady_level``, module
docstring) at the edges of each of its criteria, on a friction whose three block means are set
by hand (issue 25: a series that settles well inside every tolerance hides a criterion dropped).
Each case names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.fit.cvtail import BLOCK_SLIP, DRIFT_BLOCKS, MIN_SLIP, STEADY_TOL, steady_level

L = 0.61
TOL = STEADY_TOL * L  # 1.22e-5


def _blocks(e1: float, e2: float) -> tuple[np.ndarray, np.ndarray]:
    """Load-point positions 0..10 a0 and a friction whose last three 2-a0 blocks have means
    ``L + e2 + e1``, ``L + e2``, ``L`` (oldest first)."""
    x = np.linspace(0.0, 10.0, 1001)
    edges = x[-1] - BLOCK_SLIP * np.arange(4)[::-1]
    mu = np.where(x > edges[2], L, np.where(x > edges[1], L + e2, L + e2 + e1))
    return x, mu


@pytest.mark.parametrize("e1, e2, left, steady", [
    (0.9 * TOL, 0.0, 0.0, True),
    (1.1 * TOL, 0.0, 0.0, False),  # the first difference above: the first one ignored
    (0.0, 1.1 * TOL, 0.0, False),
    # a drift carried over at most DRIFT_BLOCKS blocks: within tolerance, however long the rest
    (0.0, 0.9 * TOL / DRIFT_BLOCKS, 1e4, True),
    (0.0, 1.1 * TOL / DRIFT_BLOCKS, 1e4, False),
    (0.0, 0.9 * TOL / 3.0, 3.0 * BLOCK_SLIP, True),  # a short rest: 3 blocks of drift
    (0.0, 1.1 * TOL / 3.0, 3.0 * BLOCK_SLIP, False),
])
def test_each_criterion_at_its_edge(e1: float, e2: float, left: float, steady: bool) -> None:
    # mistakes: the first difference left out; the drift not capped at DRIFT_BLOCKS (never
    # steady in a long segment); the drift over a fixed number of blocks; the tolerance
    # absolute (2e-5) instead of relative to the level
    x, mu = _blocks(e1, e2)
    got = steady_level(x, mu, 0.0, left)
    if steady:
        assert got == pytest.approx(L, rel=1e-14)
    else:
        assert got is None


def test_too_little_travel_is_never_steady() -> None:
    # mistake: MIN_SLIP counted from the record's start, not the segment's
    x, mu = _blocks(0.0, 0.0)
    need = max(MIN_SLIP, 3.0 * BLOCK_SLIP)
    assert steady_level(x, mu, 10.0 - need + 0.01, 0.0) is None
    assert steady_level(x, mu, 10.0 - need, 0.0) == pytest.approx(L)
