"""Normal-stress levels with steps that have no normal value among those that do, and the
levels' report by hand (fit/experiment.py; issue 25: an all-NaN or all-finite record hides
the mixed case). Each test names the mistake it is for; each was seen failing with it
applied."""

from __future__ import annotations

import math

import pytest

from dryfriction.fit.experiment import levels_report, normal_levels


def test_a_step_without_normal_value_is_a_level_of_its_own() -> None:
    # mistake: a NaN step put in level 0 with the lowest stress (fitted as one machine with
    # steps it may not share)
    nan = math.nan
    assert normal_levels([20.3e6, nan, 10.1e6, nan, 20.0e6]) == [1, 2, 0, 3, 1]
    assert normal_levels([nan, nan]) == [0, 0]


def test_levels_report_by_hand() -> None:
    # mistakes: the mean over a NaN value (NaN); holds counted as steps; the range from the
    # first and last rows instead of the smallest and largest
    rows = [{"index": 0, "kind": "step", "normal_level": 0, "normal": 10.1e6, "normal_unit": "Pa"},
            {"index": 1, "kind": "shs", "normal_level": 0, "normal": 9.9e6, "normal_unit": "Pa"},
            {"index": 2, "kind": "step", "normal_level": 0, "normal": math.nan,
             "normal_unit": "Pa"},
            {"index": 3, "kind": "step", "normal_level": 1, "normal": 30.2e6,
             "normal_unit": "Pa"},
            {"index": 4, "kind": "step", "normal_level": 0, "normal": 10.0e6, "normal_unit": "Pa"}]
    rep = levels_report(rows, {1: {"value": 2.1e3, "lo": 1.9e3, "hi": 2.3e3}})
    low, high = rep["levels"]
    assert low["normal"] == pytest.approx(10.0e6, rel=1e-14)
    assert (low["normal_min"], low["normal_max"]) == (9.9e6, 10.1e6)
    assert low["steps"] == [0, 2, 4] and low["holds"] == [1] and low["unit"] == "Pa"
    assert low["label"] == "10 MPa" and "stiffness" not in low
    assert high["stiffness"] == {"value": 2.1e3, "lo": 1.9e3, "hi": 2.3e3}
