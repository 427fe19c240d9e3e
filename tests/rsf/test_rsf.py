"""Rate-and-state friction: closed forms, limits and a tight-tolerance reference integration.

Parameters follow the classic laboratory case (rsfmodel's README example; Marone 1998):
``a = 0.005, b = 0.01, Dc = 10 um, mu0 = 0.6, V0 = 1 um/s``, so ``k_c = (b - a)/Dc = 500 /m``.
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

from dryfriction.program import Segment, VelocityProgram
from dryfriction.rsf.driving import (
    RSFInitial,
    RSFOutput,
    SolverError,
    SpringSlider,
    linear_stability,
    simulate,
    simulate_rsf,
)
from dryfriction.rsf.law import RateState
from rsf_reference import reference_run

A, B, DC, MU0, V0 = 0.005, 0.01, 1e-5, 0.6, 1e-6


def lab(law: str = "ageing", **kw: object) -> RateState:
    return RateState(A, B, DC, MU0, V0, state_law=law, **kw)  # type: ignore[arg-type]


# ----------------------------------------------------------------------------- the laws
def test_steady_state_closed_form() -> None:
    """mu_ss = mu0 + (a - b - b2) ln(V/V0) at theta_i = Dc_i/V (Ruina 1983)."""
    v = np.logspace(-9, 0, 19)
    p = lab()
    assert np.allclose(p.friction(v, DC / v), MU0 + (A - B) * np.log(v / V0), rtol=0, atol=1e-14)
    p2 = lab(b2=0.004, dc2=1e-3)
    mu = p2.friction(v, DC / v, 1e-3 / v)
    assert np.allclose(mu, MU0 + (A - B - 0.004) * np.log(v / V0), rtol=0, atol=1e-14)
    assert np.allclose(p2.steady_state_friction(v), mu, rtol=0, atol=1e-14)


def test_regularised_matches_standard_away_from_zero() -> None:
    """asinh form = standard form + O(a/(4 z^2)), z = V/(2V0) e^{Psi/a} (Rice et al. 2001)."""
    v = np.logspace(-9, 0, 10)
    p, r = lab(), lab(regularized=True)
    th = DC / v
    z = v / (2 * V0) * np.exp((MU0 + B * np.log(V0 * th / DC)) / A)
    assert np.all(np.abs(r.friction(v, th) - p.friction(v, th)) <= A / (4 * z**2) * 1.01 + 1e-15)
    # odd in V and zero at rest
    assert r.friction(0.0, 1.0) == 0.0
    assert r.friction(-1e-6, 3.0) == pytest.approx(-r.friction(1e-6, 3.0), rel=1e-15)


def test_constant_velocity_from_steady_state_stays() -> None:
    p = lab("slip")
    r = simulate(p, SpringSlider([Segment(3e-6, 50.0)], stiffness=300.0),
                 output=RSFOutput(rtol=1e-10))
    assert np.max(np.abs(r.mu - p.steady_state_friction(3e-6))) < 1e-13
    assert np.allclose(r.x, r.load, rtol=0, atol=1e-15)


# ----------------------------------------------------------------------------- kinematic
@pytest.mark.parametrize("two_state", [False, True])
def test_ageing_theta_at_constant_velocity(two_state: bool) -> None:
    """theta = Dc/V + (theta0 - Dc/V) exp(-V t/Dc) (Dieterich 1979), per state variable."""
    v, th0 = 2e-6, 40.0
    kw = {"b2": 0.003, "dc2": 1e-4} if two_state else {}
    p = lab(**kw)
    te = np.linspace(0.0, 200.0, 401)
    r = simulate(p, SpringSlider([Segment(v, 200.0)]),
                 RSFInitial(theta=th0, theta2=7.0 if two_state else None),
                 RSFOutput(rtol=1e-11, t_eval=te))
    exact = DC / v + (th0 - DC / v) * np.exp(-v * te / DC)
    assert np.max(np.abs(r.theta / exact - 1)) < 1e-9
    if two_state:
        exact2 = 1e-4 / v + (7.0 - 1e-4 / v) * np.exp(-v * te / 1e-4)
        assert r.theta2 is not None
        assert np.max(np.abs(r.theta2 / exact2 - 1)) < 1e-9


def test_slip_law_velocity_step_kinematic() -> None:
    """Infinitely stiff step V1 -> V2 (Ruina 1983): jump a ln(V2/V1), then
    mu - mu_ss(V2) = b ln(V2/V1) exp(-slip/Dc), an exact exponential in slip."""
    v1, v2 = 1e-6, 1e-5
    p = lab("slip")
    prog = VelocityProgram([Segment(v1, 10.0), Segment(v2, slip=10 * DC)])
    te = np.linspace(10.0, prog.total_time, 301)
    r = simulate(p, SpringSlider(prog), output=RSFOutput(rtol=1e-11, t_eval=te))
    slip = v2 * (te - 10.0)
    exact = p.steady_state_friction(v2) + B * math.log(v2 / v1) * np.exp(-slip / DC)
    assert np.max(np.abs(r.mu - exact)) < 1e-11
    jump = r.mu[0] - p.steady_state_friction(v1)
    assert jump == pytest.approx(A * math.log(v2 / v1), abs=1e-12)


def test_ageing_law_velocity_step_kinematic() -> None:
    v1, v2 = 1e-6, 1e-5
    p = lab("ageing")
    te = np.linspace(10.0, 30.0, 201)
    r = simulate(p, SpringSlider([Segment(v1, 10.0), Segment(v2, 20.0)]),
                 output=RSFOutput(rtol=1e-11, t_eval=te))
    th = DC / v2 + (DC / v1 - DC / v2) * np.exp(-v2 * (te - 10.0) / DC)
    exact = MU0 + A * math.log(v2 / V0) + B * np.log(V0 * th / DC)
    assert np.max(np.abs(r.mu - exact)) < 1e-11


@pytest.mark.parametrize("law", ["ageing", "slip"])
def test_kinematic_slide_hold_slide(law: str) -> None:
    """Regularised law, hold at V = 0: the ageing law heals by b ln(1 + V t_h/Dc) (theta grows
    by t_h; Dieterich 1979), the slip law not at all (no evolution without slip; Ruina 1983)."""
    p = lab(law, regularized=True)
    v = 1e-5
    for th in (10.0, 1000.0):
        r = simulate(p, SpringSlider([Segment(v, 5.0), Segment(0.0, th), Segment(v, 5.0)]),
                     output=RSFOutput(rtol=1e-11))
        i = np.searchsorted(r.t, 5.0 + th, side="right") - 1  # start of the reload
        heal = r.mu[i] - p.steady_state_friction(v)
        expect = B * math.log(1 + v * th / DC) if law == "ageing" else 0.0
        assert heal == pytest.approx(expect, abs=1e-10)
        assert np.all(r.mu[(r.t > 5.0) & (r.t < 5.0 + th)] == 0.0)  # asinh(0) at rest


# ----------------------------------------------------------------------------- stiff spring
def test_velocity_step_peak_tends_to_direct_effect() -> None:
    """For k -> inf the peak after a step approaches the direct effect a ln(V2/V1). The
    shortfall is (C + D ln k)/k (ours: loading the spring takes a slip ~ a ln(V2/V1)/k, over
    which the slip law evolves the state at a rate ~ ln(V theta/Dc)/Dc), so k * shortfall
    grows by a constant D ln 10 per decade of k."""
    v1, v2 = 1e-6, 1e-5
    p = lab("slip")
    direct = A * math.log(v2 / v1)
    ks = (1e6, 1e7, 1e8)
    short = []
    for k in ks:
        te = np.linspace(10.0, 10.0 + 40 * (direct / k) / v2, 2001)
        r = simulate(p, SpringSlider([Segment(v1, 10.0), Segment(v2, 10.0)], stiffness=k),
                     output=RSFOutput(rtol=1e-11, t_eval=te))
        short.append(direct - (r.mu.max() - p.steady_state_friction(v1)))
    assert 0 < short[2] < short[1] < short[0]
    assert short[2] / direct < 1e-3
    ks_short = [k * s for k, s in zip(ks, short, strict=True)]
    assert ks_short[2] - ks_short[1] == pytest.approx(ks_short[1] - ks_short[0], rel=0.05)


def test_slide_hold_slide_healing_rate_is_b() -> None:
    """Ageing law, spring machine: the peak on reload grows like b ln(t_h) at long holds
    (Beeler, Tullis & Weeks 1994; Marone 1998)."""
    p = lab("ageing")
    v = 1e-5
    peaks = []
    for th in (1e3, 1e4):
        prog = [Segment(v, slip=1e-4), Segment(0.0, th), Segment(v, slip=2e-4)]
        r = simulate(p, SpringSlider(prog, stiffness=1e3), output=RSFOutput(rtol=1e-9))
        peaks.append(r.mu[r.t > 10.0 + th].max())
    assert (peaks[1] - peaks[0]) / math.log(10) == pytest.approx(B, rel=0.01)


# ----------------------------------------------------------------------------- stability
def eig_closed_form(p: RateState, v: float, k: float, eta: float = 0.0,
                    m: float = 0.0) -> np.ndarray:
    """Eigenvalues (1/s) of the linearised spring slider (Rice & Ruina 1983), time scaled by
    Dc/V: quasi-static [[(b-kDc)/a', b/a'], [-1, -1]]; with inertia the cubic
    m~ l^3 + (m~ + a') l^2 + (a' - b + kDc) l + kDc = 0, m~ = m V^2/Dc, a' = a + eta V."""
    ap, kap = p.a + eta * v, k * p.dc
    if m == 0.0:
        lam = np.linalg.eigvals(np.array([[(p.b - kap) / ap, p.b / ap], [-1.0, -1.0]]))
    else:
        mt = m * v * v / p.dc
        lam = np.roots([mt, mt + ap, ap - p.b + kap, kap])
    return np.sort_complex(lam * v / p.dc)


@pytest.mark.parametrize("law", ["ageing", "slip"])
@pytest.mark.parametrize(("k", "eta", "m"), [(300.0, 0, 0), (700.0, 0, 0), (200.0, 400.0, 0),
                                             (600.0, 0, 5e6), (900.0, 100.0, 2e7)])
def test_linear_stability_closed_form(law: str, k: float, eta: float, m: float) -> None:
    p = lab(law)
    v = 1e-6
    got = np.sort_complex(linear_stability(p, v, k, eta, m))
    exp = eig_closed_form(p, v, k, eta, m)
    scale = np.max(np.abs(exp))
    assert len(got) == len(exp)
    assert np.max(np.abs(got - exp)) < 1e-10 * scale


def test_critical_stiffness_and_hopf_frequency() -> None:
    p = lab()
    v = 1e-6
    assert p.critical_stiffness() == pytest.approx((B - A) / DC, rel=1e-15)
    for eta, m in [(0.0, 0.0), (1000.0, 0.0), (0.0, 1e7), (500.0, 3e6)]:
        kc = p.critical_stiffness(v, eta, m)
        assert np.max(linear_stability(p, v, kc * 0.999, eta, m).real) > 0
        assert np.max(linear_stability(p, v, kc * 1.001, eta, m).real) < 0
        lam = linear_stability(p, v, kc, eta, m)
        w = np.max(lam.imag)
        assert w == pytest.approx(p.hopf_frequency(v, eta), rel=1e-9)


def _crossings(t: np.ndarray, u: np.ndarray) -> np.ndarray:
    i = np.where((u[:-1] < 0) & (u[1:] >= 0))[0]
    return t[i] - u[i] * (t[i + 1] - t[i]) / (u[i + 1] - u[i])


@pytest.mark.parametrize("law", ["ageing", "slip"])
@pytest.mark.parametrize("kfac", [0.97, 1.0, 1.05])
def test_small_oscillations_follow_linear_theory(law: str, kfac: float) -> None:
    """A 1e-4 kick from steady state oscillates at Im(lambda) and grows at Re(lambda)."""
    p = lab(law)
    v = 1e-6
    k = kfac * p.critical_stiffness()
    lam = eig_closed_form(p, v, k)[-1]
    period = 2 * math.pi / lam.imag
    te = np.linspace(0.0, 6 * period, 6001)
    r = simulate(p, SpringSlider([Segment(v, te[-1])], stiffness=k),
                 RSFInitial(v=v * (1 + 1e-4)),
                 RSFOutput(rtol=1e-11, t_eval=te))
    u = np.log(r.v / v)
    tc = _crossings(te, u)
    assert np.diff(tc) == pytest.approx(period, rel=2e-4)
    # amplitude of successive maxima: ratio exp(Re(lambda) T)
    peaks = [u[(te >= a) & (te < b)].max() for a, b in zip(tc[:-1], tc[1:], strict=True)]
    rate = np.log(peaks[-1] / peaks[0]) / ((len(peaks) - 1) * np.mean(np.diff(tc)))
    assert rate == pytest.approx(lam.real, abs=2e-3 * lam.imag)


# ----------------------------------------------------------------------------- stick-slip
def test_quasistatic_runaway_is_a_clear_error() -> None:
    """Below k_c without radiation damping the quasi-static slider has no finite-velocity
    solution (rsfmodel diverges here): a SolverError that says so, never NaNs."""
    p = lab()
    with pytest.raises(SolverError, match="runs away"):
        simulate(p, SpringSlider([Segment(1e-6, 1000.0)], stiffness=250.0),
                 RSFInitial(v=1.01e-6))


@pytest.mark.parametrize("law", ["ageing", "slip"])
def test_damped_stick_slip_is_finite_and_periodic(law: str) -> None:
    """Radiation damping (eta/sigma = 0.5 s/m ~ G/(2 c_s sigma) for a lab granite at 10 MPa)
    turns the runaway into finite, periodic events whose period converges with rtol."""
    p = lab(law)
    prog = [Segment(1e-5, 300.0)]
    periods = {}
    for rtol in (1e-8, 1e-10):
        r = simulate(p, SpringSlider(prog, stiffness=0.8 * p.critical_stiffness(),
                                     damping=0.5), RSFInitial(v=1.01e-5), RSFOutput(rtol=rtol))
        assert np.all(np.isfinite(r.v)) and r.v.max() < 1.0
        tc = _crossings(r.t, np.log(r.v / 1e-4))
        assert len(tc) >= 10
        per = np.diff(tc)[-5:]
        assert np.ptp(per) / per.mean() < 1e-3  # periodic limit cycle
        periods[rtol] = per.mean()
        # every event drops the stress by the same amount
        assert r.v.max() > 1e-3
    assert periods[1e-8] == pytest.approx(periods[1e-10], rel=1e-5)


# ----------------------------------------------------------------------------- reference
REF_CASES = {
    "ageing": ({"law": "ageing"}, {"stiffness": 1e3}),
    # the slip law runs away after this step at k = 1e3 (see below): a stiffer spring
    "slip": ({"law": "slip"}, {"stiffness": 5e3}),
    "two-state": ({"law": "ageing", "b2": 0.004, "dc2": 1e-4}, {"stiffness": 1e3}),
    "damped+inertia": ({"law": "slip"}, {"stiffness": 1e3, "damping": 200.0, "mass": 100.0}),
}


@pytest.mark.parametrize("case", list(REF_CASES))
def test_velocity_step_agrees_with_reference(case: str) -> None:
    """rsfmodel's standard case (k = 1e3 /m, 1 -> 10 um/s at 10 s, 40 s) against DOP853 at
    rtol 1e-12 in linear variables: |d mu| < 1e-9 and |d ln V| < 1e-7 at rtol = 1e-9 (measured
    ~1e-11 and ~1e-9)."""
    pk, dk = REF_CASES[case]
    law = str(pk["law"])
    extra = {k: v for k, v in pk.items() if k != "law"}
    p = RateState(A, B, DC, MU0, V0, state_law=law, **extra)  # type: ignore[arg-type]
    te = np.linspace(0.0, 40.0, 801)
    segs = [(1e-6, 10.0), (1e-5, 30.0)]
    ref = reference_run(A, B, DC, MU0, V0, law, segs, v_init=1e-6, t_eval=te, **extra,
                        **dk)  # type: ignore[arg-type]
    r = simulate(p, SpringSlider([Segment(v, d) for v, d in segs], **dk),
                 output=RSFOutput(t_eval=te, rtol=1e-9))
    assert np.max(np.abs(r.mu - ref["mu"])) < 1e-9
    assert np.max(np.abs(r.stress - ref["stress"])) < 1e-9
    assert np.max(np.abs(np.log(r.v / ref["v"]))) < 1e-7
    assert np.max(np.abs(np.log(r.theta / ref["theta"]))) < 1e-7


def test_slip_law_runaway_after_large_step_matches_reference() -> None:
    """Slip law, k = 2 k_c, step 1 -> 10 um/s without damping: the velocity diverges in finite
    time although k > k_c (Gu, Rice, Ruina & Tse 1984). Both integrations find the same time."""
    p = lab("slip")
    with pytest.raises(SolverError, match="runs away") as info:
        simulate(p, SpringSlider([Segment(1e-5, 30.0)], stiffness=1e3),
                 RSFInitial(v=1e-6),
                 RSFOutput(rtol=1e-10))
    # the reference (DOP853, rtol 1e-12, linear variables) stops at the blow-up time
    from scipy.integrate import solve_ivp

    def rhs(t: float, y: np.ndarray) -> list[float]:
        v, th = y
        om = v * th / DC
        thd = -om * math.log(om)
        return [(1e3 * (1e-5 - v) - B * thd / th) / (A / v), thd]

    ref = solve_ivp(rhs, (0.0, 30.0), [1e-6, DC / 1e-6], method="DOP853", rtol=1e-12,
                    atol=1e-300)
    assert not ref.success
    assert info.value.t == pytest.approx(ref.t[-1], rel=1e-8)
    assert info.value.v > 1e100


def test_stick_slip_agrees_with_reference() -> None:
    """100 s of damped stick-slip: event times within 5e-6 s and mu within 1e-5 at rtol 1e-9
    (errors at fixed times are dominated by the event timing)."""
    p = lab()
    k = 0.8 * p.critical_stiffness()
    te = np.linspace(0.0, 100.0, 10001)
    ref = reference_run(A, B, DC, MU0, V0, "ageing", [(1e-5, 100.0)], stiffness=k, damping=0.5,
                        v_init=1.01e-5, t_eval=te)
    r = simulate(p, SpringSlider([Segment(1e-5, 100.0)], stiffness=k, damping=0.5),
                 RSFInitial(v=1.01e-5),
                 RSFOutput(rtol=1e-9, t_eval=te))
    e_ref = _crossings(te, np.log(ref["v"] / 1e-4))
    e = _crossings(te, np.log(r.v / 1e-4))
    assert len(e) == len(e_ref) >= 4
    assert np.max(np.abs(e - e_ref)) < 5e-6
    assert np.max(np.abs(r.mu - ref["mu"])) < 1e-5


def test_regularised_run_matches_standard_run() -> None:
    prog = [Segment(1e-6, 10.0), Segment(1e-5, 30.0)]
    te = np.linspace(0, 40, 81)
    a = simulate(lab(), SpringSlider(prog, stiffness=1e3),
                 output=RSFOutput(rtol=1e-10, t_eval=te))
    b = simulate(lab(regularized=True), SpringSlider(prog, stiffness=1e3),
                 output=RSFOutput(rtol=1e-10, t_eval=te))
    assert np.max(np.abs(a.mu - b.mu)) < 1e-9


# ----------------------------------------------------------------------------- API
def test_result_and_mapping_round_trip() -> None:
    p = lab("slip", b2=0.002, dc2=3e-5, regularized=True)
    assert RateState.from_mapping(p.to_dict()) == p
    q = RateState.from_mapping({"law": "rsf", "a": A, "b": B, "dc": DC, "mu0": MU0, "v0": V0})
    assert q == lab()
    r = simulate(q, SpringSlider([Segment(1e-6, 1.0)], stiffness=1e3))
    d = r.to_dict()
    assert d["params"]["a"] == A and len(d["t"]) == len(r.t)
    with pytest.raises(ValueError):
        r.mu[0] = 1.0  # read-only


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"a": 0.0}, r"a = 0 is out of range: allowed finite and > 0"),
        ({"a": -0.01}, r"a = -0.01 is out of range"),
        ({"dc": 0.0}, r"dc = 0 is out of range"),
        ({"v0": -1.0}, r"v0 = -1 is out of range"),
        ({"b": -0.1}, r"b = -0.1 is out of range: allowed finite and >= 0"),
        ({"mu0": math.nan}, r"mu0 = nan is out of range"),
        ({"state_law": "aging-ish"}, r"state_law = 'aging-ish' is not allowed"),
        ({"b2": 0.01}, r"b2 = 0.01 needs dc2"),
        ({"dc2": -1.0}, r"dc2 = -1 is out of range"),
    ],
)
def test_bad_parameters(kwargs: dict[str, object], match: str) -> None:
    base: dict[str, object] = {"a": A, "b": B, "dc": DC, "mu0": MU0, "v0": V0}
    base.update(kwargs)
    with pytest.raises(ValueError, match=match):
        RateState(**base)  # type: ignore[arg-type]


def test_bad_mapping() -> None:
    base = {"a": A, "b": B, "dc": DC, "mu0": MU0, "v0": V0}
    with pytest.raises(ValueError, match="unknown rate-and-state key.*stifness"):
        RateState.from_mapping({**base, "stifness": 1.0})
    with pytest.raises(ValueError, match="missing rate-and-state key.*dc"):
        RateState.from_mapping({k: v for k, v in base.items() if k != "dc"})
    with pytest.raises(ValueError, match="law = 'trap'"):
        RateState.from_mapping({**base, "law": "trap"})


def _segs(*pairs: tuple[float, float]) -> list[Segment]:
    return [Segment(v, d) for v, d in pairs]


ONE = _segs((1e-6, 1.0))


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (lambda: SpringSlider(ONE, stiffness=-5.0), r"stiffness = -5 is out of range"),
        (lambda: SpringSlider(ONE, stiffness=0.0), r"stiffness = 0 is out of range.*or inf"),
        (lambda: SpringSlider(ONE, 1e3, damping=-1.0), r"damping = -1 is out of range"),
        (lambda: SpringSlider(ONE, 1e3, mass=math.nan), r"mass = nan is out of range"),
        (lambda: SpringSlider(ONE, damping=0.5), r"damping = 0.5 is not allowed on the kinem"),
        (lambda: SpringSlider(ONE, mass=1.0), r"mass = 1 is not allowed on the kinematic"),
        (lambda: RSFOutput(rtol=0.5), r"rtol = 0.5 is out of range"),
        (lambda: simulate(lab(), SpringSlider(_segs((1e-6, 1.0), (0.0, 1.0)))),
         r"segments\[1\].velocity = 0 m/s .* regularized"),
        (lambda: SpringSlider(_segs((1e-6, 1.0), (-1e-6, 1.0)), stiffness=1e3),
         r"segments\[1\].velocity = -1e-06"),
        (lambda: simulate(lab(), SpringSlider(_segs((0.0, 1.0)), stiffness=1e3)),
         r"starts with load velocity 0 m/s: give v_init"),
        (lambda: RSFInitial(v=0.0), r"v_init = 0 is out of range"),
        (lambda: RSFInitial(theta=-1.0), r"theta_init = -1 is out of range"),
        (lambda: simulate(lab(), SpringSlider(ONE), RSFInitial(theta2=1.0)),
         r"theta2_init is given"),
        (lambda: simulate(lab(), SpringSlider(ONE), output=RSFOutput(t_eval=[0.5, 2.0])),
         r"t_eval = 2 is out of range"),
        (lambda: RSFOutput(max_steps=0), r"max_steps = 0 is out of range"),
        (lambda: RSFOutput(every=1.0, t_eval=[0.5]), r"at most one of every"),
        (lambda: simulate(lab(), SpringSlider(ONE), "initial"), r"is not an RSFInitial"),
    ],
)
def test_bad_driver_input(make: object, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        make()  # type: ignore[operator]


def test_old_keyword_form_still_works_and_warns() -> None:
    """The deprecated ``simulate_rsf(params, program, stiffness=...)`` gives the same run."""
    prog = _segs((1e-6, 10.0), (1e-5, 30.0))
    te = np.linspace(0.0, 40.0, 81)
    with pytest.warns(DeprecationWarning, match="SpringSlider"):
        old = simulate_rsf(lab(), prog, stiffness=1e3, v_init=1.01e-6, rtol=1e-9, t_eval=te)
    new = simulate(lab(), SpringSlider(prog, 1e3), RSFInitial(v=1.01e-6),
                   RSFOutput(t_eval=te, rtol=1e-9))
    assert np.array_equal(old.mu, new.mu) and np.array_equal(old.x, new.x)
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match="stiffness = -1"):
        simulate_rsf(lab(), prog, stiffness=-1.0)
    with pytest.raises(TypeError, match="stifness"):
        simulate_rsf(lab(), prog, stifness=1e3)


def test_step_budget_is_a_clear_error() -> None:
    with pytest.raises(SolverError, match="max_steps = 5"):
        simulate(lab(), SpringSlider([Segment(1e-6, 10.0), Segment(1e-5, 30.0)], stiffness=1e3),
                 output=RSFOutput(max_steps=5))


# ----------------------------------------------------------------------------- CLI
def test_cli_rsf_writes_whole_results(tmp_path: Path) -> None:
    import json

    from typer.testing import CliRunner

    from dryfriction.cli import app

    out = tmp_path / "res"
    runner = CliRunner()
    res = runner.invoke(app, ["rsf", "--case", "stick-slip", "--v1", "1e-5", "--t1", "100",
                              "--stiffness", "400", "--damping", "0.5", "--out", str(out),
                              "--json"])
    assert res.exit_code == 0, res.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["v_max"] > 1e-3 and summary["units"]["v"] == "m/s"  # events happened
    assert summary["law"] == "rsf" and summary["case"] == "stick-slip"
    assert (out / "rsf.png").stat().st_size > 0
    header = (out / "series.csv").read_text().splitlines()[0]
    assert header.startswith("t[s],x[m],v[m/s],mu[1],theta[s],stress[1],x_load[m],v_load[m/s]")
    # runaway without damping: one line, exit 2, the old results left untouched
    res = runner.invoke(app, ["rsf", "--case", "stick-slip", "--stiffness", "250", "--t1",
                              "1000", "--out", str(out)])
    assert res.exit_code == 2 and "runs away" in res.output
    assert json.loads((out / "summary.json").read_text()) == summary
    res = runner.invoke(app, ["rsf", "--dc", "0"])
    assert res.exit_code == 2 and "dc = 0 is out of range" in res.output


def test_bad_stiffness_gives_the_same_message_everywhere(tmp_path: Path) -> None:
    """The spring is checked in one place (rsf.spring): the API, a protocol file and a fit
    report a bad stiffness in the same words."""
    from dryfriction.fit import RSFModel
    from dryfriction.io.protocol import parse_protocol

    with pytest.raises(ValueError) as api:
        SpringSlider(ONE, stiffness=-3.0)
    with pytest.raises(ValueError) as fit_model:
        RSFModel(stiffness=-3.0)
    text = ('[model]\nlaw = "rsf"\na = 0.005\nb = 0.01\ndc = 1e-5\nmu0 = 0.6\nv0 = 1e-6\n'
            '[drive]\nkind = "spring"\nstiffness = -3.0\n'
            'segments = [{velocity = 1e-6, duration = 1.0}]\n')
    with pytest.raises(ValueError) as proto:
        parse_protocol(text, "p.toml")
    msg = str(api.value)
    assert msg.startswith("stiffness = -3 is out of range") and "inf" in msg
    assert str(fit_model.value) == msg
    assert str(proto.value) == f"p.toml: in drive: {msg}"


# ----------------------------------------------------------------------------- closed forms
@pytest.mark.parametrize("law", ["ageing", "slip"])
def test_state_rate_closed_forms(law: str) -> None:
    """Dieterich's ageing law dtheta/dt = 1 - V theta/Dc; Ruina's slip law
    -(V theta/Dc) ln(V theta/Dc); both vanish in steady state theta = Dc/V, and the slip law
    does not evolve at rest. ``dc`` selects the second state variable's slip."""
    p = lab(law, b2=0.003, dc2=1e-4)
    v = np.array([1e-7, 1e-6, 3e-5, 1e-6])
    theta = np.array([50.0, 0.4, 2.0, 10.0])
    for dc in (DC, 1e-4):
        om = v * theta / dc
        exact = 1.0 - om if law == "ageing" else -om * np.log(om)
        got = p.state_rate(v, theta) if dc == DC else p.state_rate(v, theta, dc=p.dc2)
        np.testing.assert_allclose(got, exact, rtol=1e-13, atol=0)
    np.testing.assert_allclose(p.state_rate(v, DC / v), 0.0, atol=1e-14)
    at_rest = p.state_rate(0.0, 30.0)
    assert at_rest == (1.0 if law == "ageing" else 0.0)


def test_two_state_hold_peak_matches_simulate_rsf() -> None:
    """hold_peak_friction with two state variables: both heal by t_hold at rest (ageing law).
    The reference is the kinematic simulation of the hold (regularised law, V = 0), whose
    state variables after the hold give the reload friction."""
    p = lab(b2=0.004, dc2=1e-4, regularized=True)
    v = 1e-5
    for th in (10.0, 1000.0):
        r = simulate(p, SpringSlider([Segment(v, 50.0), Segment(0.0, th), Segment(v, 5.0)]),
                     RSFInitial(theta=DC / v, theta2=1e-4 / v), RSFOutput(rtol=1e-11))
        i = np.searchsorted(r.t, 50.0 + th, side="right") - 1  # start of the reload
        assert r.theta2 is not None
        assert r.theta2[i] == pytest.approx(1e-4 / v + th, rel=1e-9)
        peak = float(p.friction(v, r.theta[i], r.theta2[i]))
        assert float(p.hold_peak_friction(th, v)) == pytest.approx(peak, abs=1e-10)
        # and the healing is the sum of both: b ln(1 + V t/Dc) + b2 ln(1 + V t/Dc2)
        heal = B * math.log1p(v * th / DC) + 0.004 * math.log1p(v * th / 1e-4)
        assert peak - float(p.steady_state_friction(v)) == pytest.approx(heal, abs=1e-9)


def test_spring_outputs_are_consistent_with_the_velocity() -> None:
    """Quasi-static damped spring slider through a velocity step: the reported position is the
    integral of the reported velocity, x(t) - x(0) = int v dt, and the spring stress balances
    friction plus radiation damping, stress = mu + eta V."""
    p = lab()
    eta = 200.0
    te = np.linspace(0.0, 60.0, 60001)
    r = simulate(p, SpringSlider([Segment(1e-6, 10.0), Segment(1e-5, 50.0)], stiffness=1e3,
                                 damping=eta), output=RSFOutput(rtol=1e-10, t_eval=te))
    np.testing.assert_allclose(r.stress, r.mu + eta * r.v, rtol=0, atol=1e-12)
    dx = np.concatenate([[0.0], np.cumsum(0.5 * (r.v[1:] + r.v[:-1]) * np.diff(r.t))])
    span = float(r.x[-1] - r.x[0])
    assert span > 4e-4  # the slider moved forward about the load point's slip
    # trapezoid error on this grid is far below 1e-6 of the slip
    np.testing.assert_allclose(r.x - r.x[0], dx, rtol=0, atol=1e-6 * span)


def _lsoda_events(a, b, dc, k, eta, vl, total, v_init):
    """Stick-slip events (upward crossings of V = 10 V_load) of the quasi-static damped spring
    slider with the ageing law, integrated by SciPy's LSODA at rtol 1e-10 in (ln V, ln theta):
    ``d ln V/dt = [k (V_l - V) - b d ln theta/dt] / (a + eta V)``."""
    from scipy.integrate import solve_ivp

    def rhs(t, y):
        v, th = math.exp(y[0]), math.exp(y[1])
        dth = 1.0 / th - v / dc
        return [(k * (vl - v) - b * dth) / (a + eta * v), dth]

    sol = solve_ivp(rhs, (0.0, total), [math.log(v_init), math.log(dc / vl)], method="LSODA",
                    rtol=1e-10, atol=1e-12, max_step=1.0)
    u = sol.y[0] - math.log(10 * vl)
    return int(np.sum((u[:-1] < 0) & (u[1:] >= 0)))


def test_start_beside_an_unstable_steady_state_grows_like_the_reference() -> None:
    # issue 14: started 1e-9 off an unstable steady state (growth +0.249 1/s) the L-stable
    # solver took one 1000 s step and reported steady sliding; the step limit tied to the
    # growth rate lets the perturbation grow into the same events as an independent solver
    a, b, dc, k, eta, vl, total = 0.005, 0.01, 1e-5, 250.0, 0.5, 1e-5, 1000.0
    p = RateState(a=a, b=b, dc=dc, mu0=0.6, v0=1e-6)
    drive = SpringSlider([Segment(vl, total)], stiffness=k, damping=eta)
    v_init = vl * (1 + 1e-9)
    with pytest.warns(RuntimeWarning, match="linearly unstable.*growth rate 0.249"):
        r = simulate(p, drive, RSFInitial(v=v_init), RSFOutput(rtol=1e-9))
    u = np.log(r.v) - math.log(10 * vl)
    events = int(np.sum((u[:-1] < 0) & (u[1:] >= 0)))
    assert events == _lsoda_events(a, b, dc, k, eta, vl, total, v_init)
    assert events > 30
    info = r.summary()["unstable_start"]
    assert info["growth_rate_per_s"] == pytest.approx(0.2493, rel=1e-3)
    assert info["perturbation"] == pytest.approx(1e-9, rel=1e-6)
    # a start away from the steady state is no news; a stable spring neither
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        simulate(p, drive, RSFInitial(v=1.01 * vl), RSFOutput(rtol=1e-6))
        stiff = SpringSlider([Segment(vl, 10.0)], stiffness=2e3, damping=eta)
        assert "unstable_start" not in simulate(p, stiff).summary()


@pytest.mark.parametrize("name", ["a", "b", "b2"])
def test_rate_and_state_parameters_bounded_above(name: str) -> None:
    # a = 1e308 used to run and report friction of 4e292: refused, naming the parameter
    from dryfriction.rsf.law import MU_MAX, RateState

    kw = {"a": 0.005, "b": 0.01, "dc": 1e-5, "mu0": 0.6, "v0": 1e-6, "b2": 0.0, "dc2": 1e-4}
    kw[name] = 1e308
    with pytest.raises(ValueError, match=rf"^{name} = .*<= {MU_MAX:g}"):
        RateState(**kw)


@pytest.mark.parametrize("segments", [[Segment(1e-6, 1e308)],
                                      [Segment(3.2e-5, 40.0), Segment(0.0, 7e11),
                                       Segment(3.2e-5, slip=1e7)]])
def test_a_program_longer_than_t_max_is_refused_before_any_work(
        segments: list[Segment]) -> None:
    # found by the run-size fuzz: a spring run of 1e308 s (b = 0, stable) took steps so long
    # that the slip's quadrature overflowed, "impossible result" instead of a refusal. The
    # second program lasts 1.0125e12 s only through its last slip (1e7 m at 32 um/s)
    from dryfriction.rsf.spring import T_MAX

    refusal = "^segments last .* allowed up to " + re.escape(f"{T_MAX:g} s") + "$"
    for k in (1e3, math.inf):
        with pytest.raises(ValueError, match=refusal):
            SpringSlider(segments, stiffness=k)


def test_a_spring_run_just_under_t_max_completes_with_its_slip() -> None:
    # the bound is not set below what runs: 0.9 T_MAX at 1.3 um/s, stiff and stable (b < a)
    from dryfriction.rsf.law import RateState
    from dryfriction.rsf.spring import T_MAX

    p = RateState(0.0071, 0.0043, 2.3e-5, 0.61, 1e-6)
    res = simulate(p, SpringSlider([Segment(1.3e-6, 0.9 * T_MAX)], stiffness=2.7e3))
    assert res.x[-1] - res.x[0] == pytest.approx(1.3e-6 * 0.9 * T_MAX, rel=1e-6)
