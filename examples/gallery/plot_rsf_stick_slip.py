"""
Rate-and-state friction on a spring
===================================

The classic laboratory parameters (``a = 0.005``, ``b = 0.01``, ``Dc = 10 µm``) on a spring
slider pulled at 1 µm/s, then at 10 µm/s. Below the critical stiffness
``k_c = (b - a)/Dc = 500 /m`` steady sliding is unstable and the slider stick-slips; radiation
damping keeps the slips finite.
"""

import matplotlib.pyplot as plt

import dryfriction as df
from dryfriction.rsf import RSFInitial, RSFOutput, SpringSlider

law = df.RateState(a=0.005, b=0.01, dc=1e-5, mu0=0.6, v0=1e-6)
program = [df.Segment(1e-6, 20.0), df.Segment(1e-5, 60.0)]  # (velocity m/s, duration s)
# steady sliding at 1 µm/s is unstable on this spring: a start 1 % faster (with the steady
# state of 1 µm/s) seeds the instability, rather than rounding errors
r = df.simulate(law, SpringSlider(program, stiffness=400.0, damping=1e-2),
                RSFInitial(v=1.01e-6, theta=1e-5 / 1e-6), RSFOutput(every=0.02))

fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6, 5), sharex=True, layout="constrained")
ax1.plot(r.t, r.mu)
ax1.set_ylabel("friction μ = τ/σ_n")
ax1.set_title("Spring slider, k = 400 /m < k_c = 500 /m")
ax2.semilogy(r.t, r.v)
ax2.set_xlabel("time (s)")
ax2.set_ylabel("slider velocity (m/s)")
