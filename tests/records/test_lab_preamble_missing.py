"""The reader on what a new user's lab files hold (userfixB, problem 9): a metadata block
above the header without ``#`` (instrument and spreadsheet exports), in every separator, with
a units row, with a line that names a column and with a line of numbers alone; and a few
missing values (empty cells, NaN, ``#N/A``) in the needed columns: those rows dropped and
counted, never filled; too many refused in one line saying how many and where."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dryfriction.records.lab import MISSING_MAX, read_record

N = 100
T = 3.0 + 0.25 * np.arange(N)  # s, from 3 s
X = 1.7 * (T - T[0])  # um
MU = 0.6 + 0.01 * np.sin(T)


def rows(sep: str, comma: bool = False) -> list[str]:
    out = [sep.join(f"{v:.6f}" for v in r) for r in zip(T, X, MU, strict=True)]
    return [r.replace(".", ",") for r in out] if comma else out


# (preamble lines, header, units row or None, separator, decimal comma)
CASES = {
    "instrument, tabs": (["Experiment p4966", "Operator: X", "Sample rate: 50 Hz"],
                         "Time (s)\tLP Displacement (um)\tFriction", None, "\t", False),
    "spreadsheet, commas": (["Experiment,p4966,", "Operator,X,", "Date,2026-11-20,"],
                            "Time[s],LP_disp[um],mu", None, ",", False),
    "semicolons, decimal commas": (["Versuch: p5123;;", "Probe: Gouge A;;"],
                                   "Time[s];Disp[um];Friction", None, ";", True),
    "spaces, a units row": (["p4966 SHS series", "operator X"], "Time Displ Friction",
                            "s um -", " ", False),
    "a line naming a column": (["Normal stress: 5 MPa", "Operator: X"],
                               "Time(s)\tDispl(um)\tFriction", None, "\t", False),
    "a line of numbers alone": (["Date", "2026 11 20", "Rig 2"],
                                "Time(s)\tDispl(um)\tFriction", None, "\t", False),
}


@pytest.mark.parametrize("case", CASES)
def test_a_preamble_without_hash_is_skipped_and_said_in_one_line(tmp_path: Path,
                                                                  case: str) -> None:
    # mistakes: the header taken as the first line (the reader before: "4 cells, the header
    # names 2"), as the last line above the data (the units row), the data taken to start at
    # one line of numbers ("2026 11 20"), the preamble skipped without a word
    pre, header, units, sep, comma = CASES[case]
    lines = [*pre, header, *([units] if units else []), *rows(sep, comma)]
    p = tmp_path / "rec.txt"
    p.write_text("\n".join(lines) + "\n", encoding="utf-8")
    r = read_record(p)
    h = len(pre) + 1
    assert r.first_line == h + 1 + (1 if units else 0)
    assert len(r) == N
    assert np.allclose(r.time, T) and np.allclose(r.load_point, X * 1e-6)
    assert np.allclose(r.friction, MU)
    assert r.units["disp"] == "um"
    (note,) = r.notes
    assert note.startswith(f"{p}: {len(pre)} line(s) above the header (line {h}) skipped as a "
                           f"preamble: {pre[0].strip()!r}"), note
    assert "\n" not in note


def test_a_plain_record_has_no_note_and_hash_comments_stay_comments(tmp_path: Path) -> None:
    p = tmp_path / "rec.txt"
    p.write_text("# p4966\n# 50 Hz\nTime(s)\tDispl(um)\tFriction\n" + "\n".join(rows("\t"))
                 + "\n")
    r = read_record(p)
    assert r.first_line == 4 and len(r) == N and r.notes == ()


def _with_cells(tmp_path: Path, cells: dict[int, tuple[int, str]], extra: bool = False) -> Path:
    """The record with cell (row -> column, text) replaced; ``extra``: a fourth column, unused,
    holding NaN in every other row."""
    body = []
    for i, r in enumerate(rows("\t")):
        c = r.split("\t")
        if i in cells:
            j, text = cells[i]
            c[j] = text
        if extra:
            c.append("NaN" if i % 2 else "1.5")
        body.append("\t".join(c))
    p = tmp_path / "rec.txt"
    p.write_text("Time(s)\tDispl(um)\tFriction" + ("\tTemp(C)" if extra else "") + "\n"
                 + "\n".join(body) + "\n")
    return p


def test_rows_with_a_missing_value_are_dropped_and_counted(tmp_path: Path) -> None:
    # mistakes: a missing value filled (0, the previous row, interpolated: N rows back), a row
    # dropped for a NaN in a column not used, the note's lines counted from the data (not
    # the file), the limit applied to the cells rather than the rows
    missing = {2: (2, "NaN"), 17: (1, ""), 18: (2, "#N/A"), 40: (0, "nan")}
    p = _with_cells(tmp_path, missing, extra=True)
    r = read_record(p)
    keep = np.array([i for i in range(N) if i not in missing])
    assert len(r) == N - len(missing)
    assert np.array_equal(r.time, T[keep])
    assert np.allclose(r.load_point, X[keep] * 1e-6) and np.allclose(r.friction, MU[keep])
    (note,) = r.notes
    assert note == (f"{p}: 4 of {N} data rows dropped for a missing value (empty, NaN) in a "
                    "needed column ('Time(s)' (column 1) 1, 'Displ(um)' (column 2) 1, "
                    "'Friction' (column 3) 2; lines 4, 19, 20, 42)")


def test_a_later_refusal_names_the_file_line_after_dropped_rows(tmp_path: Path) -> None:
    # rows 2 and 3 dropped: the time that does not increase (row 10) is still on line 12
    p = _with_cells(tmp_path, {2: (2, "NaN"), 3: (2, ""), 10: (0, f"{T[8]:.6f}")})
    with pytest.raises(ValueError, match=r"rec\.txt, line 12, column 1 .*does not increase"):
        read_record(p)


def test_too_many_missing_values_are_refused_in_one_line(tmp_path: Path) -> None:
    # at the limit (5 of 100 = 5 %) read; one more refused, naming how many and where
    at = int(MISSING_MAX * N)
    assert at == 5
    ok = read_record(_with_cells(tmp_path, {5 + 7 * k: (2, "NaN") for k in range(at)}))
    assert len(ok) == N - at
    p = _with_cells(tmp_path, {5 + 7 * k: (2, "") for k in range(at + 1)})
    with pytest.raises(ValueError) as exc:
        read_record(p)
    msg = str(exc.value)
    assert msg == (f"{p}, line 7, column 3 (Friction): 6 of {N} data rows have a missing "
                   "value (empty, NaN) in a needed column ('Friction' (column 3) 6; lines 7, "
                   "14, 21, 28, 35 ...): more than 5 % to drop: fill or remove them")


def test_without_a_recognised_name_the_line_above_the_data_is_the_header(
        tmp_path: Path) -> None:
    # no name the reader knows (German), a preamble and a units row: the refusal names the
    # header's line and its names (not the units row's), and --columns then reads it.
    # Mistake: the units row taken for the header ("found 's', 'um', '-'")
    lines = ["Versuch p5123", "Bediener: X", "Zeit\tWeg\tReibung", "s\tum\t-", *rows("\t")]
    p = tmp_path / "rec.txt"
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"rec\.txt, line 3: no time column: found 'Zeit', "
                                         r"'Weg', 'Reibung'"):
        read_record(p)
    r = read_record(p, {"time": "Zeit", "disp": "Weg", "mu": "Reibung"})
    assert r.first_line == 5 and r.units["disp"] == "um" and np.allclose(r.load_point, X * 1e-6)


def test_columns_named_make_their_line_the_header(tmp_path: Path) -> None:
    # a preamble line the reader takes for a name ("Time: 12:00") above a header it does not
    # know: the guess is that line (the refusal names it); --columns names the header's columns,
    # and the line holding them wins (docs/howto/record-formats.md)
    lines = ["Time: 12:00", "Zeit\tWeg(um)\tReibung", *rows("\t")]
    p = tmp_path / "rec.txt"
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"rec\.txt, line 3: 3 cells, the header \(line 1\) "
                       r"names 1: .*, or, if line 1 is not the header, name the header's "
                       r"columns with --columns$"):
        read_record(p)
    r = read_record(p, {"time": "Zeit", "disp": "Weg", "mu": "Reibung"})
    assert r.first_line == 3 and len(r) == N and np.allclose(r.load_point, X * 1e-6)
    assert r.notes == (f"{p}: 1 line(s) above the header (line 2) skipped as a preamble: "
                       "'Time: 12:00'",)
