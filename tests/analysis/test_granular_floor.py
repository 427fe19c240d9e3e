"""The stick-slip scan's default event floor (analysis/stickslip.py ``granular_floor``: the
force one trap's death removes, eqs. 12, 23, 32) against its definition with the death age
solved here by a root finder, in both pinning regimes and at a generic velocity, density and
factor (issue 25). Each test names the mistake it is for; each was seen failing with it
applied."""

from __future__ import annotations

import math

import pytest
from scipy.optimize import brentq

from dryfriction.analysis.stickslip import granular_floor
from dryfriction.theory.model import TrapModel
from dryfriction.theory.trap import Trap


@pytest.mark.parametrize("alpha", [0.08, 0.31])  # very strong and strong pinning
def test_floor_is_one_death_at_the_spinodal(alpha: float) -> None:
    # mistakes: the radius, not its square (the force of a trap scales with its area); mu_el
    # left out (right at mu_el = 1); the death age at w = 1 instead of the spinodal y_c
    eps, mu_el, u, n, factor = 0.04, 0.37, 0.3, 73.0, 2.2
    trap = Trap(alpha)
    # eq. 32 at the spinodal: -1 + u T = y_c a_r(T), a_r^2 = 1 + eps ln(1 + T) (eq. 17)
    tau = brentq(lambda T: -1.0 + u * T - trap.y_c * math.sqrt(1 + eps * math.log1p(T)),
                 1e-9, 1e6, xtol=1e-14, rtol=1e-15)
    r2 = 1.0 + eps * math.log1p(tau)
    want = factor * mu_el * trap.f_c * r2 / (trap.H0 * n)
    got = granular_floor(n, u, TrapModel(alpha=alpha, eps=eps, mu_el=mu_el), factor=factor)
    assert got == pytest.approx(want, rel=1e-9)
