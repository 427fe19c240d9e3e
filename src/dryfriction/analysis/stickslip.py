"""Stick-slip of the spring-pulled trap ensemble: classification, the linear check, the
bifurcation (docs/model.md §6; every definition here is ours unless an equation is cited).

Reduced units throughout: lengths ``a0``, times ``t0``, velocities ``a0/t0``, forces ``F_el``
(reported forces are friction units ``mu_el F/F_el``, like
:class:`~dryfriction.ensemble.driving.SimulationResult`), stiffness ``F_el/a0``, mass
``F_el t0^2/a0``, damping ``F_el t0/a0``.

Reading a run (:func:`analyse`)
-------------------------------
The signal is the *spring force* ``K (X_pull - X)`` (what a machine's load cell reads; in the
quasi-static limit it equals the friction). After discarding a transient, a **slip event** is a
drop of that force between a confirmed peak and the next confirmed trough, found by a zig-zag
with hysteresis: a maximum is confirmed once the force has fallen ``h`` below it, a minimum once
it has risen ``h`` above it, with

    h = max(floor, rel_threshold * (max - min of the force in the window)).

The relative part makes the count robust to the inertial ringing after a slip (oscillations
smaller than ``rel_threshold`` of the stick-slip amplitude never confirm an extremum); the
``floor`` (default: three times the force step of one trap death, ``f_c r_d^2/(H0 n)`` for
``n`` traps per ``a0``) keeps the granular noise of a finite ensemble from counting as events.

* **amplitude**: mean force drop per event (peak minus the following trough); ``range`` is
  the largest minus the smallest force of the window.
* **period**: mean time between successive confirmed peaks.
* **slip per event**: slider displacement from the peak to the following trough.
* **stick time**: time per period with slider velocity below ``stick_fraction * u``
  (``u`` the load-point velocity), i.e. ``stick fraction * period``.
* **class**: ``steady`` (0) if ``range < floor``; else ``undetermined`` (-1) with fewer than
  three events; ``transient`` (3) if the drops trend (least-squares slope of ``ln drop`` over
  the window) by more than 30 %; ``periodic`` (1) if the coefficients of variation of the
  periods and of the drops are both below ``cv_periodic`` (0.1) and the slider sticks at some
  time; ``oscillation`` (4) if periodic but the slider never sticks (a finite-amplitude
  oscillation of an inertial slider, not stick-slip); ``irregular`` (2) otherwise.

Linear check (:func:`linear_check`)
-----------------------------------
From the steady population at ``u`` (``Initial("steady")``) with the slider started at
``(1 + kick) u``, the deviation ``v - u`` of an inertial, damped slider is fitted (least
squares) by ``A e^{sigma t} cos(omega t + phi) + c`` over the window where the linear forward
branch holds (``|v - u| < u/2``, stability.py's module doc) and the signal is above the granular
floor. ``sigma + i omega`` is compared with :func:`dryfriction.theory.stability.rightmost_root`, an
independent route (the characteristic equation of the continuum response ``Z``).

Bifurcation (:func:`bifurcation_scan`)
--------------------------------------
Continuation in ``K``: one ensemble is pulled at ``u`` with a list of stiffnesses taken down
then back up; each step starts from the end of the previous one (population, slider velocity
and spring force kept, :func:`dryfriction.ensemble.driving.continue_spring`) and is analysed after
its own transient. A hysteresis loop (stick-slip on the way up at stiffnesses where the way down
was steady) means a subcritical bifurcation (bistability).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..ensemble.driving import Output, SimulationResult, SpringDrive, continue_spring, simulate
from ..ensemble.population import Ensemble, Initial, Track, TrapModel
from ..io.protocol import pulling_velocity, spring_point
from ..program import Segment, VelocityProgram
from ..theory.direct import junction_strength
from ..theory.linear_stability import critical_stiffness, linear_response
from ..theory.model import TRAP_PARAMETERS, TRAPS_PER_A0_COARSE
from ..theory.stability import rightmost_root, steady_response
from ..validation import Array, check_scalar

__all__ = [
    "CLASSES",
    "SWEEP_VARIABLES",
    "StickSlipStats",
    "analyse",
    "granular_floor",
    "stick_slip_summary",
    "fit_growth",
    "linear_check",
    "bifurcation_scan",
    "phase_axes",
    "critical_line",
]


CLASSES: dict[int, str] = {
    -1: "undetermined",
    0: "steady",
    1: "periodic",
    2: "irregular",
    3: "transient",
    4: "oscillation",
}
"""Class codes (a sweep stores numbers) and their names."""

_MU = "1"  # friction mu_el F/F_el: a friction coefficient
SWEEP_VARIABLES: dict[str, dict[str, Any]] = {
    "class": {"long_name": "stick-slip class", "units": "1",
              "flag_values": list(CLASSES), "flag_meanings": " ".join(CLASSES.values())},
    "amplitude": {"long_name": "mean friction drop per slip event", "units": _MU},
    "range": {"long_name": "friction range (max - min) after the transient", "units": _MU},
    "period": {"long_name": "mean time between slip events", "units": "t0"},
    "period_cv": {"long_name": "coefficient of variation of the periods", "units": "1"},
    "amplitude_cv": {"long_name": "coefficient of variation of the drops", "units": "1"},
    "slip_per_event": {"long_name": "mean slip per event", "units": "a0"},
    "stick_time": {"long_name": "time per period with the slider stuck", "units": "t0"},
    "stick_fraction": {"long_name": "fraction of the time with the slider stuck", "units": "1"},
    "events": {"long_name": "number of slip events", "units": "1"},
    "mean_force": {"long_name": "time-averaged friction", "units": _MU},
    "threshold": {"long_name": "smallest friction drop counted as an event", "units": _MU},
    "u": {"long_name": "pulling velocity", "units": "a0/t0"},
    "stiffness": {"long_name": "spring stiffness", "units": "F_el/a0"},
}
"""CF attributes of :func:`stick_slip_summary`'s results in ``sweep.nc``
(:mod:`dryfriction.sweeps.cf`)."""


@dataclass(frozen=True)
class StickSlipStats:
    """What :func:`analyse` measures (units: friction ``mu_el F/F_el``, ``t0``, ``a0``).

    NaN where a quantity needs events and there are none (period, slip per event, ...).
    """

    code: int
    amplitude: float
    range: float
    period: float
    period_cv: float
    amplitude_cv: float
    slip_per_event: float
    stick_time: float
    stick_fraction: float
    events: int
    mean_force: float
    threshold: float

    @property
    def kind(self) -> str:
        """Class name: steady, periodic, irregular, transient or undetermined."""
        return CLASSES[self.code]

    def to_dict(self) -> dict[str, float]:
        """All fields as floats (``code`` as ``class``), for a sweep's Dataset."""
        d = {k: float(v) for k, v in asdict(self).items()}
        d["class"] = d.pop("code")
        return d


def _zigzag(y: Array, h: float) -> tuple[list[int], list[int]]:
    """Indices of confirmed peaks and troughs of ``y`` with hysteresis ``h`` (module doc).

    One sequential pass over the samples (not over traps); peaks and troughs alternate.
    """
    peaks: list[int] = []
    troughs: list[int] = []
    hi_i = lo_i = 0
    mode = 0  # 0: undecided, 1: rising (looking for a peak), -1: falling (for a trough)
    for i in range(1, y.size):
        yi = y[i]
        if mode == 0:
            if yi > y[hi_i]:
                hi_i = i
            if yi < y[lo_i]:
                lo_i = i
            if y[hi_i] - yi >= h:
                peaks.append(hi_i)
                mode, lo_i = -1, i
            elif yi - y[lo_i] >= h:
                troughs.append(lo_i)
                mode, hi_i = 1, i
        elif mode == 1:
            if yi > y[hi_i]:
                hi_i = i
            elif y[hi_i] - yi >= h:
                peaks.append(hi_i)
                mode, lo_i = -1, i
        else:
            if yi < y[lo_i]:
                lo_i = i
            elif yi - y[lo_i] >= h:
                troughs.append(lo_i)
                mode, hi_i = 1, i
    return peaks, troughs


def analyse(
    t: ArrayLike,
    x: ArrayLike,
    v: ArrayLike,
    load: ArrayLike,
    *,
    u: float,
    t_start: float | None = None,
    floor: float = 1e-3,
    rel_threshold: float = 0.25,
    stick_fraction: float = 0.5,
    cv_periodic: float = 0.1,
) -> StickSlipStats:
    """Classify a spring-slider time series and measure its stick-slip (module doc).

    Parameters
    ----------
    t, x, v : array_like
        Time (``t0``), slider position (``a0``), slider velocity (``a0/t0``).
    load : array_like
        Spring force (friction units ``mu_el F/F_el``).
    u : float
        Load-point velocity, ``a0/t0``, ``> 0``.
    t_start : float, optional
        Samples before it are a transient and ignored (default: keep all).
    floor : float
        Smallest force drop that counts, friction units, ``> 0``; a window whose force range
        is below it is ``steady``.
    rel_threshold : float
        Hysteresis of the zig-zag as a fraction of the force range, ``0 < . < 1``.
    stick_fraction : float
        The slider sticks while ``v < stick_fraction * u``.
    cv_periodic : float
        Largest coefficient of variation of periods and drops of a ``periodic`` run.

    Returns
    -------
    StickSlipStats
    """
    u = check_scalar("u", u, 0.0, lo_open=True)
    floor = check_scalar("floor", floor, 0.0, lo_open=True)
    rel_threshold = check_scalar("rel_threshold", rel_threshold, 0.0, 1.0, lo_open=True,
                                 hi_open=True)
    t, x, v, y = (np.asarray(a, float).ravel() for a in (t, x, v, load))
    if not (t.size == x.size == v.size == y.size):
        raise ValueError("t, x, v and load must have the same length")
    if t_start is not None:
        keep = t >= t_start
        t, x, v, y = t[keep], x[keep], v[keep], y[keep]
    if t.size < 3:
        raise ValueError(f"only {t.size} samples after the transient: at least 3 are needed")
    span = float(t[-1] - t[0])
    rng = float(y.max() - y.min())
    mean_force = float(np.trapezoid(y, t) / span) if span > 0 else float(y.mean())
    slow = v < stick_fraction * u
    # time-weighted fraction of the window spent sticking (each sample stands for the step
    # that ends at it)
    dt = np.diff(t)
    stick_frac = float(np.sum(dt[slow[1:]]) / span) if span > 0 else 0.0
    h = max(floor, rel_threshold * rng)
    nan = math.nan
    if rng < floor:
        return StickSlipStats(0, 0.0, rng, nan, nan, nan, nan, nan, stick_frac, 0, mean_force, h)
    peaks, troughs = _zigzag(y, h)
    tr = np.asarray(troughs, int)
    nxt = np.searchsorted(tr, np.asarray(peaks, int), side="right")
    pairs = [(p, int(tr[j])) for p, j in zip(peaks, nxt, strict=True) if j < tr.size]
    drops = np.array([y[p] - y[q] for p, q in pairs])
    slips = np.array([x[q] - x[p] for p, q in pairs])
    periods = np.diff(t[np.asarray(peaks, int)]) if len(peaks) > 1 else np.array([])
    n = len(pairs)
    amp = float(drops.mean()) if n else nan
    per = float(periods.mean()) if periods.size else nan
    per_cv = float(periods.std() / per) if periods.size > 1 else nan
    amp_cv = float(drops.std() / amp) if n > 1 else nan
    slip = float(slips.mean()) if n else nan
    stick_time = stick_frac * per if periods.size else nan
    if n < 3 or periods.size < 2:
        code = -1
    else:
        tp = t[[p for p, _ in pairs]]
        trend = np.polyfit(tp - tp[0], np.log(drops), 1)[0] * (tp[-1] - tp[0])
        if abs(trend) > math.log(1.3):
            code = 3
        elif per_cv < cv_periodic and amp_cv < cv_periodic:
            code = 1 if stick_frac > 0 else 4
        else:
            code = 2
    return StickSlipStats(code, amp, rng, per, per_cv, amp_cv, slip, stick_time, stick_frac, n,
                          mean_force, h)


def granular_floor(traps_per_a0: float, u: float, model: TrapModel,
                   factor: float = 3.0) -> float:
    """Default event floor: ``factor`` times the force lost when one trap dies (ours).

    One death at the spinodal removes ``r_d^2 f_+(y_c)`` (eq. 23) of a total normalised by
    ``n H0`` (eq. 12), ``n`` traps per ``a0``; ``r_d`` is the radius at the steady death age at
    velocity ``u`` (eq. 32). Friction units.
    """
    trap = model.trap
    tau_d = steady_response(u, model).tau_d
    r2 = float(model.law.radius(np.array([tau_d]))[0]) ** 2
    return factor * model.mu_el * trap.f_c * r2 / (trap.H0 * traps_per_a0)


# ---------------------------------------------------------------- the sweep runner


def stick_slip_summary(protocol: Mapping[str, Any]) -> dict[str, float]:
    """Sweep runner: simulate a spring protocol (dict) and summarise its stick-slip.

    The protocol is that of :mod:`dryfriction.io.protocol` (``drive.kind = "spring"``) plus an
    optional ``[stickslip]`` table (not passed to the simulator; checked by
    :func:`dryfriction.io.protocol.stickslip_options`):

    * ``transient`` — load-point travel (``a0``, ``>= 0`` and less than the travel) discarded
      before the analysis; default half of the total travel;
    * ``stick_fraction`` (0.5, in ``(0, 1]``), ``rel_threshold`` (0.25, in ``(0, 1)``),
      ``floor`` (friction units, ``> 0``; default :func:`granular_floor`) — see
      :func:`analyse`;
    * ``follow_velocity`` (true) — with ``initial = "steady"``, start from the steady state at
      the *pulling* velocity (the last segment's), so that sweeping
      ``drive.segments.0.velocity`` moves both.

    Returns :meth:`StickSlipStats.to_dict` plus ``u`` and ``stiffness``. Picklable (a module
    function), so :func:`dryfriction.sweeps.sweep.run_sweep` can ship it to workers.
    """
    proto, opts = spring_point(protocol)
    res = simulate(proto.model, proto.drive, proto.initial, proto.output)
    return summarise(res, proto.drive, proto.model, proto.track,
                     **{k: v for k, v in opts.items() if k != "follow_velocity"})


def spring_force(res: SimulationResult, drive: SpringDrive, mu_el: float = 1.0) -> Array:
    """Spring force ``K (X_pull - X)`` of a spring run, friction units."""
    return mu_el * drive.stiffness * (res.x_pull - res.x)


def summarise(res: SimulationResult, drive: SpringDrive, model: TrapModel, track: Track,
              transient: float | None = None, stick_fraction: float = 0.5,
              rel_threshold: float = 0.25, floor: float | None = None) -> dict[str, float]:
    """:func:`analyse` a spring run after ``transient`` ``a0`` of load-point travel."""
    u = pulling_velocity(drive)
    travel = res.x_pull - res.x_pull[0]
    if transient is None:
        transient = 0.5 * float(travel[-1])
    transient = check_scalar("transient", transient, 0.0)
    if transient >= float(travel[-1]):
        raise ValueError(f"stickslip.transient = {transient:g} a0 is not allowed: less than "
                         f"the load-point travel {float(travel[-1]):g}")
    if floor is None:
        floor = granular_floor(track.traps_per_a0, u, model)
    t_start = float(np.interp(transient, travel, res.t))
    st = analyse(res.t, res.x, res.v, spring_force(res, drive, model.mu_el), u=u,
                 t_start=t_start, floor=floor, rel_threshold=rel_threshold,
                 stick_fraction=stick_fraction)
    return {**st.to_dict(), "u": u, "stiffness": drive.stiffness}


# ---------------------------------------------------------------- linear check


def _damped(t: Array, a: float, s: float, w: float, ph: float, c: float) -> Array:
    return a * np.exp(s * t) * np.cos(w * t + ph) + c


def fit_growth(t: ArrayLike, y: ArrayLike) -> tuple[float, float]:
    """Growth rate ``sigma`` (1/``t0``) and angular frequency ``omega`` of a damped or growing
    oscillation: least squares of ``A e^{sigma t} cos(omega t + phi) + c`` (ours), started
    from the Hilbert envelope's log-slope and the mean zero-crossing interval."""
    t, y = np.asarray(t, float), np.asarray(y, float)
    if t.size < 20:
        raise ValueError(f"only {t.size} samples to fit a growth rate: at least 20")
    # lazily: scipy.signal and SciPy's optimizers take ~1 s to import, and only this fit and
    # the decay envelope below use them
    from scipy.optimize import curve_fit
    from scipy.signal import hilbert

    tt = t - t[0]
    yc = y - y.mean()
    env = np.abs(hilbert(yc))
    m = slice(t.size // 10, t.size - t.size // 10)
    s0 = float(np.polyfit(tt[m], np.log(np.maximum(env[m], 1e-300)), 1)[0])
    up = np.flatnonzero((yc[:-1] < 0) & (yc[1:] >= 0))
    if up.size < 3:
        raise ValueError("fewer than two full oscillations in the fit window")
    w0 = 2 * math.pi / float(np.mean(np.diff(tt[up])))
    a0 = float(env[m][0] * math.exp(-s0 * tt[m][0]))
    best = None
    for ph in np.linspace(0, 2 * math.pi, 8, endpoint=False):
        try:
            p, _ = curve_fit(_damped, tt, y, p0=[a0, s0, w0, ph, float(y.mean())], maxfev=4000)
        except RuntimeError:
            continue
        r = float(np.sum((_damped(tt, *p) - y) ** 2))
        if best is None or r < best[0]:
            best = (r, p)
    if best is None:
        raise ValueError("the damped-oscillation fit did not converge")
    return float(best[1][1]), abs(float(best[1][2]))


def linear_check(
    u: float,
    model: TrapModel,
    stiffness_factors: Sequence[float],
    *,
    mass: float,
    damping: float,
    traps_per_a0: float = TRAPS_PER_A0_COARSE,
    kick: float = 0.03,
    duration: float = 1500.0,
    skip: float = 50.0,
) -> list[dict[str, float]]:
    """Direct simulation against the linear theory, for ``K = factor * K_c`` (module doc).

    Parameters
    ----------
    u : float
        Pulling velocity (``a0/t0``).
    model : TrapModel
        The trap model.
    stiffness_factors : sequence of float
        ``K / K_c`` of the runs.
    mass, damping : float
        ``M > 0`` (``F_el t0^2/a0``) and ``eta >= 0`` (``F_el t0/a0``); the inertial case,
        where ``K_c`` is finite and well defined when ``eta > 0`` (stability.py).
    traps_per_a0 : float
        Density of the regular track.
    kick : float
        Initial slider velocity ``(1 + kick) u``.
    duration, skip : float
        Run length and the initial stretch left out of the fit (``t0``).

    Returns
    -------
    list of dict
        Per run: ``K``, ``K_over_Kc``, ``K_c``, linear ``sigma_linear``, ``omega_linear``
        (rightmost root), fitted ``sigma_sim``, ``omega_sim``, the fit window and the final
        class of the run (stick-slip reached or not).
    """
    if not mass > 0:
        raise ValueError(f"mass = {mass!r} is not allowed: > 0 (the inertial case)")
    res = critical_stiffness(u, model, mass, damping)
    Kc = res.critical_stiffness
    resp = linear_response(u, model)
    track = Track(traps_per_a0)
    floor = granular_floor(traps_per_a0, u, model)
    rows = []
    for f in stiffness_factors:
        K = float(f) * Kc
        lam = rightmost_root(resp, K, mass, damping)
        ens = Ensemble(model, track, Initial("steady", velocity=u), age_horizon=2 * duration)
        drive = SpringDrive(K, mass, VelocityProgram([Segment(u, duration=duration)]), damping)
        every = min(0.5, 2 * math.pi / (20 * max(abs(lam.imag), 1e-3)))
        r = continue_spring(ens, drive, Output(every=every), velocity=(1 + kick) * u)
        dv = r.v - u
        # the linear window: after `skip`, up to the first sample where |v - u| > u/2
        big = np.flatnonzero(np.abs(dv) > 0.5 * u)
        end = int(big[0]) if big.size else dv.size
        sel = np.arange(dv.size)[(r.t >= r.t[0] + skip) & (np.arange(dv.size) < end)]
        # and, for a decay, while the envelope is above three times the noise it decays into
        # (the median envelope of the run's last tenth, where only granular noise is left)
        if lam.real < 0 and sel.size:
            from scipy.signal import hilbert

            env = np.abs(hilbert(dv - dv.mean()))
            noise = 3.0 * float(np.median(env[-max(dv.size // 10, 1):]))
            low = np.flatnonzero(env[sel] < noise)
            if low.size and low[0] > 40:
                sel = sel[: low[0]]
        s, w = fit_growth(r.t[sel], dv[sel]) if sel.size >= 20 else (math.nan, math.nan)
        st = analyse(r.t, r.x, r.v, spring_force(r, drive), u=u,
                     t_start=r.t[0] + 0.5 * duration, floor=floor)
        rows.append({
            "K": K, "K_over_Kc": float(f), "K_c": Kc, "omega_c": res.omega,
            "sigma_linear": lam.real, "omega_linear": abs(lam.imag),
            "sigma_sim": s, "omega_sim": w,
            "fit_t0": float(r.t[sel[0]]) if sel.size else math.nan,
            "fit_t1": float(r.t[sel[-1]]) if sel.size else math.nan,
            "final_class": float(st.code), "final_amplitude": st.amplitude,
        })
    return rows


# ---------------------------------------------------------------- the bifurcation


def bifurcation_scan(
    u: float,
    model: TrapModel,
    stiffnesses: Sequence[float],
    *,
    mass: float = 0.0,
    damping: float = 0.0,
    traps_per_a0: float = TRAPS_PER_A0_COARSE,
    travel: float = 20.0,
    transient: float = 10.0,
    kick: float = 0.03,
    force_kick: float = 1e-3,
    samples_per_a0: float = 50.0,
    progress: Callable[[int, int], None] | None = None,
) -> dict[str, Any]:
    """Continuation in ``K``: stick-slip amplitude and period down then up (module doc).

    Parameters
    ----------
    u : float
        Pulling velocity (``a0/t0``).
    model : TrapModel
        The trap model; with the direct effect (``A > 0``, which needs ``M = 0``) ``K_c`` is
        that of :func:`~dryfriction.theory.linear_stability.critical_stiffness` and the force
        kick is added to the friction ``g(u) F``.
    stiffnesses : sequence of float
        ``K`` values (``F_el/a0``) in the order of the way down (largest first); the way up
        runs them in reverse from the end state of the way down.
    mass, damping : float
        ``M >= 0``, ``eta >= 0`` (``eta = 0`` when ``M = 0``).
    traps_per_a0 : float
        Density of the regular track.
    travel, transient : float
        Load-point travel per stiffness and the part of it left out of the analysis (``a0``).
    kick, force_kick : float
        Initial perturbation of the steady state: slider velocity ``(1 + kick) u`` (``M > 0``),
        or the spring force above the friction by ``force_kick`` (``F_el``, ``M = 0``). Near
        ``K_c`` the steady state's basin is small (the bifurcation is subcritical): a 1 %
        force kick at ``1.1 K_c`` already starts stick-slip at ``u = 0.1``.
    samples_per_a0 : float
        Output samples per ``a0`` of load-point travel (and at least 20 per period of the
        mass on the spring when ``M > 0``).
    progress : callable, optional
        ``progress(done, total)`` after each stiffness (``2 len(stiffnesses) - 1`` runs of
        equal load-point travel).

    Returns
    -------
    dict
        ``K_c`` and ``omega_c`` of the linear theory, and for ``"down"`` and ``"up"`` a list of
        :func:`analyse` dicts (one per stiffness, with ``stiffness`` and ``K_c_minus_K``).
    """
    ks = [check_scalar("stiffness", k, 0.0, lo_open=True) for k in stiffnesses]
    if not ks:
        raise ValueError("stiffnesses is empty")
    if transient >= travel:
        raise ValueError(f"transient = {transient:g} must be less than travel = {travel:g}")
    lin = critical_stiffness(u, model, mass, damping)
    track = Track(traps_per_a0)
    floor = granular_floor(traps_per_a0, u, model)
    ens = Ensemble(model, track, Initial("steady", velocity=u),
                   age_horizon=4 * len(ks) * travel / u)
    f0 = ens.observe().force
    if model.direct:
        f0 *= float(junction_strength(u, model.direct, model.v_ref))
    velocity = (1 + kick) * u if mass > 0 else 0.0
    force: float | None = None if mass > 0 else f0 + force_kick
    out: dict[str, Any] = {"K_c": lin.critical_stiffness, "omega_c": lin.omega, "u": u,
                           "mass": mass, "damping": damping, "down": [], "up": []}
    for leg, order in (("down", ks), ("up", ks[::-1][1:])):
        for K in order:
            drive = SpringDrive(K, mass, VelocityProgram([Segment(u, slip=travel)]), damping)
            if mass > 0:
                every = min(1.0 / (samples_per_a0 * u),
                            2 * math.pi * math.sqrt(mass / (K + model.trap.contact_stiffness))
                            / 20)
                output = Output(every=every)
            else:
                output = Output(every_slip=1.0 / samples_per_a0)
            r = continue_spring(ens, drive, output, velocity=velocity, spring_force=force)
            load = spring_force(r, drive)
            st = analyse(r.t, r.x, r.v, load, u=u, t_start=r.t[0] + transient / u, floor=floor)
            out[leg].append({**st.to_dict(), "stiffness": K,
                             "K_c_minus_K": lin.critical_stiffness - K})
            velocity = float(r.v[-1]) if mass > 0 else 0.0
            force = float(load[-1])
            if progress is not None:
                progress(len(out["down"]) + len(out["up"]), 2 * len(ks) - 1)
    return out


# ---------------------------------------------------------------- the (K, V) phase diagram

def phase_axes(spec: Any) -> tuple[str, str]:
    """The stiffness and velocity keys of a (K, V) phase-diagram sweep.

    The grid must sweep exactly ``drive.stiffness`` and the velocity of the last load-point
    segment (``drive.segments.<last>.velocity``); raises ``ValueError`` otherwise.
    """
    segs = spec.base.get("drive", {}).get("segments", [])
    v_key = f"drive.segments.{max(len(segs) - 1, 0)}.velocity"
    keys = {a.key for a in spec.axes}
    if keys != {"drive.stiffness", v_key}:
        raise ValueError(f"a phase diagram sweeps exactly drive.stiffness and {v_key}; this "
                         f"sweep has {', '.join(sorted(keys))}")
    return "drive.stiffness", v_key


def critical_line(base: Mapping[str, Any], u: ArrayLike) -> Array:
    """``K_c(u)`` of the linear analysis for the model and spring of a protocol dict."""
    m, d = base.get("model", {}), base.get("drive", {})
    # every model key, the direct effect too; the defaults are the model's own
    model = TrapModel(**{k: v for k, v in m.items() if k in TRAP_PARAMETERS})
    return np.array([
        critical_stiffness(float(uu), model, float(d.get("mass", 0.0)),
                           float(d.get("damping", 0.0))).critical_stiffness
        for uu in np.asarray(u, float).ravel()
    ])
