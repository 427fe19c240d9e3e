"""The nature of the rate-and-state Hopf point (dryfriction.analysis.rsf_hopf) against the
closed forms, the package's own solver, and direct simulation on both sides of k_c."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from dryfriction.analysis.rsf_hopf import SliderField, critical_kappa, rsf_hopf
from dryfriction.analysis.rsf_hopf_check import (
    amplitude_exponent,
    basin_threshold,
    settle_two_starts,
    settled_amplitude,
)
from dryfriction.program import Segment
from dryfriction.rsf.driving import simulate
from dryfriction.rsf.law import RateState
from dryfriction.rsf.spring import RSFInitial, RSFOutput, SpringSlider

V = 3.1e-6  # m/s; generic: not v0, not 1


def law(name: str, **kw: float) -> RateState:
    return RateState(a=0.011, b=0.016, dc=7.3e-6, mu0=0.6, v0=1.2e-6,
                     state_law=name, **kw)  # type: ignore[arg-type]


def mass_of(m: RateState, M: float) -> float:
    """Mass per unit normal force (s^2/m) of the reduced mass ``M = m V^2/Dc``."""
    return M * m.dc / V**2


@pytest.mark.parametrize("name", ["ageing", "slip", "prz"])
@pytest.mark.parametrize("eta,M", [(0.0, 0.0), (310.0, 0.0), (0.0, 0.37), (120.0, 2.3)])
def test_critical_stiffness_and_frequency_match_rice_ruina(name: str, eta: float,
                                                           M: float) -> None:
    m = law(name)
    h = rsf_hopf(m, V, eta, mass_of(m, M))
    assert h.k_c == pytest.approx(m.critical_stiffness(V, eta, mass_of(m, M)), rel=1e-10)
    assert h.frequency == pytest.approx(m.hopf_frequency(V, eta), rel=1e-9)


@pytest.mark.parametrize("name,eta,M,two", [("slip", 0.0, 0.0, False),
                                            ("ageing", 210.0, 0.41, False),
                                            ("nagata", 90.0, 0.0, False),
                                            ("prz", 0.0, 3.1, False),
                                            ("ageing", 0.0, 0.0, True)])
def test_field_follows_the_package_solver(name: str, eta: float, M: float,
                                          two: bool) -> None:
    """The reduced field integrated by SciPy against rsf.driving.simulate (its own Rosenbrock
    solver, in SI units) from a kicked start, above k_c: ``ln V`` and ``ln theta`` agree."""
    kw: dict[str, float] = {"c": 1.7} if name == "nagata" else {}
    if two:
        kw.update(b2=0.0043, dc2=2.9e-5)
    m = law(name, **kw)
    mass = mass_of(m, M)
    h = rsf_hopf(m, V, eta, mass)
    k = 1.05 * h.k_c
    fld = SliderField(m, V, eta, mass)
    tend = 20 * 2 * math.pi / h.frequency
    te = np.linspace(0.0, tend, 300)
    kick = 1.13
    r = simulate(m, SpringSlider([Segment(V, duration=tend)], k, eta, mass),
                 RSFInitial(v=kick * V), RSFOutput(t_eval=te, rtol=1e-10))
    X0 = np.zeros(fld.n)
    X0[0] = math.log(kick)
    X0[1:1 + m.n_state] = -math.log(kick)  # RSFInitial: steady state at the kicked V
    if mass:
        th2 = None if m.dc2 is None else m.dc2 / (kick * V)
        X0[-1] = (float(m.friction(kick * V, m.dc / (kick * V), th2)) + eta * kick * V
                  - float(m.steady_state_friction(V)) - eta * V) / m.a
    s = solve_ivp(lambda t, X: fld(X, k * m.dc), (0, te[-1] * V / m.dc), X0,
                  t_eval=te * V / m.dc, method="LSODA", rtol=1e-11, atol=1e-12)
    assert np.max(np.abs(s.y[0] - np.log(r.v / V))) < 1e-7
    assert np.max(np.abs(s.y[1] - np.log(r.theta * V / m.dc))) < 1e-7
    assert np.ptp(np.log(r.v / V)) > 0.1  # the run does move


@pytest.mark.parametrize("name", ["ageing", "slip"])
def test_quasistatic_ageing_and_slip_laws_are_degenerate(name: str) -> None:
    """Ranjith & Rice (1999): with the ageing law, orbits at k_c are periodic. The slip law
    gives the same (ours, found here): l1 = 0 to 1e-13 of its terms, and the return map at
    k_c is the identity to rounding at amplitudes up to 0.16 in ln V (a nonlinear centre)."""
    m = law(name)
    h = rsf_hopf(m, V)
    assert h.nature == "degenerate"
    assert abs(h.relative_l1) < 1e-12
    fld = SliderField(m, V)
    kc = critical_kappa(fld)

    def ev(t, X):  # type: ignore[no-untyped-def]
        return X[1]

    for r0 in (0.04, 0.16):
        s = solve_ivp(lambda t, X: fld(X, kc), (0, 3 * 2 * math.pi / (h.frequency * m.dc / V)),
                      [r0, 0.0], events=ev, rtol=1e-13, atol=1e-15, method="DOP853")
        back = [y[0] for t, y in zip(s.t_events[0], s.y_events[0], strict=True)
                if t > 1e-6 and y[0] > 0][0]
        assert abs(back - r0) < 1e-12


def test_prz_quasistatic_is_subcritical_and_inertia_makes_ageing_supercritical() -> None:
    assert rsf_hopf(law("prz"), V).nature == "subcritical"
    m = law("ageing")
    assert rsf_hopf(m, V, 0.0, mass_of(m, 0.1)).nature == "supercritical"
    assert rsf_hopf(m, V, 150.0).nature == "supercritical"  # radiation damping alone too


@pytest.mark.slow
def test_supercritical_amplitude_against_settled_simulations() -> None:
    """Ageing law with inertia (M = 0.1): settled cycles below k_c (two starts, 0.8 and 1.2
    times the normal form's cycle, each changing < 1e-3 over 50 periods and ending within
    2e-3 of each other after >= 6 relaxation times), exponent 1/2 and the normal form's
    coefficient (measured 1.0017, 1.0038, 1.0081 at d = 0.005, 0.01, 0.02: the next order,
    linear in d, extrapolating to 0.9996 at d = 0).

    The mistake this is for: a run judged settled on its change over 50 periods alone, which a
    slow relaxation meets long before arriving (1/(2 beta) = 650 periods at d = 0.005: a
    start 20 % low ended 1.6 % low, changing by 1.4e-3 over 50 periods, after 4 relaxation
    times); the answer then echoes the start."""
    m = law("ageing")
    mass = mass_of(m, 0.1)
    h = rsf_hopf(m, V, 0.0, mass)
    rows = [settled_amplitude(m, h, d, mass=mass) for d in (0.005, 0.01, 0.02)]
    assert all(r["settled"] and r["spread"] < 2e-3 and r["relaxations"] >= 6 for r in rows)
    beta, err, _ = amplitude_exponent(rows)
    assert abs(beta - 0.5) < 0.01 and err < 0.005
    ratios = [r["amplitude"] / (h.amp_coef * math.sqrt(r["distance"])) for r in rows]
    assert ratios[0] == pytest.approx(1.0, abs=0.004)
    # the departure from the normal form is the next order: linear in d, vanishing at d = 0
    slope = (ratios[2] - ratios[0]) / 0.015
    assert 0 < slope < 1 and abs(ratios[0] - 0.005 * slope - 1) < 1.5e-3


def test_two_starts_settle_a_slow_relaxation_not_its_start() -> None:
    """The settling rule on the normal form's own amplitude law, ``a' = beta a (1 - a^2)``
    (exact solution, relaxation time 3000 periods, given as unknown): both starts (0.8 and
    1.2) must arrive, not only slow down. The mistake this is for: settled on the change over
    50 periods alone, which the run from below meets ~2 % short of the cycle (change ~ offset
    x 50/3000)."""
    R = 3000.0
    calls: list[int] = []

    def run(a0: float, periods: int) -> np.ndarray:
        calls.append(periods)
        k = np.arange(1, periods + 1)
        return 1 / np.sqrt(1 + (1 / a0**2 - 1) * np.exp(-k / R))

    r = settle_two_starts(run, 1.0, 0.0, 200_000)
    assert r["settled"] and r["spread"] < 2e-3 and r["change"] < 1e-3
    assert r["amplitude"] == pytest.approx(1.0, abs=2e-4)
    assert calls[:2] == [200, 200] and r["periods"] == calls[-1] > 4 * R
    # given the relaxation time, the first run is already 6 of them long
    calls.clear()
    r = settle_two_starts(run, 1.0, R, 200_000)
    assert calls[0] == 6 * R and r["settled"]
    # the cap is reported, not passed off as settled
    assert not settle_two_starts(run, 1.0, 0.0, 1600)["settled"]


def test_subcritical_unstable_cycle_by_bisection() -> None:
    """PRZ law, quasi-static: above k_c the basin's edge is the unstable cycle, of the
    normal form's amplitude, on a branch ~ sqrt(d) (measured at V = 3e-6 m/s: ratios 1.004,
    1.010, 1.021 at d = 0.005, 0.01, 0.02, extrapolating to 0.998 at d = 0; exponent
    0.512 +- 0.002, the next order). The mistakes this is for: the amplitude read from the
    kick (state steady: off the cycle, half its size) or from a growing run; a threshold that
    does not shrink with d (the slip law's, below) passing for a Hopf point's."""
    m = law("prz")
    h = rsf_hopf(m, V)
    rows = [basin_threshold(m, h, d) for d in (0.005, 0.01, 0.02)]
    assert all(r["delta_hi"] - r["delta_lo"] < 1e-3 for r in rows)
    ratios = [r["amplitude"] / (h.amp_coef * math.sqrt(r["distance"])) for r in rows]
    assert ratios[1] == pytest.approx(1.0, rel=0.03)
    beta, err, _ = amplitude_exponent(rows)
    assert abs(beta - 0.5) < 0.03 and err < 0.01
    slope = (ratios[2] - ratios[0]) / 0.015
    assert abs(ratios[0] - 0.005 * slope - 1) < 5e-3


def test_ageing_above_kc_decays_from_every_kick() -> None:
    m = law("ageing")
    r = basin_threshold(m, rsf_hopf(m, V), 0.01, delta_max=2.0)
    assert math.isnan(r["delta_hi"])


@pytest.mark.slow
def test_slip_law_threshold_stays_finite_at_kc() -> None:
    """Gu et al. (1984): with the slip law, large enough kicks run away above k_c. The
    threshold does not shrink as k -> k_c (a subcritical Hopf point's would, as sqrt(d)):
    the instability is global, not the local cycle of a Hopf point."""
    m = law("slip")
    h = rsf_hopf(m, V)
    near, far = (basin_threshold(m, h, d)["delta_lo"] for d in (0.0025, 0.04))
    assert 0.5 < near < far < 1.5
    assert near > 0.9 * far  # sqrt(d) would give near = far/4


@pytest.mark.parametrize("name,power", [("ageing", lambda m: 1.0),
                                        ("slip", lambda m: m.b / m.a)])
def test_quasistatic_centre_has_an_integrating_factor(name: str, power) -> None:  # type: ignore[no-untyped-def]
    """Why the two laws are degenerate (ours, by hand): at ``kappa_c = b - a`` the
    quasi-static field ``F = (x', y')`` times ``exp(p y)`` is divergence-free, ``p = 1``
    (ageing) or ``b/a`` (slip), so the flow is area-preserving in a weighted sense, a
    Hamiltonian system: a nonlinear centre. Checked on the field, at generic points, by
    central differences; off ``kappa_c`` the divergence is not zero."""
    m = law(name)
    fld = SliderField(m, V)
    kc = critical_kappa(fld)
    p = power(m)

    def div(X, kappa: float, h: float = 1e-5) -> float:  # type: ignore[no-untyped-def]
        def g(Y):  # type: ignore[no-untyped-def]
            return math.exp(p * Y[1]) * fld(np.asarray(Y), kappa)
        dx = (g([X[0] + h, X[1]])[0] - g([X[0] - h, X[1]])[0]) / (2 * h)
        dy = (g([X[0], X[1] + h])[1] - g([X[0], X[1] - h])[1]) / (2 * h)
        return float(dx + dy)

    for X in ([0.31, -0.17], [-0.42, 0.23], [0.7, 0.55]):
        scale = abs(math.exp(p * X[1]) * fld(np.asarray(X), kc)).max()
        assert abs(div(X, kc)) < 1e-8 * scale
        assert abs(div(X, 1.1 * kc)) > 1e-3 * scale
