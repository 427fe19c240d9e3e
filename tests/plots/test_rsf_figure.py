"""The ``rsf`` command's slide-hold-slide runs past the reload peak, and every rate-and-state
figure draws friction against ln V over the law's steady state."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.plots.runs import rsf_figure
from dryfriction.program import Segment
from dryfriction.rsf.driving import RSFInitial, RSFOutput, SpringSlider, simulate
from dryfriction.rsf.law import RateState

T1, HOLD = 10.0, 100.0


def _shs(*extra: str):
    return CliRunner().invoke(app, ["rsf", "--case", "shs", "--t1", str(T1),
                                    "--hold-time", str(HOLD), "--json", *extra])


def test_shs_default_reload_passes_the_peak_and_relaxes():
    r = _shs()
    assert r.exit_code == 0, r.output
    s = json.loads(r.stdout)
    # the peak is in the reload and well before the end (was: the last sample, 30 s in)
    assert T1 + HOLD < s["peak_t"] < s["duration"] - 30.0
    # after the peak the friction comes back to steady state at v1 = v0: mu0 = 0.6
    assert s["final_mu"] == pytest.approx(0.6, abs=2e-3)
    assert "note:" not in r.output


def test_shs_with_a_short_reload_says_it_ended_before_the_peak():
    r = _shs("--t2", "5")
    assert r.exit_code == 0
    assert "had not reached its peak" in r.output and "--t2" in r.output


def test_friction_against_ln_v_over_the_steady_state():
    law = RateState(0.005, 0.01, 1e-5, 0.6, 1e-6)
    drive = SpringSlider([Segment(1e-6, 5.0), Segment(1e-5, 10.0)], 1e3)
    res = simulate(law, drive, RSFInitial(), RSFOutput())
    fig, (ax1, ax2, ax3) = rsf_figure(res, "step")
    title = fig.get_suptitle()
    for part in ("step", "a = 0.005", "b = 0.01", "1e-05 m", "k = 1000 1/m"):
        assert part in title, title
    assert ax3.get_xscale() == "log" and "V" in ax3.get_xlabel()
    run, ss = ax3.lines[0], ax3.lines[1]
    np.testing.assert_array_equal(run.get_xdata(), np.abs(res.v))
    np.testing.assert_array_equal(run.get_ydata(), res.mu)
    # Ruina's steady state of the ageing law: mu0 + (a - b) ln(V/V0)
    v = np.asarray(ss.get_xdata())
    np.testing.assert_allclose(ss.get_ydata(), 0.6 + (0.005 - 0.01) * np.log(v / 1e-6),
                               rtol=1e-12)
    assert v.min() == pytest.approx(np.abs(res.v).min()) and v.max() == pytest.approx(
        np.abs(res.v).max())
