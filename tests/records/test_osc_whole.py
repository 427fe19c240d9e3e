"""A moving step of ratio beyond ``OSC_WIDE_RATIO`` (3, 10), not a stop, in an oscillating
record is placed on a window of one oscillation period each side where its neighbours leave
room for one (``records.placement.OSC_WHOLE``, ``osc_whole``; branch stepfix): with the
amplitude following the velocity a period enters the hinge only where the window holds it
whole on each side, and the unwidened window (25 s each side under the zoo's servo error)
does not hold a 45-s period."""

from __future__ import annotations

import sys
from pathlib import Path
from unittest.mock import patch

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from benchmarks.bench_detect_oracle import draw  # noqa: E402

import records_zoo as z  # noqa: E402
from dryfriction.records import placement as P  # noqa: E402
from dryfriction.records.lab import LabRecord, detect_program  # noqa: E402


def _record(t: np.ndarray, vc: np.ndarray, osc: tuple[tuple[float, float], ...],
            rng: np.random.Generator) -> LabRecord:
    """A record of the commanded velocity ``vc`` (m/s) at times ``t`` (s): the velocity
    oscillating by ``osc`` (``(relative amplitude, period s)`` each, random phases), the
    servo's position error, 0.17 um white noise and a 20 nm quantum (as the zoo draws them)."""
    eps = np.zeros_like(t)
    for amp, per in osc:
        eps += amp * np.sin(2.0 * np.pi * t / per + rng.uniform(0.0, 2.0 * np.pi))
    vt = vc * (1.0 + eps)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (vt[1:] + vt[:-1]) * np.diff(t))])
    x += z.servo_error(t, vc, rng) + rng.normal(0.0, z.WHITE, t.size)
    x = np.round(x / z.QUANTUM) * z.QUANTUM
    return LabRecord("r.txt", t + 100.0, x, None, np.full(t.size, 0.6), None, "", {}, 2)


def _step(seed: int, ratio: float, osc: tuple[tuple[float, float], ...]
          ) -> tuple[LabRecord, float, float]:
    """An up (odd seed) or down step of ``ratio`` drawn as the zoo draws its up/down records
    (``bench_detect_oracle.draw``); returns the record, the true change time (s, record time)
    and its tolerance (s)."""
    rng = np.random.default_rng(seed)
    v1, v2, d1, d2, fs = draw(rng, ratio, bool(seed % 2))
    t = np.arange(0.0, d1 + d2, 1.0 / fs)
    return _record(t, np.where(t >= d1, v2, v1), osc, rng), d1 + 100.0, z.tolerance(t, d1)


def _hits(recs: list[tuple[LabRecord, float, float]], whole: bool | None = None,
          far: bool | None = None) -> int:
    """How many of ``recs`` get one change within its tolerance, with ``OSC_WHOLE = whole``
    and ``FAR_STEPS = far`` (None: as the detector is)."""
    with patch.object(P, "OSC_WHOLE", P.OSC_WHOLE if whole is None else whole), \
            patch.object(P, "FAR_STEPS", P.FAR_STEPS if far is None else far):
        return z.one_change_right(recs, detect_program)


def _placements(recs: list[LabRecord]) -> dict[bool, list[tuple]]:
    """Each record's segments (first sample, 95 % interval) with ``OSC_WHOLE`` on and off."""
    return z.starts_with(recs, detect_program, P, "OSC_WHOLE")


def test_osc_whole_is_a_moving_change_beyond_osc_wide_ratio_short_of_a_stop_with_room() -> None:
    # room 60 s, period 45 s: a moving change of ratio 3 or 10 either way; ratio 2 or 1.3
    # (OSC_WIDE's), a stop (ratio 30 down or up, the slower at or below RELAX_STOP of the
    # faster), a hold, no period found, or a side shorter than one period, not. The mistake
    # it is for: the ratio taken one way only, the small steps or the stops taken in, the room
    # not looked at, or a window widened with no period found
    for v1, v2 in ((1e-6, 3e-6), (3e-6, 1e-6), (-1e-6, -10e-6), (10e-6, 1e-6), (1e-6, 19e-6)):
        assert P.osc_whole(v1, v2, 60.0, 45.0), (v1, v2)
    for v1, v2 in ((1e-6, 2.06e-6), (2.06e-6, 1e-6), (1e-6, 1.3e-6), (30e-6, 1e-6),
                   (1e-6, 30e-6), (1e-6, 20e-6), (0.0, 3e-6), (3e-6, 0.0)):
        assert not P.osc_whole(v1, v2, 60.0, 45.0), (v1, v2)
    assert not P.osc_whole(1e-6, 3e-6, 44.0, 45.0) and not P.osc_whole(3e-6, 1e-6, 60.0, 0.0)
    assert P.osc_whole(1e-6, 3e-6, 45.0, 45.0)


@pytest.mark.slow
def test_ratio_3_steps_placed_better_on_one_period_each_side() -> None:
    # ratio-3 steps with the servo error and one oscillation line of 8 % at 45 s (seeds 0-59):
    # within max(1 sample, 0.5 s) 59 of 60 with the rule, 56 without (measured; with the
    # zoo's two lines, seeds 0-199: 200 and 197; one line of 5 % at 37 s: 200 and 198). The
    # mistake it is for: OSC_WHOLE off (the 45-s line left to the OU wander over 25 s each
    # side), or the ratio one way only (the down-steps, even seeds); the first count is the
    # detector's as it is, so the rule must be on by default. The rule's gain is measured with
    # the far samples at holds only (FAR_STEPS off): since stop 49 a step left not placed is
    # placed again on its stretches' far samples whatever OSC_WHOLE says, and these records
    # give 59 with the rule and 58 without (measured)
    recs = [_step(seed, 3.0, ((0.08, 45.0),)) for seed in range(60)]
    on, off = _hits(recs, far=False), _hits(recs, False, far=False)
    assert on >= 58 and on >= off + 2, (on, off)
    assert _hits(recs) >= 58


def _short(seed: int, ratio: float) -> LabRecord:
    """A short step: 0.3-10 um/s for 150-300 s, ``ratio`` times that for 8-20 s, back for
    150-300 s, 10 Hz, the zoo's oscillation, servo error, white noise and quantum."""
    rng = np.random.default_rng(seed)
    v1 = 10 ** rng.uniform(-6.5, -5.0)
    d1, ds, d3 = rng.uniform(150.0, 300.0), rng.uniform(8.0, 20.0), rng.uniform(150.0, 300.0)
    t = np.arange(0.0, d1 + ds + d3, 0.1)
    vc = np.where((t >= d1) & (t < d1 + ds), ratio * v1, v1)
    return _record(t, vc, z.WOBBLE, rng)


def test_short_step_placement_unchanged_by_osc_whole() -> None:
    # short steps of ratio 3 (8-20 s) with the zoo's oscillation, seeds 0-11, are placed as
    # before whatever OSC_WHOLE says: their short side holds no whole period. The mistake it
    # is for: the room not looked at (the long side widened alone, where the period cannot
    # enter and the long side's wander pulls the hinge)
    got = _placements([_short(seed, 3.0) for seed in range(12)])
    assert all(len(g) == 3 for g in got[True])
    assert got[True] == got[False]


def test_stop_placement_unchanged_by_osc_whole() -> None:
    # down-steps of ratio 30 with the zoo's oscillation (seeds 0-11) are placed as before
    # whatever OSC_WHOLE says: a stop is placed with the servo's relaxation and its slow side
    # carries almost no oscillation. The mistake it is for: the stops taken in. Measured with
    # the far samples at holds only (FAR_STEPS off): with them, since stop 49, these stops'
    # windows reach 300 s whatever OSC_WHOLE says, and the mistake goes unseen
    with patch.object(P, "FAR_STEPS", False):
        got = _placements([_step(2 * seed, 30.0, z.WOBBLE)[0] for seed in range(12)])
    assert got[True] == got[False]
