"""Steady dynamic friction (spec §4): eq. 34, its expansions and limits."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dryfriction.theory.model import TrapModel
from dryfriction.theory.steady import (
    DYNAMIC_SLOPE_PER_EPS,
    low_velocity_constant,
    min_velocity,
    steady_death_point,
    steady_friction,
    steady_friction_first_order,
    steady_friction_low_velocity,
    steady_friction_over_eps,
    steady_profile,
)
from dryfriction.theory.trap import ALPHA0, Trap
from reference import ref_steady

rng = np.random.default_rng(7)


def test_precision_against_mpmath():
    """<= 1e-9 relative over alpha in (0, 0.98], eps in [0, 0.2], u in [1e-4, 1e4].

    Beyond alpha ~ 0.98 the result is limited by rounding: H0 ~ (1 - alpha)^3 is a small
    difference of O(1) integrals (see the precision note in docs/quality.md).
    """
    n = 30
    alpha = np.concatenate([rng.uniform(0.005, ALPHA0, n // 2), rng.uniform(ALPHA0, 0.98, n // 2)])
    eps = rng.uniform(0.0, 0.2, n)
    u = np.exp(rng.uniform(np.log(1e-4), np.log(1e4), n))
    for a, e, v in zip(alpha, eps, u, strict=True):
        assert steady_friction(TrapModel(alpha=a, eps=e),
                               v) == pytest.approx(ref_steady(v, e, a), rel=1e-9)


def test_vectorised_equals_pointwise_and_broadcasts():
    u = np.logspace(-3, 3, 7)
    eps = np.array([[0.01], [0.05]])
    grid = steady_friction_over_eps(TrapModel(), u, eps)
    assert grid.shape == (2, 7)
    assert grid[1, 3] == pytest.approx(steady_friction(TrapModel(eps=0.05), u[3]), rel=1e-14)


def test_elastic_limit_and_saturation():
    u = np.logspace(-4, 4, 9)
    for alpha in (0.05, 0.13, 0.5):
        np.testing.assert_allclose(steady_friction(TrapModel(alpha=alpha, eps=0.0), u), 1.0,
                                   rtol=1e-12)
    # u -> inf: mu_d -> 1 like 1/u (first order: ~ eps C / u)
    big = steady_friction(TrapModel(eps=0.05), np.array([1e4, 1e5, 1e6]))
    excess = big - 1
    assert np.all(excess > 0)
    np.testing.assert_allclose(excess[1:] / excess[:-1], 0.1, rtol=1e-3)


@pytest.mark.parametrize("alpha", [0.05, 0.13, 0.4])
def test_first_order_in_eps(alpha):
    u = np.logspace(-3, 3, 7)
    prev = None
    for eps in (1e-2, 1e-3, 1e-4):
        model = TrapModel(alpha=alpha, eps=eps)
        err = np.max(np.abs(steady_friction(model, u) - steady_friction_first_order(model, u)))
        if prev is not None:
            assert err < prev / 50  # remainder O(eps^2)
        prev = err
    assert prev < 1e-6


def test_low_velocity_expansion_eq35():
    # d mu_d / d ln u -> -(3/2) eps as u -> 0 at small eps (eq. 35 reading)
    eps = 1e-4
    u = np.array([1e-6, 1e-5])
    mu = steady_friction(TrapModel(eps=eps), u)
    slope = np.diff(mu)[0] / np.diff(np.log(u))[0]
    assert slope / eps == pytest.approx(DYNAMIC_SLOPE_PER_EPS, rel=1e-3)
    # with its constant, eq. 35 is the u -> 0 limit of the first-order result
    u = np.array([1e-6, 1e-8])
    lo = steady_friction_low_velocity(TrapModel(eps=1e-3), u)
    fo = steady_friction_first_order(TrapModel(eps=1e-3), u)
    np.testing.assert_allclose(lo, fo, rtol=0, atol=1e-3 * 10 * u.max())
    assert np.isfinite(low_velocity_constant(TrapModel()))


@given(st.floats(0.005, ALPHA0), st.floats(0.001, 0.2), st.floats(1e-4, 1e3), st.floats(1.05, 10))
@settings(max_examples=60, deadline=None)
def test_velocity_weakening_and_eps_monotone(alpha, eps, u, k):
    # very strong pinning (the paper's regime): mu_d decreases with u, increases with eps
    assert steady_friction(TrapModel(alpha=alpha, eps=eps),
                           u * k) < steady_friction(TrapModel(alpha=alpha, eps=eps), u)
    assert steady_friction(TrapModel(alpha=alpha, eps=eps * min(k, 1.5)),
                           u) > steady_friction(TrapModel(alpha=alpha, eps=eps), u)


def test_strong_pinning_is_not_monotone():
    # ours: in strong pinning the aged traps on the far side of the bump return more work
    # than they took, and mu_d dips below 1 at intermediate velocity
    mu = steady_friction(TrapModel(alpha=0.5, eps=0.04), np.logspace(-4, 4, 81))
    assert mu.min() < 1.0 < mu.max()


def test_death_point_eq32_and_profile():
    u, eps = 0.1, 0.04
    pd = steady_death_point(TrapModel(eps=eps), u)
    r = np.sqrt(1 + eps * np.log1p((pd + 1) / u))
    assert pd / r == pytest.approx(Trap(0.13).y_c, rel=1e-13)  # eq. 32
    y = np.linspace(-1.5, pd + 0.5, 4001)
    f = steady_profile(TrapModel(eps=eps), y, u)
    assert np.all(f[y < -1] == 0) and np.all(f[y > pd] == 0)
    # the profile integrates to mu_d H0 (eq. 33 density) — trapezoid on a fine grid
    yy = np.linspace(-1, pd, 400001)
    integral = np.trapezoid(steady_profile(TrapModel(eps=eps), yy, u), yy)
    assert integral / Trap(0.13).H0 == pytest.approx(steady_friction(TrapModel(eps=eps), u),
                                                     rel=1e-5)


def test_eyring_nabarro_variant_and_precision():
    u = np.logspace(-2, 2, 5)
    for eps in (0.02, 0.002):
        en = steady_friction(TrapModel(eps=eps, creep="eyring-nabarro"), u)
        lg = steady_friction(TrapModel(eps=eps), u)
        assert np.all(en >= lg - 1e-14)  # the exact law ages faster
    assert np.max(en - lg) < 50 * 0.002**2


@pytest.mark.parametrize(
    "kwargs, name",
    [({"u": 0.0}, "u"), ({"u": -1.0}, "u"), ({"u": np.nan}, "u"), ({"eps": -1e-3}, "eps"),
     ({"alpha": 1.0}, "alpha"), ({"alpha": -0.2}, "alpha"), ({"creep": "x"}, "creep")],
)
def test_bad_input(kwargs, name):
    # a model's parameter is refused when the model is built, u by the call
    args = {"u": 1.0, "eps": 0.01} | kwargs
    u = args.pop("u")
    with pytest.raises(ValueError, match=f"^{name} = "):
        steady_friction(TrapModel(**args), u)


def test_continuity_across_alpha0():
    # the regime changes at alpha0 (jump out of contact vs onto the far side): results do not
    from dryfriction.theory.static import static_friction

    lo, hi = ALPHA0 * (1 - 1e-9), ALPHA0 * (1 + 1e-9)
    u = np.logspace(-3, 3, 7)
    np.testing.assert_allclose(steady_friction(TrapModel(alpha=lo, eps=0.05), u),
                               steady_friction(TrapModel(alpha=hi, eps=0.05), u),
                               rtol=1e-6)
    T = np.logspace(-3, 3, 7)
    np.testing.assert_allclose(static_friction(TrapModel(alpha=lo, eps=0.05), T),
                               static_friction(TrapModel(alpha=hi, eps=0.05), T),
                               rtol=1e-6)
    for load in (0.3, 0.8):
        np.testing.assert_allclose(static_friction(TrapModel(alpha=lo, eps=0.05), T, load=load),
                                   static_friction(TrapModel(alpha=hi, eps=0.05), T,
                                                   load=load), rtol=1e-6)


# --- range of the inputs (issue 16) -----------------------------------------------------------


def _en_steady_quadrature(u: float, eps: float, alpha: float) -> float:
    """Eq. 34 for the Eyring-Nabarro law by an independent route: a_r from the closed form
    T = (e^{1/eps}/eps)[E1(1/(eps s)) - E1(1/eps)] inverted by brentq, the death point by brentq,
    the integral by scipy's adaptive quad in ln(y + 1) (very strong pinning)."""
    import math

    from scipy.integrate import quad
    from scipy.optimize import brentq
    from scipy.special import exp1

    from dryfriction.trap import force_plus

    def s_of_T(T: float) -> float:
        if T <= 0:
            return 1.0
        f = lambda s: math.exp(1 / eps) / eps * (exp1(1 / (eps * s)) - exp1(1 / eps)) - T  # noqa: E731
        return brentq(f, 1.0, 1.0 / eps, xtol=1e-14, rtol=1e-14)

    def r(y: float) -> float:
        return math.sqrt(s_of_T((y + 1.0) / u))

    yc = Trap(alpha).y_c
    yd = brentq(lambda y: y / r(y) - yc, yc, yc / math.sqrt(eps), xtol=1e-14)

    def g(t: float) -> float:
        y = -1.0 + math.exp(t)
        rr = r(y)
        return math.exp(t) * rr * rr * float(force_plus(min(y / rr, yc), alpha))

    val, _ = quad(g, math.log(u) - 40.0, math.log1p(yd), limit=400, epsabs=1e-12, epsrel=1e-10)
    return val / Trap(alpha).H0


@pytest.mark.parametrize("eps", [0.1, 0.3])
def test_eyring_nabarro_near_its_edge_matches_an_independent_quadrature(eps):
    # catches a death-point search that lands past the law's range (NaN, 0, -1e17 before) and a
    # wrong u_min (an edge refused too early or accepted too late)
    u_min = min_velocity(TrapModel(ALPHA0, eps, "eyring-nabarro"))
    for u in (1.001 * u_min, 3.0 * u_min):
        got = float(steady_friction(TrapModel(alpha=ALPHA0, eps=eps, creep="eyring-nabarro"), u))
        assert got == pytest.approx(_en_steady_quadrature(u, eps, ALPHA0), rel=1e-7)
    with pytest.raises(ValueError, match=r"u = .* beyond the Eyring-Nabarro law's range at eps"):
        steady_friction(TrapModel(alpha=ALPHA0, eps=eps, creep="eyring-nabarro"), 0.999 * u_min)


def test_min_velocity_is_where_traps_die_at_the_end_of_the_range():
    # at u_min the trap dies (y = y_c a_r) exactly at T_v, where a_r^2 = 1/eps: -1 + u T_v = y_c
    # eps^(-1/2); catches a criterion on the wrong age (e.g. (1 + y_c)/u without the radius)
    from dryfriction.creep import max_age

    eps = 0.1
    u = min_velocity(TrapModel(ALPHA0, eps, "eyring-nabarro"))
    assert -1.0 + u * max_age(eps) == pytest.approx(Trap(ALPHA0).y_c / np.sqrt(eps), rel=1e-12)
    yd = float(steady_death_point(TrapModel(ALPHA0, eps, "eyring-nabarro"), u))
    assert yd == pytest.approx(Trap(ALPHA0).y_c / np.sqrt(eps), rel=1e-8)


@pytest.mark.parametrize("creep", ["log", "eyring-nabarro"])
def test_one_u_alone_equals_the_same_u_in_an_array(creep):
    # catches shared iteration (converged points moved while others iterate) or a batch-size
    # dependent sum
    eps = 0.1
    lo = 1.001 * min_velocity(TrapModel(ALPHA0, eps, creep)) if creep != "log" else 1e-8
    u = np.geomspace(lo, 1e3, 29)
    together = steady_friction(TrapModel(alpha=ALPHA0, eps=eps, creep=creep), u)
    alone = np.array([float(steady_friction(TrapModel(alpha=ALPHA0, eps=eps, creep=creep),
                                            x)) for x in u])
    np.testing.assert_array_equal(together, alone)


def test_extreme_but_allowed_velocities_are_right():
    # the ends of the accepted range (1e-30, 1e30) against the mpmath reference and the
    # high-velocity limit: catches overflow or lost precision at the edges
    assert float(steady_friction(TrapModel(alpha=ALPHA0, eps=0.01), 1e-30)) == pytest.approx(
        ref_steady(1e-30, 0.01, ALPHA0), rel=1e-9)
    assert float(steady_friction(TrapModel(alpha=ALPHA0, eps=0.04),
                                 1e30)) == pytest.approx(1.0, abs=1e-13)


@pytest.mark.parametrize(("u", "eps", "word"), [
    (1e-308, 0.04, "u = 1e-308 is out of range: allowed finite and >= 1e-30 and <= 1e\\+30"),
    (1e308, 0.04, "u = 1e\\+308 is out of range"),
    (1.0, 1e308, "eps = 1e\\+308 is out of range: allowed finite and >= 0 and <= 1"),
    (np.ones(3), np.full(2, 0.01), r"u has shape \(3,\) and eps \(2,\): they do not broadcast"),
])
def test_out_of_range_is_a_named_value_error(u, eps, word):
    # before: nan, inf, RuntimeError, NumPy's anonymous broadcast error
    with pytest.raises(ValueError, match=word):
        if np.ndim(eps):  # a sweep over eps
            steady_friction_over_eps(TrapModel(), u, eps)
        else:
            steady_friction(TrapModel(eps=eps), u)


def test_grouping_and_chunking_do_not_change_a_point(monkeypatch):
    # per_eps sorts the points by eps and evaluates them in chunks: a mix-up of indices would
    # give a point another point's value. Each point alone is the reference.
    import dryfriction.theory.creep as creep_mod

    rng = np.random.default_rng(3)
    u = 10.0 ** rng.uniform(-2, 2, 37)
    eps = rng.choice([0.0, 0.02, 0.04, 0.07], 37)
    monkeypatch.setattr(creep_mod, "PER_EPS_CHUNK", 5)
    together = steady_friction_over_eps(TrapModel(), u.reshape(37, 1), eps.reshape(37, 1))
    alone = np.array([steady_friction(TrapModel(eps=b), a) for a, b in zip(u, eps, strict=True)])
    assert together.shape == (37, 1)
    np.testing.assert_array_equal(together[:, 0], alone)


# velocities at which Newton's iteration for the Eyring-Nabarro death point hopped for ever
# between two floats either side of the root (found evaluating 1e6 log-spaced u in 1e-3..1e3)
_HOPPING = [0.3121422052937961, 0.3177243515784647, 0.33085409906512553, 0.3320722013976712,
            0.33624089008702995, 0.3514734674215111]


def test_death_point_converges_where_newton_hops_between_two_floats():
    from dryfriction.theory.creep import creep_law

    u = np.array(_HOPPING)
    law = creep_law("eyring-nabarro", 0.04)
    pd = steady_death_point(TrapModel(eps=0.04, creep="eyring-nabarro"), u)
    r = np.sqrt(law.radius_sq(law.clock((pd + 1.0) / u)))
    np.testing.assert_allclose(pd / r, Trap(0.13).y_c, rtol=1e-13)  # eq. 32
    mu = steady_friction(TrapModel(eps=0.04, creep="eyring-nabarro"), u)
    near = steady_friction(TrapModel(eps=0.04, creep="eyring-nabarro"), u * (1 + 1e-9))
    np.testing.assert_allclose(mu, near, rtol=1e-9)  # a regular point of a smooth curve
