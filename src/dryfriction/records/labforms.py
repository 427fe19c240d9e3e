"""Laboratory records in the other forms labs share them in: a spreadsheet (``.xlsx``, read with
openpyxl, the optional extra ``dryfriction[xlsx]``) and a MATLAB file (``.mat``, read with
SciPy). Each is turned into the header names and a table of numbers, then read exactly as a
text record is (:func:`.lab.read_record`: the same column recognition, units and refusals).

* ``.xlsx``: the first sheet (said where there are more); its header row holds the column
  names (units in parentheses or brackets, ``Time (s)``), an optional row of units under it,
  numbers below. The header is found as in a text record: the row with the most recognised
  names above the first rows of numbers; rows above it (a metadata block) are a preamble,
  skipped and said.
  Rows are numbered as the spreadsheet numbers them (``row 5``).
* ``.mat``: either one struct whose fields are the columns, or top-level variables of equal
  length (``Time``, ``Displ``, ...); a MATLAB name cannot hold a unit, so the names
  ``Time_s``, ``Displ_um``, ``Shear_stress_MPa`` are read as ``Time (s)``, ... when the part
  after the last underscore is a unit, and ``--columns disp=Displ:um`` gives any other.
  A numeric matrix (``data``, N x k: MATLAB's ``[t x tau sigma]``) is read as k columns
  named by their numbers, ``data_1`` .. ``data_k`` (its long side taken as the rows, said);
  no name can be guessed there, so ``--columns time=data_1,disp=data_2:mm,...`` maps them.
  Rows are numbered from 1.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..validation import Array, check_memory

__all__ = ["FORMS", "PREAMBLE_MAX", "read_table"]

PREAMBLE_MAX = 200
"""Most lines (rows) above a record's header that are skipped as a preamble (ours: instruments
write a few to a few dozen); the text reader's too (:func:`.lab._find_header`)."""

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


def read_table(path: Path, is_name: Callable[[str], bool] | None = None,
               notes: list[str] | None = None
               ) -> tuple[list[str], Array, int, int, list[str], str]:
    """The header names, the numbers (rows x columns, NaN where a cell is not a number), the
    header's and the first data row's numbers, the units row (or ``[]``) and the word for a
    row in messages (``"row"``).

    ``is_name(cell)``: whether a header cell is a column name the reader recognises; with it a
    spreadsheet's header is the row with the most of them above the first two rows of numbers
    (the text reader's rule, :func:`.lab._find_header`), the rows above it a preamble. What
    the reader skipped (a preamble, the other sheets) is appended to ``notes``.

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
        return _read_mat(path, src, notes if notes is not None else [])
    return _read_xlsx(path, src, is_name, notes if notes is not None else [])


def _read_xlsx(path: Path, src: str, is_name: Callable[[str], bool] | None, notes: list[str]
               ) -> tuple[list[str], Array, int, int, list[str], str]:
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
    sheets = ""
    if len(wb.worksheets) > 1:  # said: a record on another sheet would otherwise be missed
        sheets = (f"{len(wb.worksheets)} sheets: the first, {ws.title!r}, is read (save "
                  "another as its own file to read it)")
        notes.append(f"{src}: {sheets}")
    lines: list[tuple[int, list[object]]] = []  # the non-empty rows, by their number
    for r, row in enumerate(ws.iter_rows(values_only=True), start=1):
        cells = list(row)
        while cells and cells[-1] in (None, ""):
            cells.pop()
        if cells:
            lines.append((r, cells))
    wb.close()
    h = _header_index(lines, is_name) if is_name is not None else 0
    if h:  # one line: what was skipped, so that a wrong guess shows
        shown = ", ".join(repr(" ".join(str(c) for c in cells if c not in (None, ""))[:40])
                          for _, cells in lines[:min(h, 3)])
        more = f" and {h - 3} more" if h > 3 else ""
        notes.append(f"{src}: {h} row(s) above the header (row {lines[h][0]}) skipped as a "
                     f"preamble: {shown}{more}")
    header, hrow, units_row, rows, first = None, 0, [], [], 0
    for r, cells in lines[h:]:
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
    also = f"; {sheets}" if sheets else ""
    if header is None:
        raise ValueError(f"{src}: the first sheet has no header row with column names{also}")
    if not rows:
        raise ValueError(f"{src}: no data rows under the header (row {hrow}){also}")
    width = len(header)
    data = np.full((len(rows), width), np.nan)
    for i, row in enumerate(rows):
        data[i, : min(len(row), width)] = row[:width]
    return header, data, hrow, first, units_row, "row"


def _header_index(lines: list[tuple[int, list[object]]], is_name: Callable[[str], bool]
                  ) -> int:
    """Index in ``lines`` of a sheet's header: of the rows above the first two rows of numbers
    (at most PREAMBLE_MAX + 1 of them), the first with the most recognised column names; 0
    (the first row) where none has one. The text reader's rule (:func:`.lab._find_header`)."""
    def numeric(cells: list[object]) -> bool:  # a data row: two cells or more, all numbers
        vals = [c for c in cells if c not in (None, "")]
        return len(vals) >= 2 and all(not np.isnan(_number(c)) for c in vals)

    top = min(len(lines), PREAMBLE_MAX + 2)
    start = next((k for k in range(top) if numeric(lines[k][1])
                  and (k + 1 == len(lines) or numeric(lines[k + 1][1]))), top)
    score = [sum(is_name(str(c)) for c in cells if c not in (None, ""))
             for _, cells in lines[:max(min(start, PREAMBLE_MAX + 1), 1)]]
    return score.index(max(score)) if score and max(score) > 0 else 0


def _number(cell: object) -> float:
    try:
        return float(str(cell).replace(",", "."))
    except (TypeError, ValueError):
        return float("nan")


MATRIX_NOTE = "is read as columns"
"""Words of the note :func:`read_table` adds for a ``.mat`` matrix split into columns (the
reader's refusal then says how to map them)."""


def _split_matrices(found: dict[str, object], src: str, notes: list[str]
                    ) -> dict[str, object]:
    """``found`` with every 2-D numeric matrix (both sides > 1) replaced by its columns
    ``NAME_1`` .. ``NAME_k``, numbered from 1 as MATLAB and the reader's messages count;
    the long side is the rows (a k x N matrix is transposed, and that said). One note each."""
    out: dict[str, object] = {}
    for k, v in found.items():
        if not (isinstance(v, np.ndarray) and v.dtype.kind in "fiu" and v.ndim == 2
                and min(v.shape) > 1):
            out[k] = v
            continue
        flipped = v.shape[1] > v.shape[0]
        m = v.T if flipped else v
        names = [f"{k}_{j + 1}" for j in range(m.shape[1])]
        out.update({n: m[:, j] for j, n in enumerate(names)})
        notes.append(f"{src}: the {v.shape[0]} x {v.shape[1]} matrix {k!r} {MATRIX_NOTE} "
                     f"{names[0]} .. {names[-1]}"
                     + (" (its rows: a column a row in the file, transposed)" if flipped
                        else ""))
    return out


def _read_mat(path: Path, src: str, notes: list[str]
              ) -> tuple[list[str], Array, int, int, list[str], str]:
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
    found = _split_matrices(found, src, notes)
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
