"""Results are checked against physical bounds before they are returned (issue 24).

Each test names the wrong result the outside run found: a soft rate-and-state spring whose
slider moved back or outran its own velocity, a static threshold that grew with the sampling,
ramps and segments beyond what the model resolves, snapshots dropped silently.
"""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest

import dryfriction.rsf.driving as rsf_driving
from dryfriction.ensemble.driving import ForceDrive, SpringDrive, VelocityDrive, simulate
from dryfriction.ensemble.population import Initial, Track, TrapModel
from dryfriction.ensemble.result import Output
from dryfriction.program import Segment, VelocityProgram
from dryfriction.results import ImpossibleResultError, check_physical
from dryfriction.rsf.law import RateState
from dryfriction.rsf.spring import RSFOutput, SpringSlider

# velocity strengthening (a > b): steady sliding under a constant force is stable, so a slider
# on a spring too soft to change its force slides on at its initial velocity exactly
STABLE = RateState(a=0.0113, b=0.0071, dc=1.7e-5, mu0=0.58, v0=1.3e-6)


def _soft_run(k: float, every: float | None = None) -> tuple[float, float]:
    """Slip of a slider pulled through a spring of stiffness ``k`` by a load point that
    steps from 1.3 to 17 um/s; the closed form for ``k -> 0`` is ``v_init * T``."""
    prog = [Segment(1.3e-6, 11.0), Segment(1.7e-5, 23.0)]
    res = rsf_driving.simulate(STABLE, SpringSlider(prog, k), output=RSFOutput(every=every))
    return float(res.x[-1] - res.x[0]), 1.3e-6 * 34.0


@pytest.mark.parametrize("k", [1e-12, 1e-15, 1e-300])
@pytest.mark.parametrize("every", [None, 0.7])
def test_a_soft_spring_slides_at_its_initial_velocity(k: float, every: float | None) -> None:
    # mistake: the position from the force balance, x = x_load - (stress - stress0)/k,
    # divides the stress's rounding by k: slip 2.9 times too large at k = 1e-15 (the load
    # point's travel), the slider moving back at 1e-12, -1.2e285 m at 1e-300
    slip, closed = _soft_run(k, every)
    assert slip == pytest.approx(closed, rel=1e-6)


def test_the_two_routes_to_the_position_agree_where_both_hold(
        monkeypatch: pytest.MonkeyPatch) -> None:
    # k = 40/m: the force balance loses rtol (a + b)/k ~ 5e-11 m, the quadrature rtol of the
    # slip; two independent routes to x (an error in either, e.g. a wrong Gauss weight or
    # a Hermite slope not scaled by the step, shows here)
    prog = [Segment(1.3e-6, 11.0), Segment(1.7e-5, 23.0)]
    runs = {}
    for route in (False, True):
        monkeypatch.setattr(rsf_driving, "force_balance_is_ill_conditioned",
                            lambda *a, r=route: r)
        runs[route] = rsf_driving.simulate(STABLE, SpringSlider(prog, 40.0, 0.3),
                                           output=RSFOutput(every=0.5, rtol=1e-9))
    a, b = runs[False].x, runs[True].x
    assert np.max(np.abs(a - b)) <= 1e-7 * (a[-1] - a[0])


@pytest.mark.parametrize("k", [1e-12, 1e-15, 1e-300])
def test_the_old_position_is_refused_as_impossible(k: float,
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    # the check itself: forced onto the force balance at a soft spring (the old code), the
    # run must not come back as a result
    monkeypatch.setattr(rsf_driving, "force_balance_is_ill_conditioned", lambda *a: False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(ImpossibleResultError, match="impossible result"):
            rsf_driving.simulate(RateState(0.005, 0.01, 1e-5, 0.6, 1e-6),
                                 SpringSlider([Segment(1e-6, 10.0), Segment(1e-5, 30.0)], k))


def test_check_physical_names_each_bound() -> None:
    t, v, mu = np.array([0.0, 1.0, 2.0]), np.full(3, 1e-6), np.full(3, 0.6)
    with pytest.raises(ImpossibleResultError, match="x = nan"):
        check_physical("run", t, np.array([0.0, np.nan, 1.0]), v, mu, unit="m")
    with pytest.raises(ImpossibleResultError, match="mu = inf"):
        check_physical("run", t, np.zeros(3), v, np.array([0.6, np.inf, 0.6]), unit="m")
    with pytest.raises(ImpossibleResultError, match="moved backwards by 0.5 m"):
        check_physical("run", t, np.array([0.0, 1.0, 0.5]), v, mu, unit="m", forward=True)
    with pytest.raises(ImpossibleResultError, match="load-point travel plus the spring"):
        check_physical("run", t, np.array([0.0, 1.0, 2.0]), v, mu, unit="m", slip_max=1.5)
    with pytest.raises(ImpossibleResultError, match="not the integral of the velocity"):
        check_physical("run", t, np.array([0.0, 1.0, 2.0]), v, mu, unit="m",
                       slip_integral=2e-6, tol=1e-9)
    with pytest.raises(ImpossibleResultError, match="friction -0.01 at t = 1 is below the "
                                                    "model's bound 0"):
        check_physical("run", t, np.zeros(3), v, np.array([0.6, -0.01, 0.6]), unit="m",
                       mu_min=0.0)
    check_physical("run", t, np.array([0.0, 1.0, 2.0]), v, mu, unit="m", forward=True,
                   slip_max=2.0, slip_integral=2.0, mu_min=0.0)


# ----------------------------------------------------------------- the static threshold
MODEL = TrapModel(alpha=0.13, eps=0.037)


def _threshold(every_slip: float, rate: float, hold: float) -> float:
    res = simulate(MODEL, ForceDrive(rate=rate, hold=hold), Initial("rest", track=Track(300.0)),
                   Output(every_slip=every_slip))
    assert res.info["runaway"]
    return float(res.info["threshold_mu"])


@pytest.mark.parametrize("rate, hold, coarse, rel", [
    (1e4, 73.0, 1e6, 1e-6),    # 1.2204 against 1.1983 in the example (hold 100)
    (1e4, 73.0, 1e20, 1e-6),   # 2.57
    (1e4, 73.0, 1e300, 1e-6),  # 4.7e-16
    (3e-3, 0.0, 7.0, 2e-4),    # a slow ramp from fresh contacts: the creep during a step
])
def test_the_static_threshold_does_not_depend_on_the_sampling(rate: float, hold: float,
                                                              coarse: float, rel: float) -> None:
    # mistake: one equilibrium per sample, the contacts aged at the last equilibrium for the
    # whole sample interval before the force is applied
    fine = _threshold(0.004, rate, hold)
    assert _threshold(coarse, rate, hold) == pytest.approx(fine, rel=rel)


@pytest.mark.parametrize("drive, key", [
    (lambda: ForceDrive(rate=1e-300), "rate = 1e-300"),  # gave 8e-17 (the clock overflowed)
    (lambda: ForceDrive(rate=1e-20, max_force=3.0), "rate = 1e-20"),
    (lambda: ForceDrive(rate=1.0, hold=1e14), "hold = 1e+14"),
])
def test_a_ramp_beyond_the_checked_ages_is_refused(drive, key: str) -> None:
    with pytest.raises(ValueError, match=re.escape(key)) as exc:
        drive()
    assert "allowed" in str(exc.value)


def test_ramps_run_up_to_the_checked_ages_and_are_refused_past_them() -> None:
    # a hold of 5e13 t0 (within the clock's 2^46 = 7.04e13 t0) then a ramp of 1e-6 F_el/t0:
    # threshold above the one after 1e10 t0; past 2^46 t0 the clock no longer resolves the ages
    with pytest.raises(ValueError, match=r"allowed rate >= 1\.44e-13"):
        ForceDrive(rate=1e-14, hold=1e2)
    long = simulate(MODEL, ForceDrive(rate=1e-6, hold=5e13), Initial("rest", track=Track(100.0)),
                    Output(every_slip=0.5))
    short = simulate(MODEL, ForceDrive(rate=1e-6, hold=1e10), Initial("rest", track=Track(100.0)),
                     Output(every_slip=0.5))
    assert long.info["threshold_mu"] > short.info["threshold_mu"] > 1.0


# --------------------------------------------------------------- velocities, snapshots
@pytest.mark.parametrize("make", [
    lambda: VelocityDrive(VelocityProgram([Segment(1e-300, 5.0)])),
    lambda: VelocityDrive(VelocityProgram([Segment(1.0, slip=1.0), Segment(-3e-31, 2.0)])),
    lambda: SpringDrive(0.05, 0.0, VelocityProgram([Segment(1e-300, 20.0)])),
    lambda: SpringSlider([Segment(1e-300, 10.0)], 1e3),
    lambda: SpringSlider([Segment(1e-6, 10.0), Segment(2e-31, 5.0)], 1e3),
])
def test_a_moving_segment_below_what_the_model_resolves_is_refused(make) -> None:
    # 1e-300: friction 108 F_el with RuntimeWarnings in the outside run; the theory's
    # velocities start at U_MIN = 1e-30
    with pytest.raises(ValueError, match=r"segments\[\d\]\.velocity = .* allowed 0 \(a hold\) "
                                         r"or 1e-30 <= \|velocity\|"):
        make()


def test_the_slowest_resolved_velocity_runs_and_slower_is_refused() -> None:
    res = simulate(MODEL,
                   VelocityDrive(VelocityProgram([Segment(0.0, 3.0), Segment(1e-30, 2.0),
                                                  Segment(0.7, slip=0.3)])),
                   Initial("rest", track=Track(50.0)), Output(every=0.5))
    assert res.t[-1] == pytest.approx(5.0 + 0.3 / 0.7)
    with pytest.raises(ValueError, match=r"segments\[1\]\.velocity = 9e-31"):
        VelocityDrive(VelocityProgram([Segment(0.0, 3.0), Segment(9e-31, 2.0)]))


def test_a_snapshot_after_the_run_is_refused() -> None:
    drive = VelocityDrive(VelocityProgram([Segment(0.7, slip=1.3)]))
    with pytest.raises(ValueError, match="snapshots: the time 2.5 t0 is after the run's end"):
        simulate(MODEL, drive, Initial("rest", track=Track(50.0)),
                 Output(every_slip=0.1, snapshots=(0.5, 2.5)))
    res = simulate(MODEL, drive, Initial("rest", track=Track(50.0)),
                   Output(every_slip=0.1, snapshots=(0.5, 1.3 / 0.7)))
    assert len(res.snapshots) == 2


def test_snapshots_a_runaway_does_not_reach_are_listed() -> None:
    # a ramp ends at its runaway, which no check places before the run
    res = simulate(MODEL, ForceDrive(rate=1e2, hold=2.0), Initial("rest", track=Track(100.0)),
                   Output(every_slip=0.01, snapshots=(1.0, 2.0 + 0.09)))
    assert res.info["runaway"] and res.t[-1] < 2.09
    assert len(res.snapshots) == 1
    assert res.info["snapshots_not_reached"] == [2.09]
    assert res.summary()["snapshots_not_reached"] == [2.09]


def test_protocol_names_the_snapshot_key() -> None:
    from dryfriction.io.protocol import parse_protocol

    text = """
[model]
eps = 0.04
[ensemble]
traps_per_a0 = 50
initial = "rest"
[drive]
kind = "velocity"
segments = [{velocity = 1.0, slip = 2.0}]
[output]
every_slip = 0.1
snapshots = [1.0, 30.0]
"""
    with pytest.raises(ValueError, match=r"p.toml: output.snapshots: the time 30 t0 is after "
                                         r"the run's end: .* ends at t = 2 t0"):
        parse_protocol(text, "p.toml")
