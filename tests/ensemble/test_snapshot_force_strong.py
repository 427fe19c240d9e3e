"""Strong pinning (``y_c < 1``: traps on the (-) branch, ``f_-(w) = -f_+(-w)``): the
snapshot's per-trap forces, computed in Python from ``p``, the radius and the branch, sum to
the friction the compiled kernel sampled at the same instant (issue 25, strengthen7B; the
very strong case is tests/ensemble/test_snapshot_force.py). ``mu_el`` = 0.41, a step up and
a reversal, so that both branches carry force."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.ensemble.driving import Output, VelocityDrive, simulate
from dryfriction.ensemble.population import Initial, Track, TrapModel
from dryfriction.program import Segment, VelocityProgram


def test_snapshot_forces_sum_to_the_friction_in_strong_pinning() -> None:
    """Mistakes: the (-) branch's force with the sign of the (+) one (in the kernel or in the
    snapshot), the (-) branch clipped at ``+y_c``."""
    model = TrapModel(0.61, 0.043, mu_el=0.41)
    drive = VelocityDrive(VelocityProgram([Segment(0.1, slip=1.3), Segment(0.37, slip=0.9),
                                           Segment(-0.23, slip=0.4)]))
    t_step = 1.3 / 0.1
    t_back = t_step + 0.9 / 0.37 + 0.2 / 0.23
    res = simulate(model, drive, Initial("steady", velocity=0.1, track=Track(230)),
                   Output(every=0.5, snapshots=(t_step + 1.0, t_back)))
    assert len(res.snapshots) == 2
    for s in res.snapshots:
        i = int(np.argmin(np.abs(res.t - s["t"])))
        assert res.t[i] == pytest.approx(s["t"], abs=1e-9)
        minus = s["branch"] < 0
        assert minus.sum() > 20 and float(np.sum(s["force"][minus])) != 0.0
        assert float(np.sum(s["force"])) == pytest.approx(float(res.mu[i]), rel=1e-9, abs=1e-12)
