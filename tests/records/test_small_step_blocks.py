"""A small step is placed on block means of one duration (``records.placement.EVEN_BLOCKS``,
branch detect7): the blocks' duration is the placement's resolution, and blocks of one sample
count are ten times longer on the slow side of a 10-fold sampling-rate change."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import records_zoo as z  # noqa: E402
from dryfriction.records import placement as P  # noqa: E402
from dryfriction.records.lab import LabRecord, detect_program  # noqa: E402


def _rate_step(seed: int, ratio: float) -> tuple[LabRecord, float, float]:
    """A zoo-like up or down step of ``ratio`` (``bench_detect_oracle``'s draws: speed,
    slides, sampling rate), the sampling rate 10 times faster (below 10 Hz) or slower from the
    change on (the zoo's ``rate`` at a change), the servo's position error, the machine
    oscillation (6 % at 22 s, 4 % at 45 s), 0.17 um white noise and a 20 nm quantum; returns
    the record, the true change time (s, record time) and its tolerance (s)."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
    from benchmarks.bench_detect_oracle import draw

    rng = np.random.default_rng(seed)
    v1, v2, d1, d2, fs = draw(rng, ratio, bool(seed % 2))
    f2 = 10.0 if fs < 10.0 else 0.1
    t = np.concatenate([np.arange(0.0, d1, 1 / fs), np.arange(d1, d1 + d2, 1 / (fs * f2))])
    x = z.step_displacement(t, np.where(t >= d1, v2, v1), rng)
    rec = LabRecord("r.txt", t + 100.0, x, None, np.full(t.size, 0.6), None, "", {}, 2)
    return rec, d1 + 100.0, z.tolerance(t, d1)


def test_even_blocks_one_duration_across_a_rate_change() -> None:
    # 10 Hz for 20 s then 1 Hz to 39 s, cut into spans of 5 s: 50 samples a block before the
    # change and 5 after; at most 4 blocks: 4 spans of 9.75 s (a hair more); 0-9 s and
    # 30-39 s at 1 Hz: the spans over the gap give no block; evenly sampled times: the blocks
    # of one count, whatever the offset. The mistake it is for: blocks of one count (the slow
    # side's 10 times longer), a block per empty span (a mean of no sample), or spans that
    # move the blocks of an evenly sampled window (rounding at a span's edge)
    t = np.concatenate([np.arange(200) / 10.0, np.arange(20, 40, dtype=float)])
    idx = P.even_blocks(t, 5.0, 64)
    assert np.allclose(t[idx], [0.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 35.0]), t[idx]
    assert list(np.diff(np.append(idx, t.size))) == [50, 50, 50, 50, 5, 5, 5, 5]
    assert np.allclose(t[P.even_blocks(t, 5.0, 4)], [0.0, 9.8, 19.6, 30.0])
    g = np.concatenate([np.arange(0.0, 10.0), np.arange(30.0, 40.0)])
    assert list(np.diff(np.append(P.even_blocks(g, 5.0, 64), g.size))) == [5, 5, 5, 5]
    for fs, off in ((7.4, 100.0), (20.0, 1234.567), (1.0, 0.0)):
        u = np.arange(0.0, 700.0, 1.0 / fs) + off
        assert np.array_equal(P.even_blocks(u, 9 * float(np.median(np.diff(u))), 10**6),
                              np.arange(0, u.size, 9))


def test_small_step_is_a_change_of_at_most_twice_the_speed() -> None:
    # the mistake it is for: a hold (speed 0) or a large step counted as small, or the
    # ratio taken one way only (a down-step of 2 not small)
    assert P.small_step(1e-6, 1.3e-6) and P.small_step(2e-6, 1e-6) and P.small_step(-1e-6, -2e-6)
    assert not P.small_step(1e-6, 3e-6) and not P.small_step(0.0, 1e-6)
    assert not P.small_step(1e-6, 0.0)


@pytest.mark.slow
def test_small_steps_at_a_rate_change_placed_better_on_even_blocks() -> None:
    # 40 ratio-1.3 steps at a 10-fold sampling-rate change with the servo error and the
    # machine oscillation (seeds 0-39): within max(1 sample, 0.5 s) 35 of 40 on blocks of one
    # duration, 29 of one count (measured). The mistake it is for: blocks of one sample count
    # for a small step (EVEN_BLOCKS off), whose slow side's blocks are ten times longer
    # (the first count with EVEN_BLOCKS as it is: the rule must be on by default). Both with
    # RATE_EVEN off, which puts any window across a rate change on blocks of one duration and
    # so would hide the mistake (its own test: test_rate_even.py)
    recs = [_rate_step(seed, 1.3) for seed in range(40)]
    hits = {}
    default, rate = P.EVEN_BLOCKS, P.RATE_EVEN
    for even in ("default", False):
        P.RATE_EVEN = 0.0
        if even is False:
            P.EVEN_BLOCKS = False
        try:
            hits[even] = 0
            for rec, tc, tol in recs:
                segs = detect_program(rec).segments
                hits[even] += len(segs) == 2 and abs(segs[1].t_start - tc) <= tol
        finally:
            P.EVEN_BLOCKS, P.RATE_EVEN = default, rate
    assert hits["default"] >= 34 and hits["default"] >= hits[False] + 4, hits


def test_large_step_placement_unchanged_by_even_blocks() -> None:
    # a ratio-3 step (not small) at the same rate change is placed as before, on blocks of
    # one count, whatever EVEN_BLOCKS says: the rule is for the small steps only (measured
    # there; RATE_EVEN, which puts any window across a rate change on even blocks, off).
    # The mistake it is for: every change placed on even blocks
    got = {}
    default, rate = P.EVEN_BLOCKS, P.RATE_EVEN
    for even in (True, False):
        P.EVEN_BLOCKS, P.RATE_EVEN = even, 0.0
        try:
            got[even] = [tuple((s.i_start, s.start_lo, s.start_hi) for s in detect_program(
                _rate_step(seed, 3.0)[0]).segments) for seed in range(6)]
        finally:
            P.EVEN_BLOCKS, P.RATE_EVEN = default, rate
    assert got[True] == got[False]
