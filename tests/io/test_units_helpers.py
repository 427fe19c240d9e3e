"""io.units.with_units and read_rows by their docstrings (issue 25): the tables given win over
the document's own units, a later table over an earlier one, an empty unit becomes "1" and a
label (None) stays None; read_rows skips comment lines and reads both header forms."""

from __future__ import annotations

from pathlib import Path

from dryfriction.io.units import read_rows, with_units


def test_with_units_precedence_and_spellings() -> None:
    doc = {"dc": 2.3e-5, "k": 4e3, "units": {"dc": "um", "k": "", "note": None}}
    out = with_units(doc, {"dc": "m", "v": "m/s"}, {"v": "um/s", "flag": None})
    assert out["units"] == {"dc": "m", "k": "1", "note": None, "v": "um/s", "flag": None}
    assert out["dc"] == 2.3e-5 and doc["units"]["dc"] == "um"  # the input left as it was
    assert with_units({"x": 1.0})["units"] == {}


def test_read_rows_skips_comments_and_reads_both_header_forms(tmp_path: Path) -> None:
    p = tmp_path / "t.csv"
    p.write_text("# --segments 0:1e-6\nsegment,t_start[s],velocity[m/s],kind\n"
                 "0,5,1e-06,start\n#note without a space\n1,20,3e-06,step\n")
    assert read_rows(p) == [{"segment": "0", "t_start": "5", "velocity": "1e-06",
                             "kind": "start"},
                            {"segment": "1", "t_start": "20", "velocity": "3e-06",
                             "kind": "step"}]
    old = tmp_path / "old.csv"
    old.write_text("segment,t_start\n0,5\n")
    assert read_rows(old) == [{"segment": "0", "t_start": "5"}]
