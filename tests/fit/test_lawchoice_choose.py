"""The per-step choice of the state law (fit/lawchoice.py ``_choose``) on scripted results,
every number of ``law_comparison`` and of the note by its definition: the least AIC among the
laws whose fit succeeded (a lower AIC of a failed fit is not chosen), among the finite ones
when none succeeded; differences from the least of that pool; "within 2" strictly below
:data:`CLOSE`; BIC's preference over the same pool; the record's stiffness kept when every law
gave the same, notes prefixed by their law."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from dryfriction.fit import lawchoice
from dryfriction.fit.lawchoice import CLOSE, _choose
from dryfriction.fit.steps import StepsResult


def _res(rows, ok, stiffness=None, notes=()):
    fits = [SimpleNamespace(success=s, law=r["aic"]) for r, s in zip(rows, ok, strict=True)]
    return StepsResult([dict(r, notes=[], flags="") for r in rows], fits,
                       [f"data{i}" for i in range(len(rows))], None, list(notes), stiffness,
                       {"levels": 1}, {"drive": 1})


def _row(aic, bic, rms=1e-3):
    return {"aic": aic, "bic": bic, "rms": rms}


def test_choice_deltas_and_note_by_definition() -> None:
    # step 0: slip has the least AIC but its fit failed -> ageing; prz is exactly CLOSE above
    # (not "within"); BIC prefers prz. Step 1: no fit succeeded -> the least finite AIC
    # (slip), prz 1.5 above it is within 2. Mistakes: the failed fit chosen, "<=" CLOSE,
    # differences from the least over every law, BIC's preference over every law
    assert CLOSE == 2.0
    results = {
        "ageing": _res([_row(100.0, 110.0), _row(math.nan, math.nan)], [True, False],
                       notes=["n1"]),
        "slip": _res([_row(98.0, 108.5), _row(50.0, 60.0)], [False, False]),
        "prz": _res([_row(102.0, 109.0), _row(51.5, 59.0)], [True, False]),
    }
    out = _choose(results)
    r0, r1 = out.rows
    assert r0["aic"] == 100.0 and out.fits[0] is results["ageing"].fits[0]
    assert out.data[0] == "data0"
    c = r0["law_comparison"]
    assert c["slip"]["delta_aic"] == pytest.approx(-2.0) and c["prz"]["delta_aic"] == 2.0
    assert c["ageing"]["delta_bic"] == 1.0 and c["slip"]["delta_bic"] == -0.5
    assert [c[L]["success"] for L in ("ageing", "slip", "prz")] == [True, False, True]
    assert r0["notes"][-1] == ("state law by AIC: ageing; delta AIC slip -2.0, prz +2.0; BIC "
                               "prefers prz; laws whose fit did not succeed: slip")
    assert r1["aic"] == 50.0 and out.fits[1] is results["slip"].fits[1]
    assert r1["law_comparison"]["prz"]["delta_aic"] == 1.5
    assert r1["law_comparison"]["prz"]["delta_bic"] == 0.0
    assert r1["law_comparison"]["slip"]["delta_bic"] == 1.0
    assert r1["notes"][-1] == (
        "state law by AIC: slip; delta AIC ageing +nan, prz +1.5; BIC prefers prz; prz within 2 "
        "of it: the data do not decide; laws whose fit did not succeed: ageing, slip, prz")
    assert out.notes == ["ageing: n1"]
    assert out.levels == {"levels": 1} and out.drive == {"drive": 1} and out.joint is None


def test_record_stiffness_kept_when_every_law_agrees_else_found_afresh(monkeypatch) -> None:
    k = {"value": 3.1e4, "lo": 2.9e4, "hi": 3.3e4}
    same = {L: _res([_row(10.0 + i, 12.0)], [True], stiffness=dict(k))
            for i, L in enumerate(("ageing", "slip"))}
    assert _choose(same).stiffness == k
    seen = []
    monkeypatch.setattr(lawchoice, "record_stiffness", lambda rows: seen.append(rows) or "new")
    other = {"ageing": _res([_row(10.0, 12.0)], [True], stiffness=dict(k)),
             "slip": _res([_row(11.0, 12.0)], [True], stiffness={**k, "value": 4e4})}
    out = _choose(other)
    assert out.stiffness == "new" and seen == [out.rows]
