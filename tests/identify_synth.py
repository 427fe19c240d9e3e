"""Seeded synthetic one-step records, identifiable or built not to be (issue 30's acceptance
test), from the independent forward solver of ``tests/lab_synth.py`` (SciPy Radau on
``(tau, theta)``, not the project's RODAS4 in log variables).

Each record is one velocity step ``V1 -> V2`` (ratio 3 or 10, up or down) on an elastic
machine with a linear trend and white noise, ~600 samples after the change and as many
before it. Four kinds (the truth drawn from ``numpy.random.default_rng(seed)``):

* ``"identified"``: ``Dc`` at most 0.15 of the slip after the change and a transient
  ``b ln(V2/V1)`` at least 10 times the noise: ``a``, ``b``, ``Dc``, ``k`` all fixed by the data;
* ``"short"``: ``Dc`` 1.5 to 5 times the window's slip after the change (the window is
  shorter than ``Dc``);
* ``"huge"``: ``Dc`` 30 to 1000 times that slip (``Dc`` far beyond the window);
* ``"flat"``: ``a = b`` (``a - b = 0``) and a transient ``b ln(V2/V1)`` of 0.1 to 0.4 times
  the noise (lost in it).
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from lab_synth import Truth, synth_program  # noqa: E402

KINDS = ("identified", "short", "huge", "flat")
SLIP_AFTER = 300e-6  # m of load-point slip after the change
SAMPLES = 600  # samples after the change (and before it)


@dataclass(frozen=True)
class Case:
    seed: int
    kind: str
    truth: Truth
    v1: float
    v2: float
    t: np.ndarray
    v_load: np.ndarray
    mu: np.ndarray

    @property
    def identifiable(self) -> bool:
        return self.kind == "identified"


def make_case(seed: int, kind: str | None = None) -> Case:
    """The record of ``seed`` (its kind from the seed unless given)."""
    rng = np.random.default_rng(seed)
    kind = KINDS[seed % len(KINDS)] if kind is None else kind
    v1 = 1e-6
    ratio = float(rng.choice([3.0, 10.0])) ** float(rng.choice([1.0, -1.0]))
    v2 = v1 * ratio
    lr = abs(math.log(ratio))
    a = float(rng.uniform(0.004, 0.012))
    noise = float(math.exp(rng.uniform(math.log(1e-4), math.log(4e-4))))
    k = float(math.exp(rng.uniform(math.log(2e3), math.log(2e4))))
    trend = float(rng.uniform(-20.0, 20.0))
    if kind == "identified":
        dc = float(math.exp(rng.uniform(math.log(4e-6), math.log(0.15 * SLIP_AFTER))))
        b = float(max(a + rng.uniform(-0.004, 0.006), 10.0 * noise / lr))
    elif kind == "short":
        dc = float(rng.uniform(1.5, 5.0)) * SLIP_AFTER
        b = a + float(rng.uniform(-0.004, 0.006))
        b = max(b, 10.0 * noise / lr)
    elif kind == "huge":
        dc = float(math.exp(rng.uniform(math.log(30.0), math.log(1000.0)))) * SLIP_AFTER
        b = max(a + float(rng.uniform(-0.004, 0.006)), 10.0 * noise / lr)
    elif kind == "flat":
        dc = float(math.exp(rng.uniform(math.log(4e-6), math.log(0.15 * SLIP_AFTER))))
        b = a = float(rng.uniform(0.1, 0.4)) * noise / lr
    else:
        raise ValueError(f"kind {kind!r}: one of {', '.join(KINDS)}")
    tr = Truth(a=a, b=b, dc=dc, mu0=0.6, stiffness=k, trend=trend, noise=noise)
    dt = SLIP_AFTER / v2 / SAMPLES
    s1 = v1 * SAMPLES * dt * 2  # the window takes the second half of the first stretch
    t, v, mu, _ = synth_program(tr, [(v1, s1 / v1), (v2, SLIP_AFTER / v2)], dt, seed=seed)
    return Case(seed, kind, tr, v1, v2, t, v, mu)
