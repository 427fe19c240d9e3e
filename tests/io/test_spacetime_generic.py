"""Space-time fields on disk at full precision and in compact form, in units other than the
reduced ones (issue 25). Each test names the mistake it is for; each was seen failing with it
applied."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.io.spacetime import read_fields, write_fields

UNITS = {"t": "ms", "x": "mm", "slip_rate": "um/ms", "slip": "um", "load": "kN"}


@pytest.mark.parametrize("netcdf", [True, False])
def test_full_precision_is_exact_and_compact_is_float32(tmp_path, netcdf: bool) -> None:
    # mistakes: compact=False still stored in float32; compact fields kept in float64 (the
    # file twice as large as said); a field's unit swapped for another's
    if netcdf:
        pytest.importorskip("xarray")
    t = 0.37 + 0.011 * np.arange(9) + 1e-9
    x = 1.3 + 0.29 * np.arange(4)
    rate = np.sin(np.add.outer(t, x)) / 3.0
    fields = {"slip_rate": rate, "slip": np.cumsum(rate, axis=0) + 1e3, "load": 2.0 + t / 7}
    full = write_fields(tmp_path / "full.nc", t, x, fields, UNITS, compact=False, netcdf=netcdf)
    arrays, units = read_fields(full.path)
    for name, a in fields.items():
        assert np.array_equal(arrays[name], a), name
        assert units[name] == UNITS[name]
    small = write_fields(tmp_path / "small.nc", t, x, fields, UNITS, netcdf=netcdf)
    arrays, _ = read_fields(small.path)
    for name, a in fields.items():
        assert arrays[name].dtype == np.float32
        assert np.array_equal(arrays[name], a.astype(np.float32)), name
    assert np.array_equal(arrays["t"], t) and arrays["t"].dtype == np.float64
