"""Rate-and-state: the branches and edges the runs rarely reach (issue 25): the asinh's
large-argument form on both sides of its switch, the Hopf refusal at ``b = a + eta V`` itself,
the unstable-start check against its definition (the relative distance in V, theta and theta2,
the perturbation's sign), the output grid, the machine's and the solver's ranges and
defaults, each edge seen from both sides."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.program import Segment, VelocityProgram
from dryfriction.rsf.growth import NEAR_STEADY, unstable_start
from dryfriction.rsf.law import RateState, asinh_exp
from dryfriction.rsf.spring import K_MAX, RSFInitial, RSFOutput, SpringSlider
from dryfriction.rsf.stability import linear_stability

A, B, DC, MU0, V0 = 0.0047, 0.0083, 7.3e-6, 0.57, 2.3e-6
B2, DC2 = 0.0021, 4.1e-5
VL = 3.1e-6


def test_asinh_exp_on_both_sides_of_its_large_argument_switch() -> None:
    """Against ``arcsinh(exp(x))`` where that is finite (the switch at 20 moved down to a few
    would be off by ~z^-4), and ``x + ln 2`` beyond overflow."""
    x = np.array([-35.0, -2.3, 0.0, 0.7, 3.1, 4.6, 8.9, 19.7, 20.3, 41.0, 690.0])
    np.testing.assert_allclose(asinh_exp(x), np.arcsinh(np.exp(x)), rtol=1e-15, atol=0)
    assert float(asinh_exp(1e4)) == pytest.approx(1e4 + math.log(2.0), rel=1e-15)
    assert np.isfinite(asinh_exp(1e6))


def test_hopf_frequency_refused_at_b_equal_to_a_plus_eta_v() -> None:
    # exact binary fractions: a + eta V = 0.25 + 1.0 * 0.5 = 0.75 = b
    p = RateState(0.25, 0.75, 0.125, 0.5, 1.0)
    with pytest.raises(ValueError, match=r"b = 0.75 <= a \+ eta V = 0.75: steady sliding is "
                                         "stable at any stiffness"):
        p.hopf_frequency(0.5, damping=1.0)
    w = p.hopf_frequency(0.5, damping=0.9375)  # a' = 0.71875
    assert w == pytest.approx(0.5 / 0.125 * math.sqrt((0.75 - 0.71875) / 0.71875), rel=1e-15)


def _drive(model: RateState, factor: float, **kw: float) -> SpringSlider:
    return SpringSlider([Segment(VL, 30.0)], stiffness=factor * (model.b - model.a) / model.dc,
                        **kw)


def test_unstable_start_against_its_definition() -> None:
    """Started within NEAR_STEADY (1e-3, in ln V and ln theta_i) of the load velocity's steady
    state on a spring below k_c: the growth rate is the rightmost eigenvalue and the
    perturbation ``v/V - 1``; beyond that distance in any one variable, or on a stable spring,
    no report."""
    p = RateState(A, B, DC, MU0, V0)
    drive = _drive(p, 0.6)
    th = DC / VL
    assert NEAR_STEADY == 1e-3
    info = unstable_start(p, drive, VL * (1 - 4e-4), th, None)
    assert info is not None
    want = float(np.max(linear_stability(p, VL, drive.stiffness).real))
    assert want > 0
    assert info["growth_rate_per_s"] == pytest.approx(want, rel=1e-12)
    assert info["perturbation"] == pytest.approx(-4e-4, rel=1e-9)  # below the load velocity
    assert info["load_velocity"] == VL
    inside, outside = math.exp(0.99e-3), math.exp(1.01e-3)
    assert unstable_start(p, drive, VL * inside, th, None) is not None
    assert unstable_start(p, drive, VL / outside, th, None) is None
    assert unstable_start(p, drive, VL, th / inside, None) is not None
    assert unstable_start(p, drive, VL, th * outside, None) is None  # the state too far
    assert unstable_start(p, _drive(p, 1.7), VL, th, None) is None  # stable spring
    # two state variables: the second one's own Dc2 sets its steady state
    p2 = RateState(A, B, DC, MU0, V0, b2=B2, dc2=DC2)
    d2 = _drive(p2, 0.5)
    assert unstable_start(p2, d2, VL, th, DC2 / VL * inside) is not None
    assert unstable_start(p2, d2, VL, th, DC2 / VL * outside) is None


def test_output_grid_and_solver_defaults() -> None:
    prog = VelocityProgram([Segment(VL, 2.2), Segment(2 * VL, 2.8)])
    t = RSFOutput(every=0.7).times(prog)
    # ceil(5.0 / 0.7) = 8 intervals, plus the boundary at 2.2
    want = np.union1d(np.linspace(0.0, 5.0, 9), [2.2])
    np.testing.assert_allclose(t, want, rtol=1e-15)
    # an exact multiple does not add an interval (its rounding neither)
    assert RSFOutput(every=0.5).times(prog).size == 11 + 1
    assert RSFOutput().times(prog) is None
    out = RSFOutput()
    assert (out.rtol, out.max_steps, out.every, out.t_eval) == (1e-7, 1_000_000, None, None)
    for r in (1e-13, 1e-2):
        assert RSFOutput(rtol=r).rtol == r
    for r in (0.99e-13, 1.01e-2):
        with pytest.raises(ValueError, match="rtol = "):
            RSFOutput(rtol=r)
    assert RSFOutput(max_steps=1).max_steps == 1
    for n in (0, True, 2.0):
        with pytest.raises(ValueError, match=r"max_steps = .* allowed an integer >= 1"):
            RSFOutput(max_steps=n)  # type: ignore[arg-type]


def test_machine_ranges_and_initial_defaults() -> None:
    seg = [Segment(VL, 1.0)]
    assert SpringSlider(seg, stiffness=K_MAX).stiffness == 1e15
    assert SpringSlider(seg).kinematic
    with pytest.raises(ValueError, match="stiffness = "):
        SpringSlider(seg, stiffness=1.01e15)
    p2 = RateState(A, B, DC, MU0, V0, b2=B2, dc2=DC2)
    drive = SpringSlider(seg, stiffness=900.0)
    assert RSFInitial().resolve(p2, drive) == (VL, DC / VL, DC2 / VL)
    assert RSFInitial(v=2 * VL, theta2=3.3).resolve(p2, drive) == (2 * VL, DC / (2 * VL), 3.3)
    with pytest.raises(ValueError, match="theta2_init is given but the parameters have one"):
        RSFInitial(theta2=3.3).resolve(RateState(A, B, DC, MU0, V0), drive)
    hold = SpringSlider([Segment(0.0, 1.0), Segment(VL, 1.0)], stiffness=900.0)
    with pytest.raises(ValueError, match="give v_init"):
        RSFInitial().resolve(p2, hold)
    # the spring's k_c: the closed form where it applies (with damping and mass), else None
    p = RateState(A, B, DC, MU0, V0)
    sd = SpringSlider(seg, stiffness=900.0, damping=310.0, mass=2.7e5)
    ap = A + 310.0 * VL
    assert sd.critical_stiffness(p, VL) == pytest.approx(
        (B - ap) / DC * (1 + 2.7e5 * VL**2 / (ap * DC)), rel=1e-14)
    assert sd.critical_stiffness(RateState(A, B, DC, MU0, V0, regularized=True), VL) is None
    assert sd.critical_stiffness(p2, VL) is None
    assert SpringSlider(seg).critical_stiffness(p, VL) is None
    # the kinematic machine with the standard law cannot hold (ln V); the regularised one can
    holding = SpringSlider([Segment(VL, 1.0), Segment(0.0, 1.0)])
    # the fix names the option and the protocol key (a new user read "regularized = true" as
    # a command-line word)
    with pytest.raises(ValueError, match=r"segments\[1\]\.velocity = 0 m/s is out of range.*"
                       r"use the regularized law for holds \(--regularized; regularized = "
                       r"true in a protocol's \[model\]\)$"):
        holding.check_model(p)
    holding.check_model(RateState(A, B, DC, MU0, V0, regularized=True))


def test_t_eval_within_the_program_both_ends() -> None:
    prog = VelocityProgram([Segment(VL, 2.2), Segment(2 * VL, 2.8)])
    te = RSFOutput(t_eval=[0.0, 1.3, 5.0]).times(prog)
    np.testing.assert_array_equal(te, [0.0, 1.3, 5.0])  # both ends of the program allowed
    with pytest.raises(ValueError, match=r"^t_eval = 5\.01 is out of range: allowed finite and "
                                         r">= 0 and <= 5$"):
        RSFOutput(t_eval=[1.0, 5.01]).times(prog)
    with pytest.raises(ValueError, match="^t_eval = -0.1 is out of range"):
        RSFOutput(t_eval=[-0.1, 1.0])
    with pytest.raises(ValueError, match="give at most one of every"):
        RSFOutput(every=0.5, t_eval=[1.0])
    with pytest.raises(ValueError, match="^every = 0 is out of range"):
        RSFOutput(every=0.0)


def test_unstable_start_without_a_jacobian_is_no_report(monkeypatch: pytest.MonkeyPatch) -> None:
    """Where the linearisation cannot be evaluated (a fit's trial point with ``a c + eta V =
    0`` divides by zero in the compiled right-hand side), the start is not reported instead of
    stopping the run: a new user's fit of a record of pure noise ended on a ZeroDivisionError
    here. Mistake: only ValueError and LinAlgError caught."""
    import dryfriction.rsf.growth as growth

    p = RateState(A, B, DC, MU0, V0)
    drive = _drive(p, 0.6)
    assert unstable_start(p, drive, VL, DC / VL, None) is not None

    def no_jacobian(*args: object, **kw: object) -> None:
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(growth, "linear_stability", no_jacobian)
    assert unstable_start(p, drive, VL, DC / VL, None) is None
