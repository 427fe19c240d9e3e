"""app.fit's check of the files it is given (a second new user's trial): a file given twice
is refused, not fitted as twice the data (every interval narrowed by sqrt 2); a laboratory
record given with the project's CSV files is refused as a record fitted alone, not as a CSV
file with missing columns. Both in one line naming the files, before any work (no folder)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

import dryfriction.app.fitting as fitting
from dryfriction import app
from dryfriction.records.data import read_csv

ROOT = Path(__file__).resolve().parents[2]
CSV = ROOT / "examples" / "data" / "synthetic_steady_paper.csv"


@pytest.fixture
def calls(monkeypatch: pytest.MonkeyPatch) -> list[Any]:
    seen: list[Any] = []
    monkeypatch.setattr(fitting, "fit_data", lambda paths, out, **kw: seen.append(paths))
    return seen


def _record(tmp_path: Path) -> Path:
    p = tmp_path / "r.txt"
    p.write_text("Time (min)\tLP_disp (mm)\tFriction\n" +
                 "".join(f"{0.01 * i:.2f}\t{0.003 * i:.3f}\t0.6\n" for i in range(30)))
    return p


def test_a_file_given_twice_is_refused_by_name(tmp_path: Path, calls: list[Any]) -> None:
    # mistake: the files taken as given (the same rows fitted twice, intervals narrowed)
    out = tmp_path / "o"
    with pytest.raises(ValueError, match=r"synthetic_steady_paper\.csv: the same file is "
                                         r"given more than once"):
        app.fit([CSV, CSV], out)
    # another spelling of the same file is the same file
    other = CSV.parent / ".." / "data" / CSV.name
    with pytest.raises(ValueError, match=r"given more than once"):
        app.fit([CSV, other], out)
    assert not out.exists() and calls == []
    # a copy is another file: fitted (the user's choice)
    copy = tmp_path / "copy.csv"
    copy.write_bytes(CSV.read_bytes())
    app.fit([CSV, copy], out)
    assert calls == [[CSV, copy]]


def test_a_record_with_csv_files_is_refused_as_fitted_alone(tmp_path: Path,
                                                            calls: list[Any]) -> None:
    # mistake: the record read as a CSV file ("missing columns: need one of (t, v_load, ...")
    rec = _record(tmp_path)
    out = tmp_path / "o"
    for paths in ([rec, CSV], [CSV, rec]):
        with pytest.raises(ValueError) as exc:
            app.fit(paths, out)
        msg = str(exc.value)
        assert msg.startswith(f"{rec} is a laboratory record, and a record is fitted alone")
        assert str(CSV) in msg and "\n" not in msg
    assert not out.exists() and calls == []
    # a broken CSV file among several keeps the CSV reader's own refusal
    bad = tmp_path / "bad.csv"
    bad.write_text("V[um/s],friction\n1,0.6\n")
    with pytest.raises(ValueError, match=r"bad\.csv, line 1: missing columns"):
        read_csv(bad)
    app.fit([CSV, bad], out)  # routed to the data fit (replaced here), which refuses it
    assert calls == [[CSV, bad]]


class _Stop(Exception):
    pass


def test_a_semicolon_csv_is_fitted_as_ours_and_said(tmp_path: Path) -> None:
    # mistake: the reading chosen in silence (a ';' file might have been meant otherwise);
    # the note said for a comma file too
    semi = tmp_path / "semi.csv"
    semi.write_text("V[um/s];mu_d\n0,25;0,6113\n2,5;0,6021\n25;0,5987\n")
    comma = tmp_path / "comma.csv"
    comma.write_text("V[um/s],mu_d\n0.25,0.6113\n2.5,0.6021\n25,0.5987\n")
    notes: list[str] = []

    def stop() -> None:  # after the reading and its notes, before the fit
        raise _Stop

    for p in (semi, comma):
        with pytest.raises(_Stop):
            fitting.fit_data([p], tmp_path / "o", report=notes.append, on_start=stop)
    assert notes == [f"note: {semi}: read as the project's CSV with ';' separators and "
                     "decimal commas"]
