"""Steady dynamic friction (spec §4): eq. 34, its expansions and limits."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dryfriction.theory.steady import (
    DYNAMIC_SLOPE_PER_EPS,
    low_velocity_constant,
    steady_death_point,
    steady_friction,
    steady_friction_first_order,
    steady_friction_low_velocity,
    steady_profile,
)
from dryfriction.theory.trap import ALPHA0, Trap
from reference import ref_steady

rng = np.random.default_rng(7)


def test_precision_against_mpmath():
    """<= 1e-9 relative over alpha in (0, 0.98], eps in [0, 0.2], u in [1e-4, 1e4].

    Beyond alpha ~ 0.98 the result is limited by rounding: H0 ~ (1 - alpha)^3 is a small
    difference of O(1) integrals (see the precision note in the README).
    """
    n = 30
    alpha = np.concatenate([rng.uniform(0.005, ALPHA0, n // 2), rng.uniform(ALPHA0, 0.98, n // 2)])
    eps = rng.uniform(0.0, 0.2, n)
    u = np.exp(rng.uniform(np.log(1e-4), np.log(1e4), n))
    for a, e, v in zip(alpha, eps, u, strict=True):
        assert steady_friction(v, e, a) == pytest.approx(ref_steady(v, e, a), rel=1e-9)


def test_vectorised_equals_pointwise_and_broadcasts():
    u = np.logspace(-3, 3, 7)
    eps = np.array([[0.01], [0.05]])
    grid = steady_friction(u, eps)
    assert grid.shape == (2, 7)
    assert grid[1, 3] == pytest.approx(steady_friction(u[3], 0.05), rel=1e-14)


def test_elastic_limit_and_saturation():
    u = np.logspace(-4, 4, 9)
    for alpha in (0.05, 0.13, 0.5):
        np.testing.assert_allclose(steady_friction(u, 0.0, alpha), 1.0, rtol=1e-12)
    # u -> inf: mu_d -> 1 like 1/u (first order: ~ eps C / u)
    big = steady_friction(np.array([1e4, 1e5, 1e6]), 0.05)
    excess = big - 1
    assert np.all(excess > 0)
    np.testing.assert_allclose(excess[1:] / excess[:-1], 0.1, rtol=1e-3)


@pytest.mark.parametrize("alpha", [0.05, 0.13, 0.4])
def test_first_order_in_eps(alpha):
    u = np.logspace(-3, 3, 7)
    prev = None
    for eps in (1e-2, 1e-3, 1e-4):
        err = np.max(np.abs(steady_friction(u, eps, alpha) - steady_friction_first_order(
            u, eps, alpha)))
        if prev is not None:
            assert err < prev / 50  # remainder O(eps^2)
        prev = err
    assert prev < 1e-6


def test_low_velocity_expansion_eq35():
    # d mu_d / d ln u -> -(3/2) eps as u -> 0 at small eps (eq. 35 reading)
    eps = 1e-4
    u = np.array([1e-6, 1e-5])
    mu = steady_friction(u, eps)
    slope = np.diff(mu)[0] / np.diff(np.log(u))[0]
    assert slope / eps == pytest.approx(DYNAMIC_SLOPE_PER_EPS, rel=1e-3)
    # with its constant, eq. 35 is the u -> 0 limit of the first-order result
    u = np.array([1e-6, 1e-8])
    lo = steady_friction_low_velocity(u, 1e-3)
    fo = steady_friction_first_order(u, 1e-3)
    np.testing.assert_allclose(lo, fo, rtol=0, atol=1e-3 * 10 * u.max())
    assert np.isfinite(low_velocity_constant(0.13))


@given(st.floats(0.005, ALPHA0), st.floats(0.001, 0.2), st.floats(1e-4, 1e3), st.floats(1.05, 10))
@settings(max_examples=60, deadline=None)
def test_velocity_weakening_and_eps_monotone(alpha, eps, u, k):
    # very strong pinning (the paper's regime): mu_d decreases with u, increases with eps
    assert steady_friction(u * k, eps, alpha) < steady_friction(u, eps, alpha)
    assert steady_friction(u, eps * min(k, 1.5), alpha) > steady_friction(u, eps, alpha)


def test_strong_pinning_is_not_monotone():
    # ours: in strong pinning the aged traps on the far side of the bump return more work
    # than they took, and mu_d dips below 1 at intermediate velocity
    mu = steady_friction(np.logspace(-4, 4, 81), 0.04, alpha=0.5)
    assert mu.min() < 1.0 < mu.max()


def test_death_point_eq32_and_profile():
    u, eps = 0.1, 0.04
    pd = steady_death_point(u, eps)
    r = np.sqrt(1 + eps * np.log1p((pd + 1) / u))
    assert pd / r == pytest.approx(Trap(0.13).y_c, rel=1e-13)  # eq. 32
    y = np.linspace(-1.5, pd + 0.5, 4001)
    f = steady_profile(y, u, eps)
    assert np.all(f[y < -1] == 0) and np.all(f[y > pd] == 0)
    # the profile integrates to mu_d H0 (eq. 33 density) — trapezoid on a fine grid
    yy = np.linspace(-1, pd, 400001)
    integral = np.trapezoid(steady_profile(yy, u, eps), yy)
    assert integral / Trap(0.13).H0 == pytest.approx(steady_friction(u, eps), rel=1e-5)


def test_eyring_nabarro_variant_and_precision():
    u = np.logspace(-2, 2, 5)
    for eps in (0.02, 0.002):
        en = steady_friction(u, eps, creep="eyring-nabarro")
        lg = steady_friction(u, eps)
        assert np.all(en >= lg - 1e-14)  # the exact law ages faster
    assert np.max(en - lg) < 50 * 0.002**2


@pytest.mark.parametrize(
    "kwargs, name",
    [({"u": 0.0}, "u"), ({"u": -1.0}, "u"), ({"u": np.nan}, "u"), ({"eps": -1e-3}, "eps"),
     ({"alpha": 1.0}, "alpha"), ({"alpha": -0.2}, "alpha"), ({"creep": "x"}, "creep")],
)
def test_bad_input(kwargs, name):
    with pytest.raises(ValueError, match=name):
        steady_friction(**({"u": 1.0, "eps": 0.01} | kwargs))


def test_continuity_across_alpha0():
    # the regime changes at alpha0 (jump out of contact vs onto the far side): results do not
    from dryfriction.theory.static import static_friction

    lo, hi = ALPHA0 * (1 - 1e-9), ALPHA0 * (1 + 1e-9)
    u = np.logspace(-3, 3, 7)
    np.testing.assert_allclose(steady_friction(u, 0.05, lo), steady_friction(u, 0.05, hi),
                               rtol=1e-6)
    T = np.logspace(-3, 3, 7)
    np.testing.assert_allclose(static_friction(T, 0.05, lo), static_friction(T, 0.05, hi),
                               rtol=1e-6)
    for load in (0.3, 0.8):
        np.testing.assert_allclose(static_friction(T, 0.05, lo, load=load),
                                   static_friction(T, 0.05, hi, load=load), rtol=1e-6)
