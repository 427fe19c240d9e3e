"""records/labforms.py: a spreadsheet with a metadata block above its header (a second new
user's ``rec.xlsx``: ``Experiment p9999``, ``Operator: me``, a blank row, then the header) is
read as the text reader reads such a block (the header = the row with the most recognised
names above the rows of numbers; the block skipped and said); a workbook of several sheets
says that the first is read, in its notes and in a refusal."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dryfriction.records.lab import read_record

openpyxl = pytest.importorskip("openpyxl")


def _book(path: Path, preamble: list[list[object]], first_sheet: str | None = None) -> Path:
    wb = openpyxl.Workbook()
    ws = wb.active
    if first_sheet is not None:  # a notes sheet first, the record on the second
        ws.title = first_sheet
        ws.append(["this sheet has notes"])
        ws = wb.create_sheet("data")
    for row in preamble:
        ws.append(row)
    ws.append(["time[s]", "LP_disp[mm]", "Friction"])
    for i in range(40):
        ws.append([3600.0 + 0.25 * i, 1e-5 + 2.5e-4 * i, 0.6 + 1e-3 * (i % 3)])
    wb.save(path)
    return path


def test_a_metadata_block_above_the_header_is_skipped_and_said(tmp_path: Path) -> None:
    # mistake: the first non-empty row taken as the header ("row 1: no time column: found
    # 'Experiment p9999'"); the rows numbered from the header rather than as the sheet does
    p = _book(tmp_path / "rec.xlsx", [["Experiment p9999"], ["Operator: me", None, "x 3"],
                                      [], ["Sample rate: 4 Hz", 4]])
    rec = read_record(p)
    assert rec.first_line == 6 and len(rec) == 40
    np.testing.assert_allclose(rec.time[:2], [3600.0, 3600.25])
    assert rec.units["disp"] == "mm"
    (note,) = rec.notes
    assert note == (f"{p}: 3 row(s) above the header (row 5) skipped as a preamble: "
                    "'Experiment p9999', 'Operator: me x 3', 'Sample rate: 4 Hz 4'")
    # without the block: no note, the header the first row
    q = _book(tmp_path / "plain.xlsx", [])
    rec = read_record(q)
    assert rec.first_line == 2 and rec.notes == ()


def test_the_first_of_several_sheets_is_read_and_said(tmp_path: Path) -> None:
    # mistake: the other sheets passed over in silence (a notes sheet first: "no data rows")
    p = _book(tmp_path / "two.xlsx", [], first_sheet="notes")
    with pytest.raises(ValueError) as exc:
        read_record(p)
    assert str(exc.value).endswith("2 sheets: the first, 'notes', is read (save another as "
                                   "its own file to read it)")
    wb = openpyxl.load_workbook(p)
    wb.move_sheet("data", offset=-1)
    wb.save(p)
    rec = read_record(p)
    assert len(rec) == 40 and rec.notes == (
        f"{p}: 2 sheets: the first, 'data', is read (save another as its own file to read "
        "it)",)
