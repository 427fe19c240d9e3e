"""
Creep laws compared: logarithmic and Eyring–Nabarro
===================================================

Contacts grow by creep. The model's logarithmic law (eq. 17) is the long-time form of the
exact Eyring–Nabarro law (eqs. 15–16). Left: the contact radius ``a_r(T)/a0`` after a time
``T`` at rest; right: the static friction after that wait. At ``eps = 0.01`` they agree to a
few thousandths; at ``eps = 0.05`` they part beyond ``T ~ 10``, and far beyond the paper's
range (``T <= 100``) the exact law ages faster. Times in ``t0``, friction in ``F_el``.
"""

import matplotlib.pyplot as plt
import numpy as np

import dryfriction as df
from dryfriction.theory.creep import radius

T = np.logspace(-2, 4, 200)  # waiting time / t0
fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.8), layout="constrained")
for eps, color in ((0.01, "C0"), (0.05, "C3")):
    for law, ls in (("log", "-"), ("eyring-nabarro", "--")):
        left.semilogx(T, radius(T, eps, law), ls, color=color, label=f"eps = {eps}, {law}")
        right.semilogx(T, df.static_friction(df.TrapModel(eps=eps, creep=law), T), ls,
                       color=color, label=f"eps = {eps}, {law}")
    gap = np.abs(df.static_friction(df.TrapModel(eps=eps, creep="eyring-nabarro"), T)
                 - df.static_friction(df.TrapModel(eps=eps, creep="log"), T))
    print(f"eps = {eps}: largest difference in mu_s, T <= 100: {gap[T <= 100].max():.2e} F_el; "
          f"T <= 1e4: {gap.max():.2e} F_el")
left.set_xlabel("waiting time T = t_w/t0  [t0]")
left.set_ylabel("contact radius a_r/a0")
left.legend(fontsize="small")
right.set_xlabel("waiting time T = t_w/t0  [t0]")
right.set_ylabel("static friction F_s  [F_el]")
