"""``estimate_change`` (fit/loadpoint.py) at generic points: a down-step's corner between two
samples on a clock far from 0 found exactly from an exact broken line (level, velocities,
corner), and its standard error against the scatter of the corner over seeded draws of white
noise (the Wald error with the AR(1) widening near 1 on white noise)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.fit.loadpoint import estimate_change

T = 5000.0 + np.arange(0.0, 3.0, 0.1)  # 30 samples, 0.1 s apart, the clock at 5000 s
TAU = 5001.537  # between samples 15 and 16


def _line(t):
    # 20 um/s down to 4 um/s at TAU, from 1 mm
    return np.where(t < TAU, 2e-5 * (t - t[0]), 2e-5 * (TAU - t[0]) + 4e-6 * (t - TAU)) + 1e-3


def test_exact_broken_line_gives_its_corner_between_samples() -> None:
    # mistakes: the corner kept at the best sample (not refined between samples: 37 ms off),
    # the corner returned on the shifted clock (t - t[0]), the velocities swapped
    est = estimate_change(T, _line(T), 5001.5)
    assert est.t == pytest.approx(TAU, abs=1e-6)
    assert (est.v_before, est.v_after) == pytest.approx((2e-5, 4e-6), rel=1e-6)
    assert est.given == 5001.5 and est.sigma < 1e-6
    with pytest.raises(ValueError, match="fewer than 8 samples"):
        estimate_change(T[:7], _line(T[:7]), 5000.3)


def test_standard_error_is_the_scatter_of_the_corner_on_white_noise() -> None:
    # 120 draws of 0.05 um white noise: the mean reported sigma against the corner's standard
    # deviation over the draws (measured 0.97; mistakes: the residual variance left out, no
    # square root. The corner column with the two velocities swapped is no mistake: it is
    # minus the right one plus a constant, and the constant column absorbs it)
    rng = np.random.default_rng(5)
    x = _line(T)
    draws = [estimate_change(T, x + rng.normal(0.0, 5e-8, T.size), 5001.5) for _ in range(120)]
    scatter = float(np.std([d.t for d in draws]))
    mean_sigma = float(np.mean([d.sigma for d in draws]))
    assert 0.8 < mean_sigma / scatter < 1.25
    assert abs(float(np.mean([d.t for d in draws])) - TAU) < 3 * scatter / np.sqrt(120)
