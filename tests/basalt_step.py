"""A basalt-like velocity step (issue 30's held-out basalt step, rebuilt from its published
shape): 3 -> 10 um/s, sampled at 10 Hz before the change and 100 Hz after it, from the
independent rate-and-state forward model of :mod:`records_zoo` (ageing law, LSODA) with the
values the issue reports for that step (a = 0.0088, b = 0.0093, Dc = 6.8 um) on a spring of
7000 /m, a trend of -3 /m of load-point travel and white noise of 8e-4 (the record's rms
misfit, 8.3e-4). 200 s before the change, 100 s after: the step's window (50 um before the
change, :func:`dryfriction.records.lab.slice_steps`) holds 10166 samples, as the basalt step's
~1e4."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lab_synth import write_lab_file
from records_zoo import friction

TRUTH = {"a": 0.0088, "b": 0.0093, "dc": 6.8e-6, "k": 7000.0, "mu0": 0.6, "trend": -3.0,
         "noise": 8e-4}
CHANGE = 200.0  # s
V1, V2 = 3e-6, 10e-6  # m/s


def basalt_step(path: Path, seed: int = 1) -> Path:
    """Write the record (time s, displacement um, friction) to ``path``; ``seed`` seeds the
    noise."""
    t = np.concatenate([np.arange(0, 2000) * 0.1, CHANGE + np.arange(0, 10000) * 0.01])
    mu = friction(t, [(0.0, V1), (CHANGE, V2)], a=TRUTH["a"], b=TRUTH["b"], dc=TRUTH["dc"],
                  k=TRUTH["k"], mu0=TRUTH["mu0"])
    x = np.where(t < CHANGE, V1 * t, V1 * CHANGE + V2 * (t - CHANGE))
    rng = np.random.default_rng(seed)
    mu = mu + TRUTH["trend"] * x + rng.normal(0.0, TRUTH["noise"], t.size)
    return write_lab_file(path, t, x, mu)
