"""The pieces that turn the solver's step values into a rate-and-state result (rsf/result.py),
each against an independent route (issue 25): the Hermite interpolant on a cubic, the slip
quadrature on a velocity whose integral is known, the conditioning test on both sides of its
bound, build_result's columns from their definitions for each machine, and the summary's k_c
when the run ends on a hold."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.program import Segment, VelocityProgram
from dryfriction.rsf.law import RateState
from dryfriction.rsf.result import (
    UNITS,
    build_result,
    force_balance_is_ill_conditioned,
    hermite,
    slip_by_quadrature,
)

P = RateState(0.0061, 0.0097, 3.3e-6, 0.58, 1.7e-6)
P2 = RateState(0.0061, 0.0097, 3.3e-6, 0.58, 1.7e-6, b2=0.0023, dc2=2.9e-5)


def test_hermite_reproduces_a_cubic_and_is_right_continuous() -> None:
    T = np.array([0.0, 0.4, 1.3, 1.3, 2.05, 3.6])  # a segment boundary twice, uneven steps
    c = [0.7, -1.9, 0.45, -0.31]
    p = lambda t: c[0] + c[1] * t + c[2] * t**2 + c[3] * t**3  # noqa: E731
    dp = lambda t: c[1] + 2 * c[2] * t + 3 * c[3] * t**2  # noqa: E731
    Y, F = p(T)[:, None], dp(T)[:, None]
    te = np.array([0.0, 0.17, 0.4, 0.93, 1.3, 1.77, 2.9, 3.6])
    np.testing.assert_allclose(hermite(T, Y, F, te)[:, 0], p(te), rtol=1e-13, atol=1e-14)
    # at the repeated time the value is the later one (right-continuous)
    Y2 = Y.copy()
    Y2[3] += 0.25
    assert hermite(T, Y2, F, np.array([1.3]))[0, 0] == pytest.approx(p(1.3) + 0.25, rel=1e-14)
    # past the last step: its value held, not the cubic carried on (a row with no step after
    # it among rows with one)
    got = hermite(T, Y, F, np.array([0.93, 4.27, 3.6]))[:, 0]
    assert got[1] == Y[-1, 0] and got[2] == Y[-1, 0]
    assert got[0] == pytest.approx(p(0.93), rel=1e-13)
    # far past it, or at inf: held too, without a floating-point error on the way
    with np.errstate(all="raise"):
        far = hermite(T, Y, F, np.array([1e120, np.inf, 2.9]))[:, 0]
    assert far[0] == far[1] == Y[-1, 0] and far[2] == pytest.approx(p(2.9), rel=1e-13)
    # in the step values' own type
    assert hermite(T, Y.astype(np.float32), F.astype(np.float32), te).dtype == np.float32


def test_slip_quadrature_of_an_exponential_velocity() -> None:
    """``ln V = c0 + c1 t`` (its Hermite interpolant is exact):
    ``x = x0 + V0 (e^{c1 t} - 1)/c1``."""
    c0, c1, x0 = math.log(2.3e-6), 0.37, -4.1e-4
    T = np.cumsum(np.r_[0.0, np.random.default_rng(2).uniform(0.2, 1.1, 12)])
    Y = (c0 + c1 * T)[:, None]
    F = np.full_like(Y, c1)
    want = x0 + math.exp(c0) * (np.exp(c1 * T) - 1.0) / c1
    np.testing.assert_allclose(slip_by_quadrature(T, Y, F, x0), want, rtol=1e-11, atol=0)


def test_force_balance_conditioning_on_both_sides_of_its_bound() -> None:
    rtol, stress, travel = 3e-7, 0.61, 2.2e-4
    err = rtol * (P2.a + P2.b + P2.b2) + 4.0 * np.finfo(float).eps * stress
    k_edge = err / (rtol * (travel + P2.dc))  # the force route loses as much as the quadrature
    assert force_balance_is_ill_conditioned(P2, 0.99 * k_edge, rtol, stress, travel)
    assert not force_balance_is_ill_conditioned(P2, 1.01 * k_edge, rtol, stress, travel)
    # where the rounding of the stress dominates (the finest rtol, a large stress of either
    # sign): its size counts, not its sign
    rtol, stress = 1e-13, -5.0
    err = rtol * (P2.a + P2.b + P2.b2) + 4.0 * np.finfo(float).eps * abs(stress)
    k_edge = err / (rtol * (travel + P2.dc))
    assert force_balance_is_ill_conditioned(P2, 0.99 * k_edge, rtol, stress, -travel)
    assert not force_balance_is_ill_conditioned(P2, 1.01 * k_edge, rtol, stress, -travel)
    assert not force_balance_is_ill_conditioned(P2, math.inf, rtol, stress, travel)


PROG = VelocityProgram([Segment(2.1e-6, 3.0), Segment(7.3e-6, 2.0)], x0=1.5e-4)
T = np.array([0.0, 1.1, 3.0, 3.0, 4.2, 5.0])
SEG = np.array([0, 0, 0, 1, 1, 1])


def _common(res, params, k, eta, m):  # type: ignore[no-untyped-def]
    th2 = None if params.dc2 is None else res.theta2
    np.testing.assert_allclose(res.mu, params.friction(res.v, res.theta, th2), rtol=1e-15)
    np.testing.assert_allclose(res.load, PROG.position(T), rtol=1e-15)
    np.testing.assert_array_equal(res.load_velocity, [2.1e-6] * 3 + [7.3e-6] * 3)
    assert (res.stiffness, res.damping, res.mass) == (k, eta, m)
    cols = res.columns()
    assert list(cols)[:4] == ["t", "x", "v", "mu"]
    assert set(cols) <= set(UNITS) and cols["x_load"] is res.load


def test_build_result_columns_for_each_machine() -> None:
    rng = np.random.default_rng(4)
    lnv = np.log(3e-6) + 0.3 * rng.standard_normal(T.size)
    lnth = np.log(1.2) + 0.2 * rng.standard_normal((T.size, 2))
    k, eta, stress0 = 2300.0, 41.0, 0.6
    # quasi-static, two state variables: x from the force balance
    r = build_result(T, np.column_stack([lnv, lnth]), SEG, PROG, P2, kinematic=False,
                     inertial=False, stiffness=k, damping=eta, mass=0.0, rtol=1e-8,
                     stress0=stress0, stats=(7, 2, 40))
    np.testing.assert_allclose(r.v, np.exp(lnv), rtol=1e-15)
    np.testing.assert_allclose(r.theta, np.exp(lnth[:, 0]), rtol=1e-15)
    np.testing.assert_allclose(r.theta2, np.exp(lnth[:, 1]), rtol=1e-15)
    np.testing.assert_allclose(r.stress, r.mu + eta * r.v, rtol=1e-15)
    np.testing.assert_allclose(r.x, PROG.position(T) - (r.stress - stress0) / k, rtol=1e-13)
    assert (r.n_steps, r.n_rejected, r.n_rhs) == (7, 2, 40) and "theta2" in r.columns()
    _common(r, P2, k, eta, 0.0)
    # inertial, one state variable: the stress is the integrated one; x given is kept
    tau = 0.6 + 0.01 * rng.standard_normal(T.size)
    xg = np.linspace(1.5e-4, 1.9e-4, T.size)
    r = build_result(T, np.column_stack([lnv, lnth[:, 0], tau]), SEG, PROG, P, kinematic=False,
                     inertial=True, stiffness=k, damping=eta, mass=3e4, rtol=1e-8,
                     stress0=stress0, stats=(1, 0, 1), x=xg)
    np.testing.assert_array_equal(r.stress, tau)
    np.testing.assert_array_equal(r.x, xg)
    assert r.theta2 is None and "theta2" not in r.columns()
    _common(r, P, k, eta, 3e4)
    # kinematic: the slider is the load point
    r = build_result(T, lnth[:, :1], SEG, PROG, P, kinematic=True, inertial=False,
                     stiffness=math.inf, damping=0.0, mass=0.0, rtol=1e-8, stress0=stress0,
                     stats=(1, 0, 1))
    np.testing.assert_array_equal(r.v, [2.1e-6] * 3 + [7.3e-6] * 3)
    np.testing.assert_array_equal(r.x, PROG.position(T))
    _common(r, P, math.inf, 0.0, 0.0)
    assert r.critical_stiffness() is None


def test_summary_k_c_at_the_final_load_velocity_or_the_first_slip_velocity() -> None:
    hold = VelocityProgram([Segment(2.1e-6, 3.0), Segment(0.0, 2.0)])
    lnv = np.log(np.array([4.4e-6, 3e-6, 2e-6, 2e-6, 1e-7, 1e-8]))
    Y = np.column_stack([lnv, np.full(T.size, 0.3)])
    kw = {"kinematic": False, "inertial": False, "stiffness": 900.0, "damping": 310.0,
          "mass": 0.0, "rtol": 1e-8, "stress0": 0.6, "stats": (5, 1, 30)}
    r = build_result(T, Y, SEG, hold, P, **kw)
    s = r.summary()
    want = P.critical_stiffness(4.4e-6, 310.0, 0.0)  # the run ends on a hold: v[0]
    assert s["critical_stiffness_per_m"] == pytest.approx(want, rel=1e-15)
    assert (s["steps"], s["rejected_steps"], s["rhs_evaluations"]) == (5, 1, 30)
    assert (s["stiffness_per_m"], s["damping_s_per_m"], s["mass_s2_per_m"]) == (900.0, 310.0, 0.0)
    r = build_result(T, Y, SEG, PROG, P, **kw)
    assert r.summary()["critical_stiffness_per_m"] == pytest.approx(
        P.critical_stiffness(7.3e-6, 310.0, 0.0), rel=1e-15)
    r2 = build_result(T, np.column_stack([Y, Y[:, 1]]), SEG, PROG, P2, **kw)
    assert "critical_stiffness_per_m" not in r2.summary()  # no closed form: not reported
