"""Time steppers: convergence order in each branch, exact one-step maps on linear problems, the
strongly and weakly damped limits (issue 25 item 4); the bifurcation exponent on a curve that
is not exactly ``sqrt d``.

The inertial slider with the direct effect (:func:`dryfriction.ensemble.thermal.
inertial_velocity`) takes a theta-step for ``M V' = S - eta V - g(V) F``: the trapezoid
(theta = 1/2) where ``z = (eta + g'(V) F) dt/M <= 2``, backward Euler above. On a linear
problem (``F -> 0``) each branch is a known rational function of ``z`` (Hairer & Wanner,
*Solving ODEs II*, §IV.3): ``(1 - z/2)/(1 + z/2)`` and ``1/(1 + z)``; on the nonlinear one
the error against SciPy's Radau at 1e-12 falls as ``dt^2`` and ``dt``. The position weight
(:func:`~dryfriction.ensemble.thermal.drift`) is checked against the exact displacement of
a damped mass under a constant force, in a regime where ``eta dt/M`` is of order 1.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from dryfriction.analysis.bifurcation import classify
from dryfriction.ensemble.population import TrapModel
from dryfriction.ensemble.thermal import drift, inertial_velocity

DIRECT, V_REF = 0.047, 0.63
MODEL = TrapModel(alpha=0.13, eps=0.04, direct=DIRECT, v_ref=V_REF)


def _g(v: float) -> float:
    """``g(V) = A asinh(V e^{1/A}/(2 V_ref))`` (Baumberger & Caroli), written here."""
    return DIRECT * math.asinh(v * math.exp(1.0 / DIRECT) / (2.0 * V_REF))


def _spring(t: float, S: float) -> float:
    """A spring force that keeps moving, so that a slaved (stiff) velocity keeps lagging."""
    return S * (1.0 + 0.4 * math.sin(1.3 * t))


def _march(v0: float, dt: float, t_end: float, M: float, eta: float, S: float, F: float
           ) -> float:
    v = v0
    for n in range(round(t_end / dt)):
        r = _spring(n * dt, S) - eta * v - _g(v) * F
        v, _ = inertial_velocity(MODEL, v, r, dt, M, eta, _spring((n + 1) * dt, S), F)
    return v


def _reference(v0: float, t_end: float, M: float, eta: float, S: float, F: float) -> float:
    sol = solve_ivp(lambda t, y: [(_spring(t, S) - eta * y[0] - _g(y[0]) * F) / M],
                    (0.0, t_end), [v0], method="Radau", rtol=1e-12, atol=1e-14)
    return float(sol.y[0, -1])


# ------------------------------------------------------------------ the velocity step
@settings(max_examples=30, derandomize=True, deadline=None)
@given(z=st.floats(0.01, 40.0), v=st.floats(-3.0, 3.0), S=st.floats(0.1, 5.0))
def test_linear_one_step_maps_of_each_branch(z: float, v: float, S: float) -> None:
    """With a vanishing population force the step is the theta-method on ``M V' = S - eta V``:
    ``V1 - S/eta = (V - S/eta) R(z)``, ``R = (1 - z/2)/(1 + z/2)`` for ``z <= 2`` (second order),
    ``1/(1 + z)`` above (L-stable). Mistakes: the switch moved (to 0.5 or 8), theta = 1 or
    1/2 everywhere, the damping left out of the implicit mass."""
    M, eta = 1.7, 0.9
    dt = z * M / eta
    F = 1e-200  # positive: the implicit branch; its force is nothing beside S and eta V
    v1, _ = inertial_velocity(MODEL, v, S - eta * v, dt, M, eta, S, F)
    R = (1 - z / 2) / (1 + z / 2) if z <= 2.0 else 1.0 / (1.0 + z)
    vinf = S / eta
    assert v1 - vinf == pytest.approx((v - vinf) * R, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize(("eta", "dts", "order"), [
    (0.45, (1.6, 0.8, 0.4), 2.0),   # z from 0.8 to 0.2 (~0.05-1.1 with g'F): trapezoid
    (12.0, (0.8, 0.4, 0.2), 1.0),   # z from 10 to 2.5: backward Euler (measured 1.25, 1.19)
])
def test_convergence_order_in_each_branch(eta: float, dts: tuple[float, ...], order: float
                                          ) -> None:
    """Error at ``t = 4.8`` against Radau at 1e-12, the nonlinear ``g(V) F`` included and the
    spring force oscillating (``S (1 + 0.4 sin 1.3 t)``, so that the stiff slider's slaved
    velocity lags it): the observed order per halving of ``dt`` is 2 in the resolved regime
    and 1 in the stiff one (within 0.35). Mistake: the theta-switch at
    ``z = 0.5`` instead of 2 (backward Euler where the trapezoid belongs: order 1)."""
    M, S, F = 1.0, 1.9, 1.3
    v0 = 0.25 * (S - F) / eta if eta > 1 else 0.3
    ref = _reference(v0, 4.8, M, eta, S, F)
    errs = [abs(_march(v0, dt, 4.8, M, eta, S, F) - ref) for dt in dts]
    orders = [math.log2(a / b) for a, b in zip(errs, errs[1:], strict=False)]
    assert all(abs(p - order) < 0.35 for p in orders), (errs, orders)


def test_strongly_damped_limit_is_the_force_balance() -> None:
    """``z >> 1``: one step lands on the sticking slider's force balance ``S = eta V + g(V) F``
    (its creep), from either side, without overshoot (the trapezoid would flip the sign)."""
    M, eta, S, F = 1e-3, 0.2, 1.07, 1.0
    for v0 in (0.0, 5.0):
        v1, g1 = inertial_velocity(MODEL, v0, S - eta * v0 - _g(v0) * F, 1e8, M, eta, S, F)
        assert S - eta * v1 - g1 * F == pytest.approx(0.0, abs=1e-9)
        assert g1 == pytest.approx(_g(v1), rel=1e-9)
        assert v1 > 0.0


def test_weakly_damped_limit_is_the_undamped_trapezoid() -> None:
    """``eta -> 0`` and a tiny ``g' F``: the step is the trapezoid on the free mass, exact for a
    constant force: ``V1 = V + (S - g F) dt/M`` (``g`` barely moving at this speed)."""
    M, S, F, v, dt = 2.3, 1.5, 1e-9, 7.0, 0.37
    v1, _ = inertial_velocity(MODEL, v, S - _g(v) * F, dt, M, 0.0, S, F)
    assert v1 == pytest.approx(v + S * dt / M, rel=1e-10)


# ------------------------------------------------------------------ the position weight
def _exact_weight(z: float) -> float:
    """``x(dt) = x0 + V dt + w a dt^2`` for ``M x'' = S - eta x'`` (constant ``S``), solved here:
    ``V(t) = V_inf + (V - V_inf) e^{-eta t/M}``, so ``x(dt) - x0 - V dt = a M^2/eta^2 (e^{-z} - 1
    + z)`` with ``a = (S - eta V)/M``, ``z = eta dt/M``."""
    return (math.exp(-z) - 1.0 + z) / (z * z)


@pytest.mark.parametrize("z", [2.3e-4, 0.31, 1.7, 23.0])
def test_drift_weight_is_the_exact_damped_displacement(z: float) -> None:
    """Mistake: the damping dropped from the drift (``z`` from the junction only): invisible
    where ``eta dt/M ~ 2e-4`` (every driver test), ``1/2`` against 0.42, 0.31, 0.04 here."""
    M, eta = 3.1, 0.83
    dt = z * M / eta
    S, V = 2.2, 0.4
    a = (S - eta * V) / M
    vinf = S / eta
    x_exact = vinf * dt + (V - vinf) * M / eta * (1.0 - math.exp(-z))
    w = drift(MODEL, V, dt, M, eta, -1.0)  # no population force: the damping alone
    assert w == pytest.approx(_exact_weight(z), rel=1e-9)
    assert V * dt + w * a * dt * dt == pytest.approx(x_exact, rel=1e-9)
    # with the population force the junction's rate g'(V) F adds to eta
    F = 0.9
    gp = DIRECT / math.hypot(V, 2 * V_REF * math.exp(-1 / DIRECT))
    zf = (eta + gp * F) * dt / M
    assert drift(MODEL, V, dt, M, eta, F) == pytest.approx(_exact_weight(zf), rel=1e-9)


# ------------------------------------------------------------------ bifurcation exponent
def test_exponent_is_fitted_over_the_smallest_distances() -> None:
    """``amplitude = 0.8 sqrt(d) (1 + 4 d)``: the local exponent ``1/2 + 4d/(1 + 4d)`` is 0.5 at
    the onset and 0.98 at the largest distance, so a fit over the smallest four (0.002-0.016)
    gives 0.5 + ~0.03 while one over the largest (or all) gives more than 0.6. Mistake: the
    sort reversed, or the largest distances kept."""
    ds = [0.002, 0.004, 0.008, 0.016, 0.06, 0.12, 0.25, 0.5]
    up = [(d, 0.8 * math.sqrt(d) * (1 + 4 * d)) for d in ds[::-1]] + [(-0.05, 1e-4)]
    scan = {"floor": 1e-4, "down": [{"d": -0.05, "amplitude": 1e-4}],
            "up": [{"d": d, "amplitude": a, "trend": 0.5} for d, a in up]}
    r = classify(scan)
    d4 = np.log(ds[:4])
    a4 = np.log([0.8 * math.sqrt(d) * (1 + 4 * d) for d in ds[:4]])
    assert r["type"] == "supercritical"
    assert r["exponent"] == pytest.approx(float(np.polyfit(d4, a4, 1)[0]), rel=1e-12)
    assert 0.5 < r["exponent"] < 0.56


# ------------------------------------------------------------------ the ensemble's inertial slider
def _spring_run(eta: float, direct: float, every: float, t_end: float = 6.0
                ):  # type: ignore[no-untyped-def]
    """The inertial spring drive on a track with no pair within reach (``lambda = 1e-6``): the
    population force is 0, so the slider is the linear ``M X'' = K (u t - X) - eta X'``."""
    from dryfriction.ensemble.driving import SpringDrive, simulate
    from dryfriction.ensemble.population import Initial, Track
    from dryfriction.ensemble.result import Output
    from dryfriction.program import Segment

    model = TrapModel(alpha=0.13, direct=direct, v_ref=0.5)
    return simulate(model, SpringDrive(2.3, 0.7, [Segment(0.37, duration=t_end)], damping=eta),
                    Initial(track=Track(1e-6)), Output(every=every))


def _oscillator(t: np.ndarray, eta: float) -> np.ndarray:
    K, M, u = 2.3, 0.7, 0.37
    sol = solve_ivp(lambda s, y: [y[1], (K * (u * s - y[0]) - eta * y[1]) / M], (0, t[-1]),
                    [0.0, 0.0], t_eval=t, method="Radau" if eta > 5 else "DOP853",
                    rtol=1e-12, atol=1e-14)
    return sol.y[0]


@pytest.mark.parametrize("direct", [0.0, 0.02])
def test_ensemble_inertial_scheme_is_second_order(direct: float) -> None:
    """Velocity Verlet (athermal) and the direct effect's scheme (here its explicit branch, no
    population force) against Radau, the step set by the sampling (0.08, 0.04, 0.02 ``t0``):
    order 2 per halving (measured 2.02, 2.01 and 1.99, 1.99)."""
    errs = []
    for h in (0.08, 0.04, 0.02):
        r = _spring_run(0.9, direct, h)
        errs.append(float(np.max(np.abs(r.x - _oscillator(r.t, 0.9)))))
    orders = [math.log2(a / b) for a, b in zip(errs, errs[1:], strict=False)]
    assert all(abs(p - 2.0) < 0.2 for p in orders), (errs, orders)


@pytest.mark.parametrize("direct", [0.0, 0.02])
@pytest.mark.parametrize("eta", [0.0, 20.0, 200.0])
def test_ensemble_inertial_scheme_in_the_damped_limits(eta: float, direct: float) -> None:
    """Undamped (the oscillation at ``sqrt(K/M)``, energy kept) and strongly damped
    (``eta/(2 sqrt(K M))`` = 8 and 79: the slider creeps behind the load point at ``u``, lag
    ``eta u/K``) with the default steps (``eta dt/M`` up to 43 before the step was capped at
    ``M/eta``): within 3e-2 of the exact motion (measured 2.9e-2 undamped, 1e-5..6e-4
    damped), and never faster than the load point's ``u`` by more than the undamped
    overshoot. Mistake: the explicit damping with the oscillation step alone (it blew up to
    ``|x| ~ 1e6``)."""
    r = _spring_run(eta, direct, 1.0, t_end=30.0)
    exact = _oscillator(r.t, eta)
    assert float(np.max(np.abs(r.x - exact))) < 3e-2
    assert float(np.max(np.abs(r.v))) <= 2 * 0.37 + 1e-3


def test_work_estimate_counts_the_damping_limited_steps() -> None:
    """``estimate_work`` bounds the inertial steps by ``T / min(dt_osc, M/eta)``: an overdamped
    slider (``eta dt_osc/M`` = 43) takes 43x the oscillation-limited steps. Mistake: the
    driver's step capped and the estimate not (a refusal that lets a 43x longer run through)."""
    from dryfriction.ensemble.driving import SpringDrive
    from dryfriction.ensemble.population import Initial, Track
    from dryfriction.ensemble.resources import estimate_run, estimate_work
    from dryfriction.ensemble.result import Output
    from dryfriction.program import Segment

    model = TrapModel(alpha=0.13)
    K, M, T = 2.3, 0.7, 30.0
    k_c = model.trap.contact_stiffness
    dt_osc = 0.05 * 2 * math.pi * math.sqrt(M / (K + k_c))
    track = Track(1e-6)
    calls = []
    for eta in (0.0, 200.0):
        drive = SpringDrive(K, M, [Segment(0.37, duration=T)], damping=eta)
        est = estimate_run(model, track, Initial(), drive, Output(every=1.0))
        calls.append(estimate_work(model, track, drive, est)[0])
    assert calls[0] == pytest.approx(T / dt_osc, rel=1e-9)
    assert calls[1] == pytest.approx(T / (M / 200.0), rel=1e-9)
