"""Per-step fitting of a multi-step laboratory record: each velocity step (or
slide-hold-slide cycle) fitted on its own with rate-and-state friction on an elastic machine
with a linear slip trend, optionally all steps together with one ``(a, b, Dc)``.

The record is a :class:`~dryfriction.records.data.SeriesData` (time, load velocity, friction) or a
laboratory record (anything with ``time``, ``friction`` and ``source``, such as
``records.lab``'s ``LabRecord``), whose load velocity then comes from the detected ``segments``
(objects with ``velocity``, ``i_start``, ``i_end``: samples ``[i_start, i_end)``). A window
is any object with ``i_start``, ``i_end`` (samples ``[i_start, i_end)``), such as
``records.lab``'s ``StepWindow``; :func:`series_windows` makes them from a SeriesData alone.

Each window is fitted by :func:`.engine.fit` with :class:`.models.RSFModel` (reference
velocity ``v0`` = the window's first load velocity, so ``mu0`` is the steady friction before
the change). The first window starts from the data-driven guess with the lowest cost (one
forward run each, not one fit each); each later one from the previous window's optimum (a
warm start); only when that fit fails are all the guesses tried, which is what keeps a
many-step record cheap.

Noise (ours, :func:`steady_noise`): the standard deviation of the friction about a straight
line in time over the last third of the window (the steady part after the transient, where
the model is a line: steady friction plus the trend): the high-pass residual of the steady
part, independent of the fit. It holds the white noise and whatever slower fluctuation the
apparatus adds (on the shared sepiolite record a machine oscillation of a few 1e-3, far above
the sample-to-sample noise); :func:`white_noise` (first differences) gives the white part
alone. Peak residual (ours): the
peak is the extreme of the data (the maximum after an increase of velocity, the minimum after
a decrease; data smoothed by a running mean of ``PEAK_SAMPLES`` samples) between the change
and the window's end; the peak residual is the mean residual (data minus model) over those
``PEAK_SAMPLES`` samples.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..io.files import write_csv
from ..records.data import SeriesData
from ..records.labsteps import StepWindow
from ..rsf.driving import SolverError
from ..validation import Array, check_choice
from .elastic import machine_stiffness_record
from .engine import fit
from .experiment import EXPERIMENT_COLUMNS, annotate_steps, level_stiffness, levels_report
from .identify import assess_step, worse_than_noise
from .joint import JointStepsModel, fit_joint
from .lawcolumns import LAW_COLUMNS, add_law_columns
from .laws import FIT_LAWS, INITIAL_STATES
from .machine import hold_remnant
from .models import ParamSpec, RSFModel, data_kinds, rsf_series
from .results import FitResult
from .statistics import Covariance, held_parameter_covariance, quantile_95, with_stderr

__all__ = ["StepsResult", "fit_steps", "series_windows", "step_data",
           "write_steps_csv",
           "STEP_COLUMNS", "PEAK_SAMPLES", "steady_noise", "white_noise", "quick_profile",
           "PROFILED", "ERRORS", "StepCovariance", "step_covariance", "robust_estimates",
           "COMPARED", "compare_with_program"]

PEAK_SAMPLES = 11
"""Samples averaged at the peak (module docstring)."""

STEP_COLUMNS: tuple[str, ...] = (
    "index", "kind", "t_change", "v_before", "v_after", "a", "b", "a_minus_b", "dc",
    "stiffness", "trend", "mu0", "sigma_a", "sigma_b", "sigma_a_minus_b", "sigma_dc",
    "sigma_stiffness", "sigma_trend", "a_lo", "a_hi", "b_lo", "b_hi", "dc_lo", "dc_hi",
    "rms", "noise", "white_noise", "peak_residual", "n", "success", "errors", "resid_rho1",
    "hac_lags", "a_minus_b_lo", "a_minus_b_hi", "b_over_dc", "b_over_dc_lo", "b_over_dc_hi",
    "stiffness_lo", "stiffness_hi", "slip_before", "slip_after", "flags",
    "t_change_lo", "t_change_hi",
    *EXPERIMENT_COLUMNS,
) + LAW_COLUMNS
"""Columns of the per-step table (SI: velocities m/s, ``dc`` m, ``stiffness`` and ``trend``
1/m; ``*_lo``/``*_hi`` the 95 % interval, the profile where there is one; ``errors`` says how
the ``sigma_*`` and intervals allow for correlated residuals (:func:`step_covariance`),
``resid_rho1`` is the residuals' lag-1 autocorrelation and ``hac_lags`` the bandwidth used;
``b_over_dc`` in 1/m; ``slip_before`` the load-point slip since the previous change (or the
record's start), ``slip_after`` the window's slip after the change, m; ``flags`` the words of
:data:`.identify.FLAG_WORDS` separated by ``;``; ``t_change_lo``, ``t_change_hi`` the 95 %
interval of the change time as detected (:class:`dryfriction.records.labsteps.Segment`; nan
for a program given by hand); then the normal stress, its level, the hold and
the intervals' kind: :data:`.experiment.EXPERIMENT_COLUMNS`; then the state law's,
:data:`.lawcolumns.LAW_COLUMNS`). A parameter that is not identified
(:mod:`.identify`) has ``nan`` value and error, and ``nan`` interval ends where the data give
none."""

ERRORS = ("hac", "white")
"""How :func:`fit_steps` computes uncertainties: ``"hac"`` (default) allows for autocorrelated
residuals (:func:`.statistics.hac_covariance`), ``"white"`` assumes independent noise."""


def series_windows(data: SeriesData) -> tuple[StepWindow, ...]:
    """One window per change of ``v_load`` from a sliding velocity: from halfway through the
    previous stretch to the end of the stretch after the change (a hold and the reload after
    it make one "shs" window), as :class:`dryfriction.records.labsteps.StepWindow` (``t_change`` in
    the series' time, s).

    As :func:`dryfriction.records.labsteps.slice_steps` does for a laboratory record, a hold
    at the very end gives no window: nothing slides after it, so it is neither a velocity step
    nor a slide-hold-slide. (A series starts sliding, :class:`SeriesData`; every other stretch
    at rest is a hold followed by its reload.)"""
    v = data.v_load
    change = [0, *(np.flatnonzero(np.diff(v) != 0.0) + 1).tolist(), len(v)]
    out: list[StepWindow] = []
    k = 1
    while k < len(change) - 1:
        i0 = (change[k - 1] + change[k]) // 2
        kind, j = "step", k
        if v[change[k]] == 0.0:
            if k + 1 >= len(change) - 1:
                break  # a final hold: nothing slides after it
            kind, j = "shs", k + 1
        hold = float(data.t[change[j]] - data.t[change[k]])  # 0 for a plain step (j = k)
        out.append(StepWindow(len(out), kind, i0, change[j + 1], float(data.t[change[k]]),
                              float(v[change[k] - 1]), float(v[change[j]]), hold))
        k = j + 1
    return tuple(out)


def steady_noise(t: Array, mu: Array) -> float:
    """Standard deviation of ``mu`` about its least-squares line in ``t`` (two dof removed)."""
    t, mu = np.asarray(t, float), np.asarray(mu, float)
    if mu.size < 4:
        return math.nan
    coef = np.polyfit(t - t[0], mu, 1)
    r = mu - np.polyval(coef, t - t[0])
    return float(math.sqrt(r @ r / (mu.size - 2)))


def white_noise(mu: Array) -> float:
    """White-noise standard deviation of one sample from the first differences (robust:
    1.4826 x median absolute deviation, over ``sqrt 2``)."""
    d = np.diff(np.asarray(mu, float))
    if d.size < 2:
        return math.nan
    return float(1.4826 * np.median(np.abs(d - np.median(d))) / math.sqrt(2.0))


def _as_series(record: Any, segments: Sequence[Any] | None) -> SeriesData:
    if isinstance(record, SeriesData):
        return record
    if not segments:
        raise ValueError(f"{getattr(record, 'source', record)!r}: a laboratory record needs "
                         "its segments (the load program) to be fitted")
    t = np.asarray(record.time, float)
    v = np.full(len(t), np.nan)
    for s in segments:
        v[s.i_start:s.i_end] = s.velocity
    if np.any(np.isnan(v)):
        i = int(np.flatnonzero(np.isnan(v))[0])
        raise ValueError(f"{record.source}: sample {i} (t = {t[i]:g} s) is in no segment")
    return SeriesData(t, v, np.asarray(record.friction, float), source=str(record.source))


def _window_data(data: SeriesData, w: Any) -> SeriesData:
    i0, i1 = int(w.i_start), int(w.i_end)
    if not 0 <= i0 < i1 <= len(data):
        raise ValueError(f"{data.source}: window {getattr(w, 'index', '?')} covers samples "
                         f"[{i0}, {i1}), out of range: allowed within [0, {len(data)})")
    sl = slice(i0, i1)
    if hasattr(data, "window"):  # a measured drive goes with the window (.loadpoint)
        return data.window(i0, i1, f"{data.source} [step {getattr(w, 'index', '?')}]")
    return SeriesData(data.t[sl], data.v_load[sl], data.mu[sl],
                      source=f"{data.source} [step {getattr(w, 'index', '?')}]")


def step_data(record: Any, windows: Sequence[StepWindow], segments: Sequence[Any] | None = None
              ) -> list[SeriesData]:
    """Each window's data as a SeriesData (a record's load velocity from ``segments``)."""
    data = _as_series(record, segments)
    return [_window_data(data, w) for w in windows]


def _peak_residual(d: SeriesData, model_mu: Array) -> tuple[float, int]:
    """Mean residual over :data:`PEAK_SAMPLES` samples at the data's peak after the change
    (module docstring) and the peak's index in the window."""
    v = d.v_load
    ch = np.flatnonzero((np.diff(v) != 0.0) & (v[1:] > 0.0))
    i0 = int(ch[-1]) + 1 if ch.size else 0
    m = PEAK_SAMPLES
    if len(d) - i0 < m:
        return math.nan, i0
    smooth = np.convolve(d.mu[i0:], np.ones(m) / m, mode="valid")
    up = v[i0] > v[max(i0 - 1, 0)] or v[max(i0 - 1, 0)] == 0.0
    j = int(np.argmax(smooth) if up else np.argmin(smooth))
    r = d.mu[i0 + j:i0 + j + m] - model_mu[i0 + j:i0 + j + m]
    return float(np.mean(r)), i0 + j + m // 2


PROFILED = ("a", "b", "dc")
"""The parameters :func:`quick_profile` bounds (the others keep their Wald intervals)."""


@dataclass(frozen=True)
class StepCovariance:
    """The covariance of one window's fit, in the fitted (internal) variables.

    Attributes
    ----------
    specs : tuple of ParamSpec
    theta : ndarray
        The optimum (internal variables).
    cost : float
        Half the residual sum of squares there.
    dof : int
        Samples minus parameters.
    white : Covariance
        ``s^2 (J^T J)^-1``, independent noise (``s^2 = RSS/dof``).
    robust : Covariance or None
        The autocorrelation-robust one (:func:`step_covariance`); ``None`` for ``"white"``.
    rho1 : float
        Lag-1 autocorrelation of the residuals.
    lags : int
        The score HAC's Bartlett bandwidth, on the prewhitened scores (0 for ``"white"``).
    """

    specs: tuple[ParamSpec, ...]
    theta: Array
    cost: float
    dof: int
    white: Covariance
    robust: Covariance | None
    rho1: float
    lags: int

    @property
    def used(self) -> Covariance:
        """The covariance the intervals use: the robust one where there is one."""
        return self.white if self.robust is None else self.robust

    def inflation(self, j: int) -> float:
        """Robust over white standard error of parameter ``j`` (1 for ``"white"``): the factor
        by which correlated residuals widen its interval (about 1, either side, for white
        noise: the robust estimate is not floored, so that intervals and standard errors come
        from one covariance)."""
        if self.robust is None:
            return 1.0
        w, r = float(self.white.stderr[j]), float(self.robust.stderr[j])
        return r / w if w > 0 and math.isfinite(r) else math.inf


def step_covariance(r: FitResult, d: SeriesData | Sequence[SeriesData], errors: str = "hac",
                    held: tuple[float, float] | None = None, *,
                    fitted_on_d: bool = False) -> StepCovariance:
    """The covariance of a window's fit ``r`` on data ``d`` (ours): rate-and-state, or the
    trap model (:mod:`.cvsteps`), parameters held fixed in the fit held fixed here; or of the
    joint fit (:class:`.joint.JointStepsModel`) on its windows ``d``, each window its own
    block.

    ``"white"``: ``s^2 (J^T J)^-1`` with ``s^2 = RSS/(n - p)``, as the engine gives.
    ``"hac"``: also the autocorrelation-robust sandwich: a measured record's residuals are
    correlated over many samples (apparatus fluctuations, slow drifts), so the white intervals
    are far too narrow there. Rate-and-state: :func:`.statistics.local_covariance` (the joint
    fit: its windows as independent blocks, :func:`.statistics.blocked_meats`) and the
    drive's change times (:func:`.loadpoint.change_time_effect`, each window's, summed in
    quadrature); the trap model: the score HAC. ``held``: ``(var ln k, this window's share in
    it)``, the stiffness held at the record's: its error carried
    (:func:`.statistics.held_parameter_covariance`). ``fitted_on_d``: ``r`` is a fit on ``d``
    itself, so the fit's own Jacobian at its optimum (``r.jacobian``, where the engine kept
    it) is this covariance's Jacobian where its parameters and point are the same, bit for
    bit; it is computed again otherwise (one forward run per parameter and side saved each
    window).
    """
    from .loadpoint import change_time_effect
    from .problem import Problem
    from .statistics import covariance, hac_covariance, lag1_autocorrelation, local_covariance

    check_choice("errors", errors, ERRORS)
    m = r.fitted_model
    windows = [d] if isinstance(d, SeriesData) else list(d)
    joint = isinstance(m, JointStepsModel)
    val = {p.name: p.value for p in r.parameters}
    fixed = {p.name: p.value for p in r.parameters if p.fixed}
    specs = tuple(s for s in m.parameters(frozenset({"series"})) if s.name not in fixed)
    prob = Problem(m, windows, specs, fixed)
    theta = np.array([s.to_internal(val[s.name]) for s in specs])
    res = prob.residuals(theta)
    cost = 0.5 * float(res @ res)
    dof = prob.n - prob.p
    same = (fitted_on_d and r.jacobian is not None and r.theta is not None
            and r.jacobian.shape == (prob.n, prob.p)
            and tuple(s.name for s in specs) == r.free and np.array_equal(theta, r.theta))
    J = r.jacobian if same else prob.jacobian(theta)
    white = covariance(J, 2.0 * cost / dof)
    rho1 = float(lag1_autocorrelation(res)[0])
    ends = np.cumsum([0, *(len(w) for w in windows)])
    blocks = [slice(int(a), int(b)) for a, b in zip(ends[:-1], ends[1:], strict=True)]

    def moved(i: int) -> Callable[[SeriesData], Array]:
        """The residuals of the whole fit with window ``i`` replaced by ``x`` (its drive
        moved): the others' rows are unchanged."""
        if not joint:
            return lambda x: Problem(m, [x], specs, fixed).residuals(theta)

        def whole(x: SeriesData) -> Array:
            mi = replace(m, windows=tuple(x if k == i else w for k, w in enumerate(windows)))
            out = res.copy()
            out[blocks[i]] = Problem(mi, [x], specs, fixed).residuals(theta)
            return out
        return whole

    rsf, robust, lags = isinstance(m, RSFModel) or joint, None, 0
    if errors == "hac" and not rsf:
        robust, lags = hac_covariance(J, res)
    elif errors == "hac":
        t = np.concatenate([w.t for w in windows])
        robust, lags = local_covariance(J, res, t, blocks if joint else None)
        var = np.zeros(len(specs))
        for i, w in enumerate(windows):  # the windows' change times are independent
            tc = change_time_effect(moved(i), w, J)
            var += 0.0 if tc is None else tc**2
        for j in range(len(specs) if np.any(var > 0) and not robust.singular else 0):
            robust = with_stderr(robust, j, math.hypot(robust.stderr[j], math.sqrt(var[j])))
    base = white if robust is None else robust
    if held is not None and rsf and not isinstance(m.stiffness, str) and not base.singular:
        mk = replace(m, stiffness="fit")  # k free at its held value: how the others move with it
        sk = tuple(s for s in mk.parameters(frozenset({"series"})) if s.name not in fixed)
        tk = np.array([s.to_internal({**val, "stiffness": m.stiffness}[s.name]) for s in sk])
        pk, jk = Problem(mk, [d], sk, fixed), [s.name for s in sk].index("stiffness")
        Jk, rk = pk.jacobian(tk), pk.residuals(tk)
        ck = covariance(Jk, 2.0 * cost / dof) if robust is None else \
            local_covariance(Jk, rk, d.t)[0]
        mat = base.matrix + held_parameter_covariance(Jk, ck.matrix, jk, *held)
        base = Covariance(mat, np.sqrt(np.abs(np.diag(mat))), False)
        white, robust = (base, None) if robust is None else (white, base)
    return StepCovariance(specs, theta, cost, dof, white, robust, rho1, lags)


def robust_estimates(sc: StepCovariance) -> dict[str, dict[str, float]]:
    """Each free parameter's standard error and 95 % Wald interval from ``sc``'s robust
    covariance (the white one for ``"white"``), in its own units (delta method for ``log``
    parameters), and the inflation over the white standard error."""

    z = quantile_95(False, sc.dof)
    out: dict[str, dict[str, float]] = {}
    for j, spec in enumerate(sc.specs):
        se = float(sc.used.stderr[j])
        val = spec.from_internal(sc.theta[j])
        out[spec.name] = {"value": val, "stderr": val * se if spec.log else se,
                          "lo": spec.from_internal(sc.theta[j] - z * se),
                          "hi": spec.from_internal(sc.theta[j] + z * se),
                          "inflation": sc.inflation(j)}
    return out


def robust_joint(r: FitResult, pieces: Sequence[SeriesData], rows: Sequence[Mapping[str, Any]]
                 ) -> FitResult:
    """The joint fit ``r`` (:func:`.joint.fit_joint`) with autocorrelation-robust standard
    errors and Wald intervals (ours): :func:`step_covariance` on its windows, each window an
    independent block (:func:`.statistics.blocked_meats`) with its change time's error, as
    each step's own fit has; ``a - b`` by the delta method on that covariance. Parameters
    without an error bar (at a bound, not identified) keep none. Where the robust covariance
    is singular the white one stays, said in a note as a lower bound (``rows``: the steps'
    table, for their residual autocorrelation)."""
    from .engine import derived_estimates
    from .problem import Problem

    sc = step_covariance(r, pieces, "hac")
    if sc.robust is None or sc.robust.singular:
        rho = [float(w["resid_rho1"]) for w in rows
               if math.isfinite(float(w.get("resid_rho1", math.nan)))]
        return replace(r, notes=(
            *r.notes,
            "the joint fit's standard errors are white-noise ones (residuals taken as "
            "independent; the autocorrelation-robust covariance is singular here), not "
            "autocorrelation-robust as each step's"
            + (f" (the steps' lag-1 residual autocorrelation: {min(rho):.2f} to "
               f"{max(rho):.2f})" if rho else "")
            + ": with correlated residuals they are too small; quote the steps' intervals, "
            "or read the joint +- as a lower bound"))
    est = robust_estimates(sc)
    params = tuple(
        replace(p, stderr=est[p.name]["stderr"], interval_95=(est[p.name]["lo"],
                                                              est[p.name]["hi"]))
        if p.name in est and p.stderr is not None else p for p in r.parameters)
    fixed = {p.name: p.value for p in r.parameters if p.fixed}
    prob = Problem(r.fitted_model, list(pieces), sc.specs, fixed)
    derived = {**r.derived, **derived_estimates(prob, sc.theta, sc.robust, params)}
    wider = [est[n]["inflation"] for n in ("a", "b", "dc") if n in est
             and math.isfinite(est[n]["inflation"])]
    names = [sp.name for sp in sc.specs]
    order = [names.index(n) for n in r.free]
    corr = sc.robust.correlation[np.ix_(order, order)]
    return replace(r, parameters=params, derived=derived, correlation=corr, notes=(
        *r.notes,
        "the joint fit's +- and 95 % intervals are autocorrelation-robust: the time-lag "
        "sandwich with each step's window its own block (the windows' residuals independent "
        "of each other) and each window's change-time error"
        + (f"; {min(wider):.2g} to {max(wider):.2g} times those for independent residuals "
           "(a, b, dc)" if wider else "")))


def quick_profile(r: FitResult, d: SeriesData, names: Sequence[str] = PROFILED,
                  cov: StepCovariance | None = None) -> dict[str, tuple[float, float]]:
    """95 % profile-likelihood intervals of ``names`` from a few constrained fits (ours).

    The profile ``D(psi) = 2 (cost(psi) - cost_min)/s^2`` is found where it crosses
    ``(c t_{0.975, n-p})^2`` on each side, ``c`` the robust inflation of that parameter
    (:meth:`StepCovariance.inflation`; 1 with independent noise, the default when ``cov`` is
    not given): with correlated residuals the cost rises ``c^2`` times faster than their
    independent information warrants. The first trial is the Wald limit, the other
    parameters started from their conditional mean there (covariance); the next trials are
    secant steps on the signed root ``sqrt D``, which is linear in the parameter for a
    quadratic profile, until a trial is within 2 % of the quantile (at most four fits a
    side); the limit is the secant's last step from there.
    The engine's :func:`.engine.fit` profiles walk the whole curve instead (identifiability:
    open sides, flat directions); in a step window ``a``, ``b`` and ``Dc`` are identified, and
    this finds the same limits for a fraction of the cost. A side where a lower optimum turns
    up or the root does not grow keeps its Wald limit.
    """
    from .problem import Problem

    sc = step_covariance(r, d, "white") if cov is None else cov
    specs, theta, cost = list(sc.specs), sc.theta, sc.cost
    prob = Problem(r.fitted_model, [d], specs, {})
    s2 = 2.0 * cost / sc.dof
    cm = sc.white.matrix
    out: dict[str, tuple[float, float]] = {}
    for name in names:
        j = [s.name for s in specs].index(name)
        free = np.ones(prob.p, bool)
        free[j] = False
        z = quantile_95(False, sc.dof) * sc.inflation(j)
        se = float(sc.white.stderr[j])
        if not (math.isfinite(se) and se > 0 and math.isfinite(z)):
            continue
        lims = []
        for sign in (-1.0, 1.0):
            wald = theta[j] + sign * z * se
            pts: list[tuple[float, float]] = [(float(theta[j]), 0.0)]
            psi = wald
            for _ in range(4):
                t0 = theta + cm[:, j] / cm[j, j] * (psi - theta[j])
                t0[j] = psi
                _, c, _ = prob.solve(t0, free)
                root = math.sqrt(max(2.0 * (c - cost) / s2, 0.0))
                if root <= pts[-1][1]:  # a lower optimum or a flat profile: keep Wald
                    psi = wald
                    break
                pts.append((psi, root))
                (p0, r0), (p1, r1) = pts[-2], pts[-1]
                psi = p1 + (z - r1) * (p1 - p0) / (r1 - r0)
                if abs(root - z) < 0.02 * z:  # the last secant step is then tiny
                    break
            lims.append(specs[j].from_internal(psi))
        out[name] = (min(lims), max(lims))
    return out


def _row(w: Any, d: SeriesData, r: FitResult, model: RSFModel, sc: StepCovariance,
         profiles: Mapping[str, tuple[float, float]] | None = None) -> dict[str, Any]:
    """One row of the table: values, standard errors and 95 % intervals from ``sc`` (the
    robust covariance where there is one; delta method for ``log`` parameters and ``a - b``),
    the profile limits where ``profiles`` has them."""

    est = {p.name: p for p in r.parameters}
    names = [s.name for s in sc.specs]
    cov = sc.used
    z = quantile_95(False, sc.dof)

    def val(name: str, default: float = math.nan) -> float:
        return float(est[name].value) if name in est else default

    def grad(name: str) -> Array:  # d(value)/d(internal variables)
        g = np.zeros(len(names))
        if name in names:
            j = names.index(name)
            g[j] = val(name) if sc.specs[j].log else 1.0
        return g

    def se_of(g: Array) -> float:
        # a variance <= 0 of a fitted quantity is a degenerate covariance, not an exact value:
        # no error (NaN), never 0 (userfixA: a noise record's k printed "150.1 [150.1, 150.1]")
        v = float(g @ cov.matrix @ g) if np.any(g) and not cov.singular else math.nan
        return math.sqrt(v) if math.isfinite(v) and v > 0 else math.nan

    def se(name: str) -> float:
        return se_of(grad(name)) if name in names else math.nan

    def iv(name: str) -> tuple[float, float]:
        if profiles and name in profiles:
            return profiles[name]
        if name not in names or cov.singular:
            return math.nan, math.nan
        j = names.index(name)
        if not float(cov.matrix[j, j]) > 0:  # stderr is sqrt|C_jj|: a negative one is no error
            return math.nan, math.nan
        h = z * float(cov.stderr[j])
        return (sc.specs[j].from_internal(sc.theta[j] - h),
                sc.specs[j].from_internal(sc.theta[j] + h))

    values = {p.name: p.value for p in r.parameters}
    fitted = r.fitted_model if isinstance(r.fitted_model, RSFModel) else model
    mu_model = rsf_series(fitted, values, d)
    resid = d.mu - mu_model
    peak, _ = _peak_residual(d, mu_model)
    tail = slice(len(d) * 2 // 3, len(d))
    k = val("stiffness", float(fitted.stiffness) if not isinstance(fitted.stiffness, str)
            else math.nan)
    row: dict[str, Any] = {
        "index": int(getattr(w, "index", 0)), "kind": str(getattr(w, "kind", "step")),
        "t_change": float(getattr(w, "t_change", math.nan)),
        "t_change_lo": float(getattr(w, "t_change_lo", math.nan)),
        "t_change_hi": float(getattr(w, "t_change_hi", math.nan)),
        "v_before": float(getattr(w, "v_before", d.v_load[0])),
        "v_after": float(getattr(w, "v_after", d.v_load[-1])),
        "a": val("a"), "b": val("b"), "a_minus_b": val("a") - val("b"), "dc": val("dc"),
        "stiffness": k, "trend": val("trend", 0.0), "mu0": val("mu0"),
        "sigma_a": se("a"), "sigma_b": se("b"),
        "sigma_a_minus_b": se_of(grad("a") - grad("b")),
        "sigma_dc": se("dc"), "sigma_stiffness": se("stiffness"), "sigma_trend": se("trend"),
    }
    for name in ("a", "b", "dc"):
        row[f"{name}_lo"], row[f"{name}_hi"] = iv(name)
    row.update(rms=float(np.sqrt(np.mean(resid**2))), noise=steady_noise(d.t[tail], d.mu[tail]),
               white_noise=white_noise(d.mu[tail]),
               peak_residual=peak, n=len(d), success=bool(r.success),
               errors="white" if sc.robust is None else "hac", resid_rho1=sc.rho1,
               hac_lags=sc.lags)
    return row


@dataclass
class StepsResult:
    """What :func:`fit_steps` returns.

    Attributes
    ----------
    rows : list of dict
        One row per fitted window, columns :data:`STEP_COLUMNS`.
    fits : list of FitResult
        The fit of each window.
    data : list of SeriesData
        Each window's data (times, load velocity, friction).
    joint : FitResult or None
        The joint fit (``joint=True``): one ``a, b, dc`` and one stiffness, ``mu0`` and trend
        per window (``mu0_<i>``, ``trend_<i>``).
    notes : list of str
    stiffness : dict or None
        The record's one machine stiffness, from the steps' free fits and the record's
        elastic loadings (:func:`.elastic.machine_stiffness_record`); ``None`` where the steps
        are at several normal stresses (one per level in ``levels``).
    levels : dict or None
        The steps grouped by normal stress (:func:`.experiment.levels_report`).
    """

    rows: list[dict[str, Any]]
    fits: list[FitResult]
    data: list[SeriesData]
    joint: FitResult | None = None
    notes: list[str] = field(default_factory=list)
    stiffness: dict[str, Any] | None = None  # the record's k (fit.identify.record_stiffness)
    levels: dict[str, Any] | None = None  # the normal-stress levels (fit.experiment)
    drive: dict[str, Any] | None = None  # the measured drive (fit.loadpoint.drive_report)

    @property
    def success(self) -> bool:
        return all(r.success for r in self.fits) and (self.joint is None or self.joint.success)

    def model_curve(self, i: int) -> Array:
        """The fitted friction of window ``i`` at its samples."""
        r = self.fits[i]
        m = r.fitted_model
        assert isinstance(m, RSFModel)
        return rsf_series(m, {p.name: p.value for p in r.parameters}, self.data[i])

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"steps": self.rows, "success": self.success,
                               "notes": list(self.notes), "record_stiffness": self.stiffness,
                               "grouping": self.levels,
                               "drive": self.drive or {"kind": "program"}}
        if self.joint is not None:
            out["joint"] = self.joint.to_dict()
        return out


def _start(prev: FitResult | None, model: RSFModel, d: SeriesData) -> dict[str, float]:
    """The previous window's optimum (but its own ``mu0``), or else the data-driven guess with
    the lowest cost: one forward run per guess instead of one fit per guess."""
    if prev is not None and prev.success:
        return {p.name: p.value for p in prev.parameters if p.name != "mu0" and not p.fixed}
    m = model.resolve([d])
    specs = {s.name: s for s in m.parameters(data_kinds([d]))}
    best: tuple[float, dict[str, float]] | None = None
    for g in m.guesses([d]):
        # within the search bounds, as the fit puts its own guesses: a start given to it
        # outside them is refused
        g = {k: specs[k].within(v) if k in specs else v for k, v in g.items()}
        try:
            r = d.mu - rsf_series(m, g, d)
        except (SolverError, ValueError):  # a guess the simulator cannot run: skip it
            continue
        c = float(r @ r)
        if math.isfinite(c) and (best is None or c < best[0]):
            best = (c, g)
    return {} if best is None else best[1]


def fit_steps(
    record: Any,
    windows: Sequence[StepWindow] | None = None,
    segments: Sequence[Any] | None = None,
    *,
    stiffness: float | str = "fit",
    trend: bool = True,
    law: str = "ageing",
    joint: bool = False,
    profile: bool = False,
    progress: Callable[[int, int], None] | None = None,
    errors: str = "hac",
    drive: str = "program",
    initial: str = "steady",
    warm: Sequence[Mapping[str, float]] | None = None,
    held: Sequence[tuple[float, float]] | None = None,
) -> StepsResult:
    """Fit rate-and-state friction to each step window of a record (module docstring).

    Parameters
    ----------
    record : SeriesData or laboratory record
        The whole record (SI).
    windows : sequence, optional
        Step windows (``i_start``, ``i_end``, and for the table ``index``, ``kind``,
        ``t_change``, ``v_before``, ``v_after``); default :func:`series_windows` of the
        record's load velocity.
    segments : sequence, optional
        The load program (``velocity``, ``i_start``, ``i_end``) of a laboratory record.
    stiffness : float or {"fit", "slope"}
        Machine stiffness per unit normal force (1/m), fitted per window or fixed
        (:class:`.models.RSFModel`).
    trend : bool
        Fit a linear trend in load-point displacement per window.
    law : {"ageing", "slip", "prz", "nagata", "ageing2"}
        State law (:mod:`.laws`; ``--state-law auto``: :mod:`.lawchoice`).
    joint : bool
        Also fit all windows together with one ``a, b, dc`` and one stiffness (the same
        gouge, the same machine); ``mu0`` and the trend stay per window (the level and the
        drift change along a record); Wald intervals. With ``stiffness="slope"`` the first
        window's slope holds for all.
    profile : bool
        Profile-likelihood 95 % intervals of ``a``, ``b``, ``dc`` in the table
        (:func:`quick_profile`, a few times the fit's cost); default Wald intervals from the
        covariance.
    progress : callable, optional
        Called as ``progress(done, total)`` after each window, and with the windows done so
        far after each model evaluation within a window, so that a slow window (a record read
        in the wrong units takes minutes) still shows progress.
    errors : {"hac", "white"}
        ``"hac"`` (default): standard errors and intervals allow for autocorrelated residuals
        (:func:`step_covariance`); ``"white"``: independent noise assumed.
    drive : {"program", "measured"}
        What drives the forward model: the piecewise-constant program, or the record's
        measured load-point displacement, denoised (:mod:`.loadpoint`; a laboratory record
        only).
    initial : {"steady", "free"}
        Each window starts in steady sliding, or from a fitted state (:mod:`.laws`).
    warm : sequence of mappings, optional
        Starting values per window (e.g. a fit of the same window with another initial
        state, :mod:`.lawchoice`); default: the previous window's optimum.
    held : sequence of (float, float), optional
        Per window, the held stiffness's ``(var ln k, share)`` (:func:`step_covariance`).

    Returns
    -------
    StepsResult
    """
    check_choice("law", law, FIT_LAWS)
    check_choice("initial", initial, INITIAL_STATES)
    if joint and law not in ("ageing", "slip"):
        raise ValueError(f"--joint is for the ageing and slip laws, not {law!r}")
    check_choice("errors", errors, ERRORS)
    data = _as_series(record, segments)
    drive_info = None
    if drive != "program":
        from .loadpoint import check_drive, drive_report, measured_series

        check_drive(drive)
        data = measured_series(data, None if isinstance(record, SeriesData) else record)
        drive_info = drive_report(data)
    wins = list(series_windows(data) if windows is None else windows)
    if not wins:
        raise ValueError(f"{data.source}: no velocity step or slide-hold-slide to fit (the "
                         "load velocity never changes, or only to a hold at the end)")
    RSFModel(1.0, law, stiffness, trend=trend, initial=initial)  # the options, before any work
    pieces = [_window_data(data, w) for w in wins]
    fits: list[FitResult] = []
    rows: list[dict[str, Any]] = []
    notes: list[str] = []
    prev: FitResult | None = None
    for i, (w, d) in enumerate(zip(wins, pieces, strict=True)):
        model = RSFModel(float(d.v_load[0]), law, stiffness, trend=trend, initial=initial)
        # a cold start with a free k can fall into a local minimum: retried if worse than noise
        start, cold = _start(prev, model, d), stiffness == "fit" and (prev is None
                                                                     or not prev.success)
        if warm is not None:
            start, cold = dict(warm[i]), False
        tick = None if progress is None else \
            (lambda n, total, what, i=i: progress(i, len(wins)))  # type: ignore[misc]
        r = fit(d, model, start=start, multistart=False, profile=False, progress=tick)
        rms = r.goodness.get("rms_residual", 0.0)
        if not r.success or (cold and worse_than_noise(d, rms)):
            # from every data-driven guess (the cheapest one can lead to a local minimum)
            r2 = fit(d, model, profile=False, progress=tick)
            r = r2 if r2.goodness["cost"] < r.goodness["cost"] or r2.success else r
        fits.append(r)
        sc = step_covariance(r, d, errors, None if held is None else held[i], fitted_on_d=True)
        prof = quick_profile(r, d, cov=sc) if profile and r.success else None
        rows.append(_row(w, d, r, model, sc, prof))
        if not r.success:
            notes.append(f"step {rows[-1]['index']}: the fit did not succeed ({r.message})")
        rem, hold, slip = hold_remnant(data, int(w.i_start), rows[-1]["b"], rows[-1]["dc"])
        early: list[str] = []
        if rem > 2.0 * rows[-1]["white_noise"]:  # the steady start the fit assumes is not there
            early.append(f"starts {slip * 1e6:.3g} um after the reslide from a {hold:.3g} s "
                         f"hold, where friction is still about {rem:.2g} above steady sliding "
                         "(> 2x the noise): a, b, Dc and the stiffness may be biased; slide "
                         "longer between holds")
            notes.append(f"step {rows[-1]['index']}: {early[-1]}")
        assess_step(rows[-1], r.notes, sc.specs, sc.theta, sc.used.matrix, sc.used.singular,
                    quantile_95(False, sc.dof), d,
                    rsf_series(r.fitted_model, {p.name: p.value for p in r.parameters}, d)
                    if isinstance(r.fitted_model, RSFModel) else d.mu, data, int(w.i_start),
                    PEAK_SAMPLES, early)
        add_law_columns(rows[-1], law, r.information, sc.specs, sc.theta, sc.used.matrix,
                        sc.used.singular, quantile_95(False, sc.dof))
        prev = r
        if progress is not None:
            progress(i + 1, len(wins))
    joint_fit = fit_joint(pieces, fits, law, stiffness, trend) if joint else None
    if joint_fit is not None and errors == "hac":
        joint_fit = robust_joint(joint_fit, pieces, rows)
    annotate_steps(rows, record, wins, profile)  # normal stress, level, hold (fit.experiment)
    if len({int(r.get("normal_level", 0)) for r in rows}) > 1:
        one, each = level_stiffness(rows)  # k = K/sigma_n: one machine per level
    else:  # one level: the steps' free k and the record's elastic loadings (fit.elastic)
        one = machine_stiffness_record(rows, data)
        each = {int(rows[0].get("normal_level", 0)) if rows else 0: one}
    levels = levels_report(rows, each)
    if len(each) > 1:
        notes.append(f"the steps are at {len(each)} normal-stress levels ("
                     + ", ".join(lv["label"] for lv in levels["levels"]) + "): the stiffness "
                     "per unit normal stress (1/m) is K/sigma_n, one per level, so the "
                     "record's one machine is estimated per level (fit.json grouping)"
                     + ("; --joint fits one a, b, Dc and k over all of them" if joint else ""))
    return StepsResult(rows, fits, pieces, joint_fit, notes, one, levels, drive_info)


def write_steps_csv(path: Any, rows: Sequence[Mapping[str, Any]]) -> None:
    """Write the per-step table (:data:`STEP_COLUMNS`) atomically as CSV, each header
    ``name[unit]`` (:data:`dryfriction.io.units.STEP_UNITS`; ``normal`` in the record's
    ``normal_unit``)."""
    from ..io.units import STEP_UNITS

    normal = next((r["normal_unit"] for r in rows if r.get("normal_unit")), "Pa")
    write_csv(path, {c: [r[c] for r in rows] for c in STEP_COLUMNS},
              {**STEP_UNITS, "normal": normal})


COMPARED = ("a", "b", "dc", "stiffness")
"""The values :func:`compare_with_program` reports under both drives."""


def compare_with_program(pieces: list[SeriesData], fits: list[Any],
                         rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """How each step's values depend on the drive: every window refitted on the idealised
    program, started from its measured-drive optimum (one local fit each), its
    ``a, b, dc, stiffness`` and rms beside the measured drive's (the rows' values, NaN where
    not identified: the refit's are raw). One dict per step for ``fit.json``'s
    ``drive.comparison``."""
    out: list[dict[str, Any]] = []
    for d, r, row in zip(pieces, fits, rows, strict=True):
        plain = SeriesData(d.t, d.v_load, d.mu, d.sigma, d.source)
        start = {p.name: p.value for p in r.parameters if not p.fixed}
        entry: dict[str, Any] = {"index": row["index"],
                                 "measured": {n: row[n] for n in (*COMPARED, "rms")}}
        try:
            rp = fit(plain, r.fitted_model, start=start, multistart=False, profile=False)
        except ValueError as exc:  # the program cannot be run with these values
            entry["program"] = {"not_run": str(exc)}
            out.append(entry)
            continue
        vals = {p.name: p.value for p in rp.parameters}
        k_fixed = getattr(r.fitted_model, "stiffness", math.nan)
        entry["program"] = {n: float(vals.get(n, k_fixed if n == "stiffness" else math.nan))
                            for n in COMPARED}
        entry["program"]["rms"] = float(rp.goodness.get("rms_residual", math.nan))
        entry["program"]["success"] = bool(rp.success)
        out.append(entry)
    return out
