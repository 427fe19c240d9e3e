"""``rsf.stability.linear_stability`` with two state variables against the characteristic
polynomial written in the test (issue 25, strengthen7B).

Linearising ``mu = mu0 + a ln(V/V0) + sum_i b_i ln(V0 theta_i/Dc_i)`` about steady sliding at
``v`` (``x = dV/V``, ``y_i = dtheta_i/theta_i``): every state law here (ageing, slip, PRZ) gives
``y_i' = -c_i (x + y_i)``, ``c_i = v/Dc_i``; the spring ``tau' = k (V_L - V)`` and
``m v x' = dtau - (a + eta v) x - sum b_i y_i``. With ``e^{lambda t}``::

    (m v lambda^2 + (a + eta v) lambda + k v)(lambda + c1)(lambda + c2)
        - lambda [b1 c1 (lambda + c2) + b2 c2 (lambda + c1)] = 0

a cubic quasi-statically (``m = 0``) and a quartic with inertia; its roots are the
eigenvalues of the solver's Jacobian (``ln V, ln theta_1, ln theta_2[, tau]``). The second
state variable enters only here and in the driver's steps: a mistake in its Jacobian column
(``b2`` for ``b``, ``Dc`` for ``Dc2``) shifts the roots. Generic numbers: ``v`` is not ``V0``.
"""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.rsf.law import RateState
from dryfriction.rsf.stability import linear_stability

A, B, DC, B2, DC2, V0, MU0 = 0.0071, 0.0093, 23e-6, 0.0041, 310e-6, 1e-6, 0.6
V = 3.7e-6


def _roots(k: float, eta: float, m: float) -> np.ndarray:
    c1, c2 = V / DC, V / DC2
    p1 = np.poly1d([m * V, A + eta * V, k * V]) if m > 0 else np.poly1d([A + eta * V, k * V])
    lin = np.poly1d([1.0, c1]) * np.poly1d([1.0, c2])
    memory = np.poly1d([1.0, 0.0]) * (B * c1 * np.poly1d([1.0, c2])
                                      + B2 * c2 * np.poly1d([1.0, c1]))
    return np.sort_complex(np.roots((p1 * lin - memory).coeffs))


@pytest.mark.parametrize("law", ["ageing", "slip", "prz"])
@pytest.mark.parametrize("k, eta, m", [(310.0, 0.0, 0.0), (170.0, 230.0, 0.0),
                                       (410.0, 90.0, 3.1e6)])
def test_two_state_eigenvalues_are_the_characteristic_roots(law: str, k: float, eta: float,
                                                            m: float) -> None:
    p = RateState(A, B, DC, MU0, V0, law, b2=B2, dc2=DC2)  # type: ignore[arg-type]
    got = np.sort_complex(linear_stability(p, V, k, eta, m))
    want = _roots(k, eta, m)
    assert got.size == want.size == (4 if m > 0 else 3)
    assert np.max(np.abs(got - want)) < 1e-9 * np.max(np.abs(want)), (got, want)
