"""Stick-slip: event analysis on synthetic signals, direct simulation against the linear theory,
the continuation in K, and the sweep / phase-diagram commands (issue 5)."""

import math
import textwrap
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from dryfriction.analysis.stickslip import analyse, bifurcation_scan, linear_check
from dryfriction.cli import app
from dryfriction.ensemble.population import Ensemble, Initial, Track, TrapModel
from dryfriction.sweeps.sweep import MAX_POINTS, load_sweep
from dryfriction.theory.linear_stability import critical_stiffness
from sweep_protocols import spring_sweep

runner = CliRunner()

# ---------------------------------------------------------------- synthetic signals


def _sawtooth(period=10.0, amp=0.3, u=0.1, slip_time=0.5, n_cycles=12, dt=0.01, ring=0.0):
    """Stick (load rises at rate amp/(period - slip_time), slider still), then slip (load
    falls by amp while the slider moves u*period), optionally with damped ringing after the
    slip. Built from the definitions, not from the analysis code."""
    t = np.arange(0.0, n_cycles * period, dt)
    ph = np.mod(t, period)
    stick = period - slip_time
    load = np.where(ph < stick, amp * ph / stick, amp * (1 - (ph - stick) / slip_time))
    cyc = np.floor(t / period)
    x = u * period * (cyc + np.where(ph < stick, 0.0, (ph - stick) / slip_time))
    if ring:
        tr = np.where(ph < stick, ph + slip_time, ph - stick)  # time since the last slip ended
        load = load + ring * amp * np.exp(-tr / (0.15 * period)) * np.sin(2 * np.pi * tr / 0.9)
    v = np.gradient(x, t)
    return t, x, v, 1.0 + load


def test_sawtooth_amplitude_period_slip_and_stick_time():
    P, A, u, ts = 10.0, 0.3, 0.1, 0.5
    t, x, v, load = _sawtooth(P, A, u, ts)
    st = analyse(t, x, v, load, u=u, t_start=P)
    assert st.kind == "periodic"
    assert st.amplitude == pytest.approx(A, rel=0.01)
    assert st.period == pytest.approx(P, rel=1e-3)
    assert st.slip_per_event == pytest.approx(u * P, rel=0.01)
    assert st.stick_time == pytest.approx(P - ts, rel=0.02)
    assert st.events in (10, 11)


def test_ringing_after_each_slip_is_not_counted_as_events():
    P, A, u = 10.0, 0.3, 0.1
    t, x, v, load = _sawtooth(P, A, u, ring=0.15)
    st = analyse(t, x, v, load, u=u, t_start=P)
    assert st.kind == "periodic"
    assert st.period == pytest.approx(P, rel=0.01)
    assert st.events in (10, 11)
    # a zig-zag without hysteresis would count every ringing wiggle
    naive = analyse(t, x, v, load, u=u, t_start=P, rel_threshold=1e-3, floor=1e-6)
    assert naive.events > 3 * st.events


def test_sine_gives_peak_to_trough_amplitude_and_period():
    t = np.linspace(0, 200, 20001)
    A, P = 0.05, 7.0
    load = 0.8 + A * np.sin(2 * np.pi * t / P)
    x = 0.1 * t
    v = np.full_like(t, 0.1)  # never sticks: an oscillation, not stick-slip
    st = analyse(t, x, v, load, u=0.1)
    assert st.amplitude == pytest.approx(2 * A, rel=1e-3)
    assert st.period == pytest.approx(P, rel=1e-3)
    assert st.kind == "oscillation"


def test_constant_and_tiny_noise_are_steady():
    t = np.linspace(0, 100, 5001)
    rng = np.random.default_rng(1)
    for load in (np.full_like(t, 0.9), 0.9 + 1e-4 * rng.standard_normal(t.size)):
        st = analyse(t, 0.1 * t, np.full_like(t, 0.1), load, u=0.1, floor=1e-3)
        assert st.kind == "steady" and st.events == 0 and st.amplitude == 0.0


def test_random_stick_slip_is_irregular():
    rng = np.random.default_rng(3)
    ts, ys, xs = [0.0], [1.0], [0.0]
    for _ in range(30):  # random recurrence times and random drops
        P, d = rng.uniform(3, 20), rng.uniform(0.05, 0.4)
        tt = ts[-1] + np.linspace(0, P, 50)[1:]
        ts += list(tt)
        ys += list(ys[-1] + d * np.linspace(0, 1, 50)[1:])
        xs += [xs[-1]] * 49
        ts.append(ts[-1] + 0.1)
        ys.append(ys[-1] - d)
        xs.append(xs[-1] + 0.1 * P)
    t, y, x = map(np.asarray, (ts, ys, xs))
    st = analyse(t, x, np.gradient(x, t), y, u=0.1, rel_threshold=0.05)
    assert st.kind == "irregular"
    assert st.events >= 25


def test_bad_input_is_rejected():
    t = np.linspace(0, 1, 10)
    with pytest.raises(ValueError, match="same length"):
        analyse(t, t, t, t[:-1], u=0.1)
    with pytest.raises(ValueError, match="u"):
        analyse(t, t, t, t, u=0.0)
    with pytest.raises(ValueError, match="samples"):
        analyse(t, t, t, t, u=0.1, t_start=2.0)


# ---------------------------------------------------------------- direct simulation vs linear


@pytest.mark.slow
def test_growth_rates_match_the_rightmost_root(runslow):
    """Inertial, damped slider (u = 0.1, eps = 0.04, M = 10, eta = 0.1): K_c = 0.247 is finite
    and the rightmost root crosses cleanly. Below K_c the simulated perturbation grows, above it
    decays, at the rate of the characteristic equation (an independent route)."""
    factors = [0.6, 0.8, 1.2] if runslow else [0.6, 1.2]
    rows = linear_check(0.1, TrapModel(eps=0.04), factors, mass=10.0, damping=0.1,
                        traps_per_a0=200 if runslow else 100)
    for r in rows:
        assert np.sign(r["sigma_sim"]) == np.sign(r["sigma_linear"]), r
        assert r["sigma_sim"] == pytest.approx(r["sigma_linear"], rel=0.15), r
        assert r["omega_sim"] == pytest.approx(r["omega_linear"], rel=0.02), r
        if r["K_over_Kc"] < 1:  # grew into stick-slip (or a finite oscillation)
            assert r["final_class"] in (1, 2, 3, 4) and r["final_amplitude"] > 0.1
        else:
            assert r["final_class"] == 0


# ---------------------------------------------------------------- the bifurcation


def _check_cycle_mass_balance(row, u):
    # over one stick-slip cycle the slider follows the load point: slip = u * period
    assert row["slip_per_event"] == pytest.approx(u * row["period"], rel=0.1)


@pytest.mark.slow
def test_continuation_in_K_shows_hysteresis_quasi_static(runslow):
    """M = 0, u = 0.1: steady sliding survives down to about K_c and stick-slip appears there
    with a finite amplitude; on the way back up it persists above K_c (subcritical)."""
    u = 0.1
    Kc = critical_stiffness(u, TrapModel(eps=0.04)).critical_stiffness
    fr = [1.3, 1.1, 1.05, 1.0, 0.95, 0.9] if runslow else [1.3, 1.1, 0.9]
    out = bifurcation_scan(u, TrapModel(eps=0.04), [f * Kc for f in fr], traps_per_a0=100,
                           travel=40.0,
                           transient=20.0)
    down = {round(r["stiffness"] / Kc, 3): r for r in out["down"]}
    up = {round(r["stiffness"] / Kc, 3): r for r in out["up"]}
    assert down[1.1]["class"] == 0
    assert down[0.9]["class"] == 1 and down[0.9]["amplitude"] > 0.1
    _check_cycle_mass_balance(down[0.9], u)
    # hysteresis: the stick-slip branch still exists at 1.1 K_c
    assert up[1.1]["class"] == 1 and up[1.1]["amplitude"] > 0.1
    _check_cycle_mass_balance(up[1.1], u)


def test_continuation_in_K_inertial(runslow):
    """M = 10, eta = 0.1, u = 0.1: steady above K_c, stick-slip grown from the kick well below;
    with --runslow the way back up still slips at K_c (hysteresis)."""
    u = 0.1
    Kc = critical_stiffness(u, TrapModel(eps=0.04), mass=10.0, damping=0.1).critical_stiffness
    fr = [1.3, 1.0, 0.8, 0.6] if runslow else [1.2, 0.6]
    out = bifurcation_scan(u, TrapModel(eps=0.04), [f * Kc for f in fr], mass=10.0, damping=0.1,
                           traps_per_a0=100, travel=90.0, transient=40.0)
    assert out["down"][0]["class"] == 0
    # grown from the 3 % kick into stick-slip (the slider stops): at this run length the
    # drops still grow towards the limit cycle, so "transient" is allowed
    low = out["down"][-1]
    assert low["class"] in (1, 2, 3) and low["amplitude"] > 0.1 and low["stick_fraction"] > 0
    if runslow:
        at_kc = out["up"][fr[::-1].index(1.0) - 1]
        assert at_kc["amplitude"] > 0.1


# ---------------------------------------------------------------- commands


PROTO = spring_sweep(every_slip=0.05)


def _write(tmp_path, sweep, name="p.toml"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(PROTO) + sweep)
    return p


@pytest.mark.slow
def test_sweep_cli_runs_on_two_workers(tmp_path):
    p = _write(tmp_path, '"drive.stiffness" = [0.04, 0.2]\n')
    r = runner.invoke(app, ["sweep", str(p), "--out", str(tmp_path / "o"), "--workers", "2"])
    assert r.exit_code == 0, r.output
    ds = load_sweep(tmp_path / "o" / "sweep.nc")
    assert ds.attrs["n_failed"] == 0
    assert {"class", "amplitude", "period", "stick_time", "events"} <= set(ds.data_vars)
    assert ds["class"].sel({"drive.stiffness": 0.2}).item() == 0  # stiff: steady
    # soft spring below K_c = 0.056: big slips that renew the contacts
    soft = ds.sel({"drive.stiffness": 0.04})
    assert soft["class"].item() == 1 and soft["amplitude"].item() > 0.1
    assert soft["slip_per_event"].item() == pytest.approx(0.1 * soft["period"].item(), rel=0.1)
    r2 = runner.invoke(app, ["sweep", str(p), "--out", str(tmp_path / "lin"), "--workers",
                             "2", "--linear"])
    assert r2.exit_code == 0, r2.output
    lin = load_sweep(tmp_path / "lin" / "sweep.nc")
    np.testing.assert_allclose(lin["K_c"].values, critical_stiffness(0.1, TrapModel(eps=0.04))
                               .critical_stiffness, rtol=1e-9)
    np.testing.assert_array_equal(lin["linearly_stable"].values, [0.0, 1.0])


@pytest.mark.slow
@pytest.mark.ci
def test_phase_diagram_cli_writes_png_and_netcdf(tmp_path):
    p = _write(tmp_path, '"drive.stiffness" = [0.04, 0.2]\n'
                         '"drive.segments.0.velocity" = [0.1, 1.0]\n')
    r = runner.invoke(app, ["phase-diagram", str(p), "--out", str(tmp_path / "o"),
                            "--workers", "2"])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "o" / "phase_diagram.png").stat().st_size > 1000
    ds = load_sweep(tmp_path / "o" / "sweep.nc")
    assert ds["class"].shape == (2, 2)


@pytest.mark.parametrize("sweep,command,message", [
    ('"drive.nonsense" = [1, 2]\n', "sweep", "not in the protocol"),
    ('"drive.stiffness" = []\n', "sweep", "empty"),
    ('"drive.stiffness" = {lin = [0.01, 1.0, ' + str(MAX_POINTS + 1) + ']}\n', "sweep",
     "confirm with --yes"),
    ('"drive.stiffness" = [0.05, -1.0]\n', "sweep", "stiffness"),
    ('"model.eps" = [0.01, 0.02]\n', "phase-diagram", "phase diagram sweeps exactly"),
])
def test_sweep_bad_input_exit_2_nothing_written(tmp_path, sweep, command, message):
    p = _write(tmp_path, sweep)
    r = runner.invoke(app, [command, str(p), "--out", str(tmp_path / "o")])
    assert r.exit_code == 2, r.output
    assert message in r.output.replace("\n", " ")
    assert len(r.output.strip().splitlines()) == 1
    assert not (tmp_path / "o").exists()


def test_sweep_unknown_stickslip_key_and_unreachable_scheduler(tmp_path):
    p = tmp_path / "p.toml"
    p.write_text(textwrap.dedent(PROTO).replace("transient = 10.0", "transient = 10.0\nbogus = 1")
                 + '"drive.stiffness" = [0.05]\n')
    r = runner.invoke(app, ["sweep", str(p), "--out", str(tmp_path / "o")])
    assert r.exit_code == 2 and "stickslip.bogus" in r.output
    p2 = _write(tmp_path, '"drive.stiffness" = [0.05]\n', "q.toml")
    # nothing listens on port 1: Dask retries a refused connection until the timeout
    r = runner.invoke(app, ["sweep", str(p2), "--out", str(tmp_path / "o"), "--scheduler",
                            "tcp://127.0.0.1:1", "--connect-timeout", "1"])
    assert r.exit_code == 2 and "cannot reach" in r.output
    assert not (tmp_path / "o").exists()


def test_continue_spring_keeps_the_state_between_runs():
    """Two successive continuations equal one run of the summed travel (same ensemble)."""
    from dryfriction.ensemble.driving import Output, SpringDrive, continue_spring
    from dryfriction.program import Segment, VelocityProgram

    def fresh():
        return Ensemble(TrapModel(0.13, 0.04), Track(50), Initial("steady", velocity=0.1))

    one = continue_spring(fresh(), SpringDrive(0.03, 0.0, VelocityProgram(
        [Segment(0.1, slip=6.0)])), Output(every_slip=0.05))
    ens = fresh()
    a = continue_spring(ens, SpringDrive(0.03, 0.0, VelocityProgram([Segment(0.1, slip=3.0)])),
                        Output(every_slip=0.05))
    b = continue_spring(ens, SpringDrive(0.03, 0.0, VelocityProgram([Segment(0.1, slip=3.0)])),
                        Output(every_slip=0.05),
                        spring_force=0.03 * (a.x_pull[-1] - a.x[-1]))
    assert b.t[0] == pytest.approx(a.t[-1])
    np.testing.assert_allclose(b.x[-1], one.x[-1], rtol=0, atol=1e-9)
    np.testing.assert_allclose(b.mu[-1], one.mu[-1], rtol=0, atol=1e-9)
    assert math.isclose(b.x_pull[-1], one.x_pull[-1], abs_tol=1e-9)


def test_sweep_examples_are_valid_at_every_point(tmp_path):
    from dryfriction.app.sweeps import prepare_sweep

    examples = [p for p in (Path(__file__).parents[2] / "examples").glob("*.toml")
                if "\n[sweep]" in p.read_text()]
    assert examples
    for p in examples:
        spec = prepare_sweep(str(p), str(tmp_path / "o"), False, None)
        assert 1 < spec.size <= 16  # small enough to run as an example
