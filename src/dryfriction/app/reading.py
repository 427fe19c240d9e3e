"""The ``record`` workflow: what a laboratory record holds, as the reader and the step finder
see it (:func:`record`); it writes only with ``out`` (record.png and segments.csv). Moved here
from the command line."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .options import OPTIONS

__all__ = ["record", "RecordOutcome"]

_O = {k: o.default for k, o in OPTIONS["record"].items()}


@dataclass
class RecordOutcome:
    """A laboratory record as read (``dryfriction record``).

    Attributes
    ----------
    report : dict
        What ``--json`` prints: source, rows, columns and units, the load program
        (``segments``; ``segments_from`` "detected" or "--segments"), the steps, what the step
        finder found (resets, rate changes, gaps, normal-stress changes, in s), the program
        as a ``--segments`` value, and ``no_steps`` where the record cannot be cut into steps.
    record : dryfriction.records.record.LabRecord
        The record read.
    segments : list
        Its load program.
    steps : tuple
        The step windows (empty where ``report["no_steps"]`` says why).
    detection : dryfriction.records.detection.Detection or None
        The step finder's result (``None`` where ``segments`` was given).
    note : str
        A note on the record's units or apparatus ("" if none).
    out : Path or None
        The folder record.png and segments.csv were written into.
    files : list of str
        Those files, by name.
    """

    report: dict[str, Any]
    record: Any
    segments: list[Any]
    steps: tuple[Any, ...]
    detection: Any = None
    note: str = ""
    out: Path | None = None
    files: list[str] = field(default_factory=list)


def _changes(changes: Any) -> list[dict[str, float]]:
    """``(time, before, after)`` normal-stress changes as JSON objects (s; Pa or N)."""
    return [{"t_normal_change": t, "normal_before": b, "normal_after": a}
            for t, b, a in changes]


def record(path: str | Path, *, columns: str | None = _O["columns"],
           segments: str | None = _O["segments"], out: str | Path | None = _O["out"],
           force: bool = _O["force"], report: Callable[[str], None] | None = None,
           on_note: Callable[[str], None] | None = None) -> RecordOutcome:
    """Read a laboratory record, detect its load program (from the load-point displacement
    against the apparatus' own fluctuations, or take ``segments``) and cut it into steps
    (``dryfriction record``; :mod:`dryfriction.records.lab`).

    Parameters
    ----------
    path : path
        The record: a text table with a header line, units in (...) or [...].
    columns : str, optional
        A column map, ``time=Time,disp=LP_disp:mm,mu=Friction`` (``--columns``).
    segments : str, optional
        The load program instead of detecting it (``--segments``).
    out : path, optional
        Also write record.png and segments.csv here (whole or not at all).
    force : bool
        Write beside files not ours (kept).
    report : callable, optional
        ``report(line)`` for what was done to files already in ``out``.
    on_note : callable, optional
        ``on_note(line)`` with the note on the record's units or apparatus, as soon as it is
        known (before a refusal of a record without steps).

    Raises
    ------
    ValueError
        A record in which no velocity change stands above the fluctuations (give its program
        with ``segments``); a bad column map, program or folder.
    """
    from ..io.files import check_output_dir, output_directory
    from ..io.units import RECORD_UNITS, with_units
    from ..records.lab import (
        apparatus_note,
        assumed_units,
        backwards_message,
        detect_program,
        held_back_message,
        no_change_message,
        normal_change_values,
        note_text,
        parse_column_map,
        parse_segments,
        read_record,
        segments_spec,
        slice_steps,
    )
    from .records import write_record_files

    # checked as given: Path("") is "." (an empty --out must be refused, not the working folder)
    out_dir = (check_output_dir(out, force=force, command="record") if out is not None
               else None)
    rec = read_record(path, parse_column_map(columns) if columns else None)
    det = None if segments is not None else detect_program(rec)
    segs = parse_segments(segments, rec) if segments is not None else det.segments  # type: ignore[union-attr]
    note = apparatus_note(rec, [s.velocity for s in segs], given=segments is not None)
    if note and on_note is not None:
        on_note(note)
    if det is not None and len(segs) == 1 and segs[0].velocity != 0.0:
        raise ValueError(no_change_message(rec, det))
    try:
        steps = tuple(slice_steps(rec, segs, given=segments is not None))
        no_steps = ""
    except ValueError as exc:  # worth showing, not an error of this read-only workflow
        steps, no_steps = (), str(exc)
    t = rec.time
    rep: dict[str, Any] = {
        "source": rec.source,
        "rows": len(rec),
        "first_line": rec.first_line,
        "time_span_s": [float(t[0]), float(t[-1])],
        "columns": {role: {"header": h, "unit": rec.units.get(role, "")}
                    for role, h in rec.columns.items()},
        "segments_from": "--segments" if segments is not None else "detected",
        "segments": [vars(s) for s in segs],
        # a hold's normal-stress changes as objects (time and stresses have different units)
        "steps": [{**vars(w), "normal_changes": _changes(w.normal_changes)} for w in steps],
    }
    if no_steps:
        rep["no_steps"] = no_steps
    if rec.notes:  # what the reader skipped or dropped (a preamble, rows with a missing value)
        rep["reading_notes"] = list(rec.notes)
    if note:
        rep["apparatus_note"] = note_text(note)
    if assumed_units(rec):  # what the reader assumed, by column, and whether it is plausible
        rep["units_assumed"] = assumed_units(rec)
        rep["units_implausible"] = note.startswith("warning: ")
    if det is not None:
        rep["resets_s"] = list(det.resets)
        rep["rate_changes_s"] = list(det.rate_changes)
        rep["gaps_s"] = list(det.gaps)
        rep["normal_changes_s"] = list(det.normal_changes)
        rep["normal_changes"] = _changes(normal_change_values(segs, det.normal_changes))
        back = held_back_message(det, float(t[0]))
        if back:  # said where the user reads: the table's notes, the JSON, segments.csv
            rep["held_back"] = [{"t_start": a, "velocity_read": v} for a, v in det.held_back]
            rep["held_back_note"] = back
        backwards = backwards_message(segs, float(t[0]))
        if backwards:
            rep["backwards_note"] = backwards
    rep["segments_option"] = segments_spec(segs, float(t[0]), t)
    rep = with_units(rep, RECORD_UNITS, {"normal": rec.normal_unit or "Pa"})
    files: list[str] = []
    if out_dir is not None:
        with output_directory(out_dir, command="record", force=force, inputs=[rec.source],
                              report=report) as tmp:
            write_record_files(tmp, rec, segs, det, given=segments is not None)
        files = ["record.png", "segments.csv"]
    return RecordOutcome(rep, rec, list(segs), steps, det, note or "", out_dir, files)
