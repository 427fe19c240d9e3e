"""The files an interface run writes from its fields (app/interface_outputs.py), on a
synthetic side-loaded run whose events are known (tests/fronts_synth.py)."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from dryfriction.app.interface_outputs import interface_outputs
from dryfriction.ensemble.interface_result import INTERFACE_UNITS, InterfaceResult
from dryfriction.io.units import undeclared
from fronts_synth import Pulse, fields, grid
from output_units import check_folder


def _result(pulses, noise=False):
    t, x = grid(n_x=16, dx=1.0, x0=0.5, t_end=20.0, dt=0.02)
    if noise:
        v = np.random.default_rng(5).uniform(0.0, 0.05, (t.size, x.size))
        s = np.cumsum(v, axis=0) * 0.02
    else:
        v, s = fields(t, x, pulses, v_bg=0.001)
    params = {"model": {"mu_el": 0.5}, "interface": {"coupling": 4.0, "mass": 1.0},
              "drive": {"loading": "side", "segments": [{"velocity": 0.01, "duration": 20.0}]}}
    return InterfaceResult(t=t, x=x, slip=s, slip_rate=v, stress=np.ones_like(v),
                           load=1.0 + 0.2 * t, load_point=0.01 * t, params=params,
                           units=dict(INTERFACE_UNITS))


def _csv(path):
    with open(path) as fh:
        rows = list(csv.reader(fh))
    return rows[0], rows[1:]


def test_side_loaded_run_writes_catalogue_fronts_precursors_and_figures(tmp_path):
    # mistakes: a file left out; a header without its unit; the ratio not over N F_el/mu_el
    pulses = [Pulse(0, 0, 3, 1.0, 2.0), Pulse(0, 0, 7, 5.0, 2.0), Pulse(0, 0, 15, 11.0, 2.0)]
    files, notes, summary = interface_outputs(_result(pulses), tmp_path, threshold=0.5)
    assert set(files) == {"fields.nc", "events.csv", "fronts.csv", "precursors.csv",
                          "spacetime.png", "front_speed.png", "magnitude_frequency.png",
                          "precursors.png"}
    assert all((tmp_path / f).stat().st_size > 0 for f in files) and notes == []
    head, rows = _csv(tmp_path / "events.csv")
    assert len(rows) == 3 and "extent[element]" in head and "moment[a0*element]" in head
    assert [r[head.index("spanning[1]")] for r in rows] == ["0", "0", "1"]
    head, rows = _csv(tmp_path / "precursors.csv")
    assert head == ["event[1]", "load_ratio[1]", "length[element]", "t_arrest[t0]"]
    t_arrest = np.array([float(r[3]) for r in rows])
    assert [float(r[2]) for r in rows] == [4.0, 8.0]
    # normal load 16 F_el / mu_el = 32 F_el: ratio = (1 + 0.2 t) / 32
    assert [float(r[1]) for r in rows] == pytest.approx((1.0 + 0.2 * t_arrest) / 32.0)
    head, rows = _csv(tmp_path / "fronts.csv")
    assert head[:4] == ["event[1]", "direction[1]", "x[element]", "t_arrival[t0]"]
    assert len(rows) == 4 + 8 + 16 + 3  # each event's two fronts share the nucleation element
    assert summary["events"] == 3 and summary["spanning"] == 1
    assert summary["precursors"]["n"] == 2 and summary["precursors"]["grow_with_load"] == (
        "undetermined")
    assert summary["fronts"] == {"slow": 0, "fast": 3, "undetermined": 0}  # c_s = 2 element/t0
    json.dumps(summary)
    # every CSV column and every number of the summary carries its unit (io/units.py)
    assert check_folder(tmp_path) == [] and undeclared(summary) == []
    assert summary["units"]["threshold"] == "a0/t0"


def test_quiet_run_says_no_event_and_default_threshold(tmp_path):
    # the default threshold is 10 x the loading velocity (0.1 a0/t0), above this creep
    files, notes, summary = interface_outputs(_result([], noise=True), tmp_path, figure=False,
                                              fields=False)
    assert files == ["events.csv", "fronts.csv", "precursors.csv"]
    assert summary["events"] == 0 and summary["threshold"] == pytest.approx(0.1)
    assert any(n.startswith("no slip event") for n in notes)
    head, rows = _csv(tmp_path / "events.csv")
    assert rows == [] and "t_start[t0]" in head


def test_bad_threshold_before_any_file(tmp_path):
    with pytest.raises(ValueError, match=r"threshold = -1.0 is out of range.*\[a0/t0\]"):
        interface_outputs(_result([]), tmp_path, threshold=-1.0)
    assert list(tmp_path.iterdir()) == []
