"""Static friction from an explicit simulated pull, written from docs/model.md alone.

The reference below imports nothing from :mod:`dryfriction`; only the comparison does. It
builds a population of traps on a grid of spacing ``h`` (in ``a0``), ages it at rest, pulls it
rigidly in steps of ``h`` and takes the largest total force over the pull (docs/model.md §3:
"Sliding starts when ..."; the maximum of the force is what a force-controlled pull overcomes).

Re-derived independently here (not the package's readings or closed forms):

* each trap's state from the force balance ``psi'(z) + 6 alpha (z - y) = 0`` with ``psi`` of §1,
  tracked by Newton's method from the previous step (a quasi-static pull), and the branch's
  existence from its own stability condition ``psi''(z) + 6 alpha > 0`` -- no ``z+(y)`` formula,
  no spinodal ``y_c`` formula, no regime switch: a trap that loses its (+) state goes to the far
  (-) state if one exists at its ``y`` (strong pinning) and out of contact otherwise (very strong
  pinning), which is the regime distinction of §1 falling out of the mechanics;
* which traps are in contact, on which branch and with which radius at every step of the pull
  (the package instead evaluates the eq. 27 reading and candidate maxima in closed form);
* the maximum over the pull, by scanning (no candidate list);
* ``H0`` by quadrature of the same numerically solved (+) branch.

Readings it cannot avoid sharing, because they are the model's definition in the spec: the
potential ``psi``; the initial state of eq. 25 (``-a0 < p < 0`` on (+), ``0 < p < a0`` on (-),
all born at ``t = 0``); ageing by eq. 17/19 with ``a_r = sqrt(1 + eps ln(1 + T))``; the scaling
of eqs. 20-21 (``Phi0 ~ a_r^3``, ``a ~ a_r``, so a trap's force is ``a_r^2 psi'(z)`` with
``y = p / a_r``); traps out of contact do not age, and a pair that comes into contact during the
(fast) pull is fresh (radius ``a0``); forces in units of ``F_el`` of eq. 12.

Accuracy: the sum over traps and the scan over the pull are both first order in ``h`` (the
force has jumps where traps die), so the error is ``C h``; the convergence test shows that
halving ``h`` halves the error (or better), and the comparison tolerance is that bound at the
finest ``h``.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from dryfriction.theory.model import TrapModel


def _dpsi(z: np.ndarray) -> np.ndarray:
    """psi'(z) for psi = 1 - 3 z^2 + 2 |z|^3 inside |z| <= 1, 0 outside."""
    return np.where(np.abs(z) <= 1.0, -6.0 * z + 6.0 * z * np.abs(z), 0.0)


def _ddpsi(z: np.ndarray) -> np.ndarray:
    return np.where(np.abs(z) <= 1.0, -6.0 + 12.0 * np.abs(z), 0.0)


def _balance(z: np.ndarray, y: np.ndarray, alpha: float) -> np.ndarray:
    return _dpsi(z) + 6.0 * alpha * (z - y)


def _newton(z: np.ndarray, y: np.ndarray, alpha: float, lo: float, hi: float,
            steps: int = 6) -> np.ndarray:
    """Root of the force balance on one stable interval ``[lo, hi]`` (where the balance is
    monotone increasing), from a nearby start."""
    for _ in range(steps):
        z = np.clip(z - _balance(z, y, alpha) / (_ddpsi(z) + 6.0 * alpha), lo, hi)
    return z


def _bisect(y: np.ndarray, alpha: float, lo: float, hi: float) -> np.ndarray:
    a, b = np.full_like(y, lo), np.full_like(y, hi)
    for _ in range(80):
        m = 0.5 * (a + b)
        neg = _balance(m, y, alpha) < 0
        a, b = np.where(neg, m, a), np.where(neg, b, m)
    return 0.5 * (a + b)


def _intervals(alpha: float) -> tuple[float, float]:
    """Edges of the stable intervals: psi'' + 6 alpha > 0 means z < -zs (near) or z > zs (far)."""
    zs = (1.0 - alpha) / 2.0
    return -zs, zs


@functools.cache
def _forward_path(alpha: float, n: int = 20_001) -> tuple[np.ndarray, np.ndarray]:
    """A trap's force along its whole forward path: (+) from contact to where (+) ceases, then
    the far (-) state while one exists (strong pinning), found by the same mechanics as the
    pull. Two grids that meet at the end of (+), where the force jumps."""
    zp, zm = _intervals(alpha)
    y_end = _plus_end(alpha)
    y1 = np.linspace(-1.0, y_end, n)
    f1 = _dpsi(_bisect(y1, alpha, -1.0, zp))
    y2 = np.linspace(y_end, max(y_end, 1.0), n)[1:]
    far = (y2 < 1.0) & (_balance(np.full_like(y2, zm), y2, alpha) <= 0)
    f2 = np.where(far, _dpsi(_bisect(y2, alpha, zm, 1.0)), 0.0)
    return np.concatenate([y1, y2]), np.concatenate([f1, f2])


def reference_h0(alpha: float) -> float:
    """Work per trap swept through (eq. 12's ``H0``): the force integrated along the forward
    path. In strong pinning the far (-) part is negative (it returns energy); the spec's closed
    form of ``H0`` is the (+) part alone, which is the very strong case."""
    y, f = _forward_path(alpha)
    y_end = _plus_end(alpha)
    n1 = int(np.searchsorted(y, y_end, side="right"))
    plus = np.sum(0.5 * (f[1:n1] + f[:n1 - 1]) * np.diff(y[:n1]))
    rest_y = np.concatenate([[y_end], y[n1:]])
    rest_f = np.concatenate([[f[n1] if n1 < len(f) else 0.0], f[n1:]])
    return float(plus + np.sum(0.5 * (rest_f[1:] + rest_f[:-1]) * np.diff(rest_y)))


def error_constant(T: float, eps: float, alpha: float) -> float:
    """``K`` in the error bound ``|mu_s(h) - mu_s| <= K h`` of the pull (units F_el).

    The sum over traps and the scan of the pull are first order in ``h``: each force jump that
    moves with the pull (the aged edge at its end of (+), the fresh edge, the far edge) is
    misplaced by at most half a trap spacing, and the scan lands within one step of the
    maximum; each costs at most ``h/2`` times the largest force of one trap, ``r^2 f_max``.
    Four such half-steps give ``K = 2 r^2 f_max / H0``.
    """
    r2 = 1.0 + eps * np.log1p(T)
    _, f = _forward_path(alpha)
    return float(2.0 * r2 * np.max(np.abs(f)) / reference_h0(alpha))


def _plus_end(alpha: float) -> float:
    """Largest ``y`` with a (+) state: the balance at its stability edge is linear in ``y``."""
    zp, _ = _intervals(alpha)
    return float((_dpsi(np.array(zp)) + 6.0 * alpha * zp) / (6.0 * alpha))


def reference_mu_s(T: float, eps: float, alpha: float, h: float) -> float:
    """Largest force (units F_el) over a rigid pull of a population aged ``T = tw/t0`` at rest."""
    zp, zm = _intervals(alpha)
    r_aged = np.sqrt(1.0 + eps * np.log1p(T))
    y_plus_end = _plus_end(alpha)
    # every aged trap is gone once its y passes both the (+) end and the far edge y = 1
    d_max = r_aged * max(y_plus_end, 1.0) + 1.0 + 4 * h
    p0 = np.arange(-1.0 - d_max, 1.0, h) + 0.5 * h  # off the grid points p = -1, 0
    aged = np.abs(p0) < 1.0
    r = np.where(aged, r_aged, 1.0)
    FREE, PLUS, MINUS, GONE = 0, 1, 2, 3
    state = np.where(aged, np.where(p0 < 0, PLUS, MINUS), FREE)
    y = p0 / r
    z = np.zeros_like(p0)
    plus, minus = state == PLUS, state == MINUS
    z[plus] = _bisect(y[plus], alpha, -1.0, zp)
    z[minus] = _bisect(y[minus], alpha, zm, 1.0)
    h0 = reference_h0(alpha)
    best = -np.inf
    for d in np.arange(0.0, d_max + h, h):
        y = (p0 + d) / r
        enter = (state == FREE) & (y >= -1.0)
        state[enter], z[enter] = PLUS, -1.0
        plus = state == PLUS
        # (+) survives while the balance at its stability edge is still >= 0
        lost = plus & (_balance(np.full_like(y, zp), y, alpha) < 0)
        to_far = lost & (y < 1.0) & (_balance(np.full_like(y, zm), y, alpha) <= 0)
        state[lost], z[to_far] = GONE, 1.0
        state[to_far] = MINUS
        state[(state == MINUS) & (y >= 1.0)] = GONE
        plus, minus = state == PLUS, state == MINUS
        z[plus] = _newton(z[plus], y[plus], alpha, -1.0, zp)
        z[minus] = _newton(z[minus], y[minus], alpha, zm, 1.0)
        on = plus | minus
        assert np.max(np.abs(_balance(z[on], y[on], alpha)), initial=0.0) < 1e-9
        force = h * np.sum(r[on] ** 2 * _dpsi(z[on])) / h0
        best = max(best, force)
    return float(best)


# ------------------------------------------------------------------------------ comparison
def _package(T: float, eps: float, alpha: float) -> float:
    from dryfriction import static_friction

    return float(static_friction(TrapModel(alpha=alpha, eps=eps), T))


CASES = [  # (T, eps, alpha): very strong pinning at 0.13, strong pinning at 0.3
    (0.0, 0.04, 0.13), (1.0, 0.01, 0.13), (100.0, 0.04, 0.13), (1e4, 0.05, 0.13),
    (10.0, 0.04, 0.3), (1e3, 0.05, 0.3),
]


def test_the_reference_h0_is_the_papers_in_very_strong_pinning() -> None:
    # the spec's closed form (docs/model.md §1), valid where (+) ends out of contact
    a = 0.13
    yc = (1 - a) ** 2 / (4 * a)
    closed = 6 * a * ((yc**2 - 1) / 2 + (1 - a) * (yc + 1) / 2 + (1 + a) ** 3 / (12 * a))
    assert reference_h0(a) == pytest.approx(closed, rel=1e-6)


def test_aged_at_no_time_the_threshold_is_the_sliding_force() -> None:
    # T = 0: nothing aged, mu_s = 1 by the definition of F_el (eq. 12), in both regimes
    for alpha in (0.13, 0.3):
        h = 1.0 / 400
        assert reference_mu_s(0.0, 0.04, alpha, h) == pytest.approx(
            1.0, abs=error_constant(0.0, 0.04, alpha) * h)


@pytest.mark.slow
@pytest.mark.parametrize("T,eps,alpha", [(100.0, 0.04, 0.13), (10.0, 0.04, 0.3)])
def test_halving_the_step_halves_the_error(T: float, eps: float, alpha: float) -> None:
    # the error moves with where the edges fall between traps, so it is not monotone in h; it
    # stays within the first-order bound K h at every step, a bound that halves with h, and
    # eight times finer is at least four times better
    pkg = _package(T, eps, alpha)
    errors = []
    for n in (100, 200, 400, 800):
        err = abs(reference_mu_s(T, eps, alpha, 1.0 / n) - pkg)
        assert err <= error_constant(T, eps, alpha) / n, (n, err)
        errors.append(err)
    assert errors[-1] <= errors[0] / 4, errors


@pytest.mark.slow
@pytest.mark.parametrize("T,eps,alpha", CASES)
def test_package_static_friction_matches_the_explicit_pull(T: float, eps: float,
                                                          alpha: float) -> None:
    h = 1.0 / 400
    ref = reference_mu_s(T, eps, alpha, h)
    assert _package(T, eps, alpha) == pytest.approx(ref, abs=error_constant(T, eps, alpha) * h)
