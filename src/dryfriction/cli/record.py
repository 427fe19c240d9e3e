"""The record command: what a laboratory record holds, as the reader and the step finder see it
(read-only: writes nothing)."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Annotated, Any

import typer

from ..io.files import to_jsonable
from .common import app, cli_errors

COLUMNS_HELP = ("Name the columns the guesses miss: time=Time,disp=LP_disp:mm,mu=Friction "
                "(keys time, disp, velocity, mu, shear, normal; an optional :unit for a header "
                "without one).")
SEGMENTS_HELP = ("Give the load program instead of detecting it: start:velocity items, the "
                 "start in s from the record's first sample, the velocity in m/s (0: hold), "
                 "e.g. 0:2e-7,1200:2e-6.")


@app.command("record")
@cli_errors
def record_command(
    path: Annotated[Path, typer.Argument(help="Laboratory record: a text table with a header "
                                         "line, units in (...) or [...].")],
    columns: str = typer.Option(None, "--columns", help=COLUMNS_HELP),
    segments: str = typer.Option(None, "--segments", help=SEGMENTS_HELP),
    json_out: bool = typer.Option(False, "--json", help="Print the same as JSON."),
) -> None:
    """Show how a laboratory record is read: its columns and units, the load program (detected
    from the load-point displacement, or --segments) and the steps it is cut into."""
    from ..io.lab import (
        apparatus_note,
        detect_segments,
        parse_column_map,
        parse_segments,
        read_record,
        segments_table,
        slice_steps,
    )

    rec = read_record(path, parse_column_map(columns) if columns else None)
    segs = parse_segments(segments, rec) if segments else detect_segments(rec)
    note = apparatus_note(rec, [s.velocity for s in segs], given=bool(segments))
    if note:
        print(note, file=sys.stderr)
    try:
        steps = slice_steps(rec, segs)
        no_steps = ""
    except ValueError as exc:  # worth showing, not an error of this read-only command
        steps, no_steps = (), str(exc)
    t = rec.time
    report: dict[str, Any] = {
        "source": rec.source,
        "rows": len(rec),
        "first_line": rec.first_line,
        "time_span_s": [float(t[0]), float(t[-1])],
        "columns": {role: {"header": h, "unit": rec.units.get(role, "")}
                    for role, h in rec.columns.items()},
        "segments_from": "--segments" if segments else "detected",
        "segments": [vars(s) for s in segs],
        "steps": [vars(w) for w in steps],
    }
    if no_steps:
        report["no_steps"] = no_steps
    if note:
        report["apparatus_note"] = note.removeprefix("note: ")
    if json_out:
        print(json.dumps(to_jsonable(report), indent=2))
        return
    print(f"{rec.source}: {len(rec):,} rows from line {rec.first_line}, t = {t[0]:g} .. "
              f"{t[-1]:g} s")
    for role, h in rec.columns.items():
        unit = rec.units.get(role, "") or ("-" if role == "mu" else "none: read as SI")
        print(f"  {role:<9} {h!r:<32} unit {unit}")
    print(f"\nload program ({report['segments_from']}):")
    print(segments_table(segs))
    if no_steps:
        print(f"\n{no_steps}")
        return
    print("\nsteps:")
    print(f"{'#':>3} {'kind':>5} {'t_change (s)':>13} {'v_before (um/s)':>16} "
              f"{'v_after (um/s)':>15} {'hold (s)':>9} {'samples':>16}")
    for w in steps:
        print(f"{w.index:>3} {w.kind:>5} {w.t_change:>13.6g} {w.v_before * 1e6:>16.4g} "
                  f"{w.v_after * 1e6:>15.4g} {w.hold:>9.4g} {w.i_start:>7d}-{w.i_end:<8d}")
