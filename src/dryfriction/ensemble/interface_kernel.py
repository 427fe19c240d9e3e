"""The extended interface's compiled kernel: a chain of trap-model blocks stepped in time, the
contact windows of all elements updated in one parallel loop (the model is in
:mod:`.interface`).

Each element owns a stretch ``[off[i], off[i+1])`` of the flat pair arrays (positions ``c``,
states, births: :mod:`.kernel`'s layout) and its window ``[lo[i], hi[i])`` in it. A step of
velocity Verlet moves every block, then updates the windows of all blocks in a ``prange`` over
elements by the single slider's :func:`.kernel.advance_window` (so one block is the single slider
to the last bit, :mod:`.interface`), then takes the new accelerations with the coupling.

Equation of motion of block ``i`` (Burridge & Knopoff, BSSA 57, 341 (1967), with the trap
population's friction ``F_i``; ours otherwise)::

    m x_i'' = K_p (P(t) - x_i) + k_c (x_{i+1} - x_i) + k_c (x_{i-1} - x_i)
              + [i = 0] K_s (L(t) - x_0) - F_i - eta x_i'

free ends (a missing neighbour contributes nothing), ``P`` the top plate, ``L`` the edge
load point. The energy terms are trapezoid sums over each step (ours; the balance then holds
to the integrator's order): the work of the moving driver ``int S dL``, the work against the
contacts ``sum_i int F_i dx_i``, the damping ``sum_i int eta v_i^2 dt``.
"""

from __future__ import annotations

import numba
import numpy as np

from .kernel import OUT_SIZE, advance_window

__all__ = ["OUT_SIZE", "advance_chain", "load_position"]


@numba.njit(cache=True)
def load_position(t, p_times, p_pos, p_vel):  # pragma: no cover - compiled
    """Position of a piecewise-linear program at ``t``: bit for bit
    :func:`.result.position_function` (``bisect_right - 1``, clipped to the segments)."""
    i = np.searchsorted(p_times, t, side="right") - 1
    last = p_vel.shape[0] - 1
    if i < 0:
        i = 0
    if i > last:
        i = last
    return p_pos[i] + p_vel[i] * (t - p_times[i])


@numba.njit(cache=True)
def _block(i, c, state, birth, off, lo, hi, x, x_new, f_new, fscale, t, t_new, alpha, yc,
           strong, h, s_tab, ds_tab, outs):  # pragma: no cover - compiled
    """Block ``i``'s window from ``x[i]`` at ``t`` to ``x_new[i]`` at ``t_new`` and its new
    friction ``f_new[i]`` (:func:`.kernel.advance_window` on its stretch of the pairs)."""
    s0 = off[i]
    s1 = off[i + 1]
    direction = 1 if x_new[i] >= x[i] else -1
    lo_i, hi_i = advance_window(c[s0:s1], state[s0:s1], birth[s0:s1], lo[i], hi[i], x[i],
                                x_new[i], t, t_new, direction, alpha, yc, strong, h, s_tab,
                                ds_tab, True, False, outs[i])
    lo[i] = lo_i
    hi[i] = hi_i
    f_new[i] = outs[i, 0] * fscale[i]


@numba.njit(cache=True, parallel=True)
def advance_chain(c, state, birth, off, lo, hi, x, v, a, f, fscale, t, t1, dt_osc, dx_max,
                  mass, eta, kp, kc, ks, side, plate_fixed, load0, p_times, p_pos, p_vel, p_x0,
                  alpha, yc, strong, h, s_tab, ds_tab, outs, wfric, wdamp, acc, serial
                  ):  # pragma: no cover - compiled
    """Step the chain from time ``t`` to ``t1`` (arrays updated in place).

    The step follows the single slider's inertial driver (:mod:`.driving`, ``_run_spring``):
    ``dt = min(dt_osc, t1 - t, dx_max / max_i |v_i|)`` (the last step lands on ``t1``), the
    position ``x + v dt + a dt^2/2``, the window update at the new time, the acceleration with
    the damping at the predicted velocity ``v + a dt``, ``v += (a + a_new) dt/2``.

    ``f`` holds the friction at the present positions on entry and is updated; ``fscale`` the
    factor from a window's force sum to ``F_el`` per element. The load point ``L(t) = load0 +
    program(t) - p_x0`` moves the top plate (``side = False``; ``kp`` on every block) or the edge
    spring (``side = True``; ``ks`` on block 0, the plate fixed at ``plate_fixed``). ``acc``
    accumulates ``[work_load, steps, trap updates, overflow]``; ``wfric``, ``wdamp`` per element.
    ``serial`` updates the windows in a plain loop (one thread); else in a ``prange``, the same
    numbers either way (each block's update touches only its own arrays).

    Returns the time reached (``t1``, or the step where a window reached its buffer's end).
    """
    n = x.shape[0]
    x_new = np.empty(n)
    f_new = np.empty(n)
    while t < t1:
        dt = min(dt_osc, t1 - t)
        vmax = 0.0
        for i in range(n):
            av = abs(v[i])
            if av > vmax:
                vmax = av
        if vmax != 0.0:
            dt = min(dt, dx_max / vmax)
        if t1 - (t + dt) < 1e-12 * max(1.0, t1):
            dt = t1 - t
        t_new = t1 if dt == t1 - t else t + dt
        for i in range(n):
            x_new[i] = x[i] + v[i] * dt + 0.5 * a[i] * dt * dt
        if serial:  # one thread: no parallel region to open and join every step
            for i in range(n):
                _block(i, c, state, birth, off, lo, hi, x, x_new, f_new, fscale, t, t_new,
                       alpha, yc, strong, h, s_tab, ds_tab, outs)
        else:
            for i in numba.prange(n):
                _block(i, c, state, birth, off, lo, hi, x, x_new, f_new, fscale, t, t_new,
                       alpha, yc, strong, h, s_tab, ds_tab, outs)
        # the driver's position and its springs' force on the chain, before and after
        l_old = load0 + load_position(t, p_times, p_pos, p_vel) - p_x0
        l_new = load0 + load_position(t_new, p_times, p_pos, p_vel) - p_x0
        if side:
            s_old = ks * (l_old - x[0])
            s_new = ks * (l_new - x_new[0])
            plate = plate_fixed
        else:
            s_old = 0.0
            s_new = 0.0
            for i in range(n):
                s_old += kp * (l_old - x[i])
                s_new += kp * (l_new - x_new[i])
            plate = l_new
        acc[0] += 0.5 * (s_old + s_new) * (l_new - l_old)
        for i in range(n):
            cpl = 0.0
            if i > 0:
                cpl += kc * (x_new[i - 1] - x_new[i])
            if i < n - 1:
                cpl += kc * (x_new[i + 1] - x_new[i])
            edge = ks * (l_new - x_new[i]) if (side and i == 0) else 0.0
            vp = v[i] + a[i] * dt
            a_new = (kp * (plate - x_new[i]) + cpl + edge - f_new[i] - eta * vp) / mass
            v_new = v[i] + 0.5 * (a[i] + a_new) * dt
            wfric[i] += 0.5 * (f[i] + f_new[i]) * (x_new[i] - x[i])
            wdamp[i] += eta * 0.5 * (v[i] * v[i] + v_new * v_new) * dt
            acc[2] += hi[i] - lo[i]
            if outs[i, 8] != 0.0:
                acc[3] = 1.0
            x[i] = x_new[i]
            v[i] = v_new
            a[i] = a_new
            f[i] = f_new[i]
        acc[1] += 1.0
        t = t_new
        if acc[3] != 0.0:
            break
    return t
