"""
Fitting a laboratory record: a, b and Dc with honest intervals
==============================================================

A velocity step (load-point velocity 0.2 → 2 µm/s) measured on sepiolite fault gouge at
30 MPa effective normal stress (Giacomel et al. 2024; the record ships with the package, with
its licence, in ``examples/data/lab``). The record is read in SI units, its load program is
found from the displacement, the step is cut out, and rate-and-state friction (ageing law) is
fitted with the machine's stiffness and a linear drift free. The 95 % intervals are those of the
profile likelihood (a, b, Dc) and of the covariance allowing for the record's correlated noise
(a - b, k). This is what ``dryfriction fit RECORD --model rsf`` does.
"""

import matplotlib.pyplot as plt

from dryfriction.fit.models import load_point_displacement
from dryfriction.fit.steps import fit_steps
from dryfriction.io.examples import examples_path
from dryfriction.records import lab

path = examples_path() / "data" / "lab" / "sepiolite_velstep_0.2-2um_s.txt"
rec = lab.read_record(path)
program = lab.detect_program(rec)  # the load program, found from the displacement
segments = program.segments
windows = lab.slice_steps(rec, segments)
print(f"{len(rec)} samples over {rec.time[-1] - rec.time[0]:.0f} s; load program:")
for s in segments:
    print(f"  from t = {rec.time[s.i_start] - rec.time[0]:7.1f} s: V = {s.velocity * 1e6:.3g} µm/s")

result = fit_steps(rec, windows, segments, profile=True)
row = result.rows[0]
print(f"\nstep 0, {row['v_before'] * 1e6:.2g} -> {row['v_after'] * 1e6:.2g} µm/s "
      f"({row['state_law']} law), 95 % intervals:")
for name, scale, unit in (("a", 1, ""), ("b", 1, ""), ("a_minus_b", 1, ""),
                          ("dc", 1e6, " µm"), ("stiffness", 1, " /m")):
    print(f"  {name:10s} = {row[name] * scale:.4g}{unit}  "
          f"[{row[name + '_lo'] * scale:.4g}, {row[name + '_hi'] * scale:.4g}]")
print(f"  flags: {row['flags'] or 'none'} (a value at a search bound or not identified is "
      "flagged here)")

# %%
# The data (grey points) and the fitted model (red) against load-point displacement; the
# residuals below show what the model leaves: the record's own fluctuations.
d = result.data[0]
model = result.model_curve(0)
x_um = load_point_displacement(d) * 1e6
fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 5), sharex=True,
                                  gridspec_kw={"height_ratios": [3, 1]}, layout="constrained")
top.plot(x_um, d.mu, ".", ms=2, color="0.6", label="measured")
top.plot(x_um, model, color="C3", lw=1.5, label="rate-and-state fit")
top.set_ylabel("friction μ = τ/σ_n")
top.set_title(f"a = {row['a']:.4f}, b = {row['b']:.4f}, Dc = {row['dc'] * 1e6:.0f} µm")
top.legend()
bottom.plot(x_um, d.mu - model, ".", ms=2, color="0.4")
bottom.axhline(0.0, color="C3", lw=1)
bottom.set_xlabel("load-point displacement  [µm]")
bottom.set_ylabel("residual")
