"""Drive a record's fit with what the load point did (ours): ``--drive
measured``.

The idealised program (``--drive program``) changes the load velocity at a sample time, the
change time a hidden parameter: on a step whose elastic loading lasts a few samples the
fitted stiffness hangs on it (on the basalt-like record of ``tests/machine_zoo.py``,
3 -> 10 um/s, k = 3796, 5129 and 8526 /m for the change given at 68.5, 68.6 and 68.7 s; the
truth 7000 /m). The measured drive is the record's own load-point displacement, denoised:

1. **The program as a prior, its change times re-estimated** (:func:`estimate_change`): near
   each change the displacement is fitted by a continuous broken line ``c + v1 min(t - tau, 0)
   + v2 max(t - tau, 0)`` (least squares; ``tau`` continuous, not a sample time) over the
   samples within :data:`SPAN_SLIP` of load-point travel on either side (at most half of each
   segment; :data:`HOLD_SPAN` on the side of a hold). Its standard error is the Wald one of
   that fit, widened for correlated residuals by ``sqrt((1 + rho)/(1 - rho))`` (AR(1), lag-1
   autocorrelation ``rho``). The corner replaces the program's change time where its
   standard error is below the sampling interval at the change (``placed``); elsewhere the
   program's time stands and step 3 is skipped there (the displacement does not place that
   change better than the program does).
2. **The whole record's broken line** ``P(t)``: continuous, its corners at the estimated
   change times, slopes by least squares (the hinge basis ``c + v_0 t + sum_j dv_j max(t -
   tau_j, 0)``).
3. **What the servo did beyond the program**, within each change's span of step 1: the
   residual ``x - P`` smoothed by a cubic smoothing spline with its penalty chosen by
   generalised cross-validation (Craven & Wahba 1979;
   :func:`scipy.interpolate.make_smoothing_spline`), less its chord (the drive stays
   continuous): the transducer's white noise is removed, the servo's lag and overshoot
   kept where the data resolve them. Away from the changes the broken line holds: the
   displacement's slow wander there is not followed (on the shared sepiolite record,
   following it everywhere raised the rms residual from 1.67e-3 to 1.82e-3 and the CPU time
   from 1 s to 36 s: that wander is not seen by the friction as a spring would pass it).
4. **The drive** is ``P`` plus that smooth, as a piecewise-constant velocity between
   consecutive samples (and the estimated change times), held at 0 where the program holds
   and at least :data:`MIN_FRACTION` of the program's velocity where it slides (a hold is
   no slip; a smoothing wiggle is no reversal).

The forward model (:func:`.models.rsf_series`) runs on that program when the data carry a
drive (:class:`DrivenSeries`); the change times then follow from the displacement, not from
``--segments``, which only places the prior within its search span.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..program import Segment, VelocityProgram
from ..records.data import SeriesData
from ..validation import Array

__all__ = ["DRIVES", "SPAN_SLIP", "HOLD_SPAN", "MIN_FRACTION", "ChangeEstimate",
           "change_time_effect", "LoadPointDrive", "DrivenSeries", "estimate_change",
           "measured_drive",
           "measured_series", "check_drive", "drive_report",
           "load_program"]

DRIVES = ("program", "measured")
"""``--drive``: the idealised piecewise-constant program, or the measured load point."""

SPAN_SLIP = 10e-6
"""Load-point travel (m) on either side of a change used to place it (step 1)."""

HOLD_SPAN = 5.0
"""Time (s) on the side of a hold used to place a change into or out of it (step 1)."""

MIN_FRACTION = 1e-3
"""Smallest drive velocity where the program slides, as a fraction of the program's."""


def check_drive(drive: str) -> str:
    """``--drive``: one of :data:`DRIVES` (one line naming the option otherwise)."""
    if drive not in DRIVES:
        raise ValueError(f"--drive {drive!r} is not allowed: {' or '.join(DRIVES)}")
    return drive


@dataclass(frozen=True)
class ChangeEstimate:
    """A change of load velocity placed from the displacement (step 1): the given time and
    the estimate, s (the record's clock), its standard error, s, and the fitted velocities
    either side, m/s."""

    given: float
    t: float
    sigma: float
    v_before: float
    v_after: float
    placed: bool = True

    def to_dict(self) -> dict[str, Any]:
        return {"t_given": self.given, "t_change": self.t, "sigma_t_change": self.sigma,
                "v_before": self.v_before, "v_after": self.v_after, "placed": self.placed,
                "unit": "s, m/s"}


@dataclass(frozen=True)
class LoadPointDrive:
    """The denoised load point of a whole record (module docstring).

    Attributes
    ----------
    t : ndarray
        Knot times, s (the record's samples and the estimated change times).
    v : ndarray
        Load-point velocity from each knot to the next, m/s (one fewer than ``t``).
    changes : tuple of ChangeEstimate
    noise : float
        The transducer's white noise, m (robust, from the first differences of ``x - P``).
    """

    t: Array
    v: Array
    changes: tuple[ChangeEstimate, ...]
    noise: float

    def segments(self, t0: float, t1: float) -> tuple[Array, Array]:
        """``(durations, velocities)`` from ``t0`` to ``t1`` (s), as
        :meth:`SeriesData.segments` gives the program's."""
        inner = self.t[(self.t > t0) & (self.t < t1)]
        edges = np.concatenate([[t0], inner, [t1]])
        j = np.clip(np.searchsorted(self.t, edges[:-1], side="right") - 1, 0, self.v.size - 1)
        return np.diff(edges), self.v[j].copy()

    def displacement(self, t: Array) -> Array:
        """Load-point displacement (m) at ``t`` from the first knot."""
        x = np.concatenate([[0.0], np.cumsum(self.v * np.diff(self.t))])
        return np.interp(np.asarray(t, float), self.t, x)


@dataclass(frozen=True)
class DrivenSeries(SeriesData):
    """A time series whose forward model runs on a measured load point (``drive``); the
    program ``v_load`` still says where the changes and holds are."""

    drive: LoadPointDrive | None = None

    def window(self, i0: int, i1: int, source: str) -> DrivenSeries:
        """Samples ``[i0, i1)`` with the same drive."""
        sl = slice(i0, i1)
        return DrivenSeries(self.t[sl], self.v_load[sl], self.mu[sl], source=source,
                            drive=self.drive)


def _hinge_fit(t: Array, x: Array, tau: float) -> tuple[float, Array, Array]:
    """Least squares of ``c + v1 min(t - tau, 0) + v2 max(t - tau, 0)``: (rss, coef, resid)."""
    X = np.column_stack([np.ones_like(t), np.minimum(t - tau, 0.0), np.maximum(t - tau, 0.0)])
    coef = np.linalg.lstsq(X, x, rcond=None)[0]
    r = x - X @ coef
    return float(r @ r), coef, r


def estimate_change(t: Array, x: Array, given: float) -> ChangeEstimate:
    """Place one change from the displacement ``x`` (m) at times ``t`` (s) around it (step 1
    of the module docstring): the broken line's corner minimising the residual sum of
    squares over corners between the third sample and the third from last, refined between
    samples (bounded scalar search); the Wald standard error of the corner, widened for
    AR(1) residuals."""
    from scipy.optimize import minimize_scalar

    t, x = np.asarray(t, float), np.asarray(x, float)
    t_ref = float(t[0])
    tt = t - t_ref  # well-conditioned
    if t.size < 8:
        raise ValueError(f"the change at t = {given:g} s has fewer than 8 samples around it "
                         "to place it from the displacement")
    cand = tt[2:-2]
    rss = np.array([_hinge_fit(tt, x, c)[0] for c in cand])
    j = int(np.argmin(rss))
    lo, hi = cand[max(j - 1, 0)], cand[min(j + 1, cand.size - 1)]
    best = minimize_scalar(lambda c: _hinge_fit(tt, x, c)[0], bounds=(lo, hi),
                           method="bounded", options={"xatol": 1e-6 * max(hi - lo, 1e-9)})
    tau = float(best.x) if best.fun <= rss[j] else float(cand[j])
    s_rss, coef, r = _hinge_fit(tt, x, tau)
    v1, v2 = float(coef[1]), float(coef[2])
    # the Jacobian of (c, v1, v2, tau): d/dtau = -v1 [t < tau] - v2 [t > tau]
    J = np.column_stack([np.ones_like(tt), np.minimum(tt - tau, 0.0),
                         np.maximum(tt - tau, 0.0), np.where(tt < tau, -v1, -v2)])
    dof = max(t.size - 4, 1)
    s2 = s_rss / dof
    rho = float(np.corrcoef(r[1:], r[:-1])[0, 1]) if r.size > 3 and np.std(r) > 0 else 0.0
    rho = min(max(rho, 0.0), 0.99)
    try:
        cov = np.linalg.inv(J.T @ J) * s2 * (1.0 + rho) / (1.0 - rho)
        sigma = math.sqrt(max(float(cov[3, 3]), 0.0))
    except np.linalg.LinAlgError:
        sigma = math.nan
    return ChangeEstimate(float(given), tau + t_ref, sigma, v1, v2)


def _side(t: Array, i_lo: int, i_hi: int, v: float, at: float, before: bool) -> int:
    """The index bounding the local span on one side of a change (step 1)."""
    span = SPAN_SLIP / abs(v) if v != 0.0 else HOLD_SPAN
    if before:
        return max(i_lo, int(np.searchsorted(t, at - span, side="left")))
    return min(i_hi, int(np.searchsorted(t, at + span, side="right")))


def measured_drive(t: Array, x: Array, v_load: Array,
                   shift: dict[int, float] | None = None,
                   from_velocity: bool = False) -> LoadPointDrive:
    """The denoised load point of a record (module docstring).

    Parameters
    ----------
    t : ndarray
        Sample times, s.
    x : ndarray
        Measured load-point displacement, m (resets taken out).
    v_load : ndarray
        The program at each sample, m/s (piecewise constant: the prior, step 1).
    shift : dict, optional
        Hold change ``j``'s time at its estimate plus ``shift[j]`` s (for the drive's
        uncertainty: :func:`drive_sensitivity`).
    from_velocity : bool
        ``x`` is a velocity column integrated: each change's standard error is at least
        ``dt / sqrt(12)``, ``dt`` the sampling interval holding it (ours: a sampled velocity
        says only that the change lies in that interval, uniform there; the integral's
        corner is exact to rounding, and its Wald error, nanoseconds on a second new user's
        record sampled every 0.5 s, said otherwise).
    """
    from scipy.interpolate import make_smoothing_spline

    t, x, v_load = (np.asarray(a, float) for a in (t, x, v_load))
    ch = np.flatnonzero(np.diff(v_load) != 0.0) + 1
    bounds = [0, *ch.tolist(), t.size]
    changes: list[ChangeEstimate] = []
    spans: list[tuple[int, int]] = []
    for j, i in enumerate(ch.tolist()):
        a0, a1 = bounds[j], bounds[j + 2]  # the two segments around this change
        half0 = (bounds[j] + i) // 2
        half1 = (i + bounds[j + 2]) // 2
        lo = _side(t, max(half0, a0), i, float(v_load[i - 1]), float(t[i]), True)
        hi = _side(t, i, min(half1 + 1, a1), float(v_load[i]), float(t[i]), False)
        lo, hi = max(min(lo, i - 4), 0), min(max(hi, i + 4), t.size)  # >= 4 samples a side
        est = estimate_change(t[lo:hi], x[lo:hi], float(t[i]))
        if from_velocity:
            est = replace(est, sigma=max(est.sigma, float(t[i] - t[i - 1]) / math.sqrt(12.0)))
        # placed from the displacement only where that beats the program's own placement,
        # to within the sampling interval at the change (else the load point's wander,
        # not the change, sets the corner: on records_zoo's slide-hold-slide with 8 %
        # velocity wander at 1 Hz the corners were 0.7-1.7 s uncertain and up to 3.4 s off)
        placed = bool(est.sigma < float(t[i] - t[i - 1]))
        tc = (est.t if placed else est.given) + (shift or {}).get(j, 0.0)
        changes.append(ChangeEstimate(est.given, tc, est.sigma, est.v_before, est.v_after,
                                      placed))
        spans.append((lo, hi))
    taus = np.array([c.t for c in changes])
    t_ref = float(t[0])

    def hinge(s: Array) -> Array:
        return np.column_stack([np.ones_like(s), s - t_ref]
                               + [np.maximum(s - c, 0.0) for c in taus])

    coef = np.linalg.lstsq(hinge(t), x, rcond=None)[0]
    resid = x - hinge(t) @ coef
    # what the servo did beyond the broken line, near each change only (step 3): the
    # smooth of the residual, less its chord, so that the drive stays continuous and the
    # broken line's slopes hold away from the changes
    knots_list = [t[[0, -1]], taus]
    corr_t: list[Array] = []
    corr_x: list[Array] = []
    for (lo, hi), c in zip(spans, changes, strict=True):
        ts = t[lo:hi]
        if ts.size >= 5 and c.placed:
            sp = make_smoothing_spline(ts - t_ref, resid[lo:hi])  # penalty by GCV
            kt = np.unique(np.concatenate([ts, taus[(taus > ts[0]) & (taus < ts[-1])]]))
            c = sp(kt - t_ref)
            c = c - np.interp(kt, [kt[0], kt[-1]], [c[0], c[-1]])
            corr_t.append(kt)
            corr_x.append(c)
            knots_list.append(kt)
    knots = np.unique(np.concatenate(knots_list))
    xk = hinge(knots) @ coef
    for kt, c in zip(corr_t, corr_x, strict=True):
        m = (knots >= kt[0]) & (knots <= kt[-1])
        xk[m] += np.interp(knots[m], kt, c)
    v = np.diff(xk) / np.diff(knots)
    # the program at each knot interval (its start's sample, a change time moved to its
    # estimate): 0 in a hold, and at least MIN_FRACTION of the program where it slides
    prog = np.empty(knots.size - 1)
    for j in range(len(bounds) - 1):
        start = t[bounds[j]] if j == 0 else taus[j - 1]
        end = taus[j] if j < len(taus) else math.inf
        inside = (knots[:-1] >= start - 1e-12) & (knots[:-1] < end)
        prog[inside] = v_load[bounds[j]]
    v = np.where(prog == 0.0, 0.0, np.maximum(v, MIN_FRACTION * prog))
    d = np.diff(resid)
    noise = float(1.4826 * np.median(np.abs(d - np.median(d))) / math.sqrt(2.0)) \
        if d.size > 2 else math.nan
    return LoadPointDrive(knots, v, tuple(changes), noise)


def measured_series(data: SeriesData, record: Any,
                    shift: dict[int, float] | None = None) -> DrivenSeries:
    """``data`` (the record's program as a series) with the measured drive of ``record``
    (a laboratory record with a load-point displacement or velocity column)."""
    from ..records.detection import displacement, find_resets

    if record is None or (getattr(record, "load_point", None) is None
                          and getattr(record, "load_velocity", None) is None):
        raise ValueError(f"{data.source}: --drive measured needs a laboratory record with a "
                         "load-point displacement (or velocity) column; use --drive program")
    x, _ = find_resets(np.asarray(record.time, float), displacement(record))
    drive = measured_drive(data.t, np.asarray(x, float), data.v_load, shift,
                           from_velocity=getattr(record, "load_point", None) is None)
    return DrivenSeries(data.t, data.v_load, data.mu, data.sigma, data.source, drive=drive)


def drive_report(data: SeriesData) -> dict[str, Any]:
    """What ``fit.json`` says of a measured drive: each change's given and estimated time
    with its standard error, and the displacement's white noise."""
    d = getattr(data, "drive", None)
    if d is None:
        return {"kind": "program"}
    return {"kind": "measured", "changes": [c.to_dict() for c in d.changes],
            "displacement_noise": d.noise, "noise_unit": "m",
            "method": "the record's load-point displacement: the program's broken line with "
                      "its corners placed from the displacement, plus the residual smoothed by "
                      "a GCV smoothing spline (fit.loadpoint)"}


_PROGRAMS: dict[int, tuple[Any, VelocityProgram, Array, bool]] = {}
"""The load program of each data set a fit is evaluating (by ``id``, with a weak reference
that tells a reused ``id`` apart): a fit evaluates one window thousands of times, and a
measured drive has tens of segments, whose validation cost more than the integration."""


def load_program(data: SeriesData) -> tuple[VelocityProgram, Array, bool]:
    """``(program, sample times from the first, whether it holds)`` of ``data``'s load point:
    its piecewise-constant ``v_load`` (:meth:`SeriesData.segments`) or the measured drive's
    (``data.drive``, :mod:`.loadpoint`); built once per data set."""
    hit = _PROGRAMS.get(id(data))
    if hit is not None and hit[0]() is data:
        return hit[1], hit[2], hit[3]
    drive = getattr(data, "drive", None)  # the measured load point (.loadpoint), if any
    dur, vel = data.segments() if drive is None else drive.segments(float(data.t[0]),
                                                                     float(data.t[-1]))
    prog = VelocityProgram([Segment(float(v), float(t)) for v, t in zip(vel, dur, strict=True)])
    te = np.clip(data.t - data.t[0], 0.0, float(np.sum(dur)))
    if len(_PROGRAMS) >= 64:  # windows of past fits
        _PROGRAMS.clear()
    _PROGRAMS[id(data)] = (weakref.ref(data), prog, te, bool(np.any(vel <= 0.0)))
    return prog, te, bool(np.any(vel <= 0.0))


def change_time_effect(residuals: Any, d: SeriesData, J: Array) -> Array | None:
    """The fitted variables' standard errors from the measured drive's change times alone
    (ours): each change in the window, with its standard error ``sigma_c``
    (:func:`estimate_change`), moves the fit by ``-(J^T J)^-1 J^T dr``, ``dr`` the residuals'
    change when the drive moves by ``+-sigma_c`` in time (central difference, half of it):
    the delta method for an input known to its own error, independent of the friction noise,
    to be added to the noise covariance in quadrature (summed over the changes).

    ``residuals(data)`` gives the weighted residuals at the optimum on ``data``; ``d`` a
    window of a :class:`DrivenSeries`. ``None`` without a drive or a placed change in the
    window. The transducer noise moves ``k`` mainly through the change time: on the
    basalt-like records with white friction noise (tests/machine_zoo.py) this part of ``ln k``
    is 0.04-0.06 against 0.04 from the friction noise; without it ``k``'s interval held the
    truth in 13 of 20 records, with it in 17 of 20 (``benchmarks/bench_k_coverage``).
    """
    from dataclasses import replace

    drive = getattr(d, "drive", None)
    if drive is None or len(d) < 2:
        return None
    inside = [c for c in drive.changes if d.t[0] < c.t < d.t[-1]
              and math.isfinite(c.sigma) and c.sigma > 0]
    if not inside:
        return None
    bread = np.linalg.pinv(J.T @ J)
    var = np.zeros(J.shape[1])
    for c in inside:  # the drive moved as a whole: only the change near this window matters
        moved = [residuals(replace(d, drive=replace(drive, t=drive.t + s * c.sigma)))
                 for s in (1.0, -1.0)]
        var += (bread @ J.T @ (0.5 * (moved[0] - moved[1]))) ** 2
    return np.sqrt(var)
