"""app.record called directly (issue 25): the report's every entry against the record it was
given (a clock that starts at 5 s, a program with an up-step, a hold and a down-step given by
hand), the --segments form that reads back to the same program, segments.csv's columns by
their definitions, the apparatus note without its prefix, and a record without steps."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

from dryfriction import app
from dryfriction.records.lab import parse_segments

PROGRAM = "0:1e-06,15:3e-06,25:0,30:7e-07"  # s from the first sample : m/s


def _write(path: Path, disp_header: str = "Displ(um)", scale: float = 1e6) -> Path:
    t = 5.0 + 0.1 * np.arange(400)  # the record's own clock, from 5 s
    v = np.select([t < 20.0, t < 30.0, t < 35.0], [1e-6, 3e-6, 0.0], 7e-7)
    x = np.concatenate([[0.0], np.cumsum(v[:-1] * 0.1)])
    mu = 0.6 + 0.001 * np.sin(t)
    with path.open("w") as fh:
        fh.write(f"Time(s)\t{disp_header}\tFriction\n")
        for a, b, c in zip(t, x * scale, mu, strict=True):
            fh.write(f"{a:.6f}\t{b:.9f}\t{c:.6f}\n")
    return path


def test_the_report_of_a_given_program(tmp_path: Path) -> None:
    path = _write(tmp_path / "r.txt")
    done = app.record(path, segments=PROGRAM, out=tmp_path / "out")
    rep = done.report
    assert rep["source"] == str(path) and rep["rows"] == 400 and rep["first_line"] == 2
    assert rep["time_span_s"] == pytest.approx([5.0, 44.9], abs=1e-9)  # first, last: not span
    assert rep["columns"]["disp"] == {"header": "Displ(um)", "unit": "um"}
    assert rep["columns"]["mu"] == {"header": "Friction", "unit": ""}
    assert rep["segments_from"] == "--segments" and done.detection is None
    assert "resets_s" not in rep and "apparatus_note" not in rep and done.note == ""
    # the program on the record's clock: starts at 5 + the given offsets
    starts = [s["t_start"] for s in rep["segments"]]
    assert starts == pytest.approx([5.0, 20.0, 30.0, 35.0], abs=1e-9)
    assert [s["velocity"] for s in rep["segments"]] == [1e-6, 3e-6, 0.0, 7e-7]
    assert [s["i_start"] for s in rep["segments"]] == [0, 150, 250, 300]
    assert rep["segments"][-1]["i_end"] == 400
    # the --segments form, from the first sample, reads back to the same program
    assert rep["segments_option"] == PROGRAM
    again = parse_segments(rep["segments_option"], done.record)
    assert [(s.t_start, s.velocity) for s in again] == [(s.t_start, s.velocity)
                                                         for s in done.segments]
    # the steps: the up-step, and the reslide after the hold (its duration)
    assert [(w["v_before"], w["v_after"]) for w in rep["steps"]][:1] == [(1e-6, 3e-6)]
    assert rep["steps"][0]["t_change"] == pytest.approx(20.0, abs=1e-9)
    assert rep["units"]["time_span_s"] == "s"
    # segments.csv, column by column against the segments
    assert done.files == ["record.png", "segments.csv"] and done.out == tmp_path / "out"
    lines = (tmp_path / "out" / "segments.csv").read_text().splitlines()
    assert lines[0] == f"# --segments {PROGRAM}"
    rows = list(csv.DictReader(lines[1:]))
    assert [r["kind"] for r in rows] == ["start", "step", "hold", "step"]
    for r, s in zip(rows, done.segments, strict=True):
        assert float(r["t_start[s]"]) == pytest.approx(s.t_start, abs=1e-9)
        assert float(r["t_from_first[s]"]) == pytest.approx(s.t_start - 5.0, abs=1e-9)
        assert float(r["duration[s]"]) == pytest.approx(s.t_end - s.t_start, abs=1e-9)
        assert float(r["velocity_um[um/s]"]) == pytest.approx(s.velocity * 1e6, rel=1e-9)
        assert int(r["samples[1]"]) == s.i_end - s.i_start
    assert (tmp_path / "out" / "record.png").stat().st_size > 0


def test_a_unitless_displacement_gets_its_note_and_one_segment_no_steps(tmp_path: Path) -> None:
    # micrometres written without a unit: read as metres, 3 m/s: the note, said as soon as
    # known and kept in the report without its "warning: " prefix (fixE: louder, as the span
    # of 44 m is no friction apparatus')
    path = _write(tmp_path / "r.txt", "Displ", 1e6)
    heard: list[str] = []
    done = app.record(path, segments="0:3", on_note=heard.append)
    assert len(heard) == 1 and heard[0].startswith("warning: ")
    assert done.note == heard[0]
    assert done.report["apparatus_note"] == heard[0].removeprefix("warning: ")
    assert done.report["units_assumed"] == {"disp": "m"}
    assert done.report["units_implausible"] is True
    assert "--columns disp=Displ:um" in done.note
    one = app.record(_write(tmp_path / "s.txt"), segments="0:1e-6")
    assert one.steps == () and "no_steps" in one.report and one.files == []


def test_segments_csv_of_a_force_record_gives_the_force_in_kn(tmp_path: Path) -> None:
    # mistake (blind set 5, app_segments_csv_unit_dropped): the record's normal unit not passed
    # from `record --out` to segments.csv, which then reads a force in N as a stress in Pa
    # (normal_stress[MPa] = 3.7e-3 instead of normal_force[kN] = 3.7)
    path = _write(tmp_path / "r.txt")
    lines = path.read_text().splitlines()
    force = 3.7 + 0.01 * np.cos(np.arange(len(lines) - 1))  # kN
    path.write_text("\n".join([lines[0] + "\tNormal_force(kN)"]
                              + [f"{ln}\t{f:.6f}" for ln, f in zip(lines[1:], force,
                                                                      strict=True)]) + "\n")
    for given in (None, PROGRAM):  # detected, and given with --segments
        out = tmp_path / f"out{given is None}"
        done = app.record(path, segments=given, out=out)
        assert done.record.normal_unit == "N" and len(done.segments) == 4
        rows = list(csv.DictReader((out / "segments.csv").read_text().splitlines()[1:]))
        assert "normal_force[kN]" in rows[0] and not any("normal_stress" in k for k in rows[0])
        for r, s in zip(rows, done.segments, strict=True):
            want = float(np.mean(force[s.i_start:s.i_end]))
            assert float(r["normal_force[kN]"]) == pytest.approx(want, rel=1e-4)
