"""Continuation in K near K_c, down then up (dryfriction.analysis.stickslip.bifurcation_scan).

Usage: python examples/bifurcation_scan.py U MASS DAMPING TRAPS_PER_A0 FACTORS [TRAVEL]
e.g.   python examples/bifurcation_scan.py 0.1 0 0 100 1.3,1.2,1.1,1.05,1.0,0.95,0.9,0.8,0.6 60
(FACTORS are K/K_c, K_c from the linear analysis; eps = 0.04, alpha = 0.13; the second half of
each stiffness's load-point travel TRAVEL, in a0, is analysed.)
"""

import sys
import time

from dryfriction.analysis.stickslip import bifurcation_scan
from dryfriction.theory.linear_stability import critical_stiffness
from dryfriction.theory.model import TrapModel

u, M, eta, n = (float(a) for a in sys.argv[1:5])
factors = [float(a) for a in sys.argv[5].split(",")]
travel = float(sys.argv[6]) if len(sys.argv) > 6 else 20.0
model = TrapModel(eps=0.04)
Kc = critical_stiffness(u, model, mass=M, damping=eta).critical_stiffness
t = time.perf_counter()


def progress(done: int, total: int) -> None:
    """A line per stiffness on stderr (the scan takes minutes): elapsed and time left, the
    runs being of equal load-point travel."""
    elapsed = time.perf_counter() - t
    print(f"bifurcation scan: run {done} of {total} done, {elapsed:.0f} s elapsed, about "
          f"{elapsed * (total - done) / done:.0f} s left", file=sys.stderr, flush=True)


print(f"bifurcation scan: K_c = {Kc:.5g}; {2 * len(factors) - 1} runs of {travel:g} a0 "
      "(down, then up)", file=sys.stderr, flush=True)
out = bifurcation_scan(u, model, [f * Kc for f in factors], mass=M, damping=eta,
                       traps_per_a0=n, travel=travel, transient=travel / 2, progress=progress)
print(f"u = {u:g}, M = {M:g}, eta = {eta:g}: K_c = {out['K_c']:.5g} "
      f"({time.perf_counter() - t:.1f} s)")
for leg in ("down", "up"):
    for r in out[leg]:
        print(f"{leg:4s} K/Kc = {r['stiffness'] / Kc:.3f}  class = {r['class']:2.0f}  "
              f"amplitude = {r['amplitude']:.4f}  period = {r['period']:.2f}  "
              f"slip/event = {r['slip_per_event']:.3f}  stick fraction = "
              f"{r['stick_fraction']:.2f}  events = {r['events']:.0f}")
