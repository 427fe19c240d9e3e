"""Speed of the extended interface (issue 29): trap updates per second, cost against the number
of blocks (N = 32, 64, 128, 256 and the fitted exponent), one thread against two, and the
stick-slip run dynamic against event-driven (``quasi_static_rate``).

Run ``python benchmarks/bench_interface.py [--full | --bounds | --multirate | --scale]``
(``--full``: N up to 1024, the multirate cost against N and the issue's scale, N = 256 blocks
of about 200 contacts through 20 system-spanning events, event-driven and multirate;
``--bounds``: only where the steps of the stick-slip runs go, :func:`step_bounds`;
``--multirate``: only the cost against N of the stick-slip run with both savings,
:func:`multirate_cost`; ``--scale``: only the issue's scale, printing its progress).
A trap update is one pair of a block's contact window processed in one step (the pairs in
contact and the free ones between them).
Uniform steady sliding at ``u = 1`` of blocks with 100 pairs per ``a0`` (about 250 pairs in
each window), ``k_c = 1``, ``m = 1``: the step is the slip limit ``1/(4 lambda)``, so every
run of the same duration takes the same steps and the cost per step should grow linearly with
``N``. The thread comparison runs 1 and 2 threads alternately (the machine may be shared: the
load average is printed with every line, and the median of the alternating runs is compared).
"""

from __future__ import annotations

import math
import os
import statistics
import sys

import numpy as np

from dryfriction.ensemble.interface import (
    QUASI_STATIC_RATE,
    InterfaceDrive,
    InterfaceModel,
    simulate_interface,
)
from dryfriction.ensemble.population import Initial, Track
from dryfriction.ensemble.result import Output
from dryfriction.program import Segment, VelocityProgram
from dryfriction.theory.model import TrapModel


def run(n: int, duration: float, threads: int, lam: float = 100.0) -> dict[str, float]:
    """One run: ``N`` blocks in uniform steady sliding at ``u = 1`` for ``duration`` t0."""
    r = simulate_interface(
        InterfaceModel(TrapModel(eps=0.04), n, 1.0, 1.0, 0.1),
        InterfaceDrive("uniform", 0.5, VelocityProgram([Segment(1.0, duration=duration)])),
        Initial("steady", velocity=1.0, track=Track(lam, "random", seed=1)),
        Output(every=duration / 4), velocity=1.0, threads=threads)
    info = r.info
    return {"steps": info["steps"], "updates": info["trap_updates"], "wall": info["wall_s"],
            "cpu": info["cpu_s"], "threads": info["threads"]}


def _load() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load {one:.1f} {five:.1f} {fifteen:.1f}"


def cost_against_n(sizes: tuple[int, ...], duration: float) -> None:
    """CPU microseconds per step and per block, and trap updates per CPU second, one
    thread (CPU time, not wall: the machine may be shared)."""
    run(2, 0.1, 1)  # load the compiled kernel
    print(f"cost against N (one thread, {duration:g} t0 of sliding, 100 pairs/a0)")
    print(f"{'N':>6} {'steps':>7} {'updates':>10} {'wall s':>8} {'cpu s':>7} "
          f"{'us/step/block':>14} {'updates/cpu-s':>13}")
    per_step = []
    for n in sizes:
        r = run(n, duration, 1)
        per = r["cpu"] / r["steps"] / n * 1e6  # CPU time: the machine may be shared
        per_step.append(r["cpu"] / r["steps"])
        print(f"{n:>6} {r['steps']:>7.0f} {r['updates']:>10.3g} {r['wall']:>8.2f} "
              f"{r['cpu']:>7.2f} {per:>14.2f} {r['updates'] / r['cpu']:>13.3g}   {_load()}")
    # the cost of a step against N: CPU s per step ~ N^p, p by least squares in logs (ours)
    p = float(np.polyfit(np.log(sizes), np.log(per_step), 1)[0])
    print(f"  CPU time per step grows as N^{p:.2f} (linear: 1) from N = {sizes[0]} to "
          f"{sizes[-1]}")


def threads(n: int, duration: float, repeats: int) -> None:
    """One thread against two, alternately, the medians compared."""
    run(n, 0.1, 2)
    walls: dict[int, list[float]] = {1: [], 2: []}
    print(f"threads: N = {n}, {duration:g} t0, {repeats} alternating runs each")
    for _ in range(repeats):
        for th in (1, 2):
            r = run(n, duration, th)
            walls[th].append(r["wall"])
            print(f"  threads={r['threads']:.0f} wall {r['wall']:.2f} s, "
                  f"{r['updates'] / r['wall']:.3g} updates/s   {_load()}")
    m1, m2 = statistics.median(walls[1]), statistics.median(walls[2])
    print(f"  median one thread {m1:.2f} s, two threads {m2:.2f} s: speed-up {m1 / m2:.2f}x")


class _Spanning:
    """System-spanning events counted as the samples come (the rule of
    :func:`spanning_events`): an event is a run of samples with some block above ``threshold``,
    system-spanning when every block was above it in one of them; a progress line every
    ``every_s`` seconds of wall time (events, time simulated, wall and CPU so far, load)."""

    def __init__(self, threshold: float, every_s: float, target: int | None = None) -> None:
        self.threshold = threshold
        self.every_s = every_s
        self.target = target
        self.spanning = 0
        self.events = 0
        self.covered: np.ndarray | None = None
        self.last = -math.inf

    def __call__(self, t: float, rate: np.ndarray, info: dict[str, float]) -> None:
        fast = rate > self.threshold
        if fast.any():
            if self.covered is None:
                self.covered = fast.copy()
                self.events += 1
            else:
                self.covered |= fast
        elif self.covered is not None:
            self.spanning += int(self.covered.all())
            self.covered = None
        if info["wall_s"] - self.last >= self.every_s:
            self.last = info["wall_s"]
            print(f"  t {t:9.1f} t0: {self.events} events, {self.spanning} system-spanning, "
                  f"{info['steps']:.4g} steps, {info['trap_updates']:.3g} trap updates, wall "
                  f"{info['wall_s']:.0f} s, CPU {info['cpu_s']:.0f} s   {_load()}", flush=True)
        if self.target is not None and self.spanning >= self.target:
            raise KeyboardInterrupt  # enough events: the run returns its samples so far

    def close(self) -> int:
        """System-spanning events, an event still running at the end counted if spanning."""
        return self.spanning + int(self.covered is not None and bool(self.covered.all()))


def spanning_events(n: int, slip: float, threads: int | None = None, rate: float = 0.0,
                    lam: float = 100.0, multirate: bool = False, every_s: float = 30.0,
                    target: int | None = None) -> dict[str, float]:
    """Stick-slip of the chain under uniform loading (the single slider's inertial example per
    block: ``K_p = 0.05``, ``m = 1``, ``eta = 0.02``, ``V = 0.01``; ``k_c = 1``; ``lam`` pairs
    per a0, about ``2.5 lam`` in a window), dynamic (``rate = 0``) or event-driven
    (``quasi_static_rate = rate``), every window at every step or ``multirate``: the events
    whose fast part (slip rate above ``10 V``) covers every block, and the CPU time per such
    event. Prints a progress line every ``every_s`` s of wall time; with ``target``, stops at
    that many system-spanning events (the plate's travel ``slip`` then an upper bound)."""
    V = 0.01
    count = _Spanning(10.0 * V, every_s, target)
    print(f"events: N = {n}, {lam:g} pairs/a0, up to {slip:g} a0 of plate travel, "
          f"quasi_static_rate {rate:g} a0/t0, multirate {multirate}", flush=True)
    r = simulate_interface(
        InterfaceModel(TrapModel(eps=0.04), n, 1.0, 1.0, 0.02, quasi_static_rate=rate,
                       multirate=multirate),
        InterfaceDrive("uniform", 0.05, VelocityProgram([Segment(V, slip=slip)])),
        Initial("steady", velocity=V, track=Track(lam, "random", seed=1)),
        Output(every=1.0), threads=threads, progress=count, on_interrupt="partial")
    spanning = count.close()
    wall, cpu = r.info["wall_s"], r.info["cpu_s"]
    quiet = r.info["quasi_static_steps"]
    print(f"events: N = {n}, {lam:g} pairs/a0, {r.t[-1] * V:g} a0 of plate travel, "
          f"quasi_static_rate {rate:g} a0/t0, multirate {multirate}: {count.events} events, "
          f"{spanning} system-spanning, {r.info['steps']} steps "
          f"({quiet} quasi-static, {r.info['handovers']} handovers), "
          f"{r.info['trap_updates']:.3g} trap updates, wall {wall:.1f} s, CPU {cpu:.1f} s "
          f"({cpu / max(spanning, 1):.1f} CPU s per event), threads {r.info['threads']}   "
          f"{_load()}", flush=True)
    return {"events": count.events, "spanning": spanning, "steps": r.info["steps"],
            "updates": r.info["trap_updates"], "wall": wall, "cpu": cpu,
            "travel": float(r.t[-1] * V)}


def multirate_cost(sizes: tuple[int, ...], slip: float, lam: float = 80.0) -> None:
    """Cost of the stick-slip run of :func:`spanning_events` against ``N`` with both savings
    (event-driven at :data:`QUASI_STATIC_RATE`, ``multirate``), one thread, the same plate
    travel: CPU seconds, window updates per block and ``t0``, CPU microseconds per block and
    ``t0``, and the exponent ``p`` of CPU ~ N^p by least squares in logs (linear: 1)."""
    print(f"cost against N, event-driven and multirate (one thread, {slip:g} a0 of plate "
          f"travel, {lam:g} pairs/a0)", flush=True)
    cpus = []
    for n in sizes:
        r = spanning_events(n, slip, threads=1, rate=QUASI_STATIC_RATE, lam=lam,
                            multirate=True, every_s=1e9)
        span = r["travel"] / 0.01
        cpus.append(r["cpu"])
        print(f"  N {n:>5}: {r['updates'] / n / span:9.3g} trap updates per block per t0, "
              f"{r['cpu'] / n / span * 1e6:7.2f} CPU us per block per t0, "
              f"{r['spanning']} system-spanning of {r['events']} events", flush=True)
    p = float(np.polyfit(np.log(sizes), np.log(cpus), 1)[0])
    print(f"  CPU time grows as N^{p:.2f} (linear: 1) from N = {sizes[0]} to {sizes[-1]}",
          flush=True)


def step_bounds(n: int, slip: float, lam: float = 100.0) -> None:
    """Where the steps of :func:`spanning_events`' dynamic run go (ours): from slip rates
    sampled every 0.25 t0, the step of each interval ``min(dt_osc, dx_max / max_i |v_i|)``
    (``dx_max = 1/(4 lam)``, the fastest block's slip bound), the share of the steps that the
    slip bound sets, and the block-steps a step of each block's own,
    ``min(dt_osc, dx_max/|v_i|)``, would take against ``N`` times the chain's: a bound on what
    any multirate scheme could save in window updates (they are the cost)."""
    V = 0.01
    r = simulate_interface(
        InterfaceModel(TrapModel(eps=0.04), n, 1.0, 1.0, 0.02),
        InterfaceDrive("uniform", 0.05, VelocityProgram([Segment(V, slip=slip)])),
        Initial("steady", velocity=V, track=Track(lam, "random", seed=1)),
        Output(every=0.25), threads=1)
    dt_osc, dx_max = r.info["dt_max"], 0.25 / lam
    v = np.abs(r.slip_rate[1:])  # the rate at the end of each interval
    dt_block = np.minimum(dt_osc, dx_max / np.maximum(v, 1e-300))
    dt_chain = dt_block.min(axis=1)
    span = np.diff(r.t)
    steps = span / dt_chain
    bounded = dt_chain < dt_osc
    own = float((span[:, None] / dt_block).sum())
    ringing = v.max(axis=1) < 1.0
    print(f"step bounds: N = {n}, {lam:g} pairs/a0, {slip:g} a0: {r.info['steps']} steps "
          f"(estimated {steps.sum():.0f}), dt_osc {dt_osc:.3g} t0, slip-bounded "
          f"{steps[bounded].sum() / steps.sum():.1%} of the steps in "
          f"{span[bounded].sum() / span.sum():.1%} of the time; steps with every block below 1 "
          f"a0/t0 {steps[ringing].sum() / steps.sum():.1%}; each block on its own step: "
          f"{own / (n * steps.sum()):.1%} of the block-steps; CPU {r.info['cpu_s']:.1f} s   "
          f"{_load()}")


def main() -> None:
    full = "--full" in sys.argv  # the scale: N = 256 through >= 20 events (long)
    if "--scale" in sys.argv:  # the scale only: N = 256 x 200 contacts, 20 events
        # one thread unless --threads N (two help only on an idle machine: docs)
        th = int(sys.argv[sys.argv.index("--threads") + 1]) if "--threads" in sys.argv else 1
        spanning_events(256, 400.0, threads=th, rate=QUASI_STATIC_RATE, lam=80.0,
                        multirate=True, target=20)
        return
    if "--multirate" in sys.argv:  # the multirate cost against N (several CPU minutes)
        multirate_cost((32, 64, 128, 256), 30.0)
        return
    if "--bounds" in sys.argv:  # where the steps go, N = 16 and 64 (about a minute of CPU)
        step_bounds(16, 20.0)
        step_bounds(64, 30.0)
        return
    cost_against_n((32, 64, 128, 256, 1024) if full else (32, 64, 128, 256), 2.0)
    threads(256, 2.0, 3 if full else 2)
    # the same run: dynamic, event-driven, event-driven with the windows on their own clocks
    for rate, multirate in ((0.0, False), (QUASI_STATIC_RATE, False), (QUASI_STATIC_RATE, True)):
        spanning_events(64, 30.0, threads=1, rate=rate, multirate=multirate)
    if full:  # N = 256 x about 200 contacts (80 pairs per a0), both savings, 20 events
        multirate_cost((32, 64, 128, 256), 30.0)
        spanning_events(256, 400.0, threads=1, rate=QUASI_STATIC_RATE, lam=80.0,
                        multirate=True, target=20)


if __name__ == "__main__":
    main()
