"""The trap model fitted to the shared lab record (issue 11): cost estimate against the fit.

Goal on one core: the sepiolite step (examples/data/lab/sepiolite_velstep_0.2-2um_s.txt)
fitted with the trap model on the rsf fit's machine in <= 5 min CPU, with and without the
direct effect; the CLI's estimate (``app.records.cv_cost``) within a factor 3 of the measured
CPU time. Prints, for A = 0 and A free: forward runs, CPU time, the estimate and their ratio.

Run: ``python -m benchmarks bench_cv_record`` (about 3-5 min CPU).
"""

from __future__ import annotations

import os
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from dryfriction.app.records import cv_cost  # noqa: E402
from dryfriction.fit.cvsteps import fit_cv_steps, record_cv_model  # noqa: E402
from dryfriction.fit.steps import fit_steps, step_data  # noqa: E402
from dryfriction.records import lab  # noqa: E402
from dryfriction.theory.model import TrapModel  # noqa: E402

RECORD = Path(__file__).resolve().parents[1] / "examples/data/lab/sepiolite_velstep_0.2-2um_s.txt"


def main() -> None:
    rec = lab.read_record(RECORD)
    segs = lab.detect_segments(rec)
    wins = lab.slice_steps(rec, segs)
    res = fit_steps(rec, wins, segs, profile=False)
    pieces = step_data(rec, wins, segs)
    runs = [0]

    def tick() -> None:
        runs[0] += 1

    for direct in (0.0, 0.03):
        est = cv_cost(pieces, 0.13, "log", direct)
        runs[0] = 0
        c0 = time.process_time()
        model = record_cv_model(TrapModel(0.13, creep="log", direct=direct), progress=tick)
        r = fit_cv_steps(res.data, res.fits, model)[0]
        dc = time.process_time() - c0
        print(f"A {'free' if direct else '= 0'}: {runs[0]} runs, {dc:6.1f} s CPU (goal <= 300), "
              f"estimate {est:6.1f} s (ratio {est / dc:.2g}, goal 1/3..3), rms "
              f"{r.per_dataset[0]['rms_residual']:.3g}, success {r.success}")


if __name__ == "__main__":
    main()
