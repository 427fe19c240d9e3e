"""``bifurcation``'s input checks at both edges of each range (analysis/hopf_table.py; issue
25: just inside passes, just outside is refused in one line naming the option). Each case
names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import pytest

from dryfriction.analysis.hopf_table import check_trap, parse_velocities
from dryfriction.analysis.trap_hopf import ALPHA0
from dryfriction.rsf.law import V_MAX
from dryfriction.theory.model import TrapModel


def test_velocities_at_their_edges() -> None:
    # mistakes: the upper end open (V_MAX itself refused); the count's end off by one; the
    # zero velocity let through
    assert parse_velocities(f"{V_MAX!r}") == [V_MAX]
    assert parse_velocities("5e-324, 3.7e-6") == [5e-324, 3.7e-6]
    assert parse_velocities(",".join(["1e-6"] * 7), most=7) == [1e-6] * 7
    for text, words in ((f"{V_MAX * (1 + 1e-12)!r}", "is out of range: allowed (0, "),
                        ("0", "is out of range"), ("-0.0", "is out of range"),
                        (",".join(["1e-6"] * 8), "8 values: allowed 1 to 7")):
        with pytest.raises(ValueError) as err:
            parse_velocities(text, most=7, unit="m/s")
        assert str(err.value).startswith("--velocities: ") and words in str(err.value)
        assert "\n" not in str(err.value)
    with pytest.raises(ValueError, match=r"allowed \(0, 1e\+30\] a0/t0$"):
        parse_velocities("2e30", v_max=1e30, unit="a0/t0")


def test_trap_normal_form_applies_just_below_alpha0() -> None:
    # mistakes: alpha0 itself accepted (y_c = 1: the normal form's very strong pinning ends);
    # a damping without mass accepted (a first-order slider has no damping term)
    check_trap(TrapModel(alpha=ALPHA0 * (1 - 1e-9), eps=0.04, direct=1e-6), 0.0, 0.0)
    check_trap(TrapModel(alpha=0.1, eps=0.04, direct=0.013), 1.3, 0.7)
    for model, mass, damping, words in (
            (TrapModel(alpha=ALPHA0, eps=0.04, direct=0.013), 0.0, 0.0, "model.alpha = "),
            (TrapModel(alpha=0.1, eps=0.04, direct=0.013), 0.0, 1e-9, "drive.damping = 1e-09"),
            (TrapModel(alpha=0.1, eps=0.04), 0.0, 0.0, "model.direct = 0 is not allowed")):
        with pytest.raises(ValueError) as err:
            check_trap(model, mass, damping)
        assert str(err.value).startswith(words) and "\n" not in str(err.value)
