"""The rate-and-state twin's stability numbers written out (Rice & Ruina 1983), with damping
and mass, at a generic point of the trap model (issue 25: one regime only hides a term).

:func:`~dryfriction.analysis.rsf_stability.rsf_stability_prediction` takes the model's
effective ``a, b, Dc`` (:func:`~dryfriction.theory.linear_stability.effective_rsf`) and returns
``K_c = (b - a')/Dc [1 + M u^2/(a' Dc)]`` and ``omega_c = (u/Dc) sqrt((b - a')/a')`` with
``a' = a + eta u`` (the damping as an addition to the direct effect). Mistakes this is for: the
damping left out of either (every other test of the twin runs at ``eta = 0``), the mass term
with ``u`` instead of ``u^2``.
"""

from __future__ import annotations

import math

import pytest

from dryfriction.analysis.rsf_stability import rsf_stability_prediction
from dryfriction.theory.linear_stability import effective_rsf
from dryfriction.theory.model import TrapModel


@pytest.mark.parametrize("mass, damping", [(0.0, 0.0), (0.0, 0.013), (2.3, 0.013),
                                           (0.7, 0.0)])
def test_twin_stability_written_out(mass: float, damping: float) -> None:
    u, eps, alpha = 0.37, 0.023, 0.21
    p = effective_rsf(u, TrapModel(alpha=alpha, eps=eps, creep="log"))
    a1 = p["a"] + damping * u
    assert p["b"] > a1  # a Hopf point exists
    got = rsf_stability_prediction(u, TrapModel(alpha, eps), mass=mass, damping=damping)
    kc = (p["b"] - a1) / p["dc"] * (1.0 + mass * u * u / (a1 * p["dc"]))
    omega = u / p["dc"] * math.sqrt((p["b"] - a1) / a1)
    assert got["K_c"] == pytest.approx(kc, rel=1e-12)
    assert got["omega_c"] == pytest.approx(omega, rel=1e-12)
