"""classify (dryfriction.analysis.bifurcation) at generic curves and on both sides of each
threshold: the exponent against a log-log least-squares fit written here over the smallest
distances of a curve whose local exponent drifts (so which points are taken matters), the
floor factor, n_fit, the decaying trend and d = 0 (K = K_c) itself, with their defaults."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.analysis.bifurcation import classify

FLOOR = 2.3e-3


def _scan(up: list[tuple[float, float]], trend: dict[float, float] | None = None) -> dict:
    rows = [{"d": d, "amplitude": a} for d, a in up]
    for r in rows:
        if trend and r["d"] in trend:
            r["trend"] = trend[r["d"]]
    return {"floor": FLOOR, "down": [{"d": -0.07, "amplitude": FLOOR}], "up": rows}


def _ls_slope(pts: list[tuple[float, float]]) -> float:
    """Slope of ln a against ln d by the normal equations (written here, not polyfit)."""
    x = np.log([p[0] for p in pts])
    y = np.log([p[1] for p in pts])
    xm, ym = x.mean(), y.mean()
    return float(np.sum((x - xm) * (y - ym)) / np.sum((x - xm) ** 2))


def _curve(d: float) -> float:  # local exponent 0.5 at d -> 0, drifting up with d
    return 0.37 * math.sqrt(d) * math.exp(2.1 * d)


DS = [0.4, 0.013, 0.21, 0.027, 0.11, 0.055, 0.7]  # unsorted on purpose


def test_exponent_is_fitted_over_the_smallest_distances_with_the_defaults() -> None:
    up = [(-0.07, FLOOR)] + [(d, _curve(d)) for d in DS]
    r = classify(_scan(up))
    smallest = sorted((d, _curve(d)) for d in DS)[:4]  # default n_fit = 4
    assert r["type"] == "supercritical" and r["hysteresis_d"] == []
    assert r["exponent"] == pytest.approx(_ls_slope(smallest), rel=1e-10)
    assert abs(r["exponent"] - _ls_slope(sorted((d, _curve(d)) for d in DS)[-4:])) > 0.1
    r3 = classify(_scan(up), n_fit=3)
    assert r3["exponent"] == pytest.approx(_ls_slope(smallest[:3]), rel=1e-10)


def test_floor_factor_excludes_at_and_below_its_threshold() -> None:
    """Points at or below factor x floor (default 5) are not fitted; just above are."""
    thr = 5.0 * FLOOR
    up = [(0.011, thr), (0.019, 0.999 * thr), (0.03, 1.2 * thr), (0.09, 2.9 * thr),
          (0.2, 4.4 * thr)]
    r = classify(_scan(up))
    assert r["exponent"] == pytest.approx(_ls_slope(up[2:]), rel=1e-10)
    r2 = classify(_scan(up), factor=4.0)  # now the first two count too
    assert r2["exponent"] == pytest.approx(_ls_slope(up[:4]), rel=1e-10)
    # one point above the threshold: no exponent, undetermined
    one = classify(_scan([(0.03, 1.2 * thr), (0.09, 0.5 * thr)]))
    assert one["type"] == "undetermined" and math.isnan(one["exponent"])


def test_hysteresis_counts_d_zero_and_respects_the_decaying_trend() -> None:
    thr = 5.0 * FLOOR
    base = [(0.05, 3 * thr), (0.1, 4 * thr)]
    # K = K_c itself (d = 0) with a cycle above the floor factor: hysteresis, not fitted
    at_kc = classify(_scan([(0.0, 2 * thr)] + base))
    assert at_kc["type"] == "subcritical" and at_kc["hysteresis_d"] == [0.0]
    assert at_kc["exponent"] == pytest.approx(_ls_slope(base), rel=1e-10)
    # just above K_c: the default trend (no key) counts as not decaying
    assert classify(_scan([(-0.02, 1.01 * thr)] + base))["hysteresis_d"] == [-0.02]
    assert classify(_scan([(-0.02, thr)] + base))["type"] == "supercritical"
    # decaying (default 0.9): trend at the threshold is decaying, just above is not
    assert classify(_scan([(-0.02, 2 * thr)] + base, {-0.02: 0.9}))["hysteresis_d"] == []
    assert classify(_scan([(-0.02, 2 * thr)] + base, {-0.02: 0.91}))["hysteresis_d"] == [-0.02]
    assert classify(_scan([(-0.02, 2 * thr)] + base, {-0.02: 0.91}),
                    decaying=0.95)["type"] == "supercritical"
