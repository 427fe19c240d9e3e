"""Coverage of the joint fit's 95 % intervals (``fit RECORD --joint``): one ``a, b, Dc`` and
stiffness over every step of a record, its covariance the time-lag sandwich with each step's
window its own block (:func:`dryfriction.fit.steps.robust_joint`), against the engine's
white-noise one.

Records of ``tests/lab_synth.py`` (an independent Radau solver of the spring slider with the
ageing law): 1 -> 3 -> 1 -> 3 um/s, 300 um of slip each, k = 3000 /m, with AR(1) friction
noise of lag-1 correlation 0.98 (``red``) or white noise of the same variance (``white``).
Prints, per kind and parameter, how many intervals hold the truth (with the Clopper-Pearson
95 % interval of that rate), robust and white, and the median ratio of the robust standard
error to the white one.

Run: ``python -m benchmarks bench_joint_coverage [SEEDS] [KIND ...]`` (default 40 seeds and
both kinds; ``SEEDS`` ``N`` or ``A:B``; about 2.5 s of CPU per record).
"""

from __future__ import annotations

import math
import os
import sys
import time
from pathlib import Path
from typing import Any

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from benchmarks.bench_k_coverage import _seeds, rate_text  # noqa: E402
from dryfriction.fit.statistics import quantile_95  # noqa: E402
from dryfriction.fit.steps import fit_steps, step_covariance  # noqa: E402
from dryfriction.records.data import SeriesData  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

KINDS = ("red", "white")
NAMES = ("a", "b", "dc", "stiffness")


def fit_one(kind: str, seed: int) -> tuple[Any, dict[str, float]]:
    """The steps' fit with ``--joint`` of one record, and the truth."""
    from lab_synth import Truth, synth_record

    tr = Truth(rho=0.98 if kind == "red" else 0.0)
    t, v, mu, _ = synth_record(tr, [1e-6, 3e-6, 1e-6, 3e-6], duration_slip=300e-6,
                               dt_per_um=0.5, seed=200 + seed)
    res = fit_steps(SeriesData(t, v, mu, source=f"{kind} {seed}"), joint=True)
    return res, {"a": tr.a, "b": tr.b, "dc": tr.dc, "stiffness": tr.stiffness}


def coverage(kind: str, seeds: range) -> dict[str, Any]:
    """Intervals holding the truth over ``seeds``, robust and white, and the ratios."""
    hits = dict.fromkeys(NAMES, 0)
    white = dict.fromkeys(NAMES, 0)
    ratio: dict[str, list[float]] = {n: [] for n in NAMES}
    n = 0
    for seed in seeds:
        res, truth = fit_one(kind, seed)
        sc = step_covariance(res.joint, res.data)  # its white one: the engine's
        z = quantile_95(False, sc.dof)
        n += 1
        for j, spec in enumerate(sc.specs):
            if spec.name not in NAMES:
                continue
            lo, hi = (spec.from_internal(sc.theta[j] + s * z * sc.used.stderr[j])
                      for s in (-1.0, 1.0))
            hits[spec.name] += bool(lo <= truth[spec.name] <= hi)
            lo, hi = (spec.from_internal(sc.theta[j] + s * z * sc.white.stderr[j])
                      for s in (-1.0, 1.0))
            white[spec.name] += bool(lo <= truth[spec.name] <= hi)
            ratio[spec.name].append(sc.inflation(j))
    return {"n": n, "hits": hits, "white": white,
            "ratio": {k: float(np.median(v)) if v else math.nan for k, v in ratio.items()}}


def main() -> None:
    seeds = _seeds(sys.argv[1:])
    kinds = [k for k in KINDS if k in sys.argv[1:]] or list(KINDS)
    for kind in kinds:
        t0 = time.process_time()
        c = coverage(kind, seeds)
        rate = rate_text
        print(f"{kind} seeds {seeds.start}:{seeds.stop}: " + ", ".join(
            f"{p} robust {rate(c['hits'][p], c['n'])} white {rate(c['white'][p], c['n'])} "
            f"se ratio {c['ratio'][p]:.2f}" for p in NAMES)
            + f"  ({time.process_time() - t0:.0f} s CPU)", flush=True)


if __name__ == "__main__":
    main()
