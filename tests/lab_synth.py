"""Synthetic velocity-step records from an independent forward solver (issue 10 tests).

Quasi-static spring slider with rate-and-state friction and the ageing law, written here from
the equations and integrated by SciPy's ``solve_ivp`` (Radau) in the linear variables
``(tau, theta)`` (the spring force per unit normal force and the state), not the project's
RODAS4 in log variables::

    mu = mu0 + a ln(V/V0) + b ln(V0 theta/Dc)   ->   V = V0 exp((tau - mu0 - b ln(V0 theta/Dc))/a)
    dtau/dt = k (V_load - V),   dtheta/dt = 1 - V theta/Dc

The measured friction is ``tau + trend * x_lp + noise`` with ``x_lp`` the load-point
displacement from the first sample.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp


@dataclass(frozen=True)
class Truth:
    a: float = 0.006
    b: float = 0.009
    dc: float = 20e-6
    mu0: float = 0.6
    stiffness: float = 3000.0
    trend: float = -8.0
    noise: float = 3e-4
    rho: float = 0.0  # lag-1 autocorrelation of the noise (AR(1), stationary std ``noise``)


def synth_record(truth: Truth, velocities: list[float], duration_slip: float = 600e-6,
                 dt_per_um: float = 0.1, seed: int = 0) -> tuple[np.ndarray, np.ndarray,
                                                                 np.ndarray, np.ndarray]:
    """``(t, v_load, mu, x_lp)`` for load velocities ``velocities`` (m/s), each held for
    ``duration_slip`` m of load-point slip, at one fixed time step for the whole record:
    ``dt_per_um / 2`` um of slip at the slowest velocity. ``seed`` seeds the noise."""
    rng = np.random.default_rng(seed)
    tr = truth
    v0 = velocities[0]
    dt = dt_per_um * 1e-6 / min(velocities) * 0.5

    def rhs(_t: float, y: np.ndarray, vl: float) -> list[float]:
        tau, th = y
        v = v0 * math.exp((tau - tr.mu0 - tr.b * math.log(v0 * th / tr.dc)) / tr.a)
        return [tr.stiffness * (vl - v), 1.0 - v * th / tr.dc]

    y = np.array([tr.mu0 + (tr.a - tr.b) * math.log(velocities[0] / v0),
                  tr.dc / velocities[0]])
    ts, vs, taus, xs = [], [], [], []
    t_now, x_now = 0.0, 0.0
    for vl in velocities:
        span = duration_slip / vl
        n = max(int(round(span / dt)), 2)
        te = t_now + dt * np.arange(n)
        sol = solve_ivp(rhs, (t_now, t_now + n * dt), y, method="Radau", t_eval=te,
                        args=(vl,), rtol=1e-10, atol=[1e-13, 1e-12 * tr.dc / vl])
        assert sol.success, sol.message
        ts.append(te)
        vs.append(np.full(n, vl))
        taus.append(sol.y[0])
        xs.append(x_now + vl * (te - t_now))
        end = solve_ivp(rhs, (te[-1], t_now + n * dt), sol.y[:, -1], method="Radau",
                        args=(vl,), rtol=1e-10, atol=[1e-13, 1e-12 * tr.dc / vl])
        y = end.y[:, -1]
        x_now += vl * n * dt
        t_now += n * dt
    t = np.concatenate(ts)
    x = np.concatenate(xs)
    e = rng.normal(0.0, tr.noise, len(t))
    if tr.rho:  # AR(1) with the same stationary standard deviation
        from scipy.signal import lfilter
        s = math.sqrt(1.0 - tr.rho**2)
        e[1:] = lfilter([s], [1.0, -tr.rho], e[1:], zi=[tr.rho * e[0]])[0]
    mu = np.concatenate(taus) + tr.trend * x + e
    return t, np.concatenate(vs), mu, x
