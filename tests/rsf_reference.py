"""Independent reference integration of rate-and-state spring sliders for the tests.

Written from the equations (Dieterich 1979; Ruina 1983; Rice 1993 radiation damping) in
*linear* variables ``(V, theta_i[, tau])`` with SciPy's explicit DOP853 at a tight tolerance;
it shares no code with :mod:`dryfriction.rsf.driving` (which uses log variables, its own
Rosenbrock method and the exact Jacobian).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp


def reference_run(
    a, b, dc, mu0, v0, law, segments, *, stiffness, damping=0.0, mass=0.0, b2=0.0, dc2=None,
    v_init, theta_init=None, theta2_init=None, t_eval, rtol=1e-12,
):
    """Integrate segment by segment; return dict of t, v, theta(s), mu, stress at ``t_eval``.

    ``segments`` is a list of (load velocity m/s, duration s). Standard (non-regularised)
    friction, spring of finite stiffness.
    """
    dcs = [dc] + ([dc2] if dc2 is not None else [])
    bs = [b] + ([b2] if dc2 is not None else [])
    ns = len(dcs)

    def theta_dot(v, th):
        out = []
        for thi, dci in zip(th, dcs, strict=True):
            om = v * thi / dci
            out.append(1.0 - om if law == "ageing" else -om * math.log(om))
        return out

    def friction(v, th):
        return mu0 + a * np.log(v / v0) + sum(
            bi * np.log(v0 * thi / dci) for bi, thi, dci in zip(bs, th, dcs, strict=True)
        )

    th0 = [theta_init if theta_init is not None else dc / v_init]
    if ns == 2:
        th0.append(theta2_init if theta2_init is not None else dc2 / v_init)
    y = [v_init, *th0]
    if mass > 0:
        y.append(float(friction(v_init, th0)) + damping * v_init)
    y = np.array(y)
    t_eval = np.asarray(t_eval, float)
    out = np.full((len(t_eval), len(y)), np.nan)
    t0 = 0.0
    for vl, dur in segments:
        t1 = t0 + dur

        def rhs(t, y, vl=vl):
            v = y[0]
            th = y[1 : 1 + ns]
            thd = theta_dot(v, th)
            if mass > 0:
                tau = y[1 + ns]
                dv = (tau - friction(v, th) - damping * v) / mass
                return [dv, *thd, stiffness * (vl - v)]
            # d/dt of k (x_L - x) = mu + eta V: (a/V + eta) dV/dt = k(VL - V) - sum b_i thd_i/th_i
            s = sum(bi * tdi / thi for bi, tdi, thi in zip(bs, thd, th, strict=True))
            dv = (stiffness * (vl - v) - s) / (a / v + damping)
            return [dv, *thd]

        sel = (t_eval >= t0) & (t_eval < t1)
        times = np.append(t_eval[sel], t1)
        sol = solve_ivp(rhs, (t0, t1), y, method="DOP853", rtol=rtol, atol=1e-300,
                        t_eval=times)
        if not sol.success:
            raise RuntimeError(sol.message)
        out[sel] = sol.y[:, :-1].T
        y = sol.y[:, -1]
        t0 = t1
    out[t_eval == t0] = y
    v = out[:, 0]
    th = [out[:, 1 + i] for i in range(ns)]
    mu = friction(v, th)
    stress = out[:, 1 + ns] if mass > 0 else mu + damping * v
    res = {"t": t_eval, "v": v, "theta": th[0], "mu": mu, "stress": stress}
    if ns == 2:
        res["theta2"] = th[1]
    return res
