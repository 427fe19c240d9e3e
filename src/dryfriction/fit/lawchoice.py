"""A record's steps with the state law chosen per step and a free initial state where the
data say the window starts inside a transient (ours).

:func:`fit_steps_laws` runs :func:`.steps.fit_steps` (or, with ``stiffness="record"``,
:func:`.onemachine.fit_steps_one_machine`) once per state law, then:

* **initial state** (``initial="auto"``, the default): every step flagged
  ``not_steady_before`` (:func:`.identify.steady_before`, or a hold's remnant) is refitted
  from a free initial state (``state0 = ln(theta0 V/Dc)`` fitted, :mod:`.laws`), and that fit
  is the step's, whatever its AIC: the flag says the data contradict the steady start, and
  the free fit contains the steady one (``state0 = 0``). The flag stays (it describes the
  data); a note gives both fits' AIC and ``state0`` with its interval (or says it is not
  identified). Automatic rather than an option a user must think of, because a steady start inside a
  transient biases ``Dc`` silently (23.6 um for a true 20 um on a slide-hold-slide record with short
  reslides: docs/tutorials/lab-record.md), while a free start where the data were steady costs one
  parameter and an identified ``state0`` near 0. ``initial="steady"`` or ``"free"`` forces one for
  every step. With a free stiffness per step, the record's stiffness and ``k_inconsistent``
  (:func:`.identify.record_stiffness`) are then found afresh from the steps as finally fitted.
* **state law** (``law="auto"``): every law of :data:`.laws.FIT_LAWS` per step; the one of
  least AIC is the step's (``state_law`` column), and its row carries ``law_comparison``
  (AIC, BIC, their differences from the least, rms, success for each law; in fit.json) and a
  note (terminal). AIC and BIC assume independent Gaussian residuals: with correlated
  residuals (lag-1 autocorrelation near 1 on real records) their differences overstate the
  evidence, so a difference under :data:`CLOSE` is reported as not deciding. A law whose
  fit did not succeed is not chosen while one succeeded.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from ..records.data import SeriesData
from .identify import record_stiffness, split_flags
from .laws import FIT_LAWS
from .onemachine import fit_steps_one_machine
from .steps import StepsResult, fit_steps, series_windows

__all__ = ["fit_steps_laws", "CLOSE", "INITIAL_CHOICES"]

CLOSE = 2.0
"""AIC difference below which two laws are reported as equally supported (Burnham &
Anderson 2002: differences under 2 give substantial support to both)."""

INITIAL_CHOICES: tuple[str, ...] = ("auto", "steady", "free")


def _run(record: Any, windows: Any, segments: Any, stiffness: Any, **kw: Any) -> StepsResult:
    if stiffness == "record":
        return fit_steps_one_machine(record, windows, segments, **kw)
    return fit_steps(record, windows, segments, stiffness=stiffness, **kw)


def _free_start(res: StepsResult, record: Any, wins: Sequence[Any], segments: Any,
                stiffness: Any, law: str, kw: dict[str, Any]) -> None:
    """Refit each step flagged ``not_steady_before`` from a free initial state (module
    docstring), in place."""
    k = stiffness
    if stiffness == "record":  # the record's one machine, as the steady fits held it
        k = float(res.stiffness["value"]) if res.stiffness is not None else "fit"
    for i, row in enumerate(res.rows):
        if "not_steady_before" not in split_flags(row["flags"]):
            continue
        one = {**kw, "progress": None, "joint": False}
        # from the steady fit's optimum (state0 = 0 is that fit): no cold multistart
        warm = {p.name: p.value for p in res.fits[i].parameters
                if p.name != "stiffness" or k == "fit"}
        new = fit_steps(record, [wins[i]], segments, stiffness=k, law=law, initial="free",
                        warm=[{**warm, "state0": 0.0}], **one)
        nrow, nfit = new.rows[0], new.fits[0]
        words = split_flags(nrow["flags"])
        if "not_steady_before" not in words:  # the data's finding stays with the step
            words.append("not_steady_before")
            nrow["notes"] += [n for n in row["notes"] if n.startswith("not steady before")]
        if stiffness == "record" and "k_inconsistent" in split_flags(row["flags"]):
            words.append("k_inconsistent")  # its free k disagreed: the step's own finding
        nrow["flags"] = ";".join(dict.fromkeys(words))
        if stiffness == "record" and res.stiffness is not None:
            nrow["stiffness_lo"], nrow["stiffness_hi"] = res.stiffness["lo"], res.stiffness["hi"]
            nrow["sigma_stiffness"] = math.nan
        s0 = (f"state0 = ln(theta0 V/Dc) = {nrow['state0']:.3g} [{nrow['state0_lo']:.3g}, "
              f"{nrow['state0_hi']:.3g}]" if math.isfinite(nrow["state0"])
              else "state0 not identified")
        nrow["notes"].append(
            f"refitted from a free initial state (not steady before the change): {s0}; AIC "
            f"{nrow['aic']:.1f} against {row['aic']:.1f} from steady sliding; the steady fit "
            f"gave a = {row['a']:.4g}, b = {row['b']:.4g}, dc = {row['dc']:.4g} m")
        res.rows[i], res.fits[i], res.data[i] = nrow, nfit, new.data[0]
    if stiffness != "record" and any(r["initial"] == "free" for r in res.rows):
        # each step's k as now fitted: the record's k and k_inconsistent afresh
        for r in res.rows:
            r["flags"] = ";".join(w for w in split_flags(r["flags"]) if w != "k_inconsistent")
            r["notes"] = [n for n in r["notes"] if not n.startswith("k_inconsistent")]
        res.stiffness = record_stiffness(res.rows)


def _choose(results: dict[str, StepsResult]) -> StepsResult:
    """Per step, the law of least AIC among those that succeeded (module docstring)."""
    laws = list(results)
    first = results[laws[0]]
    rows, fits, data, notes = [], [], [], []
    for i in range(len(first.rows)):
        cand = {L: results[L].rows[i] for L in laws}
        ok = [L for L in laws if results[L].fits[i].success and math.isfinite(cand[L]["aic"])]
        pool = ok or [L for L in laws if math.isfinite(cand[L]["aic"])] or laws
        best = min(pool, key=lambda L: cand[L]["aic"])
        amin = min(cand[L]["aic"] for L in pool)
        bmin = min(cand[L]["bic"] for L in pool)
        comp = {L: {"aic": cand[L]["aic"], "bic": cand[L]["bic"],
                    "delta_aic": cand[L]["aic"] - amin, "delta_bic": cand[L]["bic"] - bmin,
                    "rms": cand[L]["rms"], "success": L in ok,
                    "flags": cand[L]["flags"]} for L in laws}
        row = dict(cand[best])
        row["law_comparison"] = comp
        close = [L for L in pool if L != best and comp[L]["delta_aic"] < CLOSE]
        by_bic = min(pool, key=lambda L: cand[L]["bic"])
        row["notes"] = list(row["notes"]) + [
            f"state law by AIC: {best}; delta AIC " + ", ".join(
                f"{L} {comp[L]['delta_aic']:+.1f}" for L in laws if L != best)
            + f"; BIC prefers {by_bic}"
            + (f"; {', '.join(close)} within {CLOSE:g} of it: the data do not decide"
               if close else "")
            + ("" if len(ok) == len(laws) else "; laws whose fit did not succeed: "
               + ", ".join(L for L in laws if L not in ok))]
        rows.append(row)
        fits.append(results[best].fits[i])
        data.append(results[best].data[i])
    for L in laws:
        notes += [f"{L}: {n}" for n in results[L].notes]
    stiff = first.stiffness if all(r.stiffness == first.stiffness for r in results.values()) \
        else record_stiffness(rows)
    # the grouping by normal stress and the measured drive do not depend on the law
    return StepsResult(rows, fits, data, None, notes, stiff, first.levels, first.drive)


def fit_steps_laws(record: Any, windows: Sequence[Any] | None = None,
                   segments: Sequence[Any] | None = None, *, law: str = "ageing",
                   initial: str = "auto", stiffness: float | str = "fit",
                   **kwargs: Any) -> StepsResult:
    """Fit a record's steps with ``law`` (or every law, ``"auto"``) and the initial state
    ``initial`` (module docstring). ``stiffness``: as :func:`.steps.fit_steps`, or
    ``"record"`` (:func:`.onemachine.fit_steps_one_machine`); other keywords as
    :func:`.steps.fit_steps`."""
    from ..validation import check_choice

    check_choice("--state-law", law, (*FIT_LAWS, "auto"))
    check_choice("--initial-state", initial, INITIAL_CHOICES)
    if law == "auto" and kwargs.get("joint"):
        raise ValueError("--joint is for one state law: give --state-law ageing or slip")
    laws = FIT_LAWS if law == "auto" else (law,)
    if windows is None:
        if not isinstance(record, SeriesData):
            raise ValueError("a laboratory record's windows must be given")
        windows = series_windows(record)
    wins = list(windows)
    results: dict[str, StepsResult] = {}
    outer = kwargs.pop("progress", None)
    for j, L in enumerate(laws):
        # one count over every law's fits (each law's own count went back to 0 when the
        # next began: a new user's bar with --state-law auto went backwards)
        tick = None if outer is None else (
            lambda done, total, j=j: outer(j * total + done, len(laws) * total))
        res = _run(record, wins, segments, stiffness, law=L,
                   initial="free" if initial == "free" else "steady",
                   **kwargs, **({} if tick is None else {"progress": tick}))
        if initial == "auto":
            _free_start(res, record, wins, segments, stiffness, L, kwargs)
        results[L] = res
    return results[law] if law != "auto" else _choose(results)
