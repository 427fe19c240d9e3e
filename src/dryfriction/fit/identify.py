"""What a step's fit can be trusted for: per parameter identified or not, the
combinations the data do fix, and flags that travel with the step into ``steps.csv``,
``fit.json``, the terminal table and the figures.

Everything here is ours (decision rules on top of the fit's covariance and residuals); the
numbers they use are named constants so that a reader can see and change them.

**Identified** (:func:`judge_step`). A fitted ``a``, ``b``, ``Dc`` or stiffness ``k`` is
identified when its 95 % interval (the row's: the autocorrelation-robust Wald interval in
``ln p``, or the profile with ``--profile``) is finite, lies inside the parameter's physical
range (:data:`PHYSICAL`; for ``Dc`` the slips the window probes: from one sample's
load-point slip at the velocity after the change to the slip after the change) and spans at most
:data:`MAX_SPAN` (a factor of 10: an interval wider than a decade fixes only an order of
magnitude), the value is not on its search bound, and the step
shows a transient at all (:func:`transient_test`: a fit to noise alone can have narrow Wald
intervals). Otherwise the value and its standard
error are not reported (NaN), an interval end outside the range is dropped, and the step
gets ``not_identified:<name>`` (and ``at_bound:<name>`` on a bound). The combinations the
data then do fix are reported with their 95 % intervals: ``a - b`` (the steady-state rate
dependence, Ruina 1983: ``mu_ss = mu0 + (a - b) ln(V/V0)``) and ``b/Dc`` (the initial slope
of the evolution effect against slip: for ``Dc`` far above the window's slip the ageing
law's ``b ln(V0 theta/Dc)`` falls as ``b (V - V0) t/Dc``, so only the ratio enters).

**Misfit** (:func:`misfit_words`): the rms residual above :data:`MISFIT_RMS` times the noise
(the steady part's scatter, :func:`.steps.steady_noise`); or the peak residual beyond three
standard deviations of a :data:`~.steps.PEAK_SAMPLES`-sample mean of that noise (AR(1) with
the steady part's lag-1 autocorrelation ``rho``: ``sigma sqrt((1 + rho)/((1 - rho) m))``, at
most ``sigma``); or the runs test beyond its allowance: the residuals change sign less than
half as often as the steady part's own fluctuations do (for Gaussian AR(1) noise the
sign-change rate is ``arccos(rho)/pi``; a runs test against independent signs would flag
every record with correlated apparatus noise, such as the shared one).

**Not steady before the change** (:func:`steady_before`): the fit starts the window in
steady sliding. The step is flagged when (i) the residuals before the change drift, against
load-point displacement, over the pre-step samples (the pre-step slope of ``mu`` against slip
beyond the fitted trend) by more than :data:`DRIFT_NOISE` times the noise and more than three
times the drift a line through that noise shows by chance (``sigma sqrt(12/n_eff)``,
``n_eff = n (1 - rho)/(1 + rho)`` for AR(1) noise; on red noise a drift of 2-3 sigma is
common), or (ii) the
transient of the previous change is still above twice the white noise at the change: its
amplitude on a stiff machine, ``b |ln(V_before/V_prev)|`` (or ``b ln(1 + t_h V/Dc)`` after a
hold), decayed as ``exp(-s/Dc)`` over the load-point slip ``s`` since that change (an order
of magnitude: a soft machine decays more slowly). (ii) needs an identified ``Dc`` and a
previous change inside the record.

**Short window**: the load-point slip after the change is less than :data:`SHORT_DC` times
``Dc`` (the identified value, else the lower end of its interval): the transient has not
decayed to within ``exp(-3)`` of steady sliding.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ..records.data import SeriesData
from ..validation import Array
from .machine import load_point_displacement
from .models import ParamSpec

__all__ = ["FLAG_WORDS", "PHYSICAL", "MAX_SPAN", "MISFIT_RMS", "DRIFT_NOISE", "SHORT_DC",
           "JUDGED", "judge_step", "misfit_words", "steady_before", "change_index",
           "join_flags", "split_flags", "assess_step", "record_stiffness",
           "transient_test", "TRANSIENT_P", "worse_than_noise"]

FLAG_WORDS: dict[str, str] = {
    "not_identified:<name>": "the 95 % interval of <name> (a, b, dc, stiffness; state0, c, "
                             "b2, dc2: fit.lawcolumns) is open, leaves the physical range or "
                             "spans more than a decade: the value is not reported",
    "at_bound:<name>": "<name> ended on its search bound: the value is not reported",
    "misfit": "rms residual, peak residual or residual runs beyond their allowance",
    "not_steady_before": "friction was not in steady sliding before the change",
    "short_window": "the window's slip after the change is under 3 Dc",
    "k_inconsistent": "the step's fitted stiffness disagrees with the other steps' "
                      "(record_stiffness)",
}
"""The words of the ``flags`` column (separated by ``;``) and what each means."""

JUDGED = ("a", "b", "dc", "stiffness")
"""The parameters whose identifiability is decided (where they are fitted)."""

PHYSICAL: dict[str, tuple[float, float]] = {"a": (1e-5, 0.5), "b": (1e-5, 0.5),
                                            "stiffness": (1.0, 1e9)}
"""Physical ranges of ``a``, ``b`` (dimensionless) and the stiffness per unit normal force
(1/m) (ours: laboratory values of ``a``, ``b`` are 1e-4 to 0.05; stiffnesses 1e2 to 1e6 /m).
``Dc``'s range is the window's (module docstring)."""

MAX_SPAN = 10.0
"""Largest ratio ``hi/lo`` of an identified parameter's 95 % interval."""

MISFIT_RMS = 1.5
"""rms residual over the noise above which a step is a misfit."""

DRIFT_NOISE = 2.0
"""Pre-step residual drift, in units of the noise, above which the step was not steady."""

SHORT_DC = 3.0
"""Slip after the change, in units of ``Dc``, below which the window is short."""

_BOUND_REL = 1e-3
"""A value within this relative distance of its search bound is on it."""


def join_flags(words: Sequence[str]) -> str:
    """The ``flags`` cell: the words in order, no repeats, separated by ``;``."""
    return ";".join(dict.fromkeys(words))


def split_flags(cell: str) -> list[str]:
    """The words of a ``flags`` cell (empty list for an empty cell)."""
    return [w for w in str(cell).split(";") if w]


def change_index(d: SeriesData) -> int:
    """Index in the window of its first change of load velocity (the step; for a
    slide-hold-slide window the hold's start); 0 when there is none."""
    ch = np.flatnonzero(np.diff(d.v_load) != 0.0)
    return int(ch[0]) + 1 if ch.size else 0


def _after_index(d: SeriesData) -> int:
    """Index of the last change to a sliding velocity (the step, or the reslide)."""
    v = d.v_load
    ch = np.flatnonzero((np.diff(v) != 0.0) & (v[1:] > 0.0))
    return int(ch[-1]) + 1 if ch.size else 0


def _sign_change_rate(x: Array) -> float:
    s = np.sign(np.asarray(x, float))
    s = s[s != 0]
    return float(np.mean(s[1:] != s[:-1])) if s.size > 2 else math.nan


def _detrended(t: Array, y: Array) -> Array:
    coef = np.polyfit(t - t[0], y, 1)
    return y - np.polyval(coef, t - t[0])


def _calm(d: SeriesData) -> Array:
    """The steady part (last third of the window) about its straight line in time."""
    tail = slice(len(d) * 2 // 3, len(d))
    return _detrended(d.t[tail], d.mu[tail])


def _tail_rho(d: SeriesData) -> float:
    """Lag-1 autocorrelation of the steady part's fluctuations (:func:`_calm`), in [0, 0.999]."""
    calm = _calm(d)
    if calm.size <= 3 or not np.std(calm) > 0:
        return 0.0
    return float(np.clip(np.corrcoef(calm[1:], calm[:-1])[0, 1], 0.0, 0.999))


def worse_than_noise(d: SeriesData, rms: float) -> bool:
    """Whether an rms residual exceeds :data:`MISFIT_RMS` times the steady part's noise: a
    single-start fit that did so is retried from every start (a local minimum)."""
    calm = _calm(d)
    return calm.size > 3 and rms > MISFIT_RMS * math.sqrt(float(calm @ calm) / (calm.size - 2))


def misfit_words(d: SeriesData, model_mu: Array, row: Mapping[str, Any],
                 peak_samples: int) -> list[str]:
    """Why the step is a misfit (sentences; empty when it is not): module docstring."""
    noise = float(row["noise"])
    if not (math.isfinite(noise) and noise > 0):
        return []
    resid = d.mu - model_mu
    out: list[str] = []
    if row["rms"] > MISFIT_RMS * noise:
        out.append(f"rms residual {row['rms']:.3g} is {row['rms'] / noise:.3g} times the noise "
                   f"{noise:.3g} (allowance {MISFIT_RMS:g})")
    calm = _calm(d)
    rho = _tail_rho(d)
    allow = 3.0 * noise * min(1.0, math.sqrt((1 + rho) / ((1 - rho) * peak_samples)))
    peak = float(row["peak_residual"])
    if math.isfinite(peak) and abs(peak) > allow:
        out.append(f"peak residual {peak:+.3g} beyond its allowance {allow:.2g} (3 standard "
                   f"deviations of a {peak_samples}-sample mean of the noise)")
    q_noise, q_res = _sign_change_rate(calm), _sign_change_rate(resid)
    if math.isfinite(q_noise) and math.isfinite(q_res) and q_res < 0.5 * q_noise:
        out.append(f"the residuals change sign at a rate {q_res:.3g}, under half the noise's "
                   f"own {q_noise:.3g}: a systematic misfit")
    return out


def steady_before(d: SeriesData, model_mu: Array, row: Mapping[str, Any], record: SeriesData,
                  i_start: int, b: float, dc: float) -> tuple[float, list[str]]:
    """The load-point slip (m) since the change before this window's change (or since the
    record's first sample), and why friction was not steady before the change (sentences;
    empty when nothing says so): module docstring."""
    i_ch = change_index(d)
    g_ch = i_start + i_ch
    x = load_point_displacement(record)
    v = record.v_load
    prev = np.flatnonzero(np.diff(v[:g_ch]) != 0.0)
    j = int(prev[-1]) + 1 if prev.size else 0
    slip = float(x[g_ch] - x[j])
    out: list[str] = []
    noise, white = float(row["noise"]), float(row["white_noise"])
    if i_ch >= 8 and math.isfinite(noise):
        xl = load_point_displacement(d)[:i_ch]
        r = (d.mu - model_mu)[:i_ch]
        if np.ptp(xl) > 0:
            drift = float(np.polyfit(xl, r, 1)[0]) * float(np.ptp(xl))
            # the drift a line through n samples of AR(1) noise shows by chance: sigma
            # sqrt(12/n_eff), n_eff = n (1 - rho)/(1 + rho) (rho: the steady part's)
            rho = _tail_rho(d)
            n_eff = max(i_ch * (1.0 - rho) / (1.0 + rho), 1.0)
            chance = noise * math.sqrt(12.0 / n_eff)
            if abs(drift) > max(DRIFT_NOISE * noise, 3.0 * chance):
                out.append(f"the residuals drift by {drift:+.3g} over the {np.ptp(xl) * 1e6:.3g}"
                           f" um before the change ({abs(drift) / noise:.2g} times the noise): "
                           "friction was still evolving")
    if prev.size and math.isfinite(dc) and math.isfinite(b) and math.isfinite(white):
        vb, vp = float(v[j]), float(v[j - 1])
        if vb > 0.0:
            if vp > 0.0:
                amp = b * abs(math.log(vb / vp))
            else:  # after a hold: the healing of the hold (as fit.machine.hold_remnant)
                k = int(np.flatnonzero(v[:j] != 0.0)[-1]) + 1 if np.any(v[:j] != 0.0) else 0
                vh = float(v[k - 1]) if k > 0 else vb
                amp = b * math.log1p(float(record.t[j] - record.t[k]) * vh / dc)
            rem = amp * math.exp(-slip / dc)
            if rem > 2.0 * white:
                out.append(f"{slip * 1e6:.3g} um ({slip / dc:.2g} Dc) of slip since the "
                           f"previous change leave a transient of about {rem:.2g} (> 2x the "
                           "white noise)")
    return slip, out


TRANSIENT_P = 0.01
"""Largest p-value of :func:`transient_test` at which the data show a transient."""


def transient_test(d: SeriesData, model_mu: Array, p: int, rho: float) -> str:
    """Whether the step shows a transient beyond the noise (ours): the fit against the
    model without one, a straight line in load-point displacement (``mu0 + trend x_lp``: no
    direct effect, no evolution, no change of level), by an F test with the residuals'
    correlation counted, ``F (1 - rho)/(1 + rho)`` on ``p - 2`` and ``n_eff - p`` degrees of
    freedom, ``n_eff = n (1 - rho)/(1 + rho)`` (AR(1) residuals of lag-1 autocorrelation
    ``rho``). Returns the reason when it does not (p-value above :data:`TRANSIENT_P`), else
    ""."""
    from scipy import stats

    x = load_point_displacement(d)
    X = np.column_stack([np.ones(len(d)), x - x[0]])
    r0 = d.mu - X @ np.linalg.lstsq(X, d.mu, rcond=None)[0]
    r1 = d.mu - model_mu
    rss0, rss1 = float(r0 @ r0), float(r1 @ r1)
    rho = min(max(rho, 0.0), 0.999) if math.isfinite(rho) else 0.0
    shrink = (1.0 - rho) / (1.0 + rho)
    n_eff = len(d) * shrink
    df1, df2 = p - 2, n_eff - p
    if df1 <= 0 or df2 <= 1 or rss1 <= 0:
        return ""
    F = (rss0 - rss1) / df1 / (rss1 / (len(d) - p)) * shrink
    pv = float(stats.f.sf(F, df1, df2))
    if pv <= TRANSIENT_P:
        return ""
    return (f"the fit is no better than a straight line in load-point displacement (F test, "
            f"p = {pv:.2g}): no transient beyond the noise")


def _interval(spec: ParamSpec, theta: float, se: float, z: float) -> tuple[float, float]:
    if not math.isfinite(se):
        return math.nan, math.nan
    return spec.from_internal(theta - z * se), spec.from_internal(theta + z * se)


def judge_step(row: dict[str, Any], specs: Sequence[ParamSpec], theta: Array, cov: Array,
               singular: bool, z: float, d: SeriesData, no_transient: str = "") -> list[str]:
    """Decide identifiability for the row's ``a, b, dc, stiffness`` (module docstring);
    update the row in place (values, errors and interval ends not reported set to NaN; the
    combinations ``a_minus_b_lo/_hi``, ``b_over_dc(_lo/_hi)``, ``stiffness_lo/_hi``) and
    return the flag words; the notes are appended to ``row["notes"]``.

    ``specs``, ``theta``, ``cov``: the fitted variables, the optimum and their covariance
    (the row's: robust where it is); ``z`` the 95 % quantile used for the row's intervals.
    ``no_transient``: why the data show no transient beyond the noise
    (:func:`transient_test`); then ``a``, ``b``, ``dc`` and the stiffness (which enters
    only through the transient) are not identified whatever their intervals say (a fit to
    noise can have narrow Wald intervals).
    """
    names = [s.name for s in specs]
    notes: list[str] = row.setdefault("notes", [])
    x = load_point_displacement(d)
    i_after = _after_index(d)
    slip_after = float(x[-1] - x[i_after])
    # Dc's range: one sample's slip at the velocity after the change .. the slip after it
    dt_after = float(np.min(np.diff(d.t[i_after:]))) if len(d) - i_after > 1 else math.nan
    ranges = dict(PHYSICAL, dc=(dt_after * float(d.v_load[-1]), slip_after))
    row["slip_after"] = slip_after

    def var(g: Array) -> float:
        # a variance <= 0 is a degenerate covariance, not an exact value (no interval)
        if singular:
            return math.nan
        v = float(g @ cov @ g)
        return v if math.isfinite(v) and v > 0 else math.nan

    if "stiffness" in names:
        j = names.index("stiffness")
        g_k = np.zeros(len(names))
        g_k[j] = 1.0
        row["stiffness_lo"], row["stiffness_hi"] = _interval(specs[j], theta[j],
                                                             math.sqrt(var(g_k)), z)
    else:
        row["stiffness_lo"] = row["stiffness_hi"] = math.nan
    words: list[str] = []
    unidentified: list[str] = []
    for name in JUDGED:
        if name not in names:
            continue
        spec = specs[names.index(name)]
        val = float(row[name])
        lo, hi = float(row[f"{name}_lo"]), float(row[f"{name}_hi"])
        rlo, rhi = ranges[name]
        on_bound = (math.isfinite(val) and val > 0
                    and min(abs(math.log(val / spec.lo)), abs(math.log(spec.hi / val)))
                    < _BOUND_REL)
        # hi > lo: a zero-width interval is a degenerate covariance, never a measurement
        span_ok = (math.isfinite(lo) and math.isfinite(hi) and lo > 0 and hi > lo
                   and hi / lo <= MAX_SPAN)
        inside = math.isfinite(lo) and math.isfinite(hi) and lo >= rlo and hi <= rhi
        # k too: it enters only through the transient (userfixA: a noise record's step gave
        # "stiffness = 13.76 [5.227, 36.2]" as what the data fix, from a fit no better than a line)
        noise_only = bool(no_transient) and name in ("a", "b", "dc", "stiffness")
        if span_ok and inside and not on_bound and not noise_only:
            continue
        unidentified.append(name)
        why = [no_transient] if noise_only else []
        if on_bound:
            words.append(f"at_bound:{name}")
            why.append(f"it ended on its search bound [{spec.lo:g}, {spec.hi:g}]")
        if not (math.isfinite(lo) and math.isfinite(hi)):
            why.append("the covariance gives no finite interval")
        else:
            if not span_ok:  # lo <= 0: an interval reaching 0 has no finite span
                span = ("has zero width (a degenerate covariance, not a measurement)"
                        if hi <= lo else
                        f"spans a factor {hi / lo:.3g} (> {MAX_SPAN:g})" if lo > 0
                        else "reaches 0 or below")
                why.append(f"its 95 % interval [{lo:.3g}, {hi:.3g}] {span}")
            if not inside:
                probes = " (the slips this window probes)" if name == "dc" else ""
                why.append(f"its 95 % interval [{lo:.3g}, {hi:.3g}] leaves the range "
                           f"[{rlo:.3g}, {rhi:.3g}]{probes}")
        words.append(f"not_identified:{name}")
        notes.append(f"{name} = {val:.3g}{' ' + spec.unit if spec.unit else ''} is not "
                     f"identified: {'; '.join(why)}; not reported")
        row[name] = math.nan
        row[f"sigma_{name}"] = math.nan
        keep = not noise_only  # a fit to noise: its interval means nothing either
        row[f"{name}_lo"] = lo if keep and math.isfinite(lo) and lo >= rlo else math.nan
        row[f"{name}_hi"] = hi if keep and math.isfinite(hi) and hi <= rhi else math.nan
    # the combinations, from the covariance in the fitted variables (delta method)
    g_amb = np.zeros(len(names))
    g_ratio = np.zeros(len(names))
    vals = {s.name: s.from_internal(t) for s, t in zip(specs, theta, strict=True)}
    amb = ratio = math.nan
    if "a" in names and "b" in names:
        g_amb[names.index("a")], g_amb[names.index("b")] = vals["a"], -vals["b"]
        amb = vals["a"] - vals["b"]
    if "b" in names and "dc" in names:
        g_ratio[names.index("b")], g_ratio[names.index("dc")] = 1.0, -1.0
        ratio = vals["b"] / vals["dc"]
    s_amb, s_ratio = math.sqrt(var(g_amb)), math.sqrt(var(g_ratio))  # nan stays nan
    amb_lo, amb_hi = amb - z * s_amb, amb + z * s_amb
    # the ratio's interval in ln(b/Dc), mapped back (an overflow is an open side)
    r_lo, r_hi = (ratio * float(np.exp(np.clip(sgn * z * s_ratio, -700.0, 700.0)))
                  for sgn in (-1.0, 1.0))
    amb_ok = math.isfinite(amb_lo) and math.isfinite(amb_hi) and -0.5 <= amb_lo and amb_hi <= 0.5
    ratio_ok = math.isfinite(r_lo) and math.isfinite(r_hi) and r_lo > 0 and r_hi / r_lo <= MAX_SPAN
    row["a_minus_b_lo"], row["a_minus_b_hi"] = (amb_lo, amb_hi) if amb_ok else (math.nan,
                                                                               math.nan)
    if not amb_ok:
        row["a_minus_b"] = row["sigma_a_minus_b"] = math.nan
        if {"a", "b"} <= set(names):
            words.append("not_identified:a_minus_b")
    row["b_over_dc"], row["b_over_dc_lo"], row["b_over_dc_hi"] = (
        (ratio, r_lo, r_hi) if ratio_ok else (math.nan, math.nan, math.nan))
    if unidentified:
        fixed = []
        if amb_ok:
            fixed.append(f"a - b = {amb:.4g} [{amb_lo:.4g}, {amb_hi:.4g}]")
        if ratio_ok and ({"b", "dc"} & set(unidentified)):
            fixed.append(f"b/Dc = {ratio:.4g} [{r_lo:.4g}, {r_hi:.4g}] 1/m")
        for name in ("a", "b", "dc", "stiffness"):
            if name in names and name not in unidentified:
                fixed.append(f"{name} = {row[name]:.4g} [{row[name + '_lo']:.4g}, "
                             f"{row[name + '_hi']:.4g}]")
        notes.append("what the data fix (95 %): " + ("; ".join(fixed) if fixed else "nothing"))
    known = math.isfinite(row["dc"])
    dc_scale = float(row["dc"]) if known else float(row.get("dc_lo", math.nan))
    if math.isfinite(dc_scale) and slip_after < SHORT_DC * dc_scale:
        words.append("short_window")
        notes.append(f"the window holds {slip_after * 1e6:.3g} um of slip after the change, "
                     f"under {SHORT_DC:g} Dc ({SHORT_DC * dc_scale * 1e6:.3g} um"
                     f"{'' if known else ', from the lower end of its interval'}): the "
                     "transient has not decayed; a longer step would fix Dc")
    return words


def assess_step(row: dict[str, Any], notes: Sequence[str], specs: Sequence[ParamSpec],
                theta: Array, cov: Array, singular: bool, z: float, d: SeriesData,
                model_mu: Array, record: SeriesData, i_start: int, peak_samples: int,
                not_steady: Sequence[str] = ()) -> None:
    """Judge one step's row (module docstring) and write ``row["flags"]`` (the ``;`` cell),
    ``row["notes"]`` (the fit's ``notes``, then one sentence per finding) and
    ``row["slip_before"]``/``row["slip_after"]`` (m) in place. ``not_steady``: sentences
    found elsewhere that friction was not steady where the window starts (an earlier hold's
    reslide)."""
    b, dc = float(row["b"]), float(row["dc"])  # before judge_step blanks the unidentified
    row["notes"] = list(notes)
    words = judge_step(row, specs, theta, cov, singular, z, d,
                       transient_test(d, model_mu, len(specs), float(row["resid_rho1"])))
    bad_fit = misfit_words(d, model_mu, row, peak_samples)
    if bad_fit:
        words.append("misfit")
        row["notes"] += [f"misfit: {s}" for s in bad_fit]
    elif any("runs test p" in n for n in notes):  # the engine's test assumes independent noise
        row["notes"].append("not a misfit: the runs test above assumes independent noise; "
                            "the residuals change sign about as often as the record's own "
                            "steady fluctuations do, and rms and peak residual are within "
                            "their allowances")
    ok = {s.name: math.isfinite(float(row.get(s.name, math.nan))) for s in specs}
    slip, unsteady = steady_before(d, model_mu, row, record, i_start,
                                   b if ok.get("b") else math.nan,
                                   dc if ok.get("dc") else math.nan)
    row["slip_before"] = slip
    unsteady = [*not_steady, *unsteady]
    if unsteady:
        words.append("not_steady_before")
        row["notes"] += [f"not steady before the change: {s}" for s in unsteady]
    # an error the covariance could not give is never left without its word (issue 24)
    for s in specs:
        sig = row.get(f"sigma_{s.name}")
        if sig is not None and not math.isfinite(float(sig)) \
                and f"not_identified:{s.name}" not in words:
            words.append(f"not_identified:{s.name}")
            row["notes"].append(f"{s.name}: the covariance gives no finite standard error")
    order = {w: i for i, w in enumerate(("not_identified", "at_bound", "misfit",
                                         "not_steady_before", "short_window",
                                         "k_inconsistent"))}
    row["flags"] = join_flags(sorted(words, key=lambda w: order.get(w.split(":")[0], 99)))


def record_stiffness(rows: list[dict[str, Any]], z: float = 1.96) -> dict[str, Any] | None:
    """One machine (in part; ours): the record's stiffness from the steps
    whose ``k`` is identified, the inverse-variance weighted mean of ``ln k`` (standard
    error of ``ln k_i`` from its 95 % interval: ``ln(hi/lo)/(2 z)``), with its 95 % interval.

    The step whose ``ln k`` differs most from the weighted mean of the *other* steps, by more
    than ``z`` times their combined standard error, gets ``k_inconsistent`` (flag and note, in
    place) and is left out; repeated while more than two steps remain (with two that
    disagree, both are flagged: nothing says which one is right). ``None`` with fewer than two
    such steps.
    """
    est: dict[int, tuple[float, float]] = {}
    for i, r in enumerate(rows):
        k, lo, hi = (float(r.get(c, math.nan)) for c in ("stiffness", "stiffness_lo",
                                                          "stiffness_hi"))
        if all(math.isfinite(x) and x > 0 for x in (k, lo, hi)) and hi > lo:
            est[i] = (math.log(k), math.log(hi / lo) / (2.0 * z))
    if len(est) < 2:
        return None

    def mean(idx: list[int]) -> tuple[float, float]:
        w = np.array([1.0 / est[i][1] ** 2 for i in idx])
        return float(w @ np.array([est[i][0] for i in idx]) / w.sum()), \
            float(1.0 / math.sqrt(w.sum()))

    def flag(i: int, other: float, gap: float) -> None:
        row = rows[i]
        row["flags"] = join_flags([*split_flags(row["flags"]), "k_inconsistent"])
        row.setdefault("notes", []).append(
            f"k_inconsistent: k = {math.exp(est[i][0]):.4g} /m differs from the other steps' "
            f"{math.exp(other):.4g} /m by {gap:.2g} combined standard errors (> {z:.3g}): one "
            "machine cannot be both; k trades with Dc and b in this step")

    keep = sorted(est)
    while len(keep) >= 2:
        gaps = []
        for i in keep:
            m, s = mean([j for j in keep if j != i])
            gaps.append((abs(est[i][0] - m) / math.sqrt(est[i][1] ** 2 + s**2), i, m))
        worst = max(gaps)
        if worst[0] <= z:
            break
        if len(keep) == 2:
            for g, i, m in gaps:
                flag(i, m, g)
            break
        flag(worst[1], worst[2], worst[0])
        keep.remove(worst[1])
    m, s = mean(keep)
    # two steps that disagree are both kept (nothing says which is right) and both flagged:
    # the method must say so (a second new user read "consistent" beside two flagged steps)
    split = len(keep) == 2 and all("k_inconsistent" in split_flags(rows[i]["flags"])
                                   for i in keep)
    return {"value": math.exp(m), "lo": math.exp(m - z * s), "hi": math.exp(m + z * s),
            "unit": "1/m", "steps": keep, "consistent": not split,
            "method": "inverse-variance weighted mean of ln k over the steps where k is "
                      + ("identified; the two steps disagree (both flagged k_inconsistent) and "
                         "nothing says which is right, so both are kept: the value is no "
                         "one machine's" if split else "identified and consistent")
                      + " (fit.identify.record_stiffness)"}
