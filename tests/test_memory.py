"""Bounded memory of the closed-form theory on large arrays (issue 12).

Each measurement runs in a fresh interpreter: the peak resident set size (``ru_maxrss``) after
the call minus the peak before it is what the evaluation added. The bounds are generous (about
twice what the chunked evaluation needs) and below what the same call needs when it evaluates
the whole array at once (measured: 85 MB for static_friction, 149 MB for steady_friction).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

_PROBE = """
import resource, sys
import numpy as np
import dryfriction.theory.creep as creep
if len(sys.argv) > 3:
    creep.PER_EPS_CHUNK = int(sys.argv[3])
from dryfriction.theory.static import static_friction
from dryfriction.theory.steady import steady_friction
fn = {"static": static_friction, "steady": steady_friction}[sys.argv[1]]
x = np.geomspace(1e-3, 1e3, int(sys.argv[2]))
fn(x[:10], 0.04)  # lazy imports and caches first: they are not what is measured
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
mu = fn(x, 0.04)
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
assert mu.shape == x.shape and np.isfinite(mu).all()
print((after - before) / 1024.0)
"""


def _extra_mb(which: str, n: int, chunk: int | None = None) -> float:
    import dryfriction

    src = str(Path(dryfriction.__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": src}
    args = [sys.executable, "-c", _PROBE, which, str(n)] + ([str(chunk)] if chunk else [])
    r = subprocess.run(args, capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr
    return float(r.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize(("which", "n", "bound_mb"), [("static", 1_000_000, 60.0),
                                                      ("steady", 50_000, 80.0)])
def test_large_arrays_are_evaluated_in_bounded_memory(which: str, n: int,
                                                      bound_mb: float) -> None:
    assert _extra_mb(which, n) < bound_mb


def test_the_memory_probe_sees_an_unchunked_evaluation() -> None:
    """The probe itself can fail: with one chunk for the whole array the same call goes over
    the bound."""
    assert _extra_mb("steady", 50_000, chunk=10**9) > 80.0
