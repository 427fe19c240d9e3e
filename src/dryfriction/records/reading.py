"""Where a velocity change happens, read on a servo's velocity column (ours).

A record that gives the load point's velocity as the servo reads it (no displacement
transducer) has every change as a step of that reading, within one sampling interval: the
load point's own wander (the servo's position error, a machine oscillation) changes the
reading smoothly, over a second and more, while the reading's noise is white. Integrated to a
displacement, as the detector searches it, the white noise becomes a random walk and the step
a kink, which the hinge under a single Ornstein-Uhlenbeck wander (:mod:`.placement`) places
seconds off where the step is small (ratio 1.3: zoo records 14004, 16009, 19044, 3.6-4.9 s).

Here the step is placed on the reading itself (ours). At each candidate sample ``i`` (the
first reading of the new velocity) within :data:`SEARCH` s of the displacement's place, the
jump ``J_i`` is the difference at ``t_i`` of two lines, fitted to the readings of
:data:`HALF` s after and before it (a wander correlated over a second is nearly a line over
half of one; white noise averages out over the samples). The candidates' own ``J`` is the
null: the step is the largest ``J`` (in the change's direction) where it stands
:data:`READING_Z` robust scales of the candidates' ``J`` (1.4826 times their median
absolute value: ``J`` is 0 but for the noise where the reading has no step) and measures
between half and twice the change between the stretches' velocities; elsewhere the reading
does not show the change as a step, and it stays where the displacement placed it. It is
then reported at the mode of the profile likelihood of one line with a step on the readings
within ``2 HALF`` of it (candidates within ``HALF``; the residual variance as the scale),
with that profile's interval (as the hinge's, :func:`.placement.profile_interval`, widened
:data:`.placement.WIDEN` times).

Where the readings are too slow for such lines (about 1 Hz: :data:`READING_SLOW`),
``J_i`` is the difference of the means of the :data:`SLOW_MIN` readings after and before the
candidate, judged the same way.

``READING_Z`` (5) was chosen on the zoo's velocity records of the used ranges (1537 changes
with candidates, the search centred up to 5 s off the truth at random): at 5, 1439 changes
placed, none off the tolerance (the largest ``J`` off it stood at 4.2 scales); 6, set before
measuring, leaves zoo 14004 and 19044 to the displacement (5.99 and 5.80). The fresh records
that checked it: docs/performance.md.
"""

from __future__ import annotations

import numpy as np

from ..validation import Array
from .placement import WIDEN, Placement, profile_interval, profile_weights
from .segmentation import step_gains

__all__ = ["READING_Z", "reading_step"]

SEARCH = 10.0
"""Candidates lie within this many s of the change as the displacement placed it (ours: the
hinge's misplacements on the zoo's velocity records were up to 5 s)."""
HALF = 0.5
"""Each side's line is fitted on the readings within this many s of the candidate, at least
:data:`HALF_MIN` of them (ours: the servo's wander is a velocity correlated over about a
second, nearly a line over half of one)."""
HALF_MIN = 5
SIDE_MOST = 2.0
"""A candidate whose readings on either side span more than this many s is none (ours): a
line over seconds takes up the wander's bends, and where the sampling slows (a rate change at
the step: zoo 5179, 1 Hz before a down-step at 10 Hz after) such a candidate's ``J``, 4.6 s
before the change, stood above the change's own."""
READING_Z = 5.0
"""The step must stand this many robust scales of the same statistic over the candidates, and
measure between half and twice the change between the stretches' velocities, or the change
is left where the displacement placed it (ours; chosen on the used zoo records: the module
docstring)."""


READING_SLOW = True
"""Where the readings are too few for lines (fewer than 8 candidates with :data:`HALF_MIN` of
them within :data:`SIDE_MOST` s each side: a reading at about 1 Hz), each side is the
mean of the :data:`SLOW_MIN` readings next to the candidate, judged by the same threshold
(ours): the step is still within one sample, and the candidates' own jumps are the null, the
wander over those readings included. Zoo 22249 (a ratio-30 stop at 1 Hz, the step from 0.16
to 0 um/s between two readings) was left to the displacement, two samples early. Slower
readings are not placed this way (fewer than 20 within the search, ``4 HALF_MIN``: a review
measured none placed at 0.8 Hz and below, 11 of 20 at 0.9 Hz, 20 of 20 at 1-1.5 Hz, 17 of 20
at 2 Hz, where the lines are tried first); their changes stay where the displacement put
them."""
SLOW_MIN = 2


def _local_means(y: Array, k: int) -> Array:
    """For each sample ``i``: the mean of ``y[i:i + k]`` less that of ``y[i - k:i]`` (NaN where
    either side has fewer than ``k`` samples)."""
    n = y.size
    out = np.full(n, np.nan)
    if n < 2 * k:
        return out
    sy = np.concatenate([np.zeros(1), np.cumsum(y)])
    i = np.arange(k, n - k + 1)
    out[i] = (sy[i + k] - 2.0 * sy[i] + sy[i - k]) / k
    return out


def _local_lines(t: Array, y: Array, half: float, least: int) -> tuple[Array, Array]:
    """For each sample ``i``: the jump at ``t[i]`` between a line fitted to ``y`` on the
    samples within ``half`` s before it and one on those within ``half`` s from it on (each at
    least ``least`` samples, evaluated at ``t[i]``), and the longer of the two sides' spans,
    s; NaN and inf where a side has too few samples."""
    n = t.size
    out, span = np.full(n, np.nan), np.full(n, np.inf)
    i = np.arange(least, n - least + 1)
    if i.size == 0:
        return out, span
    tt = t - t[0]
    p = np.minimum(np.searchsorted(tt, tt[i] - half), i - least)
    q = np.maximum(np.searchsorted(tt, tt[i] + half), i + least)  # <= n: i <= n - least
    z = np.zeros(1)
    s1 = np.arange(n + 1, dtype=float)
    st = np.concatenate([z, np.cumsum(tt)])
    sy = np.concatenate([z, np.cumsum(y)])
    stt = np.concatenate([z, np.cumsum(tt * tt)])
    sty = np.concatenate([z, np.cumsum(tt * y)])

    def at(a: Array, b: Array) -> Array:  # the line on samples a:b, at t[i]
        k = s1[b] - s1[a]
        bt, by = (st[b] - st[a]) / k, (sy[b] - sy[a]) / k
        sxx = (stt[b] - stt[a]) / k - bt * bt
        sxy = (sty[b] - sty[a]) / k - bt * by
        with np.errstate(divide="ignore", invalid="ignore"):
            slope = np.where(sxx > 0, sxy / sxx, 0.0)
        return by + slope * (tt[i] - bt)

    out[i] = at(i, q) - at(p, i)
    span[i] = np.maximum(tt[q - 1] - tt[i], tt[i - 1] - tt[p])
    return out, span


def reading_step(t: Array, v: Array, guess: int, lo: int, hi: int, v1: float, v2: float,
                 ) -> Placement | None:
    """A change placed on the velocity reading (module docstring), or None where the reading
    does not show it as a step (:data:`READING_Z`).

    Parameters
    ----------
    t : Array
        Times, s (record time), increasing.
    v : Array
        The servo's velocity reading, m/s.
    guess : int
        The change's sample as placed so far (first sample of the new velocity).
    lo, hi : int
        The neighbouring changes' samples: the window does not pass them.
    v1, v2 : float
        The velocities before and after the change, m/s.

    Returns
    -------
    Placement or None
        Its 95 % interval from the step's profile likelihood on the readings about it.
    """
    t = np.asarray(t, float)
    dv = float(v2 - v1)
    if not dv or hi - lo < 4 * HALF_MIN:
        return None
    tg = float(t[guess])
    a = max(lo, int(np.searchsorted(t, tg - SEARCH - 2 * HALF)))
    b = min(hi, int(np.searchsorted(t, tg + SEARCH + 2 * HALF, "right")))
    tt = t[a:b]
    y = np.asarray(v, float)[a:b] * (np.sign(dv) / abs(dv))  # the step +1
    if tt.size < 4 * HALF_MIN:
        return None
    jump, span = _local_lines(tt, y, HALF, HALF_MIN)
    cand = np.flatnonzero(np.isfinite(jump) & (np.abs(tt - tg) <= SEARCH)
                          & (span <= SIDE_MOST))
    slow = cand.size < 8 and READING_SLOW
    if slow:  # too few readings for lines: the means of the SLOW_MIN next to it each side
        jump = _local_means(y, SLOW_MIN)
        cand = np.flatnonzero(np.isfinite(jump) & (np.abs(tt - tg) <= SEARCH))
    if cand.size < 8:
        return None
    # the null: J is the difference of two lines at one point, 0 but for the noise where
    # the reading has no step, so its robust scale about 0; at least the reading's quantum's
    # (white, q**2 / 12, through two lines of HALF_MIN readings: var J ~ 8 / HALF_MIN of a
    # reading's), or a reading that holds one level (a median |J| of 0) has no scale; the
    # same floor for the slow means (there var J is 2 / SLOW_MIN = 1 reading's: the floor
    # is 1.3 times that, on the safe side)
    jc = jump[cand]
    d = np.abs(np.diff(y))
    quantum = float(d[d > 0].min()) if (d > 0).any() else 0.0
    scale = max(1.4826 * float(np.median(np.abs(jc))),
                quantum * np.sqrt(8.0 / HALF_MIN / 12.0))
    best = int(cand[np.argmax(jc)])
    if not (0.5 <= jump[best] <= 2.0 and jump[best] >= READING_Z * max(scale, 1e-12)):
        return None
    # the interval: the step's profile on the readings within 2 HALF of it (a line and a
    # step; candidates within HALF, HALF_MIN samples at least, each side)
    tb = float(tt[best])
    if slow:  # 2 SLOW_MIN readings each side, candidates the best and its neighbours
        p, q = max(0, best - 2 * SLOW_MIN), min(tt.size, best + 2 * SLOW_MIN)
        c0, c1 = max(p + 1, best - 1), min(q - 1, best + 2)
    else:
        p = max(0, min(int(np.searchsorted(tt, tb - 2 * HALF)), best - 2 * HALF_MIN))
        q = min(tt.size, max(int(np.searchsorted(tt, tb + 2 * HALF)), best + 2 * HALF_MIN))
        c0 = max(p + 1, min(int(np.searchsorted(tt, tb - HALF)), best - HALF_MIN))
        c1 = min(q - 1, max(int(np.searchsorted(tt, tb + HALF, "right")), best + HALF_MIN + 1))
    ts, ys = tt[p:q], y[p:q]
    n = ts.size
    ks = np.arange(c0, c1) - p
    r, rs, norm = step_gains(ts, ys, ks)
    with np.errstate(divide="ignore", invalid="ignore"):
        gain = np.where((norm > 1e-9 * n) & (rs > 0), rs * rs / norm, -np.inf)
    if not np.isfinite(gain).any():
        return None
    j = int(np.argmax(gain))  # the reported sample: the profile's mode
    s2 = (float(r @ r) - float(gain[j])) / max(n - 3, 1)
    at = a + p + int(ks[j])
    times = ts[ks]
    left, right = float(ts[ks[0] - 1]), float(ts[min(ks[-1] + 1, n - 1)])
    s2 = s2 if s2 > 0 else 1e-12
    lo_t, hi_t, edge = profile_interval(times, gain, s2, left, right)
    cells, weights = profile_weights(times, gain, s2, left, right)
    # as the hinge's (.placement.change_profile): WIDEN times as far each side
    ta = float(t[at])
    lo_t, hi_t = ta - WIDEN * (ta - lo_t), ta + WIDEN * (hi_t - ta)
    return Placement(at, lo_t, hi_t, edge, cells, weights, tg)
