"""
The direct effect
=================

Rate-and-state friction jumps at a velocity step by ``a ln(V2/V1)`` before it relaxes; the
athermal trap model does not: its friction is a continuous function of slip and time. With
thermally activated junctions (``direct = A``, Baumberger & Caroli 2006) the trap force is
multiplied by ``1 + A ln(V/V_ref)``, and a step up by a factor 10 raises the friction at once
by about ``A mu ln 10``. Below: the step ``u = 0.1 → 1`` with ``A = 0`` and ``A = 0.02``
(``V_ref = 1``, so both meet after the step), the jump measured in the run, and the direct
part ``a_direct`` of the effective rate-and-state ``a`` (linear response). Friction in
``F_el``, slip in ``a0``.
"""

import matplotlib.pyplot as plt
import numpy as np

import dryfriction as df
from dryfriction.ensemble.driving import Initial, Output, Track, VelocityDrive

program = df.VelocityProgram([df.Segment(0.1, slip=1.0), df.Segment(1.0, slip=4.0)])
fig, ax = plt.subplots(figsize=(6.5, 4.2), layout="constrained")
for A, color, ls in ((0.02, "C3", "-"), (0.0, "C0", "--")):
    model = df.TrapModel(eps=0.04, direct=A)
    r = df.simulate(model, VelocityDrive(program),
                    Initial("steady", velocity=0.1, track=Track(400.0)), Output(every_slip=0.002))
    before, after = np.flatnonzero(r.x <= 1.0)[-1], np.flatnonzero(r.x > 1.0)[0]
    jump = r.mu[after] - r.mu[before]
    a_direct = df.effective_rsf(0.1, model)["a_direct"]
    print(f"A = {A}: jump at the step {jump:+.4f} F_el; a_direct ln 10 = "
          f"{a_direct * np.log(10):.4f} F_el")
    ax.plot(r.x, r.mu, color=color, ls=ls, label=f"A = {A:g}: jump {jump:+.4f} F_el")
ax.axvline(1.0, color="0.6", lw=0.8, ls=":")
ax.set_xlabel("slip x  [a0]")
ax.set_ylabel("friction F  [F_el]")
ax.set_title("Velocity step u = 0.1 → 1 at x = 1 a0")
ax.legend(fontsize="small")
