"""A population snapshot's per-trap forces are each trap's share of the friction: they sum to
the friction mu (in mu_el F/F_el) sampled at the same instant, for mu_el != 1. Written for the
survivors of the second blind mutant review (benchmarks/blind_mutants2.py:
ensres_snapshot_no_mu_el, the snapshot's forces not multiplied by mu_el)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.ensemble.driving import Output, VelocityDrive, simulate
from dryfriction.ensemble.population import Initial, Track, TrapModel
from dryfriction.program import Segment, VelocityProgram


def test_snapshot_forces_sum_to_the_sampled_friction() -> None:
    model = TrapModel(0.13, 0.04, mu_el=0.41)
    drive = VelocityDrive(VelocityProgram([Segment(0.1, slip=3.0), Segment(0.37, slip=2.0)]))
    res = simulate(model, drive, Initial("steady", velocity=0.1, track=Track(200)),
                   Output(every=1.0, snapshots=(17.0, 33.0)))  # before and after the step
    assert len(res.snapshots) == 2
    for s in res.snapshots:
        i = int(np.argmin(np.abs(res.t - s["t"])))
        assert res.t[i] == pytest.approx(s["t"], abs=1e-9)  # a sample at the snapshot
        assert float(np.sum(s["force"])) == pytest.approx(float(res.mu[i]), rel=1e-9)
