"""A gap is samples not written (tests/records_zoo.py's _gap_increments) and a reset across one
fitted on windows as long as the gap (records/artifacts.py's RESET_WIDE, _offset_rows).

The zoo integrated the load point's velocity by the trapezoid over every sample interval, the
5-60 s over a gap included: the two ends' wobble and bursts stood for the whole gap, and the
displacement jumped by up to a tenth of the velocity times the gap where no apparatus moves.
Integrated exactly there, the detection's reset offsets across gaps (fitted on 30 samples a
side) read the wander as a slope and made false stretches. Each test names the mistake it is
for; each was seen failing with it applied (the numbers measured are in the docstrings).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import dryfriction.records.artifacts as artifacts
import dryfriction.records.detection as detection

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from test_missed_changes import _zoo_counts  # noqa: E402

import records_zoo as z  # noqa: E402

_record = z.record_at


def _fluctuation(rec: z.ZooRecord, u: np.ndarray) -> np.ndarray:
    """``eps`` at the times ``u`` (s from the first sample) by an independent route: the
    oscillation's two lines least-squares fitted to the record's ``eps`` samples (the bursts
    taken out), the bursts added as boxes."""
    t = rec.t - float(rec.t[0])

    def box(tt: np.ndarray) -> np.ndarray:
        out = np.zeros_like(tt)
        for s, d, amp in rec.bursts:
            out += np.where((tt >= s) & (tt < s + d), amp, 0.0)
        return out

    def lines(tt: np.ndarray) -> np.ndarray:
        return np.column_stack([f(2.0 * np.pi * tt / per) for _, per in z.WOBBLE
                                for f in (np.sin, np.cos)])

    coef = np.linalg.lstsq(lines(t), rec.eps - box(t), rcond=None)[0]
    return lines(u) @ coef + box(u)


def test_the_displacement_across_a_gap_is_the_motion_over_it() -> None:
    """Zoo 765 (a many-step run at 1.5-4.4 um/s with the oscillation, bursts, irregular
    sampling and two gaps of 13.4 and 6.4 s, no servo error, drift, reset or coarse quantum):
    over each gap the displacement grows by the velocity times the integral of ``1 + eps``
    by a fine quadrature (200001 points) of the fluctuations recovered from the record's
    ``eps`` samples (measured: 0.60 and 0.03 um off, within five times the white noise of
    two samples' difference, 1.2 um), and ``e_int`` grows by that integral (within 1e-5 s);
    off the gaps ``e_int`` is the trapezoid of ``1 + eps``. Mistake, seen failing: the
    trapezoid over the gaps as well (the increments 5.9 and 5.2 um off)."""
    rec = _record(765)
    t = rec.t - float(rec.t[0])
    vl = np.asarray(rec.velocities)[np.searchsorted(rec.changes, t, side="right")]
    g = 1.0 + rec.eps
    trap = 0.5 * (g[1:] + g[:-1]) * np.diff(t)
    dt = np.diff(t)
    gaps = np.flatnonzero(dt > 10.0 * np.median(dt))
    assert gaps.size == 2
    off = np.setdiff1d(np.arange(dt.size), gaps)
    assert np.allclose(np.diff(rec.e_int)[off], trap[off], rtol=0.0, atol=1e-9)
    for k in gaps:
        u = np.linspace(t[k], t[k + 1], 200001)
        quad = float(np.trapezoid(1.0 + _fluctuation(rec, u), u))
        assert abs(float(rec.e_int[k + 1] - rec.e_int[k]) - quad) < 1e-5
        assert vl[k] == vl[k + 1] > 0.0
        assert abs(float(rec.x[k + 1] - rec.x[k]) - vl[k] * quad) < 5.0 * np.sqrt(2.0) * z.WHITE


def test_offset_rows_reach_as_far_as_the_jump_lasts() -> None:
    """``_offset_rows`` at 50 Hz with a 28-s gap after sample 999 (t = 19.98 s): the samples
    reach 28 s before the gap and 28 s after it (1400 a side), evenly thinned to
    ``RESET_SIDE`` a side, the 30 a side always among the candidates, none past the
    neighbouring resets. Mistakes: the window of 30 samples (0.6 s) kept; thinned to fewer
    than RESET_SIDE; the neighbours ignored."""
    t = np.concatenate([np.arange(1000) * 0.02, 48.0 + np.arange(3000) * 0.02])
    i = 999
    rows = artifacts._offset_rows(t, i, 0, t.size, np.arange(i + 1 - 30, i + 1 + 30))
    left, right = rows[rows <= i], rows[rows > i]
    assert left.size == right.size == artifacts.RESET_SIDE
    assert t[i] - t[left[0]] >= 19.9 and t[right[-1]] - t[i + 1] >= 27.9
    assert left[-1] == i and right[0] == i + 1
    assert np.all(np.diff(rows) > 0)
    near = artifacts._offset_rows(t, i, 900, 1100, np.arange(i + 1 - 30, i + 1 + 30))
    assert near.min() >= 900 and near.max() < 1100


@pytest.mark.parametrize("index", [13263, 15016])
def test_a_gap_is_no_stretch_of_its_own(tmp_path: Path, index: int,
                                        monkeypatch: pytest.MonkeyPatch) -> None:
    """Zoo 13263 (a many-step run, 1.17 um/s at a 28-s gap at 50 Hz) and 15016 (a
    slide-hold-slide at 0.63 um/s, a gap at 20 Hz), every artifact: the changes counted right
    (measured: four of four each). A jump at the gap's increment (the wander over it: the
    local rates of 5 samples do not explain it) is fitted with lines reaching as far as the
    gap lasts each side (RESET_WIDE). Mistake, seen failing: the offset on 30 samples a side
    (RESET_WIDE = False: 13263 read -11 um there and a stretch at 1.56 um/s across the gap,
    six changes found; 15016 six). Judged with RESET_GAP off: with it on, those gaps are no
    resets at all and the mistake is hidden (RESET_GAP's own test: test_a_gap_is_no_reset);
    and with ``FINAL_SCORES`` off (with it, 15016's extra stretch goes at the final
    judgement)."""
    monkeypatch.setattr(artifacts, "RESET_GAP", False)
    found, true, _ = _zoo_counts((index,), tmp_path)[0]
    assert found == true
    monkeypatch.setattr(artifacts, "RESET_WIDE", False)
    monkeypatch.setattr(detection, "FINAL_SCORES", False)  # a second route to 15016's count
    assert _zoo_counts((index,), tmp_path)[0][0] > true


def _resets(index: int, tmp: Path) -> list[float]:
    """The resets (s from the first sample) the detection lists for zoo record ``index``,
    written in its dialect and read back."""
    from dryfriction.records.lab import detect_program, read_record

    rec = _record(index)
    det = detect_program(read_record(z.write(rec, tmp)))
    return [round(float(r - rec.t[0]), 1) for r in det.resets]


def test_a_gap_is_no_reset(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Zoo 396 (an up-step, every artifact, a re-zeroing at 476.3 s and gaps at 140.4-187.3
    and 827.2-868.7 s): the resets listed are the re-zeroing alone (measured). Over each gap
    the wander is beyond the local rates' reach, but its step is 0-8 times the rms residual
    of the offset's lines, the re-zeroing's hundreds (RESET_GAP). Mistake, seen failing: every
    gap that the local rates do not explain taken for a re-zeroing (RESET_GAP = False: 187.3,
    476.3 and 868.7 s)."""
    assert _resets(396, tmp_path) == [476.3]
    monkeypatch.setattr(artifacts, "RESET_GAP", False)
    assert _resets(396, tmp_path) == [187.3, 476.3, 868.7]


def test_a_re_zeroing_in_a_gap_is_still_a_reset(monkeypatch: pytest.MonkeyPatch) -> None:
    """A load point at 2.3 um/s sampled at 10 Hz (white noise 0.17 um, seed 5), a 20-s gap
    from 41.3 s, the transducer re-zeroed during it (-310 um): ``find_resets`` lists the gap's
    increment and takes the jump out (the offset within 0.5 um, the velocity's slip over the
    gap kept). Mistake, seen failing: a gap never a reset (RESET_GAP_K = 1e9: none
    listed)."""
    rng = np.random.default_rng(5)
    t = np.arange(0.0, 120.0, 0.1)
    t = t[(t < 41.3) | (t > 61.3)]
    v = 2.3e-6
    x = v * t + rng.normal(0.0, 0.17e-6, t.size)
    i = int(np.searchsorted(t, 41.3)) - 1
    x[i + 1:] -= 310e-6
    fixed, jumps = artifacts.find_resets(t, x)
    assert jumps == [i]
    assert abs(float(fixed[i + 1] - fixed[i]) - v * float(t[i + 1] - t[i])) < 0.5e-6
    monkeypatch.setattr(artifacts, "RESET_GAP_K", 1e9)
    assert artifacts.find_resets(t, x)[1] == []
