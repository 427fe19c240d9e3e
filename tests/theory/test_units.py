"""The SI layer: explicit, checked conversions around the reduced core."""

import numpy as np
import pytest

from dryfriction.theory.static import static_friction
from dryfriction.theory.steady import steady_friction
from dryfriction.theory.units import PhysicalScales, static_friction_si, steady_friction_si


def test_scales_and_conversions():
    s = PhysicalScales(a0=2e-6, t0=0.01, mu_el=0.4, normal_load=10.0)
    assert s.velocity_scale == pytest.approx(2e-4)  # m/s
    assert s.reduced_velocity(2e-5) == pytest.approx(0.1)
    assert s.reduced_time(1.0) == pytest.approx(100.0)
    assert s.elastic_force == pytest.approx(4.0)  # N
    assert s.force(1.5) == pytest.approx(6.0)
    assert s.memory_length(2.5) == pytest.approx(5e-6)


def test_si_functions_match_reduced_core():
    s = PhysicalScales(a0=1e-6, t0=0.01, mu_el=0.35)
    tw = np.array([1.0, 10.0, 100.0])  # s
    np.testing.assert_allclose(static_friction_si(tw, 0.03, s),
                               0.35 * static_friction(tw / 0.01, 0.03))
    V = np.array([1e-6, 1e-5])  # m/s
    np.testing.assert_allclose(steady_friction_si(V, 0.03, s),
                               0.35 * steady_friction(V / 1e-4, 0.03))
    # dimensional consistency: doubling t0 is the same as halving the waiting time
    s2 = PhysicalScales(a0=1e-6, t0=0.02, mu_el=0.35)
    np.testing.assert_allclose(static_friction_si(2 * tw, 0.03, s2),
                               static_friction_si(tw, 0.03, s))


@pytest.mark.parametrize("kw, name", [({"a0": 0.0}, "a0"), ({"t0": -1.0}, "t0"),
                                      ({"mu_el": 0.0}, "mu_el"),
                                      ({"normal_load": -2.0}, "normal_load")])
def test_bad_scales(kw, name):
    with pytest.raises(ValueError, match=name):
        PhysicalScales(**({"a0": 1e-6, "t0": 1.0} | kw))


def test_force_needs_normal_load():
    with pytest.raises(ValueError, match="normal_load"):
        PhysicalScales(1e-6, 1.0).force(1.0)
    with pytest.raises(ValueError, match="V"):
        PhysicalScales(1e-6, 1.0).reduced_velocity(-1.0)


def test_si_shape_mismatch_and_range_name_the_si_inputs():
    # catches NumPy's anonymous broadcast error and a range error that hides the SI meaning
    s = PhysicalScales(a0=1e-6, t0=0.01)
    with pytest.raises(ValueError, match=r"t_w has shape \(3,\) and eps \(2,\)"):
        static_friction_si(np.ones(3), np.full(2, 0.01), s)
    with pytest.raises(ValueError, match=r"V has shape \(3,\) and eps \(2,\)"):
        steady_friction_si(np.ones(3), np.full(2, 0.01), s)
    with pytest.raises(ValueError, match=r"u = 1e\+34 is out of range.*V\* = a0/t0 = 0.0001 m/s"):
        steady_friction_si(1e30, 0.01, s)
