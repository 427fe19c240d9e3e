"""Synthetic records whose load point does what a servo does (issue 30 item 3): the commanded
velocity change smeared and overshot by the servo, the load point's velocity wandering (red),
friction with white and red noise, and a sampling rate that changes at the step, as on the
held-out basalt record of the issue (3 -> 10 um/s, 10 Hz before and 100 Hz after the change).

Forward model (written here, not the package's solver, and not ``records_zoo``'s, which drives
the slider with the commanded program): a quasi-static spring slider with rate-and-state
friction and the ageing law (Dieterich 1979; Ruina 1983) in the variables ``(tau, ln theta)``,
driven by the load point's *actual* velocity ``V_lp(t)``, integrated by SciPy's ``solve_ivp``
(LSODA)::

    V = V0 exp((tau - mu0 - b ln(V0 theta / Dc)) / a)
    dtau/dt = k (V_lp(t) - V),   d ln(theta)/dt = 1/theta - V/Dc

The servo (ours, a textbook model of a position loop): the load point's velocity follows the
commanded one as a damped second-order system, ``V_lp = V1 + (V2 - V1) s(t - t_cmd)`` with the
step response ``s(u) = 1 - exp(-zeta w u) (cos(w_d u) + zeta/sqrt(1 - zeta^2) sin(w_d u))``,
``w_d = w sqrt(1 - zeta^2)``: a rise of about ``1.8/w`` and an overshoot of
``exp(-pi zeta/sqrt(1 - zeta^2))`` (16 % at ``zeta = 0.5``); times ``(1 + eps(t))`` with
``eps`` an Ornstein-Uhlenbeck wander. The recorded displacement is the integral of ``V_lp``
plus white transducer noise; the recorded friction is ``tau + trend * x_lp`` plus white and
Ornstein-Uhlenbeck noise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from records_zoo import _ou  # the zoo's exact OU update, one definition


@dataclass(frozen=True)
class Machine:
    """The truth of one record (SI: m/s, m, 1/m, s)."""

    a: float = 0.0088
    b: float = 0.0093
    dc: float = 6.8e-6
    k: float = 7000.0
    mu0: float = 0.65
    trend: float = 5.0  # 1/m of load-point displacement
    v1: float = 3e-6
    v2: float = 10e-6
    t_cmd: float = 68.65  # s: the command changes between two samples at 10 Hz
    end: float = 98.7  # s: 300 um at 10 um/s after the change
    fs_before: float = 10.0  # Hz, up to the first sample at or after the change
    fs_after: float = 100.0
    servo_w: float = 2.0 * math.pi / 0.25  # rad/s: rise ~0.07 s, settled by ~0.3 s
    servo_zeta: float = 0.5
    wander_rms: float = 0.02  # relative, of the load point's velocity
    wander_tau: float = 2.0  # s
    x_noise: float = 0.15e-6  # m, white, of the displacement transducer
    mu_white: float = 5e-4
    mu_red: float = 6e-4  # Ornstein-Uhlenbeck part of the friction noise
    mu_red_tau: float = 0.5  # s


@dataclass
class MachineRecord:
    t: np.ndarray  # s, from 0
    x: np.ndarray  # recorded load-point displacement, m
    mu: np.ndarray  # recorded friction
    x_true: np.ndarray  # the load point's actual displacement, m
    mu_clean: np.ndarray  # friction without noise (trend included)
    truth: Machine


def servo_step(u: np.ndarray | float, w: float, zeta: float) -> np.ndarray:
    """The second-order step response ``s(u)`` of the module docstring (0 for ``u < 0``)."""
    u = np.asarray(u, float)
    wd = w * math.sqrt(1.0 - zeta**2)
    up = np.maximum(u, 0.0)
    s = 1.0 - np.exp(-zeta * w * up) * (np.cos(wd * up)
                                        + zeta / math.sqrt(1.0 - zeta**2) * np.sin(wd * up))
    return np.where(u > 0.0, s, 0.0)


def sample_times(m: Machine) -> np.ndarray:
    """10 Hz up to the first sample at or after the command, 100 Hz from there."""
    before = np.round(np.arange(0.0, m.end, 1.0 / m.fs_before), 9)
    j = int(np.searchsorted(before, m.t_cmd))
    switch = float(before[j])
    after = np.round(np.arange(switch + 1.0 / m.fs_after, m.end, 1.0 / m.fs_after), 9)
    return np.concatenate([before[: j + 1], after])


def load_point(m: Machine, rng: np.random.Generator, dt: float = 1e-3
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The load point on a fine grid: ``(t, V_lp, x_lp)`` (trapezoidal integral of ``V_lp``)."""
    tf = np.arange(0.0, m.end + 2 * dt, dt)
    v = m.v1 + (m.v2 - m.v1) * servo_step(tf - m.t_cmd, m.servo_w, m.servo_zeta)
    v = v * (1.0 + _ou(tf, m.wander_tau, m.wander_rms, rng))
    x = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * dt)])
    return tf, v, x


def friction(t: np.ndarray, tf: np.ndarray, vf: np.ndarray, m: Machine) -> np.ndarray:
    """Spring force ``tau`` at ``t`` driven by the load-point velocity ``vf`` on grid ``tf``
    (linear between grid points), from steady sliding at ``vf[0]`` (module docstring)."""
    v0 = float(vf[0])

    def rhs(s: float, y: np.ndarray) -> list[float]:
        tau, lth = y
        vl = float(np.interp(s, tf, vf))
        v = v0 * math.exp((tau - m.mu0 - m.b * (math.log(v0 / m.dc) + lth)) / m.a)
        return [m.k * (vl - v), math.exp(-lth) - v / m.dc]

    y0 = np.array([m.mu0, math.log(m.dc / v0)])
    # in two pieces, the second started just before the command, with short steps through
    # the servo's transient so that LSODA does not step over it
    cut = m.t_cmd - 0.05
    early = t[t < cut]
    s1 = solve_ivp(rhs, (0.0, cut), y0, method="LSODA", t_eval=early, rtol=1e-9,
                   atol=[1e-11, 1e-9])
    s2 = solve_ivp(rhs, (cut, float(t[-1])), s1.y[:, -1], method="LSODA", t_eval=t[t >= cut],
                   rtol=1e-9, atol=[1e-11, 1e-9], max_step=0.005)
    return np.concatenate([s1.y[0], s2.y[0]])


def basalt_like(seed: int = 0, m: Machine | None = None) -> MachineRecord:
    """The basalt-like record of issue 30 (defaults of :class:`Machine`), seeded."""
    m = Machine() if m is None else m
    rng = np.random.default_rng(seed)
    t = sample_times(m)
    tf, vf, xf = load_point(m, rng)
    x_true = np.interp(t, tf, xf)
    tau = friction(t, tf, vf, m)
    clean = tau + m.trend * x_true
    mu = clean + rng.normal(0.0, m.mu_white, t.size) + _ou(t, m.mu_red_tau, m.mu_red, rng)
    x = x_true + rng.normal(0.0, m.x_noise, t.size) + 1e-3
    return MachineRecord(t, x, mu, x_true + 1e-3, clean, m)


def program_friction(t: np.ndarray, t_change: float, m: Machine, *, a: float, b: float,
                     dc: float, k: float, mu0: float, trend: float) -> np.ndarray:
    """The same forward model driven by the idealised program (``v1`` until ``t_change``,
    ``v2`` after), plus ``trend`` times the program's displacement from ``t[0]``: what an
    independent fit with a given change time uses (the issue's rsfmodel fit did the same)."""
    mm = Machine(**{**m.__dict__, "a": a, "b": b, "dc": dc, "k": k, "mu0": mu0})
    tf = np.array([t[0], t_change, t_change + 1e-9, t[-1] + 1.0])
    vf = np.array([m.v1, m.v1, m.v2, m.v2])
    tau = _friction_from(t, tf, vf, mm)
    x = np.where(t < t_change, m.v1 * (t - t[0]),
                 m.v1 * (t_change - t[0]) + m.v2 * (t - t_change))
    return tau + trend * x


def _friction_from(t: np.ndarray, tf: np.ndarray, vf: np.ndarray, m: Machine) -> np.ndarray:
    """:func:`friction` from ``t[0]`` (steady sliding there), the change at ``tf[1]``."""
    v0 = float(vf[0])

    def rhs(s: float, y: np.ndarray, vl: float) -> list[float]:
        tau, lth = y
        v = v0 * math.exp((tau - m.mu0 - m.b * (math.log(v0 / m.dc) + lth)) / m.a)
        return [m.k * (vl - v), math.exp(-lth) - v / m.dc]

    tc = float(tf[1])
    y0 = np.array([m.mu0, math.log(m.dc / v0)])
    first = t[t < tc]
    out = [first * 0.0 + m.mu0]  # steady sliding until the change
    s2 = solve_ivp(rhs, (tc, float(t[-1])), y0, method="LSODA", t_eval=t[t >= tc],
                   args=(float(vf[-1]),), rtol=1e-9, atol=[1e-11, 1e-9], max_step=0.5)
    out.append(s2.y[0])
    return np.concatenate(out)


def write_record(path, rec: MachineRecord):  # type: ignore[no-untyped-def]
    """Tab-separated time (s), displacement (microns), friction, as the shared record."""
    np.savetxt(path, np.column_stack([rec.t, rec.x * 1e6, rec.mu]), delimiter="\t",
               header="Time(s)\tDispl(microns)\tFriction", comments="", fmt="%.10g")
    return path
