"""Whole-process wall time of the commands of issue 12.

What a user waits for: interpreter start, imports, the solve (interpreted for this small job,
no Numba: :mod:`dryfriction.rsf.stepper`) and the files, for
``dryfriction simulate examples/rsf_velocity_step.toml`` with the figure and with
``--no-figure``, ``dryfriction reproduce`` and ``dryfriction --help``. The variants run
interleaved (round robin) so that a change in the machine's load hits them all alike; medians
of wall and CPU time (user + system, children included: ``reproduce`` draws in a pool, and
``simulate`` in its painter, :mod:`dryfriction.cli.painter`) are reported, with the load
average, since the machine may be shared. Targets (issue 12):
``--help`` <= 0.3 s, ``--no-figure`` <= 0.5 s, with the figure <= 1.0 s, ``reproduce`` <= 3 s.

``--first-run`` also measures the pause of the first run after an install: a fresh copy of the
package (no Numba cache) is warmed with ``python -m dryfriction.warm`` (what ``make`` does),
then timed once, then again.

rsfmodel and PyRSF are not on PyPI; the reference figures of issue 12 were measured the same
way on a 2-core machine: rsfmodel 0.41 s, PyRSF 1.2 s. Since that machine's speed is not this
one's, rsfmodel's own velocity step is run here too (below).

Issue 26 asks the velocity step without a figure at <= 0.9x the CPU of rsfmodel's own script
for the same case. rsfmodel is not installable beside the package (it needs SciPy < 1.14), so
it is run from a scratch environment of its own when one is named, ``RSFMODEL_PYTHON=PATH``
(an interpreter with rsfmodel installed: see ``../shared/peers/README.md``); its standard velocity
step (a = 0.005, b = 0.01, Dc = 10 um, k = 1e-3 /um, 1 -> 10 um/s at 10 s, 40 s at 100 Hz,
ageing law) without the plots, interleaved with the rest. Without it, the floor is what that
script imports (NumPy and ``scipy.integrate``), in this interpreter.

Run: ``python -m benchmarks bench_cli`` (add ``--first-run`` when run directly).
"""

from __future__ import annotations

import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PROTOCOL = ROOT / "examples" / "rsf_velocity_step.toml"
REFERENCE = {"rsfmodel": 0.41, "PyRSF": 1.2}  # s, issue 12 (not installable from PyPI)
TARGETS = {"dryfriction --help": 0.3, "simulate --no-figure": 0.5, "simulate (figure)": 1.0,
           "reproduce": 3.0}  # s, issue 12
RSFMODEL_FLOOR = "rsfmodel's imports"
RSFMODEL_RUN = "rsfmodel velocity step"
CPU_RATIO_GOAL = 0.9  # simulate --no-figure / rsfmodel's step, CPU (issue 26)
# rsfmodel's standard velocity step through its public API, without its plots (the case of
# its examples/velocity_step_one_state.py; written here, the peer is only called)
RSFMODEL_STEP = """
import numpy as np
from rsfmodel import rsf, staterelations
m = rsf.Model()
m.mu0, m.a, m.k, m.v, m.vref = 0.6, 0.005, 1e-3, 1.0, 1.0
s = staterelations.DieterichState()
s.b, s.Dc = 0.01, 10.0
m.state_relations = [s]
m.time = np.arange(0, 40.01, 0.01)
v = np.ones_like(m.time)
v[1000:] = 10.0
m.loadpoint_velocity = v
m.solve()
"""


def _command() -> list[str]:
    """The installed console script when there is one (what a user runs), else ``-m``."""
    script = Path(sys.executable).with_name("dryfriction")
    return [str(script)] if script.exists() else [sys.executable, "-m", "dryfriction.cli"]


def _run(args: list[str], cwd: str, env: dict[str, str] | None = None) -> tuple[float, float]:
    """Wall and CPU (user + system) seconds of one run of ``args``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run(args, cwd=cwd, env=env, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def whole_process(rounds: int = 9) -> dict[str, tuple[float, float]]:
    """Median wall and CPU times (s) of the variants, run interleaved ``rounds`` times."""
    cmd = _command()
    variants = {
        "python -c pass": [sys.executable, "-c", "pass"],
        "dryfriction --help": [*cmd, "--help"],
        "simulate --no-figure": [*cmd, "simulate", str(PROTOCOL), "--out", "nofig",
                                 "--no-figure", "--json"],
        "simulate (figure)": [*cmd, "simulate", str(PROTOCOL), "--out", "fig", "--json"],
        "  without painter": [*cmd, "simulate", str(PROTOCOL), "--out", "fig0", "--json"],
        "reproduce": [*cmd, "reproduce", "--out", "rep"],
        RSFMODEL_FLOOR: [sys.executable, "-c", "import numpy, scipy.integrate"],
    }
    peer = os.environ.get("RSFMODEL_PYTHON")
    if peer:
        variants[RSFMODEL_RUN] = [peer, "-c", RSFMODEL_STEP]
    # the figure drawn in the command's own process: what the painter saves
    environ = {"  without painter": {**os.environ, "DRYFRICTION_PAINTER": "0"}}
    times: dict[str, list[tuple[float, float]]] = {k: [] for k in variants}
    with tempfile.TemporaryDirectory() as tmp:
        for name, args in variants.items():  # warm the file cache and the kernels' cache
            _run(args, tmp, environ.get(name))
        for _ in range(rounds):
            for name, args in variants.items():
                times[name].append(_run(args, tmp, environ.get(name)))
    return {k: (statistics.median(w for w, _ in v), statistics.median(c for _, c in v))
            for k, v in times.items()}


def first_run_after_install() -> dict[str, tuple[float, float]]:
    """Wall and CPU times (s) on a fresh copy of the package: the warm-up, the first run, the
    second."""
    import dryfriction

    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "src"
        shutil.copytree(Path(dryfriction.__file__).resolve().parent, src / "dryfriction",
                        ignore=shutil.ignore_patterns("__pycache__"))
        env = {**os.environ, "PYTHONPATH": str(src)}
        run = [sys.executable, "-m", "dryfriction.cli", "simulate", str(PROTOCOL), "--json",
               "--no-figure", "--out"]
        warm = _run([sys.executable, "-m", "dryfriction.warm"], tmp, env)
        first = _run([*run, "first"], tmp, env)
        second = _run([*run, "second"], tmp, env)
    return {"warm-up (make)": warm, "first run": first, "second run": second}


def main(first_run: bool = False) -> None:
    load = os.getloadavg()[0]
    med = whole_process()
    print(f"whole process, warm cache, median of 9 interleaved runs "
          f"(load average {load:.2f} -> {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores):")
    print(f"  {'':22s} {'wall':>7s} {'CPU':>7s} {'target':>7s}")
    for name, (wall, cpu) in med.items():
        goal = f"<= {TARGETS[name]:g} s" if name in TARGETS else ""
        print(f"  {name:22s} {wall:6.3f}s {cpu:6.3f}s   {goal}")
    fig, nofig = med["simulate (figure)"][0], med["simulate --no-figure"][0]
    for ref, t in REFERENCE.items():
        print(f"  {ref} (issue's figure, {t} s): with figure x{t / fig:.2f}, without "
              f"x{t / nofig:.2f} (wall; > 1: dryfriction faster)")
    ours = med["simulate --no-figure"][1]
    peer = RSFMODEL_RUN if RSFMODEL_RUN in med else RSFMODEL_FLOOR
    what = ("its whole velocity step" if peer == RSFMODEL_RUN else
            "a floor under its run; set RSFMODEL_PYTHON to run the step itself")
    ratio = ours / med[peer][1]
    print(f"  simulate --no-figure / {peer} ({what}), CPU: x{ratio:.2f} "
          f"(goal <= {CPU_RATIO_GOAL}: {'met' if ratio <= CPU_RATIO_GOAL else 'NOT met'})")
    if first_run:
        print("first run after install (fresh copy, no Numba cache):")
        for name, (wall, cpu) in first_run_after_install().items():
            print(f"  {name:22s} {wall:6.3f}s {cpu:6.3f}s")


if __name__ == "__main__":
    main(first_run="--first-run" in sys.argv)
