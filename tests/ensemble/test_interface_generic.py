"""The interface chain's constants against an independent route (issue 25): the stiffest mode
of the free chain from a matrix eigenvalue solver, the sound speed at a generic coupling and
mass. Each test names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.ensemble.interface import InterfaceModel
from dryfriction.theory.model import TrapModel


@pytest.mark.parametrize("n", [1, 2, 3, 7, 40])
def test_stiffest_mode_of_the_free_chain_against_its_matrix(n: int) -> None:
    # mistake: the fixed-ends chain's 4 sin^2(pi N / (2 (N + 1))) for the free chain's
    # 4 sin^2(pi (N - 1) / (2 N)) (the time step's bound then too large or too small)
    lap = 2.0 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
    lap[0, 0] = lap[-1, -1] = 1.0 if n > 1 else 0.0  # free ends: one neighbour each
    want = float(np.linalg.eigvalsh(lap).max()) if n > 1 else 0.0
    m = InterfaceModel(TrapModel(eps=0.04), n_elements=n, coupling=3.7, mass=0.23)
    assert m.coupling_eigenvalue_max == pytest.approx(want, rel=1e-12, abs=1e-15)
    assert m.sound_speed() == pytest.approx(math.sqrt(3.7 / 0.23), rel=1e-15)
