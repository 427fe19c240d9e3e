"""``ensemble.thermal``'s small helpers at generic points, each branch and both sides of its
switch (issue 25, strengthen6B); the junction strength ``g(V) = A asinh(V e^{1/A}/(2 V_ref))``
is written here from docs/model.md, not taken from the package."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from dryfriction.ensemble import thermal
from dryfriction.ensemble.thermal import VelocityScale, creep_substeps, initial_velocity

A, VREF = 0.07, 0.31


def _g(v: float, direct: float = A, v_ref: float = VREF) -> float:
    return direct * math.asinh(v * math.exp(1.0 / direct) / (2.0 * v_ref))


def test_velocity_scale_is_g_of_the_step_velocity_and_its_slope() -> None:
    """``X -> g((X - X0)/dt)`` with ``X0 != 0`` and ``dt != 1``; slope by central difference."""
    s = VelocityScale(x0=2.4, dt=0.37, direct=A, v_ref=VREF)
    x = 2.4 + 0.05
    assert s(x) == pytest.approx(_g(0.05 / 0.37), rel=1e-12)
    h = 1e-6
    fd = (s(x + h) - s(x - h)) / (2 * h)
    assert s.slope(x) == pytest.approx(fd, rel=1e-6)


@pytest.mark.parametrize("z", [0.6, 19.5, 20.5, 31.0])
def test_inverse_strength_inverts_g_on_both_sides_of_its_switch(z: float) -> None:
    """``g(V(y)) = y`` for ``y/A`` below and above 20 (the logarithmic form)."""
    y = z * A
    v = thermal._inverse_strength(y, A, VREF)
    assert v > 0
    assert _g(v) == pytest.approx(y, rel=1e-12)


def test_creep_substeps_counts_substep_slips_of_the_spacing() -> None:
    ens = SimpleNamespace(model=SimpleNamespace(direct=A), track=SimpleNamespace(spacing=0.8))
    step = thermal.SUBSTEP_SLIP * 0.8
    assert creep_substeps(ens, 3.4 * step) == 4          # ceil
    assert creep_substeps(ens, -3.4 * step) == 4         # a backward travel counts too
    assert creep_substeps(ens, 3.0 * step * (1 - 1e-12)) == 3
    assert creep_substeps(ens, 0.0) == 1                 # at least one
    athermal = SimpleNamespace(model=SimpleNamespace(direct=0.0), track=ens.track)
    assert creep_substeps(athermal, 3.4 * step) == 1


def test_initial_velocity_precedence() -> None:
    thermal_m, athermal_m = SimpleNamespace(direct=A), SimpleNamespace(direct=0.0)
    steady = SimpleNamespace(kind="steady", velocity=0.23)
    rest = SimpleNamespace(kind="rest", velocity=None)
    assert initial_velocity(athermal_m, steady, 0.9) == 0.0
    assert initial_velocity(thermal_m, steady, 0.9) == 0.9        # the first segment first
    assert initial_velocity(thermal_m, steady, None) == 0.23      # then the steady state's
    assert initial_velocity(thermal_m, rest, None) == 0.0
    assert initial_velocity(thermal_m, SimpleNamespace(kind="steady", velocity=None), None) == 0.0
    assert initial_velocity(thermal_m, rest, 0.0) == 0.0
    assert initial_velocity(thermal_m, steady, 0.0) == 0.0       # a hold first: its 0, not 0.23
