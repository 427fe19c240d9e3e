"""Space-time fields on disk: NetCDF through xarray with every variable's unit, or .npz with a
one-line note where xarray is missing (io/spacetime.py)."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from dryfriction.io import spacetime
from dryfriction.io.spacetime import read_fields, write_fields

UNITS = {"t": "s", "x": "m", "slip_rate": "m/s", "slip": "m", "load": "N"}


def _fields():
    rng = np.random.default_rng(3)
    t = np.linspace(0.0, 2.0, 7) + 1e-9  # not representable in float32: the axis stays float64
    x = 0.125 * np.arange(5) + 0.3
    v = rng.uniform(0.0, 1.0, (7, 5))
    return t, x, {"slip_rate": v, "slip": np.cumsum(v, axis=0), "load": 2.0 + t}


@pytest.mark.parametrize("netcdf", [True, False])
def test_fields_round_trip_with_units(tmp_path, netcdf):
    # mistakes: the axes stored in float32 with the fields; a unit dropped; the fallback
    # written under the .nc name
    t, x, f = _fields()
    out = write_fields(tmp_path / "fields.nc", t, x, f, UNITS, attrs={"threshold": 0.5},
                       netcdf=netcdf)
    assert out.path.exists() and out.path.suffix == (".nc" if netcdf else ".npz")
    assert (out.note == "") == netcdf and "\n" not in out.note
    arrays, units = read_fields(out.path)
    assert np.array_equal(arrays["t"], t) and np.array_equal(arrays["x"], x)
    for name, a in f.items():
        assert arrays[name].shape == a.shape
        assert np.allclose(arrays[name], a, rtol=1e-6)
        assert units[name] == UNITS[name]
    assert units["t"] == "s" and units["x"] == "m"


def test_without_xarray_writes_npz_and_says_so(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)  # as if not installed
    assert not spacetime.has_xarray()
    t, x, f = _fields()
    out = write_fields(tmp_path / "fields.nc", t, x, f, UNITS)
    assert out.format == "npz" and out.path.name == "fields.npz"
    assert "xarray is not installed" in out.note and "dryfriction[sweep]" in out.note
    assert not (tmp_path / "fields.nc").exists()


@pytest.mark.parametrize("change, message", [
    (dict(t=np.array([])), "t must be a non-empty 1-D array"),
    (dict(fields={"slip": np.zeros((3, 5))}), "field slip has shape (3, 5)"),
    (dict(fields={}), "fields is empty"),
    (dict(units={"t": "s", "x": "m"}), "units names no unit for slip_rate"),
])
def test_bad_input_is_one_line(tmp_path, change, message):
    t, x, f = _fields()
    args = dict(t=t, x=x, fields=f, units=UNITS) | change
    with pytest.raises(ValueError) as err:
        write_fields(tmp_path / "f.nc", **args)
    assert message in str(err.value) and "\n" not in str(err.value)
    assert list(tmp_path.iterdir()) == []
