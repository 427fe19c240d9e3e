"""The relative wander ``r(T)`` is measured on pairs of windows that move
(detection.MOVING_Z, MOVING_SHARE), not on a long hold's (stop 53, after
``bench_detect_holds``' family B and an independent review's slide-hold-slides).

The records: slide, a slow slide (1/16-1/22 of the speed) for 40 s, a hold of 600-1000 s, slide,
from ``test_program_direction``'s generator (white noise 0.15 um, a position wander of 60 nm and
8 s that does not scale with the speed, 2 Hz, times from 3127.4 s) plus a random-walk drift of
the transducer (0.75 um rms, its own draws): a record mostly at rest, as a slide-hold-slide
with a long hold is. It has no wander that scales with the speed: what ``r(T)`` reads is the
position wander's slope scatter over the slides' speed, a few per cent.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from dryfriction.records.detection import measure_fluctuations
from dryfriction.records.lab import detect_program, read_record
from dryfriction.records.segmentation import noise_level

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_program_direction import _program, _write  # noqa: E402

CASES = ((7, 1.3e-6, 0.07e-6, 1000.0), (8, 2.9e-6, 0.13e-6, 800.0), (9, 0.63e-6, 0.04e-6, 600.0))


def _record(seed: int, v1: float, vs: float, hold: float
            ) -> tuple[np.ndarray, np.ndarray, tuple[float, ...]]:
    """Times (s), displacement (m) and stretch durations (s) of one record."""
    durations = (100.0, 40.0, hold, 100.0)
    t, x = _program((v1, vs, 0.0, v1), durations, seed=seed, fs=2.0, wander=60e-9, tau=8.0)
    # the drift's own draws (``_program`` draws its wander from default_rng(seed))
    walk = np.cumsum(np.random.default_rng([seed, 1]).standard_normal(t.size))
    return t, x + walk / np.std(walk) * 0.75e-6, durations


@pytest.mark.parametrize("case", CASES)
def test_relative_wander_of_a_record_mostly_at_rest(case: tuple) -> None:
    """Measured about the broken line that the pruning leaves when the slow slide is taken
    into the hold (slide | slow slide + hold | slide), ``r(T)`` stays under 15 % at every
    duration (measured: 2.0, 1.1 and 9.6 %). Mistake, seen failing: ``r`` from the faster
    half of the pairs by rank whatever their speed (``MOVING_Z = 0``, as before stop 53):
    105, 26 and 26 %, the hold's creep of nm/s taken for a speed."""
    t, x, durations = _record(*case)
    ends = np.cumsum(durations)
    bounds = [0, int(np.searchsorted(t - t[0], ends[0])),
              int(np.searchsorted(t - t[0], ends[2])), t.size]
    v = np.array([np.polyfit(t[a:b], x[a:b], 1)[0] for a, b in zip(bounds[:-1], bounds[1:],
                                                                    strict=True)])
    fl = measure_fluctuations(t, x, noise_level(x), bounds, v)
    assert fl.relative.max() < 0.15, fl.relative


def test_a_long_hold_keeps_its_slides(tmp_path: Path) -> None:
    """The whole detection on the first record (1.3 um/s, 0.07 um/s for 40 s, a 1000-s hold,
    1.3 um/s): the slides before and after are found at 1.3 um/s (within 5 %), the first
    change within 1 s of 100 s and the restart within 1 s of 1140 s, a hold of more than 900
    s between. Mistake, seen failing: ``MOVING_Z = 0`` (the whole record one segment at
    0.047 um/s: ``r`` read up to 0.89 as the boundaries went, every change pruned)."""
    t, x, _ = _record(*CASES[0])
    det = detect_program(read_record(_write(tmp_path / "long_hold.txt", t, x)))
    seg = det.segments
    assert len(seg) >= 3
    assert seg[0].velocity == pytest.approx(1.3e-6, rel=0.05)
    assert seg[-1].velocity == pytest.approx(1.3e-6, rel=0.05)
    assert seg[1].t_start - t[0] == pytest.approx(100.0, abs=1.0)
    assert seg[-1].t_start - t[0] == pytest.approx(1140.0, abs=1.0)
    assert any(s.velocity == 0.0 and s.t_end - s.t_start > 900.0 for s in seg)


def test_short_fast_slides_about_a_long_hold(tmp_path: Path) -> None:
    """13.8 um/s for 38 s, a 1561-s hold, 13.8 um/s for 61 s (8 Hz, a 23-nm position wander of
    22 s, a linear drift of 0.94 um over the record): three segments, the stop within 1 s of
    38.1 s and the restart within 1 s of 1599.6 s, the slides at 13.8 um/s within 2 %.
    At the longest durations the slower half's scatter is below the hold's fitted creep, so
    that the scatter alone lets the hold's pairs in (an independent review's record of the
    kind). Mistake, seen failing: no share of the top speed asked (``MOVING_SHARE = 0``:
    ``r`` 23 % at every duration from 4.4 to 140 s, the record one segment at 0.08 um/s)."""
    t, x = _program((13.83e-6, 0.0, 13.83e-6), (38.09, 1561.46, 61.49), seed=0, fs=8.0,
                    wander=23e-9, tau=22.0)
    x = x + 0.94e-6 * (t - t[0]) / (t[-1] - t[0])
    seg = detect_program(read_record(_write(tmp_path / "fast_slides.txt", t, x))).segments
    assert len(seg) == 3
    assert seg[1].velocity == 0.0
    assert seg[0].velocity == pytest.approx(13.83e-6, rel=0.02)
    assert seg[2].velocity == pytest.approx(13.83e-6, rel=0.02)
    assert seg[1].t_start - t[0] == pytest.approx(38.09, abs=1.0)
    assert seg[2].t_start - t[0] == pytest.approx(1599.55, abs=1.0)
