"""The steady-sliding entry checks (theory/steady.py check_steady_inputs) and the Eyring-Nabarro
velocity floor against its closed form ``u_min = (1 + w_d/sqrt(eps))/T_v(eps)``, each refusal
on both sides, an eps per point (issue 25: a refusal boundary, a branch rarely taken)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.theory.creep import max_age
from dryfriction.theory.model import TrapModel
from dryfriction.theory.steady import check_steady_inputs, min_velocity
from dryfriction.theory.trap import Trap


def test_velocity_floor_is_its_closed_form() -> None:
    for alpha, eps in ((0.11, 0.043), (0.3, 0.09)):  # very strong, strong pinning
        w_d = Trap(alpha).death_point
        want = (1.0 + w_d / math.sqrt(eps)) / max_age(eps)
        got = min_velocity(TrapModel(alpha, eps, "eyring-nabarro"))
        assert got == pytest.approx(want, rel=1e-9)
    assert min_velocity(TrapModel(0.11, 0.043, "log")) == 0.0


def test_checks_on_both_sides() -> None:
    a, u, e = check_steady_inputs([0.2, 3.0], 0.04, 0.11, "log")
    assert a == 0.11 and list(u) == [0.2, 3.0] and float(e) == 0.04
    check_steady_inputs(1e-30, 1.0, 0.11, "log")  # U_MIN and EPS_MAX themselves
    check_steady_inputs(1e30, 0.0, 0.11, "log")
    for args, name in (((0.5e-30, 0.04), "u"), ((2e30, 0.04), "u"), ((1.0, 1.01), "eps"),
                       ((1.0, -1e-9), "eps")):
        with pytest.raises(ValueError, match=f"^{name} = "):
            check_steady_inputs(*args, 0.11, "log")
    with pytest.raises(ValueError, match=r"^u has shape \(3,\) and eps \(2,\): they do not "):
        check_steady_inputs(np.ones(3), np.full(2, 0.04), 0.11, "log")
    # the Eyring-Nabarro floor, each eps its own
    e1, e2 = 0.09, 0.043
    u1 = min_velocity(TrapModel(0.11, e1, "eyring-nabarro"))
    u2 = min_velocity(TrapModel(0.11, e2, "eyring-nabarro"))
    check_steady_inputs([1.001 * u1, 1.001 * u2], [e1, e2], 0.11, "eyring-nabarro")
    with pytest.raises(ValueError, match=r"is beyond the Eyring-Nabarro law's range at "
                                         r"eps = 0\.09"):
        check_steady_inputs([1.001 * u2, 0.999 * u1], [e2, e1], 0.11, "eyring-nabarro")
    assert u2 < u1  # (so the first point above is inside its own floor)
