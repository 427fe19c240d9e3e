"""The machine stiffness from a record's elastic loading segments ("one
machine"; ours): the reload after each hold, and the initial loading where the record starts
from rest, read as the slope of friction against load-point displacement while the slider is
still stuck, then combined with the steps' free fits (:func:`machine_stiffness_record`).

While the slider is stuck (slip velocity ``V << V_lp``) the spring alone is loaded:
``dmu/dx_lp = k (1 - V/V_lp)`` (the force balance ``mu = k (x_lp - x)`` differentiated in
load-point displacement). A segment is a loading when friction rises after its start by
more than :data:`RISE_NOISE` times its noise to a peak in the segment's first half (the
reload's overshoot, or the end of the initial loading), more than :data:`STEEPER` times as
steeply as the segment's second half does (a slip-dependent trend is no loading). The slope
is the least-squares line of ``mu`` against ``x_lp`` over the first :data:`FRACTION` of that
rise (at least :data:`MIN_SAMPLES` samples), its standard error that of AR(1) noise,
``sigma sqrt((1 + rho)/((1 - rho) S_xx))``, with ``sigma`` and the lag-1 autocorrelation
``rho`` read from the segment's second half about its line (the steady sliding after the
peak). The slider creeps during the reload, so the slope is low by the mean ``V/V_lp`` over
that stretch: about 1.5 % on the synthetic slide-hold-slide records of
``tests/fit/test_elastic.py`` (k = 3000 /m, a reload rise of 0.03-0.04). An unloading (the
load point moving back) would do as well; the records read here do not run backwards
(``v_load >= 0``), so none is used.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..records.data import SeriesData
from .identify import record_stiffness
from .machine import load_point_displacement

__all__ = ["RISE_NOISE", "FRACTION", "MIN_SAMPLES", "STEEPER", "loading_segments",
           "machine_stiffness_record"]

RISE_NOISE = 20.0
"""Smallest rise of friction over a loading, in units of the noise, for its slope to count."""

FRACTION = 0.5
"""Part of the rise (from the start to the peak) over which the slope is read."""

MIN_SAMPLES = 6
"""Fewest samples in the stretch a slope is read from."""

STEEPER = 10.0
"""How many times steeper than the segment's steady second half (against load-point
displacement) a loading must be: a slip-dependent trend rises too, but slowly."""


def _noise(mu: np.ndarray) -> float:
    d = np.diff(mu)
    return float(1.4826 * np.median(np.abs(d - np.median(d))) / math.sqrt(2.0)) \
        if d.size > 2 else math.nan


def _slope(x: np.ndarray, mu: np.ndarray, z: float, calm: np.ndarray
           ) -> tuple[float, float, float] | None:
    """(slope, lo, hi) of ``mu`` against ``x`` with its 95 % interval, the noise's standard
    deviation and lag-1 autocorrelation ``rho`` read from ``calm`` (the segment's steady
    part about its line: a stretch of twenty samples says little of its own ``rho``), the
    residuals' own where they are larger."""
    if x.size < MIN_SAMPLES or np.ptp(x) <= 0.0:
        return None
    X = np.column_stack([np.ones_like(x), x - x[0]])
    coef, *_ = np.linalg.lstsq(X, mu, rcond=None)
    r = mu - X @ coef
    s2 = float(r @ r) / max(x.size - 2, 1)
    rho = 0.0
    if calm.size > 3 and np.std(calm) > 0:
        rho = float(np.corrcoef(calm[1:], calm[:-1])[0, 1])
        s2 = max(s2, float(calm @ calm) / (calm.size - 2))
    rho = min(max(rho, 0.0), 0.99)
    sxx = float(np.sum((x - x.mean()) ** 2))
    se = math.sqrt(s2 / sxx * (1.0 + rho) / (1.0 - rho))
    k = float(coef[1])
    return k, k - z * se, k + z * se


def loading_segments(data: SeriesData, z: float = 1.96) -> list[dict[str, Any]]:
    """The elastic loadings of a record (module docstring): one dict per loading with
    ``kind`` ("reload" after a hold, "initial"), ``t_start`` (s), the slope ``stiffness``
    and its 95 % interval ``stiffness_lo``/``_hi`` (1/m), ``rise`` (friction), ``n``
    (samples used). The load-point displacement is the measured drive's where ``data``
    carries one (:mod:`.loadpoint`), else the program's."""
    drive = getattr(data, "drive", None)
    x = drive.displacement(data.t) if drive is not None else load_point_displacement(data)
    v = data.v_load
    starts = [0] + [int(i) + 1 for i in np.flatnonzero((v[:-1] == 0.0) & (v[1:] > 0.0))]
    ends = np.flatnonzero(np.diff(v) != 0.0) + 1
    mu = np.asarray(data.mu, float)
    noise = _noise(mu)
    out: list[dict[str, Any]] = []
    for i0 in starts:
        later = ends[ends > i0]
        i1 = int(later[0]) if later.size else len(v)
        seg = mu[i0:i1]
        if seg.size < 3 * MIN_SAMPLES or not math.isfinite(noise):
            continue
        m = 5  # a running mean of a few samples finds the peak through the noise
        sm = np.convolve(seg, np.ones(m) / m, mode="valid")
        j = int(np.argmax(sm)) + m // 2
        base = float(np.mean(seg[:3]))
        rise = float(sm[j - m // 2]) - base
        if rise < RISE_NOISE * noise or j < MIN_SAMPLES or j > seg.size // 2:
            continue
        n = int(np.argmax(seg[: j + 1] - base >= FRACTION * rise))
        n = max(n, MIN_SAMPLES)
        tail = slice(seg.size // 2, seg.size)
        tt = data.t[i0:i1][tail]
        calm = seg[tail] - np.polyval(np.polyfit(tt - tt[0], seg[tail], 1), tt - tt[0])
        est = _slope(x[i0:i0 + n], seg[:n], z, calm)
        # a loading is far steeper than the steady sliding after it (a trend is not one)
        xs = x[i0:i1][tail]
        steady = abs(float(np.polyfit(xs - xs[0], seg[tail], 1)[0])) if np.ptp(xs) > 0 \
            else math.inf
        if est is None or not est[0] > STEEPER * steady:
            continue
        k, lo, hi = est
        out.append({"kind": "initial" if i0 == 0 else "reload",
                    "t_start": float(data.t[i0]), "stiffness": k,
                    "stiffness_lo": max(lo, 1e-300), "stiffness_hi": hi, "rise": rise,
                    "n": n, "unit": "1/m"})
    return out


def machine_stiffness_record(rows: list[dict[str, Any]], data: SeriesData | None
                             ) -> dict[str, Any] | None:
    """The record's one stiffness from the steps' free fits (``rows``) and the elastic
    loadings of ``data`` together (:func:`.identify.record_stiffness`: inverse-variance in
    ``ln k``, the one that disagrees with the others flagged ``k_inconsistent`` and left
    out), with ``loadings`` (each loading's estimate and whether it was kept) added; the
    steps' ``k_inconsistent`` flags as :func:`.identify.record_stiffness` sets them."""
    loads = loading_segments(data) if data is not None else []
    pseudo = [{**ld, "flags": "", "notes": []} for ld in loads]
    rec = record_stiffness([*rows, *pseudo])
    if rec is None:
        return None
    n = len(rows)
    rec["loadings"] = [{**ld, "used": (n + j) in rec["steps"],
                        "k_inconsistent": "k_inconsistent" in p["flags"]}
                       for j, (ld, p) in enumerate(zip(loads, pseudo, strict=True))]
    rec["steps"] = [i for i in rec["steps"] if i < n]
    if loads:
        rec["method"] += "; with the slopes of the record's elastic loadings (fit.elastic)"
    return rec
