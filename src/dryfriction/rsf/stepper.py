"""The RODAS4 stepper of the rate-and-state driver: one source, run interpreted or compiled.

The kernels below (state laws, friction, right-hand side and Jacobian, a small LU, the stepper)
are plain Python on scalar floats and flat containers (a matrix ``m`` is ``m[i * n + j]``), so
that the same source runs in two ways:

* interpreted, on Python lists: no Numba (0.4 s to import, and SciPy's linear algebra with it,
  plus 0.3 s to load its cache), which is what a small job such as a velocity step wants -
  a few hundred steps of ~50 us;
* compiled by Numba (``numba.njit(cache=True)`` on the same code objects, built on first use by
  :func:`compiled`), on NumPy arrays: a large job (long stick-slip, a fit calling the solver
  hundreds of times).

:func:`integrate` runs interpreted within a step budget (:data:`INTERPRETED_STEPS`, shared by
the whole process) and, when it runs out, carries on from the current state with the compiled
kernels; once they are loaded, every later run uses them (the budget drops to 0). Both routes
do the same floating-point operations in the same order, so their results agree to rounding
(``tests/rsf/test_routes.py``).
Where the interpreted route raises on what the compiled one carries as ``inf``/``nan`` (Python's
``math`` raises OverflowError and ValueError), the run is redone compiled from the start.

The stepper is the L-stable, stiffly accurate 6-stage Rosenbrock method RODAS4 of order 4(3)
(Hairer & Wanner 1996, *Solving ODEs II*, §IV.7, coefficients of their code RODAS), in the
transformed form ``(I/(h gamma) - J) K_i = f(y + sum_j A_ij K_j) + sum_j (C_ij/h) K_j``,
``y_new = y + sum_j M_j K_j``, with ``K_6`` as error estimate; see :mod:`.driving` for the
equations.
"""

from __future__ import annotations

import contextlib
import math
import types
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np

from ..interrupts import deferred
from .law import STATE_LAWS, RateState

__all__ = ["COMPILED_CHUNK", "EFOLD", "INERTIAL", "INTERPRETED_STEPS", "KINEMATIC", "QUASISTATIC",
           "below", "compiled", "growth_limit", "integrate", "interpreted_steps", "param_vector",
           "rhs_at"]

# modes of the driver
KINEMATIC, QUASISTATIC, INERTIAL = 0, 1, 2

# parameter vector layout
(_A, _B, _LNDC, _INVDC, _B2, _LNDC2, _INVDC2, _MU0, _LNV0, _LAW, _NS, _REG, _K, _ETA, _M, _VL,
 _MODE, _LN2V0, _CN) = range(19)
_NP = 19
# p[_LAW]: 0 ageing, 1 slip, 2 PRZ, 3 Nagata (the order of law.STATE_LAWS)

# the stepper's state between calls (see _integrate)
_S, _T, _H, _REJ, _MID, _N, _NACC, _NREJ, _NFEV = range(9)

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
_TABLES = (_RA.ravel(), _RC.ravel(), _RM)

_ASINH_LARGE = 20.0

INTERPRETED_STEPS = 3000
"""Steps (accepted and rejected) the process runs interpreted before it loads the compiled
kernels: at ~50 us a step interpreted, about the 0.5-0.7 s Numba costs to import and load."""
_interpreted_left = INTERPRETED_STEPS

COMPILED_CHUNK = 100_000
"""Steps (accepted and rejected) of one compiled call: about 0.1 s (a compiled step costs ~1 us),
so that a Ctrl-C or SIGTERM, held back during the call, is acted on at once after it."""


def _zeros(n: int) -> Any:
    """A zeroed work vector: a list interpreted (``numpy.zeros`` in the compiled namespace)."""
    return [0.0] * n


# --------------------------------------------------------------------------- the kernels
def _state_log_rate(law: int, v: float, lnth: float, lndc: float, invdc: float):  # type: ignore[no-untyped-def]
    """``d ln theta/dt`` and its derivatives in ``ln V`` and ``ln theta`` (v = |V| >= 0); for
    Nagata's law the ageing part (its stress-rate term is added in :func:`_rhs`)."""
    if law == 0 or law == 3:  # ageing (Dieterich 1979): 1/theta - V/Dc
        e = math.exp(-lnth)
        return e - v * invdc, -v * invdc, -e
    if law == 2:  # PRZ (Perrin, Rice & Zheng 1995), theta_ss = Dc/V: (1 - (V theta/Dc)^2)/(2 theta)
        e = math.exp(-lnth)
        q = v * invdc * v * invdc * math.exp(lnth)  # (V/Dc) * (V theta/Dc)
        return 0.5 * (e - q), -q, -0.5 * (e + q)
    if v == 0.0:  # slip law (Ruina 1983) at rest: no evolution
        return 0.0, 0.0, 0.0
    w = v * invdc
    lnom = math.log(v) + lnth - lndc
    return -w * lnom, -w * (lnom + 1.0), -w


def _friction(lnv: float, lnth1: float, lnth2: float, p):  # type: ignore[no-untyped-def]
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


def _rhs(y, p, f, jac, want_jac: bool) -> None:  # type: ignore[no-untyped-def]
    """Right-hand side (and Jacobian, ``jac[i * n + j]``) of the log-variable system."""
    n = len(y)
    mode = int(p[_MODE])
    ns = int(p[_NS])
    law = int(p[_LAW])
    if want_jac:
        for i in range(n * n):
            jac[i] = 0.0
    if mode == 0:
        v = abs(p[_VL])
        g, _, dgt = _state_log_rate(law, v, y[0], p[_LNDC], p[_INVDC])
        f[0] = g
        if want_jac:
            jac[0] = dgt
        if ns == 2:
            g, _, dgt = _state_log_rate(law, v, y[1], p[_LNDC2], p[_INVDC2])
            f[1] = g
            if want_jac:
                jac[n + 1] = dgt
        return
    lnv = y[0]
    v = math.exp(lnv)
    g1, dgv1, dgt1 = _state_log_rate(law, v, y[1], p[_LNDC], p[_INVDC])
    if law == 3:  # Nagata et al. 2012: - (c/b) dtau/dt, tau the spring's stress k (x_L - x)
        cb = p[_CN] / p[_B]
        g1 -= cb * p[_K] * (p[_VL] - v)
        dgv1 += cb * p[_K] * v
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
        jac[n] = dgv1
        jac[n + 1] = dgt1
        if ns == 2:
            jac[2 * n] = dgv2
            jac[2 * n + 2] = dgt2
    if mode == 1:
        s = b * g1 + b2 * g2
        num = k * (p[_VL] - v) - c * s
        den = a * c + eta * v
        f0 = num / den
        f[0] = f0
        if want_jac:
            dn = -k * v - cp * s - c * (b * dgv1 + b2 * dgv2)
            dd = a * cp + eta * v
            jac[0] = (dn - f0 * dd) / den
            dn = -cp * (b / a) * s - c * b * dgt1
            dd = cp * b
            jac[1] = (dn - f0 * dd) / den
            if ns == 2:
                dn = -cp * (b2 / a) * s - c * b2 * dgt2
                dd = cp * b2
                jac[2] = (dn - f0 * dd) / den
        return
    # inertial
    it = ns + 1
    tau = y[it]
    mv = p[_M] * v
    f0 = (tau - mu - eta * v) / mv
    f[0] = f0
    f[it] = k * (p[_VL] - v)
    if want_jac:
        jac[0] = (-a * c - eta * v) / mv - f0
        jac[1] = -b * c / mv
        if ns == 2:
            jac[2] = -b2 * c / mv
        jac[it] = 1.0 / mv
        jac[it * n] = -k * v


def _lu(m, piv, n: int) -> bool:  # type: ignore[no-untyped-def]
    """In-place LU with partial pivoting of a small flat matrix; False if singular."""
    for j in range(n):
        best = j
        amax = abs(m[j * n + j])
        for i in range(j + 1, n):
            if abs(m[i * n + j]) > amax:
                amax = abs(m[i * n + j])
                best = i
        piv[j] = best
        if amax == 0.0 or not math.isfinite(amax):
            return False
        if best != j:
            for q in range(n):
                tmp = m[j * n + q]
                m[j * n + q] = m[best * n + q]
                m[best * n + q] = tmp
        inv = 1.0 / m[j * n + j]
        for i in range(j + 1, n):
            m[i * n + j] *= inv
            lij = m[i * n + j]
            for q in range(j + 1, n):
                m[i * n + q] -= lij * m[j * n + q]
    return True


def _lu_solve(m, piv, x, off: int, n: int) -> None:  # type: ignore[no-untyped-def]
    """Solve in place for ``x[off:off + n]`` with the factors of :func:`_lu`."""
    for j in range(n):
        pj = int(piv[j])
        if pj != j:
            tmp = x[off + j]
            x[off + j] = x[off + pj]
            x[off + pj] = tmp
    for i in range(n):
        s = x[off + i]
        for q in range(i):
            s -= m[i * n + q] * x[off + q]
        x[off + i] = s
    for i in range(n - 1, -1, -1):
        s = x[off + i]
        for q in range(i + 1, n):
            s -= m[i * n + q] * x[off + q]
        x[off + i] = s / m[i * n + i]


def _record(T, Y, F, S, n, t, y, f, s):  # type: ignore[no-untyped-def]
    """Store step ``n`` (time, state, derivative, segment), doubling the buffers when full."""
    cap = T.shape[0]
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
    for i in range(len(y)):
        Y[n, i] = y[i]
        F[n, i] = f[i]
    S[n] = s
    return T, Y, F, S


def _integrate(y, p, seg_t, seg_v, tol, w, limit, ra, rc, rm, T, Y, F, S, st):  # type: ignore[no-untyped-def]
    """RODAS4 over the segments from the state ``st`` (updated in place, as is ``y``); returns
    ``(T, Y, F, S, status)``: the step buffers (``st[_N]`` of them filled) and 0 done, 1
    step-size underflow, 2 ``limit`` steps (accepted and rejected) reached.

    ``st`` holds the segment, time, step size, whether the last step was rejected, whether
    the segment is under way, the steps recorded and the counts of accepted and rejected steps
    and right-hand-side evaluations: a run stopped at ``limit`` resumes where it stopped.

    Besides the error control, a step never spans more than ``EFOLD`` e-folding times of a
    growing mode of the Jacobian (:func:`growth_limit`; not on the
    kinematic machine, whose state laws are stable).
    """
    ny = len(y)
    nseg = len(seg_v)
    f = _zeros(ny)
    jac = _zeros(ny * ny)
    dummy = _zeros(ny * ny)
    g = _zeros(ny * ny)
    piv = _zeros(ny)
    K = _zeros(6 * ny)
    ys = _zeros(ny)
    fs = _zeros(ny)
    ynew = _zeros(ny)
    fnew = _zeros(ny)
    s = int(st[_S])
    t = st[_T]
    h = st[_H]
    rejected = st[_REJ] != 0.0
    mid = st[_MID] != 0.0
    n = int(st[_N])
    nacc = int(st[_NACC])
    nrej = int(st[_NREJ])
    nfev = int(st[_NFEV])
    limit_growth = p[_MODE] != KINEMATIC
    while s < nseg:
        p[_VL] = seg_v[s]
        tend = seg_t[s + 1]
        if mid:  # resumed within the segment: f and jac at y, as they were (not counted again)
            _rhs(y, p, f, jac, True)
        else:
            t = seg_t[s]
            _rhs(y, p, f, jac, True)
            nfev += 1
            # record the segment start
            T, Y, F, S = _record(T, Y, F, S, n, t, y, f, s)
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
                h = growth_limit(jac, h, dummy, ny)
            rejected = False
        hmin = 1e-13 * max(abs(t), abs(tend))
        while t < tend:
            if nacc + nrej >= limit:
                st[_S], st[_T], st[_H], st[_MID] = s, t, h, 1.0
                st[_REJ] = 1.0 if rejected else 0.0
                st[_N], st[_NACC], st[_NREJ], st[_NFEV] = n, nacc, nrej, nfev
                return T, Y, F, S, 2
            last = False
            if t + h >= tend or t + 1.0001 * h >= tend:
                h = tend - t
                last = True
            ok = True
            for i in range(ny * ny):
                g[i] = -jac[i]
            for i in range(ny):
                g[i * ny + i] += 1.0 / (h * _GAMMA)
            if not _lu(g, piv, ny):
                ok = False
            err = 0.0
            if ok:
                for sg in range(6):
                    if sg == 0:
                        for i in range(ny):
                            fs[i] = f[i]
                    else:
                        for i in range(ny):
                            acc = y[i]
                            for q in range(sg):
                                acc += ra[sg * 6 + q] * K[q * ny + i]
                            ys[i] = acc
                        _rhs(ys, p, fs, dummy, False)
                        nfev += 1
                    for i in range(ny):
                        acc = fs[i]
                        for q in range(sg):
                            acc += rc[sg * 6 + q] / h * K[q * ny + i]
                        K[sg * ny + i] = acc
                    _lu_solve(g, piv, K, sg * ny, ny)
                for i in range(ny):
                    acc = y[i]
                    for q in range(6):
                        acc += rm[q] * K[q * ny + i]
                    ynew[i] = acc
                    e = K[5 * ny + i] / (tol * w[i])
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
                T, Y, F, S = _record(T, Y, F, S, n, t, y, f, s)
                n += 1
                fac = 6.0 if err == 0.0 else min(6.0, max(0.2, 0.9 * err**-0.25))
                if rejected:
                    fac = min(fac, 1.0)
                h *= fac
                if limit_growth:
                    h = growth_limit(jac, h, dummy, ny)
                rejected = False
            else:
                nrej += 1
                if ok:
                    h *= max(0.2, 0.9 * err**-0.25)
                else:
                    h *= 0.25
                rejected = True
                if h < hmin:
                    st[_S], st[_T], st[_N], st[_NACC], st[_NREJ], st[_NFEV] = (
                        s, t, n, nacc, nrej, nfev)
                    return T, Y, F, S, 1
        s += 1
        mid = False
    st[_S], st[_T], st[_N], st[_NACC], st[_NREJ], st[_NFEV] = s, t, n, nacc, nrej, nfev
    return T, Y, F, S, 0


# ------------------------------------------------------------------- growth limit (issue 14)
EFOLD = 1.0
"""Most e-folding times of an unstable mode one step may span."""


def below(jac, s: float, sq, n: int) -> bool:  # type: ignore[no-untyped-def]
    """Every eigenvalue of the ``n x n`` matrix ``jac`` (flat) has real part ``< s``
    (Routh-Hurwitz, ours).

    The characteristic polynomial of ``M = jac - s I`` from the power sums ``tr M^k``
    (Newton's identities); for the 1-4 unknowns of the driver Hurwitz's conditions are
    explicit. No eigenvalue solver and no allocation (``sq`` is scratch for ``M^2``): this
    runs at every large step and must cost a few dozen flops.
    """
    p1 = 0.0
    for i in range(n):
        p1 += jac[i * n + i] - s
    for i in range(n):
        for j in range(n):
            acc = 0.0
            for q in range(n):
                acc += ((jac[i * n + q] - (s if i == q else 0.0))
                        * (jac[q * n + j] - (s if q == j else 0.0)))
            sq[i * n + j] = acc
    p2 = p3 = p4 = 0.0
    for i in range(n):
        p2 += sq[i * n + i]
        for j in range(n):
            p3 += sq[i * n + j] * (jac[j * n + i] - (s if i == j else 0.0))
            p4 += sq[i * n + j] * sq[j * n + i]
    e1 = p1
    e2 = (e1 * p1 - p2) / 2.0
    e3 = (e2 * p1 - e1 * p2 + p3) / 3.0
    e4 = (e3 * p1 - e2 * p2 + e1 * p3 - p4) / 4.0
    a1, a2, a3, a4 = -e1, e2, -e3, e4
    if n == 1:
        return a1 > 0.0
    if n == 2:
        return a1 > 0.0 and a2 > 0.0
    if n == 3:
        return a1 > 0.0 and a3 > 0.0 and a1 * a2 > a3
    return a1 > 0.0 and a3 > 0.0 and a4 > 0.0 and a1 * a2 * a3 > a3 * a3 + a1 * a1 * a4


def growth_limit(jac, h: float, sq, n: int) -> float:  # type: ignore[no-untyped-def]
    """``h`` reduced (halved) until no eigenvalue of ``jac`` (``n x n``, flat) grows by more than
    ``EFOLD`` e-foldings in one step: an L-stable method would otherwise damp an unstable
    mode it steps over (a run started beside an unstable steady state stayed there)."""
    norm = 0.0
    for i in range(n):
        row = 0.0
        for q in range(n):
            row += abs(jac[i * n + q])
        norm = max(norm, row)
    # |Re lambda| <= ||J||: steps that short need no test
    while h * norm > EFOLD and not below(jac, EFOLD / h, sq, n):
        h *= 0.5
    return h


# --------------------------------------------------------------------------- the two routes
_KERNELS = (_state_log_rate, _friction, _rhs, _lu, _lu_solve, _record, below, growth_limit,
            _integrate)


def _jit_namespace(module: types.ModuleType, funcs: tuple[Callable[..., Any], ...],
                   overrides: dict[str, Any], njit: Callable[..., Any]) -> dict[str, Any]:
    """A copy of ``module``'s globals in which ``funcs`` are Numba dispatchers of the same code
    objects (so they call each other compiled, and Numba caches them beside ``module``'s source
    under their own names), and ``overrides`` replace what only the interpreter needs."""
    ns = {**vars(module), **overrides}
    for f in funcs:
        copy = types.FunctionType(f.__code__, ns, f.__name__, f.__defaults__, f.__closure__)
        copy.__qualname__, copy.__module__, copy.__doc__ = f.__qualname__, f.__module__, f.__doc__
        ns[f.__name__] = njit(cache=True)(copy)
    return ns


_compiled: dict[str, Any] = {}

compile_hook: Callable[[], None] | None = None
"""Called just before this process first loads (or compiles) the compiled kernels: the command
line's one-line notice when their cache is missing, said only when a run does need them."""


def compiled() -> dict[str, Any]:
    """The kernels compiled by Numba (loaded from its cache, or compiled and cached on first
    use), by name: ``_integrate``, ``_rhs``, ... Imports Numba."""
    if not _compiled:
        import sys

        if compile_hook is not None:
            compile_hook()
        import numba

        ns = _jit_namespace(sys.modules[__name__], _KERNELS, {"_zeros": np.zeros}, numba.njit)
        _compiled.update({f.__name__: ns[f.__name__] for f in _KERNELS})
        global _interpreted_left
        _interpreted_left = 0  # loaded: nothing left to save by interpreting
    return _compiled


@contextlib.contextmanager
def interpreted_steps(steps: int) -> Iterator[None]:
    """Within the block the process has ``steps`` interpreted steps left (0: compiled only, as
    in the warm-up and the benchmarks), whether or not the compiled kernels are loaded; after
    it, what was left before (0 once they are loaded)."""
    global _interpreted_left
    saved = _interpreted_left
    _interpreted_left = steps
    try:
        yield
    finally:
        _interpreted_left = 0 if _compiled else saved


def _run(kernel: Callable[..., Any], y: Any, p: Any, seg_t: Any, seg_v: Any, tol: float,
         w: Any, limit: int, tables: Any, buffers: tuple[Any, ...], st: Any
         ) -> tuple[Any, ...]:
    return kernel(y, p, seg_t, seg_v, tol, w, limit, *tables, *buffers, st)


def integrate(y0: np.ndarray, p: np.ndarray, seg_t: np.ndarray, seg_v: np.ndarray, tol: float,
              w: np.ndarray, max_steps: int) -> tuple[Any, ...]:
    """RODAS4 over every segment, interpreted within the process's step budget and compiled
    beyond it. Returns ``(T, Y, F, SEG, (accepted, rejected, rhs evaluations), status, t, y)``
    with ``status`` 0 done, 1 step-size underflow, 2 more than ``max_steps`` steps."""
    global _interpreted_left
    ny = len(y0)
    cap = 256
    buffers = (np.empty(cap), np.empty((cap, ny)), np.empty((cap, ny)), np.empty(cap, np.int64))
    st = [0.0] * 9
    y: Any = [float(v) for v in y0]
    status = 2
    budget = min(_interpreted_left, max_steps)
    if budget > 0:
        try:
            *buffers, status = _run(_integrate, y, p.tolist(), seg_t.tolist(), seg_v.tolist(),
                                    tol, w.tolist(), budget, [a.tolist() for a in _TABLES],
                                    tuple(buffers), st)
        except (ArithmeticError, ValueError):  # inf/nan where the compiled kernels carry on
            st, y, status = [0.0] * 9, [float(v) for v in y0], 2
            buffers = (np.empty(cap), np.empty((cap, ny)), np.empty((cap, ny)),
                       np.empty(cap, np.int64))
        _interpreted_left = max(0, _interpreted_left - int(st[_NACC] + st[_NREJ]))
    if status == 2 and st[_NACC] + st[_NREJ] < max_steps:
        st, y, kernel, q = np.array(st), np.array(y), compiled()["_integrate"], p.copy()
        # in chunks of COMPILED_CHUNK steps, each with the signals deferred (a handler must not
        # run while Numba boxes the returned arrays, nor in llvmlite's callbacks while the first
        # call loads or compiles the kernels: dryfriction.interrupts); a chunk resumes where
        # the last stopped, so the result is the one call's, bit for bit
        while True:
            limit = int(min(max_steps, st[_NACC] + st[_NREJ] + COMPILED_CHUNK))
            with deferred():
                *buffers, status = _run(kernel, y, q, seg_t, seg_v, tol, w, limit, _TABLES,
                                        tuple(buffers), st)
            if status != 2 or limit >= max_steps:  # done, failed, or out of max_steps
                break
    n = int(st[_N])
    T, Y, F, S = buffers
    stats = (int(st[_NACC]), int(st[_NREJ]), int(st[_NFEV]))
    return T[:n], Y[:n], F[:n], S[:n], stats, status, float(st[_T]), np.asarray(y, float)


def rhs_at(y: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The right-hand side and its Jacobian (n x n) at ``y`` (interpreted; compiled where the
    interpreter raises on an overflow the compiled kernels carry as ``inf``)."""
    n = len(y)
    f, jac = [0.0] * n, [0.0] * (n * n)
    try:
        _rhs(y.tolist(), p.tolist(), f, jac, True)
    except (ArithmeticError, ValueError):
        f, jac = np.zeros(n), np.zeros(n * n)
        with deferred():  # its first call loads the kernels (dryfriction.interrupts)
            compiled()["_rhs"](np.asarray(y, float), p, f, jac, True)
    return np.asarray(f, float), np.asarray(jac, float).reshape(n, n)


def param_vector(params: RateState, stiffness: float, damping: float, mass: float,
                 mode: int, load_velocity: float = 0.0) -> np.ndarray:
    """The kernels' parameter vector (layout ``_A`` ... ``_LN2V0`` above)."""
    p = np.zeros(_NP)
    p[_A], p[_B] = params.a, params.b
    p[_LNDC], p[_INVDC] = math.log(params.dc), 1.0 / params.dc
    p[_B2] = params.b2
    if params.dc2 is not None:
        p[_LNDC2], p[_INVDC2] = math.log(params.dc2), 1.0 / params.dc2
    p[_MU0], p[_LNV0], p[_LN2V0] = params.mu0, math.log(params.v0), math.log(2.0 * params.v0)
    p[_LAW] = float(STATE_LAWS.index(params.state_law))
    p[_CN] = params.c
    p[_NS] = params.n_state
    p[_REG] = 1.0 if params.regularized else 0.0
    p[_K] = 0.0 if math.isinf(stiffness) else stiffness
    p[_ETA], p[_M], p[_MODE] = damping, mass, mode
    p[_VL] = load_velocity
    return p
