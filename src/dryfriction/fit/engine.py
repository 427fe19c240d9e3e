"""The fit itself: :func:`fit` checks the input, minimises from several starts, computes the
covariance, profiles and identifiability, and reports; :func:`fit_static`,
:func:`fit_steady`, :func:`fit_joint` are shortcuts and :func:`compare_models` compares fits of
different models to the same data.

:func:`fit` is a sequence of named steps (``_prepare``, ``_problem``, ``_best_of_starts``,
``_check_optimum``, ``_profiles``, ``_estimates``, ``derived_estimates``, ``_goodness``,
``_consistency``) that share an :class:`_Optimum` and a list of notes; the models are in
:mod:`.models`, the statistics in :mod:`.statistics`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import stats

from ..records.data import Dataset, SeriesData, StaticData, SteadyData
from ..theory.model import TrapModel
from ..validation import Array, check_choice, check_scalar
from .models import CVModel, Model, ParamSpec, RSFModel, data_kinds
from .problem import Problem
from .progress import EvaluationTracker, FitProgress
from .results import FitResult, ParameterEstimate
from .statistics import (
    Covariance,
    classify,
    consistency_test,
    covariance,
    format_value,
    information_criteria,
    log_slope,
    nearer_bound,
    on_search_bound,
    profile_interval,
    quantile_95,
    runs_test,
)

__all__ = ["fit", "fit_static", "fit_steady", "fit_joint", "compare_models"]


Profiles = dict[int, tuple[float | None, float | None, float, float,
                           tuple[int, ...], tuple[int, ...]]]
"""Per free parameter: profile limits (``None`` where open), how far each side was searched,
in the internal variables, and the other parameters on their search bounds at each limit
(:func:`.statistics.profile_interval`'s ``pinned``)."""

_UNBOUNDED = ("bounded", "not", "poorly", "at ")
"""Identifiability labels that mean the data do not bound the parameter on some side (``at
lower bound (...)``, ``at upper bound (...)``: the value is a search bound)."""


@dataclass
class _Optimum:
    """The best fit so far (internal variables) and how the optimiser got there."""

    theta: Array
    cost: float
    success: bool
    status: int
    message: str
    nfev: int
    starts: list[dict[str, Any]] = field(default_factory=list)


def _prepare(datasets: Dataset | Iterable[Dataset], model: str | Model, alpha: float,
             creep: str, v0: float | None, state_law: str, stiffness: float | str,
             regularized: bool, trend: bool = False) -> tuple[list[Dataset], Model]:
    """The data sets as a list and the model as an object (checked)."""
    if isinstance(datasets, (StaticData, SteadyData, SeriesData)):
        datasets = [datasets]
    ds = list(datasets)
    if not ds:
        raise ValueError("no data sets to fit")
    for d in ds:
        if not isinstance(d, (StaticData, SteadyData, SeriesData)):
            raise ValueError(f"{d!r} is not a StaticData, SteadyData or SeriesData")
    if isinstance(model, str):
        check_choice("model", model, ("cv", "rsf"))
        m: Model = (CVModel(TrapModel(alpha, creep=creep)) if model == "cv"
                    else RSFModel(v0, state_law, stiffness, regularized=regularized,
                                 trend=trend))
    else:
        m = model
    if isinstance(m, RSFModel):
        m = m.resolve(ds)
    return ds, m


def _problem(ds: list[Dataset], m: Model, specs_all: Sequence[ParamSpec],
             fix: Mapping[str, float] | None, start: Mapping[str, float] | None) -> Problem:
    """Check the fixed and start names, the fixed values, the uncertainties and the number of
    points, and set up the least-squares problem in the free parameters."""
    kinds = data_kinds(ds)
    names = [s.name for s in specs_all]
    fixed = dict(fix or {})
    # each refusal names what the caller typed, fix['t0'] or start['eps'] (the command line
    # says --fix t0: app.fitting.as_typed), not the bare parameter (a new user read "t0 = -1
    # is out of range" as a protocol key) nor an option a Python caller does not have
    for k in list(fixed) + list(start or {}):
        if k not in names:
            given = "fix" if k in fixed else "start"
            raise ValueError(f"{given}[{k!r}] names an unknown parameter for model {m.name} "
                             f"with {'+'.join(sorted(kinds))} data: the parameters are "
                             f"{', '.join(names)}")
    for s in specs_all:
        unit = f" [{s.unit}]" if s.unit else ""
        if s.name in fixed:
            # the fit's range for the parameter: its search bounds, the lower one open for a
            # positive scale (its lower bound stands for 0); eps = 5 had reached the model
            fixed[s.name] = check_scalar(f"fix[{s.name!r}]{unit}", fixed[s.name], s.lo, s.hi,
                                         lo_open=s.log)
        if start is not None and s.name in start:
            if s.name in fixed:
                held = f"{fixed[s.name]:g}" + (f" {s.unit}" if s.unit else "")
                raise ValueError(f"start[{s.name!r}] is given for a parameter fix holds at "
                                 f"{held}: drop one of them")
            # a start outside the search bounds was clipped onto them in silence
            check_scalar(f"start[{s.name!r}]{unit}", start[s.name], s.lo, s.hi)
    specs = [s for s in specs_all if s.name not in fixed]
    has_sigma = [d.sigma is not None for d in ds]
    if any(has_sigma) and not all(has_sigma):
        with_s = [d.source for d in ds if d.sigma is not None]
        without = [d.source for d in ds if d.sigma is None]
        raise ValueError(f"uncertainty columns in {', '.join(with_s)} but not in "
                         f"{', '.join(without)}: give them in every file or in none")
    n = sum(len(d) for d in ds)
    p = len(specs)
    need = p + (0 if all(has_sigma) else 1)
    if n < need:
        raise ValueError(f"{', '.join(d.source for d in ds)}: {n} points for {p} free "
                         f"parameters ({', '.join(s.name for s in specs)}): need at least {need}"
                         + ("" if all(has_sigma) else " (one more than the parameters, to "
                            "estimate the noise level)"))
    return Problem(m, ds, specs, fixed)


def _starts(guesses: list[dict[str, float]], start: Mapping[str, float] | None,
            multistart: bool) -> list[tuple[str, dict[str, float]]]:
    """The starting points, labelled: the given one and/or the data-driven guesses."""
    starts_in: list[tuple[str, dict[str, float]]] = []
    if start is not None:
        base = dict(guesses[0])
        base.update(start)
        starts_in.append(("given", base))
    if multistart or start is None:
        starts_in += [(f"data guess {i + 1}", g) for i, g in enumerate(guesses)]
    return starts_in


def _best_of_starts(prob: Problem, starts_in: list[tuple[str, dict[str, float]]],
                    track: EvaluationTracker) -> _Optimum:
    """Minimise from each start; keep the lowest cost."""
    best: tuple[Array, float, Any] | None = None
    starts_out: list[dict[str, Any]] = []
    for i, (label, g) in enumerate(starts_in):
        th0 = np.array([s.to_internal(s.within(g[s.name])) for s in prob.specs])
        track.begin("start", f"start {i + 1} of {len(starts_in)}")
        th, cost, sol = prob.solve(th0)
        track.end()
        ok = sol is None or sol.status > 0
        starts_out.append({"start": label, "from": {s.name: g[s.name] for s in prob.specs},
                           "cost": cost, "converged": ok,
                           "nfev": 0 if sol is None else int(sol.nfev),
                           "message": "" if sol is None else sol.message})
        if best is None or cost < best[1]:
            best = (th, cost, sol)
    assert best is not None
    theta, cost, sol = best
    status = 1 if sol is None else int(sol.status)
    return _Optimum(theta, cost, success=status > 0 and math.isfinite(cost), status=status,
                    message="no free parameters" if sol is None else str(sol.message),
                    nfev=sum(int(st["nfev"]) for st in starts_out), starts=starts_out)


def _check_optimum(prob: Problem, opt: _Optimum, notes: list[str]) -> None:
    """A converged fit whose residuals were penalised at the optimum (the model could not be
    evaluated there) has not succeeded."""
    if prob.failures and opt.success:
        prob.failures = 0
        prob.residuals(opt.theta)
        if prob.failures:
            opt.success = False
            opt.message = "the model could not be evaluated at the final parameters"
            if prob.last_failure:  # say why, where the user reads it
                opt.message += f" ({prob.last_failure})"
    if not opt.success:
        notes.append(f"the fit did not converge: {opt.message}")


def _noise_variance(prob: Problem, cost: float) -> float:
    """``s^2``: 1 with given uncertainties, ``RSS/(n - p)`` otherwise (``nan`` for no dof)."""
    dof = prob.n - prob.p
    return 1.0 if prob.sigma_given else (2.0 * cost / dof if dof > 0 else math.nan)


def _profiles(prob: Problem, opt: _Optimum, z: float, notes: list[str],
              track: EvaluationTracker) -> tuple[Profiles, Covariance | None]:
    """Profile every free parameter; a profile that finds a lower cost restarts the fit from
    there (at most three times).

    Returns the profiles and the covariance at the final ``opt.theta`` (``None`` where it was
    not computed there), so that the Jacobian is not evaluated twice at the same point.
    """
    profiles: Profiles = {}
    cov: Covariance | None = None
    for _ in range(3):
        s2 = _noise_variance(prob, opt.cost)
        if not math.isfinite(s2):
            break
        track.begin("jacobian", "Jacobian")
        cov = covariance(prob.jacobian(opt.theta), s2)
        track.end()
        profiles, improved = {}, None
        for j in range(prob.p):
            track.begin("profile", f"profile of {prob.specs[j].name} "
                                   f"({j + 1} of {prob.p})")
            pinned: list[tuple[int, ...]] = []
            lo_c, hi_c, r_lo, r_hi, better = profile_interval(
                prob, opt.theta, opt.cost, s2, j, float(cov.stderr[j]), z * z, pinned)
            track.end()
            if better is not None:
                improved = better
                break
            profiles[j] = (lo_c, hi_c, r_lo, r_hi, pinned[0], pinned[1])
        if improved is None:
            break
        # the profiles and the Jacobian run again from the better optimum
        track.add("profile", len(profiles) + 1)
        track.add("jacobian")
        track.begin("start", "restart from a profile's better optimum")
        opt.theta, opt.cost, _ = prob.solve(improved[0])
        track.end()
        cov = None
        notes.append("a profile found a better optimum than the starts did: the fit was "
                     "restarted from there")
        profiles = {}
    return profiles, cov


def _bound_words(spec: ParamSpec, th: float) -> str:
    """``"t0's lower search bound (1e-12 s)"``: which bound an internal value sits on."""
    k = nearer_bound(spec, th)
    return (f"{spec.name}'s {('lower', 'upper')[k]} search bound "
            f"({format_value((spec.lo, spec.hi)[k], spec.unit)})")


def _estimates(prob: Problem, specs_all: Sequence[ParamSpec], opt: _Optimum, cov: Covariance,
               profiles: Profiles, z: float, notes: list[str]) -> list[ParameterEstimate]:
    """Value, standard error, Wald and profile intervals and identifiability of every
    parameter; a parameter on its search bound makes the fit unsuccessful."""
    m, ds, specs, theta = prob.model, prob.datasets, prob.specs, opt.theta
    estimates: list[ParameterEstimate] = []
    for s in specs_all:
        if s.name in prob.fixed:
            estimates.append(ParameterEstimate(s.name, s.unit, prob.fixed[s.name], fixed=True,
                                               identifiability="fixed", note="held fixed"))
            continue
        j = specs.index(s)
        val = s.from_internal(theta[j])
        sej = float(cov.stderr[j])
        wald = None
        stderr = None
        if math.isfinite(sej):
            wald = (s.from_internal(theta[j] - z * sej), s.from_internal(theta[j] + z * sej))
            stderr = val * sej if s.log else sej
        ident = "identified"
        note = ""
        at_bound = on_search_bound(s, float(theta[j]))
        prof: tuple[float | None, float | None] | None = None
        searched: tuple[float, float] | None = None
        if j in profiles:
            lo_c, hi_c, r_lo, r_hi, pin_lo, pin_hi = profiles[j]
            # a limit reached while another parameter sat on its search bound is that bound's,
            # not the data's: that side is open (its value quoted in the note)
            set_by = [(side, c, pins) for side, c, pins in (("lower", lo_c, pin_lo),
                                                            ("upper", hi_c, pin_hi))
                      if c is not None and pins]
            lo_c = None if pin_lo else lo_c
            hi_c = None if pin_hi else hi_c
            prof = (None if lo_c is None else s.from_internal(lo_c),
                    None if hi_c is None else s.from_internal(hi_c))
            searched = (s.from_internal(r_lo), s.from_internal(r_hi))
            ident, note = classify(s, theta[j], sej, lo_c, hi_c, r_lo, r_hi,
                                   m.data_window(s.name, ds), z)
            if set_by:
                note = (note + "; " if note else f"{s.name}: ") + "; ".join(
                    f"its {side} 95 % profile limit {format_value(s.from_internal(c), s.unit)}"
                    " is set by " + ", ".join(_bound_words(specs[k], theta[k]) for k in pins)
                    + ", not by the data (with "
                    + ("it" if len(pins) == 1 else "them") + " free beyond, the profile "
                    "would go on): that side is open"
                    for side, c, pins in set_by)
        elif not math.isfinite(sej) or (s.log and sej > 2.0):
            ident = "poorly determined (Jacobian; no profile)"
            note = (f"{s.name}: the Jacobian gives a relative error of {sej:.3g} in ln "
                    f"{s.name}; run with the profile to see what the data bound" if s.log else
                    f"{s.name}: the Jacobian gives no finite standard error; run with the "
                    "profile to see what the data bound")
        if at_bound:
            if ident == "identified":
                opt.success = False
            k = nearer_bound(s, float(theta[j]))
            side, bound = ("lower", "upper")[k], (s.lo, s.hi)[k]
            ident = f"at {side} bound ({format_value(bound, s.unit)})"
            note = (f"{s.name} = {format_value(val, s.unit)} sits on its {side} search bound "
                    f"{format_value(bound, s.unit)} (allowed [{s.lo:g}, {s.hi:g}]"
                    + (f" {s.unit}" if s.unit else "") + "): the data push it out of the "
                    "allowed range, so the value is the bound, not an estimate, and it has no "
                    "error bar" + (f"; {note}" if note else ""))
        if ident.startswith(_UNBOUNDED):
            stderr, wald = None, None
            notes.append(note)
        elif note:
            notes.append(note)
        estimates.append(ParameterEstimate(s.name, s.unit, val, False, stderr, wald, prof,
                                           searched, ident, note))
    return estimates


def derived_estimates(prob: Problem, theta: Array, cov: Covariance,
             estimates: Sequence[ParameterEstimate]) -> dict[str, dict[str, Any]]:
    """The model's derived quantities (delta method in the internal variables) and the
    data-fixed combinations: level and slope of each curve at the data's centre."""
    m, p = prob.model, prob.p
    derived: dict[str, dict[str, Any]] = {}
    vals = prob.values(theta)
    unbounded = {e.name for e in estimates if e.identifiability.startswith(_UNBOUNDED)}
    for name, (dval, unit) in m.derived(vals).items():
        entry: dict[str, Any] = {"value": dval, "unit": unit, "stderr": None}
        if p and np.all(np.isfinite(cov.stderr)):
            g = np.zeros(p)
            for j in range(p):
                h = 1e-6 * max(1.0, abs(theta[j]))
                tp, tm = theta.copy(), theta.copy()
                tp[j] += h
                tm[j] -= h
                g[j] = (m.derived(prob.values(tp))[name][0]
                        - m.derived(prob.values(tm))[name][0]) / (2 * h)
            entry["stderr"] = float(math.sqrt(max(g @ cov.matrix @ g, 0.0)))
        if unbounded:
            entry["note"] = f"depends on {', '.join(sorted(unbounded))}, which the data do not fix"
        derived[name] = entry
    for d in prob.datasets:
        if isinstance(d, SeriesData):
            continue
        xc = float(np.exp(np.mean(np.log(d.x[d.x > 0])))) if np.any(d.x > 0) else 1.0
        xs = np.array([xc / 1.01, xc, xc * 1.01])
        f = m.predict(vals, d, xs)
        derived[f"{d.y_name} at {d.x_name} = {xc:.3g} {d.x_unit} ({d.source})"] = {
            "value": float(f[1]), "unit": ""}
        derived[f"d {d.y_name}/d ln {d.x_name} there ({d.source})"] = {
            "value": float((f[2] - f[0]) / (2 * math.log(1.01))), "unit": ""}
    return derived


def _goodness(prob: Problem, theta: Array, cost: float, s2: float, notes: list[str]
              ) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    """Overall goodness of fit (chi-square test with given uncertainties) and, per data set,
    the residuals and a runs test on their signs."""
    n, p = prob.n, prob.p
    dof = n - p
    chi2 = 2.0 * cost
    goodness: dict[str, Any] = {"n": n, "free_parameters": p, "dof": dof,
                                "cost": cost, "noise_sigma": math.sqrt(s2) if s2 == s2 else None}
    if prob.sigma_given:
        goodness.update(chi2=chi2, reduced_chi2=chi2 / dof if dof > 0 else None,
                        p_value=float(stats.chi2.sf(chi2, dof)) if dof > 0 else None)
        if dof > 0 and stats.chi2.sf(chi2, dof) < 0.01:
            notes.append(f"chi2 = {chi2:.4g} for {dof} degrees of freedom (p = "
                         f"{stats.chi2.sf(chi2, dof):.2g}): the model does not describe the "
                         "data within their stated uncertainties")
    else:
        goodness.update(rms_residual=math.sqrt(2.0 * cost / n),
                        note="no uncertainties given: the noise level is estimated from the "
                             "residuals, so there is no absolute goodness-of-fit test")
    per: list[dict[str, Any]] = []
    for d, r, w in zip(prob.datasets, prob.split(theta), prob.w, strict=True):
        raw = r / w
        order = np.argsort(d.x, kind="stable")
        entry: dict[str, Any] = {
            "source": d.source, "kind": d.kind, "n": len(d),
            "rms_residual": float(np.sqrt(np.mean(raw**2))),
            "mean_residual": float(np.mean(raw)), "max_abs_residual": float(np.max(np.abs(raw))),
            "runs_test_p": runs_test(r[order]),
        }
        if prob.sigma_given:
            entry["chi2"] = float(r @ r)
        if entry["runs_test_p"] is not None and entry["runs_test_p"] < 0.01:
            notes.append(f"{d.source}: the residuals have too few sign changes (runs test p = "
                         f"{entry['runs_test_p']:.2g}): a systematic misfit")
        per.append(entry)
    return goodness, per


def _against_model(prob: Problem, per: list[dict[str, Any]], notes: list[str]) -> list[str]:
    """Each data set's own trend against ``ln x`` (:func:`.statistics.log_slope`) where the
    model allows one sign only (:meth:`.models.CVModel.allowed_trend`): written into its ``per``
    entry as ``trend``; a trend whose 95 % interval lies wholly on the forbidden side (or,
    with no noise estimate, a slope on that side) contradicts the model, which then fits
    only a flat line through the data and reports parameters that mean nothing. Returns the
    flags ``against_model:<source>`` and puts the reason first among the notes (ours)."""
    flags: list[str] = []
    for d, entry in zip(prob.datasets, per, strict=True):
        if isinstance(d, SeriesData):
            continue
        # a model that does not say (a step windows' joint model) allows either sign
        rule = getattr(prob.model, "allowed_trend", None)
        allowed = None if rule is None else rule(d.kind)
        if allowed is None:
            continue
        sign, why = allowed
        tr = log_slope(d.x, d.y, d.sigma)
        if tr["slope"] is None:
            continue
        slope, iv = tr["slope"], tr["interval_95"]
        against = (sign * iv[1] < 0 if sign > 0 else sign * iv[0] < 0) if iv is not None \
            else sign * slope < 0
        entry["trend"] = {
            "quantity": f"d {d.y_name}/d ln {d.x_name}", "value": slope,
            "stderr": tr["stderr"], "interval_95": iv, "per_decade": slope * math.log(10.0),
            "unit": f"1 ({d.y_name} per e-fold of {d.x_name}; per_decade: per factor 10)",
            "model_allows": "growth" if sign > 0 else "decrease", "against_model": against}
        if not against:
            continue
        flags.append(f"against_model:{d.source}")
        verb = "falls" if slope < 0 else "grows"
        ivs = ("no error estimate with two points" if iv is None else
               f"95 %: {iv[0]:.3g} to {iv[1]:.3g}")
        notes.insert(0, f"{d.source}: the data contradict the model: {d.y_name} {verb} with "
                        f"{d.x_name}, d {d.y_name}/d ln {d.x_name} = {slope:.3g} ({ivs}; "
                        f"{slope * math.log(10.0):.3g} per decade of {d.x_name}; "
                        f"{d.y_name} dimensionless), while {why}: the fit can only flatten "
                        "the curve, and its parameters mean nothing")
    return flags


def _consistency(prob: Problem, cost: float, track: EvaluationTracker) -> dict[str, Any]:
    """Fit each data set alone and test the joint fit against the separate fits."""
    m, fix = prob.model, prob.fixed
    sep_cost, sep_p = 0.0, 0
    for d in prob.datasets:
        specs = [s for s in m.parameters(data_kinds([d])) if s.name not in fix]
        names = {s.name for s in m.parameters(data_kinds([d]))}
        fx = {k: v for k, v in fix.items() if k in names}
        if len(d) <= len(specs):
            return {"test": "not run", "reason": f"{d.source} has too few points to fit alone"}
        track.begin("consistency", f"{d.source.rsplit('/', 1)[-1]} alone")
        r = fit(d, m, fix=fx, profile=False, consistency=False, progress=track.nested())
        track.end()
        if not r.success:
            return {"test": "not run", "reason": f"the separate fit of {d.source} failed"}
        sep_cost += float(r.goodness["cost"])
        sep_p += len(r.free)
    return consistency_test(cost, prob.p, prob.n, sep_cost, sep_p, prob.sigma_given)


def fit(
    datasets: Dataset | Iterable[Dataset],
    model: str | Model = "cv",
    *,
    alpha: float = 0.13,
    creep: str = "log",
    v0: float | None = None,
    state_law: str = "ageing",
    stiffness: float | str = math.inf,
    regularized: bool = False,
    trend: bool = False,
    fix: Mapping[str, float] | None = None,
    start: Mapping[str, float] | None = None,
    multistart: bool = True,
    profile: bool = True,
    consistency: bool = True,
    progress: FitProgress | None = None,
) -> FitResult:
    """Fit ``model`` to one or more data sets with one parameter set.

    Parameters
    ----------
    datasets : data set or iterable of them
        :class:`~dryfriction.records.data.StaticData`,
        :class:`~dryfriction.records.data.SteadyData`,
        :class:`~dryfriction.records.data.SeriesData` (SI units), e.g. from
        :func:`dryfriction.records.data.read_csv`.
    model : {"cv", "rsf"} or CVModel or RSFModel
        The trap model or rate-and-state friction. The keyword options below build the model
        from a name and are ignored for a model object.
    alpha, creep : float, str
        Trap model: fixed trap stiffness and creep law.
    v0, state_law, stiffness, regularized : float, str, float or str, bool
        Rate-and-state: reference velocity (m/s; for static data the hold tests' sliding
        velocity), state law, machine stiffness (1/m, ``inf`` kinematic; ``"fit"`` a free
        parameter, ``"slope"`` fixed from the loading slope: :class:`RSFModel`) and
        regularised law for time series.
    trend : bool
        Rate-and-state time series: a free linear trend in load-point displacement
        (:class:`RSFModel`).
    fix : mapping, optional
        Parameters held fixed, by name (units of the parameter: ``t0`` in s, ``a0`` in m, ...).
    start : mapping, optional
        A starting point (any subset of the free parameters; the rest from the data). With
        ``multistart=False`` it is the only start.
    multistart : bool
        Also start from the data-driven guesses and keep the best fit.
    profile : bool
        Profile-likelihood intervals and identifiability (slower: about 20 fits a parameter).
    consistency : bool
        For several data sets, also fit each alone and test whether one parameter set explains
        all of them.
    progress : callable, optional
        ``progress(done, total, what)`` after every evaluation of the model: evaluations
        done, an estimate of the total (from the stages left at the mean cost of finished
        ones: :class:`~.progress.EvaluationTracker`) and the stage (``profile of t0``).

    Returns
    -------
    FitResult

    Raises
    ------
    ValueError
        Bad input: unknown parameter names, too few points for the free parameters, data
        kinds the model cannot use, uncertainties in some files but not all.
    """
    ds, m = _prepare(datasets, model, alpha, creep, v0, state_law, stiffness, regularized,
                     trend)
    kinds = data_kinds(ds)
    specs_all = m.parameters(kinds)
    prob = _problem(ds, m, specs_all, fix, start)
    starts_in = _starts(m.guesses(ds), start, multistart)
    will_profile = profile and prob.p > 0
    track = EvaluationTracker(prob.p, {
        "start": len(starts_in), "jacobian": 1, "profile": prob.p if will_profile else 0,
        "consistency": len(ds) if consistency and len(ds) > 1 else 0}, progress)
    prob.on_evaluation = track.tick
    opt = _best_of_starts(prob, starts_in, track)
    notes: list[str] = list(m.notes(kinds))
    _check_optimum(prob, opt, notes)

    z = quantile_95(prob.sigma_given, prob.n - prob.p)
    profiles: Profiles = {}
    cov: Covariance | None = None
    if profile and opt.success and prob.p:
        profiles, cov = _profiles(prob, opt, z, notes, track)
    else:
        track.left["profile"] = 0  # a fit that did not converge is not profiled
    s2 = _noise_variance(prob, opt.cost)
    jac = None
    if cov is None:  # not computed at this theta by the profiles (bounds need p > 0)
        track.begin("jacobian", "Jacobian")
        jac = prob.jacobian(opt.theta) if prob.p else None
        if jac is not None:
            jac.flags.writeable = False  # kept on the result, shared by its copies
            theta_kept = opt.theta.copy()
            theta_kept.flags.writeable = False
        cov = covariance(np.zeros((prob.n, 0)) if jac is None else jac, s2)
        track.end()
    if cov.singular:
        notes.append("the Jacobian is singular: some parameter combinations are not "
                     "determined by the data at all")

    estimates = _estimates(prob, specs_all, opt, cov, profiles, z, notes)
    derived = derived_estimates(prob, opt.theta, cov, estimates)
    goodness, per = _goodness(prob, opt.theta, opt.cost, s2, notes)
    flags = _against_model(prob, per, notes)
    flags += [f"at_bound:{e.name}" for e in estimates if e.identifiability.startswith("at ")]
    flags += [f"not_identified:{e.name}" for e in estimates
              if e.identifiability.startswith(("bounded", "not", "poorly"))]
    cons: dict[str, Any] | None = None
    if consistency and len(ds) > 1 and opt.success:
        cons = _consistency(prob, opt.cost, track)
        if cons.get("p_value") is not None and cons["p_value"] < 0.01:
            notes.append(f"one parameter set does not explain all the data sets: the joint fit "
                         f"is worse than separate fits ({cons['test']}, p = "
                         f"{cons['p_value']:.2g})")
    if not opt.success and "did not converge" not in " ".join(notes):
        notes.append("the fit is not reliable (see the parameters on their bounds)")
    if progress is not None:
        progress(track.done, track.done, "done")
    return FitResult(
        model=m.name, options=m.options(), parameters=tuple(estimates),
        free=tuple(s.name for s in prob.specs), correlation=cov.correlation, derived=derived,
        success=opt.success, status=opt.status, message=opt.message, nfev=opt.nfev,
        starts=tuple(opt.starts), sigma_given=prob.sigma_given, goodness=goodness,
        per_dataset=tuple(per),
        information=information_criteria(opt.cost, prob.n, prob.p, prob.sigma_given),
        consistency=cons, notes=tuple(dict.fromkeys(notes)),
        sources=tuple(d.source for d in ds), fitted_model=m, flags=tuple(flags),
        theta=None if jac is None else theta_kept, jacobian=jac,
    )


def fit_static(data: StaticData, model: str | Model = "cv", **kwargs: Any) -> FitResult:
    """Fit static friction against waiting time (:func:`fit` with one StaticData)."""
    if not isinstance(data, StaticData):
        raise ValueError(f"{data!r} is not StaticData")
    return fit([data], model, **kwargs)


def fit_steady(data: SteadyData, model: str | Model = "cv", **kwargs: Any) -> FitResult:
    """Fit steady friction against velocity (:func:`fit` with one SteadyData)."""
    if not isinstance(data, SteadyData):
        raise ValueError(f"{data!r} is not SteadyData")
    return fit([data], model, **kwargs)


def fit_joint(static: StaticData, steady: SteadyData, model: str | Model = "cv",
              **kwargs: Any) -> FitResult:
    """Fit static and steady data with one parameter set (:func:`fit`)."""
    if not isinstance(static, StaticData) or not isinstance(steady, SteadyData):
        raise ValueError("fit_joint needs a StaticData and a SteadyData")
    return fit([static, steady], model, **kwargs)


def compare_models(results: Sequence[FitResult]) -> dict[str, Any]:
    """Compare fits of different models to the same data: residuals, AIC, BIC.

    ``delta_aic``/``delta_bic`` are relative to the best model; Akaike weights
    ``exp(-delta_aic/2)`` normalised. Differences below 2 do not favour either model.
    """
    srcs = {r.sources for r in results}
    if len(srcs) != 1:
        raise ValueError("model comparison needs fits to the same data files")
    aic = np.array([r.information["aic"] for r in results])
    bic = np.array([r.information["bic"] for r in results])
    w = np.exp(-(aic - aic.min()) / 2.0)
    w /= w.sum()
    out: dict[str, Any] = {}
    for r, da, db, wi in zip(results, aic - aic.min(), bic - bic.min(), w, strict=True):
        out[r.model] = {"success": r.success, "free_parameters": len(r.free),
                        "aic": r.information["aic"], "bic": r.information["bic"],
                        "delta_aic": float(da), "delta_bic": float(db), "akaike_weight": float(wi),
                        "rms_residual": [pd["rms_residual"] for pd in r.per_dataset]}
    best = results[int(np.argmin(aic))].model
    gap = np.sort(aic)[1] - aic.min() if len(aic) > 1 else math.inf
    out["verdict"] = (f"{best} is preferred (delta AIC = {gap:.3g})" if gap > 2 else
                      f"the data do not distinguish the models (delta AIC = {gap:.3g} < 2)")
    return out

