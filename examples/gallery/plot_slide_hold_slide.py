"""
Slide-hold-slide
================

Sliding at ``u = 1``, the slider stops for a hold of ``t_h``, then slides again: the friction
peaks on re-sliding, and the peak grows with the logarithm of the hold (healing), as in the
laboratory. Left: the protocol ``examples/slide_hold_slide.toml`` (holds of 10 and 1000
``t0``), run by the trap ensemble; right: the peak against the hold time for more holds, with
the healing rate ``beta = d mu_peak / d ln t_h`` of a straight-line fit (ours). Friction in
``F_el``, times in ``t0``, slip in ``a0``.
"""

import matplotlib.pyplot as plt
import numpy as np

import dryfriction as df
from dryfriction.analysis.rsf_view import hold_peaks
from dryfriction.ensemble.driving import Track
from dryfriction.io.examples import examples_path

protocol = df.load_protocol(examples_path() / "slide_hold_slide.toml")
r = protocol.run()

holds = np.logspace(0, 3, 7)  # t0
model = df.TrapModel(eps=0.04)
peaks = hold_peaks(model, Track(400.0), 1.0, holds)
beta, level = np.polyfit(np.log(holds), peaks, 1)
print(f"healing rate beta = {beta:.4f} F_el per unit ln(t_h / t0)")

fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.8), layout="constrained")
left.plot(r.x, r.mu, color="C0")
left.set_xlabel("slip x  [a0]")
left.set_ylabel("friction F  [F_el]")
left.set_title("holds of 10 and 1000 t0 at x = 1 and 5 a0", fontsize="medium")
right.semilogx(holds, peaks, "o", color="C3", label="peak on re-sliding")
right.semilogx(holds, level + beta * np.log(holds), "k--", lw=1,
               label=f"fit, beta = {beta:.4f} F_el")
right.set_xlabel("hold time t_h  [t0]")
right.set_ylabel("peak friction  [F_el]")
right.legend(fontsize="small")
