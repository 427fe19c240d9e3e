"""records/data.py: the project's CSV saved by a spreadsheet in a European locale (semicolons,
decimal commas; a second new user's ``ts_semi.csv``) is read as the same data as with commas,
and the fit's dispatch takes it as the project's CSV (it was fitted as a laboratory record:
step detection, every step flagged)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dryfriction.app.fitting import is_project_csv
from dryfriction.records.data import csv_separator, read_csv

ROWS = [(0.0, 1.3, 0.5998141995), (250.0, 1.3, 0.6013), (500.0, 0.0, 0.61275),
        (750.0, 4.7, 0.6021)]


def _write(path: Path, sep: str, decimal: str) -> Path:
    lines = ["# a comment line, kept out", sep.join(["t[ms]", "v_load[um/s]", "mu"])]
    lines += [sep.join(repr(x).replace(".", decimal) for x in row) for row in ROWS]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_semicolons_and_decimal_commas_read_as_the_commas(tmp_path: Path) -> None:
    # mistakes: the ';' line read as one column (refused or a record); a decimal comma cut
    # ("0,5998" read as 0 or refused); the unit in [] lost on the ';' header
    semi = _write(tmp_path / "semi.csv", ";", ",")
    comma = _write(tmp_path / "comma.csv", ",", ".")
    a, b = read_csv(semi), read_csv(comma)
    assert type(a).__name__ == "SeriesData" == type(b).__name__
    np.testing.assert_array_equal(a.t, b.t)
    np.testing.assert_array_equal(a.v_load, b.v_load)
    np.testing.assert_array_equal(a.mu, b.mu)
    np.testing.assert_allclose(a.t, [0.0, 0.25, 0.5, 0.75])  # ms -> s
    np.testing.assert_allclose(a.v_load[:2], 1.3e-6)  # um/s -> m/s
    assert is_project_csv(semi) and is_project_csv(comma)


def test_the_separator_rule_and_a_thousands_point(tmp_path: Path) -> None:
    # mistakes: ';' chosen where the header has commas; a thousands point read as a decimal
    assert csv_separator("t[s];v_load[um/s];mu") == ";"
    assert csv_separator("t[s],v_load[um/s],mu") == ","
    assert csv_separator("t_w[s],mu_s;note") == ","
    p = tmp_path / "k.csv"
    p.write_text("V[um/s];mu_d\n1.000,5;0,61\n")
    with pytest.raises(ValueError, match=r"k\.csv, line 2, column 1 \(V\): '1\.000,5' is not "
                                         r"a number"):
        read_csv(p)
