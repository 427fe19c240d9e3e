"""Change points of a noisy piecewise-linear signal: where a load-point displacement changes slope.

The model is a continuous broken line ``x(t)`` plus white noise. Binary segmentation splits a
stretch at the *hinge* (two lines meeting at a sample time) that lowers the residual sum of
squares most, and keeps the split when the gain beats a penalty of ``penalty * sigma**2 *
ln(n)`` (a BIC-like criterion: two more parameters, the kink and its place); each boundary is
then moved to the best hinge between its neighbours. Everything is done with cumulative sums in
the time variable, so the cost is ``O(n log k)`` and a change of sampling rate changes nothing.
"""

from __future__ import annotations

import heapq

import numpy as np

from ..validation import Array

__all__ = ["kernel_input", "median", "quantile", "noise_level", "line_fit", "step_gains", "rss",
           "best_hinge", "hinge_segments", "refine", "prune"]


def median(a: Array) -> float:
    """The median of an array's values, ``np.median``'s to the last bit (the middle value, or
    the mean of the two middle ones, ``(p + q) / 2``; NaN where one is NaN or there is none).

    From one partition at the upper middle rank and the largest value below it: NumPy's median
    partitions at both middle ranks and at the last (its NaN check), about five times the cost
    on a record of 20 000 samples, where the detector takes a dozen medians a record."""
    a = np.asarray(a, float).ravel()
    n = a.size
    if n == 0:
        return float("nan")
    k = n // 2
    p = np.partition(a, k)
    if np.isnan(p[k:]).any():  # a NaN sorts last: none before a NaN at k
        return float("nan")
    if n % 2:
        return float(p[k])
    return float((p[:k].max() + p[k]) / 2.0)


def quantile(a: Array, q: float) -> float:
    """The ``q`` quantile of an array's values, ``np.quantile``'s (its default, linear
    interpolation between the order statistics at ``floor((n - 1) q)`` and the next, by its
    own formula) to the last bit; NaN where one is NaN.

    From one partition at the upper rank and the largest value below it: NumPy partitions at
    both ranks and at the first and the last, about five times the cost on a long record."""
    a = np.asarray(a, float).ravel()
    n = a.size
    if n == 0:
        return float("nan")
    vi = (n - 1) * q
    if vi >= n - 1 or vi < 0:  # beyond the ends: the largest or the smallest
        i = n - 1 if vi >= n - 1 else 0
        p = np.partition(a, i)
        if np.isnan(p[i:]).any():
            return float("nan")
        return float(p[i])
    i = int(np.floor(vi))
    p = np.partition(a, i + 1)
    if np.isnan(p[i + 1:]).any():
        return float("nan")
    lo, hi = p[:i + 1].max(), p[i + 1]
    g = vi - i
    d = hi - lo
    # NumPy's lerp: from the lower end, or for a weight of 1/2 or more from the upper one
    return float(hi - d * (1 - g) if g >= 0.5 else lo + d * g)


def noise_level(x: Array) -> float:
    """Standard deviation of the white noise on a smooth signal, from its second differences.

    The larger of a robust (MAD) and a trimmed-RMS estimate, so that a quantised signal (most
    second differences zero, a few one quantum) is not taken as noise-free.
    """
    d2 = np.diff(np.asarray(x, float), 2)
    if d2.size == 0:
        return 0.0
    mad = 1.4826 * median(np.abs(d2 - median(d2)))
    a = np.abs(d2)
    trimmed = a[a <= quantile(a, 0.99)]
    rms = float(np.sqrt(np.mean(trimmed**2))) if trimmed.size else 0.0
    return max(mad, rms) / np.sqrt(6.0)  # var(x[i+1] - 2x[i] + x[i-1]) = 6 sigma^2


def line_fit(t: Array, x: Array) -> tuple[float, float, float]:
    """Least-squares line through ``(t, x)``.

    Returns
    -------
    slope : float
    intercept : float
        Value at ``t = mean(t)``.
    sxx : float
        ``sum((t - mean t)**2)``: the slope's standard error is ``sigma / sqrt(sxx)``.
    """
    tc = t - t.mean()
    xm = x.mean()
    # sums, not ``@``: a BLAS call per short stretch costs more than it saves
    sxx = float(np.sum(tc * tc))
    slope = float(np.sum(tc * (x - xm)) / sxx) if sxx > 0 else 0.0
    return slope, float(xm), sxx


def step_gains(t: Array, y: Array, ks: Array) -> tuple[Array, Array, Array]:
    """What a step of ``y(t)`` at each sample of ``ks`` saves over its least-squares line.

    The step ``h_k`` is 1 from sample ``k`` on, 0 before; projected off the line (columns 1
    and ``t``) its squared norm is ``n_k - n_k**2 / n - (sum_{i>=k} (t_i - tbar))**2 / Sxx``
    (``n_k = n - k``), and one more column saves ``(r . h_k)**2`` over that norm of the residual
    sum of squares, ``r`` the line's residuals (least squares with one more regressor,
    Frisch-Waugh-Lovell).

    Parameters
    ----------
    t : Array
        Times, s (not all equal).
    y : Array
        Values, any unit.
    ks : Array of int
        The steps' first samples, ``0 < k < len(t)``.

    Returns
    -------
    r : Array
        The line's residuals, ``y``'s unit.
    rs : Array
        ``r . h_k`` for each ``k``: the residuals summed from ``k`` on.
    den : Array
        ``|h_k|**2`` projected off the line; the gain is ``rs**2 / den`` where ``den > 0``.
    """
    slope, mean, sxx = line_fit(t, y)
    tc = t - t.mean()
    r = y - mean - slope * tc
    ks = np.asarray(ks, dtype=np.int64)
    rs = np.cumsum(r[::-1])[::-1][ks]
    ts = np.cumsum(tc[::-1])[::-1][ks]
    n = t.size
    ni = (n - ks).astype(float)
    return r, rs, ni - ni**2 / n - (ts**2 / sxx if sxx > 0 else 0.0)


def _plain(a: Array) -> bool:
    """Whether ``a`` is a contiguous, writable float64 ndarray (as the compiled kernel takes)."""
    if type(a) is not np.ndarray or a.dtype != np.float64:
        return False
    f = a.flags
    return bool(f.c_contiguous and f.writeable)


def kernel_input(a: Array) -> Array:
    """``a`` as the compiled kernels take it (:mod:`.hinge_kernel`): a contiguous, writable
    float64 array (the same values; a copy only where it is not one: the reader's arrays are
    read-only). One array type, so one compiled specialisation per kernel, the one
    ``python -m dryfriction.warm`` builds."""
    return a if _plain(a) else np.require(a, np.float64, ["C", "W"])


def best_hinge(t: Array, x: Array, m: int, min_dur: float, compiled: bool = True
               ) -> tuple[int, float]:
    """Best hinge sample ``k`` (``m <= k <= n - m``) and the RSS it saves over one line.

    Compiled (:func:`.hinge_kernel.hinge_scan`, the same sums sample by sample) unless
    ``compiled=False``: this NumPy form is the reference it is tested against."""
    if compiled:
        from .hinge_kernel import hinge_scan  # Numba: imported on first use only

        # contiguous, writable float64: one compiled specialisation (the one warm-up builds);
        # a slice of the detector's arrays is one already (np.require's checks cost more than
        # the scan of a short stretch: tested here first)
        k, g = hinge_scan(t if _plain(t) else np.require(t, np.float64, ["C", "W"]),
                          x if _plain(x) else np.require(x, np.float64, ["C", "W"]), int(m),
                          float(min_dur))
        return int(k), float(g)
    n = len(t)
    if n < 2 * m + 1:
        return -1, 0.0
    half = 0.5 * (t[-1] - t[0])
    tt = (t - 0.5 * (t[-1] + t[0])) / half  # in [-1, 1]: the sums stay well conditioned
    slope, mean, _ = line_fit(tt, x)
    r = x - mean - slope * (tt - tt.mean())  # the hinge's space holds every line: RSS unchanged
    cs = [np.concatenate([[0.0], np.cumsum(q)]) for q in (tt, r, tt * tt, tt * r)]
    k = np.arange(m, n - m + 1)
    keep = ((t[k] - t[0]) >= min_dur) & ((t[-1] - t[k]) >= min_dur)
    k = k[keep]
    if k.size == 0:
        return -1, 0.0
    tk = tt[k]
    st, sr, stt, str_ = (c[k] for c in cs)
    st_r, sr_r, stt_r, str_r = (c[-1] - c[k] for c in cs)
    n_l, n_r = k.astype(float), (n - k).astype(float)
    su_l, su_r = st - n_l * tk, st_r - n_r * tk
    suu_l = stt - 2 * tk * st + n_l * tk**2
    suu_r = stt_r - 2 * tk * st_r + n_r * tk**2
    sux_l, sux_r = str_ - tk * sr, str_r - tk * sr_r
    # normal equations of x = c + v1 min(t - tk, 0) + v2 max(t - tk, 0): the slopes' rows
    # give v1, v2 in terms of c, which the first row then fixes (no batched 3x3 solve)
    sx = cs[1][-1]
    gain = np.full(k.size, -np.inf)
    ok = (suu_l > 0) & (suu_r > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        den = n - su_l**2 / suu_l - su_r**2 / suu_r
        c = (sx - su_l * sux_l / suu_l - su_r * sux_r / suu_r) / den
        v1 = (sux_l - su_l * c) / suu_l
        v2 = (sux_r - su_r * c) / suu_r
        g = c * sx + v1 * sux_l + v2 * sux_r  # RSS(line) - RSS(hinge)
    ok &= np.isfinite(g) & (den > 0)
    gain[ok] = g[ok]
    best = int(np.argmax(gain))
    return int(k[best]), float(gain[best])


def hinge_segments(
    t: Array,
    x: Array,
    sigma: float,
    *,
    min_samples: int = 10,
    min_duration: float = 0.0,
    penalty: float = 10.0,
    max_segments: int = 10_000,
    max_points: int = 5_000,
    tidy: bool = True,
) -> list[int]:
    """Sample indices of the slope changes of ``x(t)``, with ``0`` and ``len(t)`` at the ends.

    A long record (more than ``max_points`` samples) is searched on the means of blocks of
    ``len(t) // max_points`` samples (time averaged too, so the sampling may vary), and each
    change found is then placed on the samples within two blocks of it: the cost stays
    about linear in the length. A stretch is then at least three blocks long.

    Parameters
    ----------
    t, x : Array
        Times (strictly increasing) and the signal.
    sigma : float
        Noise level of ``x`` (:func:`noise_level`), ``> 0``.
    min_samples, min_duration : int, float
        Shortest stretch, in samples and in time.
    penalty : float
        A split is kept when it lowers the residual sum of squares by more than
        ``penalty * sigma**2 * ln(n)``.
    max_segments : int
        Stop splitting beyond this many stretches.
    max_points : int
        Longest signal searched sample by sample.
    tidy : bool
        Prune the stretches that do not earn their place (:func:`prune`); ``False`` leaves
        that to the caller (a detector with its own criterion).
    """
    n = len(t)
    xs = (np.asarray(x, float) - x[0]) / sigma
    block = max(1, n // max_points)
    if block == 1:
        return _segment(t, xs, penalty * np.log(max(n, 2)), min_samples, min_duration,
                        max_segments, tidy)
    nb = n // block
    tb = t[: nb * block].reshape(nb, block).mean(axis=1)
    xb = xs[: nb * block].reshape(nb, block).mean(axis=1)
    # white noise averages down by sqrt(block); slow wander (a motor's wobble) does not
    sb = max(1.0 / np.sqrt(block), noise_level(xb))
    coarse = _segment(tb, xb / sb, penalty * np.log(nb), max(3, -(-min_samples // block)),
                      min_duration, max_segments)
    out = [0]
    for j in range(1, len(coarse) - 1):
        k = coarse[j] * block
        a = max(out[-1], k - 2 * block)
        b = min(coarse[j + 1] * block, k + 2 * block)
        kk, _ = best_hinge(t[a:b], xs[a:b], min(min_samples, (b - a) // 3), 0.0)
        out.append(a + kk if kk > 0 else k)
    # a block that straddles a kink lies off both lines: it may have left a short stretch
    return prune(t, xs, out + [n], penalty * np.log(n), min_samples, 0.0, window=4 * block)


def _segment(t: Array, xs: Array, threshold: float, m: int, min_dur: float,
             max_segments: int, tidy: bool = True) -> list[int]:
    """Binary segmentation, best split first (so that ``max_segments`` keeps the largest
    gains), then each boundary refined and the stretches pruned."""
    n = len(t)
    bounds = [0, n]
    heap: list[tuple[float, int, int, int]] = []

    def push(a: int, b: int) -> None:
        k, gain = best_hinge(t[a:b], xs[a:b], m, min_dur)
        if k > 0 and gain > threshold:
            heapq.heappush(heap, (-gain, a, b, a + k))

    push(0, n)
    while heap and len(bounds) - 1 < max_segments:
        _, a, b, k = heapq.heappop(heap)
        bounds.append(k)
        push(a, k)
        push(k, b)
    bounds.sort()
    bounds = refine(t, xs, bounds, m, min_dur)
    return prune(t, xs, bounds, threshold, m, min_dur) if tidy else bounds


def rss(t: Array, xs: Array, bounds: list[int]) -> float:
    """Residual sum of squares of a line fitted to each stretch."""
    total = 0.0
    for a, b in zip(bounds[:-1], bounds[1:], strict=True):
        slope, mean, _ = line_fit(t[a:b], xs[a:b])
        r = xs[a:b] - mean - slope * (t[a:b] - t[a:b].mean())
        total += float(np.sum(r * r))
    return total


def prune(t: Array, xs: Array, bounds: list[int], threshold: float, m: int,
          min_dur: float, window: int | None = None) -> list[int]:
    """Drop the stretches that do not earn their place, shortest first.

    Binary segmentation can leave a short stretch across a kink (two splits where one
    would do): a stretch is dropped when one hinge between its neighbours fits within
    ``threshold`` (in RSS) of the three stretches. With ``window``, only stretches shorter
    than ``2 * window`` samples are tried, each on its neighbours' samples within
    ``window`` of it (the cost stays local).
    """
    out = list(bounds)
    kept: set[tuple[int, ...]] = set()  # the outcome depends only on these boundaries
    changed = True
    while changed and len(out) > 2:
        changed = False
        order = sorted(range(len(out) - 1), key=lambda j: out[j + 1] - out[j])
        for j in order:
            if window is not None and out[j + 1] - out[j] >= 2 * window:
                break
            lo, hi = max(j - 1, 0), min(j + 2, len(out) - 1)
            sub = list(out[lo:hi + 1])
            if window is not None:
                sub[0], sub[-1] = max(sub[0], out[j] - window), min(sub[-1], out[j + 1] + window)
            if tuple(sub) in kept:
                continue
            a, b = sub[0], sub[-1]
            now = rss(t, xs, sub)
            if len(sub) == 4:
                k, _ = best_hinge(t[a:b], xs[a:b], min(m, (b - a) // 3), 0.0)
                if k <= 0:
                    kept.add(tuple(sub))
                    continue
                alt, new = [a, a + k, b], [a + k]
            else:
                alt, new = [a, b], []
            if rss(t, xs, alt) - now < threshold:
                out[lo + 1:hi] = new
                changed = True
                break
            kept.add(tuple(sub))
    return out


def refine(t: Array, xs: Array, bounds: list[int], m: int, min_dur: float,
           only: set[int] | None = None) -> list[int]:
    """Move each inner boundary (or those whose sample index is in ``only``) to the best hinge
    between its two neighbours (one pass)."""
    out = list(bounds)
    for j in range(1, len(out) - 1):
        if only is not None and out[j] not in only:
            continue
        a, b = out[j - 1], out[j + 1]
        k, _ = best_hinge(t[a:b], xs[a:b], m, min_dur)
        if k > 0:
            out[j] = a + k
    return out
