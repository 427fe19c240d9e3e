"""Headers ``name[unit]`` written and read back for every unit the package declares and for
drawn names and units (io/units.py; issue 25: a round trip over a hand-picked few hides a
unit the header form cannot carry). Each test names the mistake it is for; each was seen
failing with it applied."""

from __future__ import annotations

import string

from hypothesis import given, settings
from hypothesis import strategies as st

from dryfriction.io import units as U


def _tables() -> list[dict]:
    out = []
    for name in U.__all__:
        value = getattr(U, name)
        if name.endswith("_UNITS") and isinstance(value, dict):
            out += list(value.values()) if name == "SUMMARY_UNITS" else [value]
    return out


def test_every_declared_unit_survives_its_header() -> None:
    # mistakes: an empty unit written as "name[]" (not "1"); a unit's reading in parentheses
    # kept in the header (brackets or parentheses inside the brackets)
    n = 0
    for table in _tables():
        for name, unit in table.items():
            h = U.header(name, unit)
            back = U.split_header(h)
            if unit is None:
                assert h == name and back == (name, None)
                continue
            cu = U.csv_unit(unit)
            assert back == (name, cu) and cu and "(" not in cu and "[" not in cu, (name, unit)
            n += 1
    assert n > 300
    assert U.split_header(U.header("mu", "")) == ("mu", "1")


@settings(max_examples=60, derandomize=True, deadline=None)
@given(name=st.text(string.ascii_letters + string.digits + "_", min_size=1, max_size=12),
       unit=st.text(string.ascii_letters + string.digits + "/^*. ", min_size=1, max_size=12),
       reading=st.text(string.ascii_letters + " ", max_size=10))
def test_header_round_trip_of_drawn_names_and_units(name: str, unit: str, reading: str) -> None:
    # mistake: the unit cut at its first space (a unit "F_el t0" read as "F_el")
    full = f"{unit} ({reading})" if reading.strip() else unit
    back = U.split_header(U.header(name, full))
    assert back == (name, U.csv_unit(full))
    assert U.csv_unit(full) == (unit.strip() or "1")
