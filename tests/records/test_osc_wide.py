"""A step of ratio 2 in an oscillating record is placed on a window of two oscillation periods
each side where its stretches hold them (``records.placement.OSC_WIDE``, ``osc_wide``; branch
detect10): beyond ``OSC_RATIO`` a period enters the hinge only where the window holds it whole
on each side, and the unwidened window (20-60 s each side) seldom holds a long period
whole."""

from __future__ import annotations

import sys
from pathlib import Path
from unittest.mock import patch

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import records_zoo as z  # noqa: E402
from dryfriction.records import placement as P  # noqa: E402
from dryfriction.records.lab import LabRecord, detect_program  # noqa: E402


def _step(seed: int, ratio: float, osc: tuple[tuple[float, float], ...]
          ) -> tuple[LabRecord, float, float]:
    """An up (odd seed) or down step of ``ratio`` drawn as the zoo draws its up/down records
    (``bench_detect_oracle.draw``: speed, slides, sampling rate), the velocity oscillating by
    ``osc`` (``(relative amplitude, period s)`` each, random phases), the servo's position
    error, 0.17 um white noise and a 20 nm quantum; returns the record, the true change time
    (s, record time) and its tolerance (s)."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
    from benchmarks.bench_detect_oracle import draw

    rng = np.random.default_rng(seed)
    v1, v2, d1, d2, fs = draw(rng, ratio, bool(seed % 2))
    t = np.arange(0.0, d1 + d2, 1.0 / fs)
    vc = np.where(t >= d1, v2, v1)
    eps = np.zeros_like(t)
    for amp, per in osc:
        eps += amp * np.sin(2.0 * np.pi * t / per + rng.uniform(0.0, 2.0 * np.pi))
    vt = vc * (1.0 + eps)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (vt[1:] + vt[:-1]) * np.diff(t))])
    x += z.servo_error(t, vc, rng) + rng.normal(0.0, z.WHITE, t.size)
    x = np.round(x / z.QUANTUM) * z.QUANTUM
    rec = LabRecord("r.txt", t + 100.0, x, None, np.full(t.size, 0.6), None, "", {}, 2)
    return rec, d1 + 100.0, z.tolerance(t, d1)


def _hits(recs: list[tuple[LabRecord, float, float]], wide: bool | None = None,
          far: bool | None = None) -> int:
    """How many of ``recs`` get one change within its tolerance, with ``OSC_WIDE = wide``
    and ``FAR_STEPS = far`` (None: as the detector is)."""
    with patch.object(P, "OSC_WIDE", P.OSC_WIDE if wide is None else wide), \
            patch.object(P, "FAR_STEPS", P.FAR_STEPS if far is None else far):
        return z.one_change_right(recs, detect_program)


def test_osc_wide_is_a_moving_change_of_ratio_at_most_osc_wide_ratio_with_room() -> None:
    # room 200 s, period 45 s: a moving change of ratio up to 2.5 either way; ratio 3 or 10, or
    # to or from a hold, not; a side shorter than two periods (80 s) leaves a step beyond
    # OSC_RATIO unwidened but a small step widened as before. The mistake it is for: the
    # ratio taken one way only (a down-step not widened, or a large down-step widened), a
    # hold or a large step widened (zoo ratio-3 and multi steps 9182 and 10233 broke), the
    # room not looked at, or the small steps made to need the room
    for v1, v2 in ((1e-6, 2.06e-6), (2.06e-6, 1e-6), (-1e-6, -2.4e-6), (1e-6, 1.3e-6)):
        assert P.osc_wide(v1, v2, 200.0, 45.0), (v1, v2)
    for v1, v2 in ((1e-6, 3e-6), (3e-6, 1e-6), (0.0, 1e-6), (1e-6, 0.0), (10e-6, 1e-6)):
        assert not P.osc_wide(v1, v2, 200.0, 45.0), (v1, v2)
    assert not P.osc_wide(1e-6, 2e-6, 80.0, 45.0) and not P.osc_wide(2e-6, 1e-6, 80.0, 45.0)
    assert P.osc_wide(1e-6, 1.3e-6, 80.0, 45.0) and P.osc_wide(1e-6, 2e-6, 90.0, 45.0)


@pytest.mark.slow
def test_ratio_2_steps_placed_better_on_two_periods_each_side() -> None:
    # ratio-2 steps with the servo error and an oscillation that is NOT the zoo's (one line,
    # 5 % at 37 s; seeds 0-99): within max(1 sample, 0.5 s) 100 of 100 with the rule, 97
    # without; with the zoo's (6 % at 22 s, 4 % at 45 s; seeds 0-59): 60 and 58 (measured;
    # on seeds 0-149: 150 and 143 at 37 s, 149 and 141 with the zoo's, 147 and 143 with two
    # lines at 28 and 70 s, 147 and 145 with one at 60 s). The mistake it is for: OSC_WIDE off
    # (the window of a ratio-2 step not widened, its long period left to the OU wander), the
    # rule on the small steps only (a bound at OSC_RATIO), or the ratio one way only (the
    # down-steps, even seeds, not widened); the first count is the detector's as it is, so
    # the rule must be on by default. The rule's gain is measured with the far samples at
    # holds only (FAR_STEPS off): since stop 49 a step left not placed is placed again on its
    # stretches' far samples whatever OSC_WIDE says, and the first records give 100 with the
    # rule and 99 without (measured)
    one = [_step(seed, 2.0, ((0.05, 37.0),)) for seed in range(100)]
    on, off = _hits(one, far=False), _hits(one, False, far=False)
    assert on >= 99 and on >= off + 2, (on, off)
    assert _hits(one) >= 99
    zoo = [_step(seed, 2.0, z.WOBBLE) for seed in range(60)]
    on, off = _hits(zoo, far=False), _hits(zoo, False, far=False)
    assert on >= 59 and on >= off + 1, (on, off)
    assert _hits(zoo) >= 59


def _placements(recs: list[LabRecord]) -> dict[bool, list[tuple]]:
    """Each record's segments (first sample, 95 % interval) with ``OSC_WIDE`` on and off."""
    return z.starts_with(recs, detect_program, P, "OSC_WIDE")


def _short(seed: int, ratio: float) -> LabRecord:
    """A short step: 0.3-10 um/s for 150-300 s, ``ratio`` times that for 8-20 s, back for
    150-300 s, 10 Hz, the zoo's oscillation, servo error, white noise and quantum
    (``records_zoo.step_displacement``)."""
    rng = np.random.default_rng(seed)
    v1 = 10 ** rng.uniform(-6.5, -5.0)
    d1, ds, d3 = rng.uniform(150.0, 300.0), rng.uniform(8.0, 20.0), rng.uniform(150.0, 300.0)
    t = np.arange(0.0, d1 + ds + d3, 0.1)
    x = z.step_displacement(t, np.where((t >= d1) & (t < d1 + ds), ratio * v1, v1), rng)
    return LabRecord("s.txt", t + 100.0, x, None, np.full(t.size, 0.6), None, "", {}, 2)


def test_short_step_placement_unchanged_by_osc_wide() -> None:
    # short steps of ratio 2 (8-20 s) with the zoo's oscillation, seeds 0-11, are placed as
    # before whatever OSC_WIDE says: their short side holds no two periods (without that
    # guard, 16 of 20 placements moved, measured; on the zoo, short steps of ratio 3 widened
    # without it broke: 194, 5018, 7238, 11234). The mistake it is for: the room not looked
    # at (the long side widened alone)
    got = _placements([_short(seed, 2.0) for seed in range(12)])
    assert all(len(g) == 3 for g in got[True])
    assert got[True] == got[False]


def test_ratio_3_placement_unchanged_by_osc_wide() -> None:
    # ratio-3 steps with the zoo's oscillation (seeds 0-11) are placed as before whatever
    # OSC_WIDE says: the wider window is for ratios up to OSC_WIDE_RATIO only (every moving
    # step widened moves 3 of these 12, measured). The mistake it is for: every step widened
    got = _placements([_step(seed, 3.0, z.WOBBLE)[0] for seed in range(12)])
    assert got[True] == got[False]
