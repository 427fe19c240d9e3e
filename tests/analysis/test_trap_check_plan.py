"""``analysis.trap_hopf_check.check_plan`` and ``check_cost`` from their definitions (issue 25,
strengthen7B): the runs the simulated check of a Hopf point may make and the CPU estimate that
refuses a check over ``TRAP_CHECK_CPU_MAX`` before any simulation.

* supercritical (u = 0.87): at each of :func:`check_distances`, runs of 60, 120 and 240
  periods (doubling up to ``SUPER_PERIODS[1]``);
* subcritical (u = 0.013): ``2 + SUB_STEPS`` bisection starts at the swing distance, their
  periods ``2/(beta T)`` within ``SUB_PERIODS``, then the carried stick-slip's 70 periods;
* the cost: each run's periods plus 2 of preparation, a period ``u T lambda / SUBSTEP_SLIP``
  substeps of ``6e-5 + 1.5e-7 lambda WINDOW`` s, on a generic 137 pairs per a0.
"""

from __future__ import annotations

import math

import pytest

from dryfriction.analysis.trap_hopf import trap_hopf
from dryfriction.analysis.trap_hopf_check import (
    SUB_STEPS,
    SUB_SWING,
    check_cost,
    check_distances,
    check_plan,
    swing_distance,
)
from dryfriction.ensemble.population import Track
from dryfriction.theory.model import TrapModel

MODEL = TrapModel(alpha=0.13, eps=0.037, direct=0.023, v_ref=1.3)
RES = {"n": 16, "panels": 12, "stretch": 1.5}
LAM = 137.0


def _cost(plan: list[tuple[float, int]], u: float, omega: float) -> float:
    T = 2 * math.pi / omega
    per_period = u * T * LAM / 0.25 * (6e-5 + 1.5e-7 * LAM * 7.0)
    return sum((p + 2) * per_period for _, p in plan)


@pytest.mark.parametrize("u, nature", [(0.87, "supercritical"), (0.013, "subcritical")])
def test_plan_and_cost_are_their_definitions(u: float, nature: str) -> None:
    h = trap_hopf(u, MODEL, **RES)
    assert h.nature == nature
    plan = check_plan(h, u)
    if nature == "supercritical":
        want = [(d, p) for d in check_distances(h, u) for p in (60, 120, 240)]
    else:
        d = swing_distance(h, u, SUB_SWING)
        T = 2 * math.pi / h.omega
        periods = int(max(30, min(80, 2.0 / (abs(h.dbeta_dK) * h.K_c * d * T))))
        assert SUB_STEPS == 3
        want = [(d, periods)] * 5 + [(d, 70)]
    assert plan == want
    assert check_cost(h, u, Track(LAM)) == pytest.approx(_cost(want, u, h.omega), rel=1e-12)
