"""The record command: what a laboratory record holds, as the reader and the step finder see it
(it writes only with --out: record.png and segments.csv)."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Annotated, Any

import typer

from ..io.files import to_jsonable
from .common import FORCE_HELP, app, cli_errors, say

COLUMNS_HELP = ("Name the columns the guesses miss: time=Time,disp=LP_disp:mm,mu=Friction "
                "(keys time, disp, velocity, mu, shear, normal; an optional :unit for a header "
                "without one).")
def _segments_help() -> str:
    from ..records.labsteps import SEGMENTS_SYNTAX

    return "Give the load program instead of detecting it. " + SEGMENTS_SYNTAX


SEGMENTS_HELP = _segments_help()


@app.command("record")
@cli_errors
def record_command(
    path: Annotated[Path, typer.Argument(help="Laboratory record: a text table with a header "
                                         "line, units in (...) or [...].")],
    columns: str = typer.Option(None, "--columns", help=COLUMNS_HELP),
    segments: str = typer.Option(None, "--segments", help=SEGMENTS_HELP),
    json_out: bool = typer.Option(False, "--json", help="Print the same as JSON."),
    out: str = typer.Option(None, "--out", help="Also write record.png (the velocity "
                                 "with the load program on it, friction and normal stress; "
                                 "each step and hold shaded and numbered as in the table) "
                                 "and segments.csv into this folder."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
) -> None:
    """Show how a laboratory record is read: its columns and units, the load program (detected
    from the load-point displacement against the apparatus' own fluctuations, or --segments)
    and the steps it is cut into. A record in which no velocity change stands above the
    fluctuations is refused (exit 2): give its program with --segments."""
    from ..io.files import check_output_dir
    out_dir = Path(out) if out is not None else None
    from ..records.lab import (
        apparatus_note,
        detect_program,
        no_change_message,
        parse_column_map,
        parse_segments,
        read_record,
        segments_spec,
        segments_table,
        slice_steps,
    )

    if out_dir is not None:
        check_output_dir(out_dir, force=force)
    rec = read_record(path, parse_column_map(columns) if columns else None)
    det = None if segments is not None else detect_program(rec)
    segs = parse_segments(segments, rec) if segments is not None else det.segments  # type: ignore[union-attr]
    note = apparatus_note(rec, [s.velocity for s in segs], given=segments is not None)
    if note:
        print(note, file=sys.stderr)
    if det is not None and len(segs) == 1 and segs[0].velocity != 0.0:
        raise ValueError(no_change_message(rec, det))
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
        "segments_from": "--segments" if segments is not None else "detected",
        "segments": [vars(s) for s in segs],
        "steps": [vars(w) for w in steps],
    }
    if no_steps:
        report["no_steps"] = no_steps
    if note:
        report["apparatus_note"] = note.removeprefix("note: ")
    if det is not None:
        report["resets_s"] = list(det.resets)
        report["rate_changes_s"] = list(det.rate_changes)
        report["gaps_s"] = list(det.gaps)
        report["normal_changes_s"] = list(det.normal_changes)
    report["segments_option"] = segments_spec(segs, float(t[0]))
    if out_dir is not None:
        write_record_outputs(out_dir, rec, segs, det, force=force, given=segments is not None)
    if json_out:
        print(json.dumps(to_jsonable(report), indent=2))
        return
    print(f"{rec.source}: {len(rec):,} rows from line {rec.first_line}, t = {t[0]:g} .. "
              f"{t[-1]:g} s")
    for role, h in rec.columns.items():
        unit = rec.units.get(role, "") or ("-" if role == "mu" else "none: read as SI")
        print(f"  {role:<9} {h!r:<32} unit {unit}")
    print(f"\nload program ({report['segments_from']}):")
    print(segments_table(segs, rec.normal_unit))
    print(f"as --segments: {report['segments_option']}")
    for key, what in (("resets_s", "displacement resets taken out"),
                      ("rate_changes_s", "sampling-rate changes"), ("gaps_s", "gaps"),
                      ("normal_changes_s", "normal-stress changes (segment boundaries)")):
        if report.get(key):
            print(f"{what} at t = " + ", ".join(f"{v:g}" for v in report[key]) + " s")
    if out_dir is not None:
        print(f"wrote {out_dir}/record.png, segments.csv")
    if no_steps:
        print(f"\n{no_steps}")
        return
    print("\nsteps:")
    print(f"{'#':>3} {'kind':>5} {'t_change (s)':>13} {'v_before (um/s)':>16} "
              f"{'v_after (um/s)':>15} {'hold (s)':>9} {'samples':>16}")
    for w in steps:
        print(f"{w.index:>3} {w.kind:>5} {w.t_change:>13.6g} {w.v_before * 1e6:>16.4g} "
                  f"{w.v_after * 1e6:>15.4g} {w.hold:>9.4g} {w.i_start:>7d}-{w.i_end:<8d}")


def write_record_outputs(out_dir: Path, rec: Any, segs: Any, det: Any, *, force: bool,
                         given: bool, command: str = "record", inputs: Any = None) -> None:
    """Write record.png and segments.csv into ``out_dir`` (whole or not at all)."""
    from ..app.records import write_record_files
    from ..io.files import output_directory

    with output_directory(out_dir, command=command, force=force,
                          inputs=inputs or [rec.source], report=say) as tmp:
        write_record_files(tmp, rec, segs, det, given=given)
