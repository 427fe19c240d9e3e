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

__all__ = ["OUT_SIZE", "QS_NEWTON_MAX", "QS_TOL", "advance_chain", "advance_chain_multirate",
           "load_position", "probe_chain", "settle_chain"]


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


@numba.njit(cache=True)
def _driver_step(t, t_new, x, x_new, n, side, kp, ks, load0, plate_fixed, p_times, p_pos,
                 p_vel, p_x0):  # pragma: no cover - compiled
    """The load point at ``t_new``, the plate the leaf springs pull from, and the driver's
    work over the step (trapezoid of its springs' force on the chain times the load point's
    travel): shared by :func:`advance_chain` and :func:`advance_chain_multirate`."""
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
    return l_new, plate, 0.5 * (s_old + s_new) * (l_new - l_old)


@numba.njit(cache=True)
def _step_spring_force(i, n, x, load, side, plate, kp, kc, ks):  # pragma: no cover - compiled
    """The springs' force on block ``i`` in the stepping kernels, summed as
    ``kp (plate - x_i) + coupling + edge`` (that order: :func:`_spring_force` sums in another,
    which would change the runs in their last bits)."""
    cpl = 0.0
    if i > 0:
        cpl += kc * (x[i - 1] - x[i])
    if i < n - 1:
        cpl += kc * (x[i + 1] - x[i])
    edge = ks * (load - x[i]) if (side and i == 0) else 0.0
    return kp * (plate - x[i]) + cpl + edge


@numba.njit(cache=True, parallel=True)
def advance_chain(c, state, birth, off, lo, hi, x, v, a, f, fscale, t, t1, dt_osc, dx_max,
                  mass, eta, kp, kc, ks, side, plate_fixed, load0, p_times, p_pos, p_vel, p_x0,
                  alpha, yc, strong, h, s_tab, ds_tab, outs, wfric, wdamp, acc, serial,
                  v_qs=0.0, omega_qs=1.0, t_min=0.0):  # pragma: no cover - compiled
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

    Event-driven runs (:mod:`.interface`): with ``v_qs > 0`` the stepping also stops, once the
    time has passed ``t_min``, at the first step after which every block is quiet,
    ``v_i^2 + (a_i/omega_qs)^2 < v_qs^2`` (its slip rate and the rate its unbalanced force
    would give it within an oscillation of angular frequency ``omega_qs``); ``v_qs = 0`` never
    stops early, so the arithmetic is the dynamic run's.

    Returns the time reached (``t1``, the step where a window reached its buffer's end, or the
    first quiet step).
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
        l_new, plate, work = _driver_step(t, t_new, x, x_new, n, side, kp, ks, load0,
                                          plate_fixed, p_times, p_pos, p_vel, p_x0)
        acc[0] += work
        for i in range(n):
            vp = v[i] + a[i] * dt
            a_new = (_step_spring_force(i, n, x_new, l_new, side, plate, kp, kc, ks)
                     - f_new[i] - eta * vp) / mass
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
        if v_qs > 0.0 and t >= t_min and t < t1:
            quiet = True
            for i in range(n):
                if v[i] * v[i] + (a[i] / omega_qs) ** 2 >= v_qs * v_qs:
                    quiet = False
                    break
            if quiet:
                break
    return t


@numba.njit(cache=True)
def _block_lazy(i, c, state, birth, off, lo, hi, xu, tu, x_new, t_new, f_new, k_new, fscale,
                alpha, yc, strong, h, s_tab, ds_tab, outs, ne, nd):  # pragma: no cover - compiled
    """Block ``i``'s window from its last update (``xu[i]`` at ``tu[i]``) to ``x_new[i]`` at
    ``t_new``, its friction ``f_new[i]``, stiffness ``k_new[i] = dF_i/dx``, and its next
    contact's spinodal ``ne[i]`` in the direction ``nd[i]`` it moved (ours)."""
    s0 = off[i]
    s1 = off[i + 1]
    direction = 1 if x_new[i] >= xu[i] else -1
    lo_i, hi_i = advance_window(c[s0:s1], state[s0:s1], birth[s0:s1], lo[i], hi[i], xu[i],
                                x_new[i], tu[i], t_new, direction, alpha, yc, strong, h, s_tab,
                                ds_tab, True, True, outs[i])
    lo[i] = lo_i
    hi[i] = hi_i
    f_new[i] = outs[i, 0] * fscale[i]
    k_new[i] = outs[i, 1] * fscale[i]
    ne[i] = outs[i, 7]
    nd[i] = direction


@numba.njit(cache=True, parallel=True)
def advance_chain_multirate(c, state, birth, off, lo, hi, x, v, a, f, fscale, t, t1, dt_osc,
                            dx_max, mass, eta, kp, kc, ks, side, plate_fixed, load0, p_times,
                            p_pos, p_vel, p_x0, alpha, yc, strong, h, s_tab, ds_tab, outs,
                            wfric, wdamp, acc, serial, v_qs, omega_qs, t_min, xu, tu, fu, ku,
                            path, ne, nd, par_min):  # pragma: no cover - compiled
    """:func:`advance_chain` with every block's contact window on its own clock (ours).

    The chain steps together as in :func:`advance_chain` (the same step, set by the fastest
    block and the stiffest mode; velocity Verlet; the springs at every step), but block ``i``'s
    window, the cost, is updated only when its own rule asks: when it is the fastest block
    (which sets the step, so that one block is :func:`advance_chain` bit for bit), when it
    has passed the next
    spinodal of its contacts ahead (``ne``, found at the last update at frozen time: ageing
    only moves a spinodal further, so no contact gives way unseen; the step where a contact
    gives way is the step where its force drops, as in :func:`advance_chain`), or when the
    slip path since its last update would pass ``dx_max`` (a quarter trap spacing, the
    single slider's bound, now per block) after one more step of the present size, or the
    time since it would pass ``dt_osc``. In between, its friction is the first-order
    expansion about the last update, ``F_i = fu_i + ku_i (x_i - xu_i)`` (``ku_i = dF_i/dx``
    of the window then: the contacts' elastic stiffness is kept in the fast dynamics; their
    ageing over at most ``dt_osc`` and the curvature of ``f_+`` over at most ``dx_max`` are
    neglected until the next update). An
    update applies every transition on the block's straight path from ``xu_i`` at ``tu_i``
    to its present position, as one step of :func:`advance_chain` over that interval would.

    This is multiple time stepping (the idea of r-RESPA, Tuckerman, Berne & Martyna, J. Chem.
    Phys. 97, 1990 (1992): the expensive force on a slow clock, the cheap ones on the fast
    one), with the slow force extrapolated rather than applied as impulses (ours). In a step
    where every block is due, the arithmetic is :func:`advance_chain`'s (the stiffness is
    computed too, which changes no force).

    ``xu, tu, fu, ku, path, ne, nd`` (per block) carry the last updates between calls; on
    entry they must describe the windows as they are (:func:`probe_chain` after any other
    kernel moved them). Energy: the work against the contacts is the trapezoid of the force
    the blocks felt, so the balance holds as in :func:`advance_chain`. On an early return
    (every block quiet, or a window's overflow) every block is brought up to date at the time
    reached, its force replaced by the window's (no slip: no work) and its acceleration by
    the new force's.
    ``par_min``: fewest blocks due in one step whose windows are updated in a ``prange``.

    Returns the time reached, as :func:`advance_chain`; ``acc[2]`` counts the trap updates
    actually made.
    """
    n = x.shape[0]
    x_new = np.empty(n)
    f_new = np.empty(n)
    k_new = np.empty(n)
    due = np.empty(n, np.int64)
    while t < t1:
        vmax = 0.0
        fastest = 0
        for i in range(n):
            av = abs(v[i])
            if av > vmax:
                vmax = av
                fastest = i
        step = dt_osc  # the step's bound, before a sample cuts it short
        if vmax != 0.0:
            step = min(step, dx_max / vmax)
        dt = min(step, t1 - t)
        if t1 - (t + dt) < 1e-12 * max(1.0, t1):
            dt = t1 - t
        t_new = t1 if dt == t1 - t else t + dt
        m = 0
        for i in range(n):
            x_new[i] = x[i] + v[i] * dt + 0.5 * a[i] * dt * dt
            d = abs(x_new[i] - x[i])
            path[i] += d
            # due: the fastest block (it sets the step: one block is advance_chain bit for
            # bit), a block past its next spinodal, or one that one more step would take past
            # its slip or time bound
            if (i == fastest or path[i] + d > dx_max or (t_new - tu[i]) + step > dt_osc
                    or (x_new[i] - ne[i]) * nd[i] >= 0.0):
                due[m] = i
                m += 1
        if serial or m < par_min:
            for k in range(m):
                _block_lazy(due[k], c, state, birth, off, lo, hi, xu, tu, x_new, t_new, f_new,
                            k_new, fscale, alpha, yc, strong, h, s_tab, ds_tab, outs, ne, nd)
        else:
            for k in numba.prange(m):
                _block_lazy(due[k], c, state, birth, off, lo, hi, xu, tu, x_new, t_new, f_new,
                            k_new, fscale, alpha, yc, strong, h, s_tab, ds_tab, outs, ne, nd)
        for i in range(n):
            f_new[i] = fu[i] + ku[i] * (x_new[i] - xu[i])  # overwritten below if due
        for k in range(m):
            i = due[k]
            f_new[i] = outs[i, 0] * fscale[i]
            fu[i] = f_new[i]
            ku[i] = k_new[i]
            xu[i] = x_new[i]
            tu[i] = t_new
            path[i] = 0.0
            acc[2] += hi[i] - lo[i]
            if outs[i, 8] != 0.0:
                acc[3] = 1.0
        l_new, plate, work = _driver_step(t, t_new, x, x_new, n, side, kp, ks, load0,
                                          plate_fixed, p_times, p_pos, p_vel, p_x0)
        acc[0] += work
        for i in range(n):
            vp = v[i] + a[i] * dt
            a_new = (_step_spring_force(i, n, x_new, l_new, side, plate, kp, kc, ks)
                     - f_new[i] - eta * vp) / mass
            v_new = v[i] + 0.5 * (a[i] + a_new) * dt
            wfric[i] += 0.5 * (f[i] + f_new[i]) * (x_new[i] - x[i])
            wdamp[i] += eta * 0.5 * (v[i] * v[i] + v_new * v_new) * dt
            x[i] = x_new[i]
            v[i] = v_new
            a[i] = a_new
            f[i] = f_new[i]
        acc[1] += 1.0
        t = t_new
        if acc[3] != 0.0:
            break
        if v_qs > 0.0 and t >= t_min and t < t1:
            quiet = True
            for i in range(n):
                if v[i] * v[i] + (a[i] / omega_qs) ** 2 >= v_qs * v_qs:
                    quiet = False
                    break
            if quiet:
                break
    if t < t1:  # an early return: every window up to date at t
        for i in range(n):
            x_new[i] = x[i]
        m = 0
        for i in range(n):
            if tu[i] < t:
                due[m] = i
                m += 1
        for k in range(m):
            i = due[k]
            _block_lazy(i, c, state, birth, off, lo, hi, xu, tu, x_new, t, f_new, k_new,
                        fscale, alpha, yc, strong, h, s_tab, ds_tab, outs, ne, nd)
            g = outs[i, 0] * fscale[i]
            a[i] += (f[i] - g) / mass
            f[i] = g
            fu[i] = g
            ku[i] = k_new[i]
            xu[i] = x[i]
            tu[i] = t
            path[i] = 0.0
            acc[2] += hi[i] - lo[i]
            if outs[i, 8] != 0.0:
                acc[3] = 1.0
    return t


@numba.njit(cache=True)
def probe_chain(c, state, birth, off, lo, hi, x, t, fscale, alpha, yc, strong, h, s_tab, ds_tab,
                outs, xu, tu, fu, ku, path, ne, nd):  # pragma: no cover - compiled
    """The multirate kernel's per-block state from the windows as they are at ``x``, ``t``:
    ``xu = x``, ``tu = t``, ``fu`` the windows' force and ``ku = dF/dx`` (nothing committed)."""
    for i in range(x.shape[0]):
        s0 = off[i]
        s1 = off[i + 1]
        advance_window(c[s0:s1], state[s0:s1], birth[s0:s1], lo[i], hi[i], x[i], x[i], t, t, 1,
                       alpha, yc, strong, h, s_tab, ds_tab, False, True, outs[i])
        xu[i] = x[i]
        tu[i] = t
        fu[i] = outs[i, 0] * fscale[i]
        ku[i] = outs[i, 1] * fscale[i]
        path[i] = 0.0
        ne[i] = outs[i, 7]
        nd[i] = 1.0


@numba.njit(cache=True)
def _probe(i, c, state, birth, off, lo, hi, x, y, t, t_new, commit, alpha, yc, strong, h,
           s_tab, ds_tab, outs):  # pragma: no cover - compiled
    """Block ``i``'s friction at ``y[i]`` and time ``t_new``, moved from ``x[i]`` at ``t``
    (:func:`.kernel.advance_window` with its stiffness ``dF/dx`` and the next spinodal ahead);
    the pairs and window are written only when ``commit``."""
    s0 = off[i]
    s1 = off[i + 1]
    lo_i, hi_i = advance_window(c[s0:s1], state[s0:s1], birth[s0:s1], lo[i], hi[i], x[i], y[i],
                                t, t_new, 1, alpha, yc, strong, h, s_tab, ds_tab, commit, True,
                                outs[i])
    if commit:
        lo[i] = lo_i
        hi[i] = hi_i


@numba.njit(cache=True)
def _spring_force(i, n, x, load, side, plate, kp, kc, ks):  # pragma: no cover - compiled
    """Force of the loading, edge and coupling springs on block ``i`` at positions ``x``."""
    s = kp * (plate - x[i])
    if i > 0:
        s += kc * (x[i - 1] - x[i])
    if i < n - 1:
        s += kc * (x[i + 1] - x[i])
    if side and i == 0:
        s += ks * (load - x[0])
    return s


QS_NEWTON_MAX: int = 30
"""Most Newton iterations of one quasi-static step before it is halved (ours)."""
QS_TOL: float = 1e-11
"""Newton's convergence: the largest correction of a block's position, ``a0`` (ours)."""


@numba.njit(cache=True, parallel=True)
def settle_chain(c, state, birth, off, lo, hi, x, v, a, f, fscale, t, t1, dt_min, nxt,
                 mass, eta, kp, kc, ks, side, plate_fixed, load0, p_times, p_pos, p_vel, p_x0,
                 alpha, yc, strong, h, s_tab, ds_tab, outs, wfric, wdamp, wqs, acc, serial
                 ):  # pragma: no cover - compiled
    """One quasi-static step of the chain from ``t`` towards ``t1`` (arrays updated in place).

    Every block is put in equilibrium at the new time without inertia (ours): ``K_p (P - y_i)
    + k_c (y_{i+1} - 2 y_i + y_{i-1}) + [i = 0] K_s (L - y_0) - F_i(y_i) - eta (y_i - x_i)/dt =
    0``, the friction ``F_i`` of each window moved from ``x_i`` at ``t`` to ``y_i`` at ``t +
    dt`` (the contacts age over the step by creep, exactly), solved by Newton's method with
    the windows' own stiffness ``dF_i/dx`` (a tridiagonal system). The step is taken only if
    no contact reaches its spinodal on the way (no block's force drops); else it is shortened,
    to just before the first spinodal ahead (``nxt``, the next spinodal of every block at its
    last committed state), down to ``dt_min``.

    Energy (ours): the work terms are the trapezoid sums of the dynamic kernel; the unbalanced
    force ``g_i = m a_i`` at both ends (nonzero at the start of the first quasi-static step,
    where the dynamics left it) does the work ``wqs`` that the step removes, with the kinetic
    energy it drops, so that ``work_load = delta(elastic + kinetic) + work_friction +
    work_damping + wqs`` holds exactly.

    Returns ``(t_reached, hit)``: ``hit = 1`` when a block reached its threshold (a spinodal
    within ``dt_min``), the state then left at ``t_reached``, where the dynamics resume; ``v``
    holds the last step's ``(y - x)/dt`` and ``a`` the unbalanced force over ``m``.
    """
    n = x.shape[0]
    y = np.empty(n)
    fy = np.empty(n)
    ky = np.empty(n)
    g = np.empty(n)
    cp = np.empty(n)
    dp = np.empty(n)
    l_old = load0 + load_position(t, p_times, p_pos, p_vel) - p_x0
    plate_old = plate_fixed if side else l_old
    dt = t1 - t
    while True:
        t_new = t1 if dt >= t1 - t else t + dt
        dt = t_new - t
        l_new = load0 + load_position(t_new, p_times, p_pos, p_vel) - p_x0
        plate = plate_fixed if side else l_new
        for i in range(n):  # the guess: the blocks keep their velocity
            y[i] = x[i] + v[i] * dt
        converged = False
        for _ in range(QS_NEWTON_MAX):
            if serial:
                for i in range(n):
                    _probe(i, c, state, birth, off, lo, hi, x, y, t, t_new, False, alpha, yc,
                           strong, h, s_tab, ds_tab, outs)
            else:
                for i in numba.prange(n):
                    _probe(i, c, state, birth, off, lo, hi, x, y, t, t_new, False, alpha, yc,
                           strong, h, s_tab, ds_tab, outs)
            for i in range(n):
                fy[i] = outs[i, 0] * fscale[i]
                ky[i] = outs[i, 1] * fscale[i]
                acc[2] += hi[i] - lo[i]
            # residual and the Jacobian -dg/dy (tridiagonal, Thomas algorithm)
            for i in range(n):
                g[i] = (_spring_force(i, n, y, l_new, side, plate, kp, kc, ks) - fy[i]
                        - eta * (y[i] - x[i]) / dt)
            worst = 0.0
            for i in range(n):
                diag = kp + ky[i] + eta / dt
                if i > 0:
                    diag += kc
                if i < n - 1:
                    diag += kc
                if side and i == 0:
                    diag += ks
                up = -kc if i < n - 1 else 0.0
                low = -kc if i > 0 else 0.0
                den = diag - (low * cp[i - 1] if i > 0 else 0.0)
                cp[i] = up / den
                dp[i] = (g[i] - (low * dp[i - 1] if i > 0 else 0.0)) / den
            for i in range(n - 1, -1, -1):
                d = dp[i] - (cp[i] * dp[i + 1] if i < n - 1 else 0.0)
                dp[i] = d
                if abs(d) > worst:
                    worst = abs(d)
            for i in range(n):
                y[i] += dp[i]
            if not worst == worst:  # NaN: a singular Jacobian
                break
            if worst < QS_TOL:
                converged = True
                break
        dead = False
        for i in range(n):
            if outs[i, 5] != 0.0:
                dead = True
        if converged and not dead:
            break
        if dt <= dt_min * (1.0 + 1e-9):  # (t + dt) - t may round dt_min up
            # the threshold: hand over to the dynamics at t, the state untouched
            for i in range(n):
                a[i] = (_spring_force(i, n, x, l_old, side, plate_old, kp, kc, ks) - f[i]
                        - eta * v[i]) / mass
            return t, 1
        # shorten to just before the first spinodal ahead (nxt is a lower bound: ageing moves
        # a spinodal forward), at least halving
        frac = 0.5
        if converged:
            for i in range(n):
                if outs[i, 5] != 0.0 and y[i] > x[i]:
                    s = 0.9 * (nxt[i] - x[i]) / (y[i] - x[i])
                    if s < frac:
                        frac = s
        if frac < 0.0:
            frac = 0.0
        dt = max(dt * frac, dt_min)
    # commit the equilibrium at t_new and book the energy
    if serial:
        for i in range(n):
            _probe(i, c, state, birth, off, lo, hi, x, y, t, t_new, True, alpha, yc, strong, h,
                   s_tab, ds_tab, outs)
    else:
        for i in numba.prange(n):
            _probe(i, c, state, birth, off, lo, hi, x, y, t, t_new, True, alpha, yc, strong, h,
                   s_tab, ds_tab, outs)
    s_old = 0.0
    s_new = 0.0
    if side:
        s_old = ks * (l_old - x[0])
        s_new = ks * (l_new - y[0])
    else:
        for i in range(n):
            s_old += kp * (l_old - x[i])
            s_new += kp * (l_new - y[i])
    acc[0] += 0.5 * (s_old + s_new) * (l_new - l_old)
    hit = 0
    for i in range(n):
        fy[i] = outs[i, 0] * fscale[i]
        nxt[i] = outs[i, 7]
        if outs[i, 5] != 0.0:  # a spinodal within the last Newton correction: dynamics now
            hit = 1
        if outs[i, 8] != 0.0:
            acc[3] = 1.0
        acc[2] += hi[i] - lo[i]
    for i in range(n):
        dx = y[i] - x[i]
        v_new = dx / dt
        cp[i] = v_new
        g_old = (_spring_force(i, n, x, l_old, side, plate_old, kp, kc, ks) - f[i]
                 - eta * v[i])
        g_new = _spring_force(i, n, y, l_new, side, plate, kp, kc, ks) - fy[i] - eta * v_new
        wfric[i] += 0.5 * (f[i] + fy[i]) * dx
        wdamp[i] += 0.5 * eta * (v[i] + v_new) * dx
        wqs[i] += 0.5 * (g_old + g_new) * dx + 0.5 * mass * (v[i] * v[i] - v_new * v_new)
        a[i] = g_new / mass
    for i in range(n):
        x[i] = y[i]
        v[i] = cp[i]
        f[i] = fy[i]
    acc[1] += 1.0
    return t_new, hit
