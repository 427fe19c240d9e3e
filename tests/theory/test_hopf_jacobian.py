"""``theory.hopf.jacobian`` against the Jacobian written by hand, both methods, and
``first_lyapunov``'s residual bound on both sides (issue 25, strengthen7B).

A field of three components that mixes every coordinate, at a generic point with a generic
``scale``: the complex step is exact to rounding, the fourth-order differences to ``(h/L)^4``
with ``h = 0.01 scale`` (``L`` the field's own length, here about 1). A field whose critical
pair has ``Re lambda / omega = 3e-7`` is accepted under the default ``residual_max = 1e-6``,
one of ``3e-6`` refused.
"""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.theory.hopf import first_lyapunov, jacobian

X0 = np.array([0.37, -1.13, 0.71])


def _f(x: np.ndarray) -> np.ndarray:
    a, b, c = x
    return np.array([np.exp(0.7 * a) * b - c**2, np.sin(b) * c + a**3, np.log(2.0 + a * c) - b])


def _jac(x: np.ndarray) -> np.ndarray:
    a, b, c = x
    e = np.exp(0.7 * a)
    return np.array([[0.7 * e * b, e, -2.0 * c],
                     [3.0 * a**2, np.cos(b) * c, np.sin(b)],
                     [c / (2.0 + a * c), -1.0, a / (2.0 + a * c)]])


def test_complex_step_jacobian_is_the_hand_written_one() -> None:
    """Mistake: the complex step's ``h`` not divided out, or taken without ``scale``."""
    got = jacobian(_f, X0, "complex", 3.7)
    assert np.max(np.abs(got - _jac(X0))) < 1e-14 * np.max(np.abs(_jac(X0)))


def test_difference_jacobian_is_fourth_order_in_the_step_scale() -> None:
    """``h = 0.01 scale``: the error is ``O(h^4)``, 165 times larger at ``scale`` 1.9 than at
    0.53 (``(1.9/0.53)^4``), and 2e-11 relative at 0.53. Mistakes: a stencil weight off (a
    second-order or inconsistent stencil), the step without ``scale`` (the ratio is then 1)."""
    want = _jac(X0)
    big = float(np.max(np.abs(want)))
    errs = [float(np.max(np.abs(jacobian(_f, X0, "fd", s) - want))) / big for s in (0.53, 1.9)]
    assert errs[0] < 2e-11, errs
    assert errs[1] / errs[0] == pytest.approx((1.9 / 0.53) ** 4, rel=0.3), errs


def _rotation(sigma: float) -> object:
    def f(x: np.ndarray) -> np.ndarray:
        u, v = x
        r2 = u * u + v * v
        return np.array([sigma * u - 2.3 * v - u * r2, 2.3 * u + sigma * v - v * r2])
    return f


def test_residual_bound_on_both_sides() -> None:
    omega = 2.3
    ok = first_lyapunov(_rotation(3e-7 * omega), np.zeros(2))
    assert ok.residual == pytest.approx(3e-7, rel=1e-6)
    # z = w/sqrt(2) for w = u + i v (x = 2 Re(z q), |q| = 1): Re c1 = -2, l1 = -2/omega
    assert ok.l1 == pytest.approx(-2.0 / omega, rel=1e-6)
    with pytest.raises(ValueError, match="exceeds residual_max = 1e-06"):
        first_lyapunov(_rotation(3e-6 * omega), np.zeros(2))
