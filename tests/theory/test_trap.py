"""Single-trap physics (spec §1) against closed forms, quadrature and first principles."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from dryfriction.theory.trap import (
    ALPHA0,
    Regime,
    Trap,
    branch_work,
    dpsi,
    force_forward,
    force_minus,
    force_plus,
    psi,
    regime,
    work_forward,
    z_minus,
    z_plus,
    z_unstable,
)

ALPHAS = [0.01, 0.05, 0.13, ALPHA0 - 1e-9, ALPHA0 + 1e-9, 0.3, 0.6, 0.9]
alphas = st.floats(1e-3, 0.999)


def test_regimes_and_alpha0():
    # alpha0 is where y_c = 1: (1 - a)^2 = 4 a
    assert (1 - ALPHA0) ** 2 == pytest.approx(4 * ALPHA0, rel=1e-15)
    assert regime(0.13) is Regime.VERY_STRONG
    assert regime(0.2) is Regime.STRONG
    assert regime(1.0) is Regime.NONE
    assert regime(3.0) is Regime.NONE
    assert Trap(1.5).H0 == 0.0 and Trap(1.5).maxwell_jump == 0.0


@pytest.mark.parametrize("bad", [0.0, -0.1, math.nan, math.inf])
def test_bad_alpha(bad):
    with pytest.raises(ValueError, match="alpha"):
        Trap(bad)


def test_potential_shape():
    z = np.linspace(-1.5, 1.5, 3001)
    assert psi(0.0) == 1.0 and psi(1.0) == 0.0 and psi(-1.0) == 0.0
    assert np.all(psi(z) >= 0) and np.all(psi(z) == psi(-z))
    # dpsi is the derivative of psi (central differences)
    h = 1e-6
    zi = z[np.abs(np.abs(z) - 1) > 1e-3]
    np.testing.assert_allclose(dpsi(zi), (psi(zi + h) - psi(zi - h)) / (2 * h), atol=1e-7)


@pytest.mark.parametrize("alpha", ALPHAS)
def test_branches_are_stable_equilibria(alpha):
    trap = Trap(alpha)
    yc = trap.y_c
    y = np.linspace(-1, yc, 2001)
    for zfun, ys in ((z_plus, y), (z_minus, -y)):
        z = zfun(ys, alpha)
        # equilibrium: psi'(z) + 6 alpha (z - y) = 0
        np.testing.assert_allclose(dpsi(z) + 6 * alpha * (z - ys), 0.0, atol=1e-12)
        # local stability: U'' = psi''(z) + 6 alpha >= 0 (zero only at the spinodal)
        upp = -6 + 12 * np.abs(z) + 6 * alpha
        assert np.all(upp[:-1] > 0) and upp[-1] == pytest.approx(0.0, abs=1e-6)
    yu = np.linspace(-yc, yc, 2001)[1:-1]
    zu = z_unstable(yu, alpha)
    np.testing.assert_allclose(dpsi(zu) + 6 * alpha * (zu - yu), 0.0, atol=1e-12)
    assert np.all(-6 + 12 * np.abs(zu) + 6 * alpha < 0)
    # the unstable branch joins the (+) spinodal
    # sqrt branch point: a rounding of y_c moves z by ~sqrt(1e-16)
    assert z_unstable(yc, alpha) == pytest.approx(z_plus(yc, alpha), abs=1e-7)


@given(alphas, st.floats(-1, 1))
def test_branch_symmetry(alpha, t):
    y = t * min(1.0, Trap(alpha).y_c)  # where both branches exist
    assert z_minus(y, alpha) == pytest.approx(-z_plus(-y, alpha), abs=1e-14)
    assert force_minus(y, alpha) == pytest.approx(-force_plus(-y, alpha), abs=1e-14)


@pytest.mark.parametrize("alpha", ALPHAS)
def test_contact_edges_and_maxwell(alpha):
    trap = Trap(alpha)
    assert z_plus(-1.0, alpha) == pytest.approx(-1.0, abs=1e-15)
    assert force_plus(-1.0, alpha) == pytest.approx(0.0, abs=1e-14)
    assert force_minus(1.0, alpha) == pytest.approx(0.0, abs=1e-14)
    assert z_plus(trap.y_c, alpha) == pytest.approx(trap.z_c, abs=1e-7)  # sqrt branch point
    jump = force_plus(0.0, alpha) - force_minus(0.0, alpha)
    assert jump == pytest.approx(12 * alpha * (1 - alpha), rel=1e-13)
    assert trap.maxwell_jump == pytest.approx(jump, rel=1e-13)


@pytest.mark.parametrize("alpha", ALPHAS)
def test_H0_closed_form_vs_quadrature(alpha):
    trap = Trap(alpha)
    pts = [trap.y_c] if trap.y_c < 1 else None
    q, _ = quad(lambda y: force_forward(y, alpha), -1, trap.death_point, points=pts,
                epsabs=1e-14, epsrel=1e-13, limit=200)
    assert trap.H0 == pytest.approx(q, rel=1e-10)
    if alpha < ALPHA0:  # the paper's closed form (line after eq. 12) holds in its regime
        assert trap.H0 == pytest.approx(trap.H0_paper, rel=1e-13)
    q1, _ = quad(lambda y: force_forward(y, alpha), trap.y_c - 1, trap.death_point, points=pts,
                 epsabs=1e-14, epsrel=1e-13, limit=200)
    assert trap.H1 == pytest.approx(q1, rel=1e-10)


@given(alphas, st.floats(0, 1))
@settings(max_examples=60)
def test_branch_work_is_antiderivative(alpha, t):
    yc = (1 - alpha) ** 2 / (4 * alpha)
    y = -1 + t * (yc + 1)
    q, _ = quad(lambda s: force_plus(s, alpha), -1, y, epsabs=1e-13, epsrel=1e-12)
    assert branch_work(z_plus(y, alpha), alpha) == pytest.approx(q, rel=1e-9, abs=1e-12)
    assert work_forward(y, alpha) == pytest.approx(q, rel=1e-9, abs=1e-12)


def test_H0_vanishes_as_alpha_to_one():
    a = np.array([0.9, 0.99, 0.999])
    H0 = np.array([Trap(x).H0 for x in a])
    assert np.all(np.diff(H0) < 0) and H0[-1] < 1e-8
    # leading order (ours): H0 ~ c (1 - alpha)^3; the ratio settles
    ratios = H0 / (1 - a) ** 3
    assert ratios[2] == pytest.approx(ratios[1], rel=0.02)


def test_continuity_across_alpha0():
    lo, hi = Trap(ALPHA0 * (1 - 1e-10)), Trap(ALPHA0 * (1 + 1e-10))
    assert lo.regime is Regime.VERY_STRONG and hi.regime is Regime.STRONG
    for k in ("y_c", "H0", "H1", "maxwell_jump", "contact_stiffness", "death_point"):
        assert getattr(lo, k) == pytest.approx(getattr(hi, k), rel=1e-8), k


def test_contact_stiffness_is_slope_of_fresh_force():
    from dryfriction.theory.model import TrapModel
    from dryfriction.theory.static import fresh_force

    for alpha in (0.13, 0.4):
        h = 1e-7
        slope = float(fresh_force(TrapModel(alpha), h)) / h
        assert slope == pytest.approx(Trap(alpha).contact_stiffness, rel=1e-5)


@pytest.mark.parametrize("alpha", ALPHAS)
def test_largest_force_before_spinodal(alpha):
    trap = Trap(alpha)
    y = np.linspace(-1, trap.y_c, 200001)
    f = force_plus(y, alpha)
    assert f.max() == pytest.approx(trap.f_max, rel=1e-7)
    y_m = (1 - 2 * alpha) / (4 * alpha)
    assert y[np.argmax(f)] == pytest.approx(y_m, abs=1e-3 * (1 + trap.y_c))
    assert trap.f_c <= trap.f_max


def test_alpha_one_itself_does_not_pin_and_the_summary_is_the_properties() -> None:
    """alpha = 1 is the no-pinning regime's edge (Tomlinson: pinning for alpha < 1): no
    spinodal, H0 = 0, infinite contact stiffness; just below it every constant is finite.
    The summary's entries are the properties (mistake: a key reporting another one)."""
    import math

    t = Trap(1.0)
    assert not t.pinned and t.H0 == 0.0 and t.H1 == 0.0 and t.maxwell_jump == 0.0
    assert math.isnan(t.y_c) and math.isnan(t.z_c) and math.isnan(t.f_c)
    assert math.isnan(t.death_point) and t.contact_stiffness == math.inf
    below = Trap(0.999)  # H0 ~ (1 - alpha)^3: rounds to 0 much closer to 1
    assert below.pinned and below.H0 > 0.0 and math.isfinite(below.contact_stiffness)
    g = Trap(0.37)
    s = g.summary()
    for k in ("y_c", "z_c", "f_c", "f_max", "death_point", "maxwell_point", "maxwell_jump",
              "H0", "H1", "contact_stiffness"):
        assert s[k] == getattr(g, k), k
    assert s["alpha"] == 0.37 and s["alpha0"] == ALPHA0 and s["regime"] == "strong pinning"
    assert g.beta == pytest.approx(6 * 0.37, rel=1e-15)
    z = np.array([-0.9, -0.2, 0.45])
    np.testing.assert_allclose(g.energy(z, 0.3), psi(z) + 3 * 0.37 * (z - 0.3) ** 2, rtol=1e-15)
