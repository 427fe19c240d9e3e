"""Synthetic space-time fields of an extended interface with known fronts and events (for the
tests of analysis/fronts.py, analysis/catalogue.py and their figures).

Each event is a front leaving element ``i_nuc`` at time ``t_nuc`` at speed ``c`` in both
directions over the elements ``lo..hi``; element ``i`` slips with the trapezoid
``A * trap(t - T_i)`` (rise ``r``, hold ``h``, fall ``r``) from its arrival ``T_i = t_nuc +
|x_i - x_nuc|/c``, so the threshold crossings are on straight pieces of the slip rate and the
slip of element ``i`` in the event is ``A (r + h)``; the slip is the exact integral.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Pulse:
    i_nuc: int
    lo: int
    hi: int
    t_nuc: float
    c: float
    A: float = 4.0
    r: float = 0.2
    h: float = 0.3


def _q(u):
    return 0.5 * np.maximum(u, 0.0) ** 2


def _r(u):
    return np.maximum(u, 0.0)


def fields(t, x, pulses, v_bg=0.0):
    """(slip_rate, slip) of the pulses over a uniform creep ``v_bg``."""
    t = np.asarray(t, float)[:, None]
    v = np.full((t.size, len(x)), v_bg)
    s = v_bg * (t - t[0]) * np.ones((1, len(x)))
    for p in pulses:
        for i in range(p.lo, p.hi + 1):
            tau = t[:, 0] - (p.t_nuc + abs(x[i] - x[p.i_nuc]) / p.c)
            a, r, h = p.A, p.r, p.h
            v[:, i] += a / r * (_r(tau) - _r(tau - r) - _r(tau - r - h) + _r(tau - 2 * r - h))
            s[:, i] += a / r * (_q(tau) - _q(tau - r) - _q(tau - r - h) + _q(tau - 2 * r - h))
    return v, s


def grid(n_x=40, dx=0.5, x0=1.25, t_end=6.0, dt=0.013):
    x = x0 + dx * np.arange(n_x)
    t = np.arange(0.0, t_end, dt)
    return t, x
