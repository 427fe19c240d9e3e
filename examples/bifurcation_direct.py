"""Continuation in K through K_c with the direct effect, at one velocity
(dryfriction.analysis.bifurcation.continuation).

Usage: python examples/bifurcation_direct.py U [A] [TRAPS_PER_A0] [PERIODS] [DISTANCES]
e.g.   python examples/bifurcation_direct.py 0.01 0.02 100 15 \
           -0.05,0.03,0.06,0.1,0.15,0.2,0.3,0.45,0.6
(quasi-static spring, eps = 0.04, alpha = 0.13; DISTANCES are (K_c - K)/K_c of the way down,
K_c from the linear theory; PERIODS linear periods per stiffness, the last 4 measured.)
"""

import sys
import time

from dryfriction.analysis.bifurcation import continuation
from dryfriction.theory.model import TrapModel

u = float(sys.argv[1])
A = float(sys.argv[2]) if len(sys.argv) > 2 else 0.02
n = float(sys.argv[3]) if len(sys.argv) > 3 else 100.0
periods = float(sys.argv[4]) if len(sys.argv) > 4 else 15.0
ds = ([float(a) for a in sys.argv[5].split(",")] if len(sys.argv) > 5
      else [-0.05, 0.03, 0.06, 0.1, 0.15, 0.2, 0.3, 0.45, 0.6])
t = time.process_time()
out = continuation(u, TrapModel(eps=0.04, direct=A), ds, traps_per_a0=n, periods=periods)
print(f"u = {u:g}, A = {A:g}, {n:g} traps/a0: K_c = {out['K_c']:.5g}, noise floor "
      f"{out['floor']:.2e}, type {out['type']}, exponent {out['exponent']:.3f}, hysteresis "
      f"at d = {out['hysteresis_d']} ({time.process_time() - t:.0f} s CPU)")
for leg in ("down", "up"):
    for r in out[leg]:
        print(f"{leg:4s} d = {r['d']:+.3f}  K = {r['K']:.5f}  amplitude = {r['amplitude']:.3e}  "
              f"v_min/u = {r['v_min']:.3f}")
