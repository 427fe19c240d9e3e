"""The artifacts of a laboratory record that are not velocity changes.

Displacement resets (a transducer re-zeroed: a jump in one sample that neither neighbouring
velocity explains; or, too small for that, a short excursion that a jump fits as well),
sampling-rate changes and gaps, and normal-stress changes (a segment boundary). Found here,
reported by :func:`.detection.detect_program`; every criterion is ours.
"""

from __future__ import annotations

import numpy as np

from ..validation import Array
from .segmentation import kernel_input, line_fit, median, noise_level, step_gains

__all__ = ["find_resets", "jump_excursions", "moves_backwards", "normal_changes", "same_velocity",
           "sampling_changes", "split_rss", "trapezoid_displacement"]

_RESET_K = 10.0
"""A reset's jump, in robust scales of the increments' scatter beyond the range the local
rates explain (ours). 15 before (set a priori); 10 since measured: on 2520 used zoo records
the largest such excess away from the true re-zeroing was below 10 on all but 17 (and below 15
on all but 10; every one of the 17 in a record with a re-zeroing of hundreds of scales), while
re-zeroings of 10-15 scales were missed: zoo 9000 and 22020 (a 3.7-um re-zeroing 2.4 s after
a ratio-3 up-step, read as a stretch of its own). Over the 4650 used records and 1800 looked
into (17000-22299) the change fixed 9000, 15171 and 22020 and broke none, at the same CPU."""
_NORMAL_REL = 0.03  # a normal-stress change: at least 3 % of the level ...
_NORMAL_K = 10.0  # ... and 10 robust scales of its block-to-block scatter
_RATE_FACTOR = 1.5  # a sampling-rate change: the median interval changes by this factor
NORMAL_BLOCKS = 10
"""Normal-stress changes found within this many blocks of each other are one (a ramp split
several times), whatever the time between them (ours): the blocks are of a fixed count of
samples, so where the sampling is slow (a 10-fold rate change) or a gap lies between two
blocks, 30 s held only two or three blocks, and one ramp was reported as two changes, at
the same sample (zoo records 7049, 7186, 8125: each cluster's half-way crossing is looked
for within two blocks of it) or beside each other (208, 5160)."""


def _median5(a: Array, b: Array, c: Array, d: Array, e: Array) -> Array:
    """Elementwise median of five arrays (a selection network: the lowest and the highest of
    the first four cannot be the median, which is then the median of the other two and
    ``e``)."""
    f = np.maximum(np.minimum(a, b), np.minimum(c, d))
    g = np.minimum(np.maximum(a, b), np.maximum(c, d))
    return np.maximum(np.minimum(f, g), np.minimum(np.maximum(f, g), e))


def _local_rate(rate: Array, side: str, k: int = 5) -> Array:
    """Median of the ``k`` increment rates before (``side='before'``) or after each increment
    (the record's first or last rate standing in beyond its ends)."""
    n = len(rate)
    pad = np.concatenate([np.full(k, rate[0]), rate, np.full(k, rate[-1])])
    # window j covers pad[j:j+k] = rate[j-k:j]: before increment i is window i, after is i+k+1
    o = 0 if side == "before" else k + 1
    if k == 5:  # a network, not a sort per row (a tenth of the time); the windows' j-th
        # members are the slice pad[o + j:o + j + n], no copy of the n x k windows
        return _median5(*(pad[o + j:o + j + n] for j in range(5)))
    win = np.lib.stride_tricks.sliding_window_view(pad, k)
    return np.median(win[np.arange(n) + o], axis=1)


def find_resets(t: Array, x: Array) -> tuple[Array, list[int]]:
    """``x`` with its resets taken out, and the increments ``i`` (``x[i] -> x[i+1]``) that were.

    A reset is one increment outside the range that the velocities just before and just after
    it explain, by more than :data:`_RESET_K` robust scales of the increments' scatter (ours).
    """
    if len(x) - 1 < 12:
        return x, []
    if COMPILED_RESETS:
        from .hinge_kernel import reset_increments, reset_jumps  # Numba: on first use only

        # the lines below in one compiled pass (the same numbers): the medians stay NumPy's
        d, dt, lo, hi, e, r, quantum = reset_increments(kernel_input(t), kernel_input(x))
    else:
        d = np.diff(x)
        dt = np.diff(t)
        rate = d / dt
        vb, va = _local_rate(rate, "before"), _local_rate(rate, "after")
        vb = np.where(np.isfinite(vb), vb, va)
        va = np.where(np.isfinite(va), va, vb)
        lo, hi = np.minimum(vb, va) * dt, np.maximum(vb, va) * dt
        e = d - vb * dt  # the increment less the slip the velocity just before gives
        e = e[np.isfinite(e)]
        nz = np.abs(d[d != 0.0])
        quantum = float(nz.min()) if nz.size else 0.0
        r = (rate - vb)[np.isfinite(rate - vb)]
    spread = 1.4826 * median(np.abs(e - median(e))) if e.size else 0.0
    scale = max(spread, quantum, 1e-12 * float(np.ptp(x)), 1e-300)
    # the local rates are medians of 5 noisy increment rates: their error, times an
    # increment's duration, is large across a gap (a fast-sampled record's 5-s gap is
    # hundreds of intervals), so it widens the range by 3 of its scales (1.2533: a median's)
    s_v = 1.2533 * 1.4826 * median(np.abs(r - median(r))) / np.sqrt(5.0) if (
        r.size) else 0.0
    if COMPILED_RESETS:
        jump = reset_jumps(d, dt, lo, hi, 3.0 * s_v, _RESET_K * scale)
    else:
        lo, hi = lo - 3.0 * s_v * dt, hi + 3.0 * s_v * dt
        jump = np.flatnonzero((d < lo - _RESET_K * scale) | (d > hi + _RESET_K * scale))
    if jump.size == 0:
        return x, []
    fix = np.zeros_like(x)
    edges = [0] + [int(i) + 1 for i in jump] + [len(x)]
    gap = gap_intervals(dt, median(dt))
    kept: list[int] = []
    for j, i in enumerate(jump):
        # the offset: one line with a step at the jump, fitted to up to 30 samples a side,
        # or as far each side as the increment lasts (RESET_WIDE: a gap)
        a, b = max(edges[j], i + 1 - 30), min(edges[j + 2], i + 1 + 30)
        rows = np.arange(a, b)
        if RESET_WIDE:
            rows = _offset_rows(t, i, edges[j], edges[j + 2], rows)
        tt = t[rows] - t[i]
        A = np.column_stack([np.ones(rows.size), tt, (rows > i).astype(float)])
        step = _reset_offset(tt, A, x[rows], scale) if RESET_KINK else float(np.linalg.lstsq(
            A, x[rows], rcond=None)[0][2])
        if RESET_GAP and gap[i]:
            # across a gap: a reset only where the step stands out of the lines' own scatter
            res = x[rows] - A @ np.linalg.lstsq(A, x[rows], rcond=None)[0]
            if abs(step) <= RESET_GAP_K * float(np.sqrt(np.mean(res * res))):
                continue
        fix[i + 1:] -= step
        kept.append(int(i))
    return x + fix, kept


COMPILED_RESETS = True
"""Whether :func:`find_resets` tests the increments in one compiled pass
(:func:`.hinge_kernel.reset_increments`, :func:`.hinge_kernel.reset_jumps`) rather than
NumPy's dozen passes over the record, and the block medians of :func:`sampling_changes` and
:func:`normal_changes` are compiled (:func:`.hinge_kernel.row_medians`): the same operations,
the same numbers (a speed change only; the NumPy forms are kept as the reference the tests
compare with)."""

RESET_WIDE = True
"""A reset's offset is fitted on samples reaching at least as far each side as its increment
lasts (ours): the step is the difference of the two sides' lines at the jump, so the slope's
error is carried across the increment, and over a gap (a record's logging paused for 5-60 s,
where a re-zeroing is likeliest and where the local rates cannot tell a jump from the
wander's slip) 30 samples a side (0.6 s at 50 Hz) put a slope of 1.2 s's wander across 28 s:
zoo 13263, a 28-s gap at 50 Hz, read a -11 um offset there and a false stretch at 1.56 um/s
across the gap between two of 1.17 (the zoo's gaps integrated exactly: the zoo's note). At most
:data:`RESET_SIDE` samples a side, evenly picked."""
RESET_SIDE = 200
"""The most samples a side a reset's offset is fitted on (:data:`RESET_WIDE`; ours: the
kink's columns of :func:`_reset_offset` are a square of the rows, 1.3 MB at 400)."""


def _offset_rows(t: Array, i: int, lo: int, hi: int, rows: Array) -> Array:
    """The samples (indices into ``t``, s) a reset's offset at increment ``i`` is fitted on
    (:data:`RESET_WIDE`): ``rows`` (30 a side), widened to reach ``t[i + 1] - t[i]`` before
    ``t[i]`` and after ``t[i + 1]``, not past ``lo`` and ``hi`` (the neighbouring resets), at
    most :data:`RESET_SIDE` a side."""
    span = float(t[i + 1] - t[i])
    a = min(int(rows[0]), max(lo, int(np.searchsorted(t, t[i] - span))))
    b = max(int(rows[-1]) + 1, min(hi, int(np.searchsorted(t, t[i + 1] + span, "right"))))
    left = np.arange(a, i + 1)
    right = np.arange(i + 1, b)
    if left.size > RESET_SIDE:
        left = left[np.linspace(0, left.size - 1, RESET_SIDE).round().astype(np.int64)]
    if right.size > RESET_SIDE:
        right = right[np.linspace(0, right.size - 1, RESET_SIDE).round().astype(np.int64)]
    return np.concatenate([left, right])


RESET_GAP = True
"""An increment across a gap (longer than 10 times the median interval and the one before it,
as :func:`sampling_changes` finds gaps) that the local rates do not explain is a reset only
where its step exceeds :data:`RESET_GAP_K` times the rms residual of the offset's lines (ours).
Why: over a gap of 5-60 s the load point's wander (the servo's error, the machine
oscillation: a few tenths of the velocity times a second) is beyond the reach of rates
measured over 5 increments, so every such gap read as a re-zeroing, and the table listed a
reset the apparatus never made (zoo 396: its two gaps' ends, 187.3 and 868.7 s). Measured on
zoo records 3000-3299 with gaps (120, the zoo's gaps integrated exactly): the step over the
residual rms was 0.0-8.0 at the 18 gaps taken for jumps, 172-1096 at the 86 true resets."""
RESET_GAP_K = 20.0

RESET_KINK = True
"""A reset's offset is fitted with a kink of the line allowed in its window (ours, detect11):
the window is up to 30 samples a side, 6-36 s in a slowly sampled record, and a velocity
change within it bent the one line, whose step then took 1-2 um that was slip; that offset
read as a stretch of its own beside the change (zoo 3210, a reset 17 s before an up-step at
0.8 Hz; 6058, 2.4 s before a restart at 5 Hz)."""

RESET_KINK_PENALTY = 10.0
"""The kink is used where it lowers the residual sum of squares by more than this many
``sigma**2 ln n`` (the penalty of :func:`.segmentation.hinge_segments` as the detector calls
it: two more parameters, the kink and its place)."""


def _reset_offset(tt: Array, A: Array, x: Array, scale: float) -> float:
    """The step of ``x`` (m) at a reset, from a line with a step and, where
    :data:`RESET_KINK_PENALTY` says so, a kink at the best sample of the window (ours).

    Parameters
    ----------
    tt : Array
        Times from the jump, s.
    A : Array
        Design of the line with a step: columns 1, ``tt`` and the step (0 before, 1 after).
    x : Array
        Displacement, m.
    scale : float
        Robust scale of the increments' scatter, m (``sqrt 2`` times the samples' noise).

    Returns
    -------
    float
        The step, m.
    """
    coef = np.linalg.lstsq(A, x, rcond=None)[0]
    r = x - A @ coef
    step = float(coef[2])
    if len(tt) < 5:
        return step
    # each kink's gain over the line with a step, all at once: its column less its
    # projection on A's, then (r . h)**2 / |h|**2 (one more column of a least-squares fit)
    q, _ = np.linalg.qr(A)
    H = np.maximum(tt[:, None] - tt[None, 2:len(tt) - 2], 0.0)
    H = H - q @ (q.T @ H)
    norm = np.einsum("ij,ij->j", H, H)
    with np.errstate(divide="ignore", invalid="ignore"):
        gain = np.where(norm > 1e-9 * norm.max(), (r @ H) ** 2 / norm, 0.0)
    k = int(np.argmax(gain))
    sigma2 = 0.5 * scale**2  # the increments' scatter is sqrt(2) the samples'
    if gain[k] > RESET_KINK_PENALTY * sigma2 * np.log(len(tt)):
        Ak = np.column_stack([A, np.maximum(tt - tt[k + 2], 0.0)])
        step = float(np.linalg.lstsq(Ak, x, rcond=None)[0][2])
    return step


JUMP_REL = 0.1
"""An excursion is a jump of the displacement when a line with a step fits within this fraction
of the three stretches' residual sum of squares (ours; zoo record 123, a 3-um re-zeroing at 20
Hz under a 0.12-um quantum: 6 %)."""


JUMP_REFINED = True
"""Where the detector searched block means (a long record), an excursion is compared with a
jump as the load point makes one: a continuous broken line whose two kinks are each moved to
the sample within two blocks of where the search put them that fits best
(:func:`_broken_line`; the ``reach`` of :func:`jump_excursions`; ours). Why: a boundary found
on block means is known to a block, and a hold shorter than one is found as a longer stretch
at a lower speed (zoo 18046: 1084408 rows in blocks of 543, 27 s at its 20 Hz; a 19-s hold at
0.107 um/s found as a 52-s stretch at 0.055 um/s). The three lines at those boundaries fitted
worse than one line with a step, and the hold (2 um of slip not made) was taken out as a
re-zeroing of the transducer: the record lost a slide-hold-slide (zoo 11290, 18046).

Continuous, because three separate lines hold two jumps of their own: with their boundaries
free they took a true re-zeroing at one boundary and the wander in the middle stretch, and
re-zeroings were kept as excursions (zoo 123 and 368, searched on blocks of 13 and 6; tried
first, with the boundaries moved as far as the jump is searched for, ``m``: also 4061, 7103,
10151 and 14267, short records searched on the samples). Not where the search ran on the
samples: there its boundaries are where the data put them, and the broken line with kinks
moved that far broke zoo 7103 (a 33-um re-zeroing in a 60-s record, two false changes)."""


def _broken_line(t: Array, y: Array, b1: int, b2: int, m: int) -> float:
    """Least residual sum of squares of a continuous broken line of ``y(t)`` with kinks at
    samples ``b1`` and ``b2`` (``y = c + s t + d1 (t - t_b1)+ + d2 (t - t_b2)+``), each kink
    moved, in turn and twice, to its best sample within ``m`` of where it is, one sample at
    least strictly between them (ours; :data:`JUMP_REFINED`).

    An excursion of the velocity moves the load point continuously: no jump, which a kink
    on each side of one sample's step (nothing between them) would stand for.

    Parameters
    ----------
    t : Array
        Times, s (centred and scaled here: the normal equations are formed from sums).
    y : Array
        The values, best about one line (scaled here), any unit.
    b1, b2 : int
        The kinks' samples, ``0 < b1 < b2 - 1 < n - 3`` (held to it).
    m : int
        How far each may move, samples.

    Returns
    -------
    float
        The residual sum of squares, in ``y``'s unit squared.
    """
    n = len(t)
    scale = float(np.sqrt(np.mean(y * y))) or 1.0
    u = y / scale  # O(1) values: the sums below are differenced
    half = 0.5 * float(t[-1] - t[0]) or 1.0
    tt = (t - 0.5 * float(t[-1] + t[0])) / half  # in [-1, 1]: the normal equations stay sound

    def rev(a: Array) -> Array:  # sums from each sample to the end
        return np.cumsum(a[::-1])[::-1]

    # every product of the columns 1, t, (t - t_p)+, (t - t_q)+ and with u is a sum from the
    # later kink on, sum (t - t_c) w = S_tw(c) - t_c S_w(c): the reverse sums once, then each
    # candidate's 4 x 4 normal equations (no pass over the samples per candidate)
    s1, st, stt = rev(np.ones(n)), rev(tt), rev(tt * tt)
    su, stu = rev(u), rev(tt * u)
    uu = float(u @ u)

    def rss(p: Array, q: Array) -> Array:  # p < q, arrays of kinks
        tp, tq = tt[p], tt[q]
        g = np.empty((p.size, 4, 4))
        g[:, 0, 0], g[:, 0, 1], g[:, 1, 1] = n, st[0], stt[0]
        for col, c, tc in ((2, p, tp), (3, q, tq)):
            g[:, 0, col] = st[c] - tc * s1[c]
            g[:, 1, col] = stt[c] - tc * st[c]
            g[:, col, col] = stt[c] - 2.0 * tc * st[c] + tc * tc * s1[c]
        g[:, 2, 3] = stt[q] - (tp + tq) * st[q] + tp * tq * s1[q]
        g[:, 1, 0], g[:, 2, 0], g[:, 3, 0] = g[:, 0, 1], g[:, 0, 2], g[:, 0, 3]
        g[:, 2, 1], g[:, 3, 1], g[:, 3, 2] = g[:, 1, 2], g[:, 1, 3], g[:, 2, 3]
        rhs = np.column_stack([np.full(p.size, su[0]), np.full(p.size, stu[0]),
                               stu[p] - tp * su[p], stu[q] - tq * su[q]])
        # full rank: a sample before the first kink, one between them, one after the second
        coef = np.linalg.solve(g, rhs[:, :, None])[:, :, 0]
        return uu - np.einsum("ij,ij->i", coef, rhs)

    b2 = min(max(int(b2), 3), n - 2)
    b1 = min(max(int(b1), 1), b2 - 2)
    out = float("inf")
    for _ in range(2):
        c1 = np.arange(max(1, b1 - m), min(b2 - 2, b1 + m) + 1)
        if c1.size:
            r1 = rss(c1, np.full(c1.size, b2))
            b1, out = int(c1[np.argmin(r1)]), float(np.min(r1))
        c2 = np.arange(max(b1 + 2, b2 - m), min(n - 2, b2 + m) + 1)
        if c2.size:
            r2 = rss(np.full(c2.size, b1), c2)
            b2, out = int(c2[np.argmin(r2)]), float(np.min(r2))
    return max(out, 0.0) * scale * scale


JUMP_BETWEEN = True
"""A short stretch between two of different velocities is looked at as a jump too where it is
a spike, faster or slower than both by more than ``rel_tol``, of at most twice ``m`` samples
(the shortest stretch the search holds, about a jump it smears; ours): the line with a step is
then two lines with a step between them (:func:`split_rss`: the velocity may change at the
jump), compared with the three stretches as before; the caller puts one change between the
two stretches left (:func:`same_velocity` tells it which).

Why: a re-zeroing below :data:`_RESET_K` scales (a few quanta, or tens of um at high speeds
where the increments scatter more) that lies near a velocity change, or in a servo's
settling after one, is a spike between two different velocities, and was taken for two
changes: zoo 84086 (a 4.8-um jump 6.6 s after a 22.5 -> 7.3 um/s step, read as two changes
of confidence 1.2-1.6 after placement) and 84852 (a -3.5-um jump 6 s after a 4.0 -> 7.8 um/s
step, the step itself lost, the jump read as two changes). Not a longer spike: between two
velocities a slow stretch read with the wander fits a step about as well as its own line
(a settling of 330 samples after a step, 84086; pieces of a hold in ``bench_detect_holds`` C
and E, read as re-zeroings of 0.4-0.7 um that were never made)."""


def same_velocity(v: Array, j: int, rel_tol: float, drift: float) -> bool:
    """Whether the stretches either side of stretch ``j`` (velocities ``v``, m/s) are one
    velocity for :func:`jump_excursions`: within ``rel_tol`` of the faster, or apart by less
    than ``drift`` times the fastest speed around (stretches ``j - 2`` to ``j + 2``; two pieces
    of one hold, each read with the drift's creep)."""
    va, vb = float(v[j - 1]), float(v[j + 1])
    around = float(np.max(np.abs(v[max(j - 2, 0):j + 3])))
    return abs(vb - va) <= rel_tol * max(abs(va), abs(vb)) or abs(vb - va) < drift * around


def split_rss(t: Array, y: Array, ks: Array) -> tuple[Array, Array]:
    """For each split ``k`` of ``ks`` (``2 <= k <= len(t) - 2``): the residual sum of squares of
    two least-squares lines of ``y(t)``, one on the samples before ``k`` and one from ``k`` on,
    and the jump between them at ``t[k]`` (the right line less the left, ``y``'s unit); ours,
    from cumulative sums, on the times centred and the values less their own least-squares
    line (which changes neither: each piece's line takes a line up whole): a steep ramp with
    little noise would otherwise cancel in each piece's sums (an independent review: a
    relative error of 1 on 5000 samples at 1 mm/s with 0.1 nm of noise)."""
    tc = t - t.mean()
    yc = y - y.mean()
    stt = float(tc @ tc)
    if stt > 0.0:
        yc = yc - tc * (float(tc @ yc) / stt)
    z = np.zeros(1)
    c0 = np.arange(t.size + 1, dtype=float)
    c1, c2 = np.concatenate([z, np.cumsum(tc)]), np.concatenate([z, np.cumsum(tc * tc)])
    cy, cty = np.concatenate([z, np.cumsum(yc)]), np.concatenate([z, np.cumsum(tc * yc)])
    cyy = np.concatenate([z, np.cumsum(yc * yc)])
    ks = np.asarray(ks, np.int64)
    out_rss = np.zeros(ks.size)
    ends = []
    for lo, hi in ((np.zeros_like(ks), ks), (ks, np.full_like(ks, t.size))):
        n = c0[hi] - c0[lo]
        st, s2 = c1[hi] - c1[lo], c2[hi] - c2[lo]  # the piece's sums of t and t**2
        sy, sty, syy = cy[hi] - cy[lo], cty[hi] - cty[lo], cyy[hi] - cyy[lo]
        sxx = s2 - st * st / n
        sxy = sty - st * sy / n
        with np.errstate(divide="ignore", invalid="ignore"):
            slope = np.where(sxx > 0, sxy / sxx, 0.0)
        out_rss += np.maximum(syy - sy * sy / n - slope * sxy, 0.0)
        ends.append(sy / n + slope * (tc[ks] - st / n))  # each line at t[k]
    return out_rss, ends[1] - ends[0]


def jump_excursions(t: Array, x: Array, bounds: list[int], v: Array, rel_tol: float, m: int,
                    drift: float = 0.0, reach: int = 0) -> list[tuple[int, int, float]]:
    """Excursions (a stretch between two of the same velocity) that one line with a jump of
    the displacement fits as well: ``(j, k, jump)``, ``j`` the excursion's first boundary
    (index in ``bounds``), ``k`` the first sample after the jump, ``jump`` in m.

    Ours: a velocity excursion is a ramp of the displacement, a re-zeroing a jump. The line
    plus a step at the best sample ``k`` (its gain over one line from cumulative sums of the
    line's residuals) is compared with the three stretches' own lines near the excursion; it
    stands in for them when its residual sum of squares exceeds theirs by less than
    :data:`JUMP_REL` of theirs (relative: the residuals are mostly the red wander, not the
    white noise), with three parameters fewer.

    Parameters
    ----------
    t, x : Array
        Times, s, and load-point displacement, m (every sample).
    bounds : list of int
        Stretch boundaries (samples, from 0 to ``len(t)``).
    v : Array
        Velocity of each stretch, m/s.
    rel_tol : float
        Velocities within this fraction are the same (an excursion returns to it).
    m : int
        Samples either side of the excursion's boundaries where the jump may lie.
    drift : float
        Velocities apart by less than this fraction of the fastest speed around (the
        excursion, its neighbours and theirs) are the same too (two pieces of one hold, each
        read with the drift: :data:`.detection.DRIFT_SIZED`); 0 for ``rel_tol`` alone.
    reach : int
        Where positive, the excursion is a continuous broken line whose kinks are each moved
        up to this many samples to fit best (:data:`JUMP_REFINED`): the boundaries of a
        search on block means are known to a block; 0: three lines at the boundaries given.
    """
    out: list[tuple[int, int, float]] = []
    for j in range(1, len(bounds) - 2):
        if out and out[-1][0] >= j - 1:
            continue
        va, vb = v[j - 1], v[j + 1]
        # the same velocity on both sides (within rel_tol, or drift-sized)
        same = same_velocity(v, j, rel_tol, drift)
        # or a spike between two velocities (JUMP_BETWEEN): faster or slower than both
        spike = (JUMP_BETWEEN and (v[j] - va) * (v[j] - vb) > 0.0
                 and abs(v[j] - vb) > rel_tol * abs(vb)
                 and bounds[j + 1] - bounds[j] <= 2 * m)
        if not (same or spike) or abs(v[j] - va) <= rel_tol * abs(va):
            continue
        # near the excursion only (twice its length and m samples each side): the
        # neighbours' own wander far from it is no evidence either way
        w = 2 * (bounds[j + 1] - bounds[j]) + m
        a, c = max(bounds[j - 1], bounds[j] - w), min(bounds[j + 2], bounds[j + 1] + w)
        tt, y = t[a:c], x[a:c]
        n = c - a
        # the gain of a step starting at each sample (a-relative) over the line
        ks = np.arange(max(1, bounds[j] - m - a), min(n - 1, bounds[j + 1] + m - a))
        if ks.size == 0 or tt[-1] <= tt[0]:
            continue
        # (the line's residuals r are the broken line's data below, in either case)
        r, rs, den = step_gains(tt, y, ks)
        if same:
            with np.errstate(divide="ignore", invalid="ignore"):
                gain = np.where(den > 0, rs**2 / den, -np.inf)
            i = int(np.argmax(gain))
            rss_jump = float(r @ r) - float(gain[i])
            jump = float(rs[i] / den[i])
        else:
            # two lines with a step between them (the velocity may change at the jump), each
            # of at least two samples
            ks = ks[(ks >= 2) & (ks <= n - 2)]
            if ks.size == 0:
                continue
            rss_k, jumps = split_rss(tt, y, ks)
            i = int(np.argmin(rss_k))
            rss_jump, jump = float(rss_k[i]), float(jumps[i])
        if JUMP_REFINED and reach > 0:
            # boundaries known to a block: the excursion a continuous broken line, each
            # kink at its best sample within reach
            rss3 = _broken_line(tt - tt.mean(), r, bounds[j] - a, bounds[j + 1] - a, reach)
        else:
            rss3 = 0.0
            for p, q in zip([a, bounds[j], bounds[j + 1]], [bounds[j], bounds[j + 1], c],
                            strict=True):
                sl, mu, _ = line_fit(t[p:q], x[p:q])
                e = x[p:q] - mu - sl * (t[p:q] - t[p:q].mean())
                rss3 += float(e @ e)
        if rss_jump - rss3 < JUMP_REL * rss3:
            out.append((j, a + int(ks[i]), jump))
    return out


def _block_medians(a: Array) -> Array:
    """``np.median(a, axis=1)`` of blocks of samples (rows), compiled where it is the same
    and faster (:func:`.hinge_kernel.row_medians`, an insertion sort: a float64 array of rows
    of at most 32, :data:`COMPILED_RESETS`)."""
    if not COMPILED_RESETS or a.dtype != np.float64 or not 0 < a.shape[1] <= 32:
        return np.median(a, axis=1)
    from .hinge_kernel import row_medians  # Numba: imported on first use only

    return row_medians(kernel_input(a))


def sampling_changes(t: Array, block: int = 16) -> tuple[list[float], list[float]]:
    """Times of sampling-rate changes and of gaps (see :class:`Detection`)."""
    dt = np.diff(t)
    if dt.size < 2 * block:
        return [], []
    med = median(dt)
    m = dt.size // block
    bm = _block_medians(dt[: m * block].reshape(m, block))
    changes: list[float] = []
    ratio = bm[1:] / bm[:-1]
    for j in np.flatnonzero((ratio > _RATE_FACTOR) | (ratio < 1.0 / _RATE_FACTOR)):
        seg = dt[j * block:(j + 2) * block]
        new = bm[j + 1]
        k = int(np.argmax(np.abs(np.log(seg / new)) < np.log(1.2)))  # first at the new rate
        changes.append(float(t[j * block + k]))
    gap = np.flatnonzero(gap_intervals(dt, med))
    return changes, [float(t[i]) for i in gap]


def gap_intervals(dt: Array, med: float) -> Array:
    """Which sampling intervals ``dt`` (s) are gaps: longer than 10 times the larger of their
    median ``med`` and the interval before (ours; :func:`sampling_changes`, :data:`RESET_GAP`)."""
    return dt > 10.0 * np.maximum(med, np.concatenate([[med], dt[:-1]]))


def normal_changes(t: Array, sn: Array | None, min_samples: int = 10) -> list[int]:
    """Sample indices where the normal stress (or force) changes level (module docstring)."""
    if sn is None or len(sn) < 4 * min_samples:
        return []
    sn = np.asarray(sn, float)
    block = max(min_samples // 2, len(sn) // 2000, 1)
    m = len(sn) // block
    bm = _block_medians(sn[: m * block].reshape(m, block))
    noise = 1.4826 * median(np.abs(np.diff(bm) - median(np.diff(bm))))
    out: list[int] = []
    todo = [(0, m)]
    while todo:
        a, b = todo.pop()
        if b - a < 4:
            continue
        c = np.cumsum(bm[a:b])
        k = np.arange(2, b - a - 1)
        left = c[k - 1] / k
        right = (c[-1] - c[k - 1]) / (b - a - k)
        gain = np.abs(left - right) * np.sqrt(k * (b - a - k) / (b - a))
        j = int(np.argmax(gain))
        diff = abs(left[j] - right[j])
        level = max(abs(left[j]), abs(right[j]))
        if diff >= _NORMAL_REL * level and diff >= _NORMAL_K * noise:
            kk = a + int(k[j])
            out.append(kk)
            todo += [(a, kk), (kk, b)]
    # a ramp splits many times: changes within 30 s (or 10 blocks) of each other are one,
    # placed where the level crosses half-way between the levels outside the cluster
    tb = t[: m * block].reshape(m, block)[:, 0]
    # (the record's median interval, a pass over every sample, only where two changes may
    # be one)
    gap = max(30.0, 10 * block * median(np.diff(t))) if len(out) > 1 else 0.0
    clusters: list[list[int]] = []
    for kk in sorted(out):
        if clusters and (tb[kk] - tb[clusters[-1][-1]] <= gap
                         or kk - clusters[-1][-1] <= NORMAL_BLOCKS):
            clusters[-1].append(kk)
        else:
            clusters.append([kk])
    idx = []
    for c in clusters:
        lo_b, hi_b = c[0], c[-1]
        before = float(np.median(bm[max(lo_b - 5, 0):lo_b]))
        after = float(np.median(bm[hi_b:min(hi_b + 5, m)]))
        lo, hi = max((lo_b - 2) * block, 0), min((hi_b + 2) * block, len(sn))
        mid = 0.5 * (before + after)
        seg = sn[lo:hi]
        cross = np.flatnonzero(seg >= mid if after > before else seg <= mid)
        idx.append(_nearest_crossing(t, sn, lo + int(cross[0]), mid) if cross.size
                   else lo_b * block)
    return idx


NEAREST_CROSSING = True
"""Whether a normal-stress change whose half-way crossing falls in a gap is placed at the
sample nearer the crossing (:func:`_nearest_crossing`; ours)."""


def _nearest_crossing(t: Array, sn: Array, j: int, mid: float) -> int:
    """``j`` (the first sample past the half-way level ``mid``), or, where a gap of the record
    (as :func:`sampling_changes` has it: an interval over 10 times the median and the one
    before) lies between it and the sample before, whichever of the two is nearer the time
    the level crosses ``mid``, interpolated linearly across the gap (ours). Why: across a gap
    the first sample past the level can be seconds after the crossing (zoo 12014: a 6.3-s
    gap opening 2 ms after a ramp's half-way time, the change reported at the gap's end);
    elsewhere the first sample of the new level is the boundary, as for a velocity."""
    if not NEAREST_CROSSING or j < 2 or sn[j] == sn[j - 1]:
        return j
    dt = t[j] - t[j - 1]
    # the interval before first: the record's median interval (a pass over every sample) is
    # needed only where the gap stands out from it
    if not dt > 10.0 * float(t[j - 1] - t[j - 2]) or not dt > 10.0 * max(
            median(np.diff(t)), float(t[j - 1] - t[j - 2])):
        return j
    tc = t[j - 1] + (mid - sn[j - 1]) / (sn[j] - sn[j - 1]) * (t[j] - t[j - 1])
    return j - 1 if tc - t[j - 1] < t[j] - tc else j


BACK_BLOCKS = 50
"""Blocks of equal duration over which :func:`moves_backwards` weighs a record's motion."""
BACK_FACTOR = 10.0
"""A record moves backwards when its significant backward travel is at least this many times
its significant forward travel (:func:`moves_backwards`)."""


def moves_backwards(t: Array, values: Array, velocity: bool = False) -> bool:
    """Whether a record's load point plainly moves backwards as a whole (ours): its
    displacement (resets taken out, :func:`find_resets`; a ``velocity`` column, m/s,
    integrated over the times ``t``, s) is cut into :data:`BACK_BLOCKS` blocks of equal
    duration, and a block's change counts where it stands beyond 5 times the white noise of
    its two ends (:func:`.segmentation.noise_level`; so that the noise does not); it moves
    backwards when the backward travel so counted is at least :data:`BACK_FACTOR` times the
    forward travel. A lab whose displacement decreases as the load point advances (a
    transducer's sign convention) then reads forward, as the load programs of this package
    move (forward or held: :func:`.lab.parse_segments`); a forward record with long holds
    drifting back, or ending with a fast retraction, does not (an independent review: a
    sum of all increments flipped 70 of 178 forward records whose holds drift back)."""
    tt = np.asarray(t, float)
    v = np.asarray(values, float)
    if v.size < 3 or not tt[-1] > tt[0]:
        return False
    edges = np.searchsorted(tt, np.linspace(tt[0], tt[-1], BACK_BLOCKS + 1)[1:-1])
    ends = np.unique(np.concatenate([[0], edges, [v.size - 1]]))

    def travel(x: Array) -> tuple[float, float]:
        """Forward and backward travel of the blocks' changes beyond the ends' white noise."""
        d = np.diff(x[ends])
        big = np.abs(d) > 5.0 * np.sqrt(2.0) * noise_level(x)
        return float(d[big & (d > 0)].sum()), float(-d[big & (d < 0)].sum())

    if velocity:
        forward, backward = travel(trapezoid_displacement(tt, v))
    else:
        # the reset finder only where some block moves back (a re-zeroing is a jump back):
        # most records move forward throughout, and reading them need not pay for it
        forward, backward = travel(v)
        if backward > 0.0:
            forward, backward = travel(find_resets(tt, v)[0])
    return backward > 0.0 and backward >= BACK_FACTOR * forward


def trapezoid_displacement(t: Array, v: Array) -> Array:
    """The displacement (m, from 0) of a velocity ``v`` (m/s) sampled at the times ``t`` (s),
    integrated by trapezoids."""
    v = np.asarray(v, float)
    return np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
