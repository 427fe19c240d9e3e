"""Wall time of a 32-point sweep with 1 and with 2 Dask workers (goal: >= 1.6x, issue 12).

Each point is a linear-stability analysis with a fine frequency scan (compute bound, ~0.5 s),
so the measured speed-up is that of the scheduling, not of the work. Cluster start-up is
included, as a user meets it; all points are submitted at once, so each worker imports the
package once and stays warm for the whole grid. The load average is printed: on a shared
machine the speed-up measures the other users too. Run: ``python -m benchmarks bench_sweep``.
"""

from __future__ import annotations

import os
import tempfile
import time

from dryfriction.io.sweep import parse_sweep, run_sweep
from dryfriction.theory.stability import critical_stiffness


def heavy_point(protocol: dict) -> dict[str, float]:  # type: ignore[type-arg]
    d = protocol["drive"]
    res = critical_stiffness(d["velocity"], protocol["model"]["eps"], damping=d["damping"],
                             n_omega=60000)
    return {"K_c": res.critical_stiffness}


PROTO = {
    "model": {"eps": 0.04},
    "drive": {"velocity": 0.1, "damping": 0.05},
    "sweep": {"drive.velocity": {"log": [0.01, 1.0, 4]}, "model.eps": {"lin": [0.02, 0.05, 8]}},
}


def main() -> None:
    spec = parse_sweep(PROTO)
    load = os.getloadavg()[0]
    times = {}
    for n in (1, 2):
        with tempfile.TemporaryDirectory() as tmp:
            t = time.perf_counter()
            run_sweep(spec, heavy_point, f"{tmp}/out", n_workers=n)
            times[n] = time.perf_counter() - t
    one = heavy_point(spec.protocol(next(spec.points())[1]))
    t = time.perf_counter()
    heavy_point(spec.protocol(next(spec.points())[1]))
    per_point = time.perf_counter() - t
    print(f"{spec.size}-point sweep (one point ~{per_point:.2f} s in-process, "
          f"K_c = {one['K_c']:.4f}; load average {load:.2f} -> {os.getloadavg()[0]:.2f} on "
          f"{os.cpu_count()} cores):")
    print(f"  1 worker : {times[1]:.2f} s")
    print(f"  2 workers: {times[2]:.2f} s   speed-up {times[1] / times[2]:.2f}x")


if __name__ == "__main__":
    main()
