"""Changes the detector missed (issue 23, detect12; records/detection.py's REPLACE_REACH).

A short hold in a long slide-hold-slide was found as a candidate and stood in the pruning
until a weak boundary beside it was removed: its end, re-placed at the best hinge between its
new neighbours, moved hundreds of seconds into the slide (a wobble's kink over the merged
stretch outweighs the short hold's), and the hold was lost (zoo 3112; a short step, 278,
likewise). Each test names
the mistake it is for, and each was seen failing with it applied.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import dryfriction.records.detection as detection
from dryfriction.records.detection import _reach, _replace
from dryfriction.records.placement import FINE_RATIO
from dryfriction.records.segmentation import refine


def _zoo_counts(indices: tuple[int, ...], tmp: Path) -> list[tuple[int, int, bool]]:
    """(changes found, true changes, every change within its tolerance) of each of these zoo
    records, written in its dialect and read back as bench_detect does."""
    from dryfriction.records.lab import detect_program, read_record
    from records_zoo import record_at, score, write

    out = []
    for i in sorted(set(indices)):
        rec = record_at(i)
        s = score(rec, detect_program(read_record(write(rec, tmp))), 0.0)
        out.append((s.found, len(rec.changes), bool(s.right)))
    return out


def test_reach_only_for_large_changes_and_the_shorter_stretch() -> None:
    """``_reach`` at generic speeds (1.7 um/s, stretches of 300, 20, 380 and 300 samples): a
    hold's two ends (ratio infinite) and a ratio-3 step reach as far as their shorter
    stretch; a ratio-1.5 excursion (a servo burst read with the wander: the zoo's 12 %
    bursts read at 26-34 %) and a change just under ``FINE_RATIO`` are not listed; a
    reversal is, and so is a change just over ``FINE_RATIO``. Mistakes: the longer stretch
    for the shorter; the ratio the wrong way round (small changes listed, large not); every
    change listed."""
    v = 1.7e-6
    b = [0, 300, 320, 700, 1000]
    assert _reach(b, np.array([v, 0.0, v, 3.0 * v])) == {300: 20, 320: 20, 700: 300}
    assert _reach(b, np.array([v, 1.5 * v, v, 0.99 * FINE_RATIO * v])) == {}
    assert _reach(b, np.array([v, -v, v / 1.5, v / 1.5 * 1.01 * FINE_RATIO])) == {
        300: 20, 320: 20, 700: 300}


def test_a_hold_end_is_re_placed_within_its_hold_not_at_a_far_kink() -> None:
    """A 20-s hold at 300-320 s in a slide of 1.7 um/s that changes by 15 % at 700 s (10 Hz,
    white noise 0.05 um, the clock starting at 37 s): the hold's end re-placed between its
    neighbours (the hold's start and the record's end) by ``refine`` moves to the 15 % kink
    (sample 6932, 693 s: the kink over two stretches of hundreds of seconds gains more than
    the short hold's); ``_replace`` within its reach (the hold's 200 samples) keeps it at
    sample 3200. Mistakes: the reach ignored (between the neighbours, as ``refine``); the
    reach on one side only."""
    rng = np.random.default_rng(3)
    t = np.arange(0.0, 1000.0, 0.1) + 37.0
    s = t - 37.0
    v = np.where(s < 300, 1.7, np.where(s < 320, 0.0, np.where(s < 700, 1.7, 1.7 * 1.15)))
    x = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
    xs = (x + rng.normal(0.0, 0.05, t.size)) / 0.05
    b = [0, 3000, 3200, t.size]
    reach = _reach(b, np.array([1.7, 0.0, 1.7]))
    assert reach[3200] == 200
    assert abs(refine(t, xs, b, 10, 0.0, only={3200})[2] - 3200) > 2000  # the mistake
    assert abs(_replace(t, xs, b, {3200: reach[3200]}, 10)[2] - 3200) <= 5
    # a boundary not listed moves as refine moves it
    assert _replace(t, xs, b, {3200: t.size}, 10) == refine(t, xs, b, 10, 0.0, only={3200})


def test_a_short_stretch_in_a_long_record_is_kept(tmp_path: Path,
                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    """Zoo 8068 (a slide-hold-slide at 0.11 um/s, 86408 rows at 20 Hz, every artifact): every
    change found (measured: four of four, within 0.31 of their tolerance). Mistake, seen failing:
    ``REPLACE_REACH`` off (none found of four: a weak boundary beside a short stretch went, in
    the pruning or in the move from block means to samples, and the hold's end moved far into
    the slide). The rule's examples until stop 42, zoo 3112 and 278, lost it when the zoo came
    to integrate its gaps exactly and a reset's offset across a gap to be fitted on windows as
    long as the gap (``RESET_WIDE``): both are counted right with it off too
    (``test_records_with_a_short_stretch_counted``)."""
    found, true, _ = _zoo_counts((8068,), tmp_path)[0]
    assert found == true
    monkeypatch.setattr(detection, "REPLACE_REACH", False)
    assert _zoo_counts((8068,), tmp_path)[0][0] < true


@pytest.mark.parametrize("index", [3112, 278])
def test_records_with_a_short_stretch_counted(tmp_path: Path, index: int) -> None:
    """Zoo 3112 (a 19-s hold at 443 s in a 23729-row slide-hold-slide, every artifact) and
    278 (an 8-s step of ratio 2.8 at 101 s in 34672 rows, every artifact): every change
    found (``REPLACE_REACH``'s examples until stop 42). 3-5 s each."""
    found, true, _ = _zoo_counts((index,), tmp_path)[0]
    assert found == true
