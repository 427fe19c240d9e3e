"""Coverage of the machine stiffness's 95 % interval (issue 30; the time-lag kernel of
:func:`dryfriction.fit.statistics.time_hac_covariance`).

Per step: the basalt-like records of ``tests/machine_zoo.py`` (3 -> 10 um/s, k = 7000 /m,
10 Hz then 100 Hz, the measured drive), with the generator's red friction noise or with
white noise of the same variance. The record's one machine (``fit.json``'s
``record_stiffness``, the inverse-variance mean of the steps' ``ln k``): the records of
``tests/lab_synth.py`` (1 -> 3 -> 1 um/s, k = 3000 /m) with AR(1) noise (rho = 0.98) or
white. Prints, per kind, how many intervals hold the truth (k, and a, b, Dc, which the
change leaves as they were) and the median ratio of k's standard error to the score-HAC's
(:func:`dryfriction.fit.statistics.hac_covariance`, what k had before).

Run: ``python -m benchmarks bench_k_coverage [SEEDS]`` (default 20 seeds a kind; ~15 min on
one core).
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from dryfriction.fit.steps import fit_steps  # noqa: E402
from dryfriction.records.data import SeriesData  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

KINDS = ("basalt_red", "basalt_white", "lab_red", "lab_white")


def _old_ratio(res: Any) -> list[float]:
    """k's standard error over the score-HAC's (the estimate before the time-lag kernel)."""
    from dryfriction.fit.problem import Problem
    from dryfriction.fit.statistics import hac_covariance
    from dryfriction.fit.steps import step_covariance

    out = []
    for r, d in zip(res.fits, res.data, strict=True):
        sc = step_covariance(r, d)
        names = [s.name for s in sc.specs]
        if "stiffness" not in names:
            continue
        fixed = {p.name: p.value for p in r.parameters if p.fixed}
        prob = Problem(r.fitted_model, [d], list(sc.specs), fixed)
        old = hac_covariance(prob.jacobian(sc.theta), prob.residuals(sc.theta))[0]
        j = names.index("stiffness")
        out.append(float(sc.used.stderr[j] / old.stderr[j]))
    return out


def fit_one(kind: str, seed: int) -> tuple[Any, dict[str, float]]:
    """The fit of one seeded record of ``kind`` (:data:`KINDS`) and its truth."""
    if kind.startswith("basalt"):
        from dryfriction.records import lab
        from machine_zoo import Machine, basalt_like, write_record

        m = Machine() if kind == "basalt_red" else Machine(mu_red=0.0,
                                                          mu_white=math.hypot(5e-4, 6e-4))
        with tempfile.TemporaryDirectory() as tmp:
            lr = lab.read_record(write_record(Path(tmp) / "basalt.txt", basalt_like(seed, m)))
        segs = lab.parse_segments("0:3e-6,68.6:1e-5", lr)
        res = fit_steps(lr, lab.slice_steps(lr, segs), segs, drive="measured")
        return res, {"a": m.a, "b": m.b, "dc": m.dc, "stiffness": m.k}
    from lab_synth import Truth, synth_record

    tr = Truth(rho=0.98 if kind == "lab_red" else 0.0)
    t, v, mu, _ = synth_record(tr, [1e-6, 3e-6, 1e-6], duration_slip=300e-6, dt_per_um=0.5,
                               seed=100 + seed)
    res = fit_steps(SeriesData(t, v, mu, source=f"{kind} {seed}"))
    return res, {"a": tr.a, "b": tr.b, "dc": tr.dc, "stiffness": tr.stiffness}


def coverage(kind: str, seeds: range) -> dict[str, Any]:
    """Intervals holding the truth over ``seeds``: per step (k, a, b, dc) and the record's
    one machine (``record``), with the totals, and k's standard-error ratio to the old
    estimate."""
    hits = dict.fromkeys(("stiffness", "a", "b", "dc", "record"), 0)
    steps = records = 0
    ratios: list[float] = []
    for seed in seeds:
        res, truth = fit_one(kind, seed)
        for row in res.rows:
            steps += 1
            for p in ("a", "b", "dc", "stiffness"):
                hits[p] += bool(row[f"{p}_lo"] <= truth[p] <= row[f"{p}_hi"])
        if res.stiffness is not None:
            records += 1
            hits["record"] += bool(res.stiffness["lo"] <= truth["stiffness"]
                                   <= res.stiffness["hi"])
        ratios += _old_ratio(res)
    return {"hits": hits, "steps": steps, "records": records,
            "ratio_to_old": float(np.median(ratios)) if ratios else math.nan}


def main() -> None:
    n = int(sys.argv[-1]) if sys.argv[-1].isdigit() else 20
    for kind in KINDS:
        t0 = time.process_time()
        c = coverage(kind, range(n))
        h, s = c["hits"], c["steps"]
        line = (f"{kind:12s}: k {h['stiffness']}/{s}, a {h['a']}/{s}, b {h['b']}/{s}, "
                f"Dc {h['dc']}/{s}")
        if c["records"]:
            line += f"; record's k {h['record']}/{c['records']}"
        print(line + f"; k's se / score-HAC's (median) {c['ratio_to_old']:.2f}  "
              f"({time.process_time() - t0:.0f} s CPU)", flush=True)


if __name__ == "__main__":
    main()
