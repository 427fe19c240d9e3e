"""
A velocity step on the trap ensemble
====================================

The simulator runs the model's asperity pairs one by one. Sliding steadily at ``u = 1``,
the slider is slowed to ``u = 0.01``: the friction rises to the new, higher steady level
(velocity weakening) over a memory length of about ``(1 + y_c) a0``, with no direct effect.
The dashed lines are the steady levels of eq. 34.
"""

import matplotlib.pyplot as plt

import dryfriction as df
from dryfriction.ensemble.driving import Initial, Output, Track, TrapModel, VelocityDrive

eps = 0.04
program = df.VelocityProgram([{"velocity": 1.0, "slip": 1.0}, {"velocity": 0.01, "slip": 4.0}])
r = df.simulate(TrapModel(eps=eps), VelocityDrive(program),
                Initial("steady", velocity=1.0, track=Track(200.0)), Output(every_slip=0.01))

fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
ax.plot(r.x, r.mu, label="trap ensemble, 200 pairs per a0")
for u in (1.0, 0.01):
    ax.axhline(float(df.steady_friction(TrapModel(eps=eps), u)), ls="--", color="0.5", lw=0.8)
ax.set_xlabel("slip x  [a0]")
ax.set_ylabel("friction F  [F_el]")
ax.set_title("Velocity step u = 1 → 0.01 at x = 1")
ax.legend(fontsize="small")
