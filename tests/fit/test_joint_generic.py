"""The joint fit of a record's steps (fit/joint.py) at generic points: each window's prediction
against the closed form of the ageing law on a kinematic machine (its own reference velocity,
``mu0`` and trend; an up-step and a down-step; times that do not start at 0), the parameter
table, and ``fit_joint``'s start (the geometric median of the per-step fits, per window its
own ``mu0`` and trend) and the fit it asks for."""

from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest

from dryfriction.fit import joint
from dryfriction.fit.joint import JointStepsModel, fit_joint
from dryfriction.fit.models import RSFModel, rsf_series
from dryfriction.records.data import SeriesData


def _window(t0: float, v1: float, v2: float, ts: float, source: str) -> SeriesData:
    t = t0 + np.linspace(0.0, 20.0, 201)
    return SeriesData(t, np.where(t < ts, v1, v2), np.zeros_like(t), source=source)


UP = _window(5.0, 3e-6, 1.2e-5, 10.0, "up.csv")  # up-step at t = 10 s
DOWN = _window(2.0, 4e-5, 7e-6, 7.0, "down.csv")  # down-step at t = 7 s
VALUES = {"a": 0.0083, "b": 0.0117, "dc": 3.1e-5, "mu0_0": 0.612, "trend_0": 45.0,
          "mu0_1": 0.587, "trend_1": -20.0}


def _closed_form(d: SeriesData, ts: float, mu0: float, trend: float) -> np.ndarray:
    """Ageing law (Dieterich), kinematic: after a step V1 -> V2 at ``ts``,
    ``theta = Dc/V2 + (Dc/V1 - Dc/V2) exp(-V2 (t - ts)/Dc)``, ``mu = mu0 + a ln(V/V1)
    + b ln(V1 theta/Dc)`` (reference velocity: the window's first, V1), plus the trend times
    the load point's travel from the first sample."""
    a, b, dc = VALUES["a"], VALUES["b"], VALUES["dc"]
    v1, v2 = float(d.v_load[0]), float(d.v_load[-1])
    t = d.t
    after = t >= ts
    theta = np.where(after, dc / v2 + (dc / v1 - dc / v2) * np.exp(-v2 * (t - ts) / dc),
                     dc / v1)
    v = np.where(after, v2, v1)
    x_lp = np.where(after, v1 * (ts - t[0]) + v2 * (t - ts), v1 * (t - t[0]))
    return mu0 + a * np.log(v / v1) + b * np.log(v1 * theta / dc) + trend * x_lp


def test_each_window_predicted_with_its_own_reference_level_and_trend() -> None:
    # mistakes: the first window's v_load[0] as every window's reference velocity (shifts the
    # second by (a - b) ln(V_down/V_up)), mu0_0 or trend_0 for every window, the trend dropped
    jm = JointStepsModel((UP, DOWN), RSFModel(1.0, "ageing", math.inf, trend=True))
    for d, ts, i in ((UP, 10.0, 0), (DOWN, 7.0, 1)):
        got = jm.predict(VALUES, d)
        want = _closed_form(d, ts, VALUES[f"mu0_{i}"], VALUES[f"trend_{i}"])
        keep = np.abs(d.t - ts) > 1e-9  # the step's own sample: either side of the jump
        np.testing.assert_allclose(got[keep], want[keep], rtol=0, atol=2e-7)
        # an absolute level: steady at the window's first velocity, mu = mu0 + trend x_lp
        assert got[0] == pytest.approx(VALUES[f"mu0_{i}"], abs=1e-9)


def test_parameters_shared_then_per_window_with_the_bases_units_and_bounds() -> None:
    base = RSFModel(1.0, "ageing", "fit", trend=True)
    jm = JointStepsModel((UP, DOWN, UP), base)
    specs = jm.parameters(frozenset({"series"}))
    own = {s.name: s for s in base.parameters(frozenset({"series"}))}
    assert [s.name for s in specs] == ["a", "b", "dc", "stiffness", "mu0_0", "trend_0",
                                       "mu0_1", "trend_1", "mu0_2", "trend_2"]
    for s in specs:
        o = own[s.name.split("_")[0]] if s.name not in own else own[s.name]
        assert (s.unit, s.log, s.lo, s.hi) == (o.unit, o.log, o.lo, o.hi), s.name
    assert jm.options()["joint_windows"] == 3
    assert jm.notes(frozenset())[0].startswith("joint fit of 3 windows")
    assert jm.derived({"a": 0.0083, "b": 0.0117}) == {"a_minus_b": (0.0083 - 0.0117, "")}
    # without a trend nor a fitted stiffness: a, b, dc and one mu0 per window
    plain = JointStepsModel((UP, DOWN), RSFModel(1.0, "ageing", math.inf))
    assert [s.name for s in plain.parameters(frozenset({"series"}))] == [
        "a", "b", "dc", "mu0_0", "mu0_1"]


def test_a_window_that_is_not_one_of_the_joint_fits_is_refused_by_name() -> None:
    jm = JointStepsModel((UP, DOWN), RSFModel(1.0, "ageing", math.inf, trend=True))
    twin = dataclasses.replace(UP, source="elsewhere.csv")  # equal arrays, another object
    with pytest.raises(ValueError, match=r"elsewhere\.csv is not one of the joint fit"):
        jm.predict(VALUES, twin)


def _fits(*rows: dict) -> list[SimpleNamespace]:
    return [SimpleNamespace(parameters=[SimpleNamespace(name=k, value=v) for k, v in r.items()])
            for r in rows]


def test_fit_joint_starts_from_the_geometric_median_and_each_windows_own_mu0(monkeypatch
                                                                             ) -> None:
    # two per-step fits: the median of two is their mean; of the logarithms, the geometric
    # mean (mistake: the arithmetic mean 0.013 instead of sqrt(0.008 x 0.018) = 0.012)
    seen = {}

    def fake_fit(pieces, model, **kw):
        seen.update(pieces=pieces, model=model, kw=kw)
        return "result"

    monkeypatch.setattr(joint, "fit", fake_fit)
    fits = _fits({"a": 0.008, "b": 0.0125, "dc": 2e-5, "mu0": 0.61, "trend": 30.0},
                 {"a": 0.018, "b": 0.02, "dc": 8e-5, "mu0": 0.58})
    assert fit_joint([UP, DOWN], fits, "slip", 2.5e4, True) == "result"
    start = seen["kw"]["start"]
    assert start["a"] == pytest.approx(0.012, rel=1e-12)
    assert start["b"] == pytest.approx(math.sqrt(0.0125 * 0.02), rel=1e-12)
    assert start["dc"] == pytest.approx(4e-5, rel=1e-12)
    assert (start["mu0_0"], start["mu0_1"], start["trend_0"], start["trend_1"]) == (
        0.61, 0.58, 30.0, 0.0)
    assert "stiffness" not in start  # a fixed machine is not a parameter
    jm = seen["model"]
    assert jm.windows == (UP, DOWN) and jm.start == start and jm.guesses([]) == [start]
    assert (jm.base.state_law, jm.base.stiffness, jm.base.trend) == ("slip", 2.5e4, True)
    assert seen["kw"] == {"start": start, "multistart": False, "profile": False,
                          "consistency": False}
    # without the trend: no trend keys; three fits: the median is the middle one
    fit_joint([UP, DOWN, UP], _fits({"a": 0.008, "b": 0.01, "dc": 1e-5, "mu0": 0.6},
                                    {"a": 0.02, "b": 0.03, "dc": 9e-5, "mu0": 0.5},
                                    {"a": 0.011, "b": 0.02, "dc": 2e-5, "mu0": 0.4}),
              "ageing", "fit", False)
    start = seen["kw"]["start"]
    assert sorted(start) == ["a", "b", "dc", "mu0_0", "mu0_1", "mu0_2"]
    assert (start["a"], start["b"], start["dc"]) == pytest.approx((0.011, 0.02, 2e-5),
                                                                  rel=1e-12)


def test_fit_joint_slope_stiffness_from_the_first_window(monkeypatch) -> None:
    # one machine: "slope" resolved once, on the first window (mistake: the last one)
    seen = {}
    monkeypatch.setattr(joint, "fit", lambda pieces, model, **kw: seen.update(model=model))
    vals = {"a": 0.01, "b": 0.014, "dc": 2e-5, "mu0": 0.6}
    wins = []
    for k, src in ((1.0e4, "soft.csv"), (4.0e4, "stiff.csv")):
        t = 1.5 + np.linspace(0.0, 3.0, 3001)  # 1 ms: the elastic loading takes tens
        d = SeriesData(t, np.where(t < 2.0, 2e-6, 2e-5), np.zeros_like(t), source=src)
        mu = rsf_series(RSFModel(2e-6, "ageing", k), vals, d)
        wins.append(SeriesData(d.t, d.v_load, mu, source=src))
    fit_joint(wins, _fits({**vals}, {**vals}), "ageing", "slope", False)
    first = RSFModel(1.0, "ageing", "slope").resolve([wins[0]]).stiffness
    last = RSFModel(1.0, "ageing", "slope").resolve([wins[1]]).stiffness
    assert seen["model"].base.stiffness == first
    assert abs(first - last) > 0.2 * first  # the two windows tell them apart
