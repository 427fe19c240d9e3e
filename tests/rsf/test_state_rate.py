"""The state laws' rates (rsf/law.py ``RateState.state_rate``, a public function the compiled
stepper does not call) against the laws written here at generic points, both signs of the
velocity, the second state variable's Dc (issue 25: no test read it directly; a PRZ rate
without its 1/2 went unnoticed). Each test names the mistake it is for; each was seen failing
with it applied."""

from __future__ import annotations

import math

import pytest

from dryfriction.rsf.law import RateState

V, THETA, DC, DC2 = 2.3e-6, 7.1, 13e-6, 170e-6


def _law(state_law: str, **kw: float) -> RateState:
    return RateState(0.011, 0.015, DC, 0.6, 1e-6, state_law=state_law, **kw)  # type: ignore[arg-type]


@pytest.mark.parametrize("v", [V, -V])
def test_each_law_at_a_generic_point(v: float) -> None:
    # mistakes: PRZ's rate without its 1/2; the slip law's sign; a reverse velocity's rate of
    # its signed value (the state grows without bound when sliding backwards)
    w = V * THETA / DC  # 1.256: away from steady state, above it
    want = {"ageing": 1.0 - w, "nagata": 1.0 - w, "prz": 0.5 * (1.0 - w * w),
            "slip": -w * math.log(w)}
    for name, rate in want.items():
        got = float(_law(name, regularized=(v < 0)).state_rate(v, THETA))
        assert got == pytest.approx(rate, rel=1e-13), name


def test_second_state_variable_and_steady_state() -> None:
    # mistakes: the second state's rate with the first's Dc; a law whose rate is not zero in
    # steady state
    law = _law("ageing", b2=0.004, dc2=DC2)
    assert float(law.state_rate(V, THETA, dc=DC2)) == pytest.approx(1.0 - V * THETA / DC2)
    for name in ("ageing", "slip", "prz", "nagata"):
        assert float(_law(name).state_rate(V, DC / V)) == pytest.approx(0.0, abs=1e-15)
