"""app.simulate called directly: timeseries.csv column by column against the protocol's own
definitions (the load program integrated by hand, the steady state of the law at an absolute
level, the velocity as the slope of the position) and summary.json's numbers recomputed from
that CSV (issue 25: every column a user keeps, checked against its definition)."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

from dryfriction import app

ROOT = Path(__file__).resolve().parents[2]

RSF_STEP = """
[model]
law = "rsf"
state_law = "ageing"
a = 0.0061
b = 0.0093
dc = 2.3e-6
mu0 = 0.57
v0 = 1.7e-6
[drive]
kind = "spring"
stiffness = 4e3
segments = [{velocity = 2.9e-6, duration = 3.0}, {velocity = 0.8e-6, slip = 4e-5}]
[output]
every = 0.1
"""


def _columns(path: Path) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    with path.open() as fh:
        rows = list(csv.reader(fh))
    names, units = [], {}
    for cell in rows[0]:
        name, unit = cell[:-1].split("[")
        names.append(name)
        units[name] = unit
    data = np.array(rows[1:], float)
    return {n: data[:, i] for i, n in enumerate(names)}, units


def test_rsf_timeseries_and_summary_by_their_definitions(tmp_path: Path) -> None:
    proto = tmp_path / "down.toml"
    proto.write_text(RSF_STEP)
    done = app.simulate(proto, tmp_path / "out", figure=False)
    assert done.files == ["timeseries.csv", "summary.json"] and done.units == "SI"
    c, units = _columns(tmp_path / "out" / "timeseries.csv")
    assert units == {"t": "s", "x": "m", "v": "m/s", "mu": "1", "theta": "s", "stress": "1",
                     "x_load": "m", "v_load": "m/s"}
    t = c["t"]
    np.testing.assert_allclose(np.diff(t)[:25], 0.1, rtol=1e-9)  # every = 0.1 s, from 0
    assert t[0] == 0.0 and t[-1] == pytest.approx(3.0 + 4e-5 / 0.8e-6, rel=1e-9)
    # the load program, integrated by hand: 2.9 um/s for 3 s, then 0.8 um/s (a step down)
    v_load = np.where(t <= 3.0 + 1e-9, 2.9e-6, 0.8e-6)
    x_load = np.where(t <= 3.0, 2.9e-6 * t, 2.9e-6 * 3.0 + 0.8e-6 * (t - 3.0))
    inner = np.abs(t - 3.0) > 1e-6
    np.testing.assert_allclose(c["v_load"][inner], v_load[inner], rtol=1e-12)
    np.testing.assert_allclose(c["x_load"], x_load, rtol=1e-9, atol=1e-15)
    # steady at the start, at its absolute level: mu = mu0 + (a - b) ln(V/V0), theta = Dc/V
    a, b, dc, mu0, v0 = 0.0061, 0.0093, 2.3e-6, 0.57, 1.7e-6
    assert c["mu"][0] == pytest.approx(mu0 + (a - b) * math.log(2.9e-6 / v0), abs=1e-9)
    assert c["theta"][0] == pytest.approx(dc / 2.9e-6, rel=1e-6)
    assert c["v"][0] == pytest.approx(2.9e-6, rel=1e-6)
    # and at the end, relaxed after the step down (25 dc of slip at 0.8 um/s)
    assert c["mu"][-1] == pytest.approx(mu0 + (a - b) * math.log(0.8e-6 / v0), abs=2e-5)
    assert c["mu"][-1] > c["mu"][0]  # velocity weakening: slower is stronger
    # the velocity is the slope of the position (central differences, a smooth run)
    mid = (c["x"][2:] - c["x"][:-2]) / (t[2:] - t[:-2])
    np.testing.assert_allclose(mid[40:], c["v"][1:-1][40:], rtol=2e-2)
    # the spring's stress: mu at the start plus k times its stretch (no inertia: = mu)
    stretch = (c["x_load"] - c["x"]) - (c["x_load"][0] - c["x"][0])
    np.testing.assert_allclose(c["stress"], c["mu"][0] + 4e3 * stretch, atol=1e-9)
    np.testing.assert_allclose(c["stress"], c["mu"], atol=1e-9)
    # summary.json from the CSV, key by key
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert s["law"] == "rsf" and s["partial"] is False and s["samples"] == t.size
    assert s["duration"] == pytest.approx(t[-1] - t[0], rel=1e-12)
    assert s["slip"] == pytest.approx(c["x"][-1] - c["x"][0], rel=1e-9)
    assert s["path_length"] == pytest.approx(float(np.sum(np.abs(np.diff(c["x"])))), rel=1e-9)
    k = int(np.argmax(c["mu"]))
    assert (s["peak_mu"], s["peak_t"]) == (pytest.approx(c["mu"][k]), pytest.approx(t[k]))
    assert s["final_mu"] == pytest.approx(c["mu"][-1], rel=1e-12)
    area = float(np.sum(0.5 * (c["mu"][1:] + c["mu"][:-1]) * np.diff(t)))
    assert s["mean_mu"] == pytest.approx(area / (t[-1] - t[0]), rel=1e-9)
    assert s["v_max"] == pytest.approx(float(np.max(c["v"])), rel=1e-12)
    assert s["protocol"] == str(proto) and s["wall_s"] >= 0.0
    assert s["units"]["duration"] == "s" and s["units"]["slip"] == "m"


def test_a_trap_run_reports_progress_in_percent_and_its_reduced_columns(tmp_path: Path) -> None:
    proto = tmp_path / "steps.toml"
    proto.write_text("""
[model]
eps = 0.04
[ensemble]
traps_per_a0 = 30
initial = "steady"
initial_velocity = 0.13
[drive]
kind = "velocity"
segments = [{velocity = 0.13, slip = 0.3}, {velocity = 1.7, slip = 0.6}]
[output]
every_slip = 0.05
""")
    said: list[float] = []
    done = app.simulate(proto, tmp_path / "out", figure=False, progress=said.append)
    assert done.units == "reduced" and not done.partial
    assert said and said[-1] == pytest.approx(100.0) and all(0.0 <= p <= 100.0 for p in said)
    c, units = _columns(tmp_path / "out" / "timeseries.csv")
    assert (units["t"], units["x"], units["v"], units["mean_age"]) == ("t0", "a0", "a0/t0", "t0")
    # a kinematic drive: the slider is the load point; 0.3 a0 at 0.13 then 0.6 at 1.7
    assert c["t"][-1] == pytest.approx(0.3 / 0.13 + 0.6 / 1.7, rel=1e-9)
    assert c["x"][-1] - c["x"][0] == pytest.approx(0.9, rel=1e-9)
    assert set(np.round(c["v"][1:], 12)) == {0.13, 1.7}
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert s["slip"] == pytest.approx(0.9, rel=1e-9) and s["units"]["duration"] == "t0"
