"""The testing machine seen from a friction record (ours): the load-point displacement of a
piecewise-constant load program, the machine stiffness read off the elastic loading slope
after a velocity change (standard in velocity-step analysis), and what an earlier hold leaves
of its transient where a fitted window starts."""

from __future__ import annotations

import math

import numpy as np

from ..records.data import SeriesData
from ..validation import Array

__all__ = ["load_point_displacement", "loading_slope_stiffness", "hold_remnant"]


def load_point_displacement(data: SeriesData) -> Array:
    """Load-point displacement (m) at ``data.t``, from ``data.t[0]``: the integral of the
    piecewise-constant load program (:meth:`SeriesData.segments`)."""
    dur, vel = data.segments()
    edges = np.concatenate([[0.0], np.cumsum(dur)])
    x_edges = np.concatenate([[0.0], np.cumsum(dur * vel)])
    return np.interp(data.t - data.t[0], edges, x_edges)


def loading_slope_stiffness(data: SeriesData, fraction: float = 1.0 / 3.0) -> float:
    """Machine stiffness (1/m) from the elastic loading slope just after a velocity change.

    The first change of ``v_load`` to a sliding velocity ``v_after > 0`` is used (a hold's
    start is skipped: unloading at rest says nothing about the load point). Just after it the
    slider still moves at about ``v_before``, so ``dmu/dt = k (v_after - v_before)``, i.e.
    ``dmu/dx_lp = k (1 - v_before/v_after)`` against load-point displacement ``x_lp``. The
    slope is the least-squares line of ``mu`` against ``x_lp`` over the samples from the change
    until ``mu`` has covered ``fraction`` of its way from the level before the change (mean of
    the last 10 samples) to the extreme after it (the maximum for an increase, the minimum
    for a decrease); at least 5 samples. The slider accelerates during that stretch, so the
    estimate is low by a few per cent to tens of per cent (smaller ``fraction``: less bias,
    more noise); ``stiffness="fit"`` has no such bias.
    """
    v = data.v_load
    change = np.flatnonzero((np.diff(v) != 0.0) & (v[1:] > 0.0)) + 1
    if change.size == 0:
        raise ValueError(f"{data.source}: stiffness = 'slope' needs a change of load velocity "
                         "to a sliding velocity in the record: there is none")
    i0 = int(change[0])
    vb, va = float(v[i0 - 1]), float(v[i0])
    end = int(np.flatnonzero(np.diff(v[i0:]) != 0.0)[0]) + i0 + 1 \
        if np.any(np.diff(v[i0:]) != 0.0) else len(v)
    x = load_point_displacement(data)
    mu = data.mu
    base = float(np.mean(mu[max(0, i0 - 10):i0])) if i0 > 0 else float(mu[0])
    after = mu[i0:end]
    ext = float(after.max() if va > vb else after.min())
    far = np.abs(after - base) >= fraction * abs(ext - base)
    n = max(5, int(np.argmax(far)) + 1 if np.any(far) else len(after))
    n = min(n, len(after))
    if n < 3:
        raise ValueError(f"{data.source}: stiffness = 'slope' needs at least 3 samples after "
                         f"the change at t = {data.t[i0]:g} s")
    slope = float(np.polyfit(x[i0:i0 + n], mu[i0:i0 + n], 1)[0])
    k = slope / (1.0 - vb / va)
    if not (math.isfinite(k) and k > 0.0):
        raise ValueError(f"{data.source}: stiffness = 'slope' found a loading slope of "
                         f"{slope:.3g} /m after the change at t = {data.t[i0]:g} s ({vb:g} -> "
                         f"{va:g} m/s): not a positive stiffness; use stiffness = 'fit' or a "
                         "number (1/m)")
    return k


def hold_remnant(data: SeriesData, i_start: int, b: float, dc: float
                 ) -> tuple[float, float, float]:
    """How far sample ``i_start`` still is from steady sliding after the last hold before it
    (ours): ``(remnant, hold, slip)``.

    A window's fit starts in steady sliding (:func:`.models.rsf_series`); in a slide-hold-slide
    record the sliding before a hold is the reslide of the hold before, whose peak decays over
    a few ``Dc`` of slip. ``remnant`` is that peak's excess on a stiff machine with the ageing
    law, ``b ln(1 + t_h V/Dc)`` (``V`` the velocity before that hold), decayed as
    ``exp(-s/Dc)`` over the load-point slip ``s`` from the reslide to ``i_start``: an order of
    magnitude, low on a soft machine, whose transient decays more slowly (on the synthetic
    record of ``tests/fit/test_shs.py`` with k = 3000 /m: 1.8e-3 for a true 4.1e-3).
    ``(0, 0, inf)`` when no hold comes before ``i_start`` or the record is not sliding there.
    """
    v = data.v_load[: i_start + 1]
    zero = np.flatnonzero(v == 0.0)
    if zero.size == 0 or v[-1] == 0.0:
        return 0.0, 0.0, math.inf
    j1 = int(zero[-1]) + 1  # the reslide's first sample
    moving = np.flatnonzero(v[:j1] != 0.0)
    j0 = int(moving[-1]) + 1 if moving.size else 0  # the hold's first sample
    hold = float(data.t[j1] - data.t[j0])
    v_before = abs(float(v[j0 - 1])) if j0 > 0 else abs(float(v[-1]))
    x = load_point_displacement(data)
    slip = abs(float(x[i_start] - x[j1]))
    return b * math.log1p(hold * v_before / dc) * math.exp(-slip / dc), hold, slip
