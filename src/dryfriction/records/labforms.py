"""Laboratory records in the other forms labs share them in: a spreadsheet (``.xlsx``, read with
openpyxl, the optional extra ``dryfriction[xlsx]``) and a MATLAB file (``.mat``, read with
SciPy). Each is turned into the header names and a table of numbers, then read exactly as a
text record is (:func:`.lab.read_record`: the same column recognition, units and refusals).

* ``.xlsx``: the first sheet; its first non-empty row holds the column names (units in
  parentheses or brackets, ``Time (s)``), an optional row of units under it, numbers below.
  Rows are numbered as the spreadsheet numbers them (``row 5``).
* ``.mat``: either one struct whose fields are the columns, or top-level variables of equal
  length (``Time``, ``Displ``, ...); a MATLAB name cannot hold a unit, so the names
  ``Time_s``, ``Displ_um``, ``Shear_stress_MPa`` are read as ``Time (s)``, ... when the part
  after the last underscore is a unit, and ``--columns disp=Displ:um`` gives any other.
  Rows are numbered from 1.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ..validation import Array, check_memory

__all__ = ["FORMS", "read_table"]

FORMS = (".xlsx", ".xlsm", ".mat")
"""File suffixes read here rather than as text."""

_UNIT_SUFFIX = re.compile(r"^(.+?)_(s|ms|us|min|h|m|cm|mm|um|microns?|nm|Pa|kPa|MPa|GPa|N|kN|MN|"
                          r"um_s|mm_s|m_s)$")


def _name_with_unit(name: str) -> str:
    """``Displ_um`` -> ``Displ (um)``; ``Vel_um_s`` -> ``Vel (um/s)``; others unchanged."""
    m = _UNIT_SUFFIX.match(name)
    if not m:
        return name
    unit = m.group(2).replace("_", "/")
    return f"{m.group(1)} ({unit})"


def read_table(path: Path) -> tuple[list[str], Array, int, int, list[str], str]:
    """The header names, the numbers (rows x columns, NaN where a cell is not a number), the
    header's and the first data row's numbers, the units row (or ``[]``) and the word for a
    row in messages (``"row"``).

    Raises
    ------
    ValueError
        A file that is not the form its name says, one without a header or without
        numbers, or a spreadsheet reader that is not installed: one line naming the file.
    """
    src = str(path)
    size = path.stat().st_size
    # a spreadsheet or MATLAB file is compressed: allow 20 times its size, as floats twice
    check_memory(f"{src}: reading this {size / 1e6:.0f} MB file needs", 40.0 * size,
                 "export it as a text table and split it")
    if path.suffix.lower() == ".mat":
        return _read_mat(path, src)
    return _read_xlsx(path, src)


def _read_xlsx(path: Path, src: str) -> tuple[list[str], Array, int, int, list[str], str]:
    try:
        import openpyxl
    except ImportError:
        raise ValueError(f"{src}: reading a spreadsheet needs openpyxl (pip install "
                         "'dryfriction[xlsx]'), or save the sheet as a text table (CSV)") from None
    try:
        wb = openpyxl.load_workbook(path, read_only=True, data_only=True)
    except Exception as exc:  # openpyxl raises zipfile, KeyError and its own errors
        raise ValueError(f"{src}: not a readable .xlsx spreadsheet ({type(exc).__name__}: "
                         f"{exc})") from None
    ws = wb.worksheets[0]
    header, hrow, units_row, rows, first = None, 0, [], [], 0
    for r, row in enumerate(ws.iter_rows(values_only=True), start=1):
        cells = list(row)
        while cells and cells[-1] in (None, ""):
            cells.pop()
        if not cells:
            continue
        if header is None:
            header, hrow = ["" if c is None else str(c) for c in cells], r
            continue
        numeric = [isinstance(c, (int, float)) and not isinstance(c, bool) for c in cells]
        if not rows and not any(numeric) and not units_row:
            units_row = ["" if c is None else str(c) for c in cells]
            continue
        if not rows:
            first = r
        rows.append([float(c) if isinstance(c, (int, float)) and not isinstance(c, bool)
                     else _number(c) for c in cells])
    wb.close()
    if header is None:
        raise ValueError(f"{src}: the first sheet has no header row with column names")
    if not rows:
        raise ValueError(f"{src}: no data rows under the header (row {hrow})")
    width = len(header)
    data = np.full((len(rows), width), np.nan)
    for i, row in enumerate(rows):
        data[i, : min(len(row), width)] = row[:width]
    return header, data, hrow, first, units_row, "row"


def _number(cell: object) -> float:
    try:
        return float(str(cell).replace(",", "."))
    except (TypeError, ValueError):
        return float("nan")


def _read_mat(path: Path, src: str) -> tuple[list[str], Array, int, int, list[str], str]:
    from scipy.io import loadmat
    from scipy.io.matlab import MatReadError  # not a ValueError: a truncated or false .mat

    try:
        raw = loadmat(path, squeeze_me=True, struct_as_record=True)
    except (ValueError, TypeError, OSError, NotImplementedError, MatReadError) as exc:
        raise ValueError(f"{src}: not a readable MATLAB .mat file ({exc}); a v7.3 (HDF5) "
                         "file: save it with -v7, or as a text table") from None
    found = {k: v for k, v in raw.items() if not k.startswith("__")}
    # a struct is a structured array (its fields the dtype's names)
    structs = [v for v in found.values() if isinstance(v, np.ndarray) and v.dtype.names]
    if len(structs) == 1:
        st = structs[0].reshape(-1)[0]
        found = {f: st[f] for f in structs[0].dtype.names}
    cols = {k: np.asarray(v, float).ravel() for k, v in found.items()
            if isinstance(v, np.ndarray) and v.dtype.kind in "fiu" and v.size > 1}
    if not cols:
        raise ValueError(f"{src}: no numeric column vectors (variables or struct fields) in "
                         f"the file: found {', '.join(found) or 'nothing'}")
    lengths = {len(v) for v in cols.values()}
    if len(lengths) > 1:
        which = ", ".join(f"{k} ({len(v)})" for k, v in cols.items())
        raise ValueError(f"{src}: the column vectors differ in length: {which}; name the "
                         "ones of the record with --columns")
    names = [_name_with_unit(k) for k in cols]
    return names, np.column_stack(list(cols.values())), 0, 1, [], "row"
