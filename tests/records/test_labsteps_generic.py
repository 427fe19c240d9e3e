"""records/labsteps.py at generic points, every number by hand: the windows of a program with a
hold at its start, a normal change at one velocity, an up-step whose lead is cut by
``pre_fraction`` and a slide-hold-slide whose lead is ``pre_slip`` of travel, on a record whose
clock starts at 1000 s; both edges of the two options' ranges; the load velocity per sample
and its refusals; the program table's units (um/s, kN) and its note on unplaced changes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.records.labsteps import (
    Segment,
    load_velocity_series,
    make_segments,
    segments_table,
    slice_steps,
)
from dryfriction.records.record import LabRecord

T = 1000.0 + 0.5 * np.arange(400)  # 0.5 s a sample, the clock starting at 1000 s


def _record(t=T) -> LabRecord:
    return LabRecord("bench.csv", t, None, None, np.full(t.size, 0.6), None, "", {}, 1)


SEGS = make_segments(T, [0, 40, 100, 160, 220, 300, 400], [0.0, 2e-6, 2e-6, 8e-6, 0.0, 3e-6])


def test_make_segments_times_and_the_last_ends_at_the_last_sample() -> None:
    assert [(s.t_start, s.t_end) for s in SEGS] == [
        (1000.0, 1020.0), (1020.0, 1050.0), (1050.0, 1080.0), (1080.0, 1110.0),
        (1110.0, 1150.0), (1150.0, 1199.5)]
    assert [(s.i_start, s.i_end) for s in SEGS][-1] == (300, 400)


def test_windows_by_hand() -> None:
    # the hold at the start and the normal change at 2 um/s give no window; the up-step at
    # 1080 s: lead min(0.5 x 30 s, 50 um / 2 um/s = 25 s) = 15 s -> from 1065 s (sample 130);
    # the hold at 1110 s: lead min(15 s, 50 um / 8 um/s = 6.25 s) -> from 1103.75 s, the first
    # sample at or after it is 1104 s (208); it ends where the sliding after the hold ends.
    # Mistakes: the lead as pre_slip x v, pre_fraction ignored, a normal change taken for a
    # step, the slide-hold-slide's v_after the hold's 0 or its end the hold's
    w = slice_steps(_record(), SEGS)
    assert [(x.index, x.kind, x.i_start, x.i_end, x.t_change, x.v_before, x.v_after, x.hold)
            for x in w] == [(0, "step", 130, 220, 1080.0, 2e-6, 8e-6, 0.0),
                            (1, "shs", 208, 400, 1110.0, 8e-6, 3e-6, 40.0)]
    assert math.isnan(w[0].t_change_lo)
    # a larger pre_slip: the up-step's lead is the whole half of the segment before, no more
    w = slice_steps(_record(), SEGS, pre_slip=1e-3, pre_fraction=1.0)
    assert (w[0].i_start, w[1].i_start) == (100, 160)
    # a change placed between samples, 1 s before the first sample of its segment: the window
    # still starts at that segment's first sample, never in the segment before it
    early = (SEGS[0], SEGS[1], Segment(1049.0, 1080.0, 2e-6, 100, 160), *SEGS[3:])
    w = slice_steps(_record(), early, pre_slip=1e-3, pre_fraction=1.0)
    assert w[0].i_start == 100


def test_a_final_hold_gives_no_window_and_none_at_all_is_refused() -> None:
    segs = make_segments(T, [0, 100, 250, 400], [2e-6, 5e-6, 0.0])
    w = slice_steps(_record(), segs)
    assert [(x.kind, x.i_end) for x in w] == [("step", 250)]
    flat = make_segments(T, [0, 100, 400], [0.0, 5e-6])
    with pytest.raises(ValueError, match=r"bench\.csv: no velocity step or hold.*2 segment"):
        slice_steps(_record(), flat)


@pytest.mark.parametrize("kw, ok", [
    ({"pre_fraction": 1.0}, True), ({"pre_fraction": 1.0 + 1e-12}, False),
    ({"pre_fraction": 1e-9}, True), ({"pre_fraction": 0.0}, False),
    ({"pre_slip": 1e-12}, True), ({"pre_slip": 0.0}, False), ({"pre_slip": math.inf}, False),
])
def test_option_ranges_both_edges(kw, ok) -> None:
    if ok:
        assert slice_steps(_record(), SEGS, **kw)
    else:
        with pytest.raises(ValueError, match=f"{next(iter(kw))} = .* is out of range"):
            slice_steps(_record(), SEGS, **kw)


def test_load_velocity_per_sample_and_its_refusals() -> None:
    v = load_velocity_series(_record(), SEGS)
    assert v[39] == 0.0 and v[40] == 2e-6 and v[219] == 8e-6 and v[220] == 0.0
    assert v[-1] == 3e-6 and v.size == 400
    with pytest.raises(ValueError, match="expected 40"):  # a gap between two segments
        load_velocity_series(_record(), SEGS[:1] + SEGS[2:])
    with pytest.raises(ValueError, match="end at sample 300, the record has 400"):
        load_velocity_series(_record(), SEGS[:-1])


def test_program_table_in_um_per_s_and_kn_with_the_unplaced_note() -> None:
    segs = (Segment(1000.0, 1080.0, 2.5e-6, 0, 160, normal=12500.0),
            Segment(1080.0, 1150.0, 0.0, 160, 300, 7.25, 12600.0, 1079.2, 1080.5, False, False,
                    0.42))
    lines = segments_table(segs, "N").splitlines()
    assert "normal (kN)" in lines[0]
    row0, row1 = lines[1].split(), lines[2].split()
    # velocity in m/s and um/s, samples i_end - i_start, confidence, normal force in kN
    assert row0 == ["0", "1000", "-", "1080", "80", "2.5000e-06", "2.5", "160", "-", "12.5"]
    assert row1 == ["1", "1080", "-0.8/+0.5*", "1150", "70", "0.0000e+00", "0", "140", "7.25",
                    "12.6", "hold"]
    assert "normal: mean normal force, kN" in lines[3]
    assert lines[4].startswith("* segment(s) 1: the record does not place the change")
    assert "below 90 %" in lines[4]
    # in Pa: MPa, and no note when every change is placed
    pa = segments_table((Segment(1000.0, 1080.0, 2.5e-6, 0, 160, normal=7.5e6),), "Pa")
    assert pa.splitlines()[1].split()[-1] == "7.5" and "MPa" in pa.splitlines()[0]
    assert len(pa.splitlines()) == 3


# --- userfixB (6, 15): a hold split by a normal-stress change; a program without a step
def test_a_normal_change_during_a_hold_leaves_one_hold_and_its_reslide() -> None:
    # 2 um/s to 1050 s; at rest 1050-1110 s with the normal stress 5 -> 7 MPa at 1080 s
    # (two segments, as detection gives them: a normal-stress change is a boundary); 3 um/s
    # after. Lead min(0.5 x 50 s, 50 um / 2 um/s = 25 s) = 25 s -> from 1025 s (sample 50).
    # Mistakes: the hold cut at the change (30 s, the window ending at 1110 s with v_after 0:
    # the user's report), the reslide's segment skipped, before and after swapped
    from dataclasses import replace

    segs = make_segments(T, [0, 100, 160, 220, 400], [2e-6, 0.0, 0.0, 3e-6])
    segs = tuple(replace(s, normal=n) for s, n in zip(segs, (5e6, 5e6, 7e6, 7e6), strict=True))
    (w,) = slice_steps(_record(), segs)
    assert (w.kind, w.i_start, w.i_end, w.t_change, w.v_before, w.v_after, w.hold) == (
        "shs", 50, 400, 1050.0, 2e-6, 3e-6, 60.0)
    assert w.normal_changes == ((1080.0, 5e6, 7e6),)
    # a hold without a normal change has none; one split at its end gives no window
    (plain,) = slice_steps(_record(), make_segments(T, [0, 100, 220, 400], [2e-6, 0.0, 3e-6]))
    assert plain.hold == 60.0 and plain.normal_changes == ()
    with pytest.raises(ValueError, match="no velocity step or hold"):
        slice_steps(_record(), make_segments(T, [0, 100, 220, 300], [2e-6, 0.0, 0.0]))


def test_normal_change_values_and_text_in_the_tables_units() -> None:
    from dataclasses import replace

    from dryfriction.records.labsteps import normal_change_text, normal_change_values

    segs = make_segments(T, [0, 100, 160, 400], [2e-6, 0.0, 0.0])
    segs = tuple(replace(s, normal=n) for s, n in zip(segs, (5e6, 5.5e6, 7.25e6), strict=True))
    # the change reported at 1080.02 s finds the boundary at 1080 s (segment 2)
    ch = normal_change_values(segs, [1080.02])
    assert ch == ((1080.02, 5.5e6, 7.25e6),)
    assert normal_change_text(ch) == "t = 1080.02 s: 5.5 -> 7.25 MPa"
    assert normal_change_text(((1080.0, 2500.0, 3750.0),), "N") == "t = 1080 s: 2.5 -> 3.75 kN"


def test_a_one_velocity_program_is_refused_with_its_reason() -> None:
    # given by hand: the reason, not "give the program with --segments" (what the user did);
    # detected: an example inside the record, at its speed, that parse_segments accepts
    from dryfriction.records.labsteps import parse_segments

    one = make_segments(T, [0, 400], [2.5e-6])
    with pytest.raises(ValueError) as exc:
        slice_steps(_record(), one, given=True)
    assert str(exc.value) == ("bench.csv: no velocity step or hold in the load program given "
                              "with --segments (1 segment(s), velocities 2.5e-06 m/s): a "
                              "one-velocity record has no velocity step to fit")
    with pytest.raises(ValueError) as exc:
        slice_steps(_record(), one)
    msg = str(exc.value)
    assert "--segments, e.g. 0:2.5e-06,99.8:2.5e-05 (2.5 um/s, then 25 um/s from 99.8 s" in msg
    example = msg.split("e.g. ")[1].split(" ")[0]
    segs = parse_segments(example, _record())
    assert [s.velocity for s in segs] == [2.5e-6, 2.5e-5]
    assert len(slice_steps(_record(), segs)) == 1
    hold_end = make_segments(T, [0, 200, 400], [2.5e-6, 0.0])
    with pytest.raises(ValueError, match="one sliding velocity and a hold with no sliding on "
                       "one side"):
        slice_steps(_record(), hold_end, given=True)
    with pytest.raises(ValueError, match=r"velocities 0 m/s\): the load point does not move"):
        slice_steps(_record(), make_segments(T, [0, 400], [0.0]))
