"""The trap run's sampling and recording (ensemble/result.py) against definitions written
here (issue 25): the sampling interval of a backward segment and of a hold, the grid of a
program (ceil per segment, boundaries and snapshots kept), the off-lattice resampling at its
thresholds, the scalar position against the program's, the snapshot refusal at the run's end
itself, the recorder's friction units and the summary's event totals."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from dryfriction.ensemble.result import (
    COLUMNS,
    Output,
    Recorder,
    _off_lattice,
    check_snapshots,
    position_function,
    sample_interval,
    segment_grid,
)
from dryfriction.program import Segment, VelocityProgram

PROG = VelocityProgram([Segment(0.4, duration=2.5), Segment(0.0, duration=1.5),
                        Segment(-0.25, slip=0.3), Segment(1.6, duration=0.7)], x0=0.35)


def test_sample_interval_in_time_and_in_slip() -> None:
    assert sample_interval(-0.25, Output(every=0.7)) == 0.7
    assert sample_interval(-0.25, Output(every_slip=0.05)) == pytest.approx(0.2, rel=1e-15)
    assert sample_interval(0.4, Output(every_slip=0.05)) == pytest.approx(0.125, rel=1e-15)
    assert sample_interval(0.0, Output(every_slip=0.05)) == math.inf  # a hold: one step


def test_segment_grid_is_ceil_per_segment_with_boundaries_and_snapshots() -> None:
    out = Output(every_slip=0.3, snapshots=(0.9, 3.0, 99.0))
    g = segment_grid(PROG, out)
    # segment slips 1.0, hold, 0.3, 1.12 at every_slip 0.3: 4, 1, 1, 4 equal steps
    want = np.r_[0.0, 2.5 * np.arange(1, 5) / 4, 4.0, 5.2, 5.2 + 0.7 * np.arange(1, 5) / 4]
    want = np.union1d(want, [0.9, 3.0])  # a snapshot after the end is not a sample time
    np.testing.assert_allclose(g, want, rtol=1e-14)
    # a step exactly dividing the segment adds no sample
    assert segment_grid(VelocityProgram([Segment(0.5, duration=2.0)]),
                        Output(every=0.5)).size == 5


def test_off_lattice_thresholds() -> None:
    # 60 steps of exactly 2 cells each: the phase never moves -> the least n' coprime
    assert _off_lattice(120.0, 60) == 61
    # the steps' phases drift by n |step - m| cells over the segment: under half a cell the
    # samples see too few phases (resampled), from half a cell on they are left alone
    assert _off_lattice(120.45, 60) == 61 and _off_lattice(119.55, 60) == 61
    assert _off_lattice(120.55, 60) == 60 and _off_lattice(119.45, 60) == 60
    assert _off_lattice(98.0, 49) == 49  # fewer than 50 samples: left alone
    assert _off_lattice(25.0, 60) == 60  # steps under a cell
    # the choice: gcd(cells mod n', n') = 1
    n = _off_lattice(300.0, 100)
    assert n > 100 and math.gcd(300 % n, n) == 1
    assert all(math.gcd(300 % k, k) != 1 for k in range(101, n))


def test_position_function_is_the_programs_position() -> None:
    f = position_function(PROG)
    t = np.array([-0.3, 0.0, 1.7, 2.5, 3.3, 4.0, 4.6, 5.2, 5.5, 5.9, 7.0])
    np.testing.assert_array_equal([f(float(s)) for s in t], PROG.position(t))


def test_snapshots_up_to_the_run_end_itself() -> None:
    drive = SimpleNamespace(program=PROG)
    check_snapshots(drive, Output(every=1.0, snapshots=(0.0, 5.9)))
    with pytest.raises(ValueError, match=r"^output\.snapshots: the time 5\.91 t0 is after the "
                                         r"run's end: the drive's program ends at t = 5\.9 t0"):
        check_snapshots(drive, Output(every=1.0, snapshots=(5.91, 1.0)), qualified=True)
    ramp = SimpleNamespace(hold=2.0, max_force=3.0, rate=0.5)  # a force drive: ends at 8
    check_snapshots(ramp, Output(every=1.0, snapshots=(8.0,)))
    with pytest.raises(ValueError, match="the force ramp reaches max_force at t = 8 t0"):
        check_snapshots(ramp, Output(every=1.0, snapshots=(8.01,)))
    assert Output(every=1.0, snapshots=(3.0, 1.0)).snapshots == (1.0, 3.0)
    with pytest.raises(ValueError, match="exactly one of every"):
        Output()


def test_recorder_scales_friction_and_the_summary_totals_events() -> None:
    rec = Recorder(mu_el=0.45)
    ens = SimpleNamespace(t=0.0, x=0.0)
    for i, ev in enumerate([(3, 1, 0), (2, 2, 1), (0, 1, 4)]):
        ens.t, ens.x = 0.5 * i, 0.1 * i
        o = SimpleNamespace(force=0.8 + 0.1 * i, n_active=10 - i, mean_age=2.0 + i)
        rec.add(ens, o, v=0.2, x_pull=1.0 + i, f_applied=0.7, events=ev)  # type: ignore[arg-type]
    res = rec.result({"partial": True, "threshold": 0.6})
    assert list(res.columns()) == list(COLUMNS)
    np.testing.assert_allclose(res.mu, 0.45 * np.array([0.8, 0.9, 1.0]), rtol=1e-15)
    np.testing.assert_allclose(res.f_applied, 0.45 * 0.7, rtol=1e-15)
    np.testing.assert_array_equal(res.n_active, [10, 9, 8])
    np.testing.assert_array_equal(res.x_pull, [1.0, 2.0, 3.0])
    s = res.summary()
    assert s["events"] == {"births": 5, "spinodal": 4, "exits": 5}
    assert s["threshold"] == 0.6 and res.partial
