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
    assert creep_law_difference(0.2, 1e4) > 100  # runaway regime


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
