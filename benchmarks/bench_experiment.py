"""A whole experiment in one command (issue 23 item 4): where the time of
``dryfriction fit RECORD --model rsf --out DIR`` goes on a 20-step record.

The record is the generated experiment of the tests (``tests/experiment_zoo.py``, seed 1): 1 ->
3 -> 10 -> 30 -> 100 -> 300 -> 10 um/s at 10, 20 and 30 MPa with a 30-s slide-hold-slide at
each level (20 velocity steps, 3 holds, 23 windows, 30,690 rows). Goal: the whole process in
<= 20 s. Printed: the whole process (a subprocess, CPU from ``getrusage`` and wall), then its
parts in-process (CPU time): reading and detection, the fits (HAC intervals, the default for
more than ``PROFILE_MAX_STEPS`` windows), the profiles that ``--profile`` adds, the figures
(the step figures each new, then as the command draws them: one figure redrawn step after
step).

Run: ``python -m benchmarks bench_experiment``.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))


def _whole(path: Path, out: Path, *extra: str) -> tuple[float, float]:
    exe = Path(sys.executable).with_name("dryfriction")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    w0 = time.perf_counter()
    subprocess.run([str(exe), "fit", str(path), "--model", "rsf", "--out", str(out), *extra],
                   check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    return cpu, time.perf_counter() - w0


def main() -> None:
    from dryfriction.fit.steps import fit_steps
    from dryfriction.plots.record import plot_record
    from dryfriction.plots.steps import plot_step, plot_steps_summary
    from dryfriction.plots.style import save_figure
    from dryfriction.records import lab
    from experiment_zoo import make_experiment
    from records_zoo import write

    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        path = write(make_experiment(1), folder)
        for extra in ((), ("--profile",)):
            cpu, wall = _whole(path, folder / f"out{len(extra)}", *extra)
            print(f"whole process {' '.join(extra) or '(default)':>10}: {cpu:6.2f} s CPU, "
                  f"{wall:6.2f} s wall  (goal <= 20 s)")
        c = time.process_time()
        rec = lab.read_record(path)
        det = lab.detect_program(rec)
        wins = lab.slice_steps(rec, det.segments)
        print(f"  read + detect ({len(rec)} rows, {len(wins)} windows): "
              f"{time.process_time() - c:6.2f} s CPU")
        c = time.process_time()
        res = fit_steps(rec, wins, det.segments)
        print(f"  fits (HAC intervals):          {time.process_time() - c:6.2f} s CPU")
        c = time.process_time()
        fit_steps(rec, wins, det.segments, profile=True)
        print(f"  fits with --profile:           {time.process_time() - c:6.2f} s CPU")
        c = time.process_time()
        for i in range(len(res.rows)):
            save_figure(plot_step(res, i)[0], folder / f"step_{i}.png", "png", None)
        print(f"  {len(res.rows)} step figures, each new:      {time.process_time() - c:6.2f} s "
              "CPU")
        c = time.process_time()
        drawn = None
        for i in range(len(res.rows)):  # as the fit command draws them: one figure redrawn
            drawn = plot_step(res, i, into=drawn)[0]
            save_figure(drawn, folder / f"step_{i}.png", "png", None)
        print(f"  {len(res.rows)} step figures, one redrawn:   {time.process_time() - c:6.2f} s "
              "CPU")
        c = time.process_time()
        save_figure(plot_record(rec, det.segments, det, given=False)[0], folder / "r.png",
                    "png", None)
        save_figure(plot_steps_summary(res)[0], folder / "s.png", "png", None)
        print(f"  record.png + steps_summary.png: {time.process_time() - c:6.2f} s CPU")


if __name__ == "__main__":
    main()
