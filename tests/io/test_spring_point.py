"""io.protocol.spring_point and pulling_velocity called directly (issue 25): the sweep point's
pull is its LAST segment's velocity (two segments of different velocities), the steady
initial population follows it unless told not to, and each refusal on both sides of its edge
(the transient against the load-point travel, a pull of zero)."""

from __future__ import annotations

from typing import Any

import pytest

from dryfriction.io.protocol import pulling_velocity, spring_point


def _point(**stickslip: Any) -> dict[str, Any]:
    doc: dict[str, Any] = {
        "model": {"alpha": 0.13, "eps": 0.04},
        "ensemble": {"traps_per_a0": 20, "initial": "steady", "initial_velocity": 0.11},
        "drive": {"kind": "spring", "stiffness": 0.05, "mass": 0.0,
                  "segments": [{"velocity": 0.21, "slip": 1.5},
                               {"velocity": 0.37, "slip": 2.5}]},
        "output": {"every_slip": 0.05},
    }
    if stickslip:
        doc["stickslip"] = stickslip
    return doc


def test_the_pull_is_the_last_segments_velocity_and_the_population_follows_it() -> None:
    proto, opts = spring_point(_point(transient=1.0), "p")
    assert pulling_velocity(proto.drive) == 0.37 and opts == {"transient": 1.0}
    assert proto.initial.velocity == pytest.approx(0.37)  # followed by default
    proto, _ = spring_point(_point(follow_velocity=False), "p")
    assert proto.initial.velocity == pytest.approx(0.11)


def test_the_transient_must_be_shorter_than_the_travel() -> None:
    # travel 1.5 + 2.5 = 4 a0: 4 refused (not shorter), just below accepted
    with pytest.raises(ValueError, match=r"^p: stickslip.transient = 4 a0 is out of range: "
                                         r"allowed less than the load-point travel 4 a0$"):
        spring_point(_point(transient=4.0), "p")
    spring_point(_point(transient=4.0 * (1 - 1e-9)), "p")
    # the linear analysis has no transient to fit in
    proto, _ = spring_point(_point(transient=9.0), "p", "linear")
    assert pulling_velocity(proto.drive) == 0.37


def test_a_point_that_does_not_pull_is_refused() -> None:
    doc = _point(follow_velocity=False)  # followed, the steady population at 0 is refused
    doc["drive"]["segments"][-1] = {"velocity": 0.0, "duration": 3.0}  # a hold
    with pytest.raises(ValueError, match="^p: the last segment's velocity 0 must be > 0"):
        spring_point(doc, "p")
    doc["drive"]["segments"][-1] = {"velocity": 1e-9, "slip": 1e-3}  # slow, but it pulls
    assert pulling_velocity(spring_point(doc, "p")[0].drive) == 1e-9
    doc = _point()
    doc["model"]["law"] = "rsf"
    with pytest.raises(ValueError, match="^p: model.law = 'rsf': sweeps of rate-and-state"):
        spring_point(doc, "p")
    doc = _point()
    doc["drive"] = {"kind": "velocity", "segments": [{"velocity": 0.2, "slip": 1.0}]}
    with pytest.raises(ValueError, match="^p: drive.kind must be 'spring'"):
        spring_point(doc, "p")
