"""Wall time of a 32-point sweep with 1 and with 2 Dask workers (goal: >= 1.6x, issue 12).

Two sweeps of 32 points. ``light``: each point is a linear-stability analysis with a fine
frequency scan (compute bound, 0.1-0.2 s), so the cluster's start weighs as much as a fifth of
a one-worker run and bounds the speed-up. ``stick-slip``: the points of the phase diagram
(``examples/phase_diagram.toml``, the stick-slip simulation ``dryfriction sweep`` runs by
default, 0.6-0.9 s a point) over 4 stiffnesses and 8 velocities: a sweep worth running on
several workers. Every sweep runs in a
fresh process, as a user's command does: the times include the cluster's start (the workers'
imports) and its stop, and no run profits from modules an earlier one imported. The two
worker counts alternate (``--repeat`` rounds, median and best shown), and the CPU time of each
run (its process and every worker) and the load average are printed: on a shared machine the
wall times measure the other users too. The phases (medians) say where a sweep's time goes: to
the first finished point (the cluster's start and one point), from the first to the last, and
after the last (the cluster's stop, the Dataset and ``sweep.nc``). Run:
``python -m benchmarks bench_sweep``, or ``python -m benchmarks.bench_sweep --repeat 5
--case light``.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path
from typing import Any

from dryfriction.sweeps.sweep import parse_sweep, run_sweep
from dryfriction.theory.linear_stability import critical_stiffness
from dryfriction.theory.model import TrapModel

ROOT = Path(__file__).resolve().parents[1]


def heavy_point(protocol: dict) -> dict[str, float]:  # type: ignore[type-arg]
    d = protocol["drive"]
    res = critical_stiffness(d["velocity"], TrapModel(eps=protocol["model"]["eps"]),
                             damping=d["damping"], n_omega=60000)
    return {"K_c": res.critical_stiffness}


PROTO = {
    "model": {"eps": 0.04},
    "drive": {"velocity": 0.1, "damping": 0.05},
    "sweep": {"drive.velocity": {"log": [0.01, 1.0, 4]}, "model.eps": {"lin": [0.02, 0.05, 8]}},
}


def _phase_protocol() -> dict[str, Any]:
    """The phase-diagram example over a 4 x 8 grid of stiffness and pulling velocity."""
    proto = tomllib.loads((ROOT / "examples" / "phase_diagram.toml").read_text())
    proto["sweep"] = {"drive.stiffness": {"lin": [0.025, 0.1, 4]},
                      "drive.segments.0.velocity": {"log": [0.01, 1.0, 8]}}
    return proto


def _stick_slip_case() -> tuple[dict[str, Any], Any]:
    # imported here, not with this module: the fork server imports this module (the light
    # sweep's runner lives here), and the stick-slip modules would lengthen its start
    from dryfriction.analysis.stickslip import stick_slip_summary

    return _phase_protocol(), stick_slip_summary


CASES = {"light": lambda: (PROTO, heavy_point), "stick-slip": _stick_slip_case}
"""name: () -> (protocol, runner); the stick-slip runner is the package's own (its module is
what the fork server imports, as for ``dryfriction sweep``)."""


def one_sweep(n_workers: int, case: str = "light") -> None:
    """Run the sweep once in this process and print its wall time and its phases (the child's
    side): seconds to the first finished point (the cluster's start, one point), from the
    first to the last finished point, and after the last one (the cluster's stop, the
    Dataset, ``sweep.nc``)."""
    protocol, runner = CASES[case]()
    spec = parse_sweep(protocol)
    finished: list[float] = []

    def progress(done: int, total: int) -> None:
        finished.append(time.perf_counter())  # the first call comes before any point runs

    with tempfile.TemporaryDirectory() as tmp:
        t = time.perf_counter()
        run_sweep(spec, runner, f"{tmp}/out", n_workers=n_workers, progress=progress)
        end = time.perf_counter()
    print(f"{finished[1] - t:.4f} {finished[-1] - finished[1]:.4f} {end - finished[-1]:.4f}")
    print(f"{end - t:.4f}")


def _cpu_of_children() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed_run(n_workers: int, case: str = "light") -> tuple[float, float, float,
                                                          tuple[float, ...]]:
    """(sweep wall, whole process wall, CPU of the process and its workers, phases of the
    sweep as :func:`one_sweep` prints them) of one run."""
    cpu = _cpu_of_children()
    t = time.perf_counter()
    # heavy_point must live in an importable module (not __main__): the workers import it
    code = f"from benchmarks.bench_sweep import one_sweep; one_sweep({n_workers}, {case!r})"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       check=True, cwd=ROOT)
    whole = time.perf_counter() - t
    *phases, sweep = (float(x) for x in r.stdout.split()[-4:])
    return sweep, whole, _cpu_of_children() - cpu, tuple(phases)


def main(repeat: int = 3, cases: tuple[str, ...] = tuple(CASES)) -> None:
    for case in cases:
        one_case(case, repeat)


def one_case(case: str, repeat: int) -> None:
    protocol, runner = CASES[case]()
    spec = parse_sweep(protocol)
    load = os.getloadavg()[0]
    runs: dict[int, list[tuple[float, float, float, tuple[float, ...]]]] = {1: [], 2: []}
    for _ in range(repeat):
        for n in runs:
            runs[n].append(timed_run(n, case))
    point = spec.protocol(next(spec.points())[1])
    runner(point)  # a first call pays for touching its arrays' memory the first time
    t = time.perf_counter()
    runner(point)
    per_point = time.perf_counter() - t
    print(f"{case}: {spec.size}-point sweep, each run a fresh process, {repeat} rounds alternating "
          f"(one point ~{per_point:.2f} s in this process, after a first; load average "
          f"{load:.2f} -> "
          f"{os.getloadavg()[0]:.2f} on {os.cpu_count()} cores):")
    med = {}
    for n, rs in runs.items():
        sweep, whole, cpu = (sorted(x) for x in list(zip(*rs, strict=True))[:3])
        first, points, after = (statistics.median(x) for x in zip(*(r[3] for r in rs),
                                                                     strict=True))
        med[n] = statistics.median(sweep)
        print(f"  {n} worker{'s' if n > 1 else ' '}: sweep median {med[n]:.2f} s "
              f"(best {sweep[0]:.2f}), whole process {statistics.median(whole):.2f} s, "
              f"CPU {statistics.median(cpu):.2f} s; to the first point {first:.2f} s, "
              f"first to last {points:.2f} s, after the last {after:.2f} s")
    print(f"  speed-up (medians) {med[1] / med[2]:.2f}x, "
          f"best against best {min(r[0] for r in runs[1]) / min(r[0] for r in runs[2]):.2f}x")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="rounds of (1, 2) workers")
    parser.add_argument("--case", choices=sorted(CASES), action="append",
                        help="the sweep(s) to time (default: all)")
    args = parser.parse_args()
    main(args.repeat, tuple(args.case or CASES))
