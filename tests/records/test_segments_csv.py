"""segments.csv (records/labsteps.py ``write_segments_csv``) against a hand computation of each
column, for a program with a step up, a hold, a step down and a normal-stress change at one
velocity, its record starting at a time other than 0 (issue 25). Each test names the mistake it
is for; each was seen failing with it applied."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from dryfriction.io.units import read_rows
from dryfriction.records.labsteps import Segment, write_segments_csv

T0 = 1003.7  # the record's first sample, s


def test_every_column_by_hand(tmp_path: Path) -> None:
    # mistakes: a row's kind from the velocity alone (a normal change at one velocity called a
    # step, a first segment a step); velocity_um off by 1e3; samples i_end - i_start + 1;
    # t_from_first from 0 instead of the record's first sample; the --segments line's times
    # absolute
    segs = (Segment(T0, 1123.7, 1.3e-6, 0, 1200, normal=10.2e6),
            Segment(1123.7, 1190.2, 4.1e-6, 1200, 1865, 37.0, 10.2e6),
            Segment(1190.2, 1290.2, 0.0, 1865, 2865, 25.0, 10.2e6),
            Segment(1290.2, 1402.5, 0.7e-6, 2865, 3988, 19.0, 10.2e6),
            Segment(1402.5, 1500.0, 0.7e-6, 3988, 4963, math.nan, 15.3e6))
    path = tmp_path / "segments.csv"
    write_segments_csv(path, segs, T0, "Pa")
    first = path.read_text().splitlines()[0]
    assert first == ("# --segments 0:1.3e-06,120:4.1e-06,186.5:0,286.5:7e-07,398.8:7e-07")
    rows = read_rows(path)
    assert [r["kind"] for r in rows] == ["start", "step", "hold", "step", "normal change"]
    for r, s in zip(rows, segs, strict=True):
        assert float(r["t_from_first"]) == pytest.approx(s.t_start - T0, abs=1e-9)
        assert float(r["duration"]) == pytest.approx(s.t_end - s.t_start, abs=1e-9)
        assert float(r["velocity"]) == pytest.approx(s.velocity, rel=1e-6)
        assert float(r["velocity_um"]) == pytest.approx(s.velocity * 1e6, rel=1e-6)
        assert int(r["samples"]) == s.i_end - s.i_start
        assert float(r["normal_stress"]) == pytest.approx(s.normal / 1e6, rel=1e-6)
    assert rows[0]["confidence"] == "" and float(rows[1]["confidence"]) == 37.0
