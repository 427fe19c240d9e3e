"""The record command: what a laboratory record holds, as the reader and the step finder see it
(it writes only with --out: record.png and segments.csv). Parses, calls
:func:`dryfriction.app.reading.record`, prints."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Annotated

import typer

from ..app.options import OPTIONS
from ..io.files import to_jsonable
from .common import FORCE_HELP, app, cli_errors, say

COLUMNS_HELP = ("Name the columns the guesses miss: time=Time,disp=LP_disp:mm,mu=Friction "
                "(keys time, disp, velocity, mu, shear, normal; an optional :unit for a header "
                "without one).")
def _segments_help() -> str:
    from ..records.labsteps import SEGMENTS_SYNTAX

    return "Give the load program instead of detecting it. " + SEGMENTS_SYNTAX


SEGMENTS_HELP = _segments_help()
_O = OPTIONS["record"]


@app.command("record")
@cli_errors
def record_command(
    path: Annotated[Path, typer.Argument(help="Laboratory record: a text table with a header "
                                         "line, units in (...) or [...].")],
    columns: str = typer.Option(_O["columns"].default, "--columns", help=COLUMNS_HELP),
    segments: str = typer.Option(_O["segments"].default, "--segments", help=SEGMENTS_HELP),
    json_out: bool = typer.Option(False, "--json", help="Print the same as JSON."),
    out: str = typer.Option(_O["out"].default, "--out", help="Also write record.png (the "
                            "velocity with the load program on it, friction and normal "
                            "stress; each step and hold shaded and numbered as in the table) "
                            "and segments.csv into this folder."),
    force: bool = typer.Option(_O["force"].default, "--force", help=FORCE_HELP),
) -> None:
    """Show how a laboratory record is read: its columns and units, the load program (detected
    from the load-point displacement against the apparatus' own fluctuations, or --segments)
    and the steps it is cut into. A record in which no velocity change stands above the
    fluctuations is refused (exit 2): give its program with --segments."""
    from ..app.reading import record as run
    from ..records.lab import normal_change_text, normal_change_values, segments_table

    done = run(path, columns=columns, segments=segments, out=out, force=force, report=say,
               on_note=lambda line: print(line, file=sys.stderr))
    report, rec, segs, steps = done.report, done.record, done.segments, done.steps
    out_dir, no_steps, t = done.out, report.get("no_steps", ""), done.record.time
    if json_out:
        print(json.dumps(to_jsonable(report), indent=2))
        return
    print(f"{rec.source}: {len(rec):,} rows from line {rec.first_line}, t = {t[0]:g} .. "
              f"{t[-1]:g} s")
    assumed = report.get("units_assumed", {})
    for role, h in rec.columns.items():
        unit = rec.units.get(role, "") or ("-" if role == "mu" else "none")
        if role in assumed:  # what was assumed, and the entry that changes it
            unit += f": read in {assumed[role]} (--columns {role}={h}:UNIT if not)"
        print(f"  {role:<9} {h!r:<32} unit {unit}")
    for line in report.get("reading_notes", []):
        print(f"note: {line}")
    print(f"\nload program ({report['segments_from']}):")
    print(segments_table(segs, rec.normal_unit))
    print(f"as --segments: {report['segments_option']}")
    for key, what in (("resets_s", "displacement resets taken out"),
                      ("rate_changes_s", "sampling-rate changes"), ("gaps_s", "gaps")):
        if report.get(key):
            print(f"{what} at t = " + ", ".join(f"{v:g}" for v in report[key]) + " s")
    for key in ("held_back_note", "backwards_note"):
        if report.get(key):
            print(f"note: {report[key]}")
    if report.get("normal_changes_s"):  # with the stresses either side, as the table gives
        print("normal-stress changes (segment boundaries): " + normal_change_text(
            normal_change_values(segs, report["normal_changes_s"]), rec.normal_unit))
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
    for w in steps:
        if w.normal_changes:  # the hold runs across them: its duration is the time at rest
            print(f"step {w.index}: the normal stress changed during its hold, "
                  + normal_change_text(w.normal_changes, rec.normal_unit))

