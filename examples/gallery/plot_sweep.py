"""
A parameter sweep
=================

A protocol's ``[sweep]`` table names the parameters to vary and their values; ``dryfriction
sweep`` runs every point on a Dask cluster (here a local one with a single worker), stores each
point as it finishes (a second run resumes), and gathers them in a NetCDF file, ``sweep.nc``,
with the units of every variable. Here: the critical stiffness of steady sliding (``--linear``:
the linear stability of each point, no simulation) over the creep parameter ``eps`` and the
pulling velocity ``u``. For many points, start a cluster and pass ``--scheduler ADDRESS``.
"""

import os
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

from dryfriction.sweeps.sweep import load_sweep

work = Path(tempfile.mkdtemp())
(work / "sweep.toml").write_text("""
[model]
alpha = 0.13
eps = 0.04

[ensemble]
traps_per_a0 = 100
initial = "steady"
initial_velocity = 0.1

[drive]
kind = "spring"
stiffness = 0.05
mass = 0.0
segments = [{velocity = 0.1, slip = 10.0}]

[output]
every_slip = 0.02

[sweep]
"model.eps" = [0.02, 0.05]
"drive.segments.0.velocity" = {log = [0.01, 10.0, 5]}
""")
r = subprocess.run([sys.executable, "-m", "dryfriction.cli", "sweep", "sweep.toml",
                    "--out", "out", "--workers", "1", "--linear"],
                   cwd=work, capture_output=True, text=True, env={**os.environ, "COLUMNS": "80"})
if r.returncode != 0:
    raise RuntimeError(f"dryfriction sweep failed:\n{r.stdout}{r.stderr}")
print((r.stdout + r.stderr).strip().splitlines()[-1])  # its last line: what it wrote

ds = load_sweep(work / "out" / "sweep.nc")
print(ds["K_c"])

# %%
# Each variable carries its unit (CF attributes): ``K_c`` in ``F_el/a0``.
u_name, eps_name = "drive.segments.0.velocity", "model.eps"
fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
for eps in ds[eps_name].values:
    k = ds["K_c"].sel({eps_name: eps})
    ax.loglog(ds[u_name], k, "o-", label=f"eps = {eps:g}")
ax.set_xlabel(f"pulling velocity u  [{ds[u_name].attrs.get('units', 'a0/t0')}]")
ax.set_ylabel(f"critical stiffness K_c  [{ds['K_c'].attrs['units']}]")
ax.set_title("Sweep: stick-slip below K_c, steady sliding above")
ax.legend()
