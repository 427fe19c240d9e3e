"""Synthetic velocity steps made by the trap model itself (the CV time-series tests share them):
u = 1 -> 10 -> 0.1 at ``V* = a0/t0``, 0.3, 3 and 3 ``a0`` of slip, a sample every 0.1 ``a0``,
Gaussian noise of a known level."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from dryfriction.records.data import SeriesData


def synthetic_steps(true: Mapping[str, float], model: Any, seed: int,
                    sigma: float = 2e-3) -> SeriesData:
    """``model.predict(true, ...)`` along the step program, plus noise ``sigma`` (seeded)."""
    vs = true["a0"] / true["t0"]
    t: list[float] = []
    v: list[float] = []
    now = 0.0
    for u, slip in ((1.0, 0.3), (10.0, 3.0), (0.1, 3.0)):
        dur = slip / u * true["t0"]
        n = max(3, round(slip / 0.1))
        t.extend(now + np.linspace(0.0, dur, n + 1)[:-1])
        v.extend([u * vs] * n)
        now += dur
    t.append(now)
    v.append(0.1 * vs)
    ta, va = np.array(t), np.array(v)
    clean = model.predict(true, SeriesData(ta, va, np.ones_like(ta)))
    rng = np.random.default_rng(seed)
    return SeriesData(ta, va, clean + rng.normal(0.0, sigma, ta.size), np.full(ta.size, sigma))
