"""Peak memory and time of ``steady_friction`` and ``static_friction`` on 1e6 points, and of
the trap ensemble at 2e6 pairs per ``a0`` (issue 12).

Each case runs in a fresh interpreter; the figure is the peak resident set size the call
added (``VmHWM`` after minus before) and the whole process's peak. Targets: <= 100 MB for the
closed forms; 2e6 pairs per ``a0`` within 1 GB (a velocity-driven run of 25 ``a0`` from steady
sliding, long enough for the buffer to move). Run: ``python -m benchmarks bench_memory``.
"""

from __future__ import annotations

import os
import subprocess
import sys

_PROBE = """
import resource, sys


def peak_kb():
    # VmHWM is this process's own high-water mark; ru_maxrss also keeps the parent's (a
    # child started by vfork + exec inherits it), which hides the call in a large parent
    try:
        with open("/proc/self/status") as f:
            return next(int(ln.split()[1]) for ln in f if ln.startswith("VmHWM:"))
    except OSError:
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss

import time
import numpy as np
from dryfriction.theory.model import TrapModel
from dryfriction.theory.static import static_friction
from dryfriction.theory.steady import steady_friction
fn = {"static": static_friction, "steady": steady_friction}[sys.argv[1]]
model = TrapModel(eps=0.04, creep=sys.argv[2])
x = np.geomspace(1e-3, 1e3, 1_000_000)
fn(model, x[:10])
before = peak_kb()
t = time.perf_counter()
fn(model, x)
dt = time.perf_counter() - t
after = peak_kb()
print(f"{dt:.2f} {(after - before) / 1024:.0f} {after / 1024:.0f}")
"""


_ENSEMBLE_PROBE = """
import time
from dryfriction.ensemble.driving import Output, VelocityDrive, simulate
from dryfriction.ensemble.population import Initial, Track, TrapModel
from dryfriction.program import VelocityProgram


def peak_mb():
    with open("/proc/self/status") as f:
        return next(int(ln.split()[1]) for ln in f if ln.startswith("VmHWM:")) / 1024


def run(lam, slip):
    return simulate(TrapModel(0.13, 0.04),
                    VelocityDrive(VelocityProgram([{"velocity": 1.0, "slip": slip}])),
                    Initial("steady", velocity=1.0, track=Track(lam)), Output(every_slip=0.5))


run(100.0, 0.5)  # compiled code and caches in, before the baseline
before = peak_mb()
t = time.perf_counter()
run(2e6, 25.0)
print(f"{time.perf_counter() - t:.1f} {peak_mb() - before:.0f} {peak_mb():.0f}")
"""


def main() -> None:
    print(f"1e6 points, eps = 0.04 (load average {os.getloadavg()[0]:.2f}):")
    for which in ("static", "steady"):
        for creep in ("log", "eyring-nabarro"):
            r = subprocess.run([sys.executable, "-c", _PROBE, which, creep],
                               capture_output=True, text=True)
            if r.returncode:
                last = r.stderr.strip().splitlines()[-1]
                print(f"  {which}_friction {creep:15s} failed: {last}")
                continue
            dt, extra, peak = r.stdout.split()
            print(f"  {which}_friction {creep:15s} {dt:>6s} s  +{extra:>4s} MB "
                  f"(process peak {peak} MB)")
    r = subprocess.run([sys.executable, "-c", _ENSEMBLE_PROBE], capture_output=True, text=True)
    if r.returncode:
        print(f"  ensemble 2e6 pairs/a0 failed: {r.stderr.strip().splitlines()[-1]}")
        return
    dt, extra, peak = r.stdout.split()
    print(f"  ensemble, 2e6 pairs/a0, 25 a0  {dt:>6s} s  +{extra:>4s} MB (process peak {peak} MB;"
          " target: within 1 GB)")


if __name__ == "__main__":
    main()
