"""Units and scaling: every unit the readers accept against a table written here, and the
model's results independent of the unit system (issue 25 items 1 and 5).

Symmetric inputs hide asymmetric code: a velocity unit computed as ``length x time`` instead
of ``length / time`` is right for every per-second unit (``x 1 = / 1``). So the properties here
draw the unit pair (per-ms, per-minute, per-hour, nm, kPa, kN, ...) and a generic value, write a
file, read it back, and compare with the value converted by the table below (SI definitions).
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dryfriction.records.data import read_csv
from dryfriction.records.lab import read_record
from dryfriction.theory.model import TrapModel
from dryfriction.theory.units import PhysicalScales, static_friction_si, steady_friction_si

# SI value of each unit, written from the definitions (not imported)
LENGTH = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9}
TIME = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6, "ns": 1e-9, "min": 60.0, "h": 3600.0,
        "d": 86400.0}
LAB_LENGTH = {**LENGTH, "μm": 1e-6, "micron": 1e-6, "microns": 1e-6}
LAB_TIME = {**TIME, "sec": 1.0, "hr": 3600.0}
STRESS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9}
FORCE = {"N": 1.0, "kN": 1e3, "MN": 1e6}

PROPS = settings(max_examples=40, derandomize=True, deadline=None)


def _rows(n: int = 12) -> np.ndarray:
    k = np.arange(n, dtype=float)
    return np.column_stack([0.37 + 1.3 * k, 2.9 + 0.71 * k, 3.3 + 0.1 * np.sin(k),
                            0.59 + 0.01 * np.cos(k), 1.7 + 0.0 * k])


@PROPS
@given(lu=st.sampled_from(sorted(LAB_LENGTH)), tu=st.sampled_from(sorted(LAB_TIME)),
       vl=st.sampled_from(sorted(LAB_LENGTH)), vt=st.sampled_from(sorted(LAB_TIME)),
       su=st.sampled_from(sorted(STRESS)), nu=st.sampled_from(sorted(STRESS)))
def test_lab_reader_units_round_trip(lu: str, tu: str, vl: str, vt: str, su: str, nu: str
                                     ) -> None:
    """Time, displacement and ``length/time`` velocity columns in any accepted units, shear and
    normal stresses in two different ones: the record holds the table's SI values and friction
    ``shear f_s / (normal f_n)``. Mistakes: ``f_len * f_time``; a kPa taken as 1e6."""
    rows = _rows()
    head = (f"Time ({tu})\tLP_disp ({lu})\tLP_velocity ({vl}/{vt})\tShear stress ({su})\t"
            f"Normal stress ({nu})")
    # shear chosen so that the friction is 0.59..0.6 whatever the two units
    shear = rows[:, 3] * rows[:, 4] * STRESS[nu] / STRESS[su]
    data = np.column_stack([rows[:, 0], rows[:, 1], rows[:, 2], shear, rows[:, 4]])
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "rec.txt"
        np.savetxt(path, data, delimiter="\t", header=head, comments="", fmt="%.17g")
        rec = read_record(path)
    np.testing.assert_allclose(rec.time, rows[:, 0] * LAB_TIME[tu], rtol=1e-14)
    assert rec.load_point is not None and rec.load_velocity is not None
    np.testing.assert_allclose(rec.load_point, rows[:, 1] * LAB_LENGTH[lu], rtol=1e-14)
    np.testing.assert_allclose(rec.load_velocity, rows[:, 2] * LAB_LENGTH[vl] / LAB_TIME[vt],
                               rtol=1e-14)
    np.testing.assert_allclose(rec.friction, rows[:, 3], rtol=1e-13)
    assert rec.normal_stress is not None and rec.normal_unit == "Pa"
    np.testing.assert_allclose(rec.normal_stress, rows[:, 4] * STRESS[nu], rtol=1e-14)


@PROPS
@given(su=st.sampled_from(sorted(FORCE)), nu=st.sampled_from(sorted(FORCE)))
def test_lab_reader_forces_give_friction_and_newtons(su: str, nu: str) -> None:
    """Shear and normal forces (N, kN, MN): friction is their ratio in SI, the normal load is in
    newtons."""
    rows = _rows()
    shear = rows[:, 3] * rows[:, 4] * FORCE[nu] / FORCE[su]
    data = np.column_stack([rows[:, 0], rows[:, 1], shear, rows[:, 4]])
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "rec.csv"
        np.savetxt(path, data, delimiter=",", header=f"time (s),disp (mm),shear force ({su}),"
                   f"normal force ({nu})", comments="", fmt="%.17g")
        rec = read_record(path)
    np.testing.assert_allclose(rec.friction, rows[:, 3], rtol=1e-13)
    assert rec.normal_unit == "N" and rec.normal_stress is not None
    np.testing.assert_allclose(rec.normal_stress, rows[:, 4] * FORCE[nu], rtol=1e-14)


@PROPS
@given(tu=st.sampled_from(sorted(TIME)), lu=st.sampled_from(sorted(LENGTH)),
       vt=st.sampled_from(sorted(TIME)))
def test_series_csv_units_round_trip(tu: str, lu: str, vt: str) -> None:
    """The data-set CSV (``t[unit]``, ``v_load[length/time]``): the same table."""
    t = 0.5 + 0.37 * np.arange(6)
    v = np.array([2.9, 2.9, 0.0, 0.0, 7.3, 7.3])
    mu = 0.6 + 0.01 * np.arange(6)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "series.csv"
        np.savetxt(path, np.column_stack([t, v, mu]), delimiter=",",
                   header=f"t[{tu}],v_load[{lu}/{vt}],mu", comments="", fmt="%.17g")
        d = read_csv(path)
    np.testing.assert_allclose(d.t, t * TIME[tu], rtol=1e-14)
    np.testing.assert_allclose(d.v_load, v * LENGTH[lu] / TIME[vt], rtol=1e-14)
    np.testing.assert_allclose(d.mu, mu, rtol=1e-15)


# ------------------------------------------------------------------ unit-system independence
@settings(max_examples=15, derandomize=True, deadline=None)
@given(a0=st.floats(1e-9, 1e-5), t0=st.floats(1e-3, 1e3), c=st.floats(0.01, 100.0),
       direct=st.sampled_from([0.0, 0.013]))
def test_si_friction_depends_on_reduced_variables_only(a0: float, t0: float, c: float,
                                                       direct: float) -> None:
    """``mu_d(V; a0, t0)`` depends on ``V t0/a0`` only, ``mu_s(t_w; t0)`` on ``t_w/t0`` only, and
    the direct effect on ``V/V_ref`` (rescale a0 by ``c``: V and V_ref by ``c``; t0 by ``c``:
    t_w by ``c``, V and V_ref by ``1/c``). Mistakes: ``V* = t0/a0``; ``v_ref`` not converted.
    The model's ``v_ref`` is reduced (``a0/t0``): the SI reference velocity is converted by the
    scales, as a user of the SI forms does."""
    eps, mu_el = 0.04, 0.37
    V, v_ref, t_w = 0.3 * a0 / t0, 0.05 * a0 / t0, 37.0 * t0
    s1 = PhysicalScales(a0, t0, mu_el)
    s2 = PhysicalScales(c * a0, t0, mu_el)
    s3 = PhysicalScales(a0, c * t0, mu_el)

    def model(s: PhysicalScales, v_ref_si: float) -> TrapModel:
        return TrapModel(eps=eps, direct=direct, v_ref=float(s.reduced_velocity(v_ref_si)))

    m1 = float(steady_friction_si(model(s1, v_ref), V, s1))
    assert float(steady_friction_si(model(s2, c * v_ref), c * V, s2)) == (
        pytest.approx(m1, rel=1e-12))
    assert float(steady_friction_si(model(s3, v_ref / c), V / c, s3)) == (
        pytest.approx(m1, rel=1e-12))
    athermal = TrapModel(eps=eps)
    ms = float(static_friction_si(athermal, t_w, s1))
    assert float(static_friction_si(athermal, c * t_w, s3)) == pytest.approx(ms, rel=1e-12)
    assert float(static_friction_si(athermal, t_w, s2)) == pytest.approx(ms, rel=1e-12)


def test_physical_scales_conversions_at_a_generic_point() -> None:
    """``V* = a0/t0``, ``u = V/V*``, ``T = t/t0``, ``F = mu_el W mu``, ``D0 = C a0``."""
    s = PhysicalScales(a0=2.3e-7, t0=41.0, mu_el=0.37, normal_load=130.0)
    assert s.velocity_scale == pytest.approx(2.3e-7 / 41.0, rel=1e-15)
    assert float(s.reduced_velocity(4.4e-6)) == pytest.approx(4.4e-6 * 41.0 / 2.3e-7, rel=1e-14)
    assert float(s.reduced_time(7.0)) == pytest.approx(7.0 / 41.0, rel=1e-15)
    assert float(s.reduced_length(1.1e-6)) == pytest.approx(1.1e-6 / 2.3e-7, rel=1e-15)
    assert float(s.friction_coefficient(1.7)) == pytest.approx(0.37 * 1.7, rel=1e-15)
    assert float(s.force(1.7)) == pytest.approx(0.37 * 130.0 * 1.7, rel=1e-15)
    assert float(s.memory_length(3.1)) == pytest.approx(3.1 * 2.3e-7, rel=1e-15)
    assert math.isclose(s.elastic_force, 0.37 * 130.0)
