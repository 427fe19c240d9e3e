"""What a sweep's axes hold and the units sweep.nc gives them, against definitions written here.

The mistakes these are for (a blind review's survivors, benchmarks/blind_mutants3.py):
``{log = [start, stop, n]}`` read as exponents (``np.logspace``: 1e-3 .. 1 became 1.002 ..
10), and a swept mass written with the damping's unit ``F_el t0/a0``.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from dryfriction.sweeps.cf import KEY_UNITS
from dryfriction.sweeps.sweep import parse_sweep

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "phase_diagram.toml"


def test_log_axis_runs_from_start_to_stop_in_equal_ratios() -> None:
    protocol = tomllib.loads(EXAMPLE.read_text())
    protocol["sweep"] = {"drive.stiffness": {"log": [3e-3, 0.75, 4]},
                         "drive.segments.0.velocity": {"lin": [0.02, 0.11, 4]}}
    spec = parse_sweep(protocol)
    log_axis, lin_axis = spec.axes
    ratio = (0.75 / 3e-3) ** (1 / 3)  # equal ratios, ends included
    assert log_axis.values == pytest.approx([3e-3 * ratio ** i for i in range(4)], rel=1e-12)
    assert lin_axis.values == pytest.approx([0.02, 0.05, 0.08, 0.11], rel=1e-12)


def test_swept_quantities_carry_their_dimensions() -> None:
    """Reduced units: force F_el, length a0, time t0. From F = k x, F = eta v and F = m a:
    stiffness F_el/a0, damping F_el t0/a0, mass F_el t0^2/a0; velocity a0/t0."""
    assert KEY_UNITS["stiffness"] == "F_el/a0"
    assert KEY_UNITS["damping"] == "F_el t0/a0"
    assert KEY_UNITS["mass"] == "F_el t0^2/a0"
    assert KEY_UNITS["velocity"] == "a0/t0"
    assert KEY_UNITS["mass"] != KEY_UNITS["damping"]
