"""``ensemble.resources.RunEstimate``'s byte counts from the documented per-item sizes
(issue 25, strengthen6B): a snapshot holds six float64 arrays over the traps in contact; every
part enters the total once. Generic counts, none of them 1."""

from __future__ import annotations

import pytest

from dryfriction.ensemble.resources import BYTES_PER_SAMPLE, BYTES_PER_TRAP, RunEstimate


def test_bytes_add_up_from_their_parts() -> None:
    e = RunEstimate(samples=3100.0, traps=7.3e4, active=820.0, snapshots=7)
    assert e.snapshot_bytes == pytest.approx(7 * 820.0 * 6 * 8, rel=1e-15)
    assert e.sample_bytes == pytest.approx(3100.0 * BYTES_PER_SAMPLE, rel=1e-15)
    assert e.trap_bytes == pytest.approx(7.3e4 * BYTES_PER_TRAP, rel=1e-15)
    assert e.total_bytes == pytest.approx(e.sample_bytes + e.trap_bytes + e.snapshot_bytes,
                                          rel=1e-15)
    # the measured sizes the constants stand for (module docstrings): 456 and 15-16 bytes
    assert 456.0 <= BYTES_PER_SAMPLE < 2 * 456.0 and 16.0 <= BYTES_PER_TRAP < 32.0
    none = RunEstimate(samples=0.0, traps=0.0, active=820.0, snapshots=0)
    assert none.total_bytes == 0.0
