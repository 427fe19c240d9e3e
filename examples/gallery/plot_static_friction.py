"""
Static friction grows with waiting time
=======================================

The static friction coefficient after a wait ``T`` at rest (eq. 27), in units of the
purely elastic friction ``F_el``, for three creep rates ``eps``, and after ageing under a
tangential load ``0.5 F_el``. Times are in the creep time ``t0``.
"""

import matplotlib.pyplot as plt
import numpy as np

import dryfriction as df

T = np.logspace(-2, 4, 200)  # waiting time / t0
fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
for eps in (0.02, 0.04, 0.06):
    model = df.TrapModel(eps=eps)
    line, = ax.semilogx(T, df.static_friction(model, T), label=f"eps = {eps}, at rest")
    ax.semilogx(T, df.static_friction(model, T, load=0.5), "--", color=line.get_color(),
                label=f"eps = {eps}, under load 0.5 F_el")
ax.set_xlabel("waiting time T = t_w/t0  [t0]")
ax.set_ylabel("static friction F_s  [F_el]")
ax.set_title("Static friction after a hold (eq. 27)")
ax.legend(fontsize="small")
