"""app.rsf called directly (issue 25): each case's load program and start by definition (the
step's default second duration, the slide-hold-slide's reload time, stick-slip's start at
1.01 v1), the defaults of the law at an absolute level, series.csv by column, and each range
check on both sides of its edge (a hold accepted, a velocity under V_MIN refused; sliding back
only on a rigid machine with the regularised law; rtol in the solver's [1e-13, 0.01], one
range whatever the value)."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from dryfriction import app
from dryfriction.app.ratestate import reload_time


def test_a_step_down_with_the_default_law(tmp_path: Path) -> None:
    # the defaults: a = 0.005, b = 0.01, Dc = 10 um, mu0 = 0.6 at v0 = 1 um/s, k = 1e3 /m
    v1, v2, t1 = 3.1e-6, 2.3e-6, 4.0
    done = app.rsf(v1=v1, v2=v2, t1=t1, out=tmp_path / "o", figure=False)
    r = done.result
    assert done.summary["duration"] == pytest.approx(t1 + 30.0, rel=1e-12)  # t2: 30 s
    assert r.v[0] == pytest.approx(v1, rel=1e-9)  # v_init: v1
    assert r.mu[0] == pytest.approx(0.6 + (0.005 - 0.01) * math.log(v1 / 1e-6), abs=1e-9)
    assert r.theta[0] == pytest.approx(1e-5 / v1, rel=1e-9)
    assert r.mu[-1] == pytest.approx(0.6 + (0.005 - 0.01) * math.log(v2 / 1e-6), abs=1e-4)
    with (tmp_path / "o" / "series.csv").open() as fh:
        rows = list(csv.reader(fh))
    head = rows[0]
    assert head[:4] == ["t[s]", "x[m]", "v[m/s]", "mu[1]"]
    data = np.array(rows[1:], float)
    col = {h.split("[")[0]: data[:, i] for i, h in enumerate(head)}
    late = col["t"] > t1 + 1e-9
    assert set(col["v_load"][col["t"] < t1 - 1e-9]) == {v1} and set(col["v_load"][late]) == {v2}
    np.testing.assert_allclose(col["mu"], r.mu, rtol=1e-15)
    assert done.files == ["series.csv", "summary.json"]


def test_the_shs_reload_and_the_stick_slip_start() -> None:
    a, b, dc, k, v1, hold = 0.0071, 0.0083, 7.3e-6, 200.0, 3.1e-6, 23.0
    t2 = reload_time(a, b, dc, v1, hold, k)
    assert t2 > 60.0  # a soft spring: longer than the 30 s floor
    shs = app.rsf(case="shs", a=a, b=b, dc=dc, stiffness=k, v1=v1, t1=4.0, hold=hold)
    assert shs.summary["duration"] == pytest.approx(4.0 + hold + t2, rel=1e-12)
    lv = shs.result.load_velocity
    assert lv[0] == v1 and lv[-1] == v1 and np.any(lv == 0.0)
    ss = app.rsf(case="stick-slip", a=a, b=b, dc=dc, stiffness=150.0, v1=v1, t1=6.0)
    assert ss.result.v[0] == pytest.approx(1.01 * v1, rel=1e-9)
    assert ss.summary["duration"] == pytest.approx(6.0, rel=1e-12)


def test_velocity_and_tolerance_edges() -> None:
    # a hold as the second segment is accepted; a speed under V_MIN is not
    assert app.rsf(v2=0.0, t1=2.0, t2=3.0).result.load_velocity[-1] == 0.0
    with pytest.raises(ValueError, match=r"^--v2 5e-31 is out of range: allowed 0 \(a hold\)"):
        app.rsf(v2=5e-31)
    # sliding back: refused on a spring, accepted on a rigid machine with the asinh law
    for rigid in ({}, {"stiffness": math.inf}, {"regularized": True}):  # one of the two only
        with pytest.raises(ValueError, match=r"^--v2 -1.3e-06 is out of range: allowed 0 to "
                                             r".*\(sliding back needs --stiffness inf "
                                             r"--regularized\)$"):
            app.rsf(v2=-1.3e-6, **rigid)  # type: ignore[arg-type]
    back = app.rsf(v2=-1.3e-6, t1=2.0, t2=3.0, stiffness=math.inf, regularized=True)
    assert back.result.load_velocity[-1] == -1.3e-6
    assert app.rsf(rtol=0.01, t1=2.0, t2=3.0).summary["rtol"] == 0.01
    for bad in (0.0, 0.99e-13, 0.01 * (1 + 1e-9), 0.05):  # 0.05 passed a first check once
        with pytest.raises(ValueError, match=r"^--rtol = \S+ is out of range: allowed finite "
                                             r"and >= 1e-13 and <= 0.01$"):
            app.rsf(rtol=bad)
    for kw, flag in (({"v_init": 0.0}, "--v-init"),
                     ({"mass": -1e-12}, "--mass"), ({"damping": -1e-12}, "--damping")):
        with pytest.raises(ValueError, match=f"^{flag} = "):
            app.rsf(**kw)  # type: ignore[arg-type]
