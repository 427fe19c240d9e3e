"""The ensemble's compiled kernel: one Numba loop over the window of pairs (docs/model.md §6).

The model (states, transitions, units) is described in :mod:`.population`, which owns the
population and calls :func:`advance_window`; this module holds only what is compiled and the
radius table the compiled code reads.

Numerics
--------
Only a window of pairs is touched: the pairs are kept sorted by ``c`` in a buffer that follows
the slider, and every pair outside the window ``[lo, hi)`` is free, far-side below ``lo`` and
near-side from ``hi`` on. The per-trap update is one Numba-compiled loop over the window. The
radius ``a_r`` is read from a cubic Hermite table in ``ln(1 + age)`` built from the creep law's
own exact functions (exact for the log law, whose ``a_r^2`` is linear in that variable).

Every compiled function keeps ``cache=True``: a fresh process loads the machine code from
Numba's disk cache instead of compiling for seconds.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..theory.creep import CreepLaw
from ..validation import Array

__all__ = ["FREE_NEAR", "PLUS", "MINUS", "FREE_FAR", "OUT_SIZE", "radius_table", "advance_window"]


# The kernel spells these states as the literals 0-3 (see advance_window).
FREE_NEAR: int = 0
"""Not in contact, on the near side (``p < -1``)."""
PLUS: int = 1
"""On the (+) branch (asperity held on the near side)."""
MINUS: int = 2
"""On the (-) branch (far side of the bump)."""
FREE_FAR: int = 3
"""Not in contact, on the far side."""

OUT_SIZE: int = 9
"""Length of the ``out`` array that :func:`advance_window` fills."""

_TABLE_POINTS = 4097  # nodes of the a_r^2 table in ln(1 + age)
_FORCE_TABLE = False  # tests set this to check the table against the closed-form log law
# fast-math flags without "no NaN / no inf" (the kernel uses inf as a sentinel)
_FAST = {"nsz", "arcp", "contract", "afn", "reassoc"}


def radius_table(law: CreepLaw, age_max: float) -> tuple[float, Array, Array, float]:
    """Tabulate ``a_r^2`` and its derivative on a uniform grid of ``u = ln(1 + age)``.

    Parameters
    ----------
    law : CreepLaw
        The creep law whose exact functions are tabulated.
    age_max : float
        Largest age (``t0``) the table must cover; it covers somewhat more.

    Returns
    -------
    h, s_tab, ds_tab, age_cover : float, ndarray, ndarray, float
        Grid step in ``u``, ``a_r^2`` and ``d(a_r^2)/du`` at the nodes (the arguments of the
        compiled ``_radius_sq``), and the largest age covered. For the log law ``h = -1`` and
        ``s_tab = [eps, 0]``: the kernel then uses the closed form, which the table would
        reproduce exactly but more slowly.
    """
    u_max = math.log1p(age_max) * 1.25 + 1.0
    u = np.linspace(0.0, u_max, _TABLE_POINTS)
    T = np.expm1(u)
    q = law.clock(T)
    s = law.radius_sq(q)
    # d(a_r^2)/du = [d(a_r^2)/dc] / [dT/dc] * dT/du, dT/du = 1 + T
    ds = law.dradius_sq(q) / law.dage(q) * (1.0 + T)
    h = float(u[1] - u[0])
    s_tab = np.ascontiguousarray(s, dtype=float)
    ds_tab = np.ascontiguousarray(ds, dtype=float)
    if law.name == "log" and not _FORCE_TABLE:
        h = -1.0
        s_tab = np.array([law.eps, 0.0])
    return h, s_tab, ds_tab, float(np.expm1(u_max))


@numba.njit(cache=True, inline="always", fastmath=_FAST)
def _radius_sq(age: float, h: float, s_tab: Array, ds_tab: Array) -> float:
    """``a_r^2(age)`` by cubic Hermite interpolation in ``u = ln(1 + age)`` (ours).

    ``h < 0`` flags the log law, ``a_r^2 = 1 + eps u`` with ``eps = s_tab[0]`` (eq. 17), which
    the table would reproduce exactly (it is linear in ``u``) but more slowly.
    """
    u = math.log(1.0 + age)  # not log1p: 2.5x faster here; the rounding of 1 + age only
    # shifts a_r^2 by eps * 1e-16 in absolute terms
    if h < 0.0:
        return 1.0 + s_tab[0] * u
    x = u / h
    j = int(x)
    n = s_tab.shape[0]
    if j > n - 2:
        j = n - 2
    tt = x - j
    t2 = tt * tt
    t3 = t2 * tt
    return ((2.0 * t3 - 3.0 * t2 + 1.0) * s_tab[j] + (t3 - 2.0 * t2 + tt) * h * ds_tab[j]
            + (3.0 * t2 - 2.0 * t3) * s_tab[j + 1] + (t3 - t2) * h * ds_tab[j + 1])


@numba.njit(cache=True, inline="always", fastmath=_FAST)
def _f_plus(w: float, alpha: float, want_k: bool) -> tuple[float, float]:
    """``f_+(w)`` and (if ``want_k``, else 0) ``f_+'(w)``, units ``Phi0/a`` (docs/model.md §1).

    ``f_+ = 6 alpha (w - z_+)``, ``z_+ = -((1 - alpha) + sqrt(D))/2``,
    ``D = (1 - alpha)^2 - 4 alpha w``; ``f_+' = 6 alpha (1 - alpha/sqrt(D))`` (ours).
    """
    d = (1.0 - alpha) ** 2 - 4.0 * alpha * w
    if d < 1e-300:
        d = 1e-300
    sd = math.sqrt(d)
    z = -0.5 * ((1.0 - alpha) + sd)
    return 6.0 * alpha * (w - z), (6.0 * alpha * (1.0 - alpha / sd) if want_k else 0.0)


@numba.njit(cache=True, fastmath=_FAST)
def advance_window(c, state, birth, lo, hi, x0, x1, t0, t1, direction, alpha, yc, strong,
             h, s_tab, ds_tab, commit, want_k, out):  # pragma: no cover - compiled
    """Move the slider from ``x0`` (time ``t0``) to ``x1`` (time ``t1``), linearly in between.

    Applies every transition of the module docstring to the pairs of the window (extended by
    the pairs that enter contact), writes the new states when ``commit`` and returns the new
    window ``(lo, hi)``. ``out`` receives ``[sum f, sum df/dp, n_active, sum age, births,
    spinodal, exits, next_event, overflow]``; ``next_event`` is evaluated at frozen time
    ``t1`` in ``direction`` (+1 or -1). ``overflow`` is 1 if the window reached the buffer end.
    """
    n = c.shape[0]
    dx = x1 - x0
    a = lo
    b = hi
    while b < n and x1 - c[b] >= -1.0:
        b += 1
    while a > 0 and x1 - c[a - 1] <= 1.0:
        a -= 1
    overflow = 0.0
    if b >= n or a <= 0:
        overflow = 1.0
    F = 0.0
    K = 0.0
    nact = 0
    agesum = 0.0
    born = 0
    spin = 0
    exits = 0
    nxt = math.inf if direction > 0 else -math.inf
    for i in range(a, b):
        s = state[i]
        p = x1 - c[i]
        if s == 1:  # fast path: a (+) trap that stays on (+)
            tb = birth[i]
            R = _radius_sq(t1 - tb, h, s_tab, ds_tab)
            r = math.sqrt(R)
            w = p / r
            if -1.0 <= w <= yc:
                f, df = _f_plus(w, alpha, want_k)
                F += R * f
                K += r * df
                nact += 1
                agesum += t1 - tb
                if direction > 0:
                    e = c[i] + yc * r
                    if e < nxt:
                        nxt = e
                continue
        tb = birth[i]
        r = 1.0
        w = p
        for _ in range(6):
            if s == 0:  # FREE_NEAR
                if dx > 0.0 and p >= -1.0:
                    frac = (-1.0 - (x0 - c[i])) / dx
                    frac = min(max(frac, 0.0), 1.0)
                    tb = t0 + frac * (t1 - t0)
                    s = 1
                    born += 1
                else:
                    break
            elif s == 3:  # FREE_FAR
                if dx < 0.0 and p <= 1.0:
                    frac = (1.0 - (x0 - c[i])) / dx
                    frac = min(max(frac, 0.0), 1.0)
                    tb = t0 + frac * (t1 - t0)
                    s = 2
                    born += 1
                else:
                    break
            else:
                r = math.sqrt(_radius_sq(t1 - tb, h, s_tab, ds_tab))
                w = p / r
                if s == 1:
                    if w > yc:
                        spin += 1
                        if strong:
                            s = 2
                        else:
                            s = 3
                            break
                    elif w < -1.0:
                        s = 0
                        exits += 1
                        break
                    else:
                        break
                else:
                    if w > 1.0:
                        s = 3
                        exits += 1
                        break
                    elif w < -yc:
                        spin += 1
                        if strong:
                            s = 1
                        else:
                            s = 0
                            break
                    else:
                        break
        if s == 1 or s == 2:
            if s == 1:
                f, df = _f_plus(w, alpha, want_k)
            else:
                f, df = _f_plus(-w, alpha, want_k)
                f = -f
            F += r * r * f
            K += r * df
            nact += 1
            agesum += t1 - tb
            if direction > 0 and s == 1:
                e = c[i] + yc * r
                if e < nxt:
                    nxt = e
            elif direction < 0 and s == 2:
                e = c[i] - yc * r
                if e > nxt:
                    nxt = e
        elif s == 0 and direction > 0:
            e = c[i] + yc
            if e < nxt:
                nxt = e
        elif s == 3 and direction < 0:
            e = c[i] - yc
            if e > nxt:
                nxt = e
        if commit:
            state[i] = s
            birth[i] = tb
    # pairs not yet in the window that would enter next
    if direction > 0 and b < n:
        e = c[b] + yc
        if e < nxt:
            nxt = e
    if direction < 0 and a > 0:
        e = c[a - 1] - yc
        if e > nxt:
            nxt = e
    out[0] = F
    out[1] = K
    out[2] = nact
    out[3] = agesum
    out[4] = born
    out[5] = spin
    out[6] = exits
    out[7] = nxt
    out[8] = overflow
    if not commit:
        return lo, hi
    while a < b and state[a] == 3:
        a += 1
    while b > a and state[b - 1] == 0:
        b -= 1
    return a, b

