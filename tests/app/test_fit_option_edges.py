"""``fit``'s ``--stiffness`` and ``--fix`` at the edges of what they accept (issue 25: just
inside passes, just outside is refused in one line naming the option). Each case names the
mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import math

import pytest

from dryfriction.app.fitting import parse_fix, parse_stiffness


@pytest.mark.parametrize("text, want", [
    ("1e-300", 1e-300), (" 3700 ", 3700.0), ("inf", math.inf), ("Slope", "slope"),
    ("RECORD", "record"), ("fit", "fit"), (4.1e3, 4100.0),
])
def test_stiffness_accepted(text, want) -> None:  # type: ignore[no-untyped-def]
    assert parse_stiffness(text) == want


@pytest.mark.parametrize("text", ["0", "-0.0", "-1e-300", "nan", "-inf"])
def test_stiffness_refused_at_and_below_zero(text: str) -> None:
    # mistakes: the range as >= 0 (a zero stiffness, no spring at all, accepted); a NaN let
    # through (the comparison k <= 0 is false for NaN)
    with pytest.raises(ValueError) as err:
        parse_stiffness(text)
    msg = str(err.value)
    assert msg.startswith(f"--stiffness {text!r} is out of range: allowed > 0 (1/m)")
    assert "\n" not in msg


def test_fix_pairs_and_their_refusals() -> None:
    # mistakes: a value with '=' in it cut at the second '='; a name of blanks accepted; the
    # value's text left as a string
    assert parse_fix(["t0 = 0.013", "eps=4e-2"]) == {"t0": 0.013, "eps": 0.04}
    assert parse_fix({"alpha": "0.13"}) == {"alpha": 0.13}
    assert parse_fix(None) == {}
    for item, words in (("t0", "expected name=value"), (" =3", "expected name=value"),
                        ("t0=0.1=2", "'0.1=2' is not a number"),
                        ("t0=ten", "'ten' is not a number")):
        with pytest.raises(ValueError) as err:
            parse_fix([item])
        assert str(err.value).startswith(f"--fix {item!r}: ") and words in str(err.value)
