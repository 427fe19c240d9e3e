"""
Velocity-weakening dynamic friction
===================================

Steady sliding friction ``mu_d(u)`` (eq. 34) against the reduced velocity ``u = V t0 / a0``,
with the low-velocity law ``mu_d ≈ 1 - (3/2) eps ln u`` plus its constant (eq. 35), and
saturation at ``mu_d → 1`` at high velocity.
"""

import matplotlib.pyplot as plt
import numpy as np

import dryfriction as df

eps = 0.04
model = df.TrapModel(eps=eps)
u = np.logspace(-3, 3, 200)
fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
ax.semilogx(u, df.steady_friction(model, u), label="eq. 34 (exact in the model)")
low = u < 1
ax.semilogx(u[low], df.steady_friction_low_velocity(model, u[low]), "--",
            label="low-velocity law (eq. 35)")
ax.axhline(1.0, color="0.6", lw=0.8, label="saturation F_el")
ax.set_xlabel("velocity u = V t0/a0  [a0/t0]")
ax.set_ylabel("dynamic friction F_d  [F_el]")
ax.set_title(f"Steady sliding, eps = {eps}")
ax.legend(fontsize="small")
