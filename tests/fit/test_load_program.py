"""A series' load program by its definitions (issue 25): SeriesData.segments (a stretch from
the first sample of each run of equal v_load to the next, the last single-sample run given the
median sampling interval) on a non-uniform clock that starts at 13 s, and
fit.loadpoint.load_program built on it (times from the first sample, whether it holds, built
once per data set); drive_report and check_drive."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.fit.loadpoint import check_drive, drive_report, load_program
from dryfriction.records.data import SeriesData

T = np.array([13.0, 13.4, 14.1, 14.3, 15.6, 16.0, 16.9])
V = np.array([2e-6, 2e-6, 0.0, 0.0, 5e-6, 5e-6, 0.7e-6])  # a hold; a last run of one sample


def test_segments_by_their_definition() -> None:
    d = SeriesData(T, V, np.full(T.size, 0.6))
    dur, vel = d.segments()
    med = float(np.median(np.diff(T)))
    assert med == pytest.approx(0.55) and med != pytest.approx(float(np.mean(np.diff(T))))
    np.testing.assert_allclose(dur, [14.1 - 13.0, 15.6 - 14.1, 16.9 - 15.6, med], rtol=1e-12)
    np.testing.assert_array_equal(vel, [2e-6, 0.0, 5e-6, 0.7e-6])
    # a last run of two samples keeps its own duration
    dur2, _ = SeriesData(T, np.concatenate([V[:-2], [0.7e-6, 0.7e-6]]), d.mu).segments()
    assert dur2[-1] == pytest.approx(16.9 - 16.0)


def test_load_program_from_the_first_sample_once_per_data_set() -> None:
    d = SeriesData(T, V, np.full(T.size, 0.6))
    prog, te, holds = load_program(d)
    np.testing.assert_allclose(te, T - 13.0, rtol=1e-12)  # from the first sample
    assert holds is True
    assert [s.velocity for s in prog.segments] == [2e-6, 0.0, 5e-6, 0.7e-6]
    again = load_program(d)
    assert again[0] is prog  # built once
    slide = SeriesData(T, np.where(V == 0.0, 1e-6, V), d.mu)
    assert load_program(slide)[2] is False
    assert drive_report(d) == {"kind": "program"}


def test_check_drive() -> None:
    assert check_drive("program") == "program" and check_drive("measured") == "measured"
    with pytest.raises(ValueError, match="^--drive 'Measured' is not allowed: program or "
                                         "measured$"):
        check_drive("Measured")
