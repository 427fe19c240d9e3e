"""The record fit's terminal tables (cli.records) built directly (issue 25): each column's
head with its unit and each cell by its definition; the normal stress shown in MPa, a normal
force in kN (the branch a record in newtons takes); a value not reported as a dash; the 95 %
intervals low then high; the last line's count of flagged steps in each of its three cases."""

from __future__ import annotations

import math
from types import SimpleNamespace
from typing import Any

from dryfriction.cli.records import _intervals_table, _steps_table, flagged_line


def _row(i: int, flags: str, unit: str, normal: float) -> dict[str, Any]:
    r: dict[str, Any] = {
        "index": i, "kind": "step", "v_before": 1.3e-6, "v_after": 4.1e-6, "normal": normal,
        "normal_unit": unit, "a": 0.01234567, "b": math.nan, "a_minus_b": -0.00321,
        "dc": 2.7e-5, "stiffness": 3.3e4, "trend": -1.7, "rms": 2.1e-4, "noise": 1.9e-4,
        "peak_residual": 3e-5, "flags": flags, "state_law": "ageing", "mu0": 0.6123456}
    for c, lo, hi in (("a", 0.011, 0.014), ("b", math.nan, math.nan),
                      ("a_minus_b", -0.005, -0.001), ("dc", 1.9e-5, 3.6e-5),
                      ("b_over_dc", 400.0, 700.0), ("stiffness", 2.9e4, 3.8e4)):
        r[c + "_lo"], r[c + "_hi"] = lo, hi
    return r


def _fit(*free: str) -> Any:
    names = ("a", "b", "dc", "stiffness", "trend")
    return SimpleNamespace(parameters=[SimpleNamespace(name=n, fixed=n not in free)
                                       for n in names])


def _cells(table: Any) -> dict[str, list[str]]:
    return {str(c.header): [str(x) for x in c._cells] for c in table.columns}


def test_the_steps_table_in_mpa_and_in_kn() -> None:
    rows = [_row(0, "", "Pa", 17.3e6), _row(1, "misfit;at_bound:dc", "Pa", 22.9e6)]
    cells = _cells(_steps_table(rows, "t", [_fit("a", "b", "dc", "stiffness", "trend"),
                                            _fit("a", "b", "dc")]))
    assert cells["normal[MPa]"] == ["17.3", "22.9"]
    assert cells["a[1]"] == ["0.01235", "0.01235"] and cells["b[1]"] == ["—", "—"]
    assert cells["v_after[m/s]"] == ["4.1e-06", "4.1e-06"] and cells["dc[m]"][0] == "2.7e-05"
    assert cells["mu0[1]"][0] == "0.6123" and cells["stiffness[1/m]"][0] == "3.3e+04"
    assert cells["flags"] == ["—", "misfit;at_bound:dc"]
    assert cells["fitted"] == ["k, trend", "—"]  # the machine's parameters left free
    kn = _cells(_steps_table([_row(0, "", "N", 4.7e3)], "t", [_fit("stiffness")]))
    assert kn["normal[kN]"] == ["4.7"] and kn["fitted"] == ["k"]


def test_the_intervals_low_then_high() -> None:
    cells = _cells(_intervals_table([_row(3, "", "Pa", 1e7)]))
    assert cells["index"] == ["3"]
    assert cells["a[1]"] == ["[0.011, 0.014]"] and cells["b[1]"] == ["[—, —]"]
    assert cells["a_minus_b[1]"] == ["[-0.005, -0.001]"]
    assert cells["b_over_dc[1/m]"] == ["[400, 700]"]
    assert cells["stiffness[1/m]"] == ["[2.9e+04, 3.8e+04]"]


def test_the_flagged_line_counts_steps_not_flags() -> None:
    assert flagged_line([_row(0, "", "Pa", 1.0)] * 3) == "no step flagged (3 step(s))"
    some = [_row(0, "misfit;at_bound:dc;k_inconsistent", "Pa", 1.0), _row(1, "", "Pa", 1.0),
            _row(2, "", "Pa", 1.0)]
    assert flagged_line(some) == "1 of 3 steps flagged: read their flags and notes"
    every = [_row(0, "misfit", "Pa", 1.0), _row(1, "bound;misfit", "Pa", 1.0)]
    assert flagged_line(every).startswith("every step is flagged (2 of 2)")


def test_drive_comparison_prints_no_raw_value_the_measured_drive_does_not_identify() -> None:
    """userfixA: a noise record printed "measured drive k = — /m ...; program drive k = 150.1
    /m, a = 0.000274 (rms 0.003037 against 10)": the program refit's raw values beside
    values the data do not identify, from a refit that had failed. The program's k and a are
    printed only beside an identified measured one, and a failed refit gives no values.
    Mistakes: the raw values printed whatever the measured ones (the old line), a failed
    refit's values printed."""
    from dryfriction.cli.records import drive_comparison_lines

    ok = {"index": 0, "measured": {"stiffness": 2009.0, "a": 0.0213, "rms": 1.66e-3},
          "program": {"stiffness": 2066.0, "a": 0.02123, "rms": 1.67e-3, "success": True}}
    lost = {"index": 1, "measured": {"stiffness": math.nan, "a": math.nan, "rms": 3.0e-3},
            "program": {"stiffness": 150.1, "a": 2.74e-4, "rms": 3.1e-3, "success": True}}
    failed = {"index": 2, "measured": {"stiffness": 450.0, "a": math.nan, "rms": 3.0e-3},
              "program": {"stiffness": 150.1, "a": 2.74e-4, "rms": 10.0, "success": False}}
    skipped = {"index": 3, "measured": {"stiffness": 1.0, "a": 0.01, "rms": 1e-3},
               "program": {"not_run": "why"}}
    one, two, three = drive_comparison_lines([ok, skipped, lost, failed])
    assert one == ("step 0: measured drive k = 2009 /m, a = 0.0213; program drive k = 2066 /m,"
                   " a = 0.02123 (rms 0.00166 against 0.00167)")
    assert "150.1" not in two and "0.000274" not in two
    assert "program drive k = — /m, a = —" in two
    assert "150.1" not in three and "did not succeed (rms 10)" in three
    assert "measured drive k = 450 /m" in three


def test_a_stiffness_held_at_a_given_value_reads_fixed() -> None:
    """userfixA: with --stiffness K the step's k is not fitted and has no interval; the
    intervals table said "[—, —]" under "not given by the data". It reads "fixed"; a free k
    the data do not bound keeps the dash, and the record's one machine (held, with its own
    interval) keeps that interval. Mistake: "fixed" written for every k without an interval
    (a free one the data do not fix then looks given)."""
    held = _row(0, "", "Pa", 1e7)
    held["stiffness_lo"] = held["stiffness_hi"] = math.nan
    lost = _row(1, "not_identified:stiffness", "Pa", 1e7)
    lost["stiffness_lo"] = lost["stiffness_hi"] = math.nan
    record = _row(2, "", "Pa", 1e7)  # the record's one machine: held, its interval given
    cells = _cells(_intervals_table([held, lost, record],
                                    [_fit("a", "b", "dc", "trend"),
                                     _fit("a", "b", "dc", "stiffness", "trend"),
                                     _fit("a", "b", "dc", "trend")]))
    assert cells["stiffness[1/m]"] == ["fixed", "[—, —]", "[2.9e+04, 3.8e+04]"]
