"""
Stick-slip and its stability: the critical stiffness
====================================================

A slider pulled through a spring of stiffness ``K`` slides steadily when ``K`` is above the
critical stiffness ``K_c`` of the linear stability analysis, and sticks and slips below it.
Top: ``K_c(u)`` of the trap model (quasi-static spring, no mass). Bottom: two springs pulled
at ``u = 0.01``, one on each side of ``K_c``, simulated with the trap ensemble (100 traps per
``a0``): the soft one sticks and slips, the stiff one slides. Stiffness in ``F_el/a0``,
velocities in ``a0/t0``, forces in ``F_el``.
"""

import matplotlib.pyplot as plt
import numpy as np

import dryfriction as df
from dryfriction.analysis.stickslip import spring_force
from dryfriction.ensemble.driving import Initial, Output, SpringDrive, Track

model = df.TrapModel(eps=0.04)
u = np.logspace(-2, 1, 7)  # each K_c is a Nyquist scan: about 0.4 s
k_c = np.array([df.critical_stiffness(x, model).critical_stiffness for x in u])

u_run = 0.01
k_here = df.critical_stiffness(u_run, model).critical_stiffness
print(f"K_c(u = {u_run}) = {k_here:.4f} F_el/a0")

runs = {}
for factor in (0.5, 2.0):  # one spring below K_c, one above
    drive = SpringDrive(stiffness=factor * k_here, mass=0.0,
                        program=df.VelocityProgram([df.Segment(u_run, slip=25.0)]))
    r = df.simulate(model, drive, Initial("steady", velocity=u_run, track=Track(100.0)),
                    Output(every_slip=0.01))
    runs[factor] = (r, spring_force(r, drive))

fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.5, 6.5), layout="constrained")
top.loglog(u, k_c, "k-", label="K_c(u), linear stability")
for factor in runs:
    top.plot(u_run, factor * k_here, "o", color="C3" if factor < 1 else "C0",
             label=f"the spring K = {factor:g} K_c below")
top.text(0.97, 0.9, "steady sliding", transform=top.transAxes, ha="right", color="C0")
top.text(0.03, 0.06, "stick-slip", transform=top.transAxes, color="C3")
top.set_ylim(k_c.min() / 3, k_c.max() * 4)
top.set_xlabel("pulling velocity u = V t0/a0  [a0/t0]")
top.set_ylabel("critical stiffness K_c  [F_el/a0]")
top.legend(fontsize="small", loc="lower center")
for factor, (r, force) in runs.items():
    bottom.plot(r.t * u_run, force, color="C3" if factor < 1 else "C0",
                label=f"K = {factor:g} K_c")
bottom.set_xlabel("load-point travel u t  [a0]")
bottom.set_ylabel("spring force  [F_el]")
bottom.legend(fontsize="small")
