"""fronts.csv and summary.json of an interface run against a hand computation (issue 25): an
event whose two fronts run at different speeds, with jittered arrivals (exact arrivals give a
speed interval of zero width, which hides its two ends swapped), a coupling and mass whose
sound speed is not 1 or 2. Each test names the mistake it is for; each was seen failing with
it applied."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.app.interface_outputs import interface_outputs
from dryfriction.ensemble.interface_result import INTERFACE_UNITS, InterfaceResult
from dryfriction.io.units import read_rows
from fronts_synth import Pulse, fields, grid

THR, R, A = 0.5, 0.2, 4.0  # threshold and the pulses' rise and height: crossing R THR/A after


def _run() -> tuple[InterfaceResult, np.ndarray, np.ndarray]:
    t, x = grid(n_x=16, dx=1.0, x0=0.5, t_end=16.0, dt=0.017)
    rng = np.random.default_rng(23)
    # element i of 1..14 reached at T_i: from element 6 at t = 2, leftwards at 1.3, rightwards
    # at 3.7 element/t0, each arrival jittered by up to 0.04 t0; one pulse per element
    arrive = np.array([2.0 + abs(x[i] - x[6]) / (3.7 if i >= 6 else 1.3)
                       + (0.0 if i == 6 else rng.uniform(-0.04, 0.04)) for i in range(16)])
    pulses = [Pulse(i, i, i, float(arrive[i]), 1.0, A=A, r=R, h=1.0) for i in range(1, 15)]
    v, s = fields(t, x, pulses)
    params = {"model": {"mu_el": 0.45}, "interface": {"coupling": 3.7, "mass": 0.6},
              "drive": {"loading": "side", "segments": [{"velocity": 0.013, "duration": 16}]}}
    res = InterfaceResult(t=t, x=x, slip=s, slip_rate=v, stress=np.ones_like(v),
                          load=1.0 + 0.2 * t, load_point=0.013 * t, params=params,
                          units=dict(INTERFACE_UNITS))
    return res, x, arrive


def test_fronts_csv_rows_by_hand(tmp_path) -> None:
    # mistakes: the position and arrival columns swapped; a speed interval's two ends swapped;
    # the left front's rows labelled +1
    res, x, arrive = _run()
    files, _, summary = interface_outputs(res, tmp_path, threshold=THR, figure=False,
                                          fields=False)
    rows = read_rows(tmp_path / "fronts.csv")
    assert summary["events"] == 1 and len(rows) == 6 + 9
    for r in rows:
        i = int(round(float(r["x"]) - 0.5))
        assert float(r["x"]) == x[i]
        assert float(r["t_arrival"]) == pytest.approx(arrive[i] + R * THR / A, abs=1e-9)
        assert int(r["direction"]) == (-1 if i < 6 else 1) or i == 6
        lo, sp, hi = float(r["speed_low"]), float(r["speed"]), float(r["speed_high"])
        if math.isfinite(sp):
            assert lo <= sp <= hi and lo < hi
            assert sp == pytest.approx(3.7 if int(r["direction"]) > 0 else 1.3, rel=0.15)
    left = [r for r in rows if int(r["direction"]) == -1]
    assert [float(r["x"]) for r in left] == list(x[6:0:-1])  # from the nucleation outwards
    ev = read_rows(tmp_path / "events.csv")[0]
    assert float(ev["speed_left"]) == pytest.approx(1.3, rel=0.05)
    assert float(ev["speed_right"]) == pytest.approx(3.7, rel=0.05)
    assert float(ev["speed_right_low"]) < float(ev["speed_right"]) < float(
        ev["speed_right_high"])


def test_summary_numbers_by_hand(tmp_path) -> None:
    # mistakes: the sound speed sqrt(m/k); the default threshold not 10 x the loading
    # velocity; the precursors' time cut not reported
    res, _, _ = _run()
    _, _, summary = interface_outputs(res, tmp_path, figure=False, fields=False,
                                      transient=1.7)
    assert summary["sound_speed"] == pytest.approx(math.sqrt(3.7 / 0.6), rel=1e-15)
    assert summary["threshold"] == pytest.approx(0.13, rel=1e-15)
    assert summary["precursors"]["after"] == 1.7
    assert summary["units"]["sound_speed"] == "element/t0"


def test_the_default_edge_gap_keeps_an_event_beside_the_creeping_edge_block(tmp_path) -> None:
    """Side loading keeps the edge block creeping below the threshold, so an event from the
    loaded edge starts at element 1: by default (``edge_gap = 1``) it is a precursor, its
    length from the loaded end to the far side of the last element it reached (cells of width
1: elements 0 to 14, 15), and summary.json says the gap used. Mistake: a default of 0
    (every precursor of a side-loaded run lost)."""
    res, x, _ = _run()
    _, _, summary = interface_outputs(res, tmp_path, threshold=THR, figure=False, fields=False)
    rows = read_rows(tmp_path / "precursors.csv")
    assert len(rows) == 1
    assert float(rows[0]["length"]) == pytest.approx(x[14] + 0.5 * (x[1] - x[0]), rel=1e-12)
    assert summary["precursors"]["edge_gap"] == 1
