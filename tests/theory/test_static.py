"""Static friction (spec §3): eq. 27, eq. 28, the pull, the loaded protocol."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dryfriction.theory.model import TrapModel
from dryfriction.theory.static import (
    fresh_force,
    loaded_edge,
    pull_force,
    static_friction,
    static_friction_at_radius,
    static_friction_first_order,
    static_friction_over_eps,
    static_slope_per_eps,
    threshold_shift,
)
from dryfriction.theory.trap import ALPHA0, Trap
from reference import ref_pull_force, ref_static_eq27

rng = np.random.default_rng(20261122)


def _log_uniform(lo, hi, n):
    return np.exp(rng.uniform(np.log(lo), np.log(hi), n))


def test_precision_against_mpmath_eq27():
    # paper's regime (very strong pinning, eq. 27 literally) over the whole stated box
    alpha = rng.uniform(0.02, ALPHA0, 24)
    eps = rng.uniform(0.0, 0.2, 24)
    T = _log_uniform(1e-4, 1e4, 24)
    for a, e, t in zip(alpha, eps, T, strict=True):
        r = math.sqrt(1 + e * math.log1p(t))
        if r * Trap(a).y_c - 1 > Trap(a).y_c:
            continue  # fresh traps die before the aged edge: eq. 27 literally undefined there
        assert static_friction(TrapModel(alpha=a, eps=e),
                               t) == pytest.approx(ref_static_eq27(t, e, a), rel=1e-9)


def test_pull_force_against_trap_by_trap_sum():
    cases = [(0.13, 1.05, 0.0), (0.13, 1.2, 0.5), (0.05, 1.1, 0.0), (0.3, 1.08, 0.2),
             (0.6, 1.3, 0.05), (0.9, 1.1, 0.0)]
    for alpha, r, d_w in cases:
        yc = Trap(alpha).y_c
        for d in np.linspace(0.0, 1.3 * (1 + yc) * r, 7)[1:]:
            ref = ref_pull_force(d, r, alpha, d_w)
            got = pull_force(TrapModel(alpha), d, r, d_w)
            assert got == pytest.approx(ref, rel=1e-9, abs=1e-12)


@pytest.mark.slow
@given(st.floats(0.005, 0.995), st.floats(1.0, 2.5), st.floats(0.0, 0.99))
@settings(max_examples=150, deadline=None)
def test_threshold_is_max_of_pull(alpha, r, load):
    d_w = loaded_edge(TrapModel(alpha), load)
    d = np.linspace(0.0, 1.0 + r * Trap(alpha).death_point + 1.0, 40001)
    scan = pull_force(TrapModel(alpha), d, r, d_w).max()
    mu_s = static_friction_at_radius(TrapModel(alpha=alpha), r, d_w=d_w)
    # the dense scan can only undershoot the true maximum, by at most slope * step; both carry
    # rounding of relative size 1e-16 / H0 (H0 ~ (1 - alpha)^3 as alpha -> 1)
    assert mu_s >= scan - 1e-12 - 1e-14 / Trap(alpha).H0
    assert mu_s - scan < 50 * (d[1] - d[0]) * Trap(alpha).f_c * r**2 / Trap(alpha).H0


def test_paper_regime_threshold_is_eq27_point():
    # for the paper's parameters the maximum is at d* = r y_c (the [reading] of eq. 27)
    for eps in (0.01, 0.05):
        for T in (0.01, 1.0, 100.0):
            r = math.sqrt(1 + eps * math.log1p(T))
            assert static_friction(TrapModel(eps=eps), T) == pytest.approx(
                float(pull_force(TrapModel(), threshold_shift(TrapModel(), r), r)), rel=1e-15)


def test_limits():
    assert static_friction(TrapModel(eps=0.05), 0.0) == pytest.approx(1.0, rel=1e-14)
    assert static_friction(TrapModel(eps=0.0), 1e6) == pytest.approx(1.0, rel=1e-14)
    assert static_friction(TrapModel(alpha=0.5, eps=0.05), 0.0) == pytest.approx(1.0, rel=1e-13)
    # fresh contact: force 0 at rest (eq. 25), 1 at the elastic threshold d = y_c (eq. 12)
    for alpha in (0.13, 0.5):
        assert fresh_force(TrapModel(alpha), 0.0) == pytest.approx(0.0, abs=1e-14)
        assert fresh_force(TrapModel(alpha), Trap(alpha).y_c) == pytest.approx(1.0, rel=1e-13)


@pytest.mark.parametrize("alpha", [0.05, 0.13, 0.3])
def test_first_order_expansion_eq28(alpha):
    T = np.logspace(-2, 2, 9)
    prev = None
    for eps in (1e-2, 1e-3, 1e-4):
        model = TrapModel(alpha=alpha, eps=eps)
        err = np.max(np.abs(static_friction(model, T) - static_friction_first_order(model, T)))
        if prev is not None:  # the remainder is O(eps^2)
            assert err < prev / 50
        prev = err
    assert prev < 1e-7


def test_slope_per_eps_paper_value():
    # independent arithmetic for alpha = 0.13 from eq. 28: y_c, f_+(y_c - 1), H1, H0
    a = 0.13
    yc = 0.87**2 / 0.52
    y1 = yc - 1
    f1 = 6 * a * (y1 + (0.87 + math.sqrt(0.87**2 - 4 * a * y1)) / 2)
    trap = Trap(a)
    assert static_slope_per_eps(TrapModel(a)) == pytest.approx(
        (3 * trap.H1 + y1 * f1) / (2 * trap.H0_paper), rel=1e-12)
    # mu_s is not log-linear in T at short times (paper §4): slope grows with T
    T = np.array([0.01, 0.1, 1, 10, 100])
    mu = static_friction(TrapModel(eps=0.03), T)
    slopes = np.diff(mu) / np.diff(np.log(T))
    assert np.all(np.diff(slopes) > 0)
    assert slopes[-1] == pytest.approx(0.03 * static_slope_per_eps(TrapModel(a)), rel=0.05)


@given(st.floats(0.01, ALPHA0), st.floats(0.001, 0.2), st.floats(1e-3, 1e3), st.floats(1.01, 10))
@settings(max_examples=60, deadline=None)
def test_monotone_in_T_and_eps(alpha, eps, T, k):
    # very strong pinning (the paper's regime); strong pinning is checked below
    assert static_friction(TrapModel(alpha=alpha, eps=eps),
                           T * k) > static_friction(TrapModel(alpha=alpha, eps=eps), T)
    assert static_friction(TrapModel(alpha=alpha, eps=eps * min(k, 1.5)),
                           T) > static_friction(TrapModel(alpha=alpha, eps=eps), T)


def test_loaded_protocol_larger_and_steeper():
    # paper §4: ageing under load gives larger mu_s and larger d mu_s / d ln t_w
    T = np.array([1.0, 100.0])
    rest = static_friction(TrapModel(eps=0.03), T)
    slope_rest = np.diff(rest) / np.diff(np.log(T))
    for load in (0.3, 0.6, 0.9):
        loaded = static_friction(TrapModel(eps=0.03), T, load=load)
        assert np.all(loaded > rest)
        assert (np.diff(loaded) / np.diff(np.log(T)))[0] > slope_rest[0]
        # the edge really carries the load at T = 0
        edge = loaded_edge(TrapModel(), load)
        assert fresh_force(TrapModel(), edge) == pytest.approx(load, rel=1e-12)
        assert static_friction(TrapModel(eps=0.03), 0.0, load=load) == pytest.approx(1.0, rel=1e-13)


def test_eyring_nabarro_variant():
    # the exact law ages faster than its first-order form (rate factor s e^{(1/s-1)/eps} >=
    # e^{(1-s)/eps} for s >= 1), so its static friction is larger, by O(eps^2)
    T = np.logspace(-2, 2, 5)
    for eps in (0.02, 0.002):
        en = static_friction(TrapModel(eps=eps, creep="eyring-nabarro"), T)
        lg = static_friction(TrapModel(eps=eps), T)
        assert np.all(en >= lg - 1e-15)
    assert np.max(en - lg) < 20 * 0.002**2 * np.log1p(T[-1]) ** 2


@pytest.mark.parametrize(
    "kwargs, name",
    [({"T": -1.0}, "T"), ({"T": math.nan}, "T"), ({"eps": -0.01}, "eps"),
     ({"eps": math.inf}, "eps"), ({"alpha": 0.0}, "alpha"), ({"alpha": 1.0}, "alpha"),
     ({"alpha": 1.5}, "alpha"), ({"load": 1.0}, "load"), ({"load": -1.0}, "load"),
     ({"hold": "time"}, "hold"),
     ({"creep": "power"}, "creep")],
)
def test_bad_input(kwargs, name):
    # a model's parameter is refused when the model is built, the others by the call
    args = {"T": 1.0, "eps": 0.01} | kwargs
    T = args.pop("T")
    call = {k: args.pop(k) for k in ("load", "hold") if k in args}
    with pytest.raises(ValueError, match=f"^{name} = "):
        static_friction(TrapModel(**args), T, **call)


def test_eyring_nabarro_static_range_and_array_consistency():
    # catches T past the law's range computed as garbage (7e14 at T = 1e12, eps = 0.05, before)
    # and a T whose answer depends on its neighbours in the array
    from dryfriction.creep import max_age

    eps = 0.05
    t_v = max_age(eps)
    T = np.geomspace(1e-2, 0.999 * t_v, 23)
    together = static_friction(TrapModel(alpha=ALPHA0, eps=eps, creep="eyring-nabarro"), T)
    alone = np.array([float(static_friction(TrapModel(alpha=ALPHA0, eps=eps,
                                                      creep="eyring-nabarro"), t)) for t in T])
    np.testing.assert_array_equal(together, alone)
    with pytest.raises(ValueError, match=r"T = 1e\+12 is beyond the Eyring-Nabarro law's range"):
        static_friction(TrapModel(alpha=ALPHA0, eps=eps, creep="eyring-nabarro"), 1e12)


@pytest.mark.parametrize(("T", "eps", "word"), [
    (1e308, 0.04, r"T = 1e\+308 is out of range: allowed finite and >= 0 and <= 1e\+30"),
    (1.0, 1e308, r"eps = 1e\+308 is out of range: allowed finite and >= 0 and <= 1"),
    (np.ones(3), np.full(2, 0.01), r"T has shape \(3,\) and eps \(2,\): they do not broadcast"),
])
def test_static_out_of_range_is_a_named_value_error(T, eps, word):
    with pytest.raises(ValueError, match=word):
        if np.ndim(eps):  # a sweep over eps
            static_friction_over_eps(TrapModel(), T, eps)
        else:
            static_friction(TrapModel(eps=eps), T)


@pytest.mark.slow
def test_reversed_load_and_the_two_holds():
    # a reversed load is the mirror population: d_w(-f) = -d_w(f); at zero load the holds agree
    edge_back = loaded_edge(TrapModel(), -0.4)
    assert edge_back == pytest.approx(-loaded_edge(TrapModel(), 0.4), rel=1e-15)
    T = np.array([1.0, 100.0])
    rest = static_friction(TrapModel(eps=0.04), T)
    assert np.array_equal(static_friction(TrapModel(eps=0.04), T, hold="force"), rest)
    from dryfriction.theory.static import force_hold_shift

    # the force hold moves the slider against the load as the contacts age (it stays put at
    # T = 0) and by the same amount for +-f (mirror symmetry of the held population)
    assert force_hold_shift(TrapModel(eps=0.04), 0.0, load=0.5) == 0.0
    back = force_hold_shift(TrapModel(eps=0.04), 100.0, load=0.5)
    fwd = force_hold_shift(TrapModel(eps=0.04), 100.0, load=-0.5)
    assert back < -0.05 and fwd == pytest.approx(-back, rel=1e-9)
    # Dillavou & Rubinstein's sign and trend: a forward load ages faster than rest, a reversed
    # one slower (both holds)
    for hold in ("position", "force"):
        up = static_friction(TrapModel(eps=0.04), T, load=0.5, hold=hold)
        down = static_friction(TrapModel(eps=0.04), T, load=-0.5, hold=hold)
        assert np.all(down < rest) and np.all(rest < up)
        assert up[1] - up[0] > rest[1] - rest[0] > down[1] - down[0] > 0
    # under a reversed force hold the slider creeps forward and the pairs it meets age during
    # the wait (the ensemble agrees: test_driving, slow): stronger than the position hold
    gap = static_friction(TrapModel(eps=0.04), 100.0, load=-0.5,
                          hold="force") - static_friction(TrapModel(eps=0.04), 100.0, load=-0.5,
                                                          hold="position")
    assert 0.01 < gap < 0.013


def test_force_hold_rear_exits_lower_the_loaded_threshold():
    # at f_w = 0.5 the slider creeps back 0.12 a0 by T = 100, pushing the rearmost aged traps
    # past w = -1: they leave and come back fresh in the pull. The ensemble's force-controlled
    # run (examples/static_threshold_loaded.toml, 1000 pairs/a0, about 3e-4 density error)
    # gives 1.2477; the position hold's closed form is 1.2490
    force = float(static_friction(TrapModel(eps=0.04), 100.0, load=0.5, hold="force"))
    position = float(static_friction(TrapModel(eps=0.04), 100.0, load=0.5, hold="position"))
    assert force == pytest.approx(1.2474, abs=4e-4)
    assert position - force > 1e-3


def test_a_reversed_load_is_refused_by_its_own_range() -> None:
    # the mistake: a reversed load whose mirrored edge is at or past -a0 refused as
    # "d_w = -1.03882 is out of range" (a second new user's --load -0.7), a name no user gave
    from dryfriction.theory.model import TrapModel as TM
    from dryfriction.theory.static import fresh_force, loaded_edge, static_friction

    m = TM(0.13, 0.043, "log")
    lim = float(fresh_force(m, 1.0))  # the load whose edge is exactly at a0
    assert 0.67 < lim < 0.68 and loaded_edge(m, -(lim - 1e-6)) > -1.0
    ok = static_friction(m, [1.7, 170.0], load=-(lim - 1e-4))
    assert np.all(np.isfinite(ok)) and np.all(ok >= 1.0)
    for load in (-0.7, -(lim + 1e-4)):
        with pytest.raises(ValueError, match=rf"^load = {load:g} is out of range: allowed "
                           rf"-{lim:.4g} < load < 1 at alpha = 0\.13 with the position held"):
            static_friction(m, [1.7], load=load)
        # the force held: the edge creeps back, the load's whole range is taken
        assert np.isfinite(static_friction(m, [1.7], load=load, hold="force")).all()
    # alpha with y_c < 1: the edge never reaches -a0, the whole -1 < load < 1 is allowed
    assert np.isfinite(static_friction(TM(0.31, 0.043, "log"), [1.7], load=-0.97)).all()
