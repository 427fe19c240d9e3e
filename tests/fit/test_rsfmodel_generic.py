"""fit/models.py's rate-and-state model at generic points: the reference velocity it takes
from the data (a series' first load velocity; the geometric mean of steady velocities), its
refusals, the steady state's absolute level ``mu0 + (a - b) ln(V/V0)`` (Ruina 1983) by that
closed form, and the slips the data probe for ``Dc`` (the classification's window): a hold's
``V0 t_w``, a series' shortest sample's slip at its fastest velocity up to its whole travel."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.fit import CVModel
from dryfriction.fit.models import RSFModel
from dryfriction.records.data import SeriesData, StaticData, SteadyData

V = np.array([2e-7, 3e-6, 5e-5, 7e-6])


def test_reference_velocity_from_the_data() -> None:
    # mistakes: the arithmetic mean (1.5e-5 instead of 3.9e-6), the last series' velocity
    steady = SteadyData(V, 0.6 + 0.0 * V)
    assert RSFModel().resolve([steady]).v0 == pytest.approx(
        float(np.prod(V)) ** 0.25, rel=1e-12)
    t = 3.0 + np.linspace(0.0, 10.0, 11)
    s1 = SeriesData(t, np.where(t < 8, 4e-6, 9e-6), 0.6 + 0.0 * t)
    s2 = SeriesData(t, np.full(t.size, 2e-5), 0.6 + 0.0 * t)
    assert RSFModel().resolve([s1, s2]).v0 == 4e-6
    assert RSFModel(v0=1.3e-6).resolve([steady]).v0 == 1.3e-6
    static = StaticData(np.array([1.0, 10.0, 100.0]), np.array([0.6, 0.61, 0.62]))
    with pytest.raises(ValueError, match=r"need v0 \(--v0\)"):
        RSFModel().resolve([static])
    with pytest.raises(ValueError, match="need the ageing law"):
        RSFModel(v0=1e-6, state_law="slip").resolve([static])


def test_steady_state_absolute_level() -> None:
    # mu_ss = mu0 + (a - b) ln(V/V0) at V0 = 3.3e-6, with a - b < 0 (mistakes: ln(V0/V), a
    # log10, the level taken at V = 1 m/s)
    m = RSFModel(v0=3.3e-6)
    steady = SteadyData(V, 0.6 + 0.0 * V)
    got = m.predict({"mu0": 0.643, "a_minus_b": -0.0037}, steady)
    np.testing.assert_allclose(got, 0.643 - 0.0037 * np.log(V / 3.3e-6), rtol=0, atol=1e-12)
    got = m.predict({"mu0": 0.643, "a": 0.0081, "b": 0.0118, "dc": 2e-5}, steady)
    np.testing.assert_allclose(got, 0.643 + (0.0081 - 0.0118) * np.log(V / 3.3e-6), rtol=0,
                               atol=1e-12)
    assert m.derived({"a": 0.0081, "b": 0.0118}) == {"a_minus_b": (0.0081 - 0.0118, "")}


def test_the_slips_the_data_probe_for_dc() -> None:
    # holds: V0 t_w; a series: its shortest sample interval times its fastest velocity, and
    # its whole travel (mistakes: the slowest velocity, the mean interval, the last segment's
    # travel only)
    m = RSFModel(v0=2e-6)
    static = StaticData(np.array([3.0, 30.0, 300.0]), np.array([0.6, 0.61, 0.62]))
    assert m.data_window("dc", [static]) == pytest.approx((6e-6, 6e-4), rel=1e-12)
    t = 5.0 + np.concatenate([np.linspace(0.0, 4.0, 41), 4.0 + np.linspace(0.25, 6.0, 24)])
    v = np.where(t < 9.0, 1e-6, 8e-6)
    d = SeriesData(t, v, 0.6 + 0.0 * t)
    dt_min = float(np.min(np.diff(t)))
    travel = 1e-6 * 4.0 + 8e-6 * (t[-1] - 9.0)
    lo, hi = m.data_window("dc", [d])
    assert lo == pytest.approx(dt_min * 8e-6, rel=1e-9)
    assert hi == pytest.approx(travel, rel=1e-9)
    assert m.data_window("a", [d]) is None
    both = m.data_window("dc", [static, d])
    assert both == pytest.approx((dt_min * 8e-6, 6e-4), rel=1e-9)
    # the trap model's scales: t0 from hold times, vstar from steady velocities
    cv = CVModel()
    assert cv.data_window("t0", [static, SteadyData(V, 0.6 + 0.0 * V)]) == (3.0, 300.0)
    assert cv.data_window("vstar", [static, SteadyData(V, 0.6 + 0.0 * V)]) == (2e-7, 5e-5)
    assert cv.data_window("eps", [static]) is None
