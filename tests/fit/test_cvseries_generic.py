"""fit/cvseries.py at generic points: the scales of a fit from each set of values it may hold
(a0 and t0; vstar alone with t0 = 1 s; t0 alone with a0 = 1 m), the member's reduced v_ref,
and the start from a rate-and-state fit at a reduced velocity ``u`` other than 1 (the twin
inverted at ``u``; ``t0 = u a0/v0``)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.fit import CVModel, cv_series
from dryfriction.fit.cvseries import cv_start_from_rsf, fitted_scales, fitted_trap
from dryfriction.records.data import SeriesData
from dryfriction.theory.direct import junction_strength
from dryfriction.theory.linear_stability import effective_rsf
from dryfriction.theory.model import TrapModel
from dryfriction.theory.steady import steady_friction


def test_fitted_scales_from_each_set_of_values() -> None:
    # mistakes: vstar taken as t0's inverse (a0 = 1 m), the static branch's a0 = t0
    sc = fitted_scales({"a0": 3.2e-6, "t0": 0.45, "mu_el": 0.57})
    assert (sc.a0, sc.t0, sc.mu_el) == (3.2e-6, 0.45, 0.57)
    sc = fitted_scales({"vstar": 7.5e-6, "mu_el": 0.62})
    assert (sc.a0, sc.t0, sc.mu_el) == (7.5e-6, 1.0, 0.62)
    assert sc.velocity_scale == pytest.approx(7.5e-6, rel=1e-15)
    sc = fitted_scales({"t0": 2.7, "mu_el": 0.51})
    assert (sc.a0, sc.t0, sc.mu_el) == (1.0, 2.7, 0.51)


def test_fitted_trap_reduces_v_ref_by_the_fitted_velocity_scale() -> None:
    held = TrapModel(0.12, creep="eyring-nabarro", direct=0.02)
    m = fitted_trap(held, 1.7e-6, {"eps": 0.021, "direct": 0.013, "a0": 2.5e-6, "t0": 0.8,
                                   "mu_el": 0.55})
    # v_ref in a0/t0: 1.7e-6 m/s / (2.5e-6 m / 0.8 s) = 0.544 (mistake: times, or in m/s)
    assert m.v_ref == pytest.approx(1.7e-6 * 0.8 / 2.5e-6, rel=1e-14)
    assert (m.alpha, m.eps, m.creep, m.mu_el, m.direct) == (0.12, 0.021, "eyring-nabarro",
                                                             0.55, 0.013)
    # the athermal member keeps the held mu_el when the values have none
    assert fitted_trap(TrapModel(0.12, mu_el=0.7), 1e-6, {"eps": 0.03}).mu_el == 0.7
    with pytest.raises(ValueError, match="eps is not given"):
        fitted_trap(held, 1e-6, {"direct": 0.01})


@pytest.mark.parametrize("direct", [0.0, 0.025])
def test_start_from_rsf_inverts_the_twin_at_a_reduced_velocity_other_than_one(direct) -> None:
    # the twin of steady sliding at u = v0 t0/a0 = 0.3 (not the default 1): a = mu_el (g a_0
    # + A mu_d), b = mu_el g b_0, Dc = a0 Dc_red, mu0 = mu_el g mu_d(u). Mistakes: t0 = a0/v0
    # (u dropped), the twin taken at u = 1 whatever u
    eps, a0, mu_el, v_ref, u = 0.018, 40e-6, 0.65, 1.2e-6, 0.3
    v0 = 3e-7
    t0 = u * a0 / v0
    u_ref = v_ref * t0 / a0
    tw = effective_rsf(u, TrapModel(eps=eps, direct=direct, v_ref=u_ref))
    g = float(junction_strength(u, direct, u_ref)) if direct else 1.0
    rsf = {"a": mu_el * tw["a"], "b": mu_el * tw["b"], "dc": tw["dc"] * a0,
           "mu0": mu_el * g * float(steady_friction(TrapModel(eps=eps), u))}
    model = CVModel(TrapModel(direct=0.01), v_ref=v_ref) if direct else CVModel()
    s = cv_start_from_rsf(model, rsf, v0, u)
    assert s["eps"] == pytest.approx(eps, rel=0.02)
    assert s["a0"] == pytest.approx(a0, rel=0.02)
    assert s["t0"] == pytest.approx(t0, rel=0.02)
    assert s["t0"] == pytest.approx(u * s["a0"] / v0, rel=1e-14)
    assert s["mu_el"] == pytest.approx(mu_el, rel=0.01)
    if direct:
        assert s["direct"] == pytest.approx(direct, rel=0.05)
    else:
        assert "direct" not in s


def test_series_on_a_clock_far_from_zero_and_its_steady_level() -> None:
    # the record's clock starts anywhere: the run is read at t - t[0] (mistake: at t, the
    # whole series then reads the run's last sample); after 6 a0 at the second velocity the
    # friction is the steady mu_el mu_d(u) (eq. 34) to the track's granularity
    a0, t0, mu_el = 1e-6, 1.0, 0.5
    v1, v2 = 0.3e-6, 3e-6
    t1, t2 = 4.0 * a0 / v1, 6.0 * a0 / v2
    t = np.linspace(0.0, t1 + t2, 300, endpoint=False)
    d0 = SeriesData(t, np.where(t < t1, v1, v2), np.zeros(t.size))
    d1 = SeriesData(t + 1234.5, d0.v_load, d0.mu)
    model = CVModel(TrapModel(), traps_per_a0=100, sample_slip=0.01)
    values = {"eps": 0.02, "t0": t0, "a0": a0, "mu_el": mu_el}
    m0, m1 = cv_series(model, values, d0), cv_series(model, values, d1)
    np.testing.assert_allclose(m1, m0, rtol=0, atol=1e-12)
    want = mu_el * float(steady_friction(TrapModel(eps=0.02), v2 * t0 / a0))
    assert float(np.mean(m0[-20:])) == pytest.approx(want, abs=2e-3)
    assert float(np.mean(m0[40:60])) == pytest.approx(
        mu_el * float(steady_friction(TrapModel(eps=0.02), v1 * t0 / a0)), abs=2e-3)


def test_the_spring_in_reduced_units_is_k_a0_over_mu_el() -> None:
    # friction mu = k (x_lp - x) per unit normal force (k in 1/m) is F/F_el = (k a0/mu_el)
    # (X_lp - X) in a0: the ensemble's spring K = k a0/mu_el (mistake: k a0, the spring mu_el
    # times too stiff). Against the ensemble run directly with that K, at mu_el = 0.45
    from dryfriction.ensemble.driving import Output, SpringDrive, simulate
    from dryfriction.ensemble.population import Initial, Track
    from dryfriction.program import Segment

    a0, t0, mu_el, k = 1e-6, 1.0, 0.45, 3.0e5  # K = 0.675 F_el/a0, near the contacts' own
    v1, v2 = 0.3e-6, 3e-6
    t1, t2 = 4.0 * a0 / v1, 6.0 * a0 / v2
    t = 50.0 + np.linspace(0.0, t1 + t2, 300, endpoint=False)
    d = SeriesData(t, np.where(t < 50.0 + t1, v1, v2), np.zeros(t.size))
    values = {"eps": 0.02, "t0": t0, "a0": a0, "mu_el": mu_el}
    got = cv_series(CVModel(TrapModel(), traps_per_a0=100, sample_slip=0.01, stiffness=k),
                    values, d)
    dur, vel = d.segments()
    prog = [Segment(float(v * t0 / a0), float(s / t0)) for s, v in zip(dur, vel, strict=True)]
    res = simulate(TrapModel(eps=0.02, mu_el=mu_el), SpringDrive(k * a0 / mu_el, 0.0, prog),
                   Initial("steady", velocity=v1 * t0 / a0, track=Track(100)),
                   Output(every_slip=0.01))
    want = np.interp((t - t[0]) / t0, res.t, res.mu)
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)
