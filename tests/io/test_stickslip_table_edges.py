"""The ``[stickslip]`` table's ranges at both edges (issue 25: a refusal range is checked just
inside, where it must pass, and just outside, where it must be refused in one line naming the
key). Each case names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import pytest

from dryfriction.io.protocol import stickslip_options

# key, allowed edge value, refused value just outside it; mistakes in the comments
EDGES = [
    ("stick_fraction", 1.0, 1.0 + 1e-9),  # the upper end taken as open (1 refused)
    ("stick_fraction", 1e-12, 0.0),  # the lower end taken as closed (0 accepted)
    ("rel_threshold", 1.0 - 1e-9, 1.0),  # the upper end taken as closed (1 accepted)
    ("rel_threshold", 1e-12, 0.0),
    ("floor", 1e-300, 0.0),  # a zero floor accepted (the classes then divide by it)
    ("floor", 3.7e12, -1e-12),
    ("transient", 0.0, -1e-12),  # the lower end taken as open (no transient refused)
]


@pytest.mark.parametrize("key, inside, outside", EDGES)
def test_edges_of_each_range(key: str, inside: float, outside: float) -> None:
    assert stickslip_options({key: inside}, "p.toml") == {key: inside}
    with pytest.raises(ValueError) as err:
        stickslip_options({key: outside}, "p.toml")
    msg = str(err.value)
    assert msg.startswith(f"p.toml: stickslip.{key} = ") and "out of range" in msg
    assert "\n" not in msg


def test_a_boolean_is_no_number_and_follow_velocity_no_number() -> None:
    # mistakes: TOML's true read as 1 (a stick fraction of 1); follow_velocity = 1 taken as true
    with pytest.raises(ValueError, match=r"^p: stickslip.stick_fraction = True is not a number$"):
        stickslip_options({"stick_fraction": True}, "p")
    with pytest.raises(ValueError, match=r"stickslip.follow_velocity = 1 is not allowed"):
        stickslip_options({"follow_velocity": 1}, "p")
    assert stickslip_options({"follow_velocity": False, "transient": 7}, "p") == {
        "follow_velocity": False, "transient": 7.0}
