"""The per-step table's law columns (fit/lawcolumns.py) against a hand computation at generic
values (issue 25): Wald intervals in the fitted variable, the identification rule at both
edges of its span, Nagata's c = 0 as an answer, the two-state note's number. Each test names
the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.fit.lawcolumns import add_law_columns
from dryfriction.fit.models import ParamSpec

Z = 1.96


def _row(law: str, specs: list[ParamSpec], theta: list[float], se: list[float]) -> dict:
    row: dict = {"a_minus_b": -0.0031, "flags": ""}
    add_law_columns(row, law, {"aic": -812.3, "bic": -799.1}, specs, np.array(theta),
                    np.diag(np.square(se)), False, Z)
    return row


def test_two_state_law_columns_by_hand() -> None:
    # mistakes: a log parameter's interval taken as value +- z se (not exp of the fitted
    # variable's); the span rule for state0 as a factor 10 instead of ln 10; the note's
    # steady-state dependence a - b + b2
    specs = [ParamSpec("mu0", "", False, 0.0, 2.0), ParamSpec("b2", "", True, 1e-6, 1.0),
             ParamSpec("dc2", "m", True, 1e-12, 1.0), ParamSpec("state0", "", False, -20, 20)]
    se_b2 = math.log(9.5) / (2 * Z)  # an interval of a factor 9.5: identified
    se_dc2 = math.log(10.5) / (2 * Z)  # of 10.5: not
    theta = [0.6, math.log(0.0041), math.log(3.3e-5), 0.37]
    row = _row("ageing2", specs, theta, [1e-3, se_b2, se_dc2, 1.1 / Z])
    assert row["state_law"] == "ageing2" and row["initial"] == "free"
    assert (row["aic"], row["bic"]) == (-812.3, -799.1)
    assert row["b2"] == pytest.approx(0.0041, rel=1e-12)
    assert row["b2_lo"] == pytest.approx(0.0041 / math.sqrt(9.5), rel=1e-12)
    assert row["b2_hi"] == pytest.approx(0.0041 * math.sqrt(9.5), rel=1e-12)
    assert math.isnan(row["dc2"]) and math.isnan(row["dc2_hi"])
    assert "not_identified:dc2" in row["flags"] and "not_identified:b2" not in row["flags"]
    assert (row["state0"], row["state0_lo"], row["state0_hi"]) == pytest.approx(
        (0.37, 0.37 - 1.1, 0.37 + 1.1), rel=1e-12)  # width 2.2 < ln 10
    assert math.isnan(row["c"])
    assert any("dc2 = 3.3e-05 m is not identified" in n and "factor 10" in n
               for n in row["notes"])
    assert any("a - b - b2 = -0.0072" in n for n in row["notes"])
    wide = _row("ageing2", specs, theta, [1e-3, se_b2, se_dc2, 1.2 / Z])  # width 2.4 > ln 10
    assert math.isnan(wide["state0"]) and "not_identified:state0" in wide["flags"]


def test_nagata_c_at_zero_is_an_answer_at_its_top_bound_not() -> None:
    # mistakes: c = 0 (the ageing law, a result) flagged as on its search bound; c at its upper
    # search bound reported
    specs = [ParamSpec("c", "", False, 0.0, 50.0)]
    zero = _row("nagata", specs, [0.0], [0.7])
    assert zero["c"] == 0.0 and zero["c_hi"] == pytest.approx(0.7 * Z, rel=1e-12)
    assert zero["initial"] == "steady" and zero["flags"] == ""
    top = _row("nagata", specs, [50.0 - 1e-4], [0.7])
    assert math.isnan(top["c"]) and "not_identified:c" in top["flags"]
    assert any("search bound" in n for n in top["notes"])
    b2_low = _row("ageing2", [ParamSpec("b2", "", True, 1e-6, 1.0)], [math.log(1e-6) + 1e-4],
                  [0.1])
    assert math.isnan(b2_low["b2"]) and "not_identified:b2" in b2_low["flags"]
