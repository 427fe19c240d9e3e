"""The inertial slider with the direct effect (issue 11, part 3).

``M V' = K (X_pull - X) - eta V - g(V) F(X)``. References that do not come from the code under
test: the athermal velocity-Verlet loop (re-written here as it stood before the direct effect:
``A = 0`` must give it bit for bit); the velocity drive (a stiff spring with a critically
damped small mass is the kinematic limit); the work-energy identity of Newton's equation
(``int K (X_pull - X) dX = int friction dX + int eta V dX + Delta(M V^2/2)``); and a
linearisation written in this file (closed-form ``g`` and ``g'``, the athermal response ``Z``)
for the ring-down of a kicked slider.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from dryfriction.analysis.stickslip import fit_growth
from dryfriction.ensemble.driving import (
    Output,
    SpringDrive,
    VelocityDrive,
    continue_spring,
    simulate,
)
from dryfriction.ensemble.population import Ensemble, Initial, Track, TrapModel
from dryfriction.ensemble.result import segment_grid
from dryfriction.program import Segment, VelocityProgram
from dryfriction.theory.linear_stability import critical_stiffness, linear_response
from dryfriction.theory.stability import rightmost_root, steady_response
from dryfriction.theory.steady import steady_friction

EPS = 0.04


# ---------------------------------------------------------------- A = 0: the athermal scheme


def _athermal_verlet(model: TrapModel, track: Track, initial: Initial, drive: SpringDrive,
                     output: Output) -> dict[str, np.ndarray]:
    """The inertial spring drive as it was before the direct effect (velocity Verlet, force
    from positions and ages, the damping from the predicted velocity): samples 1..n."""
    prog, K, M, eta = drive.program, drive.stiffness, drive.mass, drive.damping
    ens = Ensemble(model, track, initial, age_horizon=prog.total_time)
    o = ens.observe()
    x_pull0 = ens.x + o.force / K
    grid = segment_grid(prog, output, track.spacing if track.layout == "regular" else None)
    xp = x_pull0 + (prog.position(grid) - prog.x0)
    dt_osc = 0.05 * 2.0 * math.pi * math.sqrt(M / (K + model.trap.contact_stiffness))
    dx_max = 0.25 * track.spacing

    def accel(x: float, v: float, f: float, t: float) -> float:
        xpl = x_pull0 + float(prog.position(t)) - prog.x0
        return (K * (xpl - x) - f - eta * v) / M

    V, a = 0.0, accel(ens.x, 0.0, o.force, 0.0)
    rows = []
    for t1, xp1 in zip(grid[1:], xp[1:], strict=True):
        while ens.t < t1:
            dt = min(dt_osc, float(t1) - ens.t)
            if V != 0.0:
                dt = min(dt, dx_max / abs(V))
            if t1 - (ens.t + dt) < 1e-12 * max(1.0, t1):
                dt = float(t1) - ens.t
            x_new = ens.x + V * dt + 0.5 * a * dt * dt
            t_new = float(t1) if dt == float(t1) - ens.t else ens.t + dt
            o = ens.advance(x_new, t_new)
            a_new = accel(x_new, V + a * dt, o.force, t_new)
            V = V + 0.5 * (a + a_new) * dt
            a = a_new
        rows.append((ens.t, ens.x, V, model.mu_el * o.force, float(xp1)))
    return dict(zip(("t", "x", "v", "mu", "x_pull"), np.array(rows).T, strict=True))


def test_zero_direct_inertial_slider_is_the_athermal_verlet_bit_for_bit() -> None:
    """``direct = 0`` (any ``v_ref``) with ``mass > 0``: the same numbers as the athermal
    scheme, from rest (a stick-slip start) and from steady sliding with damping and a hold."""
    prog = VelocityProgram([{"velocity": 0.3, "slip": 1.0}, {"velocity": 0.0, "duration": 4.0},
                            {"velocity": 2.0, "slip": 1.5}])
    for init, drive in ((Initial("rest"), SpringDrive(0.5, 0.02, prog)),
                        (Initial("steady", velocity=0.3), SpringDrive(0.05, 1.0, prog, 0.1))):
        out = Output(every_slip=0.02)
        ref = _athermal_verlet(TrapModel(eps=EPS), Track(150.0), init, drive, out)
        for model in (TrapModel(eps=EPS), TrapModel(eps=EPS, direct=0.0, v_ref=5.0)):
            r = simulate(model, drive, replace(init, track=Track(150.0)), out)
            for k, col in ref.items():
                np.testing.assert_array_equal(getattr(r, k)[1:], col, err_msg=k)
            assert "direct" not in r.info["parameters"]["model"]


# ---------------------------------------------------------------- the kinematic limit


def test_stiff_spring_and_small_mass_follow_a_velocity_step_like_the_velocity_drive() -> None:
    """K = 1e4, M = 1e-4, critically damped (eta = 2 sqrt(K M), ringing time 1e-4 t0): a load
    point stepping 1 -> 10 drags the slider like the velocity drive. Before the step the
    friction equals the kinematic run's at the same slider position; after the step it has
    jumped like the kinematic run's (window means over 5e-3..2.5e-2 a0 after it), by A mu1
    ln 10 within one sawtooth step (the granular error), and the velocity is 10 after 1e-2
    a0 (the damper's time eta/K = 2e-4 t0)."""
    A, lam, K, M = 0.02, 500.0, 1e4, 1e-4
    u1, u2, s0 = 1.0, 10.0, 0.1
    prog = VelocityProgram([{"velocity": u1, "slip": s0}, {"velocity": u2, "slip": 0.2}])
    model, d = TrapModel(eps=EPS, direct=A), 1 / (8 * lam)
    sp = simulate(model, SpringDrive(K, M, prog, 2 * math.sqrt(K * M)),
                  Initial("steady", velocity=u1, track=Track(lam)), Output(every_slip=d))
    kin = simulate(model, VelocityDrive(prog), Initial("steady", velocity=u1, track=Track(lam)),
                   Output(every_slip=d))
    before = sp.x < s0 - 1e-3
    np.testing.assert_allclose(sp.mu[before], np.interp(sp.x[before], kin.x, kin.mu),
                               atol=1e-4)
    after = sp.x > s0 + 0.01
    np.testing.assert_allclose(sp.v[after], u2, rtol=1e-3)

    def jump(r) -> float:
        b, a = (r.x > s0 - 0.02) & (r.x < s0), (r.x > s0 + 0.005) & (r.x < s0 + 0.025)
        return float(np.mean(r.mu[a]) - np.mean(r.mu[b]))

    i = int(np.flatnonzero(kin.x > s0 + 1e-12)[0])
    granular = float(np.max(np.abs(np.diff(kin.mu[i - 40: i]))))
    predicted = A * float(steady_friction(TrapModel(eps=EPS, direct=A), u1)) * math.log(u2 / u1)
    print(f"REPORT inertial kinematic limit: jump {jump(sp):.5f} (velocity drive "
          f"{jump(kin):.5f}, A mu1 ln 10 = {predicted:.5f}, granular {granular:.1e})")
    assert jump(sp) == pytest.approx(jump(kin), abs=2e-4)
    assert jump(sp) == pytest.approx(predicted, abs=granular)


# ---------------------------------------------------------------- work and energy


def _work_residual(h: float) -> tuple[float, float, np.ndarray]:
    """Stick-slip from rest (the slider creeps from V = 0, where g' is stiffest, then slips
    and sticks again), sampled at every step: ``W_spring - W_friction - W_eta - Delta KE`` by
    the trapezoid over the steps, the spring work, and the samples (t, x, v)."""
    A, v_ref, lam, u, K, M, eta = 0.02, 0.01, 20.0, 1.0, 0.1, 0.1, 0.02
    model = TrapModel(eps=EPS, direct=A, v_ref=v_ref)
    # steps are min(oscillation/20, a quarter spacing of slip, the sample): h below both
    r = simulate(model,
                 SpringDrive(K, M, VelocityProgram([{"velocity": u, "duration": 16.0}]), eta),
                 Initial("rest", track=Track(lam)), Output(every=h))
    assert r.info["slip_events"] >= 1 and np.max(r.v) * h <= 0.25 / lam
    x, v, f, s = r.x, r.v, r.mu / model.mu_el, K * (r.x_pull - r.x)

    def work(y: np.ndarray) -> float:
        return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)))

    res = work(s) - work(f) - work(eta * v) - 0.5 * M * (v[-1] ** 2 - v[0] ** 2)
    return res, work(s), np.c_[r.t, r.x, r.v]


def test_work_of_the_spring_is_friction_damping_and_kinetic_energy() -> None:
    """Newton's equation times V, integrated: the balance closes to 1e-6 of the spring work
    (7e-9 at h = 1e-3) and converges at second order (the residual falls 4x per halving of the
    step; the trajectory, whose force jumps at every spinodal, at first order); a
    friction force recorded without, or used without, g(V) would leave ~10 % of it (v_ref =
    0.01: g ~ 1.09 at V ~ 1). The velocity never reverses while the slider sticks: the
    stiff g'(V) near rest is taken implicitly."""
    res = [_work_residual(h) for h in (4e-3, 2e-3, 1e-3)]
    print("REPORT inertial work balance: residual " + ", ".join(
        f"{r:.2e} (h = {h:g})" for (r, _, _), h in zip(res, (4e-3, 2e-3, 1e-3), strict=True))
        + f" of W_spring = {res[-1][1]:.4f}")
    for r, w, samples in res:
        assert abs(r) < 1e-6 * w
        assert np.min(samples[:, 2]) >= 0.0
    assert abs(res[0][0]) > 3.0 * abs(res[1][0]) > 9.0 * abs(res[2][0])
    # the motion itself converges too (first order: the force jumps inside a step)
    x = [s[:, 1][:: 2 ** i] for i, (_, _, s) in enumerate(res)]
    assert np.max(np.abs(x[1] - x[2])) < 0.6 * np.max(np.abs(x[0] - x[1])) < 0.01


# ---------------------------------------------------------------- linear theory with mass


def _chi(lam: complex, u: float, A: float, K: float, M: float, eta: float) -> complex:
    """Characteristic function of the slider with mass and the direct effect, linearised here:
    ``delta friction = g(u) delta F + g'(u) F_d(u) delta V``, ``F_d = mu_d(u)`` athermal, with
    ``g = A asinh(u e^{1/A}/2)`` (v_ref = 1) and ``g'`` by a central difference of it."""
    def g(v: float) -> float:
        return A * math.asinh(v * math.exp(1.0 / A) / 2.0) if A else 1.0

    dg = (g(u * 1.0001) - g(u / 1.0001)) / (u * (1.0001 - 1 / 1.0001))
    Z = complex(steady_response(u, TrapModel(eps=EPS)).Z(lam))
    return M * lam**2 + eta * lam + K + g(u) * Z + dg * float(steady_friction(TrapModel(eps=EPS),
                                                                              u)) * lam


def _root_near(z: complex, *args: float) -> complex:
    for _ in range(60):
        f = _chi(z, *args)
        z = z - f / ((_chi(z + 1e-7, *args) - f) / 1e-7)
    assert abs(_chi(z, *args)) < 1e-9
    return z


def test_kicked_slider_rings_down_at_the_linear_rate_with_mass_and_direct_effect() -> None:
    """u = 1, K = 2 (far above K_c), M = 0.2, eta = 0: the only damping beyond the population's
    is the direct term A mu_d/u. The slider kicked to 1.5 u rings down at the root of the
    linearisation above (-0.124 +- 3.14 i; without the direct term it would grow), which is
    the library's rightmost root; the simulation agrees within 5 % (rate) and 0.5 % (frequency)
    at 100 traps/a0. With mass and eta = 0 the library's K_c (A = 0.02) is finite and its
    crossing is a root of the linearisation above."""
    u, A, K, M = 1.0, 0.05, 2.0, 0.2
    root = _root_near(complex(-0.1, 3.1), u, A, K, M, 0.0)
    lib = rightmost_root(linear_response(u, TrapModel(eps=EPS, direct=A)), K, M,
                         0.0)  # type: ignore[arg-type]
    assert complex(lib.real, abs(lib.imag)) == pytest.approx(root, abs=1e-6)
    assert root.real < 0 < _root_near(complex(0.0, 3.1), u, 0.0, K, M, 0.0).real
    ens = Ensemble(TrapModel(eps=EPS, direct=A), Track(100.0), Initial("steady", velocity=u),
                   age_horizon=40.0)
    r = continue_spring(ens, SpringDrive(K, M, VelocityProgram([Segment(u, duration=20.0)])),
                        Output(every=0.02), velocity=1.5 * u)
    assert np.min(r.v) > 0  # forward sliding throughout: the linear regime of g
    sigma, omega = fit_growth(r.t[10:], r.v[10:] - u)
    print(f"REPORT inertial ring-down u = {u}, A = {A}, M = {M}: linear {root.real:+.4f} "
          f"{abs(root.imag):.4f}i, simulated {sigma:+.4f} {omega:.4f}i")
    assert sigma == pytest.approx(root.real, rel=0.05)
    assert omega == pytest.approx(abs(root.imag), rel=0.005)
    for uu, m in ((0.1, 1.0), (1.0, 0.2)):  # A = 0.02: velocity weakening at both
        res = critical_stiffness(uu, TrapModel(eps=EPS, direct=0.02), mass=m)
        assert 0 < res.critical_stiffness < 10 and not res.supremum_at_infinity
        kc = res.critical_stiffness
        assert abs(_chi(complex(0.0, res.omega), uu, 0.02, kc, m, 0.0)) < 1e-3 * kc


@pytest.mark.slow
def test_growth_below_and_decay_above_K_c_with_mass() -> None:
    """u = 1, A = 0.02, M = 0.2, eta = 0 (K_c = 0.163 with mass): a slider kicked to 1.05 u
    grows at 0.7 K_c and decays at 1.3 K_c with the rightmost root's sign, rate (within 30 %:
    the rates are ~1e-2, the granular noise of 200 traps/a0 is not) and frequency (1 %)."""
    u, A, M = 1.0, 0.02, 0.2
    kc = critical_stiffness(u, TrapModel(eps=EPS, direct=A), mass=M).critical_stiffness
    resp = linear_response(u, TrapModel(eps=EPS, direct=A))
    for f in (0.7, 1.3):
        lam = rightmost_root(resp, f * kc, M, 0.0)  # type: ignore[arg-type]
        assert abs(_root_near(complex(lam.real, abs(lam.imag)), u, A, f * kc, M, 0.0)
                   - complex(lam.real, abs(lam.imag))) < 1e-6
        period = 2 * math.pi / abs(lam.imag)
        ens = Ensemble(TrapModel(eps=EPS, direct=A), Track(200.0),
                       Initial("steady", velocity=u), age_horizon=200.0)
        r = continue_spring(ens, SpringDrive(f * kc, M, VelocityProgram(
            [Segment(u, duration=6 * period)])), Output(every=period / 100), velocity=1.05 * u)
        assert np.max(np.abs(r.v - u)) < 0.5 * u  # still linear
        s, w = fit_growth(r.t[5:], r.v[5:] - u)
        print(f"REPORT inertial K = {f} K_c (M = {M}): linear {lam.real:+.5f} "
              f"{abs(lam.imag):.4f}i, simulated {s:+.5f} {w:.4f}i")
        assert np.sign(s) == np.sign(lam.real) == np.sign(1.0 - f)
        assert s == pytest.approx(lam.real, rel=0.3)
        assert w == pytest.approx(abs(lam.imag), rel=0.01)


# ---------------------------------------------------------------- files and the CLI


def test_protocol_file_with_direct_and_mass_runs(tmp_path) -> None:
    import json

    from typer.testing import CliRunner

    from dryfriction.cli import app

    p = tmp_path / "p.toml"
    p.write_text("""
[model]
eps = 0.04
direct = 0.02
v_ref = 0.1
[ensemble]
traps_per_a0 = 100
initial = "steady"
initial_velocity = 1.0
[drive]
kind = "spring"
stiffness = 0.5
mass = 0.1
damping = 0.05
segments = [{velocity = 1.0, slip = 1.0}]
[output]
every_slip = 0.05
""")
    r = CliRunner().invoke(app, ["simulate", str(p), "--out", str(tmp_path / "res"), "--json"])
    assert r.exit_code == 0, r.output
    s = json.loads((tmp_path / "res" / "summary.json").read_text())
    # steady start at u = 1 with the spring balancing g(1) mu_d + eta u: it stays steady
    mu = float(steady_friction(TrapModel(eps=EPS, direct=0.02, v_ref=0.1), 1.0))
    assert s["mean_mu"] == pytest.approx(mu, rel=0.01)


@pytest.mark.parametrize("A", [0.02, 0.001])
def test_a_loaded_slider_at_rest_creeps_with_friction_balancing_the_spring(A: float) -> None:
    """A slider at rest (V = 0, where g' is ~e^{1/A}) on a steady population, the spring pulling
    with half the friction level and its load point still: the junctions creep (V = g^-1(S/F),
    ~e^{-25} here, positive) and the friction balances the spring from the first step. The
    trapezoid in V would not damp that mode (the friction would alternate between ~2 S and
    ~0 from step to step), and Verlet's position step, blind to it, would move the slider by
    S dt^2/2M (1.5e-2 a0 at once). A = 0.001: e^{1/A} overflows, V ~ e^{-500}."""
    u = 1.0
    ens = Ensemble(TrapModel(eps=EPS, direct=A), Track(100.0), Initial("steady", velocity=u),
                   age_horizon=20.0)
    s0 = 0.5 * float(steady_friction(TrapModel(eps=EPS), u))
    r = continue_spring(ens, SpringDrive(1.0, 0.01, VelocityProgram([Segment(0.0, duration=2.0)])),
                        Output(every=0.1), spring_force=s0)
    np.testing.assert_allclose(r.mu[1:], 1.0 * (r.x_pull - r.x)[1:], rtol=1e-9)
    np.testing.assert_allclose(r.mu[1:], s0, rtol=1e-6)
    assert np.all((r.v[1:] > 0) & (r.v[1:] < 1e-8))


def test_stability_cli_takes_mass_without_damping_with_the_direct_effect() -> None:
    """The direct term damps like eta = A mu_d/u, so --mass without --damping has a finite K_c
    with --direct (still refused without it: tests/cli/test_words.py)."""
    import json

    from typer.testing import CliRunner

    from dryfriction.cli import app

    r = CliRunner().invoke(app, ["stability", "--eps", "0.04", "--u", "1", "--M", "0.2",
                                 "--direct", "0.02", "--json"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["K_c"][0] == pytest.approx(
        critical_stiffness(1.0, TrapModel(eps=EPS, direct=0.02), mass=0.2).critical_stiffness,
        rel=1e-9)
