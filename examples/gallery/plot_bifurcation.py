"""
The Hopf bifurcation of sliding: the first Lyapunov coefficient l1
==================================================================

At the critical stiffness ``k_c`` steady sliding of a spring slider loses stability through a
Hopf bifurcation. Its first Lyapunov coefficient ``l1`` (computed from the normal form, in
the reduced coordinates: dimensionless) says what happens next: ``l1 < 0`` (supercritical)
gives small oscillations that grow smoothly as ``k`` drops below ``k_c``; ``l1 > 0``
(subcritical) gives a jump to large stick-slip, with hysteresis. Without inertia a one-state
law is degenerate here (``l1 = 0`` up to rounding); the mass per unit normal force ``M``
(s²/m) decides the sign. Below: ``l1`` against ``M`` for the ageing and the slip laws,
``a = 0.005``, ``b = 0.01``, ``Dc = 10 µm``, ``V = 1 µm/s`` (``dryfriction bifurcation``
computes the same from the command line).
"""

import matplotlib.pyplot as plt
import numpy as np

import dryfriction as df
from dryfriction.analysis.rsf_hopf import rsf_hopf

masses = np.logspace(-4, 3, 15)  # s^2/m
fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True, layout="constrained")
for law, color in (("ageing", "C3"), ("slip", "C0")):
    model = df.RateState(a=0.005, b=0.01, dc=1e-5, mu0=0.6, v0=1e-6, state_law=law)
    rows = [rsf_hopf(model, 1e-6, mass=m) for m in masses]
    l1 = np.array([h.l1 for h in rows])
    k_c = np.array([h.k_c for h in rows])
    natures = sorted({h.nature for h in rows})
    print(f"{law} law: k_c from {k_c.min():.4g} to {k_c.max():.4g} /m; natures: {natures}")
    top.loglog(masses, np.abs(l1), "o-", color=color,
               label=f"{law} law: l1 {'> 0, subcritical' if l1[-1] > 0 else '< 0, supercritical'}")
    bottom.semilogx(masses, k_c, "o-", color=color, label=f"{law} law")
top.set_ylabel("|l1|  (reduced, dimensionless)")
top.legend(fontsize="small")
bottom.axhline((0.01 - 0.005) / 1e-5, color="0.5", lw=0.8, ls="--",
               label="(b - a)/Dc, quasi-static")
bottom.set_xlabel("mass per unit normal force M  [s²/m]")
bottom.set_ylabel("critical stiffness k_c  [1/m]")
bottom.legend(fontsize="small")
