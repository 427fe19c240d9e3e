"""The stick-slip summary analyses the spring force in friction units (mu_el K (X_pull - X)):
after the transient of a steadily sliding spring run its mean force is the mean friction the
run samples (force balance, quasi-static, no damping), for mu_el != 1. Written for the
survivors of the second blind mutant review (benchmarks/blind_mutants2.py:
stickslip_force_no_mu_el, the force in F_el units, off by mu_el)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.analysis.stickslip import summarise
from dryfriction.ensemble.driving import Output, SpringDrive, simulate
from dryfriction.ensemble.population import Initial, Track, TrapModel
from dryfriction.program import Segment, VelocityProgram


def test_summary_mean_force_is_the_mean_friction() -> None:
    model, track = TrapModel(0.13, 0.04, mu_el=0.41), Track(50)
    drive = SpringDrive(0.03, 0.0, VelocityProgram([Segment(0.1, slip=6.0)]))
    res = simulate(model, drive, Initial("steady", velocity=0.1, track=track),
                   Output(every_slip=0.05))
    s = summarise(res, drive, model, track)  # transient: half the travel
    after = (res.x_pull - res.x_pull[0]) >= 3.0
    spring = 0.41 * 0.03 * (res.x_pull - res.x)  # mu_el K (X_pull - X), written here
    assert s["mean_force"] == pytest.approx(float(np.mean(res.mu[after])), rel=2e-3)
    assert s["mean_force"] == pytest.approx(float(np.mean(spring[after])), rel=2e-3)
    assert s["range"] <= float(np.ptp(spring[after])) * (1 + 1e-9)
