"""fixE item 1 (a second new user's trial, problem 16): a record's column without a unit is
read as SI, and that is said where the user reads it (the ``record`` table and its JSON, the
note before and after a fit, fit.json), naming the column and the ``--columns ROLE=NAME:UNIT``
entry that changes it; where the SI reading leaves what friction apparatus do
(:data:`APPARATUS_V_TYPICAL`, :data:`APPARATUS_X_TYPICAL`) it is a louder warning naming the
units that would fit. The family: millimetres, micrometres and metres without a unit, a clock
in milliseconds, a velocity column, the unit given with ``--columns``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from dryfriction import app
from dryfriction.cli import main
from dryfriction.records.lab import (
    APPARATUS_V_TYPICAL,
    APPARATUS_X_TYPICAL,
    apparatus_note,
    assumed_units,
    detect_program,
    read_record,
)

# 0.3 um/s, then 3.7 um/s at 80 s (10 Hz, 150 s): a velocity step of a biaxial machine
V1, V2, T_CHANGE = 3e-7, 3.7e-6, 80.0


def _write(path: Path, length_factor: float, *, disp: str = "LP_disp", time: str = "Time",
           time_factor: float = 1.0) -> Path:
    """The step written with its displacement times ``length_factor`` (1e3: mm) and its
    clock times ``time_factor`` (1e3: ms), under the headers given (no unit unless named)."""
    rng = np.random.default_rng(7)
    t = 0.1 * np.arange(1500) + 12.0
    v = np.where(t - t[0] < T_CHANGE, V1, V2)
    x = np.concatenate([[0.0], np.cumsum(v[:-1] * 0.1)]) + rng.normal(0.0, 2e-9, t.size)
    mu = 0.62 + 0.004 * np.where(t - t[0] >= T_CHANGE,
                                 np.exp(-(t - t[0] - T_CHANGE) / 4.0), 0.0)
    with path.open("w") as fh:
        fh.write(f"{time}\t{disp}\tmu\n")
        for a, b, c in zip(t * time_factor, x * length_factor, mu, strict=True):
            fh.write(f"{a:.6f}\t{b:.10g}\t{c:.6f}\n")
    return path


def _note(path: Path, columns: dict[str, str] | None = None) -> tuple[str | None, dict[str, str]]:
    rec = read_record(path, columns)
    segs = detect_program(rec).segments
    return apparatus_note(rec, [s.velocity for s in segs]), assumed_units(rec)


def test_the_range_is_the_apparatus_one() -> None:
    # the numbers the notes quote: 1 nm/s to 1 mm/s, 5 cm (the docstrings' reasons)
    assert APPARATUS_V_TYPICAL == (1e-9, 1e-3) and APPARATUS_X_TYPICAL == 0.05


@pytest.mark.parametrize("unit, factor", [("mm", 1e3), ("um", 1e6)])
def test_a_length_without_its_unit_is_flagged_louder_with_the_unit_that_fits(
        tmp_path: Path, unit: str, factor: float) -> None:
    """mm or um read as m: velocities of 0.37 or 370 cm/s... a warning naming both the
    column and the entry that gives the record's own speeds back (3.7 um/s). Mistakes: no
    word at all (the user's run), the quiet note for an impossible reading, the suggestion
    scaled the wrong way (x 1e3 instead of 1e-3)."""
    note, assumed = _note(_write(tmp_path / f"{unit}.txt", factor))
    assert assumed == {"time": "s", "disp": "m"}
    assert note is not None and note.startswith("warning: "), note
    assert "'LP_disp' in metres" in note and "'Time' is read in seconds" in note
    assert f"--columns disp=LP_disp:{unit} gives up to 3.7 um/s over" in note
    assert "--columns time=Time:UNIT,disp=LP_disp:UNIT" in note
    # given its unit, the displacement is no longer named (the clock still is, quietly)
    note, assumed = _note(tmp_path / f"{unit}.txt", {"disp": f"LP_disp:{unit}"})
    assert assumed == {"time": "s"}
    assert note is not None and note.startswith("note: ") and "LP_disp" not in note
    assert "up to 3.7 um/s" in note


def test_metres_without_a_unit_get_the_quiet_note_and_si_written_out_none(
        tmp_path: Path) -> None:
    """A record truly in m and s: the assumption said, not flagged. Written out (:m, :s):
    nothing to say. Mistakes: the unit-less reading left unsaid when plausible (the old
    rule), a note for a record whose every unit is given."""
    path = _write(tmp_path / "m.txt", 1.0)
    note, assumed = _note(path)
    assert assumed == {"time": "s", "disp": "m"}
    assert note is not None and note.startswith("note: "), note
    assert "up to 3.7 um/s over" in note
    assert note.endswith("if a unit is another, give --columns time=Time:UNIT,disp=LP_disp:UNIT")
    assert _note(path, {"disp": "LP_disp:m", "time": "Time:s"}) == (None, {})


def test_a_clock_in_milliseconds_read_as_seconds(tmp_path: Path) -> None:
    # the velocities 1000 times too slow (3.7 nm/s and 0.3 nm/s: the top one in range, so
    # the span and the slowest decide nothing; a slower record: 0.37 nm/s at most)
    path = _write(tmp_path / "ms.txt", 1e-1, time_factor=1e3)  # 0.37 um/s as 0.37 nm/s
    note, _ = _note(path, {"disp": "LP_disp:m"})
    assert note is not None and note.startswith("warning: "), note
    assert "--columns time=Time:ms gives up to 370 nm/s" in note


def test_the_record_command_says_it_in_its_table_json_and_on_stderr(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _write(tmp_path / "mm.txt", 1e3)
    capsys.readouterr()
    assert main(["record", str(path)]) == 0
    out, err = capsys.readouterr()
    assert "unit none: read in m (--columns disp=LP_disp:UNIT if not)" in out
    assert "unit none: read in s (--columns time=Time:UNIT if not)" in out
    assert err.startswith("warning: ") and "--columns disp=LP_disp:mm" in err
    assert main(["record", str(path), "--json"]) == 0
    rep = json.loads(capsys.readouterr().out)
    assert rep["units_assumed"] == {"time": "s", "disp": "m"}
    assert rep["units_implausible"] is True
    assert rep["apparatus_note"].startswith(f"{path}: no unit in the header")
    done = app.record(_write(tmp_path / "m.txt", 1.0))
    assert done.report["units_implausible"] is False
    assert done.report["apparatus_note"].startswith(f"{tmp_path / 'm.txt'}: no unit")


@pytest.mark.slow
def test_a_fit_says_it_before_last_and_in_fit_json(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The warning before the fit (on stderr) and again as the last line, and fit.json's
    units_assumed, units_implausible and apparatus_note. Mistake: said only before the
    fit's pages of tables (the user's 1000-times-off Dc went unnoticed)."""
    path = _write(tmp_path / "mm.txt", 1e3)
    capsys.readouterr()
    code = main(["fit", str(path), "--out", str(tmp_path / "o"), "--no-figure",
                 "--no-profile"])
    out, err = capsys.readouterr()
    assert code in (0, 1), err
    lines = err.strip().splitlines()
    assert lines[0].startswith("warning: ") and lines[-1] == lines[0]
    doc = json.loads((tmp_path / "o" / "fit.json").read_text())
    assert doc["units_assumed"] == {"time": "s", "disp": "m"}
    assert doc["units_implausible"] is True
    assert "--columns disp=LP_disp:mm" in doc["apparatus_note"]


def test_the_files_a_user_keeps_say_it_too(tmp_path: Path) -> None:
    """``record --out``: segments.csv carries the note as a comment line under its
    ``--segments`` line (still read by ``read_rows``), and record.png's title a short form of
    it; a record whose units are all given gets neither. The mistake: the note said on the
    console only, so the files a user keeps of the detection read mm as m without a word."""
    from dryfriction.io.units import read_rows
    from dryfriction.plots import record as plots

    seen: list[str | None] = []
    real = plots.plot_record

    def spy(*args, **kw):  # the title's extra line, as drawn
        fig, info = real(*args, **kw)
        seen.append(fig._suptitle.get_text())
        return fig, info

    plots.plot_record = spy
    try:
        for name, disp, time, factor in (("mm.txt", "LP_disp", "Time", 1e3),
                                         ("um.txt", "LP_disp (um)", "Time (s)", 1e6)):
            path = _write(tmp_path / name, factor, disp=disp, time=time)
            out = tmp_path / f"out_{name}"
            assert main(["record", str(path), "--out", str(out)]) == 0
            lines = (out / "segments.csv").read_text().splitlines()
            assert lines[0].startswith("# --segments ")
            assert len(read_rows(out / "segments.csv")) == 2
            if "(" in disp:
                assert not lines[1].startswith("#")
                assert "no unit in the header" not in seen[-1]
            else:
                assert lines[1].startswith("# warning: ") and "'LP_disp'" in lines[1]
                assert "--columns disp=LP_disp:mm" in lines[1]
                assert ("warning: no unit in the header: 'Time' read in s, 'LP_disp' read in m"
                        in seen[-1])
    finally:
        plots.plot_record = real
