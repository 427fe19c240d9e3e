"""``ensemble.balance.root_in_bracket`` on closed-form roots: rising and falling ``G``, the
bracket given in either order, no usable slope (bisection only), a root at ``xb`` itself and a
slope that overstates the nearness of the root (issue 25, strengthen6B)."""

from __future__ import annotations

import math

import pytest

from dryfriction.ensemble.balance import root_in_bracket

ROOT = 2.7 ** (1.0 / 3.0)


def _rise(x: float) -> tuple[float, float]:
    return x**3 - 2.7, 3.0 * x**2


def _fall(x: float) -> tuple[float, float]:
    return 2.7 - x**3, -3.0 * x**2


@pytest.mark.parametrize("h", [_rise, _fall])
@pytest.mark.parametrize("xa, xb", [(0.4, 3.1), (3.1, 0.4)])
def test_root_of_a_cubic_either_way(h, xa: float, xb: float) -> None:
    x = root_in_bracket(h, xa, h(xa), xb, h(xb))
    assert x == pytest.approx(ROOT, abs=1e-12)


def test_bisection_without_a_slope_and_a_root_at_the_end() -> None:
    def h(x: float) -> tuple[float, float]:
        return x**3 - 2.7, math.nan

    assert root_in_bracket(h, 0.4, h(0.4), 3.1, h(3.1)) == pytest.approx(ROOT, abs=1e-12)
    assert root_in_bracket(_rise, 0.4, _rise(0.4), ROOT, (0.0, 3.0 * ROOT**2)) == ROOT


def test_a_huge_slope_at_the_start_does_not_stop_the_search() -> None:
    """``G = sqrt(x - x0) - c`` near ``x0``: the slope is huge there, the first Newton step tiny."""
    x0, c = 1.3, 0.45

    def h(x: float) -> tuple[float, float]:
        d = max(x - x0, 1e-300)
        return math.sqrt(d) - c, 0.5 / math.sqrt(d)

    xa, xb = x0, x0 + 1.0  # G'(xa) ~ 5e149: a first Newton step ~ 1e-150
    x = root_in_bracket(h, xa, h(xa), xb, h(xb))
    assert x == pytest.approx(x0 + c * c, abs=1e-12)
