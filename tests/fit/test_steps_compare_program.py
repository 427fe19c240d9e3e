"""``compare_with_program`` (fit/steps.py), each field of ``fit.json``'s ``drive.comparison``
from its definition, on a scripted refit (what is tested is the bookkeeping, not the fit):
the refit on the plain program from the free values only, the measured side from the row, a
fixed stiffness reported as the model's, the refit's rms and verdict, and a refusal kept as
``not_run`` without stopping the other steps."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from dryfriction.fit import steps
from dryfriction.fit.steps import COMPARED, compare_with_program
from dryfriction.records.data import SeriesData


def _piece(src: str) -> SeriesData:
    t = 4.0 + np.linspace(0.0, 10.0, 21)
    return SeriesData(t, np.where(t < 8.0, 1e-6, 3e-6), 0.6 + 0.0 * t, source=src)


def _p(name, value, fixed=False):
    return SimpleNamespace(name=name, value=value, fixed=fixed)


def test_each_field_by_its_definition(monkeypatch) -> None:
    seen = []

    def fake_fit(data, model, **kw):
        seen.append((data, model, kw))
        if model.name == "bad":
            raise ValueError("the program cannot be run")
        return SimpleNamespace(parameters=[_p("a", 0.0123), _p("b", 0.0171), _p("dc", 4.2e-5),
                                           _p("mu0", 0.61)],
                               goodness={"rms_residual": 0.00089}, success=False)

    monkeypatch.setattr(steps, "fit", fake_fit)
    model = SimpleNamespace(name="rsf", stiffness=3.7e4)  # a fixed machine
    good = SimpleNamespace(parameters=[_p("a", 0.011), _p("b", 0.016), _p("dc", 4e-5),
                                       _p("mu0", 0.6), _p("stiffness", 3.7e4, fixed=True)],
                           fitted_model=model)
    bad = SimpleNamespace(parameters=[_p("a", 0.02)], fitted_model=SimpleNamespace(name="bad"))
    rows = [{"index": 3, "a": 0.011, "b": 0.016, "dc": 4e-5, "stiffness": 3.7e4, "rms": 0.0007},
            {"index": 5, "a": math.nan, "b": 0.02, "dc": 1e-5, "stiffness": 2e4, "rms": 0.002}]
    pieces = [_piece("one.csv"), _piece("two.csv")]
    out = compare_with_program(pieces, [good, bad], rows)
    assert COMPARED == ("a", "b", "dc", "stiffness")
    data, m, kw = seen[0]
    # the refit: on the program only (a plain SeriesData, same arrays), from the free values
    assert type(data) is SeriesData and data.source == "one.csv"
    np.testing.assert_array_equal(data.mu, pieces[0].mu)
    assert m is model
    assert kw == {"start": {"a": 0.011, "b": 0.016, "dc": 4e-5, "mu0": 0.6},
                  "multistart": False, "profile": False}
    assert out[0] == {
        "index": 3,
        "measured": {"a": 0.011, "b": 0.016, "dc": 4e-5, "stiffness": 3.7e4, "rms": 0.0007},
        "program": {"a": 0.0123, "b": 0.0171, "dc": 4.2e-5, "stiffness": 3.7e4,
                    "rms": 0.00089, "success": False}}
    assert out[1]["index"] == 5 and out[1]["program"] == {"not_run": "the program cannot be run"}
    assert math.isnan(out[1]["measured"]["a"])  # NaN where not identified, as the row says
