"""``fit.elastic.machine_stiffness_record``: the steps' stiffnesses and the record's elastic
loadings pooled, written here from the definition (inverse-variance mean of ``ln k``, standard
error ``ln(hi/lo)/(2 z)``), with the loadings' indices kept apart from the steps' (issue 25,
strengthen6B). The loadings are given by hand (``loading_segments`` replaced)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.fit import elastic

Z = 1.96


def _row(k: float, se: float) -> dict:
    return {"stiffness": k, "stiffness_lo": k * math.exp(-Z * se),
            "stiffness_hi": k * math.exp(Z * se), "flags": ""}


def _pooled(ks: list[float], ses: list[float]) -> tuple[float, float, float]:
    w = 1.0 / np.square(ses)
    m = float(w @ np.log(ks) / w.sum())
    s = 1.0 / math.sqrt(w.sum())
    return math.exp(m), math.exp(m - Z * s), math.exp(m + Z * s)


def test_steps_alone_and_with_loadings(monkeypatch: pytest.MonkeyPatch) -> None:
    rows = [_row(2.1e6, 0.05), _row(2.4e6, 0.08), _row(9.0e6, 0.04)]  # the last one disagrees
    rec = elastic.machine_stiffness_record([dict(r) for r in rows], None)
    assert rec is not None and rec["steps"] == [0, 1] and rec["loadings"] == []
    assert (rec["value"], rec["lo"], rec["hi"]) == pytest.approx(
        _pooled([2.1e6, 2.4e6], [0.05, 0.08]), rel=1e-10)
    assert "elastic loadings" not in rec["method"] and rec["unit"] == "1/m"

    loads = [_row(2.2e6, 0.03), _row(0.5e6, 0.03)]  # the second loading disagrees too
    monkeypatch.setattr(elastic, "loading_segments", lambda data, z=Z: [dict(d) for d in loads])
    steps = [dict(r) for r in rows]
    rec = elastic.machine_stiffness_record(steps, object())  # type: ignore[arg-type]
    assert rec is not None
    assert rec["steps"] == [0, 1]                  # step indices only, not the loadings'
    assert [ld["used"] for ld in rec["loadings"]] == [True, False]
    assert [ld["k_inconsistent"] for ld in rec["loadings"]] == [False, True]
    assert "k_inconsistent" in steps[2]["flags"] and "k_inconsistent" not in steps[0]["flags"]
    assert (rec["value"], rec["lo"], rec["hi"]) == pytest.approx(
        _pooled([2.1e6, 2.4e6, 2.2e6], [0.05, 0.08, 0.03]), rel=1e-10)
    assert rec["method"].endswith("with the slopes of the record's elastic loadings (fit.elastic)")


def test_fewer_than_two_identified_gives_none() -> None:
    one = [_row(2.1e6, 0.05), {"stiffness": math.nan, "flags": ""}]
    assert elastic.machine_stiffness_record(one, None) is None
