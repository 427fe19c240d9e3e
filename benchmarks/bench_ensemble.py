"""Speed of the trap ensemble (issue 3): trap updates per second and a steady-sliding run.

Run ``python benchmarks/bench_ensemble.py``. Single thread (the kernel is not parallel), so the
rates are per core. A trap update is one active trap (in contact) processed in one step;
free pairs in the window are not counted.

Issue 11 (the direct effect): :func:`drive_rate` measures whole runs of the velocity,
quasi-static spring and inertial drives with ``direct = 0`` and ``> 0``, counting every kernel
pass (committed steps, and the probes of the quasi-static force balance apart) per CPU second.
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
    args = (TrapModel(eps=0.04), VelocityDrive(VelocityProgram([{"velocity": 1.0, "slip": slip}])),
            Initial("steady", velocity=1.0, track=Track(lam)), Output(every_slip=every_slip))
    simulate(args[0], VelocityDrive(VelocityProgram([{"velocity": 1.0, "slip": 0.01}])),
             *args[2:])  # warm up
    t0 = time.perf_counter()
    r = simulate(*args)
    return time.perf_counter() - t0, len(r.t), float(np.mean(r.n_active))


class _Counter:
    """Counts the active traps of every kernel pass of :class:`Ensemble` (committed steps and
    probes apart) while installed: the benchmark's own accounting, not the library's."""

    def __init__(self) -> None:
        self.committed = 0
        self.probed = 0
        self._saved = (Ensemble.advance, Ensemble.probe)

    def __enter__(self) -> _Counter:
        advance, probe = self._saved

        def counted_advance(ens: Ensemble, x1: float, t1: float):  # type: ignore[no-untyped-def]
            o = advance(ens, x1, t1)
            self.committed += o.n_active
            return o

        def counted_probe(ens: Ensemble, x1: float, direction=None,  # type: ignore[no-untyped-def]
                          **kwargs):
            o = probe(ens, x1, direction, **kwargs)
            self.probed += o.n_active
            return o

        Ensemble.advance, Ensemble.probe = counted_advance, counted_probe  # type: ignore
        return self

    def __exit__(self, *exc: object) -> None:
        Ensemble.advance, Ensemble.probe = self._saved  # type: ignore[method-assign]


def drive_rate(kind: str, direct: float, lam: float = 10000.0, slip: float = 0.2
               ) -> tuple[float, float, float]:
    """Trap updates per second of a whole ``simulate`` run at u = 1 from steady sliding
    (issue 11): ``kind`` is "velocity" (sampled every 1e-4 a0, one step a sample),
    "quasi-static" (spring K = 200, mass 0: with ``direct > 0`` each creep step solves the
    force balance by probes) or "inertial" (K = 1, M = 1, steps of a quarter trap spacing).

    Returns (committed active-trap updates per CPU second, all updates per CPU second probes
    included, wall s): CPU time, as the machine is shared; the updates are counted per kernel
    pass (:class:`_Counter`)."""
    prog = VelocityProgram([{"velocity": 1.0, "slip": slip}])
    drive = {"velocity": VelocityDrive(prog), "quasi-static": SpringDrive(200.0, 0.0, prog),
             "inertial": SpringDrive(1.0, 1.0, prog)}[kind]
    model = TrapModel(eps=0.04, direct=direct)
    initial = Initial("steady", velocity=1.0, track=Track(lam))
    simulate(model, drive, initial, Output(every_slip=0.5))  # warm up (compiled code, caches)
    with _Counter() as c:
        t0, c0 = time.perf_counter(), time.process_time()
        simulate(model, drive, initial, Output(every_slip=1e-4))
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return c.committed / cpu, (c.committed + c.probed) / cpu, wall


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
    print(f"load average {os.getloadavg()[0]:.2f} (shared machine: rates scale down with it)")
    for kind in ("velocity", "quasi-static", "inertial"):
        for direct in (0.0, 0.01):
            done, every, wall = drive_rate(kind, direct)
            print(f"simulate, {kind:>12} drive, direct = {direct:<4g}, lambda = 10000/a0: "
                  f"{done:.3g} committed active-trap updates per CPU s, {every:.3g} with the "
                  f"probes ({wall:.2f} s wall; goal 4e7 with direct > 0)")
    print(f"load average {os.getloadavg()[0]:.2f}")

if __name__ == "__main__":
    main()
