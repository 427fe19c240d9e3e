"""An independent forward model of the state laws of issue 30 item 5, for tests: written here,
not the package's solver (RODAS4 on ``ln V, ln theta``).

A quasi-static spring slider with the standard rate-and-state friction, in the variables
``(tau, ln theta[, ln theta2])``, integrated by SciPy's ``solve_ivp`` (LSODA)::

    V = V0 exp((tau - mu0 - b ln(V0 theta/Dc) - b2 ln(V0 theta2/Dc2)) / a)
    dtau/dt = k (V_load - V)

and per law, ``d ln theta/dt`` =

* ageing (Dieterich 1979): ``1/theta - V/Dc``;
* slip (Ruina 1983): ``-(V/Dc) ln(V theta/Dc)``;
* prz (Perrin, Rice & Zheng 1995, ``theta = theta'/2`` so that ``theta_ss = Dc/V``):
  ``(1 - (V theta/Dc)^2)/(2 theta)``;
* nagata (Nagata, Nakatani & Yoshida 2012): ``1/theta - V/Dc - (c/b) dtau/dt``;
* ageing2: the ageing law for ``theta`` and ``theta2`` (with ``Dc2``).
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
    k: float = 3000.0  # 1/m
    law: str = "ageing"
    c: float = 0.0
    b2: float = 0.0
    dc2: float = 1.0


def _dlnth(tr: Truth, v: float, lnth: float, dc: float, dtau: float) -> float:
    th = math.exp(lnth)
    if tr.law in ("ageing", "ageing2"):
        return 1.0 / th - v / dc
    if tr.law == "nagata":
        return 1.0 / th - v / dc - tr.c / tr.b * dtau
    if tr.law == "prz":
        om = v * th / dc
        return (1.0 - om * om) / (2.0 * th)
    return -(v / dc) * math.log(v * th / dc)


def simulate(tr: Truth, program: list[tuple[float, float]], dt: float, v0: float,
             lnth0: float | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(t, v_load, mu)`` sampled every ``dt`` s along ``program`` (``(velocity m/s,
    duration s)``), from steady sliding at the first velocity (or ``ln theta = lnth0``, the
    slider at the load velocity), reference velocity ``v0``."""
    two = tr.law == "ageing2"
    v1 = program[0][0]
    lnth = math.log(tr.dc / v1) if lnth0 is None else lnth0
    y = [tr.mu0 + tr.a * math.log(v1 / v0) + tr.b * math.log(v0 * math.exp(lnth) / tr.dc),
         lnth]
    if two:  # the second state variable starts steady
        y.append(math.log(tr.dc2 / v1))
        y[0] += tr.b2 * math.log(v0 / v1)
    ts, vs, mus = [], [], []
    t0 = 0.0
    for j, (vl, dur) in enumerate(program):
        def f(_t: float, z: np.ndarray, vl: float = vl) -> list[float]:
            psi = tr.mu0 + tr.b * math.log(v0 * math.exp(z[1]) / tr.dc)
            if two:
                psi += tr.b2 * math.log(v0 * math.exp(z[2]) / tr.dc2)
            v = v0 * math.exp((z[0] - psi) / tr.a)
            dtau = tr.k * (vl - v)
            out = [dtau, _dlnth(tr, v, z[1], tr.dc, dtau)]
            if two:
                out.append(1.0 / math.exp(z[2]) - v / tr.dc2)
            return out

        n = int(round(dur / dt))
        te = t0 + dt * np.arange(n + 1)
        sol = solve_ivp(f, (t0, te[-1]), y, method="LSODA", t_eval=te, rtol=1e-11,
                        atol=1e-13)
        assert sol.success, sol.message
        # a sample at a change belongs to the new velocity (SeriesData.segments)
        keep = slice(0, None) if j == len(program) - 1 else slice(0, -1)
        ts.append(sol.t[keep])
        mus.append(sol.y[0][keep])
        vs.append(np.full(len(sol.t[keep]), vl))
        y = list(sol.y[:, -1])
        t0 = float(te[-1])
    return np.concatenate(ts), np.concatenate(vs), np.concatenate(mus)
