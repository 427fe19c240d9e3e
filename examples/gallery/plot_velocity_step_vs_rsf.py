"""
A velocity step: the trap model against rate-and-state friction
===============================================================

The protocol ``examples/velocity_step.toml`` (steady sliding at ``u = 1``, then ``u = 0.01``)
run by the trap ensemble, and rate-and-state friction fitted to that run (its "twin", ageing
and slip laws, in reduced units: ``a``, ``b`` in ``F_el``, ``Dc`` in ``a0``). The trap model
has no direct effect (no jump at the step) and a finite memory: its transient ends after a
slip of about ``1 + p_d``, where the rate-and-state relaxation is exponential. This is what
``dryfriction compare`` does.
"""

import matplotlib.pyplot as plt

import dryfriction as df
from dryfriction.analysis.rsf_view import compare_protocol
from dryfriction.io.examples import examples_path

path = examples_path() / "velocity_step.toml"
protocol = df.load_protocol(path)
fig, ax = plt.subplots(figsize=(6.5, 4.2), layout="constrained")
for law, color in (("ageing", "C3"), ("slip", "C2")):
    c = compare_protocol(protocol, state_law=law)
    if law == "ageing":
        ax.plot(c.x, c.mu_trap, color="0.3", lw=2.0, label="trap model")
    tw = c.twin
    print(f"{law} law: a = {tw.a:.4f}, b = {tw.b:.4f} F_el, Dc = {tw.dc:.3f} a0; "
          f"misfit rms {c.misfit['rms']:.4f} F_el")
    for note in tw.notes:  # what the fit says about itself (a bound, a systematic misfit)
        print(f"  note: {note.replace(str(path), path.name)}")
    ax.plot(c.x, c.mu_rsf, color=color, lw=1.2, ls="--",
            label=f"rate-and-state, {law} law (a = {tw.a:.3f}, Dc = {tw.dc:.2f} a0)")
ax.set_xlabel("slip x  [a0]")
ax.set_ylabel("friction F  [F_el]")
ax.set_title("Velocity step u = 1 → 0.01 at x = 1 a0")
ax.legend(fontsize="small")
