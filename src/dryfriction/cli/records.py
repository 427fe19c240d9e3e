"""``dryfriction fit RECORD.txt``: a laboratory record (issue 10) read as it comes, its load
program detected, cut into steps and each step fitted with rate-and-state friction on an
elastic machine with a trend (:func:`dryfriction.fit.steps.fit_steps`)."""

from __future__ import annotations

import json
import math
import re
import time
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.table import Table

from ..io.files import to_jsonable
from .common import err, out, progress_bar, say

__all__ = ["is_project_csv", "parse_stiffness", "fit_record", "cv_cost", "CV_CALLS_PER_STEP"]

_PROJECT_COLUMNS = ({"t_w", "mu_s"}, {"v", "mu_d"}, {"t", "v_load", "mu"})

CV_CALLS_PER_STEP = 91
"""Forward runs of the trap model for one step of a record (:func:`dryfriction.fit.cvsteps.
fit_cv_steps`: the batched search of :func:`~dryfriction.fit.cvsteps.search_step`, then one
evaluation for the result and covariance, runs read back from the memory of past runs not
counted), for the cost estimate; counted on the shared sepiolite record with the direct effect
free (91 runs; 74 with A = 0: ``python -m benchmarks bench_cv_record``). It was 130 before the
search of issue 30, when the estimate ran 2.2 times over the measured CPU."""


def is_project_csv(path: Path) -> bool:
    """Whether ``path`` is in the project's own CSV format (:mod:`dryfriction.records.data`): its
    first line that is not a comment or blank is a comma-separated header holding the columns
    of one data kind. Anything else is read as a laboratory record."""
    from ..io.textfile import check_text_file
    from ..records.labforms import FORMS

    if Path(path).suffix.lower() in FORMS:  # a .xlsx or .mat is a record, as `record` reads it
        return False
    check_text_file(path)  # a compressed or UTF-16 file is named here, whatever it holds
    with open(path, encoding="utf-8", errors="replace") as fh:
        for line in fh:
            s = line.strip()
            if not s or s.startswith("#"):
                continue
            names = {re.sub(r"\[.*?\]", "", c).strip().lower() for c in s.split(",")}
            return any(cols <= names for cols in _PROJECT_COLUMNS)
    return False


def parse_stiffness(text: str) -> float | str:
    """``--stiffness``: ``fit``, ``slope``, ``record`` (a record's one machine) or a number
    (1/m, ``> 0``; ``inf`` kinematic)."""
    t = text.strip().lower()
    if t in ("fit", "slope", "record"):
        return t
    try:
        k = float(t)
    except ValueError:
        raise ValueError(f"--stiffness {text!r} is not allowed: fit, slope, record or a number "
                         "(1/m, > 0; inf for the kinematic machine)") from None
    if not k > 0:
        raise ValueError(f"--stiffness {text!r} is out of range: allowed > 0 (1/m), fit, "
                         "slope or record")
    return k


def cv_cost(pieces: list[Any], alpha: float, creep: str, direct: float = 0.0,
            v_ref: float = 1e-6, traps_per_a0: float | None = None) -> float:
    """Seconds a trap-model fit of the steps would take: one forward run of the first window
    at its data-driven start, as the record fit runs it
    (:func:`dryfriction.fit.cvsteps.record_cv_model`), timed (CPU time: on a shared machine
    the wall clock counts the others' work), scaled to all windows by their durations and
    times :data:`CV_CALLS_PER_STEP` a window (so the estimate costs one run, not a fit)."""
    from ..fit.cvsteps import RECORD_TRAPS_PER_A0, record_cv_model

    first = pieces[0]
    m = record_cv_model(alpha, creep, direct, v_ref, traps_per_a0 or RECORD_TRAPS_PER_A0)
    guess = m.guesses([first])[0]
    t0 = time.process_time()
    try:
        m.predict(guess, first)
    except ValueError:  # the start is too long to simulate: the fit would be longer still
        return math.inf
    span = sum(float(p.t[-1] - p.t[0]) for p in pieces) / max(float(first.t[-1] - first.t[0]),
                                                             1e-300)
    return (time.process_time() - t0) * span * CV_CALLS_PER_STEP


def _cell(x: Any) -> str:
    """A table cell: 4 significant digits; a value not reported (NaN) as a dash."""
    if isinstance(x, float):
        return "—" if math.isnan(x) else f"{x:.4g}"
    return str(x)


def _steps_table(rows: list[dict[str, Any]], title: str) -> Table:
    table = Table(title=title)
    cols = ("index", "kind", "v_before", "v_after", "normal", "a", "b", "a_minus_b", "dc",
            "stiffness", "trend", "rms", "noise", "peak_residual", "flags", "state_law")
    unit = next((r.get("normal_unit") for r in rows if r.get("normal_unit")), "")
    scale, shown = (1e-3, "kN") if unit == "N" else (1e-6, "MPa")
    for c in cols:
        table.add_column(f"normal [{shown}]" if c == "normal" else c,
                         justify="left" if c in ("flags", "state_law") else "right")
    for r in rows:
        table.add_row(*(_cell(float(r[c]) * scale) if c == "normal" else
                        _cell(r[c]) if c != "flags" else (r[c] or "—") for c in cols))
    return table


INTERVALS = ("a", "b", "a_minus_b", "dc", "b_over_dc", "stiffness")
"""The 95 % intervals the terminal shows (columns ``<name>_lo``, ``<name>_hi`` of steps.csv)."""


def _intervals_table(rows: list[dict[str, Any]]) -> Table:
    table = Table(title="95 % intervals (— : not given by the data)")
    table.add_column("index", justify="right")
    for c in INTERVALS:
        table.add_column(c, justify="right")
    for r in rows:
        table.add_row(str(r["index"]), *(f"[{_cell(r[c + '_lo'])}, {_cell(r[c + '_hi'])}]"
                                         for c in INTERVALS))
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


def fit_record(path: Path, out_dir: Path, *, model: str, columns: str | None,
               segments: str | None, stiffness: float | str, trend: bool, law: str,
               joint: bool, profile: bool | None, run_cv: bool, alpha: float, creep: str,
               json_out: bool, force: bool, fmt: str = "png", dpi: int | None = None,
               figure: bool = True, errors: str = "hac", direct: float = 0.0,
               v_ref: float = 1e-6, traps_per_a0: float | None = None,
               drive: str = "measured", initial: str = "auto") -> None:
    """Read, slice, fit, print and write one laboratory record (module docstring)."""
    import typer

    from ..fit import compare_models
    from ..fit.cvsteps import RECORD_TRAPS_PER_A0, fit_cv_steps
    from ..fit.experiment import default_profile, levels_lines
    from ..fit.lawchoice import INITIAL_CHOICES, fit_steps_laws
    from ..fit.steps import (
        ERRORS,
        robust_estimates,
        step_covariance,
        step_data,
        write_steps_csv,
    )
    from ..io.files import output_directory, write_json
    from ..records import lab
    from ..validation import check_choice

    check_choice("errors", errors, ERRORS)
    from ..fit.loadpoint import check_drive

    check_drive(drive)  # before any work
    check_choice("--initial-state", initial, INITIAL_CHOICES)
    rec = lab.read_record(path, lab.parse_column_map(columns) if columns else None)
    det = None if segments is not None else lab.detect_program(rec)
    segs = lab.parse_segments(segments, rec) if segments is not None else det.segments  # type: ignore[union-attr]
    note = lab.apparatus_note(rec, [s.velocity for s in segs], given=segments is not None)
    if note:  # before the fit: a record of micrometres read as metres fits for minutes
        say(note)
    if det is not None and len(segs) == 1 and segs[0].velocity != 0.0:
        raise ValueError(lab.no_change_message(rec, det))
    wins = lab.slice_steps(rec, segs)
    if not wins:
        raise ValueError(f"{path}: no velocity step to fit: the detected load program is one "
                         "constant velocity (give it with --segments if it is not)")
    out.print(lab.segments_table(segs, rec.normal_unit), highlight=False, markup=False)
    profile, profile_note = default_profile(len(wins), profile)  # many steps: HAC unless asked
    if model == "cv" and not run_cv:  # the trap model is not run unasked (issue 10)
        # the estimate is one trap-model run: made only when the trap model was asked for
        # (on the shared record it costs several times the whole rsf fit)
        cost = cv_cost(step_data(rec, wins, segs), alpha, creep, direct, v_ref, traps_per_a0)
        raise ValueError(f"{path}: the trap model (cv) on this record would take about "
                         f"{cost:.3g} s CPU for {len(wins)} step(s), against seconds for rsf: "
                         "run --model rsf --run-cv [--direct A] to fit both and compare")
    with progress_bar("fitting steps", len(wins), unit="steps") as update:
        # one machine (stiffness "record"), the law (or every law: auto) and the initial state
        res = fit_steps_laws(rec, wins, segs, law=law, initial=initial, stiffness=stiffness,
                             trend=trend, joint=joint, profile=profile, errors=errors,
                             progress=update, drive=drive)
    if profile_note:
        res.notes.append(profile_note)
    if res.drive is not None and res.drive.get("kind") == "measured":
        if profile:  # the same rule as the profiles: a fit of its own per step
            from ..fit.steps import compare_with_program

            # how k and a depend on the drive: each step once more on the program (issue 30)
            res.drive["comparison"] = compare_with_program(res.data, res.fits, res.rows)
        else:
            res.notes.append("the measured drive's comparison with the program (each step "
                             "refitted on it) is left out with the profiles; --profile gives "
                             "both")
    report: dict[str, Any] = {"record": str(path), "columns": list(rec.columns),
                              "segments": [vars(s) if hasattr(s, "__dict__") else s
                                           for s in segs],
                              "model": "rsf", "options": {"stiffness": stiffness,
                                                          "trend": trend, "law": law,
                                                          "initial_state": initial,
                                                          "profile": profile,
                                                          "errors": errors,
                                                          "drive": drive},
                              **res.to_dict()}
    if note:
        report["apparatus_note"] = note.removeprefix("note: ")
    cv_results: dict[int, Any] = {}  # step -> the trap model's fit (--run-cv), for the figures
    if run_cv:
        comp: list[dict[str, Any]] = []
        cv_fits = []
        tpa = RECORD_TRAPS_PER_A0 if traps_per_a0 is None else traps_per_a0
        total = len(res.data) * CV_CALLS_PER_STEP
        with progress_bar("cv fits", total, unit="runs") as update:
            runs = [0]

            def run_done() -> None:
                runs[0] += 1
                update(runs[0], max(total, runs[0]))

            for i, d in enumerate(res.data):
                update(runs[0], what=f"step {i + 1} of {len(res.data)}")
                try:
                    alt = fit_cv_steps([d], [res.fits[i]], alpha, creep, direct, v_ref, tpa,
                                       progress=run_done)[0]
                    cv_results[i] = alt
                    entry = {"step": i, **alt.to_dict()}
                    if errors == "hac":  # the record's residuals are correlated: as for rsf
                        sc = step_covariance(alt, d, errors)
                        entry["robust"] = {"parameters": robust_estimates(sc),
                                           "resid_rho1": sc.rho1, "hac_lags": sc.lags}
                    cv_fits.append(entry)
                    comp.append({"step": i, **compare_models([res.fits[i], alt]),
                                 "note": "cv and rsf on the same machine: a fitted spring "
                                         "and a linear trend in load-point displacement"})
                except (ValueError, NotImplementedError) as exc:
                    comp.append({"step": i, "not_run": f"cv: {exc}"})
        report["comparison"] = comp
        report["cv_fits"] = cv_fits
    else:
        report["comparison"] = {"not_run": "the trap model (cv) was not fitted: it costs "
                                           "minutes to hours a step; --model cv prints the "
                                           "estimate for this record, --run-cv fits it"}
    with output_directory(out_dir, command="fit", force=force, inputs=[path],
                          report=say) as tmp:
        write_json(tmp / "fit.json", report)
        write_steps_csv(tmp / "steps.csv", res.rows)
        if figure:
            from ..plots.steps import plot_step, plot_steps_summary
            from ..plots.style import save_figure
            from .record import write_record_files

            # what the step finder decided, as the record command draws it (issue 23)
            write_record_files(tmp, rec, segs, det, given=segments is not None, fmt=fmt, dpi=dpi)

            for i in range(len(res.rows)):
                # the trap model beside rsf: one more forward run of its fit per step
                others = ({"trap model (cv)": cv_results[i].predict(res.data[i])}
                          if i in cv_results else None)
                save_figure(plot_step(res, i, others=others)[0], tmp / f"step_{i}.{fmt}",
                            fmt, dpi)
            save_figure(plot_steps_summary(res)[0], tmp / f"steps_summary.{fmt}", fmt, dpi)
    if json_out:
        print(json.dumps(to_jsonable(report), indent=2))
        err.print(flagged_line(res.rows), highlight=False)  # stdout stays one JSON document
    else:
        # one row per step in full, flags included: a console's width would squash them
        wide = Console(width=max(out.width, 190 + max(len(r["flags"]) for r in res.rows)))
        wide.print(_steps_table(res.rows, f"rsf fit of {path}, one row per step (SI)"))
        wide.print(_intervals_table(res.rows))
        for row, f in zip(res.rows, res.fits, strict=True):  # what raised each flag
            for note in row["notes"][len(f.notes):]:
                out.print(f"- step {row['index']}: {note}", highlight=False, soft_wrap=True)
        if res.joint is not None:
            est = {p.name: p for p in res.joint.parameters}
            out.print("joint fit (all steps): " + ", ".join(
                f"{n} = {est[n].value:.4g}" + ("" if est[n].stderr is None
                                               else f" +- {est[n].stderr:.2g}")
                for n in ("a", "b", "dc", "stiffness") if n in est), highlight=False)
        for line in levels_lines(res.levels):
            out.print(line, highlight=False, soft_wrap=True)
        if res.stiffness is not None:
            k = res.stiffness
            n_load = sum(ld["used"] for ld in k.get("loadings", []))
            out.print(f"one machine: k = {k['value']:.4g} /m [{k['lo']:.4g}, {k['hi']:.4g}] "
                      f"(95 %, steps {', '.join(map(str, k['steps'])) or 'none'}"
                      + (f", {n_load} elastic loading(s)" if n_load else "") + ")",
                      highlight=False)
        for c in (res.drive or {}).get("changes", []):
            out.print(f"measured drive: change at {c['t_change']:.6g} s +- "
                      f"{c['sigma_t_change']:.2g} s (given {c['t_given']:.6g} s), "
                      f"{c['v_before']:.4g} -> {c['v_after']:.4g} m/s", highlight=False,
                      soft_wrap=True)
        for c in (res.drive or {}).get("comparison", []):
            m, p = c["measured"], c["program"]
            if "not_run" in p:
                continue
            out.print(f"step {c['index']}: measured drive k = {_cell(m['stiffness'])} /m, "
                      f"a = {_cell(m['a'])}; program drive k = {_cell(p['stiffness'])} /m, "
                      f"a = {_cell(p['a'])} (rms {_cell(m['rms'])} against "
                      f"{_cell(p['rms'])})", highlight=False, soft_wrap=True)
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
                for n, p in f["parameters"].items()) + f"; {verdicts.get(f['step'])}",
                highlight=False, soft_wrap=True)
        out.print(f"wrote {out_dir}/fit.json, steps.csv"
                  + (f", step_*.{fmt}, steps_summary.{fmt}, record.{fmt}, segments.csv"
                     if figure else ""), highlight=False)
        out.print(flagged_line(res.rows), highlight=False)
    if not res.success:
        err.print("[bold red]a step's fit did not succeed[/] (see the notes)", highlight=False)
        raise typer.Exit(1)
