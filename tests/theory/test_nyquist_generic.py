"""``theory.stability.nyquist_crossings`` against a closed form (issue 25, strengthen6B).

For ``Z(lambda) = c / (1 + lambda tau)`` (ours: a Debye relaxation) the imaginary-axis root of
``M lambda^2 + eta lambda + K + Z`` needs ``eta omega + Im Z(i omega) = 0``, i.e.
``1 + omega^2 tau^2 = c tau / eta``, and then ``K = M omega^2 - Re Z(i omega)
= M omega^2 - eta / tau``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.theory.stability import nyquist_crossings

C, TAU, ETA, MASS = 3.7, 0.42, 0.55, 0.23


def _z(lam: np.ndarray) -> np.ndarray:
    return C / (1.0 + np.asarray(lam, complex) * TAU)


OMEGA = math.sqrt(C * TAU / ETA - 1.0) / TAU
K_C = MASS * OMEGA**2 - ETA / TAU


def test_crossing_is_the_closed_form() -> None:
    K, om = nyquist_crossings(_z, MASS, ETA, omega_max=50.0 * OMEGA)
    assert om == pytest.approx(OMEGA, rel=1e-9)
    assert K == pytest.approx(K_C, rel=1e-9)
    # the default grid (4000 points) and a coarse one agree: the root is refined
    K2, om2 = nyquist_crossings(_z, MASS, ETA, omega_max=50.0 * OMEGA, n_omega=50)
    assert (K2, om2) == pytest.approx((K_C, OMEGA), rel=1e-9)


def test_scan_window_edges() -> None:
    """The grid spans ``[1e-7, 1] * omega_max``: a crossing just below omega_max is found,
    one just above it, or below its bottom edge, is not."""
    K, om = nyquist_crossings(_z, MASS, ETA, omega_max=1.02 * OMEGA)
    assert om == pytest.approx(OMEGA, rel=1e-9)
    assert nyquist_crossings(_z, MASS, ETA, omega_max=0.98 * OMEGA)[0] == -np.inf
    K, om = nyquist_crossings(_z, MASS, ETA, omega_max=0.98 * OMEGA / 1e-7)
    assert om == pytest.approx(OMEGA, rel=1e-9)
    K, om = nyquist_crossings(_z, MASS, ETA, omega_max=1.02 * OMEGA / 1e-7)
    assert K == -np.inf and math.isnan(om)


def test_largest_of_several_crossings_is_returned() -> None:
    """A delay ``Z = c e^{-lambda tau}`` crosses many times; with ``M = 0.01`` the largest
    ``K = M omega^2 - c cos(omega tau)`` is neither the first nor the last crossing (brute
    force here)."""
    c, tau, eta, m = 5.0, 1.3, 0.3, 0.01

    def z2(lam: np.ndarray) -> np.ndarray:
        return c * np.exp(-np.asarray(lam, complex) * tau)

    om = np.linspace(1e-3, 30.0, 600_001)
    g = eta * om - c * np.sin(om * tau)
    i = np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:]))
    ks = m * om[i] ** 2 - c * np.cos(om[i] * tau)
    best = int(np.argmax(ks))
    assert i.size >= 4 and 0 < best < i.size - 1
    K, o = nyquist_crossings(z2, m, eta, omega_max=30.0)
    assert K == pytest.approx(ks[best], rel=1e-4)  # grid error; neighbours differ by 4e-3
    assert o == pytest.approx(om[i[best]], rel=1e-4)
    # no crossing beyond c/eta: a scan reaching 1e5 on its log grid finds the same one
    K5, o5 = nyquist_crossings(z2, m, eta, omega_max=1e5)
    assert (K5, o5) == pytest.approx((K, o), rel=1e-9)


def test_omega_max_refusal_edges() -> None:
    for bad in (0.0, -1.0):
        with pytest.raises(ValueError, match="omega_max"):
            nyquist_crossings(_z, MASS, ETA, omega_max=bad)
    K, _ = nyquist_crossings(_z, MASS, ETA, omega_max=1e-300)
    assert K == -np.inf
