"""fixE item 3 (a second new user's trial, problem 17): a ``.mat`` file holding one N x k
numeric matrix was read as one column ``data`` of N k numbers and refused with a hint that
could not work (``--columns time=NAME``: there is no name). Now its columns are ``data_1`` ..
``data_k`` (numbered from 1, as MATLAB and the reader's messages count), the long side taken
as the rows; without a map the refusal says how to map them, and that map reads it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dryfriction.cli import main
from dryfriction.records.lab import read_record

scipy_io = pytest.importorskip("scipy.io")

N = 300
T = 7.0 + 0.05 * np.arange(N)  # s, from 7 s
X_MM = np.where(T < 12.0, 3e-3 * (T - 7.0), 0.015 + 2.2e-2 * (T - 12.0))  # mm: 3 -> 22 um/s
SHEAR = 11.0 + 0.02 * np.sin(T)  # MPa
NORMAL = 18.0 + 0.01 * np.cos(T)


def _matrix() -> np.ndarray:
    return np.column_stack([T, X_MM, SHEAR, NORMAL])


MAP = "time=data_1:s,disp=data_2:mm,shear=data_3:MPa,normal=data_4:MPa"


def _read(path: Path) -> object:
    from dryfriction.records.lab import parse_column_map

    return read_record(path, parse_column_map(MAP))


@pytest.mark.parametrize("transposed", [False, True])
def test_a_matrix_is_read_as_numbered_columns(tmp_path: Path, transposed: bool) -> None:
    """N x 4 and 4 x N give the same record, each column the matrix's, in SI; the note says
    how it was read. Mistakes: the matrix flattened into one column (the user's refusal), a
    4 x N matrix taken as 4 rows, the columns numbered from 0."""
    path = tmp_path / "m.mat"
    scipy_io.savemat(path, {"data": _matrix().T if transposed else _matrix()})
    rec = _read(path)
    assert len(rec) == N
    np.testing.assert_allclose(rec.time, T, rtol=1e-12)
    np.testing.assert_allclose(rec.load_point, X_MM * 1e-3, rtol=1e-12)
    np.testing.assert_allclose(rec.friction, SHEAR / NORMAL, rtol=1e-12)
    assert rec.columns["disp"] == "data_2"
    (note,) = rec.notes
    want = "300 x 4" if not transposed else "4 x 300"
    assert f"the {want} matrix 'data' is read as columns data_1 .. data_4" in note
    assert ("transposed" in note) == transposed


def test_the_refusal_s_hint_works(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Without a map: one line naming the numbered columns and a map of them; that map (with
    the units) then reads the file, exit 0. Mistake: the old hint, --columns time=NAME, with
    no name to give."""
    path = tmp_path / "m.mat"
    scipy_io.savemat(path, {"data": _matrix()})
    capsys.readouterr()
    assert main(["record", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "found 'data_1', 'data_2', 'data_3', 'data_4'" in err
    assert "map each, e.g. --columns time=data_1,disp=data_2:UNIT,mu=data_3" in err
    assert main(["record", str(path), "--columns", MAP]) == 0
    out = capsys.readouterr().out
    assert "disp      'data_2'" in out and "note: " in out


def test_a_matrix_beside_vectors_and_in_a_struct(tmp_path: Path) -> None:
    # a time vector with a 3-column matrix of the rest; and the matrix as a struct's field
    path = tmp_path / "v.mat"
    scipy_io.savemat(path, {"t": T, "rest": _matrix()[:, 1:]})
    from dryfriction.records.lab import parse_column_map

    rec = read_record(path, parse_column_map(
        "time=t:s,disp=rest_1:mm,shear=rest_2:MPa,normal=rest_3:MPa"))
    np.testing.assert_allclose(rec.friction, SHEAR / NORMAL, rtol=1e-12)
    path = tmp_path / "s.mat"
    scipy_io.savemat(path, {"run": {"data": _matrix()}})
    rec = _read(path)
    np.testing.assert_allclose(rec.load_point, X_MM * 1e-3, rtol=1e-12)
    # a matrix whose length is not the vectors': the lengths named, as before
    path = tmp_path / "bad.mat"
    scipy_io.savemat(path, {"t": T[:-1], "rest": _matrix()[:, 1:]})
    with pytest.raises(ValueError, match=r"differ in length: t \(299\), rest_1 \(300\)"):
        read_record(path)
