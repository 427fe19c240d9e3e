"""records/labforms.py ``read_table`` on a spreadsheet laid out as labs lay them out: empty rows
above the header (rows numbered as the spreadsheet numbers them), a units row under it, a
decimal comma in a text cell, trailing empty cells, a short row; and the MATLAB names whose
last part is a unit (per second, nm, kPa, kN) against a table written here."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dryfriction.records.labforms import _name_with_unit, read_table


def test_xlsx_header_units_row_numbers_and_cells(tmp_path: Path) -> None:
    # mistakes: rows counted from the header (or from 0), the units row read as data (a row
    # of NaN), a decimal comma read as NaN, a short row shifted, the trailing empty cells
    # counted as columns
    openpyxl = pytest.importorskip("openpyxl")
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.cell(row=3, column=1, value="Time")
    ws.cell(row=3, column=2, value="Displ")
    ws.cell(row=3, column=3, value="Friction")
    ws.append(["s", "um", None, None, None])
    ws.append([12.5, "3,25", 0.61])
    ws.append([13.0, 3.5])  # a short row: its missing cell is NaN
    ws.append([13.5, 3.75, "0.63", None])
    p = tmp_path / "lab.xlsx"
    wb.save(p)
    header, data, hrow, first, units, word = read_table(p)
    assert header == ["Time", "Displ", "Friction"] and units == ["s", "um"]
    assert (hrow, first, word) == (3, 5, "row")
    np.testing.assert_array_equal(data[:, :2], [[12.5, 3.25], [13.0, 3.5], [13.5, 3.75]])
    assert data[0, 2] == 0.61 and np.isnan(data[1, 2]) and data[2, 2] == 0.63
    # without a units row the first data row is the one under the header
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.append(["Time (s)", "Displ (um)"])
    ws.append([1.0, 2.0])
    wb.save(p)
    _, data, hrow, first, units, _ = read_table(p)
    assert (hrow, first, units) == (1, 2, []) and data.tolist() == [[1.0, 2.0]]
    wb = openpyxl.Workbook()
    wb.active.append(["Time (s)", "Displ (um)"])
    wb.save(p)
    with pytest.raises(ValueError, match=r"lab\.xlsx: no data rows under the header \(row 1\)"):
        read_table(p)


@pytest.mark.parametrize("name, read", [
    ("Time_ms", "Time (ms)"), ("Vel_um_s", "Vel (um/s)"), ("LP_mm_s", "LP (mm/s)"),
    ("Gap_nm", "Gap (nm)"), ("Shear_stress_kPa", "Shear_stress (kPa)"),
    ("Load_kN", "Load (kN)"), ("Time_min", "Time (min)"), ("Displ_microns", "Displ (microns)"),
    ("Friction", "Friction"), ("mu_el", "mu_el"), ("Sample_2", "Sample_2"),
])
def test_mat_names_with_a_unit_suffix(name, read) -> None:
    # mistakes: "um_s" read as um (a velocity taken for a length), a unit not in the list
    # (min, nm, kN) left in the name, a non-unit suffix ("el", "2") taken for a unit
    assert _name_with_unit(name) == read
