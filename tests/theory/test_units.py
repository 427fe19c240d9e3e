"""The SI layer: explicit, checked conversions around the reduced core."""

import numpy as np
import pytest

from dryfriction.theory.model import OldTheoryFormWarning, TrapModel
from dryfriction.theory.static import static_friction
from dryfriction.theory.steady import steady_friction
from dryfriction.theory.units import (
    PhysicalScales,
    friction_level,
    static_friction_si,
    steady_friction_si,
)


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
    m = TrapModel(eps=0.03)
    tw = np.array([1.0, 10.0, 100.0])  # s
    np.testing.assert_allclose(static_friction_si(m, tw, s),
                               0.35 * static_friction(m, tw / 0.01))
    V = np.array([1e-6, 1e-5])  # m/s
    np.testing.assert_allclose(steady_friction_si(m, V, s),
                               0.35 * steady_friction(m, V / 1e-4))
    # dimensional consistency: doubling t0 is the same as halving the waiting time
    s2 = PhysicalScales(a0=1e-6, t0=0.02, mu_el=0.35)
    np.testing.assert_allclose(static_friction_si(m, 2 * tw, s2), static_friction_si(m, tw, s))


@pytest.mark.slow
def test_si_forms_take_every_field_of_the_model():
    # mistakes caught: the SI form dropping the model's alpha, creep, direct, load or hold
    s = PhysicalScales(a0=2e-6, t0=0.5)
    m = TrapModel(alpha=0.3, eps=0.05, creep="eyring-nabarro", direct=0.02, v_ref=0.7)
    V = np.array([3e-7, 4e-5])  # m/s: u = 0.075, 10
    np.testing.assert_array_equal(steady_friction_si(m, V, s), steady_friction(m, V / 4e-6))
    tw = np.array([0.3, 40.0])  # s
    got = static_friction_si(m, tw, s, load=0.4, pull_velocity=8e-6, hold="force")
    np.testing.assert_array_equal(got, static_friction(m, tw / 0.5, load=0.4, pull_velocity=2.0,
                                                       hold="force"))
    paper = m.replace(alpha=0.13)  # where the two holds differ (at alpha = 0.3 they agree)
    assert not np.allclose(static_friction_si(paper, tw, s, load=0.4, pull_velocity=8e-6,
                                              hold="force"),
                           static_friction_si(paper, tw, s, load=0.4, pull_velocity=8e-6),
                           rtol=1e-5)
    with pytest.raises(ValueError, match="^pull_velocity is required .* m/s"):
        static_friction_si(m, tw, s)


def test_the_friction_level_is_one_number_given_once():
    # mistake caught: the model's mu_el ignored in SI (or the scales' one)
    m = TrapModel(eps=0.03, mu_el=0.6)
    bare = PhysicalScales(a0=1e-6, t0=1.0)
    np.testing.assert_allclose(steady_friction_si(m, 1e-6, bare),
                               0.6 * steady_friction(m, 1.0), rtol=1e-15)
    assert friction_level(m, PhysicalScales(1e-6, 1.0, mu_el=0.6)) == 0.6
    assert friction_level(TrapModel(), PhysicalScales(1e-6, 1.0, mu_el=0.45)) == 0.45
    with pytest.raises(ValueError, match=r"^mu_el = 0.6 \(model\) and mu_el = 0.45 \(scales\)"):
        static_friction_si(m, 1.0, PhysicalScales(1e-6, 1.0, mu_el=0.45))


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
    # catches NumPy's anonymous broadcast error (the old form, eps an array) and a range error
    # that hides the SI meaning
    s = PhysicalScales(a0=1e-6, t0=0.01)
    with pytest.warns(OldTheoryFormWarning), \
            pytest.raises(ValueError, match=r"t_w has shape \(3,\) and eps \(2,\)"):
        static_friction_si(np.ones(3), np.full(2, 0.01), s)
    with pytest.warns(OldTheoryFormWarning), \
            pytest.raises(ValueError, match=r"V has shape \(3,\) and eps \(2,\)"):
        steady_friction_si(np.ones(3), np.full(2, 0.01), s)
    with pytest.raises(ValueError, match=r"u = 1e\+34 is out of range.*V\* = a0/t0 = 0.0001 m/s"):
        steady_friction_si(TrapModel(eps=0.01), 1e30, s)
    with pytest.raises(ValueError, match=r"T = 1e\+31 is out of range.*T = t_w/t0, t0 = 0.01 s"):
        static_friction_si(TrapModel(eps=0.01), 1e29, s)
