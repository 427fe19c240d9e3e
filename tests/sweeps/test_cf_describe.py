"""sweep.nc's CF attributes (sweeps/cf.py describe) on a small Dataset written here: each
coordinate's unit by its key's last part (and none for a key not in the table), the runner's
variables with their attributes, a flag variable's values in the variable's own type, a
variable not listed named by itself, the global attributes (issue 25: a column's unit)."""

from __future__ import annotations

import numpy as np
import pytest

xr = pytest.importorskip("xarray")

from dryfriction.sweeps.cf import KEY_UNITS, UNITS_NOTE, describe  # noqa: E402


def test_describe_sets_units_by_the_last_key_part() -> None:
    ds = xr.Dataset(
        {"amplitude": (("a", "b"), np.ones((2, 3))), "class": (("a", "b"), np.ones((2, 3))),
         "extra": (("a", "b"), np.zeros((2, 3))),
         "error": (("a", "b"), np.full((2, 3), ""))},
        coords={"a": [0.1, 0.2], "b": [1.0, 2.0, 3.0]})
    ds = ds.rename({"a": "drive.segments.1.velocity", "b": "ensemble.layout_x"})
    variables = {"amplitude": {"long_name": "drop", "units": "1"},
                 "class": {"long_name": "kind", "units": "1", "flag_values": [0, 1, 2],
                           "flag_meanings": "a b c"}}
    out = describe(ds, variables, protocol="[model]\n", source="p.toml", analysis="stickslip")
    v = out["drive.segments.1.velocity"].attrs
    assert v == {"long_name": "protocol value drive.segments.1.velocity",
                 "units": KEY_UNITS["velocity"]} and KEY_UNITS["velocity"] == "a0/t0"
    assert "units" not in out["ensemble.layout_x"].attrs
    assert out["amplitude"].attrs == {"long_name": "drop", "units": "1"}
    fv = out["class"].attrs["flag_values"]
    assert fv.dtype == out["class"].dtype and list(fv) == [0.0, 1.0, 2.0]
    assert out["extra"].attrs == {"long_name": "extra"}
    assert out["error"].attrs["long_name"].startswith("error of a failed point")
    g = out.attrs
    assert g["Conventions"] == "CF-1.8" and g["analysis"] == "stickslip"
    assert g["title"] == "dryfriction parameter sweep (stickslip)"
    assert g["source"].endswith("; protocol p.toml") and g["protocol"] == "[model]\n"
    assert g["units_note"] == UNITS_NOTE and g["history"].endswith(" dryfriction sweep")
    assert variables["class"]["flag_values"] == [0, 1, 2]  # the runner's table untouched


def test_key_units_against_a_hand_written_table() -> None:
    """Reduced units (force F_el, length a0, time t0) of the swept keys that name a time, a
    length, a force or a rate (test_axis_units.py checks the spring's)."""
    table = {"rate": "F_el/t0", "hold": "t0", "max_force": "F_el", "every": "t0",
             "every_slip": "a0", "transient": "a0", "slip": "a0", "duration": "t0",
             "initial_force": "F_el", "initial_velocity": "a0/t0", "traps_per_a0": "1/a0",
             "eps": "1", "alpha": "1", "floor": "1"}
    assert {k: KEY_UNITS[k] for k in table} == table
