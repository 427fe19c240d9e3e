"""Drive rate-and-state friction (:class:`~dryfriction.rsf.RateState`) through a velocity program.

The slider is pulled through a spring of stiffness ``k`` (1/m, per unit normal force: the
rsfmodel convention) whose far end (the load point) follows a
:class:`~dryfriction.program.VelocityProgram` in m/s and s::

    k (x_load(t) - x) = mu(V, theta) + eta V + m dV/dt

with quasi-dynamic radiation damping ``eta`` (``eta/sigma``, s/m; Rice 1993) and the mass
per unit normal force ``m`` (s^2/m). ``k = inf`` is the infinitely stiff (kinematic) machine:
the slider moves with the load point, ``V = V_load(t)``.

Integration (ours): the unknowns are ``ln V``, ``ln theta_i`` (and, with inertia, the spring
force ``tau = k (x_load - x) + const``), so that velocities over tens of decades keep their
relative accuracy and stay positive. Quasi-statically (``m = 0``) the force balance is
differentiated in time::

    d ln V/dt = [k (V_load - V) - sum_i (dmu/dln theta_i) d ln theta_i/dt]
                / (dmu/dln V + eta V)

and the slider position is recovered exactly from the force balance. With inertia,
``d ln V/dt = (tau - mu - eta V)/(m V)`` and ``dtau/dt = k (V_load - V)``. The state laws in
log form are ``d ln theta/dt = 1/theta - V/Dc`` (ageing) and ``-(V/Dc) ln(V theta/Dc)`` (slip).

The stiff system is integrated segment by segment (the load velocity is constant within a
segment) by the L-stable, stiffly accurate 6-stage Rosenbrock method RODAS4 of order 4(3)
(Hairer & Wanner 1996, *Solving ODEs II*, §IV.7, coefficients of their code RODAS), with the
exact Jacobian and a Numba-compiled right-hand side. The local error per step is held below
``rtol`` in ``ln V`` and ``ln theta`` (a relative error in ``V`` and ``theta``) and below
``rtol * a`` in the spring force. Values between steps (``t_eval``) come from cubic Hermite
interpolation of the log variables (ours).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Mapping
from typing import Any

import numba as nb
import numpy as np
from numpy.typing import NDArray

from ..program import Segment, VelocityProgram
from ..validation import Array, check_scalar
from .growth import growth_limit, unstable_start, warn_unstable
from .law import RateState
from .resources import check_rsf_run
from .result import RSFResult, build_result, hermite
from .spring import RSFInitial, RSFOutput, SpringSlider, check_spring

__all__ = ["RSFInitial", "RSFOutput", "RSFResult", "SolverError", "SpringSlider", "simulate_rsf",
           "linear_stability"]


# modes of the driver
_KINEMATIC, _QUASISTATIC, _INERTIAL = 0, 1, 2

# parameter vector layout for the compiled code
(_A, _B, _LNDC, _INVDC, _B2, _LNDC2, _INVDC2, _MU0, _LNV0, _LAW, _NS, _REG, _K, _ETA, _M, _VL,
 _MODE, _LN2V0) = range(18)
_NP = 18

# RODAS4 (Hairer & Wanner 1996, §IV.7; code RODAS), in the transformed form
# (I/(h gamma) - J) K_i = f(y + sum_j A_ij K_j) + sum_j (C_ij/h) K_j,
# y_new = y + sum_j M_j K_j, error estimate K_6 (stiffly accurate).
_GAMMA = 0.25
_RA = np.zeros((6, 6))
_RC = np.zeros((6, 6))
_RA[1, 0] = 1.544
_RA[2, 0], _RA[2, 1] = 0.9466785280815826, 0.2557011698983284
_RA[3, 0], _RA[3, 1], _RA[3, 2] = 3.314825187068521, 2.896124015972201, 0.9986419139977817
_RA[4, :4] = [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895]
_RA[5, :4] = _RA[4, :4]
_RA[5, 4] = 1.0
_RC[1, 0] = -5.6688
_RC[2, 0], _RC[2, 1] = -2.430093356833875, -0.2063599157091915
_RC[3, :3] = [-0.1073529058151375, -9.594562251023355, -20.47028614809616]
_RC[4, :4] = [7.496443313967647, -10.24680431464352, -33.99990352819905, 11.7089089320616]
_RC[5, :5] = [8.083246795921522, -7.981132988064893, -31.52159432874371, 16.31930543123136,
              -6.058818238834054]
_RM = np.array([*_RA[4, :4], 1.0, 1.0])

_ASINH_LARGE = 20.0


class SolverError(RuntimeError):
    """The integration could not be carried to the end (the message says why).

    Attributes
    ----------
    t : float
        Time (s) reached.
    v : float
        Slip velocity (m/s) there (``nan`` for the kinematic machine).
    """

    def __init__(self, message: str, t: float = math.nan, v: float = math.nan) -> None:
        super().__init__(message)
        self.t = t
        self.v = v


# --------------------------------------------------------------------------- compiled core
@nb.njit(cache=True)
def _state_log_rate(law: int, v: float, lnth: float, lndc: float, invdc: float):
    """``d ln theta/dt`` and its derivatives in ``ln V`` and ``ln theta`` (v = |V| >= 0)."""
    if law == 0:  # ageing (Dieterich 1979): 1/theta - V/Dc
        e = math.exp(-lnth)
        return e - v * invdc, -v * invdc, -e
    if v == 0.0:  # slip law (Ruina 1983) at rest: no evolution
        return 0.0, 0.0, 0.0
    w = v * invdc
    lnom = math.log(v) + lnth - lndc
    return -w * lnom, -w * (lnom + 1.0), -w


@nb.njit(cache=True)
def _friction(lnv: float, lnth1: float, lnth2: float, p):
    """Friction, ``c = (dmu/dlnV)/a`` and ``dc/dln z`` (regularised: ``c = tanh asinh z``)."""
    psi = p[_MU0] + p[_B] * (p[_LNV0] + lnth1 - p[_LNDC])
    if p[_NS] == 2.0:
        psi += p[_B2] * (p[_LNV0] + lnth2 - p[_LNDC2])
    a = p[_A]
    if p[_REG] == 0.0:
        return psi + a * (lnv - p[_LNV0]), 1.0, 0.0
    lnz = lnv - p[_LN2V0] + psi / a
    if lnz > _ASINH_LARGE:
        mu = a * (lnz + math.log(2.0) + 0.25 * math.exp(-2.0 * lnz))
    else:
        mu = a * math.asinh(math.exp(lnz))
    if lnz < -_ASINH_LARGE:
        z = math.exp(lnz)
        c = z / math.sqrt(1.0 + z * z)
        cp = c / (1.0 + z * z)
    else:
        e = math.exp(-2.0 * lnz)
        c = 1.0 / math.sqrt(1.0 + e)
        cp = c * e / (1.0 + e)
    return mu, c, cp


@nb.njit(cache=True)
def _rhs(y, p, f, jac, want_jac: bool) -> None:
    """Right-hand side (and Jacobian) of the log-variable system; see the module docstring."""
    mode = int(p[_MODE])
    ns = int(p[_NS])
    law = int(p[_LAW])
    if want_jac:
        jac[:, :] = 0.0
    if mode == 0:
        v = abs(p[_VL])
        g, _, dgt = _state_log_rate(law, v, y[0], p[_LNDC], p[_INVDC])
        f[0] = g
        if want_jac:
            jac[0, 0] = dgt
        if ns == 2:
            g, _, dgt = _state_log_rate(law, v, y[1], p[_LNDC2], p[_INVDC2])
            f[1] = g
            if want_jac:
                jac[1, 1] = dgt
        return
    lnv = y[0]
    v = math.exp(lnv)
    g1, dgv1, dgt1 = _state_log_rate(law, v, y[1], p[_LNDC], p[_INVDC])
    f[1] = g1
    lnth2 = 0.0
    g2, dgv2, dgt2 = 0.0, 0.0, 0.0
    if ns == 2:
        lnth2 = y[2]
        g2, dgv2, dgt2 = _state_log_rate(law, v, lnth2, p[_LNDC2], p[_INVDC2])
        f[2] = g2
    a, b, b2, k, eta = p[_A], p[_B], p[_B2], p[_K], p[_ETA]
    mu, c, cp = _friction(lnv, y[1], lnth2, p)
    if want_jac:
        jac[1, 0] = dgv1
        jac[1, 1] = dgt1
        if ns == 2:
            jac[2, 0] = dgv2
            jac[2, 2] = dgt2
    if mode == 1:
        s = b * g1 + b2 * g2
        num = k * (p[_VL] - v) - c * s
        den = a * c + eta * v
        f0 = num / den
        f[0] = f0
        if want_jac:
            dn = -k * v - cp * s - c * (b * dgv1 + b2 * dgv2)
            dd = a * cp + eta * v
            jac[0, 0] = (dn - f0 * dd) / den
            dn = -cp * (b / a) * s - c * b * dgt1
            dd = cp * b
            jac[0, 1] = (dn - f0 * dd) / den
            if ns == 2:
                dn = -cp * (b2 / a) * s - c * b2 * dgt2
                dd = cp * b2
                jac[0, 2] = (dn - f0 * dd) / den
        return
    # inertial
    it = ns + 1
    tau = y[it]
    mv = p[_M] * v
    f0 = (tau - mu - eta * v) / mv
    f[0] = f0
    f[it] = k * (p[_VL] - v)
    if want_jac:
        jac[0, 0] = (-a * c - eta * v) / mv - f0
        jac[0, 1] = -b * c / mv
        if ns == 2:
            jac[0, 2] = -b2 * c / mv
        jac[0, it] = 1.0 / mv
        jac[it, 0] = -k * v


@nb.njit(cache=True)
def _lu(m, piv) -> bool:
    """In-place LU with partial pivoting of a small matrix; False if singular."""
    n = m.shape[0]
    for j in range(n):
        best = j
        amax = abs(m[j, j])
        for i in range(j + 1, n):
            if abs(m[i, j]) > amax:
                amax = abs(m[i, j])
                best = i
        piv[j] = best
        if amax == 0.0 or not math.isfinite(amax):
            return False
        if best != j:
            for q in range(n):
                tmp = m[j, q]
                m[j, q] = m[best, q]
                m[best, q] = tmp
        inv = 1.0 / m[j, j]
        for i in range(j + 1, n):
            m[i, j] *= inv
            lij = m[i, j]
            for q in range(j + 1, n):
                m[i, q] -= lij * m[j, q]
    return True


@nb.njit(cache=True)
def _lu_solve(m, piv, x) -> None:
    n = m.shape[0]
    for j in range(n):
        pj = piv[j]
        if pj != j:
            tmp = x[j]
            x[j] = x[pj]
            x[pj] = tmp
    for i in range(n):
        s = x[i]
        for q in range(i):
            s -= m[i, q] * x[q]
        x[i] = s
    for i in range(n - 1, -1, -1):
        s = x[i]
        for q in range(i + 1, n):
            s -= m[i, q] * x[q]
        x[i] = s / m[i, i]


@nb.njit(cache=True)
def _record(T, Y, F, S, n, cap, t, y, f, s):  # type: ignore[no-untyped-def]
    """Store step ``n`` (time, state, derivative, segment), doubling the buffers when full."""
    if n == cap:
        cap *= 2
        T2 = np.empty(cap)
        Y2 = np.empty((cap, Y.shape[1]))
        F2 = np.empty((cap, F.shape[1]))
        S2 = np.empty(cap, np.int64)
        T2[:n] = T[:n]
        Y2[:n] = Y[:n]
        F2[:n] = F[:n]
        S2[:n] = S[:n]
        T, Y, F, S = T2, Y2, F2, S2
    T[n] = t
    Y[n] = y
    F[n] = f
    S[n] = s
    return T, Y, F, S, cap


@nb.njit(cache=True)
def _integrate(y0, p, seg_t, seg_v, tol, w, max_steps, ra, rc, rm):
    """RODAS4 over every segment. Returns (T, Y, F, SEG, stats, status, t_fail, y_fail).

    Besides the error control, a step never spans more than ``EFOLD`` e-folding times of a
    growing mode of the Jacobian (:func:`dryfriction.rsf.growth.growth_limit`; not on the
    kinematic machine, whose state laws are stable).

    ``status``: 0 done, 1 step-size underflow, 2 too many steps.
    """
    ny = y0.shape[0]
    nseg = seg_v.shape[0]
    cap = 256
    T = np.empty(cap)
    Y = np.empty((cap, ny))
    F = np.empty((cap, ny))
    S = np.empty(cap, np.int64)
    n = 0
    y = y0.copy()
    f = np.empty(ny)
    jac = np.empty((ny, ny))
    dummy = np.empty((ny, ny))
    g = np.empty((ny, ny))
    piv = np.empty(ny, np.int64)
    K = np.empty((6, ny))
    ys = np.empty(ny)
    fs = np.empty(ny)
    ynew = np.empty(ny)
    fnew = np.empty(ny)
    nacc = 0
    nrej = 0
    nfev = 0
    status = 0
    t = seg_t[0]
    h = 0.0
    limit_growth = p[_MODE] != _KINEMATIC
    for s in range(nseg):
        p[_VL] = seg_v[s]
        t = seg_t[s]
        tend = seg_t[s + 1]
        _rhs(y, p, f, jac, True)
        nfev += 1
        # record the segment start
        T, Y, F, S, cap = _record(T, Y, F, S, n, cap, t, y, f, s)
        n += 1
        # initial step: change of the log variables ~ 0.01 tol^(1/4)
        fmax = 0.0
        for i in range(ny):
            fmax = max(fmax, abs(f[i]) / w[i])
        span = tend - t
        h = span
        if fmax > 0.0:
            h = min(span, 0.01 * tol**0.25 / fmax)
        if limit_growth:
            h = growth_limit(jac, h, dummy)
        hmin = 1e-13 * max(abs(t), abs(tend))
        rejected = False
        while t < tend:
            if nacc + nrej >= max_steps:
                return T[:n], Y[:n], F[:n], S[:n], (nacc, nrej, nfev), 2, t, y
            last = False
            if t + h >= tend or t + 1.0001 * h >= tend:
                h = tend - t
                last = True
            ok = True
            for i in range(ny):
                for q in range(ny):
                    g[i, q] = -jac[i, q]
                g[i, i] += 1.0 / (h * _GAMMA)
            if not _lu(g, piv):
                ok = False
            if ok:
                for st in range(6):
                    if st == 0:
                        for i in range(ny):
                            fs[i] = f[i]
                    else:
                        for i in range(ny):
                            acc = y[i]
                            for q in range(st):
                                acc += ra[st, q] * K[q, i]
                            ys[i] = acc
                        _rhs(ys, p, fs, dummy, False)
                        nfev += 1
                    for i in range(ny):
                        acc = fs[i]
                        for q in range(st):
                            acc += rc[st, q] / h * K[q, i]
                        K[st, i] = acc
                    _lu_solve(g, piv, K[st])
                err = 0.0
                for i in range(ny):
                    acc = y[i]
                    for q in range(6):
                        acc += rm[q] * K[q, i]
                    ynew[i] = acc
                    e = K[5, i] / (tol * w[i])
                    err += e * e
                err = math.sqrt(err / ny)
                if not math.isfinite(err):
                    ok = False
            if ok and err <= 1.0:
                _rhs(ynew, p, fnew, jac, True)
                nfev += 1
                for i in range(ny):
                    if not math.isfinite(fnew[i]):
                        ok = False
                if not ok:  # restore the Jacobian at the current point
                    _rhs(y, p, f, jac, True)
                    nfev += 1
            if ok and err <= 1.0:
                nacc += 1
                t = tend if last else t + h
                for i in range(ny):
                    y[i] = ynew[i]
                    f[i] = fnew[i]
                T, Y, F, S, cap = _record(T, Y, F, S, n, cap, t, y, f, s)
                n += 1
                fac = 6.0 if err == 0.0 else min(6.0, max(0.2, 0.9 * err**-0.25))
                if rejected:
                    fac = min(fac, 1.0)
                h *= fac
                if limit_growth:
                    h = growth_limit(jac, h, dummy)
                rejected = False
            else:
                nrej += 1
                if ok:
                    h *= max(0.2, 0.9 * err**-0.25)
                else:
                    h *= 0.25
                rejected = True
                if h < hmin:
                    return T[:n], Y[:n], F[:n], S[:n], (nacc, nrej, nfev), 1, t, y
    return T[:n], Y[:n], F[:n], S[:n], (nacc, nrej, nfev), status, t, y


# --------------------------------------------------------------------------- Python side
def _param_vector(params: RateState, stiffness: float, damping: float, mass: float,
                  mode: int) -> Array:
    p = np.zeros(_NP)
    p[_A], p[_B] = params.a, params.b
    p[_LNDC], p[_INVDC] = math.log(params.dc), 1.0 / params.dc
    p[_B2] = params.b2
    if params.dc2 is not None:
        p[_LNDC2], p[_INVDC2] = math.log(params.dc2), 1.0 / params.dc2
    p[_MU0], p[_LNV0], p[_LN2V0] = params.mu0, math.log(params.v0), math.log(2.0 * params.v0)
    p[_LAW] = 0.0 if params.state_law == "ageing" else 1.0
    p[_NS] = params.n_state
    p[_REG] = 1.0 if params.regularized else 0.0
    p[_K] = 0.0 if math.isinf(stiffness) else stiffness
    p[_ETA], p[_M], p[_MODE] = damping, mass, mode
    return p


_LEGACY = ("stiffness", "damping", "mass", "v_init", "theta_init", "theta2_init", "rtol", "t_eval",
           "max_steps")


def simulate_rsf(
    model: RateState,
    drive: SpringSlider | VelocityProgram | Iterable[Segment | Mapping[str, float]],
    initial: RSFInitial | None = None,
    output: RSFOutput | None = None,
    **legacy: Any,
) -> RSFResult:
    """Run rate-and-state friction on a spring slider through a load-point velocity program.

    Parameters
    ----------
    model : RateState
        Friction law and parameters.
    drive : SpringSlider
        Load-point program, stiffness (``inf``: kinematic machine), damping and mass.
    initial : RSFInitial, optional
        Initial slip velocity and state; default steady sliding at the first load velocity.
    output : RSFOutput, optional
        Output times, tolerance and step budget; default every accepted step, ``rtol = 1e-7``.
    **legacy
        Deprecated: the old form ``simulate_rsf(params, program, stiffness=..., damping=...,
        mass=..., v_init=..., theta_init=..., theta2_init=..., rtol=..., t_eval=...,
        max_steps=...)`` still works for one release and warns (``DeprecationWarning``).

    Returns
    -------
    RSFResult

    Raises
    ------
    ValueError
        Bad input (named parameter, value and allowed range), before any work.
    SolverError
        The integration failed (step-size underflow: e.g. an unbounded slip velocity below
        the critical stiffness without damping; or the step budget ran out).
    """
    if not isinstance(drive, SpringSlider) or legacy:
        drive, initial, output = _from_legacy(drive, initial, output, legacy)
    if not isinstance(model, RateState):
        raise ValueError(f"model = {model!r} is not a RateState")
    initial = RSFInitial() if initial is None else initial
    output = RSFOutput() if output is None else output
    if not isinstance(initial, RSFInitial):
        raise ValueError(f"initial = {initial!r} is not an RSFInitial")
    if not isinstance(output, RSFOutput):
        raise ValueError(f"output = {output!r} is not an RSFOutput")
    drive.check_model(model)
    v_init, theta_init, theta2_init = initial.resolve(model, drive)
    check_rsf_run(model, drive, output)
    prog = drive.program
    te = output.times(prog)
    stiffness, damping, mass = drive.stiffness, drive.damping, drive.mass

    mode = _KINEMATIC if drive.kinematic else (_INERTIAL if mass > 0.0 else _QUASISTATIC)
    ns = model.n_state
    lnth = [math.log(theta_init)] + ([math.log(theta2_init)] if theta2_init is not None else [])
    stress0 = float(model.friction(v_init, theta_init, theta2_init)) + damping * v_init
    if mode == _KINEMATIC:
        y0 = np.array(lnth)
        w = np.ones(ns)
    elif mode == _QUASISTATIC:
        y0 = np.array([math.log(v_init), *lnth])
        w = np.ones(ns + 1)
    else:
        y0 = np.array([math.log(v_init), *lnth, stress0])
        w = np.array([1.0] * (ns + 1) + [model.a])
    p = _param_vector(model, stiffness, damping, mass, mode)
    unstable = unstable_start(model, drive, v_init, theta_init, theta2_init)
    if unstable is not None:
        warn_unstable(unstable)

    try:
        T, Y, F, SEG, stats, status, t_fail, y_fail = _integrate(
            y0, p, prog.times, prog.velocities, output.rtol, w, output.max_steps, _RA, _RC, _RM
        )
    except ZeroDivisionError:  # a rate overflowed, so the step size became 0 (a, dc ~ 1e-308)
        v_top = float(np.max(np.abs(prog.velocities)))
        raise SolverError(f"the integration failed: the step size fell to zero, the rates "
                          f"overflow floating point (a = {model.a:g}, dc = {model.dc:g}, load "
                          f"velocity up to {v_top:g} m/s)") from None
    if status != 0:
        v_fail = math.nan if mode == _KINEMATIC else math.exp(min(float(y_fail[0]), 709.0))
        raise SolverError(_failure_message(status, mode, t_fail, y_fail, model, stiffness,
                                           damping, output.max_steps), float(t_fail), v_fail)
    if te is not None:
        Y, SEG = hermite(T, Y, F, te), np.asarray(prog.segment_index(te))
        T = te.copy()
    res = build_result(T, Y, SEG, prog, model, kinematic=mode == _KINEMATIC,
                       inertial=mode == _INERTIAL, stiffness=stiffness, damping=damping,
                       mass=mass, rtol=output.rtol, stress0=stress0, stats=stats)
    if unstable is not None:
        res.meta["unstable_start"] = unstable
    return res


def _from_legacy(program: Any, initial: Any, output: Any, legacy: dict[str, Any]
                 ) -> tuple[SpringSlider, RSFInitial, RSFOutput]:
    """The old keyword form of :func:`simulate_rsf` as the frozen objects (with a warning)."""
    unknown = sorted(set(legacy) - set(_LEGACY))
    if unknown:
        raise TypeError(f"simulate_rsf() got unexpected keyword argument(s) {', '.join(unknown)}")
    if isinstance(program, SpringSlider) or initial is not None or output is not None:
        raise ValueError(
            "simulate_rsf(model, drive, initial, output) takes SpringSlider, RSFInitial and "
            f"RSFOutput: give {', '.join(sorted(legacy))} through them, not as keywords"
        )
    warnings.warn(
        "simulate_rsf(params, program, stiffness=..., ...) is deprecated and will be removed "
        "in the next release: use simulate_rsf(model, SpringSlider(program, stiffness, "
        "damping, mass), RSFInitial(v, theta, theta2), RSFOutput(every|t_eval, rtol, "
        "max_steps))", DeprecationWarning, stacklevel=3)
    g = legacy.get
    te = g("t_eval")
    return (
        SpringSlider(program, g("stiffness", math.inf), g("damping", 0.0), g("mass", 0.0)),
        RSFInitial(g("v_init"), g("theta_init"), g("theta2_init")),
        RSFOutput(t_eval=None if te is None else np.asarray(te, float), rtol=g("rtol", 1e-7),
                  max_steps=g("max_steps", 1_000_000)),
    )


def _failure_message(status: int, mode: int, t: float, y: Array, params: RateState,
                     stiffness: float, damping: float, max_steps: int) -> str:
    where = f"at t = {t:.6g} s"
    if mode != _KINEMATIC:
        where += f" (slip velocity V = {math.exp(min(y[0], 709.0)):.3g} m/s)"
    if status == 2:
        return f"the integration needed more than max_steps = {max_steps} steps {where}"
    msg = f"the integration failed {where}: the step size fell below the rounding limit"
    if mode == _QUASISTATIC and damping == 0.0:
        msg += (
            f"; the slip velocity runs away: without radiation damping the quasi-static slider "
            f"(k = {stiffness:.4g} 1/m) reaches unbounded velocity in finite time, below the "
            "critical stiffness or, with the slip law, after a large enough velocity jump even "
            "above it (Gu, Rice, Ruina & Tse 1984) - add damping (eta/sigma, s/m) or mass"
        )
    return msg


def linear_stability(params: RateState, v: float, stiffness: float, damping: float = 0.0,
                     mass: float = 0.0) -> NDArray[np.complex128]:
    """Eigenvalues (1/s) of the spring slider linearised about steady sliding at ``v``.

    Computed from the exact Jacobian of the log-variable system above at steady state (the
    method of Rice & Ruina 1983; any number of state variables, either law, standard or
    regularised friction). Steady sliding is linearly stable iff every real part is < 0.
    With inertia the eigenvalues of ``(ln V, ln theta_i, tau)`` are returned.

    Parameters
    ----------
    params : RateState
    v : float
        Steady sliding (= load) velocity, m/s, ``> 0``.
    stiffness : float
        Spring stiffness per unit normal force, 1/m, ``> 0`` (finite).
    damping : float
        Radiation damping ``eta/sigma``, s/m, ``>= 0``.
    mass : float
        Mass per unit normal force, s^2/m, ``>= 0``.
    """
    v = check_scalar("v", v, 0.0, lo_open=True)
    stiffness, damping, mass = check_spring(stiffness, damping, mass)
    if math.isinf(stiffness):
        raise ValueError("stiffness = inf is out of range: the linearisation needs a finite "
                         "spring, allowed > 0 (1/m)")
    mode = _INERTIAL if mass > 0.0 else _QUASISTATIC
    p = _param_vector(params, stiffness, damping, mass, mode)
    p[_VL] = v
    ns = params.n_state
    lnth = [math.log(params.dc / v)] + ([math.log(params.dc2 / v)] if ns == 2 else [])
    y = [math.log(v), *lnth]
    if mode == _INERTIAL:
        th2 = None if ns == 1 else params.dc2 / v
        y.append(float(params.friction(v, params.dc / v, th2)) + damping * v)
    y_arr = np.array(y)
    f = np.empty(len(y_arr))
    jac = np.empty((len(y_arr), len(y_arr)))
    _rhs(y_arr, p, f, jac, True)
    return np.linalg.eigvals(jac).astype(np.complex128)
