"""``dryfriction fit RECORD.txt``: a laboratory record read as it comes, its load
program detected, cut into steps and each step fitted with rate-and-state friction on an
elastic machine with a trend (:func:`dryfriction.fit.steps.fit_steps`); the trap model beside
it on request (``run_cv``). Moved here from the command line."""

from __future__ import annotations

import contextlib
import math
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from .options import OPTIONS
from .outcome import RecordFitOutcome

__all__ = ["fit_record", "cv_cost", "CV_CALLS_PER_STEP", "write_record_files"]

_D = {k: o.default for k, o in OPTIONS["fit"].items()}
Bar = Callable[..., Any]
"""A progress-bar factory. ``bar(label, total, unit)`` gives a context manager yielding
``update(done, total=None, what=None)``."""


@contextlib.contextmanager
def _no_bar(label: str, total: float | None = None, unit: str = "") -> Iterator[Any]:
    yield lambda done, total=None, what=None: None


def _say(report: Callable[[str], None] | None, line: str) -> None:
    if report is not None:
        report(line)


CV_CALLS_PER_STEP = 91
"""Forward runs of the trap model for one step of a record
(:func:`dryfriction.fit.cvsteps.fit_cv_steps`: the batched search of
:func:`~dryfriction.fit.cvsteps.search_step`, then one evaluation for the result and covariance,
runs read back from the memory of past runs not counted), for the cost estimate; counted on the
shared sepiolite record with the direct effect free (91 runs; 74 with A = 0: ``python -m
benchmarks bench_cv_record``). It was 130 before the windowed search
(:func:`dryfriction.fit.cvsteps.search_step`), when the estimate ran 2.2 times over the
measured CPU."""


def cv_cost(pieces: list[Any], alpha: float, creep: str, direct: float = 0.0,
            v_ref: float = 1e-6, traps_per_a0: float | None = None) -> float:
    """Seconds a trap-model fit of the steps would take: one forward run of the first window
    at its data-driven start, as the record fit runs it
    (:func:`dryfriction.fit.cvsteps.record_cv_model`), timed (CPU time: on a shared machine
    the wall clock counts the others' work), scaled to all windows by their durations and
    times :data:`CV_CALLS_PER_STEP` a window (so the estimate costs one run, not a fit)."""
    from ..fit.cvsteps import RECORD_TRAPS_PER_A0, record_cv_model
    from ..theory.model import TrapModel

    first = pieces[0]
    m = record_cv_model(TrapModel(alpha, creep=creep, direct=direct), v_ref,
                        traps_per_a0 or RECORD_TRAPS_PER_A0)
    guess = m.guesses([first])[0]
    t0 = time.process_time()
    try:
        m.predict(guess, first)
    except ValueError:  # the start is too long to simulate: the fit would be longer still
        return math.inf
    span = sum(float(p.t[-1] - p.t[0]) for p in pieces) / max(float(first.t[-1] - first.t[0]),
                                                             1e-300)
    return (time.process_time() - t0) * span * CV_CALLS_PER_STEP


def sign_note(rec: Any) -> str | None:
    """The line ``record.png``'s title carries when the load point's column was read with its
    sign changed (:attr:`LabRecord.sign_changed`), else ``None``: the figure draws the program
    forward, and a user comparing it with the file must see why (stop 50's note: only
    segments.csv and the terminal said it)."""
    if not rec.sign_changed:
        return None
    role = "disp" if rec.load_point is not None else "velocity"
    word = "displacement" if role == "disp" else "velocity"
    return (f"note: the load point's {word} column ({rec.columns[role]}) read with its sign "
            "changed (its net motion in the file is backwards)")


def write_record_files(folder: Path, rec: Any, segs: Any, det: Any, *, given: bool,
                       fmt: str = "png", dpi: int | None = None) -> None:
    """record.{fmt} and segments.csv into ``folder`` (a staging folder): the record as the
    step finder saw it (``dryfriction record --out``, and beside a record's fit)."""
    from ..plots.record import plot_record
    from ..plots.style import save_figure
    from ..records.lab import (
        apparatus_note,
        assumed_units,
        backwards_message,
        held_back_message,
        write_segments_csv,
    )

    # a unit assumed for want of one in the header is said in these files too: they are
    # what a user keeps of the detection (a new user's mm column read as m)
    note = apparatus_note(rec, [s.velocity for s in segs], given=given)
    assumed = assumed_units(rec)
    short = None if not assumed else (
        ("warning" if note and note.startswith("warning") else "note")
        + ": no unit in the header: " + ", ".join(f"{rec.columns[r]!r} read in {u}"
                                                  for r, u in assumed.items())
        + " (give the units with --columns ROLE=NAME:UNIT if not)")
    t0 = float(rec.time[0])
    back = held_back_message(det, t0) if det is not None else None
    backwards = backwards_message(segs, t0) if det is not None else None
    # the reading's notes too (a sign changed, a preamble skipped): what a user keeps
    write_segments_csv(folder / "segments.csv", segs, t0, rec.normal_unit, rec.time,
                       notes=tuple(q for q in (note, *rec.notes, back, backwards) if q))
    fig, _ = plot_record(rec, segs, det, given=given,
                         note="\n".join(q for q in (sign_note(rec), short) if q) or None)
    save_figure(fig, folder / f"record.{fmt}", fmt, dpi)


def fit_record(path: str | Path, out: str | Path, *, model: str = "rsf",
               columns: str | None = _D["columns"], segments: str | None = _D["segments"],
               stiffness: float | str = "record", trend: bool = True,
               law: str = _D["state_law"], joint: bool = _D["joint"],
               profile: bool | None = _D["profile"], run_cv: bool = _D["run_cv"],
               alpha: float = _D["alpha"], creep: str = _D["creep"],
               force: bool = _D["force"], fmt: str = _D["fmt"], dpi: int | None = _D["dpi"],
               figure: bool = _D["figure"], errors: str = _D["errors"],
               direct: float = _D["direct"], v_ref: float = _D["v_ref"],
               traps_per_a0: float | None = _D["traps_per_a0"], drive: str = _D["drive"],
               initial: str = _D["initial_state"], bar: Bar | None = None,
               report: Callable[[str], None] | None = None,
               on_start: Callable[[], None] | None = None,
               on_program: Callable[[list[Any], Any], None] | None = None) -> RecordFitOutcome:
    """Read one laboratory record, detect its load program, cut it into steps, fit each with
    rate-and-state on an elastic machine with a trend, and write fit.json, steps.csv and the
    figures (``dryfriction fit RECORD``; module docstring).

    Parameters
    ----------
    path : path
        The record (any text table, .xlsx, .mat: :func:`dryfriction.records.lab.read_record`).
    out : path
        Results folder: new, empty, or written by this program before.
    stiffness : float or str
        The machine: ``"record"`` (default: its one machine), ``"fit"``, ``"slope"`` or a
        number (1/m) (``--stiffness``, :func:`dryfriction.app.fitting.parse_stiffness`).
    trend : bool
        A linear trend in load-point displacement (``--trend``; default on for a record).
    law : str
        The state law, or ``auto`` (``--state-law``).
    initial : str
        ``--initial-state``: steady, free or auto.
    bar : callable, optional
        A progress-bar factory ``progress(label, total, unit)``, a context manager yielding
        ``update(done, total=None, what=None)`` (the command line's
        :func:`dryfriction.cli.common.progress_bar`).
    report : callable, optional
        ``report(line)``: a note on the record's units, said before the fit, and what was done
        to files already in ``out``.
    on_start : callable, optional
        Called after every check, before the record is read.
    on_program : callable, optional
        ``on_program(segments, record)``: the load program, before the fit (the command
        prints it).
    model, columns, segments, joint, profile, run_cv, alpha, creep, force
        As :func:`dryfriction.app.fitting.fit` (:data:`dryfriction.app.options.OPTIONS`).
    fmt, dpi, figure, errors, direct, v_ref, traps_per_a0, drive
        As :func:`dryfriction.app.fitting.fit` (:data:`dryfriction.app.options.OPTIONS`).

    Returns
    -------
    RecordFitOutcome
        ``success`` False: a step's fit did not succeed (see the notes; the command exits 1).

    Raises
    ------
    ValueError
        An option out of range, a record without a velocity step, ``model="cv"`` without
        ``run_cv`` (with the estimated cost of the trap model on this record).
    """
    from ..io.files import check_output_dir
    from ..validation import check_figure_format
    from .checks import check_fit_options

    fmt, dpi = check_figure_format(fmt, dpi)
    check_fit_options(alpha=alpha, creep=creep, v0=None, state_law=law, errors=errors,
                      traps_per_a0=traps_per_a0, direct=direct, v_ref=v_ref)
    path = Path(path)
    bar = bar or _no_bar
    from ..fit import compare_models
    from ..fit.cvsteps import RECORD_TRAPS_PER_A0, fit_cv_steps, record_cv_model
    from ..fit.experiment import default_profile
    from ..fit.lawchoice import INITIAL_CHOICES, fit_steps_laws
    from ..fit.steps import (
        ERRORS,
        robust_estimates,
        step_covariance,
        step_data,
        write_steps_csv,
    )
    from ..io.files import output_directory, write_json
    from ..io.units import RECORD_FIT_UNITS, with_units
    from ..records import lab
    from ..theory.model import TrapModel
    from ..validation import check_choice

    check_choice("errors", errors, ERRORS)
    from ..fit.loadpoint import check_drive

    check_drive(drive)  # before any work
    check_choice("--initial-state", initial, INITIAL_CHOICES)
    check_output_dir(out, force=force, command="fit")
    if on_start is not None:
        on_start()
    rec = lab.read_record(path, lab.parse_column_map(columns) if columns else None)
    det = None if segments is not None else lab.detect_program(rec)
    segs = lab.parse_segments(segments, rec) if segments is not None else det.segments  # type: ignore[union-attr]
    for line in rec.notes:  # a preamble skipped, rows with a missing value dropped
        _say(report, f"note: {line}")
    note = lab.apparatus_note(rec, [s.velocity for s in segs], given=segments is not None)
    if note:  # before the fit: a record of micrometres read as metres fits for minutes
        _say(report, note)
    if det is not None and len(segs) == 1 and segs[0].velocity != 0.0:
        raise ValueError(lab.no_change_message(rec, det))
    back = lab.held_back_message(det, float(rec.time[0])) if det is not None else None
    if back:
        _say(report, f"note: {back}")
    backwards = lab.backwards_message(segs, float(rec.time[0])) if det is not None else None
    if backwards:  # before any work: the fits take a program forward or held
        raise ValueError(f"{path}: {backwards}")
    wins = lab.slice_steps(rec, segs, given=segments is not None)
    if not wins:
        raise ValueError(f"{path}: no velocity step to fit: the detected load program is one "
                         "constant velocity (give it with --segments if it is not)")
    if on_program is not None:
        on_program(segs, rec)
    profile, profile_note = default_profile(len(wins), profile)  # many steps: HAC unless asked
    if model == "cv" and not run_cv:  # the trap model is not run unasked (issue 10)
        # the estimate is one trap-model run: made only when the trap model was asked for
        # (on the shared record it costs several times the whole rsf fit)
        cost = cv_cost(step_data(rec, wins, segs), alpha, creep, direct, v_ref, traps_per_a0)
        raise ValueError(f"{path}: the trap model (cv) on this record would take about "
                         f"{cost:.3g} s CPU for {len(wins)} step(s), against seconds for rsf: "
                         "drop --model (a record is fitted with rsf) and add --run-cv "
                         "[--direct A] to fit both and compare")
    from ..fit.laws import FIT_LAWS

    laws = FIT_LAWS if law == "auto" else (law,)
    with bar(f"fitting steps ({' and '.join(laws)} law{'s' if len(laws) > 1 else ''})",
             len(wins) * len(laws), unit="fits") as update:
        # one machine (stiffness "record"), the law (or every law: auto) and the initial state
        res = fit_steps_laws(rec, wins, segs, law=law, initial=initial, stiffness=stiffness,
                             trend=trend, joint=joint, profile=profile, errors=errors,
                             progress=update, drive=drive)
    if profile_note:
        res.notes.append(profile_note)
    for w, row in zip(wins, res.rows, strict=True):
        if w.normal_changes:  # said beside the step's values (terminal, fit.json)
            row["notes"].append(
                "the normal stress changed during its hold (" + lab.normal_change_text(
                    w.normal_changes, rec.normal_unit) + "); the hold is the whole time at "
                "rest, but friction is shear over normal stress and the rate-and-state fit "
                "has no normal-stress effect on the state (Linker & Dieterich 1992): a, b "
                "and Dc may be biased")
    if res.drive is not None and res.drive.get("kind") == "measured":
        if profile:  # the same rule as the profiles: a fit of its own per step
            from ..fit.steps import compare_with_program

            # how k and a depend on the drive: each step once more on the program (issue 30)
            res.drive["comparison"] = compare_with_program(res.data, res.fits, res.rows)
        else:
            res.notes.append("the measured drive's comparison with the program (each step "
                             "refitted on it) is left out with the profiles; --profile gives "
                             "both")
    doc: dict[str, Any] = {"record": str(path), "columns": list(rec.columns),
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
        doc["apparatus_note"] = lab.note_text(note)
    if lab.assumed_units(rec):  # what the reader assumed, by column, and whether plausible
        doc["units_assumed"] = lab.assumed_units(rec)
        doc["units_implausible"] = note.startswith("warning: ")
    if rec.notes:
        doc["reading_notes"] = list(rec.notes)
    if back:
        doc["held_back_note"] = back
    normal = next((r["normal_unit"] for r in res.rows if r.get("normal_unit")), "Pa")
    doc = with_units(doc, RECORD_FIT_UNITS, {"normal": normal})
    cv_results: dict[int, Any] = {}  # step -> the trap model's fit (--run-cv), for the figures
    if run_cv:
        comp: list[dict[str, Any]] = []
        cv_fits = []
        tpa = RECORD_TRAPS_PER_A0 if traps_per_a0 is None else traps_per_a0
        total = len(res.data) * CV_CALLS_PER_STEP
        with bar("cv fits", total, unit="runs") as update:
            runs = [0]

            def run_done() -> None:
                runs[0] += 1
                update(runs[0], max(total, runs[0]))

            for i, d in enumerate(res.data):
                update(runs[0], what=f"step {i + 1} of {len(res.data)}")
                try:
                    alt = fit_cv_steps([d], [res.fits[i]], record_cv_model(
                        TrapModel(alpha, creep=creep, direct=direct), v_ref, tpa,
                        progress=run_done))[0]
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
        doc["comparison"] = comp
        doc["cv_fits"] = cv_fits
    else:
        doc["comparison"] = {"not_run": "the trap model (cv) was not fitted: it costs "
                                           "minutes to hours a step; --model cv prints the "
                                           "estimate for this record, --run-cv fits it"}
    files = ["fit.json", "steps.csv"]
    with output_directory(out, command="fit", force=force, inputs=[path],
                          report=report) as tmp:
        write_json(tmp / "fit.json", doc)
        write_steps_csv(tmp / "steps.csv", res.rows)
        if figure:
            from ..plots.steps import plot_step, plot_steps_summary
            from ..plots.style import save_figure

            # what the step finder decided, as the record command draws it (issue 23)
            write_record_files(tmp, rec, segs, det, given=segments is not None, fmt=fmt, dpi=dpi)

            drawn = None
            for i in range(len(res.rows)):
                # the trap model beside rsf: one more forward run of its fit per step
                others = ({"trap model (cv)": cv_results[i].predict(res.data[i])}
                          if i in cv_results else None)
                # one figure redrawn step after step (its axes and ticks made once: about
                # half of a step figure's CPU; the same PNG bytes as a new figure's)
                drawn = plot_step(res, i, others=others, into=drawn)[0]
                save_figure(drawn, tmp / f"step_{i}.{fmt}", fmt, dpi)
            save_figure(plot_steps_summary(res)[0], tmp / f"steps_summary.{fmt}", fmt, dpi)
            files += [f"record.{fmt}", "segments.csv",
                      *(f"step_{i}.{fmt}" for i in range(len(res.rows))),
                      f"steps_summary.{fmt}"]
    return RecordFitOutcome(Path(out), files, doc, res, rec, list(segs), det,
                            lab.note_text(note) if note else None, fmt)
