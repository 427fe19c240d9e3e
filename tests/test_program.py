"""The load-point program (dryfriction.program) against its definition written here: a
generic program with a backward segment, a hold, a slip-given segment and x0 != 0 (issue 25:
the down-step and the backward branch, both edges of each refusal)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.program import Segment, VelocityProgram

# velocity, duration (or slip): forward 0.7 for 2.5, hold 1.25, backward -0.4 over slip 0.3
# (time 0.75), forward 2.2 over slip 1.1 (time 0.5); x0 = -1.3
PROG = VelocityProgram([Segment(0.7, duration=2.5), {"velocity": 0.0, "duration": 1.25},
                        Segment(-0.4, slip=0.3), {"velocity": 2.2, "slip": 1.1}], x0=-1.3)


def _by_hand(t: float) -> tuple[float, float]:
    """Position and velocity of PROG at ``t``, written out segment by segment."""
    ends = [2.5, 3.75, 4.5, 5.0]
    if t < ends[0]:
        return -1.3 + 0.7 * t, 0.7
    x1 = -1.3 + 0.7 * 2.5
    if t < ends[1]:
        return x1, 0.0
    if t < ends[2]:
        return x1 - 0.4 * (t - 3.75), -0.4
    x3 = x1 - 0.3
    return x3 + 2.2 * (t - 4.5), 2.2


def test_times_positions_and_totals() -> None:
    np.testing.assert_allclose(PROG.times, [0.0, 2.5, 3.75, 4.5, 5.0], rtol=1e-15)
    np.testing.assert_allclose(PROG.positions, [-1.3, 0.45, 0.45, 0.15, 1.25], rtol=1e-14)
    assert PROG.total_time == pytest.approx(5.0, rel=1e-15)
    np.testing.assert_array_equal(PROG.velocities, [0.7, 0.0, -0.4, 2.2])
    back = PROG.segments[2]
    assert back.time == pytest.approx(0.75, rel=1e-15)  # slip / |velocity|: positive
    assert back.displacement == pytest.approx(-0.3, rel=1e-15)  # signed
    # computed once and shared: read-only, so that a caller's edit cannot change the program
    for name in ("times", "positions", "velocities"):
        with pytest.raises(ValueError, match="read-only"):
            getattr(PROG, name)[1] = 9.9
    np.testing.assert_allclose(PROG.times, [0.0, 2.5, 3.75, 4.5, 5.0], rtol=1e-15)


def test_a_program_unpickled_or_copied_keeps_its_arrays_read_only() -> None:
    """Pickled, deep-copied, or unpickled from a state without the kept arrays (a pickle
    from before they were kept): the same program, its arrays derived again, read-only."""
    import copy
    import pickle

    for q in (pickle.loads(pickle.dumps(PROG)), copy.deepcopy(PROG)):
        assert q == PROG
        np.testing.assert_array_equal(q.positions, PROG.positions)
        assert not (q.times.flags.writeable or q.positions.flags.writeable
                    or q.velocities.flags.writeable)
    old = VelocityProgram.__new__(VelocityProgram)
    old.__setstate__({"segments": PROG.segments, "x0": PROG.x0})
    np.testing.assert_array_equal(old.times, PROG.times)
    assert old.position(4.2) == PROG.position(4.2)


def test_position_and_velocity_at_generic_times() -> None:
    t = np.array([0.0, 1.1, 2.5, 3.1, 3.75, 4.2, 4.5, 4.93, 5.0])
    want = np.array([_by_hand(s) for s in t])
    np.testing.assert_allclose(PROG.position(t), want[:, 0], rtol=1e-13, atol=1e-15)
    # right-continuous: at a boundary the velocity is the next segment's
    np.testing.assert_array_equal(PROG.velocity(t), want[:, 1])
    # outside the program: the first and last segments continue
    assert PROG.velocity(-1.0) == 0.7 and PROG.velocity(7.0) == 2.2
    assert PROG.position(6.0) == pytest.approx(1.25 + 2.2, rel=1e-14)
    assert PROG.position(-0.5) == pytest.approx(-1.3 - 0.35, rel=1e-14)
    np.testing.assert_array_equal(PROG.segment_index(np.array([2.5 - 1e-12, 2.5, 5.0])),
                                  [0, 1, 3])


def test_check_speeds_edges() -> None:
    lo, hi = 1e-3, 2.2
    PROG.check_speeds(0.4, hi, "m/s")  # |-0.4| = lo and 2.2 = hi: both allowed; the hold too
    with pytest.raises(ValueError, match=r"^segments\[2\]\.velocity = -0.4 m/s is out of range: "
                                         r"allowed 0 \(a hold\) or 0.41 <= \|velocity\| <= 2.2 "
                                         r"m/s$"):
        PROG.check_speeds(0.41, hi, "m/s")
    with pytest.raises(ValueError, match=r"segments\[3\]\.velocity = 2.2 a0/t0 is out of range"):
        PROG.check_speeds(lo, 2.19, "a0/t0")


def test_segment_refusals() -> None:
    with pytest.raises(ValueError, match="exactly one of duration and slip"):
        Segment(1.0)
    with pytest.raises(ValueError, match="exactly one of duration and slip"):
        Segment(1.0, duration=1.0, slip=1.0)
    with pytest.raises(ValueError, match="slip is given for a segment with velocity = 0"):
        Segment(0.0, slip=1.0)
    for kw in ({"duration": 0.0}, {"slip": 0.0}, {"duration": -1.0}):
        with pytest.raises(ValueError, match="out of range: allowed finite and > 0"):
            Segment(0.5, **kw)
    with pytest.raises(ValueError, match="unknown segment key"):
        Segment.from_mapping({"velocity": 1.0, "time": 2.0})
    with pytest.raises(ValueError, match="a segment needs a velocity"):
        Segment.from_mapping({"duration": 2.0})
    with pytest.raises(ValueError, match="at least one segment"):
        VelocityProgram([])
    with pytest.raises(ValueError, match="x0 = "):
        VelocityProgram([Segment(1.0, duration=1.0)], x0=float("nan"))


def test_a_segment_too_short_to_resolve_is_refused_both_sides_of_the_bound() -> None:
    # the bound: a segment lasts at least 1e-12 of its end time
    VelocityProgram([Segment(1.0, duration=1e6), Segment(2.0, duration=2e-6)])  # 2e-12 of end
    with pytest.raises(ValueError, match=r"^segment 2 \(duration 5e-07\) starts at t = 1e\+06"):
        VelocityProgram([Segment(1.0, duration=1e6), Segment(2.0, duration=5e-7)])
    with pytest.raises(ValueError, match=r"segment 2 \(slip 1e-06\)"):  # time 5e-7 again
        VelocityProgram([Segment(1.0, duration=1e6), Segment(-2.0, slip=1e-6)])
