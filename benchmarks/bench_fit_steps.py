"""Speed of the per-step fit of laboratory records (issue 10).

Goals on one core, in-process: one velocity step of ~6000 samples fitted with the machine
stiffness and the trend free, profile-likelihood intervals included, in <= 1 s; a 20-step
record in <= 20 s (Wald intervals, warm starts from step to step). The records come from the
independent solver of the tests (``tests/lab_synth.py``): a = 0.006, b = 0.009, Dc = 20 um,
k = 3000 /m, trend -8 /m, noise 3e-4.

Run: ``python -m benchmarks bench_fit_steps``.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from dryfriction.fit.steps import fit_steps  # noqa: E402
from dryfriction.records.data import SeriesData  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from lab_synth import Truth, synth_record  # noqa: E402


def _record(vels: list[float], slip: float, dt_per_um: float) -> SeriesData:
    t, v, mu, _ = synth_record(Truth(), vels, duration_slip=slip, dt_per_um=dt_per_um, seed=1)
    return SeriesData(t, v, mu, source="synthetic")


def main() -> None:
    one = _record([1e-6, 3e-6], 600e-6, 0.25)  # one step
    print(f"one step: {len(one)} samples")
    fit_steps(one)  # compile and warm the caches
    for profile in (False, True):
        t0, c0 = time.perf_counter(), time.process_time()
        res = fit_steps(one, profile=profile)
        dt, dc = time.perf_counter() - t0, time.process_time() - c0
        r = res.rows[0]
        print(f"  profile={profile!s:5}: {dt:6.2f} s wall, {dc:6.2f} s CPU  (goal <= 1 s with "
              f"profiles)  a = "
              f"{r['a']:.4g} +- {r['sigma_a']:.2g}, k = {r['stiffness']:.4g}, "
              f"success {res.success}")
    vels = [1e-6, 3e-6] * 10 + [1e-6]
    many = _record(vels, 150e-6, 0.5)
    t0, c0 = time.perf_counter(), time.process_time()
    res = fit_steps(many)
    dt, dc = time.perf_counter() - t0, time.process_time() - c0
    a = np.array([r["a"] for r in res.rows])
    print(f"20 steps ({len(many)} samples): {dt:6.2f} s wall, {dc:6.2f} s CPU  (goal <= 20 s)  "
          f"a = "
          f"{a.mean():.4g} +- {a.std():.2g} over the steps, success {res.success}")


if __name__ == "__main__":
    main()
