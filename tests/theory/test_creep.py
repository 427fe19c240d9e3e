"""Creep laws (spec §2): log law, exact Eyring-Nabarro law, material constants."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from dryfriction.theory.creep import (
    CreepMaterial,
    EyringNabarroCreep,
    LogCreep,
    creep_law,
    creep_law_difference,
    max_age,
    radius,
)


def _en_ode(eps, T):
    """Independent route: integrate ds/dT = eps s exp((1/s - 1)/eps) (eqs. 15-16 reduced)."""
    sol = solve_ivp(lambda t, s: eps * s * np.exp((1 / s - 1) / eps), [0, T[-1]], [1.0],
                    t_eval=T, rtol=1e-12, atol=1e-14, method="DOP853")
    return np.sqrt(sol.y[0])


@pytest.mark.parametrize("eps", [0.005, 0.02, 0.05, 0.2])
def test_eyring_nabarro_matches_ode(eps):
    T = np.array([1e-3, 0.1, 1.0, 10.0, 100.0, 1000.0])
    np.testing.assert_allclose(EyringNabarroCreep(eps).radius(T), _en_ode(eps, T), rtol=1e-10)


@pytest.mark.parametrize("eps", [0.0, 1e-6, 0.01, 0.2])
def test_eyring_nabarro_clock_roundtrip(eps):
    law = EyringNabarroCreep(eps)
    T = np.logspace(-8, 4, 25)
    np.testing.assert_allclose(law.age(law.clock(T)), T, rtol=1e-10)
    # dT/dc by central differences
    c = law.clock(T[5:-5])
    h = 1e-6 * np.maximum(c, 1e-3)
    np.testing.assert_allclose((law.age(c + h) - law.age(c - h)) / (2 * h), law.dage(c), rtol=1e-6)


def test_log_law_closed_form_and_first_order_agreement():
    T = np.logspace(-2, 2, 9)
    np.testing.assert_allclose(LogCreep(0.03).radius(T), np.sqrt(1 + 0.03 * np.log1p(T)))
    # the exact law reduces to the log law at first order in eps (eq. 17 from eqs. 15-16):
    for eps in (1e-3, 1e-4):
        d = creep_law_difference(eps, T)
        assert np.max(np.abs(d)) < 5 * eps**2 * np.log1p(T[-1]) ** 2


def test_laws_differ_at_long_times_only():
    # the exact law runs away once T ~ exp(1/eps); over the figure ranges it stays close
    assert abs(creep_law_difference(0.01, 100.0)) < 1e-3
    # at the end of the exact law's range a_r = eps^(-1/2) = 2.24 against 1.45 for the log law
    assert creep_law_difference(0.2, max_age(0.2)) == pytest.approx(
        0.2**-0.5 - math.sqrt(1 + 0.2 * math.log1p(max_age(0.2))), rel=1e-9)
    with pytest.raises(ValueError, match="T = 10000 is beyond the Eyring-Nabarro"):
        creep_law_difference(0.2, 1e4)  # the runaway regime is refused, not computed


def test_material_round_trip():
    mat = CreepMaterial(Y=1e8, S=1e6, edot0=1e-30)
    assert mat.eps == pytest.approx(0.01)
    # eq. 18: 1/t0 = edot0 (Y/S) exp(Y/S)
    assert 1 / mat.t0 == pytest.approx(1e-30 * 100 * math.exp(100), rel=1e-12)
    back = CreepMaterial.from_reduced(mat.eps, mat.t0, mat.Y)
    assert back.edot0 == pytest.approx(mat.edot0, rel=1e-10)
    assert back.S == pytest.approx(mat.S, rel=1e-12)


def test_radius_broadcasts_and_validates():
    r = radius(np.array([[1.0], [10.0]]), np.array([0.01, 0.02, 0.03]))
    assert r.shape == (2, 3)
    assert r[1, 2] == pytest.approx(math.sqrt(1 + 0.03 * math.log(11)))
    with pytest.raises(ValueError, match="eps"):
        radius(1.0, -0.1)
    with pytest.raises(ValueError, match="T"):
        radius(-1.0, 0.1)
    with pytest.raises(ValueError, match="creep"):
        creep_law("power", 0.1)


def _en_age_closed_form(eps: float, s: float) -> float:
    """Independent route to T(a_r^2 = s): T = (e^{1/eps}/eps) [E1(1/(eps s)) - E1(1/eps)]."""
    from scipy.special import exp1

    return math.exp(1 / eps) / eps * (exp1(1 / (eps * s)) - exp1(1 / eps))


@pytest.mark.parametrize("eps", [0.05, 0.1, 0.3])
def test_en_range_end_is_where_the_stress_has_relaxed_to_s(eps):
    # catches a wrong closed form of T_v (e.g. missing the E1(1/eps) term or the 1/eps prefactor)
    # and an edge that is not where a_r^2 = 1/eps
    t_v = max_age(eps)
    assert t_v == pytest.approx(_en_age_closed_form(eps, 1 / eps), rel=1e-12)
    # just inside the edge the radius agrees with the ODE and the closed form
    T = 0.999 * t_v
    r = float(radius(T, eps, "eyring-nabarro"))
    assert float(_en_ode(eps, np.array([T]))[0]) == pytest.approx(r, rel=1e-8)
    assert _en_age_closed_form(eps, r * r) == pytest.approx(T, rel=1e-9)
    with pytest.raises(ValueError, match=r"T = .* beyond the Eyring-Nabarro law's range at eps"):
        radius(1.001 * t_v, eps, "eyring-nabarro")
    assert np.isfinite(radius(1e30, eps, "log"))  # the log law has no such limit


def test_en_radius_alone_equals_radius_in_an_array():
    # catches a vectorised Newton that keeps moving converged points while others iterate
    eps = 0.1
    T = np.concatenate([np.logspace(-3, np.log10(0.99 * max_age(eps)), 37), [0.0]])
    together = radius(T, eps, "eyring-nabarro")
    alone = np.array([float(radius(t, eps, "eyring-nabarro")) for t in T])
    np.testing.assert_array_equal(together, alone)


def test_radius_shape_mismatch_names_the_parameters():
    with pytest.raises(ValueError, match=r"T has shape \(3,\) and eps \(2,\): they do not"):
        radius(np.ones(3), np.full(2, 0.01))
