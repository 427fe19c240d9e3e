"""A change placed on a servo's velocity reading (records/reading.py, detection.READING).

Integrated to a displacement, a velocity column's white noise is a random walk that the
hinge's wander model does not have, and small steps were placed seconds off (zoo 19044: a
ratio-1.3 up-step at 0.11 um/s placed 4.9 s early, its interval 2485.4-2495.7 s missing the
truth, 2500.0 s). On the reading the step is within one sample. Each test names the mistake
it is for; each was seen failing with it applied.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import dryfriction.records.detection as detection
from dryfriction.records.reading import READING_Z, reading_step

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_missed_changes import _zoo_counts  # noqa: E402


def _reading(seed: int, v1: float, v2: float, at: float, fs: float = 17.0,
             span: float = 140.0, quantum: float = 0.02e-6, wander: float = 0.08,
             white: float = 0.02) -> tuple[np.ndarray, np.ndarray]:
    """A servo's velocity reading (m/s) at ``fs`` Hz (jittered +-20 %) from 412.6 s: the
    commanded ``v1`` then ``v2`` from ``at`` (s after the start), times ``1 + w`` (``w`` an
    Ornstein-Uhlenbeck wander of ``wander`` rms and 1 s, exact AR(1) on the samples), white
    noise of ``white`` of it, rounded to ``quantum`` (an independent generator: not the zoo's)."""
    rng = np.random.default_rng(seed)
    dt = rng.uniform(0.8, 1.2, int(span * fs)) / fs
    u = np.concatenate([[0.0], np.cumsum(dt)])
    w = np.empty(u.size)
    w[0] = rng.normal(0.0, wander)
    rho = np.exp(-dt / 1.0)
    for i in range(1, u.size):
        w[i] = rho[i - 1] * w[i - 1] + wander * np.sqrt(1.0 - rho[i - 1] ** 2) * rng.normal()
    vc = np.where(u >= at, v2, v1)
    v = vc * (1.0 + w) * (1.0 + rng.normal(0.0, white, u.size))
    return 412.6 + u, np.round(v / quantum) * quantum


@pytest.mark.parametrize("v1, v2, least", [(1.47e-6, 1.13e-6, 2), (0.112e-6, 0.146e-6, 4),
                                           (3.3e-6, 0.0, 20)])
def test_a_step_of_the_reading_is_placed_within_a_sample(v1: float, v2: float,
                                                         least: int) -> None:
    """A ratio-1.3 down-step at 1.47 um/s, a ratio-1.3 up-step at 0.112 um/s (1.7 quanta
    of 0.02 um/s) and a stop from 3.3 um/s, at 71.37 s, the search centred 4.4 s early (as
    the hinge put 19044's), 20 seeds: every placement is at the first reading of the new
    velocity, its interval holding the truth; the stop is placed on every seed, the small
    steps on some (measured 4 and 6: the wander here, 8 % on the velocity itself, is rougher
    than the zoo's servo; the others are left to the displacement). Mistakes: the jump's sign
    ignored (a down-step read as the largest rise); the first sample of the new velocity off
    by one."""
    placed = 0
    for seed in range(20):
        t, v = _reading(100 + seed, v1, v2, 71.37)
        tc = 412.6 + 71.37
        k = int(np.searchsorted(t, tc))
        pl = reading_step(t, v, int(np.searchsorted(t, tc - 4.4)), 0, t.size, v1, v2)
        if pl is not None:
            placed += 1
            assert pl.index == k and pl.lo <= tc <= pl.hi
    assert placed >= least


def test_no_step_no_placement() -> None:
    """The same readings with no change (``v2 = v1``) searched for a ratio-1.3 up-step (and
    for a down-step) at 0.71 um/s: no placement on 58 of 60 at least (measured: none).
    Mistake: a threshold ``READING_Z`` of a few scales (the largest of some 200 candidates'
    null ``J`` stands at 3-4)."""
    placed = 0
    for seed in range(30):
        t, v = _reading(500 + seed, 0.71e-6, 0.71e-6, 71.37)
        g = int(np.searchsorted(t, 412.6 + 70.0))
        placed += reading_step(t, v, g, 0, t.size, 0.71e-6, 0.923e-6) is not None
        placed += reading_step(t, v, g, 0, t.size, 0.71e-6, 0.546e-6) is not None
    assert placed <= 2
    assert READING_Z >= 5.0


def test_a_reading_step_too_small_for_the_stretches_is_left() -> None:
    """A quiet reading (0.5 % wander, 0.1 % white noise, no quantum) stepping 1.47 -> 1.39
    um/s (a burst's size: a quarter of the change between the stretches, 1.47 and 1.13
    um/s), far above its noise: no placement; stepping to 1.13 it is placed. Mistake: the
    size check left out (the largest step taken for the change, whatever its size)."""
    for v2, placed in ((1.39e-6, False), (1.13e-6, True)):
        t, v = _reading(9, 1.47e-6, v2, 71.37, quantum=1e-12, wander=0.005, white=0.001)
        g = int(np.searchsorted(t, 412.6 + 70.0))
        assert (reading_step(t, v, g, 0, t.size, 1.47e-6, 1.13e-6) is not None) is placed


@pytest.mark.slow
def test_zoo_velocity_records_placed_on_their_reading(tmp_path: Path,
                                                      monkeypatch: pytest.MonkeyPatch
                                                      ) -> None:
    """Zoo 19044 (a ratio-1.3 up-step at 0.11 um/s, every artifact, 28767 rows) and 18184 (a
    slide-hold-slide at 0.14 um/s, 362756 rows, its first stop placed 1.65 s early): every
    change within its tolerance; with ``READING`` off 19044 is not (4.9 s off, measured)."""
    assert _zoo_counts((18184, 19044), tmp_path) == [(4, 4, True), (1, 1, True)]
    monkeypatch.setattr(detection, "READING", False)
    assert _zoo_counts((19044,), tmp_path) == [(1, 1, False)]


@pytest.mark.parametrize("v1, v2", [(0.172e-6, 0.0), (2.9e-6, 0.29e-6), (0.31e-6, 0.93e-6)])
def test_a_step_of_a_slow_reading_is_placed_within_a_sample(v1: float, v2: float) -> None:
    """Readings at 1 Hz (jittered +-20 %; too few for lines on half a second), a stop, a
    ratio-10 down-step and a ratio-3 up-step at 71.37 s, the search centred 2.2 s early, 20
    seeds: each placed (measured: 20 of 20 each) at the first reading of the new velocity, its
    interval holding the truth (READING_SLOW: the means of the SLOW_MIN readings each side).
    Mistakes: the slow readings left to the displacement (READING_SLOW off: none placed);
    the means' windows off by one (the step's own reading on both sides)."""
    for seed in range(20):
        t, v = _reading(300 + seed, v1, v2, 71.37, fs=1.0)
        tc = 412.6 + 71.37
        k = int(np.searchsorted(t, tc))
        pl = reading_step(t, v, int(np.searchsorted(t, tc - 2.2)), 0, t.size, v1, v2)
        assert pl is not None, seed
        assert pl.index == k and pl.lo <= tc <= pl.hi, (seed, t[pl.index] - tc)


def test_no_step_in_a_slow_reading_no_placement() -> None:
    """Readings at 1 Hz with no change searched for a ratio-1.3 up-step and down-step at
    0.71 um/s: no placement on 58 of 60 at least (measured: none). Mistake: the slow means
    judged by a lower threshold (READING_Z of 2: 13 placed; of 3: 1, measured)."""
    placed = 0
    for seed in range(30):
        t, v = _reading(700 + seed, 0.71e-6, 0.71e-6, 71.37, fs=1.0)
        g = int(np.searchsorted(t, 412.6 + 70.0))
        placed += reading_step(t, v, g, 0, t.size, 0.71e-6, 0.923e-6) is not None
        placed += reading_step(t, v, g, 0, t.size, 0.71e-6, 0.546e-6) is not None
    assert placed <= 2, placed


def test_zoo_slow_reading_stop_placed(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Zoo 22249 (a ratio-30 stop from 0.17 um/s in a velocity column read at 1 Hz there,
    every artifact, 22038 rows): its change within the tolerance; with ``READING_SLOW`` off it
    is not (1.25 s early, measured)."""
    import dryfriction.records.reading as reading

    assert _zoo_counts((22249,), tmp_path) == [(1, 1, True)]
    monkeypatch.setattr(reading, "READING_SLOW", False)
    assert _zoo_counts((22249,), tmp_path) == [(1, 1, False)]
