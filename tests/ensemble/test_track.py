"""The track of asperity pairs (ensemble/population.py's Track) against its definition: the
regular lattice ``c_k = (k + 1/2)/lambda``, index spans that hold every pair of a stretch for
both layouts (negative positions too), the random blocks' extent, and the seed's refusals on
both sides (issue 25: a half-spacing offset that a difference cancels, an off-by-one span)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.ensemble.population import Track


def test_regular_lattice_and_spacing() -> None:
    tr = Track(37.0)
    np.testing.assert_allclose(tr.positions(-3, 5), (np.arange(-3, 5) + 0.5) / 37.0,
                               rtol=1e-15)
    assert tr.spacing == pytest.approx(1 / 37.0, rel=1e-15)


@pytest.mark.parametrize("layout, seed", [("regular", None), ("random", 4)])
def test_index_span_holds_every_pair_of_the_stretch(layout: str, seed: int | None) -> None:
    tr = Track(37.0, layout, seed)
    allk0, allk1 = -5000, 5000
    c = tr.positions(allk0, allk1)
    for lo, hi in ((-3.217, -1.04), (0.0135, 0.0135), (0.5 / 37.0, 0.5 / 37.0),
                   (2.5 / 37.0, 7.5 / 37.0), (-0.4, 11.9)):
        k0, k1 = tr.index_span(lo, hi)
        inside = (c >= lo) & (c <= hi)
        ks = np.arange(allk0, allk1)[inside]
        if ks.size:  # a stretch between two pairs holds none
            assert k0 <= ks.min() and ks.max() < k1, (lo, hi)
        assert k0 < k1
        assert np.all(tr.positions(k0, k1) == c[k0 - allk0:k1 - allk0])


def test_random_blocks_lie_in_their_extent() -> None:
    tr = Track(37.0, "random", seed=0)  # seed 0 is a seed
    L = 1024 / 37.0
    for b in (-2, -1, 0, 3):
        c = tr.positions(1024 * b, 1024 * (b + 1))
        assert c.size == 1024 and np.all(c >= b * L) and np.all(c < (b + 1) * L)
        assert np.all(np.diff(c) >= 0)
    # blocks -1 and +1 are different draws (the zig-zag word of a negative block)
    assert not np.allclose(tr.positions(-1024, 0) + 2 * L, tr.positions(1024, 2048))


def test_track_refusals() -> None:
    with pytest.raises(ValueError, match="seed is required for layout = 'random'"):
        Track(10.0, "random")
    for bad in (True, 2.0, "3"):
        with pytest.raises(ValueError, match="is not allowed: a non-negative integer"):
            Track(10.0, "regular", bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"^seed = -1 is out of range: allowed >= 0"):
        Track(10.0, "random", -1)
    assert Track(10.0, "random", np.int64(5)).seed == 5
    assert Track(1e-6).traps_per_a0 == 1e-6
    with pytest.raises(ValueError, match="^traps_per_a0 = "):
        Track(0.99e-6)
    with pytest.raises(ValueError, match="^layout = 'hex' is not allowed"):
        Track(10.0, "hex")
