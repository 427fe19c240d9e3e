"""Peak memory and time of ``steady_friction`` and ``static_friction`` on 1e6 points (issue 12).

Each case runs in a fresh interpreter; the figure is the peak resident set size the call
added (``VmHWM`` after minus before) and the whole process's peak. Target: <= 100 MB.
Run: ``python -m benchmarks bench_memory``.
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
from dryfriction.theory.static import static_friction
from dryfriction.theory.steady import steady_friction
fn = {"static": static_friction, "steady": steady_friction}[sys.argv[1]]
x = np.geomspace(1e-3, 1e3, 1_000_000)
fn(x[:10], 0.04, creep=sys.argv[2])
before = peak_kb()
t = time.perf_counter()
fn(x, 0.04, creep=sys.argv[2])
dt = time.perf_counter() - t
after = peak_kb()
print(f"{dt:.2f} {(after - before) / 1024:.0f} {after / 1024:.0f}")
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


if __name__ == "__main__":
    main()
