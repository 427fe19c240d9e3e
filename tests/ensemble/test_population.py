"""The trap population on its own: initial states, kernel vs exact functions, symmetries."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.ensemble import kernel
from dryfriction.ensemble.population import (
    MINUS,
    PLUS,
    Ensemble,
    Initial,
    Track,
    TrapModel,
)
from dryfriction.theory.static import fresh_force, loaded_edge
from dryfriction.theory.steady import steady_death_point, steady_friction
from dryfriction.theory.trap import Trap


def _sum_force(snap: dict[str, np.ndarray], lam: float, alpha: float) -> float:
    """Friction from a snapshot (exact creep law, NumPy trap functions): ``sum f/(lam H0)``."""
    return float(snap["force"].sum() / (lam * Trap(alpha).H0))


def test_rest_state_is_eq25_and_balanced() -> None:
    lam = 400.0
    e = Ensemble(TrapModel(eps=0.04), Track(lam), Initial("rest"))
    o = e.observe()
    # (+) on [-1, 0), (-) on [0, 1]: 2 lam traps whose forces cancel pairwise (even potential)
    assert o.n_active == 2 * lam
    assert abs(o.force) < 1e-12
    snap = e.snapshot()
    assert np.all(snap["p"][snap["branch"] > 0] < 0) and np.all(snap["p"][snap["branch"] < 0] > 0)
    # ageing at fixed X: every trap ages, none changes state, the force stays balanced
    o2 = e.advance(0.0, 1000.0)
    assert o2.n_active == o.n_active and o2.births == 0 and o2.spinodal == 0
    assert abs(o2.force) < 1e-12
    assert o2.mean_age == pytest.approx(1000.0, rel=1e-14)


@pytest.mark.parametrize("f_w", [0.3, 0.7])
def test_loaded_state_carries_its_force(f_w: float) -> None:
    # the discrete population converges to the continuum force f_w at rate 1/lambda
    errs = []
    for lam in (250.0, 1000.0):
        e = Ensemble(TrapModel(eps=0.0), Track(lam), Initial("loaded", force=f_w))
        errs.append(abs(e.observe().force - f_w))
    assert errs[1] < 2e-3
    assert errs[1] < errs[0] or errs[1] < 1e-6
    edge = loaded_edge(TrapModel(), f_w)
    assert float(fresh_force(TrapModel(), edge)) == pytest.approx(f_w, abs=1e-12)


def test_kernel_agrees_with_exact_functions_eyring_nabarro() -> None:
    """The compiled kernel (tabulated a_r, inline f_+) against NumPy + the exact creep law."""
    lam = 300.0
    model = TrapModel(eps=0.05, creep="eyring-nabarro")
    e = Ensemble(model, Track(lam), Initial("steady", velocity=0.1), age_horizon=1e4)
    for x, t in [(0.3, 3.0), (0.3, 2000.0), (1.7, 2010.0)]:
        o = e.advance(x, t)
        assert o.force == pytest.approx(_sum_force(e.snapshot(), lam, model.alpha), abs=1e-11)


def test_log_table_equals_closed_form(monkeypatch: pytest.MonkeyPatch) -> None:
    """The Hermite table is exact for the log law (a_r^2 linear in ln(1 + age))."""
    model = TrapModel(eps=0.04)
    prog = [(1.0, 1.0), (1.0, 50.0), (3.5, 51.0)]
    runs = []
    for table in (False, True):
        monkeypatch.setattr(kernel, "_FORCE_TABLE", table)
        e = Ensemble(model, Track(200.0), Initial("rest"))
        runs.append([e.advance(x, t).force for x, t in prog])
    np.testing.assert_allclose(runs[0], runs[1], rtol=0, atol=1e-13)


def test_radius_table_is_eq17_for_the_log_law(monkeypatch: pytest.MonkeyPatch) -> None:
    """Closed form by default; when forced, a table of a_r^2 = 1 + eps u (eq. 17) and eps."""
    law = TrapModel(eps=0.04).law
    h, s_tab, _, cover = kernel.radius_table(law, 500.0)
    assert h < 0 and s_tab[0] == 0.04 and cover >= 500.0
    monkeypatch.setattr(kernel, "_FORCE_TABLE", True)
    h, s_tab, ds_tab, cover = kernel.radius_table(law, 500.0)
    u = h * np.arange(len(s_tab))
    assert h > 0 and np.expm1(u[-1]) == pytest.approx(cover) and cover >= 500.0
    np.testing.assert_allclose(s_tab, 1.0 + 0.04 * u, rtol=1e-14)
    np.testing.assert_allclose(ds_tab, 0.04, rtol=1e-12)


def test_radius_table_slope_is_the_derivative_in_u() -> None:
    """The Hermite slopes are d(a_r^2)/du of the tabulated values (chain rule through the age)."""
    law = TrapModel(eps=0.04, creep="eyring-nabarro").law
    h, s_tab, ds_tab, cover = kernel.radius_table(law, 1e3)
    u = h * np.arange(len(s_tab))
    np.testing.assert_allclose(s_tab, law.radius(np.expm1(u)) ** 2, rtol=1e-12)
    # centred differences are O(h^2) accurate: h ~ 2e-3 here
    np.testing.assert_allclose(np.gradient(s_tab, h)[1:-1], ds_tab[1:-1], rtol=1e-4)
    assert cover >= 1e3


def test_public_views_of_the_ensemble() -> None:
    """force_scale is 1/(lambda H0) (eq. 12), y_c the trap's, oldest_birth the oldest trap's."""
    lam, alpha, u = 300.0, 0.2, 0.5
    trap = Trap(alpha)
    e = Ensemble(TrapModel(alpha=alpha, eps=0.04), Track(lam), Initial("steady", velocity=u))
    assert e.force_scale == pytest.approx(1.0 / (lam * trap.H0), rel=1e-15)
    assert e.y_c == trap.y_c
    snap = e.snapshot()
    assert e.oldest_birth == pytest.approx(-snap["age"].max(), rel=1e-15) and e.oldest_birth < 0
    assert e.observe().force == pytest.approx(snap["force"].sum() * e.force_scale, abs=1e-12)
    rest = Ensemble(TrapModel(alpha=alpha, eps=0.04), Track(lam), Initial("rest"))
    rest.advance(0.5, 10.0)
    assert rest.oldest_birth == 0.0


@pytest.mark.parametrize("u", [0.01, 1.0, 100.0])
def test_steady_initial_state_matches_eq34(u: float) -> None:
    """The steady population's lattice average is eq. 34; its extent is eq. 32."""
    lam = 500.0
    e = Ensemble(TrapModel(eps=0.04), Track(lam), Initial("steady", velocity=u))
    m = 16
    f = []
    for k in range(m):  # average over one lattice period, frozen-age probes
        f.append(e.probe(k / (m * lam)).force)
    # probes at frozen ages shift the population rigidly; their period average differs from
    # eq. 34 only by the slip 1/lam of ageing ignored (checked at the level below)
    assert np.mean(f) == pytest.approx(float(steady_friction(TrapModel(eps=0.04), u)), rel=2e-3)
    snap = e.snapshot()
    p_d = float(steady_death_point(TrapModel(eps=0.04), u))
    assert snap["p"].max() <= p_d + 1e-12
    assert snap["p"].max() > p_d - 1.0 / lam


def test_strong_pinning_steady_state_uses_minus_branch() -> None:
    alpha = 0.3  # strong pinning: y_c < 1
    trap = Trap(alpha)
    assert trap.y_c < 1
    e = Ensemble(TrapModel(alpha=alpha, eps=0.0), Track(400.0), Initial("steady", velocity=1.0))
    st = e.state[e.lo : e.hi]
    p = e.x - e.c[e.lo : e.hi]
    assert np.all(p[st == MINUS] > trap.y_c) and np.all(p[st == MINUS] <= 1.0)
    assert np.all(p[st == PLUS] <= trap.y_c)


def test_random_track_is_reproducible_and_has_the_density() -> None:
    a = Track(100.0, "random", seed=7)
    c1 = a.positions(-3000, 5000)
    c2 = Track(100.0, "random", seed=7).positions(-1000, 2000)
    np.testing.assert_array_equal(c1[2000:5000], c2)
    assert np.all(np.diff(c1) >= 0)
    assert (len(c1) / (c1[-1] - c1[0])) == pytest.approx(100.0, rel=0.02)
    assert not np.array_equal(Track(100.0, "random", seed=8).positions(0, 100), c1[3000:3100])


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"alpha": 1.2, "eps": 0.0}, "alpha"),
        ({"eps": -0.1}, "eps"),
        ({"eps": 0.0, "creep": "power"}, "creep"),
        ({"eps": 0.0, "mu_el": 0.0}, "mu_el"),
    ],
)
def test_model_rejects_bad_parameters(kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        TrapModel(**kwargs)


def test_track_and_initial_reject_bad_input() -> None:
    with pytest.raises(ValueError, match="traps_per_a0"):
        Track(-5.0)
    with pytest.raises(ValueError, match="seed"):
        Track(10.0, "random")
    with pytest.raises(ValueError, match="initial_force"):
        Initial("loaded")
    with pytest.raises(ValueError, match="initial_force"):
        Initial("loaded", force=1.5)
    with pytest.raises(ValueError, match="initial_velocity"):
        Initial("steady", velocity=-1.0)
    with pytest.raises(ValueError, match="initial_force applies only"):
        Initial("rest", force=0.2)


@pytest.mark.parametrize("cells", [1, 2, 3])
def test_regular_lattice_sampling_does_not_alias(cells: int) -> None:
    # issue 14: a slip step every_slip = cells/lambda met the periodic (sawtooth) force of steady
    # sliding at one phase, and the sampled mean was off by 3.6e-4. The grid gets the fewest
    # extra samples that visit every phase, and the mean is eq. 34's to the lattice's
    # granular error (off-lattice sampling, e.g. 13.0/lambda, is 2e-7 off here)
    from dryfriction.ensemble.driving import Output, VelocityDrive, simulate
    from dryfriction.program import Segment, VelocityProgram

    lam, u, eps = 1000.0, 1.0, 0.04
    r = simulate(TrapModel(eps=eps), VelocityDrive(VelocityProgram([Segment(u, 3.0 / u)])),
                 Initial("steady", velocity=u, track=Track(lam)), Output(every_slip=cells / lam))
    n = round(3.0 * lam / cells)
    assert n < r.mu.size - 1 <= n + 64  # a few samples more, not a different sampling
    assert np.std(r.mu[1:]) > 1e-5  # the sawtooth is seen, not one phase of it
    assert r.summary()["mean_mu"] == pytest.approx(float(steady_friction(TrapModel(eps=eps), u)),
                                                   abs=1e-5)
