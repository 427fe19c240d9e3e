"""``analysis.rsf_stability.rsf_stability_prediction`` where the twin is stable at any
stiffness (issue 25, strengthen7B): with ``eta`` such that ``a + eta u > b``, Rice & Ruina's
``K_c = (b - a')/Dc`` is negative and there is no Hopf frequency: NaN, not 0 (a 0 in the
table would read as a frequency)."""

from __future__ import annotations

import math

import pytest

from dryfriction.analysis.rsf_stability import rsf_stability_prediction
from dryfriction.theory.linear_stability import effective_rsf
from dryfriction.theory.model import TrapModel


def test_no_hopf_frequency_when_damping_stabilises() -> None:
    u, model = 0.37, TrapModel(alpha=0.21, eps=0.023)
    p = effective_rsf(u, model)
    eta = 1.7 * (p["b"] - p["a"]) / u  # a' = a + eta u exceeds b by 0.7 (b - a)
    got = rsf_stability_prediction(u, model, damping=eta)
    a1 = p["a"] + eta * u
    assert got["K_c"] == pytest.approx((p["b"] - a1) / p["dc"], rel=1e-12) and got["K_c"] < 0
    assert math.isnan(got["omega_c"])
