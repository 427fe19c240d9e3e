"""A MATLAB file's column names carry their units after the last underscore (records/
labforms.py): units other than the SI base, a velocity per second as ``um_s`` (issue 25: a
per-second unit hides a velocity's time factor taken wrongly). Each test names the mistake it
is for; each was seen failing with it applied."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dryfriction.records.lab import read_record


def test_mat_names_with_units_read_in_si(tmp_path: Path) -> None:
    # mistakes: a velocity's "um_s" left as "um_s" (not um/s); "ms" not a unit (the time read
    # in seconds); kPa taken as Pa
    from scipy.io import savemat

    k = np.arange(40, dtype=float)
    t_ms = 130.0 + 250.0 * k
    disp_mm = 0.37 + 0.0011 * k
    vel = np.full(40, 4.4)
    shear_kpa = 6.1e3 + 13.0 * np.sin(k)
    normal_mpa = np.full(40, 10.3)
    p = tmp_path / "rec.mat"
    savemat(p, {"Time_ms": t_ms, "Displ_mm": disp_mm, "LP_velocity_um_s": vel,
                "Shear_stress_kPa": shear_kpa, "Normal_stress_MPa": normal_mpa})
    rec = read_record(p)
    np.testing.assert_allclose(rec.time, t_ms * 1e-3, rtol=1e-14)
    np.testing.assert_allclose(rec.load_point, disp_mm * 1e-3, rtol=1e-14)
    assert rec.load_velocity is not None
    np.testing.assert_allclose(rec.load_velocity, 4.4e-6, rtol=1e-14)
    np.testing.assert_allclose(rec.friction, shear_kpa * 1e3 / (normal_mpa * 1e6), rtol=1e-13)
    assert rec.normal_stress is not None
    assert rec.normal_stress == pytest.approx(10.3e6, rel=1e-14)
