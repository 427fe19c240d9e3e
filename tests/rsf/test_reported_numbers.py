"""Rate-and-state numbers a user reads (summary.json's critical stiffness, the hold peak)
against closed forms computed here. Written for the survivors of the second blind mutant
review (benchmarks/blind_mutants2.py)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.program import Segment
from dryfriction.rsf.driving import simulate
from dryfriction.rsf.law import RateState
from dryfriction.rsf.spring import RSFOutput, SpringSlider

A, B, DC, MU0, V0 = 0.0113, 0.0157, 23e-6, 0.583, 1.3e-6


def test_critical_stiffness_at_the_final_load_velocity() -> None:
    """critical_stiffness_per_m = (b - a')/Dc with a' = a + eta V at the final load velocity
    (Rice & Ruina 1983 with the damping term, rsf.law.critical_stiffness), for a step
    1.7 -> 6.1 um/s with eta V comparable to a (mutant rsf_kc_first_load_velocity: taken at the
    first load velocity)."""
    v1, v2, eta = 1.7e-6, 6.1e-6, 310.0
    k = 3.0 * (B - A) / DC
    res = simulate(RateState(A, B, DC, MU0, V0),
                   SpringSlider([Segment(v1, slip=5 * DC), Segment(v2, slip=20 * DC)],
                                stiffness=k, damping=eta),
                   output=RSFOutput(every=2.0))
    want = (B - (A + eta * v2)) / DC
    assert abs(want - (B - (A + eta * v1)) / DC) > 0.05 * abs(want)  # the two differ
    assert res.summary()["critical_stiffness_per_m"] == pytest.approx(want, rel=1e-12)


def test_prz_hold_peak_heals_at_half_rate() -> None:
    """PRZ (Perrin, Rice & Zheng 1995): dtheta'/dt = 1 - (V theta'/(2 Dc))^2, and the package's
    theta = theta'/2 (so that theta_ss = Dc/V): at rest theta grows at 1/2. Kinematic hold
    peak mu_ss(V) + b ln(1 + V t_hold/(2 Dc)); the ageing law's, with rate 1, is higher
    (mutant rsf_prz_heal_rate: PRZ healing at theta' 's rate 1)."""
    v = 3.7e-6
    t_hold = np.array([0.7, 13.0, 410.0])
    prz = RateState(A, B, DC, MU0, V0, state_law="prz")
    mu_ss = MU0 + (A - B) * np.log(v / V0)
    want = mu_ss + B * np.log(1.0 + v * t_hold / (2.0 * DC))
    np.testing.assert_allclose(prz.hold_peak_friction(t_hold, v), want, rtol=0, atol=1e-12)
    ageing = RateState(A, B, DC, MU0, V0).hold_peak_friction(t_hold, v)
    assert np.all(ageing - want > 0.03 * B)  # b ln 2 at long holds
