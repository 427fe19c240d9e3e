"""``step_data`` (fit/steps.py): each window's samples ``[i_start, i_end)`` of a laboratory
record, its load velocity from the segments, named by its step; both edges of the allowed
range and a sample no segment covers refused by name."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from dryfriction.fit.steps import step_data
from dryfriction.records.labsteps import make_segments
from dryfriction.records.record import LabRecord

T = 300.0 + 0.25 * np.arange(120)
REC = LabRecord("bench.csv", T, None, None, 0.6 + 0.001 * np.arange(120), None, "", {}, 1)
SEGS = make_segments(T, [0, 50, 80, 120], [2e-6, 0.0, 7e-6])


def test_windows_samples_velocity_and_names() -> None:
    # mistakes: the window's last sample included (i_end + 1), the velocity of the segment
    # before, the friction of the whole record
    w = [SimpleNamespace(index=0, i_start=10, i_end=80), SimpleNamespace(index=1, i_start=45,
                                                                         i_end=120)]
    a, b = step_data(REC, w, SEGS)
    np.testing.assert_array_equal(a.t, T[10:80])
    np.testing.assert_array_equal(a.mu, REC.friction[10:80])
    np.testing.assert_array_equal(a.v_load, np.where(np.arange(10, 80) < 50, 2e-6, 0.0))
    assert a.source == "bench.csv [step 0]" and b.source == "bench.csv [step 1]"
    k = np.arange(45, 120)
    np.testing.assert_array_equal(b.v_load, np.where(k < 50, 2e-6, np.where(k < 80, 0.0, 7e-6)))
    assert len(b) == 75  # up to the record's last sample


@pytest.mark.parametrize("i0, i1, ok", [(0, 120, True), (0, 121, False), (-1, 40, False),
                                         (60, 60, False)])
def test_window_range_both_edges(i0, i1, ok) -> None:
    w = [SimpleNamespace(index=4, i_start=i0, i_end=i1)]
    if ok:
        assert len(step_data(REC, w, SEGS)[0]) == i1 - i0
    else:
        with pytest.raises(ValueError, match=r"bench\.csv: window 4 covers samples .* out of "
                                             r"range: allowed within \[0, 120\)"):
            step_data(REC, w, SEGS)


def test_a_sample_in_no_segment_is_refused() -> None:
    short = make_segments(T, [0, 50, 80, 119], [2e-6, 0.0, 7e-6])
    with pytest.raises(ValueError, match=r"sample 119 \(t = 329.75 s\) is in no segment"):
        step_data(REC, [SimpleNamespace(index=0, i_start=0, i_end=10)], short)
    with pytest.raises(ValueError, match="needs its segments"):
        step_data(REC, [SimpleNamespace(index=0, i_start=0, i_end=10)], None)
