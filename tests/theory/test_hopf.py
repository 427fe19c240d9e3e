"""The first Lyapunov coefficient (dryfriction.theory.hopf) against closed forms and an
independent route: Guckenheimer & Holmes's formula (1983, *Nonlinear Oscillations*, eq. (3.4.11))
for a planar system in its canonical form, with derivatives from mpmath; the coordinate law
``l1 -> l1 / |T q|^2``; the sign under time reversal; the cycle amplitude against a simulation."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from dryfriction.theory.hopf import cycle_amplitude, first_lyapunov

OMEGA = 1.7
# generic quadratic and cubic coefficients f_ij, g_ij of x^i y^j (no symmetry, no unit values)
F = {(2, 0): 0.31, (1, 1): -0.57, (0, 2): 0.23, (3, 0): -0.41, (2, 1): 0.17, (1, 2): 0.29,
     (0, 3): -0.13}
G = {(2, 0): -0.19, (1, 1): 0.44, (0, 2): 0.37, (3, 0): 0.21, (2, 1): -0.35, (1, 2): 0.11,
     (0, 3): 0.27}


def poly(c: dict[tuple[int, int], float], x, y):  # type: ignore[no-untyped-def]
    return sum(v * x**i * y**j for (i, j), v in c.items())


def canonical(x, beta: float = 0.0):  # type: ignore[no-untyped-def]
    """``x' = beta x - omega y + f``, ``y' = omega x + beta y + g``."""
    return np.array([beta * x[0] - OMEGA * x[1] + poly(F, x[0], x[1]),
                     OMEGA * x[0] + beta * x[1] + poly(G, x[0], x[1])])


def gh_a(fd, gd, omega: float) -> float:  # type: ignore[no-untyped-def]
    """Guckenheimer & Holmes (3.4.11): the cubic coefficient ``a`` of ``r' = beta r + a r^3``
    from the partial derivatives ``fd[(i, j)] = d^(i+j) f / dx^i dy^j`` at 0."""
    return ((fd[3, 0] + fd[1, 2] + gd[2, 1] + gd[0, 3]) / 16
            + (fd[1, 1] * (fd[2, 0] + fd[0, 2]) - gd[1, 1] * (gd[2, 0] + gd[0, 2])
               - fd[2, 0] * gd[2, 0] + fd[0, 2] * gd[0, 2]) / (16 * omega))


def poly_derivs(c: dict[tuple[int, int], float]) -> dict[tuple[int, int], float]:
    return {k: v * math.factorial(k[0]) * math.factorial(k[1]) for k, v in c.items()}


def test_canonical_form_matches_guckenheimer_holmes_both_methods() -> None:
    # with |q| = 1, q = (1, -i)/sqrt 2 and z = w/sqrt 2 (w = x + i y): l1 = 2 a / omega
    expected = 2 * gh_a(poly_derivs(F), poly_derivs(G), OMEGA) / OMEGA
    for method, tol in (("complex", 1e-12), ("fd", 1e-7)):
        hp = first_lyapunov(canonical, np.zeros(2), method=method)
        assert hp.omega == pytest.approx(OMEGA, rel=1e-12)
        assert hp.l1 == pytest.approx(expected, rel=tol, abs=tol)


def test_pure_normal_form_gives_its_coefficient_and_sign_flips() -> None:
    for s in (-0.73, 0.73):
        def f(x, s=s):  # type: ignore[no-untyped-def]
            r2 = x[0] ** 2 + x[1] ** 2
            return np.array([-OMEGA * x[1] + s * x[0] * r2, OMEGA * x[0] + s * x[1] * r2])

        assert first_lyapunov(f, np.zeros(2)).l1 == pytest.approx(2 * s / OMEGA, rel=1e-12)


def test_time_reversal_flips_the_sign() -> None:
    l1 = first_lyapunov(canonical, np.zeros(2)).l1
    back = first_lyapunov(lambda x: -canonical(x), np.zeros(2)).l1
    assert back == pytest.approx(-l1, rel=1e-12)


def test_linear_change_of_coordinates() -> None:
    """``y = T x``: ``l1_y = l1_x / |T q_x|^2`` (a 3-D system: the canonical pair plus a
    decaying coordinate coupled nonlinearly, so the centre-manifold terms matter)."""
    def f3(x):  # type: ignore[no-untyped-def]
        base = canonical(x[:2])
        return np.array([base[0] + 0.4 * x[0] * x[2], base[1] - 0.3 * x[1] * x[2],
                         -0.9 * x[2] + 0.8 * x[0] ** 2 - 0.5 * x[0] * x[1]])

    T = np.array([[1.3, -0.4, 0.7], [0.2, 0.9, -0.6], [0.5, 0.3, 1.1]])
    Ti = np.linalg.inv(T)
    hx = first_lyapunov(f3, np.zeros(3))
    hy = first_lyapunov(lambda y: T @ f3(Ti @ y), np.zeros(3))
    assert hy.l1 == pytest.approx(hx.l1 / np.linalg.norm(T @ hx.q) ** 2, rel=1e-10)
    assert abs(hx.l1 - first_lyapunov(canonical, np.zeros(2)).l1) > 0.05 * abs(hx.l1)
    assert hy.l1 == pytest.approx(first_lyapunov(lambda y: T @ f3(Ti @ y), np.zeros(3),
                                                 method="fd").l1, rel=1e-6)


def brusselator(x, A: float):  # type: ignore[no-untyped-def]
    B = 1 + A * A
    return np.array([A - (B + 1) * x[0] + x[0] ** 2 * x[1], B * x[0] - x[0] ** 2 * x[1]])


def test_brusselator_against_an_independent_route() -> None:
    """Brusselator at ``B = 1 + A^2`` (``omega = A``): moved to its canonical coordinates
    ``x = x* + T u`` by hand (``T = [v_i, v_r]``, ``v = (A^2, i A - A^2)`` the eigenvector of
    ``i A``), G&H's formula with mpmath's derivatives, then back by the coordinate law."""
    A = 1.37
    xs = np.array([A, (1 + A * A) / A])
    vr, vi = np.array([A * A, -A * A]), np.array([0.0, A])
    T = np.column_stack([vi, vr])
    Ti = mpmath.matrix(np.linalg.inv(T).tolist())

    def nonlinear(k: int):  # type: ignore[no-untyped-def]
        def h(u1, u2):  # type: ignore[no-untyped-def]
            x1 = xs[0] + T[0, 0] * u1 + T[0, 1] * u2
            x2 = xs[1] + T[1, 0] * u1 + T[1, 1] * u2
            w = x1 ** 2 * x2  # the only nonlinear term, +w in x', -w in y'
            return Ti[k, 0] * w - Ti[k, 1] * w
        return h

    d = [{(i, j): float(mpmath.diff(nonlinear(k), (0, 0), (i, j)))
          for i, j in ((2, 0), (1, 1), (0, 2), (3, 0), (2, 1), (1, 2), (0, 3))} for k in (0, 1)]
    l1_u = 2 * gh_a(d[0], d[1], A) / A
    q_u = np.array([1, -1j]) / math.sqrt(2)
    expected = l1_u / np.linalg.norm(T @ q_u) ** 2
    hp = first_lyapunov(lambda x: brusselator(x, A), xs)
    assert hp.omega == pytest.approx(A, rel=1e-10)
    assert hp.l1 == pytest.approx(expected, rel=1e-9)
    assert hp.l1 < 0  # the Brusselator's Hopf is supercritical


@pytest.mark.slow
def test_cycle_amplitude_against_simulation() -> None:
    """The canonical system at ``beta`` on the unstable side of a supercritical point: the
    settled cycle's amplitude over the prediction tends to 1 as ``beta -> 0`` (error O(beta))."""
    hp = first_lyapunov(canonical, np.zeros(2))
    assert hp.l1 < 0
    errs = []
    for beta in (1e-2, 2.5e-3):
        pred = cycle_amplitude(hp, beta)[0]
        # starting on the predicted circle, off the cycle by O(beta), which decays as
        # exp(-2 beta t): 3/beta leaves e^-6 of it
        sol = solve_ivp(lambda t, x, beta=beta: canonical(x, beta), (0, 3 / beta), [pred, 0.0],
                        method="DOP853", rtol=1e-9, atol=1e-12, dense_output=True)
        tt = np.linspace(sol.t[-1] - 4 * math.pi / OMEGA, sol.t[-1], 2000)
        amp = np.ptp(sol.sol(tt)[0]) / 2
        errs.append(abs(amp / pred - 1))
    assert errs[1] < 0.02
    assert errs[1] < 0.5 * errs[0]  # converging as beta -> 0


def test_not_a_hopf_point() -> None:
    with pytest.raises(ValueError, match="residual_max"):
        first_lyapunov(lambda x: canonical(x, 0.1), np.zeros(2))
    with pytest.raises(ValueError, match="no complex pair"):
        first_lyapunov(lambda x: np.array([-x[0], -2 * x[1] + x[0] ** 2]), np.zeros(2))


def test_fd_step_is_in_its_plateau() -> None:
    """The difference step (0.01 scale) sits where truncation and rounding balance: halving
    or doubling it changes l1 by < 1e-6 relative on a non-polynomial field."""
    def f(x, s=1.0):  # type: ignore[no-untyped-def]
        return np.array([-OMEGA * np.sin(x[1]) + 0.3 * np.expm1(x[0]) * x[0] - 0.5 * x[0] ** 3,
                         OMEGA * np.tanh(x[0]) + 0.2 * np.exp(x[1]) * x[0] * x[1]])

    ref = first_lyapunov(f, np.zeros(2)).l1
    for scale in (0.5, 1.0, 2.0):
        assert first_lyapunov(f, np.zeros(2), method="fd", scale=scale).l1 == pytest.approx(
            ref, rel=1e-6)
