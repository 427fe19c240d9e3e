"""
The command line
================

Everything the package computes is also a ``dryfriction`` command. This script runs a few of
them as a user would in a terminal (here through :mod:`subprocess`, with the interpreter that
runs the script) and shows what they print and draw, in a fresh folder holding a copy of the
shipped examples. ``dryfriction COMMAND --help`` lists every option with its unit.
"""

import os
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib.image as mpimg
import matplotlib.pyplot as plt

work = Path(tempfile.mkdtemp())  # the terminal's working folder
env = {**os.environ, "COLUMNS": "80"}  # tables as wide as a terminal


def dryfriction(*args: str) -> str:
    """Run ``dryfriction ARGS`` in ``work`` and return what it printed; an error stops the
    script with the command's message."""
    cmd = [sys.executable, "-m", "dryfriction.cli", *args]
    print("$ dryfriction " + " ".join(args))
    r = subprocess.run(cmd, capture_output=True, text=True, cwd=work, env=env)
    if r.returncode != 0:
        raise RuntimeError(f"dryfriction {' '.join(args)} failed:\n{r.stdout}{r.stderr}")
    print(r.stdout + r.stderr)  # tables on stdout, messages on stderr
    return r.stdout


# %%
# A copy of the example protocols and data, to run and to edit:
dryfriction("examples", "--copy", "examples")

# %%
# Steady sliding friction of the trap model (eq. 34) at three reduced velocities
# ``u = V t0/a0``, in units of the elastic friction ``F_el``:
dryfriction("steady", "--eps", "0.04", "--u", "0.01", "1", "100")

# %%
# How a laboratory record is read: its columns, units, load program and steps:
dryfriction("record", "examples/data/lab/sepiolite_velstep_0.2-2um_s.txt")

# %%
# A protocol file runs the trap-model simulator; the results folder holds the data
# (``run.csv``), the parameters and a figure:
dryfriction("simulate", "examples/velocity_step.toml", "--out", "run")
out = work / "run"
print("run/:", ", ".join(sorted(p.name for p in out.iterdir())))

fig, ax = plt.subplots(figsize=(7.5, 5.5), layout="constrained")
ax.imshow(mpimg.imread(next(out.glob("*.png"))))
ax.set_axis_off()
