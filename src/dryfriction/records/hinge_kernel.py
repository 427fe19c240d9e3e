"""The detector's compiled kernels (Numba): the best hinge of a stretch in one pass (the kernel
of :func:`.segmentation.best_hinge`, which documents the model), and the slopes of adjacent
windows of one duration, the loop over the durations that takes their medians, and the
residuals about each stretch's line (the kernels of :func:`.detection.measure_fluctuations`),
the increments' tests of
:func:`.artifacts.find_resets`, and the medians of short blocks (:func:`row_medians`).

The candidate search calls the best hinge of a stretch thousands of times per record, each on
tens to thousands of samples: vectorised NumPy spends its time in the calls' overhead there,
one compiled pass does not. Same sums, same formulas (the normal equations of
``x = c + v1 min(t - tk, 0) + v2 max(t - tk, 0)``), accumulated sample by sample. The window
slopes are taken at some 20 durations and offsets per fluctuation measurement, several
measurements per record: one pass over the samples each, not a dozen NumPy calls.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["fluctuation_scales", "hinge_scan", "pairwise_sum", "reset_increments", "reset_jumps",
           "row_medians", "stretch_residuals", "window_pairs"]


@numba.njit(cache=True)
def hinge_scan(t: np.ndarray, x: np.ndarray, m: int, min_dur: float) -> tuple[int, float]:
    """Best hinge sample ``k`` (``m <= k <= n - m``, ``min_dur`` from both ends) of ``x(t)``
    and the residual sum of squares it saves over one line; ``(-1, 0.0)`` where none."""
    n = t.size
    if n < 2 * m + 1:
        return -1, 0.0
    half = 0.5 * (t[n - 1] - t[0])
    mid = 0.5 * (t[n - 1] + t[0])
    tt = np.empty(n)
    st_all = 0.0
    sx_all = 0.0
    for i in range(n):
        tt[i] = (t[i] - mid) / half  # in [-1, 1]: the sums stay well conditioned
        st_all += tt[i]
        sx_all += x[i]
    tm = st_all / n
    xm = sx_all / n
    sxx = 0.0
    sxy = 0.0
    for i in range(n):
        sxx += (tt[i] - tm) ** 2
        sxy += (tt[i] - tm) * (x[i] - xm)
    slope = sxy / sxx if sxx > 0 else 0.0
    # residuals about the line: the hinge's space holds every line, so the RSS saved is the same
    r = np.empty(n)
    T1 = 0.0
    R1 = 0.0
    T2 = 0.0
    TR = 0.0
    for i in range(n):
        r[i] = x[i] - xm - slope * (tt[i] - tm)
        T1 += tt[i]
        R1 += r[i]
        T2 += tt[i] * tt[i]
        TR += tt[i] * r[i]
    best_k = -1
    best_g = -np.inf
    st = 0.0
    sr = 0.0
    stt = 0.0
    s_tr = 0.0
    for k in range(n - m + 1):
        if k >= m and (t[k] - t[0]) >= min_dur and (t[n - 1] - t[k]) >= min_dur:
            tk = tt[k]
            n_l = float(k)
            n_r = float(n - k)
            su_l = st - n_l * tk
            su_r = (T1 - st) - n_r * tk
            suu_l = stt - 2.0 * tk * st + n_l * tk * tk
            suu_r = (T2 - stt) - 2.0 * tk * (T1 - st) + n_r * tk * tk
            sux_l = s_tr - tk * sr
            sux_r = (TR - s_tr) - tk * (R1 - sr)
            if suu_l > 0.0 and suu_r > 0.0:
                den = n - su_l * su_l / suu_l - su_r * su_r / suu_r
                if den > 0.0:
                    c = (R1 - su_l * sux_l / suu_l - su_r * sux_r / suu_r) / den
                    v1 = (sux_l - su_l * c) / suu_l
                    v2 = (sux_r - su_r * c) / suu_r
                    g = c * R1 + v1 * sux_l + v2 * sux_r  # RSS(line) - RSS(hinge)
                    if np.isfinite(g) and g > best_g:
                        best_g = g
                        best_k = k
        st += tt[k]
        sr += r[k]
        stt += tt[k] * tt[k]
        s_tr += tt[k] * r[k]
    if best_k < 0:
        return -1, 0.0
    return best_k, best_g


@numba.njit(cache=True, error_model="numpy")
def window_pairs(t: np.ndarray, x: np.ndarray, speed: np.ndarray, width: float, offset: float,
                 half_s2: float, min_var: float) -> tuple[np.ndarray, np.ndarray]:
    """For each pair of adjacent usable windows ``[offset + m width, offset + (m+1) width)``
    of ``x(t)``: ``(s2 - s1)**2 / 2 - half_s2 (1/Sxx1 + 1/Sxx2)`` (``s`` the windows' OLS
    slopes) and the mean of the two windows' mean ``speed``; a window is usable with >= 3
    samples, a time variance of at least ``min_var`` and a finite slope.

    The sums and formulas of :func:`.detection.measure_fluctuations` (which documents them:
    its ``_window_slopes``, ``np.bincount`` per window, with times taken from each window's
    start), in the same order: the same numbers to the last bit, in one pass."""
    n = t.size
    w0 = np.int64(np.floor((t[0] - offset) / width))
    nw = np.int64(np.floor((t[n - 1] - offset) / width)) - w0 + 1
    cnt = np.zeros(nw)
    st = np.zeros(nw)
    sx = np.zeros(nw)
    stt = np.zeros(nw)
    stx = np.zeros(nw)
    su = np.zeros(nw)
    for i in range(n):
        wi = np.int64(np.floor((t[i] - offset) / width))
        k = wi - w0
        tt = t[i] - (offset + wi * width)  # in [0, width): well-conditioned sums
        cnt[k] += 1.0
        st[k] += tt
        sx[k] += x[i]
        stt[k] += tt * tt
        stx[k] += tt * x[i]
        su[k] += speed[i]
    slope = np.empty(nw)
    sxx = np.empty(nw)
    u = np.empty(nw)
    ok = np.zeros(nw, np.bool_)
    for k in range(nw):
        c = cnt[k]
        mt = st[k] / c
        var_t = stt[k] / c - mt * mt
        slope[k] = (stx[k] / c - st[k] * sx[k] / (c * c)) / var_t
        sxx[k] = c * var_t
        u[k] = su[k] / max(c, 1.0)
        ok[k] = c >= 3.0 and var_t >= min_var and np.isfinite(slope[k])
    m = 0
    for k in range(nw - 1):
        if ok[k] and ok[k + 1]:
            m += 1
    y = np.empty(m)
    up = np.empty(m)
    j = 0
    for k in range(nw - 1):
        if ok[k] and ok[k + 1]:
            d = slope[k + 1] - slope[k]
            y[j] = 0.5 * (d * d) - half_s2 * (1.0 / sxx[k + 1] + 1.0 / sxx[k])
            up[j] = 0.5 * (u[k + 1] + u[k])
            j += 1
    return y, up


@numba.njit(cache=True)
def pairwise_sum(a: np.ndarray, lo: int, n: int) -> float:
    """``a[lo:lo + n].sum()`` as NumPy sums a contiguous float64 array (its pairwise summation:
    blocks of at most 128 summed in eight interleaved partial sums, longer runs halved at a
    multiple of 8), so that the same numbers give the same sum to the last bit."""
    if n < 8:
        res = 0.0
        for i in range(n):
            res += a[lo + i]
        return res
    if n <= 128:
        r0 = a[lo]
        r1 = a[lo + 1]
        r2 = a[lo + 2]
        r3 = a[lo + 3]
        r4 = a[lo + 4]
        r5 = a[lo + 5]
        r6 = a[lo + 6]
        r7 = a[lo + 7]
        i = 8
        while i < n - n % 8:
            r0 += a[lo + i]
            r1 += a[lo + i + 1]
            r2 += a[lo + i + 2]
            r3 += a[lo + i + 3]
            r4 += a[lo + i + 4]
            r5 += a[lo + i + 5]
            r6 += a[lo + i + 6]
            r7 += a[lo + i + 7]
            i += 8
        res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
        while i < n:
            res += a[lo + i]
            i += 1
        return res
    n2 = n // 2
    n2 -= n2 % 8
    return pairwise_sum(a, lo, n2) + pairwise_sum(a, lo + n2, n - n2)


@numba.njit(cache=True, error_model="numpy")
def stretch_residuals(t: np.ndarray, x: np.ndarray, bounds: np.ndarray, velocity: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray]:
    """The residuals of ``x(t)`` about the least-squares line of each stretch between
    ``bounds`` and each sample's stretch speed ``|velocity|``: per stretch, as
    :func:`.segmentation.line_fit` and :func:`.detection.measure_fluctuations` compute them
    with NumPy (means and sums by :func:`pairwise_sum`, the same operations in the same
    order), the same numbers to the last bit, without a dozen NumPy calls per stretch."""
    n = t.size
    res = np.empty(n)
    speed = np.empty(n)
    tc = np.empty(n)
    prod = np.empty(n)
    for j in range(bounds.size - 1):
        a = bounds[j]
        b = bounds[j + 1]
        m = b - a
        if m <= 0:
            continue
        tm = pairwise_sum(t, a, m) / m
        xm = pairwise_sum(x, a, m) / m
        for i in range(a, b):
            tc[i] = t[i] - tm
            prod[i] = tc[i] * tc[i]
        sxx = pairwise_sum(prod, a, m)
        for i in range(a, b):
            prod[i] = tc[i] * (x[i] - xm)
        slope = pairwise_sum(prod, a, m) / sxx if sxx > 0 else 0.0
        u = abs(velocity[j])
        for i in range(a, b):
            res[i] = (x[i] - xm) - slope * tc[i]
            speed[i] = u
    return res, speed


@numba.njit(cache=True)
def _nmin(a: float, b: float) -> float:
    """``np.minimum`` of two floats (a NaN propagates)."""
    if a != a:
        return a
    if b != b:
        return b
    return a if a <= b else b


@numba.njit(cache=True)
def _nmax(a: float, b: float) -> float:
    """``np.maximum`` of two floats (a NaN propagates)."""
    if a != a:
        return a
    if b != b:
        return b
    return a if a >= b else b


@numba.njit(cache=True)
def _median5(a: float, b: float, c: float, d: float, e: float) -> float:
    """The selection network of :func:`.artifacts.find_resets`' local rates, on five floats."""
    f = _nmax(_nmin(a, b), _nmin(c, d))
    g = _nmin(_nmax(a, b), _nmax(c, d))
    return _nmax(_nmin(f, g), _nmin(_nmax(f, g), e))


@numba.njit(cache=True, error_model="numpy")
def reset_increments(t: np.ndarray, x: np.ndarray):  # type: ignore[no-untyped-def]
    """The increments of :func:`.artifacts.find_resets` (which documents them) in one pass:
    ``d``, ``dt``, the range ``lo``, ``hi`` the local rates before and after each increment
    explain (the median of 5 rates each side, the record's first or last rate beyond its
    ends), the finite ``d - vb dt`` and ``rate - vb``, and the smallest nonzero ``|d|`` (0:
    none). The same operations as the NumPy form, element by element: the same numbers."""
    n = x.size - 1
    d = np.empty(n)
    dt = np.empty(n)
    # pad[j] = rate[0] (j < 5), rate[j - 5], rate[n - 1] (j >= n + 5): before increment i the
    # window pad[i:i + 5], after it pad[i + 6:i + 11], the median of window j med[j]
    pad = np.empty(n + 10)
    for i in range(n):
        d[i] = x[i + 1] - x[i]
        dt[i] = t[i + 1] - t[i]
        pad[i + 5] = d[i] / dt[i]
    for j in range(5):
        pad[j] = pad[5]
        pad[n + 5 + j] = pad[n + 4]
    med = np.empty(n + 6)
    for j in range(n + 6):
        med[j] = _median5(pad[j], pad[j + 1], pad[j + 2], pad[j + 3], pad[j + 4])
    lo = np.empty(n)
    hi = np.empty(n)
    e = np.empty(n)
    r = np.empty(n)
    ne = 0
    nr = 0
    quantum = np.inf
    nz = False
    for i in range(n):
        vb = med[i]
        va = med[i + 6]
        if not np.isfinite(vb):
            vb = va
        if not np.isfinite(va):
            va = vb
        lo[i] = _nmin(vb, va) * dt[i]
        hi[i] = _nmax(vb, va) * dt[i]
        ei = d[i] - vb * dt[i]
        if np.isfinite(ei):
            e[ne] = ei
            ne += 1
        ri = pad[i + 5] - vb
        if np.isfinite(ri):
            r[nr] = ri
            nr += 1
        if d[i] != 0.0:
            a = abs(d[i])
            if nz:
                quantum = _nmin(quantum, a)
            else:
                quantum = a
                nz = True
    return d, dt, lo, hi, e[:ne], r[:nr], quantum if nz else 0.0


@numba.njit(cache=True)
def reset_jumps(d: np.ndarray, dt: np.ndarray, lo: np.ndarray, hi: np.ndarray, widen: float,
                margin: float) -> np.ndarray:
    """The increments outside ``[lo - widen dt - margin, hi + widen dt + margin]``
    (:func:`.artifacts.find_resets`: the same operations, in the same order)."""
    out = np.empty(d.size, np.int64)
    m = 0
    for i in range(d.size):
        w = widen * dt[i]
        if d[i] < (lo[i] - w) - margin or d[i] > (hi[i] + w) + margin:
            out[m] = i
            m += 1
    return out[:m]


@numba.njit(cache=True)
def row_medians(a: np.ndarray) -> np.ndarray:
    """``np.median(a, axis=1)`` of a C-contiguous 2-d float64 array of short rows (blocks of a
    few to a few tens of samples): each row sorted by insertion, the middle value or the mean
    of the two middle ones (``(p + q) / 2``, as NumPy's mean of them), NaN for a row that holds
    one, as NumPy's: the same numbers, without a partition call per row."""
    m, k = a.shape
    out = np.empty(m)
    s = np.empty(k)
    h = k // 2
    for i in range(m):
        nan = False
        for j in range(k):
            v = a[i, j]
            if v != v:
                nan = True
            # insertion: s[:j] sorted
            p = j
            while p > 0 and s[p - 1] > v:
                s[p] = s[p - 1]
                p -= 1
            s[p] = v
        if nan:
            out[i] = np.nan
        elif k % 2:
            out[i] = s[h]
        else:
            out[i] = (s[h - 1] + s[h]) / 2.0
    return out


@numba.njit(cache=True)
def _median(a: np.ndarray) -> float:
    """:func:`.segmentation.median` of a 1-d float64 array (sorted: the middle value or ``(p +
    q) / 2`` of the two middle ones; NaN where one is NaN or there is none): the same number."""
    n = a.size
    if n == 0:
        return np.nan
    s = np.sort(a)  # a NaN sorts last, as in the partition
    k = n // 2
    for i in range(k, n):
        if s[i] != s[i]:
            return np.nan
    if n % 2:
        return s[k]
    return (s[k - 1] + s[k]) / 2.0


@numba.njit(cache=True)
def _floor0(a: float) -> float:
    """Python's ``max(a, 0.0)``: 0 only where ``0.0 > a`` (a NaN is kept)."""
    return 0.0 if 0.0 > a else a


@numba.njit(cache=True, error_model="numpy")
def fluctuation_scales(t: np.ndarray, res: np.ndarray, speed: np.ndarray, widths: np.ndarray,
                       min_vars: np.ndarray, half_s2: float, top: float, moving_z: float,
                       moving_share: float, moving_min: int, two: float
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The wander's ``r(T)`` and ``a(T)`` at each duration of ``widths`` where 24 window pairs or
    more are usable, and those durations (:func:`.detection.measure_fluctuations`, which
    documents the model; before its non-increasing envelope).

    Its loop over the durations, compiled: the pairs of :func:`window_pairs` at the offsets 0,
    1/2, 1/4 and 3/4 of a duration (the last two only while fewer than 100 pairs), the faster
    half by a stable sort of the speeds, the medians of :func:`_median`; the same operations in
    the same order, so the same numbers to the last bit. ``min_vars`` (``T**2 / 48``) and
    ``half_s2`` (``sigma**2 / 2``) come computed as the NumPy form computes them, and ``two``
    (2.0) is an argument so that ``r**2`` of the shorter duration is C's ``pow``, as NumPy's
    scalar power is, not a product the compiler would fold it to."""
    nT = widths.size
    scales = np.empty(nT)
    rel = np.empty(nT)
    ab = np.empty(nT)
    kept = 0
    for iT in range(nT):
        T = widths[iT]
        ys = []
        us = []
        count = 0
        for io in range(4):
            off = (0.0, 0.5 * T, 0.25 * T, 0.75 * T)[io]
            if io >= 2 and count >= 100:
                break  # pairs enough from two offsets (the other two only for long T)
            y_off, u_off = window_pairs(t, res, speed, T, t[0] - off, half_s2, min_vars[iT])
            ys.append(y_off)
            us.append(u_off)
            count += y_off.size
        y = np.empty(count)
        u = np.empty(count)
        j = 0
        for q in range(len(ys)):
            for i in range(ys[q].size):
                y[j] = ys[q][i]
                u[j] = us[q][i]
                j += 1
        if count < 24:
            continue
        fast = np.zeros(count, np.bool_)
        order = np.argsort(u, kind="mergesort")  # stable: ties split by rank
        for i in range(count // 2, count):
            fast[order[i]] = True
        slow_y = y[~fast]
        a0 = np.sqrt(_floor0(2.198 * _median(slow_y)))
        moving = fast.copy()
        if moving_z > 0.0:
            for i in range(count):
                moving[i] = fast[i] and u[i] >= moving_z * a0 and u[i] >= moving_share * top
        n_mov = 0
        all_pos = True
        for i in range(count):
            if moving[i]:
                n_mov += 1
                if not u[i] > 0.0:
                    all_pos = False
        if moving_z > 0.0 and n_mov < moving_min:
            r2 = math.pow(rel[kept - 1], two) if kept > 0 else 0.0  # the shorter scale's
        elif all_pos:
            q = np.empty(n_mov)
            j = 0
            for i in range(count):
                if moving[i]:
                    q[j] = y[i] / (u[i] * u[i])
                    j += 1
            r2 = 2.198 * _median(q)
        else:
            r2 = 0.0
        r2 = _floor0(r2)
        e = np.empty(count // 2)  # the slower half
        j = 0
        for i in range(count):
            if not fast[i]:
                e[j] = y[i] - r2 * (u[i] * u[i])
                j += 1
        a2 = _floor0(2.198 * _median(e))
        scales[kept] = T
        rel[kept] = np.sqrt(r2)
        ab[kept] = np.sqrt(a2)
        kept += 1
    return scales[:kept], rel[:kept], ab[:kept]
