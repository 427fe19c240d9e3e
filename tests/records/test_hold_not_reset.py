"""A short hold is not a re-zeroing of the transducer (records/artifacts.py's JUMP_REFINED,
_broken_line).

On a long record the detector searches block means, and a short hold's boundaries come out
seconds off (zoo 18046: a 19-s hold at 0.107 um/s, 20 Hz, found as a 52-s stretch at 0.055
um/s). ``jump_excursions`` compared one line with a step against the three stretches' lines
at those boundaries, the step won, and the hold (2 um of slip not made) was taken out as a
reset: the record lost a slide-hold-slide. Each test names the mistake it is for; each was
seen failing with it applied.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import dryfriction.records.artifacts as artifacts

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_missed_changes import _zoo_counts  # noqa: E402


def _broken_rss(t: np.ndarray, y: np.ndarray, k1: int, k2: int) -> float:
    """Residual sum of squares of the continuous broken line with kinks at samples ``k1`` and
    ``k2`` (an independent route: numpy's lstsq on its four columns)."""
    A = np.column_stack([np.ones(t.size), t, np.maximum(t - t[k1], 0.0),
                         np.maximum(t - t[k2], 0.0)])
    r = y - A @ np.linalg.lstsq(A, y, rcond=None)[0]
    return float(r @ r)


def test_broken_line_at_fixed_kinks_is_its_least_squares() -> None:
    """``m = 0``: the residual sum of squares of the broken line at the kinks given (lstsq),
    at generic times (0.37-s steps from 811 s, jittered, centred) and values (um), to 1e-8
    relative. Mistakes: the fixed kink's column left out of the projection; the scale not
    restored. (A kink's sums taken from the sample after it is no mistake: its term is 0.)"""
    rng = np.random.default_rng(7)
    t = 811.0 + np.cumsum(rng.uniform(0.3, 0.44, 97))
    y = 3.3e-6 * np.sin(t / 7.0) + rng.normal(0.0, 0.2e-6, t.size)
    tc, yc = t - t.mean(), y - y.mean()
    got = artifacts._broken_line(tc, yc, 31, 64, 0)
    assert got == pytest.approx(_broken_rss(tc, yc, 31, 64), rel=1e-8)


def test_broken_line_finds_its_kinks_within_reach() -> None:
    """A noiseless broken line (slopes 1.7, -0.4 and 2.9 um/s, kinks at -3 and 9 s on 0.2-s
    samples) given kinks 6 and 9 samples off, ``m = 12``: the sum is ~0 (the kinks found,
    each the best for the other's place in turn); ``m = 3`` (out of reach): it is not; a
    jump of 2 um instead of the second kink is not fitted (the line is continuous). Mistakes:
    the kinks not moved (``reach`` ignored); separate lines (a jump fitted)."""
    t = np.linspace(-20.0, 20.0, 201)
    y = 1e-6 * (1.7 * t + (-0.4 - 1.7) * np.maximum(t + 3.0, 0.0)
                + (2.9 + 0.4) * np.maximum(t - 9.0, 0.0))
    k1, k2 = int(np.searchsorted(t, -3.0)), int(np.searchsorted(t, 9.0))
    yc = y - y.mean()
    assert artifacts._broken_line(t, yc, k1 - 6, k2 + 9, 12) < 1e-12 * float(yc @ yc)
    assert artifacts._broken_line(t, yc, k1 - 6, k2 + 9, 3) > 1e-4 * float(yc @ yc)
    jump = 1e-6 * (1.7 * t + (-0.4 - 1.7) * np.maximum(t + 3.0, 0.0)) + np.where(
        t >= 9.0, 2e-6, 0.0)
    jc = jump - jump.mean()
    assert artifacts._broken_line(t, jc, k1 - 6, k2 + 9, 12) > 1e-3 * float(jc @ jc)


def _hold_record() -> tuple[np.ndarray, np.ndarray, list[int], np.ndarray]:
    """Zoo 18046's case, generated here: a slide at 0.107 um/s, 20 Hz from 1203.7 s, a 19-s
    hold 200 s in, 0.17 um of white noise, a 0.146-um quantum; the boundaries and speeds as
    the block search gave them there (30 s early, 3 s late; 0.055 um/s between)."""
    rng = np.random.default_rng(18046)
    dt, v = 0.05, 0.107e-6
    t = 1203.7 + np.arange(0.0, 400.0, dt)
    u = t - t[0]
    vel = np.where((u >= 200.0) & (u < 219.0), 0.0, v)
    x = 1.27e-3 + np.concatenate([[0.0], np.cumsum(0.5 * (vel[1:] + vel[:-1]) * dt)])
    x = np.round((x + rng.normal(0.0, 0.17e-6, t.size)) / 0.146e-6) * 0.146e-6
    bounds = [0, int(np.searchsorted(u, 170.65)), int(np.searchsorted(u, 222.24)), t.size]
    return t, x, bounds, np.array([v, 0.0546e-6, v])


def test_a_short_hold_found_coarsely_is_not_a_jump(monkeypatch: pytest.MonkeyPatch) -> None:
    """The hold above, ``m`` = 1629 samples and ``reach`` = 1086 (blocks of 543, as the
    detector gave): no jump. With ``JUMP_REFINED`` off, or ``reach`` 0 (the three lines at
    the block search's boundaries), it is taken for a -1.85 um jump (measured), which is the
    mistake this is for."""
    t, x, bounds, speeds = _hold_record()
    assert artifacts.jump_excursions(t, x, bounds, speeds, 0.1, 1629, 0.01, 1086) == []
    (found,) = artifacts.jump_excursions(t, x, bounds, speeds, 0.1, 1629, 0.01, 0)
    assert found[2] == pytest.approx(-1.85e-6, abs=0.1e-6)
    monkeypatch.setattr(artifacts, "JUMP_REFINED", False)
    (found,) = artifacts.jump_excursions(t, x, bounds, speeds, 0.1, 1629, 0.01, 1086)
    assert found[2] == pytest.approx(-1.85e-6, abs=0.1e-6)


def test_a_jump_inside_such_an_excursion_is_still_one() -> None:
    """The same record with no hold and the transducer re-zeroed by -0.9 um at 211.3 s (the
    same coarse boundaries): the jump is found at its sample, of its size within 0.15 um.
    Mistake: the jump searched only where the excursion's kinks were moved to (its first
    sample off), or its size from the broken line (the ramp's slope, not the step). Kinks at
    adjacent samples (a one-interval ramp for the jump) were tried as a mutant and pass here
    and on zoo 123, 368, 11290 and 18046: the jump still fits as well, so it is kept."""
    t, x, bounds, speeds = _hold_record()
    v = 0.107e-6
    u = t - t[0]
    rng = np.random.default_rng(2113)
    x = 1.27e-3 + v * u + rng.normal(0.0, 0.17e-6, t.size)
    k = int(np.searchsorted(u, 211.3))
    x[k:] -= 0.9e-6
    x = np.round(x / 0.146e-6) * 0.146e-6
    (found,) = artifacts.jump_excursions(t, x, bounds, speeds, 0.1, 1629, 0.01, 1086)
    assert abs(found[1] - k) <= 1
    assert found[2] == pytest.approx(-0.9e-6, abs=0.15e-6)


@pytest.mark.slow
def test_zoo_slide_hold_slides_keep_their_short_holds(tmp_path: Path) -> None:
    """Zoo 11290 (a 13-s hold at 0.228 um/s, 200 Hz, 434204 rows, read as a -2.7 um reset
    before) and 18046 (the hold above in the zoo, 1084408 rows, with the servo error, the
    oscillation, a rate change at the restart, a reset and a 0.146-um quantum): four changes
    each, every one within its tolerance (both lost their first slide-hold-slide with
    ``JUMP_REFINED`` off: two changes found)."""
    assert _zoo_counts((11290, 18046), tmp_path) == [(4, 4, True), (4, 4, True)]
