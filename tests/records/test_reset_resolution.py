"""A re-zeroing in a fast quantised slide (records/artifacts.py, RESET_QUANTUM).

The quantum that floors a reset's scale was the smallest increment, which in a fast slide is
several quanta (zoo 20197: 27 um/s at 10 Hz under a 0.40-um quantum, no increment below
three), so a 15.7-um re-zeroing was not taken out and read as a 1-s excursion: two false
changes. The floor is now the resolution, the smallest spacing of the increments' distinct
values. Each test names the mistake it is for; each was seen failing with it applied.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import dryfriction.records.artifacts as artifacts
from dryfriction.records.artifacts import _resolution, find_resets

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_missed_changes import _zoo_counts  # noqa: E402


def test_resolution_is_the_spacing_of_the_increments_values() -> None:
    """Increments of a signal on a 0.3986-um grid, none below 3 quanta, read back through
    decimal text (a spread of 1e-17 m about each multiple): the resolution is the quantum
    to 1e-9 of it; an unquantised signal's is below a hundredth of its scatter; all zero:
    0. Mistakes: the smallest increment (3 quanta); the text's rounding taken for values
    apart (1e-17 m)."""
    rng = np.random.default_rng(4)
    q = 0.3986e-6
    d = q * rng.integers(3, 10, 5000) + rng.uniform(-1e-17, 1e-17, 5000)
    smallest = float(np.abs(d[d != 0]).min())
    assert smallest > 2.9 * q
    assert abs(_resolution(d, smallest) - q) < 1e-9 * q
    white = rng.normal(2.7e-6, 0.24e-6, 5000)
    assert _resolution(white, float(np.abs(white).min())) < 0.01 * 0.24e-6
    assert _resolution(np.zeros(100), 0.0) == 0.0


def _fast_slide_with_reset(seed: int) -> tuple[np.ndarray, np.ndarray, int, float]:
    """27.3 um/s at 10 Hz (intervals jittered +-25 %), 0.17 um of white noise, a 0.3986-um
    quantum, a -8.3 um re-zeroing at a random sample between 40 and 80 s: times (s),
    displacement (m), the jump's increment and size (m). An independent generator (not the
    zoo's)."""
    rng = np.random.default_rng(seed)
    t = np.concatenate([[0.0], np.cumsum(rng.uniform(0.075, 0.125, 1200))])
    x = 27.3e-6 * t + rng.normal(0.0, 0.17e-6, t.size)
    i = int(rng.integers(np.searchsorted(t, 40.0), np.searchsorted(t, 80.0)))
    x[i + 1:] -= 8.3e-6
    q = 0.3986e-6
    return t, np.round(x / q) * q, i, -8.3e-6


def test_a_reset_in_a_fast_quantised_slide_is_found(monkeypatch: pytest.MonkeyPatch) -> None:
    """Ten seeds of the slide above: the re-zeroing (about 24 robust scales of the increments,
    5-7 of their smallest) found at its increment, its offset within 1 um, and nothing else;
    with RESET_QUANTUM off none is found (measured: 0 of 10)."""
    assert artifacts.RESET_QUANTUM is True
    for seed in range(10):
        t, x, i, jump = _fast_slide_with_reset(seed)
        y, kept = find_resets(t, x)
        assert kept == [i], (seed, kept, i)
        assert abs((x[i + 1] - y[i + 1]) - jump) < 1e-6
    monkeypatch.setattr(artifacts, "RESET_QUANTUM", False)
    assert not any(find_resets(*_fast_slide_with_reset(s)[:2])[1] for s in range(10))


def test_zoo_reset_in_a_fast_slide(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Zoo 20197 (a ratio-2 down-step from 27 um/s, every artifact, a 15.7-um re-zeroing 10 s
    before it): 1 change of 1, right; with RESET_QUANTUM off and the threshold of 15 scales
    (the detector before either) 3 changes (measured). Either alone finds this re-zeroing."""
    assert _zoo_counts((20197,), tmp_path) == [(1, 1, True)]
    monkeypatch.setattr(artifacts, "RESET_QUANTUM", False)
    monkeypatch.setattr(artifacts, "_RESET_K", 15.0)
    assert _zoo_counts((20197,), tmp_path) == [(3, 1, False)]


def test_zoo_reset_of_eleven_scales_after_a_step(tmp_path: Path,
                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    """Zoo 22020 (a ratio-3 up-step, every artifact, a 3.7-um re-zeroing 2.4 s after it,
    about 11 robust scales of the increments) and 9000 (a 4.9-um one 4.4 s from a ratio-1.3
    up-step): right with ``_RESET_K`` of 10; with 15 each reads the re-zeroing as a stretch
    of its own (2 changes of 1, measured). Mistake: the threshold of 15 scales."""
    assert artifacts._RESET_K <= 10.0
    assert _zoo_counts((9000, 22020), tmp_path) == [(1, 1, True), (1, 1, True)]
    monkeypatch.setattr(artifacts, "_RESET_K", 15.0)
    assert _zoo_counts((9000, 22020), tmp_path) == [(2, 1, False), (2, 1, False)]
