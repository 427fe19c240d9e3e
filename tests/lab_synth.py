"""Synthetic friction records from an independent forward solver (issue 10 tests): velocity
steps, and slide-hold-slide programs with holds (load-point velocity 0).

Quasi-static spring slider with rate-and-state friction and the ageing law, written here from
the equations and integrated by SciPy's ``solve_ivp`` (Radau) in the linear variables
``(tau, theta)`` (the spring force per unit normal force and the state), not the project's
RODAS4 in log variables::

    mu = mu0 + a ln(V/V0) + b ln(V0 theta/Dc)   ->   V = V0 exp((tau - mu0 - b ln(V0 theta/Dc))/a)
    dtau/dt = k (V_load - V),   dtheta/dt = 1 - V theta/Dc

The slip rate is a function of ``(tau, theta)``, positive for any finite ``tau``, so this
standard (unregularised) law stays valid through a hold: with the load point stopped the spring
unloads, ``V`` falls by decades but never reaches 0, and ``theta`` grows at nearly ``1``. (The
project uses the regularised ``asinh`` law for a program with a hold; the two differ by a
relative ``exp(-2 mu/a)``, about ``1e-87`` here.) ``tests/fit/test_shs.py`` checks the holds
against the closed-form healing ``b ln(1 + t_h/theta_ss)`` on a stiff machine.

The measured friction is ``tau + trend * x_lp + noise`` with ``x_lp`` the load-point
displacement from the first sample; the returned ``x_lp`` carries its own white noise
``Truth.x_noise`` (a displacement transducer's), the friction's trend uses the exact one.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

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
    x_noise: float = 0.0  # white noise on the returned load-point displacement, m


def synth_record(truth: Truth, velocities: list[float], duration_slip: float = 600e-6,
                 dt_per_um: float = 0.1, seed: int = 0) -> tuple[np.ndarray, np.ndarray,
                                                                 np.ndarray, np.ndarray]:
    """``(t, v_load, mu, x_lp)`` for load velocities ``velocities`` (m/s), each held for
    ``duration_slip`` m of load-point slip, at one fixed time step for the whole record:
    ``dt_per_um / 2`` um of slip at the slowest velocity. ``seed`` seeds the noise."""
    dt = dt_per_um * 1e-6 / min(velocities) * 0.5
    return synth_program(truth, [(vl, duration_slip / vl) for vl in velocities], dt, seed=seed)


def synth_program(truth: Truth, program: Sequence[tuple[float, float]], dt: float, *,
                  hold_dt: float | None = None, seed: int = 0
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(t, v_load, mu, x_lp)`` for a load program of ``(velocity m/s, duration s)`` items
    (velocity ``0``: a hold), starting in steady sliding at the first velocity (which must be
    ``> 0``; it is also ``V0``). Sampled every ``dt`` s, every ``hold_dt`` s in a hold (default
    ``dt``), with a sample at each change; each duration is rounded to whole samples (at least
    two). ``seed`` seeds the noise."""
    rng = np.random.default_rng(seed)
    tr = truth
    v0 = program[0][0]
    vmax = max(v for v, _ in program)
    assert v0 > 0.0, "the program starts sliding"

    def rhs(_t: float, y: np.ndarray, vl: float) -> list[float]:
        tau, th = y
        v = v0 * math.exp((tau - tr.mu0 - tr.b * math.log(v0 * th / tr.dc)) / tr.a)
        return [tr.stiffness * (vl - v), 1.0 - v * th / tr.dc]

    y = np.array([tr.mu0, tr.dc / v0])  # steady sliding at V0
    ts, vs, taus, xs = [], [], [], []
    t_now, x_now = 0.0, 0.0
    for vl, span in program:
        step = dt if vl > 0.0 or hold_dt is None else hold_dt
        n = max(int(round(span / step)), 2)
        te = t_now + step * np.arange(n)
        # theta's absolute tolerance on its steady value at this velocity (the fastest for a hold)
        tol = dict(rtol=1e-10, atol=[1e-13, 1e-12 * tr.dc / (vl if vl > 0.0 else vmax)])
        sol = solve_ivp(rhs, (t_now, t_now + n * step), y, method="Radau", t_eval=te,
                        args=(vl,), **tol)
        assert sol.success, sol.message
        ts.append(te)
        vs.append(np.full(n, vl))
        taus.append(sol.y[0])
        xs.append(x_now + vl * (te - t_now))
        end = solve_ivp(rhs, (te[-1], t_now + n * step), sol.y[:, -1], method="Radau",
                        args=(vl,), **tol)
        y = end.y[:, -1]
        x_now += vl * n * step
        t_now += n * step
    t = np.concatenate(ts)
    x = np.concatenate(xs)
    e = rng.normal(0.0, tr.noise, len(t))
    if tr.rho:  # AR(1) with the same stationary standard deviation
        from scipy.signal import lfilter
        s = math.sqrt(1.0 - tr.rho**2)
        e[1:] = lfilter([s], [1.0, -tr.rho], e[1:], zi=[tr.rho * e[0]])[0]
    mu = np.concatenate(taus) + tr.trend * x + e
    if tr.x_noise:  # drawn last: the friction's noise does not depend on it
        x = x + rng.normal(0.0, tr.x_noise, len(t))
    return t, np.concatenate(vs), mu, x


def shs_program(velocity: float, holds: Sequence[float], slide: float = 200e-6
                ) -> list[tuple[float, float]]:
    """Slide ``slide`` m at ``velocity``, then for each hold (s) the hold and a reslide of
    ``slide`` m at the same velocity: the ``(velocity, duration)`` items of
    :func:`synth_program`."""
    out = [(velocity, slide / velocity)]
    for h in holds:
        out += [(0.0, h), (velocity, slide / velocity)]
    return out


def write_lab_file(path: Path, t: np.ndarray, x: np.ndarray, mu: np.ndarray) -> Path:
    """A record as a lab file: tab-separated time (s), displacement (microns), friction."""
    np.savetxt(path, np.column_stack([t, x * 1e6, mu]), delimiter="\t",
               header="Time(s)\tDispl(microns)\tFriction", comments="", fmt="%.10g")
    return path
