"""A whole experiment in one record (ours): the steps of a record grouped by
the normal stress they were run at, what the summary figure draws of them, and what it leaves
out and why.

**Normal stress of a step**: the median of the record's normal column (stress in Pa, or force
in N where the file gives a force) over the window's samples from the change to the window's
end (after the hold for a slide-hold-slide): the stress the transient after the change was
measured at (a median, so that a few samples of a ramp at the window's edge do not move it).
NaN when the record has no normal column.

**Levels** (:func:`normal_levels`): the steps sorted by normal stress; a step joins the level
of the lowest stress below it when it lies within :data:`LEVEL_REL` of it, else it opens a new
level. Levels are numbered from 0 at the lowest stress. Without a normal column every step is
in level 0, labelled "normal stress not recorded".

**Holds**: a slide-hold-slide window (``kind`` ``shs``) is fitted and listed in ``steps.csv``
like a step (its row says ``kind`` ``shs`` and its ``hold`` duration), but it is not a velocity
step (the velocity after the hold is the one before it), so the summary figure of the
velocity dependence leaves it out and says so.

**The summary figure** (:func:`summary_points`): for each of ``a - b``, ``a``, ``b``, ``Dc``
the velocity steps whose value is reported (finite: :mod:`.identify` sets a value that is not
identified, or at its search bound, to NaN), at the velocity after the change, grouped by
level, with the row's 95 % interval; each step left out is counted with its reason.

**One machine per level** (:func:`level_stiffness`): the fits' stiffness is per unit normal
stress (1/m): a machine of stiffness ``K`` (Pa/m) gives ``k = K / sigma_n``, lower at a higher
normal stress. So steps at different normal stresses cannot share one ``k``; the record's
stiffness (:func:`.identify.record_stiffness`, which flags ``k_inconsistent``) is estimated
per level.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .identify import record_stiffness, split_flags

__all__ = ["LEVEL_REL", "PANELS", "EXPERIMENT_COLUMNS", "PROFILE_MAX_STEPS", "step_normal",
           "normal_levels", "annotate_steps", "level_label", "levels_report",
           "summary_points", "level_stiffness", "default_profile", "interval_words",
           "levels_lines"]

LEVEL_REL = 0.03
"""Two steps are at one normal-stress level when their normal stresses differ by at most this
fraction of the lower one: the size of change the detector takes for a change of level
(:mod:`dryfriction.records.detection`, a normal-stress change is at least 3 % of the level), so that
levels and the detector's boundaries agree."""

PANELS: tuple[tuple[str, str], ...] = (("a_minus_b", "a - b"), ("a", "a"), ("b", "b"),
                                        ("dc", "Dc"))
"""The summary figure's panels: row column and label."""

EXPERIMENT_COLUMNS = ("normal", "normal_unit", "normal_level", "hold", "intervals")
"""Columns this module adds to each row (``steps.csv``): the step's normal stress (``normal``,
in ``normal_unit``: ``Pa``, or ``N`` for a force; NaN and ``""`` without a normal column), its
level (0 at the lowest), the hold's duration (s, 0 for a velocity step) and which 95 %
intervals the row's ``a``, ``b``, ``dc`` carry (``profile``, ``hac`` or ``white``;
:func:`interval_words`)."""

PROFILE_MAX_STEPS = 6
"""A record with more windows than this gets the covariance's (HAC) intervals unless
``--profile`` is given: the profiles cost about three times the fits (measured on the
20-step generated experiment, docs/tutorials/lab-record.md "A whole experiment"); with
fewer they are the default."""


def default_profile(n_windows: int, given: bool | None) -> tuple[bool, str]:
    """Whether to profile (``given`` if the user said, else up to :data:`PROFILE_MAX_STEPS`
    windows) and the note saying so when the default left the profiles out."""
    if given is not None:
        return given, ""
    if n_windows <= PROFILE_MAX_STEPS:
        return True, ""
    return False, (f"{n_windows} windows: 95 % intervals from the autocorrelation-robust (HAC) "
                   f"covariance, not profiles (the default above {PROFILE_MAX_STEPS} windows: "
                   "profiles cost about three times the fits); --profile gives them")


def interval_words(kind: str) -> str:
    """What a row's ``intervals`` value means, for a figure or a table."""
    return {"profile": "profile likelihood", "hac": "HAC (autocorrelation-robust) Wald",
            "white": "Wald (independent noise)"}.get(kind, kind)


def _change_index(t: np.ndarray, w: Any) -> int:
    """First sample of window ``w`` at or after its change (after the hold for ``shs``)."""
    at = float(getattr(w, "t_change", math.nan)) + float(getattr(w, "hold", 0.0) or 0.0)
    i0, i1 = int(w.i_start), int(w.i_end)
    if not math.isfinite(at):
        return i0
    return int(min(max(np.searchsorted(t, at, side="left"), i0), i1 - 1))


def step_normal(record: Any, w: Any) -> float:
    """The normal stress (Pa) or force (N) of window ``w`` of ``record`` (module docstring);
    NaN without a normal column."""
    sn = getattr(record, "normal_stress", None)
    if sn is None:
        return math.nan
    t = np.asarray(record.time if hasattr(record, "time") else record.t, float)
    i = _change_index(t, w)
    return float(np.median(np.asarray(sn, float)[i:int(w.i_end)]))


def normal_levels(values: Sequence[float], rel: float = LEVEL_REL) -> list[int]:
    """Level of each value (module docstring): 0 at the lowest; NaN values all in level 0 when
    every value is NaN, else each NaN in a level of its own after the others.

    Raises
    ------
    ValueError
        If ``rel`` is not in ``[0, 1)``.
    """
    if not 0.0 <= rel < 1.0:
        raise ValueError(f"rel = {rel:g} is out of range: allowed 0 <= rel < 1")
    x = np.asarray(values, float)
    out = [-1] * len(x)
    finite = [i for i in np.argsort(x, kind="stable") if math.isfinite(x[i])]
    level, base = -1, math.nan
    for i in finite:
        if not (abs(x[i] - base) <= rel * abs(base)):
            level, base = level + 1, float(x[i])
        out[i] = level
    if not finite:
        return [0] * len(x)
    for i in range(len(x)):
        if out[i] < 0:
            level += 1
            out[i] = level
    return out


def annotate_steps(rows: Sequence[dict[str, Any]], record: Any, windows: Sequence[Any],
                   profile: bool) -> None:
    """Add :data:`EXPERIMENT_COLUMNS` to each row in place (``windows`` as fitted, one per
    row; ``profile``: whether :func:`.steps.quick_profile` gave the ``a, b, dc`` intervals)."""
    normals = [step_normal(record, w) for w in windows]
    unit = str(getattr(record, "normal_unit", "") or "")
    unit = unit if any(math.isfinite(v) for v in normals) else ""
    for row, w, v, lv in zip(rows, windows, normals, normal_levels(normals), strict=True):
        row["normal"], row["normal_unit"], row["normal_level"] = v, unit, lv
        row["hold"] = float(getattr(w, "hold", 0.0) or 0.0)
        row["intervals"] = "profile" if profile else str(row.get("errors", "hac"))


def level_label(value: float, unit: str) -> str:
    """A level's legend entry: ``"20 MPa"`` (a stress), ``"5 kN"`` (a force)."""
    if not math.isfinite(value) or not unit:
        return "normal stress not recorded"
    if unit == "N":
        return f"{value / 1e3:.3g} kN"
    return f"{value / 1e6:.3g} MPa"


def levels_report(rows: Sequence[Mapping[str, Any]],
                  stiffness: Mapping[int, Mapping[str, Any] | None] | None = None
                  ) -> dict[str, Any]:
    """The grouping for ``fit.json``: each level's normal stress (mean and range over its
    steps, with the unit), label, velocity steps and slide-hold-slides (row ``index``), and
    its one-machine stiffness where ``stiffness`` has it; the rule."""
    levels: dict[int, dict[str, Any]] = {}
    for r in rows:
        lv = levels.setdefault(int(r["normal_level"]), {"steps": [], "holds": [], "values": []})
        lv["holds" if r["kind"] == "shs" else "steps"].append(int(r["index"]))
        lv["values"].append(float(r["normal"]))
    unit = str(rows[0]["normal_unit"]) if rows else ""
    out = []
    for k in sorted(levels):
        v = np.asarray(levels[k].pop("values"))
        ok = v[np.isfinite(v)]
        mean = float(ok.mean()) if ok.size else math.nan
        entry = {"level": k, "normal": mean, "unit": unit,
                 "normal_min": float(ok.min()) if ok.size else math.nan,
                 "normal_max": float(ok.max()) if ok.size else math.nan,
                 "label": level_label(mean, unit), **levels[k]}
        if stiffness is not None and stiffness.get(k) is not None:
            entry["stiffness"] = dict(stiffness[k])  # type: ignore[arg-type]
        out.append(entry)
    return {"levels": out,
            "rule": (f"a step's normal stress is the median over its window from the change to "
                     f"its end; steps within {LEVEL_REL:.0%} of a level's lowest value share "
                     "that level (fit.experiment)"),
            "holds": "slide-hold-slide windows (kind shs) are fitted and listed in steps.csv "
                     "but left out of steps_summary (not velocity steps)"}


def summary_points(rows: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """What the summary figure draws (module docstring), per panel name of :data:`PANELS`:
    ``{"levels": {level: [(index, v_after, value, lo, hi), ...]}, "left_out": {index:
    reason}}``, and ``"intervals"``: the interval kinds of the rows drawn, and ``"holds"``:
    the slide-hold-slide rows (left out of every panel)."""
    holds = [int(r["index"]) for r in rows if r["kind"] == "shs"]
    out: dict[str, Any] = {"holds": holds,
                           "intervals": sorted({str(r.get("intervals", "")) for r in rows
                                                if r["kind"] != "shs"})}
    for name, _ in PANELS:
        levels: dict[int, list[tuple[int, float, float, float, float]]] = {}
        left: dict[int, str] = {}
        for r in rows:
            if r["kind"] == "shs":
                continue
            val = float(r[name])
            if not math.isfinite(val):
                words = split_flags(str(r.get("flags", "")))
                left[int(r["index"])] = ("at a bound" if f"at_bound:{name}" in words
                                         else "not identified")
                continue
            levels.setdefault(int(r["normal_level"]), []).append(
                (int(r["index"]), float(r["v_after"]), val, float(r[f"{name}_lo"]),
                 float(r[f"{name}_hi"])))
        out[name] = {"levels": levels, "left_out": left}
    return out


def level_stiffness(rows: list[dict[str, Any]]) -> tuple[dict[str, Any] | None,
                                                          dict[int, dict[str, Any] | None]]:
    """The record's one machine per normal-stress level (module docstring):
    :func:`.identify.record_stiffness` over each level's rows (which flags
    ``k_inconsistent`` in place, within the level). Returns the record's stiffness when there
    is one level (else ``None``: no one ``k`` in 1/m holds for all steps) and each level's."""
    by: dict[int, list[dict[str, Any]]] = {}
    for r in rows:
        by.setdefault(int(r.get("normal_level", 0)), []).append(r)
    each: dict[int, dict[str, Any] | None] = {}
    for k, level in sorted(by.items()):
        rec = record_stiffness(level)
        if rec is not None:  # its "steps" are positions in the level: the rows' own indices
            rec["steps"] = [int(level[i].get("index", i)) for i in rec["steps"]]
        each[k] = rec
    return (each[next(iter(each))] if len(each) == 1 else None), each


def levels_lines(report: Mapping[str, Any] | None) -> list[str]:
    """The terminal's lines for :func:`levels_report` (nothing for a single level without a
    stiffness of its own to say)."""
    if not report or len(report["levels"]) < 2:
        return []
    out = [f"{len(report['levels'])} normal-stress levels:"]
    for lv in report["levels"]:
        k = lv.get("stiffness")
        ks = "" if not k else (f"; one machine at this level: k = {k['value']:.4g} /m "
                               f"[{k['lo']:.4g}, {k['hi']:.4g}] (95 %)")
        holds = f", slide-hold-slide {', '.join(map(str, lv['holds']))}" if lv["holds"] else ""
        out.append(f"  level {lv['level']}: {lv['label']}: steps "
                   f"{', '.join(map(str, lv['steps'])) or 'none'}{holds}{ks}")
    return out
