"""Speed of the trap ensemble (issue 3): trap updates per second and a steady-sliding run.

Run ``python benchmarks/bench_ensemble.py``. Single thread (the kernel is not parallel), so the
rates are per core. A trap update is one active trap (in contact) processed in one step;
free pairs in the window are not counted.
"""

from __future__ import annotations

import os
import platform
import time

import numpy as np

from dryfriction.ensemble.driving import Output, SpringDrive, VelocityDrive, simulate
from dryfriction.ensemble.population import Ensemble, Initial, Track, TrapModel
from dryfriction.program import VelocityProgram


def updates_per_second(lam: float, steps: int, eps: float = 0.04, creep: str = "log") -> float:
    """Active-trap updates per second of ``Ensemble.advance`` in steady sliding at u = 1."""
    e = Ensemble(TrapModel(eps=eps, creep=creep), Track(lam), Initial("steady", velocity=1.0),
                 age_horizon=1e3)
    dx = 1e-4
    e.advance(e.x + dx, e.t + dx)  # compile / warm up
    n_active = 0
    t0 = time.perf_counter()
    for _ in range(steps):
        n_active += e.advance(e.x + dx, e.t + dx).n_active
    return n_active / (time.perf_counter() - t0)


def steady_run(lam: float, slip: float, every_slip: float) -> tuple[float, int, float]:
    """Wall time of ``simulate`` for steady sliding at u = 1 (from the steady state)."""
    args = (TrapModel(eps=0.04), Track(lam), Initial("steady", velocity=1.0),
            VelocityDrive(VelocityProgram([{"velocity": 1.0, "slip": slip}])),
            Output(every_slip=every_slip))
    simulate(*args[:3], VelocityDrive(VelocityProgram([{"velocity": 1.0, "slip": 0.01}])),
             args[4])  # warm up
    t0 = time.perf_counter()
    r = simulate(*args)
    return time.perf_counter() - t0, len(r.t), float(np.mean(r.n_active))


def direct_rate(lam: float, slip: float, every_slip: float, direct: float,
                spring: float | None = None) -> float:
    """Active-trap updates per second of a whole ``simulate`` run at u = 1 with the direct
    effect (issue 11): velocity drive, or a quasi-static spring of stiffness ``spring``, where
    each sample solves the force balance (several kernel probes, counted once)."""
    prog = VelocityProgram([{"velocity": 1.0, "slip": slip}])
    drive = VelocityDrive(prog) if spring is None else SpringDrive(spring, 0.0, prog)
    args = (TrapModel(eps=0.04, direct=direct), Track(lam), Initial("steady", velocity=1.0))
    simulate(*args, drive, Output(every_slip=0.5))  # warm up
    t0 = time.perf_counter()
    r = simulate(*args, drive, Output(every_slip=every_slip))
    return float(np.sum(r.n_active[1:])) / (time.perf_counter() - t0)


def main() -> None:
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores "
          f"(single-threaded kernel: rates are per core)")
    for lam, steps in [(1000.0, 20000), (10000.0, 3000), (100000.0, 300)]:
        rate = updates_per_second(lam, steps)
        print(f"log creep, lambda = {lam:>8g}/a0: {rate:.3g} active-trap updates/s "
              f"(goal 5e7)")
    rate = updates_per_second(10000.0, 3000, creep="eyring-nabarro")
    print(f"Eyring-Nabarro (tabulated a_r), lambda = 10000/a0: {rate:.3g} updates/s")
    for every in (1e-2, 1e-3):
        wall, n, act = steady_run(1000.0, 100.0, every)
        print(f"steady sliding 100 a0 at 1000 pairs/a0, u = 1, every_slip = {every:g}: "
              f"{wall:.2f} s wall, {n} samples, {act:.0f} traps in contact on average")
    for direct in (0.0, 0.01):
        rate = direct_rate(10000.0, 2.0, 1e-4, direct)
        print(f"simulate, velocity drive, direct = {direct:g}, lambda = 10000/a0, every_slip = "
              f"1e-4: {rate:.3g} active-trap updates/s (goal 4e7 with direct > 0)")
    rate = direct_rate(10000.0, 0.2, 1e-4, 0.01, spring=200.0)
    print(f"simulate, quasi-static spring K = 200, direct = 0.01, lambda = 10000/a0: {rate:.3g} "
          "committed active-trap updates/s (each step solves the force balance)")


if __name__ == "__main__":
    main()
