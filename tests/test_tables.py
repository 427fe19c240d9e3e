"""Tables out of results: ``to_records()`` (NumPy structured arrays, always) and
``to_dataframe()`` (pandas, optional) on the trap-ensemble, rate-and-state, fit and sweep
results."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from dryfriction import simulate as df_simulate
from dryfriction.ensemble.driving import Initial, Output, Track, TrapModel, VelocityDrive, simulate
from dryfriction.fit import fit_static
from dryfriction.program import Segment, VelocityProgram
from dryfriction.records.data import StaticData
from dryfriction.results import dataset_records, records, to_dataframe
from dryfriction.rsf import RSFOutput, SpringSlider
from dryfriction.rsf.law import RateState
from dryfriction.theory.units import PhysicalScales, static_friction_si


def test_records_keep_order_values_and_kinds() -> None:
    rec = records({"b": [3.0, 4.0], "a": np.array([1, 2], np.int32), "ok": [True, False]})
    assert rec.dtype.names == ("b", "a", "ok")
    # a column reordered or shifted by one record would pass a length check, not this one
    assert rec["b"].tolist() == [3.0, 4.0] and rec["a"].tolist() == [1, 2]
    assert rec["a"].dtype == np.int32 and rec["b"].dtype == np.float64
    assert rec["ok"].dtype == bool and rec[1]["ok"] == np.False_
    rows = records([{"n": "eps", "v": 0.1, "e": None}, {"n": "t0", "v": 2.0, "e": 0.5}])
    assert rows["n"].tolist() == ["eps", "t0"] and np.isnan(rows["e"][0]) and rows["e"][1] == 0.5
    with pytest.raises(ValueError, match="differ in length"):
        records({"a": [1.0], "b": [1.0, 2.0]})
    with pytest.raises(ValueError, match="row 1"):
        records([{"a": 1.0}, {"b": 2.0}])


def test_ensemble_and_rsf_results_as_records() -> None:
    r = simulate(TrapModel(eps=0.04),
                 VelocityDrive(VelocityProgram([{"velocity": 1.0, "slip": 0.2}])),
                 Initial("steady", velocity=1.0, track=Track(50.0)), Output(every_slip=0.05))
    rec = r.to_records()
    assert rec.dtype.names == tuple(r.columns())
    for k, col in r.columns().items():
        np.testing.assert_array_equal(rec[k], col)

    p = RateState(0.005, 0.01, 1e-5, 0.6, 1e-6)
    s = df_simulate(p, SpringSlider([Segment(1e-6, 1.0), Segment(1e-5, 1.0)]),
                    output=RSFOutput(every=0.5))
    rec = s.to_records()
    assert rec.dtype.names == ("t", "x", "v", "mu", "theta", "stress", "x_load", "v_load")
    np.testing.assert_array_equal(rec["mu"], s.mu)
    np.testing.assert_array_equal(rec["v_load"], s.load_velocity)
    pytest.importorskip("pandas")
    df = s.to_dataframe()
    assert list(df.columns) == list(rec.dtype.names) and df["theta"].iloc[-1] == s.theta[-1]


def test_fit_result_parameter_table() -> None:
    tw = np.geomspace(0.01, 1e4, 12)
    y = static_friction_si(TrapModel(eps=0.03), tw, PhysicalScales(1e-6, 1.0, 0.4))
    y = y + np.random.default_rng(1).normal(0.0, 2e-3, tw.size)
    r = fit_static(StaticData(tw, y, np.full(tw.size, 2e-3), "s"), "cv", profile=False,
                   multistart=False)
    rec = r.to_records()
    assert rec["name"].tolist() == [p.name for p in r.parameters]
    for row, p in zip(rec, r.parameters, strict=True):
        assert row["value"] == p.value and row["unit"] == p.unit
        if p.interval_95 is None:
            assert np.isnan(row["interval_95_lo"])
        else:  # lo and hi not swapped
            assert (row["interval_95_lo"], row["interval_95_hi"]) == p.interval_95
            assert row["interval_95_lo"] < row["value"] < row["interval_95_hi"]
    pytest.importorskip("pandas")
    df = r.to_dataframe()
    assert df.loc["eps", "value"] == r["eps"].value


def test_sweep_dataset_as_records() -> None:
    xr = pytest.importorskip("xarray")
    k, u = [1.0, 2.0], [0.1, 0.2, 0.3]
    amp = np.arange(6.0).reshape(2, 3)
    ds = xr.Dataset({"amplitude": (("k", "u"), amp), "note": ("k", ["a", "b"])},
                    coords={"k": k, "u": u})
    rec = dataset_records(ds)
    assert rec.dtype.names == ("k", "u", "amplitude")  # 1-D 'note' is not a per-point field
    assert len(rec) == 6
    for row in rec:  # each record carries its own grid point's value (C order, no transposition)
        assert row["amplitude"] == ds["amplitude"].sel(k=row["k"], u=row["u"]).item()


def test_to_dataframe_without_pandas_says_what_to_use(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas now raises ImportError
    with pytest.raises(ImportError, match=r"needs pandas.*to_records\(\)"):
        to_dataframe({"a": [1.0]})
