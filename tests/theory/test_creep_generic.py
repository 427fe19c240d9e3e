"""The creep laws' derivatives and inverses against finite differences and round trips at generic
clocks and creep parameters (issue 25): ``dradius_sq`` and ``clock_at_radius`` feed the
ensemble's kernel and the stability's memory integrals, and no test read them directly. Each
test names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dryfriction.theory.creep import EyringNabarroCreep, LogCreep

PROPS = settings(max_examples=30, derandomize=True, deadline=None)
LAWS = {"log": LogCreep, "eyring-nabarro": EyringNabarroCreep}


@PROPS
@given(name=st.sampled_from(sorted(LAWS)), eps=st.floats(0.003, 0.2),
       frac=st.floats(0.02, 0.9))
def test_radius_sq_slope_is_its_finite_difference(name: str, eps: float, frac: float) -> None:
    """``d(a_r^2)/dQ``: for the log law ``eps``; for Eyring-Nabarro ``eps/(1 - eps Q)^2``. The
    clock is a fraction of the law's range (``1/eps`` for Eyring-Nabarro). Mistakes: the
    square of the denominator dropped; ``eps`` left out of the numerator (right at eps = 1)."""
    law = LAWS[name](eps)
    c = frac / eps
    h = 1e-5 * c
    fd = (law.radius_sq(c + h) - law.radius_sq(c - h)) / (2 * h)
    assert float(law.dradius_sq(c)) == pytest.approx(float(fd), rel=1e-7)


@PROPS
@given(name=st.sampled_from(sorted(LAWS)), eps=st.floats(0.003, 0.2),
       frac=st.floats(0.02, 0.9))
def test_clock_at_radius_inverts_the_radius(name: str, eps: float, frac: float) -> None:
    """``clock_at_radius(sqrt(radius_sq(Q))) = Q``, and the age round trip through the clock.
    Mistakes: ``1 - 1/r`` for ``1 - 1/r^2``; ``r^2 - 1`` times ``eps`` for over it."""
    law = LAWS[name](eps)
    c = frac / eps
    r = float(np.sqrt(law.radius_sq(c)))
    assert float(law.clock_at_radius(r)) == pytest.approx(c, rel=1e-10)
    T = float(law.age(c))
    assert float(law.radius(T)) == pytest.approx(r, rel=1e-9)


def test_eyring_nabarro_range_end_and_age_derivative() -> None:
    """At the end of the law's range ``Q_v = (1 - eps)/eps`` the radius squared is ``1/eps``; the
    age's derivative is ``e^Q/(1 - eps Q)`` (a central difference of the quadrature). Mistakes:
    the range end at ``1/eps``; the derivative without its denominator."""
    law = EyringNabarroCreep(0.037)
    assert float(law.radius_sq(law.valid_clock)) == pytest.approx(1 / 0.037, rel=1e-12)
    for c in (3.1, 17.0, 24.5):
        h = 1e-4
        fd = (law.age(c + h) - law.age(c - h)) / (2 * h)
        assert float(law.dage(c)) == pytest.approx(float(fd), rel=1e-7)
        assert float(law.dage(c)) == pytest.approx(np.exp(c) / (1 - 0.037 * c), rel=1e-14)
