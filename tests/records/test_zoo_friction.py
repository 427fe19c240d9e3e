"""The zoo's friction feels the load point's actual motion (``records_zoo.friction_felt``).

Mistakes these are for: the spring driven by the commanded program, not the load point (a
friction channel with none of the servo's fluctuations); the spring's sign or an RK4 weight
wrong; the load point's speed taken at the wrong end of an interval. Checked against an
independent route (``records_zoo.friction``, LSODA on the commanded program) and against the
two limits of a small sinusoidal wobble of the load point, both closed forms of the model in
``records_zoo``'s docstring: far above the slider's relaxation rate ``k V / a`` the slider
cannot follow and the friction oscillates as the spring's stretch, ``k eps V / omega``; far
below every relaxation rate it stays at steady state, ``(a - b) ln(1 + eps sin)``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import records_zoo as zoo  # noqa: E402

A, B, DC = 0.0093, 0.0067, 13e-6  # 1, 1, m (generic, a > b)
K = 20.0 * B / DC  # 1/m, the zoo's machine
V = 2.7e-6  # m/s


def _wobbled(period: float, eps: float, per_period: int, periods: int) -> tuple:
    """Times (s) and the load point's displacement (m) under ``V (1 + eps sin(2 pi t / P))``."""
    w = 2.0 * np.pi / period
    t = np.linspace(0.0, periods * period, periods * per_period + 1)
    x = V * t + eps * V / w * (1.0 - np.cos(w * t))
    return t, x


def test_commanded_program_two_routes() -> None:
    """A 2.7 -> 8.1 -> 1.35 um/s program whose changes fall on samples: the load point's
    displacement is then exactly piecewise linear, and the RK4 kernel must agree with LSODA."""
    t = np.arange(0.0, 90.0, 0.05)
    prog = [(0.0, V), (30.0, 3.0 * V), (55.0, 0.5 * V)]
    x = np.zeros_like(t)
    for (s, v), (e, _) in zip(prog, prog[1:] + [(1e9, 0.0)], strict=True):
        x += v * np.clip(np.minimum(t, e) - s, 0.0, None)
    felt = zoo.friction_felt(t, x, a=A, b=B, dc=DC, k=K, v0=V)
    ref = zoo.friction(t, prog, a=A, b=B, dc=DC, k=K)
    assert np.ptp(ref) > 2 * A  # the program moves the friction (direct effect, evolution)
    np.testing.assert_allclose(felt, ref, rtol=0, atol=2e-7)


@pytest.mark.parametrize("eps", [0.02, -0.03])
def test_fast_wobble_is_the_springs_stretch(eps: float) -> None:
    """Period 0.02 s against a relaxation time ``a / (k V)`` = 0.33 s: the friction's
    oscillation is ``k eps V / omega`` (1 % correction at this ratio)."""
    period = 0.02
    t, x = _wobbled(period, eps, 40, 400)
    mu = zoo.friction_felt(t, x, a=A, b=B, dc=DC, k=K, v0=V)
    late = t > 0.5 * t[-1]
    w = 2.0 * np.pi / period
    # the oscillating part: least squares on sin, cos and a line (the slow drift beneath)
    cols = np.column_stack([np.sin(w * t[late]), np.cos(w * t[late]), np.ones(late.sum()),
                            t[late]])
    c = np.linalg.lstsq(cols, mu[late], rcond=None)[0]
    amp = float(np.hypot(c[0], c[1]))
    assert amp == pytest.approx(K * abs(eps) * V / w, rel=0.03)


@pytest.mark.parametrize("eps", [0.05, -0.04])
def test_slow_wobble_is_steady_state(eps: float) -> None:
    """Period 3000 s against ``dc / V`` = 4.8 s and ``a / (k V)`` = 0.33 s: the friction
    follows the steady state ``mu0 + (a - b) ln(V (1 + eps sin) / v0)``."""
    period = 3000.0
    t, x = _wobbled(period, eps, 3000, 2)
    mu = zoo.friction_felt(t, x, a=A, b=B, dc=DC, k=K, v0=V)
    w = 2.0 * np.pi / period
    steady = 0.6 + (A - B) * np.log(1.0 + eps * np.sin(w * t))
    late = t > 0.5 * period
    # lag corrections of order omega dc / V ~ 1 % of the (a - b) eps swing
    np.testing.assert_allclose(mu[late], steady[late], rtol=0,
                               atol=0.03 * (A - B) * abs(eps))


def _commanded(index: int) -> tuple[np.ndarray, np.ndarray]:
    """Zoo record ``index``'s friction and the friction its commanded program alone would
    give, with the record's own a, b, Dc and k (the first draws of ``make_record``)."""
    rec = zoo.record_at(index)
    rng = np.random.default_rng(index)
    dc = float(10 ** rng.uniform(-5.3, -4.7))
    a = float(rng.uniform(0.005, 0.012))
    b = a + float(rng.uniform(-0.004, 0.003))
    prog = list(zip([0.0, *rec.changes], rec.velocities, strict=True))
    return rec.mu, zoo.friction(rec.t - rec.t[0], prog, a=a, b=b, dc=dc, k=20.0 * b / dc)


def test_a_records_friction_feels_its_wobble() -> None:
    """Zoo 12 (0.30 -> 0.91 um/s, the machine oscillation alone): the friction scatters about
    the commanded program's by more than its white noise (1.9 times, measured); zoo 0 (no
    artifact) by the noise alone (1.00)."""
    mu, ref = _commanded(12)
    assert np.std(mu - ref) > 1.5 * zoo.MU_NOISE
    mu, ref = _commanded(0)
    assert np.std(mu - ref) == pytest.approx(zoo.MU_NOISE, rel=0.1)
