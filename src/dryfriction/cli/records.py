"""``dryfriction fit RECORD.txt``: what a record's fit prints (the workflow is
:func:`dryfriction.app.records.fit_record`)."""

from __future__ import annotations

import json
import math
from typing import Any

from rich.console import Console
from rich.table import Table

from ..io.files import to_jsonable
from .common import err, out, unit_after

__all__ = ["print_record_fit", "flagged_line", "drive_comparison_lines"]


def _cell(x: Any) -> str:
    """A table cell: 4 significant digits; a value not reported (NaN) as a dash."""
    if isinstance(x, float):
        return "—" if math.isnan(x) else f"{x:.4g}"
    return str(x)


def _isfinite(x: Any) -> bool:
    """Whether a cell holds a reported number (not NaN, not None)."""
    return isinstance(x, (int, float)) and math.isfinite(x)


def _fitted(fit: Any) -> str:
    """Which of the machine's parameters a step's fit had free: ``k``, ``trend``."""
    free = {p.name for p in fit.parameters if not getattr(p, "fixed", False)}
    words = [w for n, w in (("stiffness", "k"), ("trend", "trend")) if n in free]
    return ", ".join(words) or "—"


def _steps_table(rows: list[dict[str, Any]], title: str, fits: list[Any]) -> Table:
    from rich.text import Text

    from ..io.units import STEP_UNITS, header

    table = Table(title=title)
    cols = ("index", "kind", "v_before", "v_after", "normal", "a", "b", "a_minus_b", "dc",
            "stiffness", "trend", "rms", "noise", "peak_residual", "flags", "state_law", "mu0",
            "fitted")
    unit = next((r.get("normal_unit") for r in rows if r.get("normal_unit")), "")
    scale, shown = (1e-3, "kN") if unit == "N" else (1e-6, "MPa")
    units = {**STEP_UNITS, "normal": shown, "fitted": None}
    for c in cols:
        # the unit of each column, as in steps.csv (a Text: "[m/s]" is no Rich markup)
        table.add_column(Text(header(c, units[c])),
                         justify="left" if c in ("flags", "state_law", "fitted") else "right")
    for r, f in zip(rows, fits, strict=True):
        table.add_row(*(_cell(float(r[c]) * scale) if c == "normal" else
                        _fitted(f) if c == "fitted" else
                        _cell(r[c]) if c != "flags" else (r[c] or "—") for c in cols))
    return table


LEGEND = ("rms: the residuals' root mean square; noise: the friction's scatter about a line "
          "in the steady part; peak_residual: data minus model at the transient's peak; "
          "stiffness: the machine's, per unit normal force; trend: friction per metre of "
          "load-point travel. Intervals: profile likelihood, or (--errors hac) allowing "
          "for correlated residuals.")
"""What the record table's less common columns mean, printed under it."""

INTERVALS = ("a", "b", "a_minus_b", "dc", "b_over_dc", "stiffness")
"""The 95 % intervals the terminal shows (columns ``<name>_lo``, ``<name>_hi`` of steps.csv)."""


def _intervals_table(rows: list[dict[str, Any]], fits: list[Any] | None = None) -> Table:
    """The 95 % intervals, one row per step; a stiffness the step held at a given value
    (``--stiffness K``: not among its fit's free parameters, no interval) reads ``fixed``,
    not ``[—, —]`` (which says the data do not give it)."""
    from rich.text import Text

    from ..io.units import STEP_UNITS, header

    table = Table(title="95 % intervals (— : not given by the data; fixed: held at a given "
                        "value)")
    table.add_column("index", justify="right")
    for c in INTERVALS:
        table.add_column(Text(header(c, STEP_UNITS[c])), justify="right")
    for i, r in enumerate(rows):
        held = fits is not None and "k" not in _fitted(fits[i]).split(", ")
        table.add_row(str(r["index"]), *(
            "fixed" if c == "stiffness" and held and not _isfinite(r[c + "_lo"])
            else f"[{_cell(r[c + '_lo'])}, {_cell(r[c + '_hi'])}]" for c in INTERVALS))
    return table


def flagged_line(rows: list[dict[str, Any]]) -> str:
    """The last line of a record fit: how many steps carry flags."""
    n = sum(bool(r["flags"]) for r in rows)
    if n == 0:
        return f"no step flagged ({len(rows)} step(s))"
    if n == len(rows):
        return (f"every step is flagged ({n} of {n}): read the flags and notes before using "
                "any value")
    return f"{n} of {len(rows)} steps flagged: read their flags and notes"


def drive_comparison_lines(comparison: list[dict[str, Any]]) -> list[str]:
    """The terminal's lines of ``fit.json``'s ``drive.comparison``: per step, ``k`` and ``a``
    under the measured and the program drive. The program's values are its refit's raw ones
    (:func:`dryfriction.fit.steps.compare_with_program`), so they are printed only beside a
    measured value the data identify, and not at all where the refit did not succeed
    (userfixA: a noise record's "program drive k = 150.1 /m ... (rms ... against 10)")."""
    lines = []
    for c in comparison:
        m, p = c["measured"], c["program"]
        if "not_run" in p:
            continue
        head = (f"step {c['index']}: measured drive k = {_cell(m['stiffness'])} /m, "
                f"a = {_cell(m['a'])}; ")
        if not p.get("success", True):
            lines.append(head + f"the refit on the program drive did not succeed (rms "
                                f"{_cell(p['rms'])}): no values")
            continue
        pk, pa = (_cell(p[n]) if _isfinite(m[n]) else "—" for n in ("stiffness", "a"))
        lines.append(head + f"program drive k = {pk} /m, a = {pa} (rms {_cell(m['rms'])} "
                            f"against {_cell(p['rms'])})")
    return lines


def print_record_fit(done: Any, *, json_out: bool, run_cv: bool, fmt: str,
                     figure: bool) -> None:
    """Print a record's fit (:class:`dryfriction.app.outcome.RecordFitOutcome`): fit.json
    (``--json``) or the tables and notes; the last line says how many steps are flagged."""
    import typer

    from ..fit.experiment import levels_lines

    report, res, path, out_dir = done.report, done.steps, done.report["record"], done.out
    if json_out:
        print(json.dumps(to_jsonable(report), indent=2))
        err.print(flagged_line(res.rows), highlight=False)  # stdout stays one JSON document
    else:
        # one row per step in full, flags included: a console's width would squash them
        wide = Console(width=max(out.width, 260 + max(len(r["flags"]) for r in res.rows)))
        wide.print(_steps_table(res.rows, f"rsf fit of {path}, one row per step (SI; v0 = "
                                "v_before, mu0 the steady friction at v0; fitted: the "
                                "machine's parameters left free)", res.fits))
        wide.print(_intervals_table(res.rows, res.fits))
        out.print(LEGEND, highlight=False, soft_wrap=True)
        for row, f in zip(res.rows, res.fits, strict=True):  # what raised each flag
            for note in row["notes"][len(f.notes):]:
                out.print(f"- step {row['index']}: {note}", highlight=False, soft_wrap=True)
        if res.joint is not None:
            est = {p.name: p for p in res.joint.parameters}
            white = any("white-noise ones" in n for n in res.joint.notes)
            out.print("joint fit (all steps" + ("; +- white-noise, a lower bound: see the "
                                                "note" if white else "") + "): " + ", ".join(
                f"{n} = {est[n].value:.4g}" + ("" if est[n].stderr is None
                                               else f" +- {est[n].stderr:.2g}")
                + unit_after(est[n].unit)
                for n in ("a", "b", "dc", "stiffness") if n in est), highlight=False,
                soft_wrap=True)
            for note in res.joint.notes:
                out.print(f"- joint fit: {note}", highlight=False, soft_wrap=True)
        for line in levels_lines(res.levels):
            out.print(line, highlight=False, soft_wrap=True)
        if res.stiffness is not None:
            k = res.stiffness
            n_load = sum(ld["used"] for ld in k.get("loadings", []))
            out.print(f"one machine: k = {k['value']:.4g} /m [{k['lo']:.4g}, {k['hi']:.4g}] "
                      f"(95 %, steps {', '.join(map(str, k['steps'])) or 'none'}"
                      + (f", {n_load} elastic loading(s)" if n_load else "") + ")"
                      + ("; the two steps disagree (k_inconsistent): no one machine's value"
                         if k.get("consistent") is False else ""),
                      highlight=False, soft_wrap=True)
        for c in (res.drive or {}).get("changes", []):
            out.print(f"measured drive: change at {c['t_change']:.6g} s +- "
                      f"{c['sigma_t_change']:.2g} s (given {c['t_given']:.6g} s), "
                      f"{c['v_before']:.4g} -> {c['v_after']:.4g} m/s", highlight=False,
                      soft_wrap=True)
        for line in drive_comparison_lines((res.drive or {}).get("comparison", [])):
            out.print(line, highlight=False, soft_wrap=True)
        for note in res.notes:
            out.print(f"- {note}", highlight=False, soft_wrap=True)
        if not run_cv:
            out.print(f"- {report['comparison']['not_run']}", highlight=False, soft_wrap=True)
        verdicts = {c["step"]: c.get("verdict", c.get("not_run")) for c in report["comparison"]
                    if isinstance(c, dict) and "step" in c}
        for f in report.get("cv_fits", []):
            rob = f.get("robust", {}).get("parameters", {})  # robust errors where computed
            out.print(f"step {f['step']} cv: " + ", ".join(
                f"{n} = {p['value']:.4g}" + ("" if rob.get(n, p).get("stderr") is None
                                             else f" +- {rob.get(n, p)['stderr']:.2g}")
                + unit_after(p.get("unit"))
                for n, p in f["parameters"].items()) + f"; {verdicts.get(f['step'])}",
                highlight=False, soft_wrap=True)
        out.print(f"wrote {out_dir}/fit.json, steps.csv"
                  + (f", step_*.{fmt}, steps_summary.{fmt}, record.{fmt}, segments.csv"
                     if figure else ""), highlight=False, soft_wrap=True)
        out.print(flagged_line(res.rows), highlight=False, soft_wrap=True)
    if report.get("units_implausible"):  # said before the fit; again last, where one looks
        err.print(f"warning: {report['apparatus_note']}", highlight=False, markup=False,
                  soft_wrap=True)
    if not res.success:
        err.print("[bold red]a step's fit did not succeed[/] (see the notes)", highlight=False)
        raise typer.Exit(1)
