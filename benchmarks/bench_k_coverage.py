"""Coverage of the 95 % intervals of a step fit (issue 30: "the coverage tests still hold
(>= 90 % on red-noise records) with k taken from the record"): the time-lag kernel of
:func:`dryfriction.fit.statistics.local_covariance` and the record's ``k``'s error carried
into ``a, b, Dc`` (:func:`dryfriction.fit.statistics.held_parameter_covariance`).

``basalt_*``: the basalt-like records of ``tests/machine_zoo.py`` (3 -> 10 um/s, k = 7000 /m,
10 Hz then 100 Hz, the measured drive), with the generator's red friction noise or with
white noise of the same variance; one step, so ``--stiffness record`` has one estimate of
``k`` and keeps the step's free fit (:mod:`dryfriction.fit.onemachine`). ``lab_*``: the
records of ``tests/lab_synth.py`` (1 -> 3 -> 1 um/s, k = 3000 /m) with AR(1) noise (rho =
0.98) or white, fitted as ``--stiffness record`` does (the record's one machine held in
both steps; ``k``'s interval is then the record's). Prints, per kind and parameter, how many
intervals hold the truth with the Clopper-Pearson 95 % interval of that rate, the mean
width of the intervals in ``ln p``, and the median ratio of a free ``k``'s standard error to
the score HAC's (:func:`dryfriction.fit.statistics.hac_covariance`).

Run: ``python -m benchmarks bench_k_coverage [SEEDS] [KIND ...]`` (default 40 seeds and
every kind; ``SEEDS`` ``N`` or ``A:B``; 330 s of CPU for 40, measured).
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

from dryfriction.fit.onemachine import fit_steps_one_machine  # noqa: E402
from dryfriction.records.data import SeriesData  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

KINDS = ("basalt_red", "basalt_white", "lab_red", "lab_white")


def _old_ratio(res: Any, name: str = "stiffness") -> list[float]:
    """A free parameter's standard error over the score HAC's (the estimate before the
    time-lag kernel), per fit that has it free."""
    from dryfriction.fit.problem import Problem
    from dryfriction.fit.statistics import hac_covariance
    from dryfriction.fit.steps import step_covariance

    out = []
    for r, d in zip(res.fits, res.data, strict=True):
        sc = step_covariance(r, d)
        names = [s.name for s in sc.specs]
        if name not in names:
            continue
        fixed = {p.name: p.value for p in r.parameters if p.fixed}
        prob = Problem(r.fitted_model, [d], list(sc.specs), fixed)
        old = hac_covariance(prob.jacobian(sc.theta), prob.residuals(sc.theta))[0]
        j = names.index(name)
        out.append(float(sc.used.stderr[j] / old.stderr[j]))
    return out


def _score_hac_rows(res: Any) -> list[dict[str, float]]:
    """Per fit, the 95 % Wald intervals of its free a, b, Dc, k from the score HAC alone
    (:func:`dryfriction.fit.statistics.hac_covariance`; what the table gave before the
    time-lag kernel and the held k's error)."""
    from dryfriction.fit.problem import Problem
    from dryfriction.fit.statistics import hac_covariance, quantile_95
    from dryfriction.fit.steps import step_covariance

    out = []
    for r, d in zip(res.fits, res.data, strict=True):
        sc = step_covariance(r, d, "white")
        fixed = {p.name: p.value for p in r.parameters if p.fixed}
        prob = Problem(r.fitted_model, [d], list(sc.specs), fixed)
        se = hac_covariance(prob.jacobian(sc.theta), prob.residuals(sc.theta))[0].stderr
        z = quantile_95(False, sc.dof)
        row = {}
        for j, spec in enumerate(sc.specs):
            row[f"{spec.name}_lo"] = spec.from_internal(sc.theta[j] - z * se[j])
            row[f"{spec.name}_hi"] = spec.from_internal(sc.theta[j] + z * se[j])
        out.append(row)
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
        res = fit_steps_one_machine(lr, lab.slice_steps(lr, segs), segs, drive="measured")
        return res, {"a": m.a, "b": m.b, "dc": m.dc, "stiffness": m.k}
    from lab_synth import Truth, synth_record

    tr = Truth(rho=0.98 if kind == "lab_red" else 0.0)
    t, v, mu, _ = synth_record(tr, [1e-6, 3e-6, 1e-6], duration_slip=300e-6, dt_per_um=0.5,
                               seed=100 + seed)
    res = fit_steps_one_machine(SeriesData(t, v, mu, source=f"{kind} {seed}"))
    return res, {"a": tr.a, "b": tr.b, "dc": tr.dc, "stiffness": tr.stiffness}


def coverage(kind: str, seeds: range) -> dict[str, Any]:
    """Intervals holding the truth over ``seeds``: per step (k, a, b, dc; ``k``'s is the
    record's where the record's one machine is held) and the record's one machine
    (``record``), with the totals, the mean widths ``ln(hi/lo)`` per parameter, and a free
    k's standard-error ratio to the score HAC's."""
    hits = dict.fromkeys(("stiffness", "a", "b", "dc", "record"), 0)
    old = dict.fromkeys(("stiffness", "a", "b", "dc"), 0)
    old_n = dict.fromkeys(("stiffness", "a", "b", "dc"), 0)
    widths: dict[str, list[float]] = {p: [] for p in ("stiffness", "a", "b", "dc")}
    old_w: dict[str, list[float]] = {p: [] for p in ("stiffness", "a", "b", "dc")}
    steps = records = 0
    ratios: list[float] = []
    for seed in seeds:
        res, truth = fit_one(kind, seed)
        for row, prev in zip(res.rows, _score_hac_rows(res), strict=True):
            steps += 1
            for p in ("a", "b", "dc", "stiffness"):
                hits[p] += bool(row[f"{p}_lo"] <= truth[p] <= row[f"{p}_hi"])
                widths[p].append(math.log(row[f"{p}_hi"] / row[f"{p}_lo"]))
                if f"{p}_lo" in prev:
                    old_n[p] += 1
                    old[p] += bool(prev[f"{p}_lo"] <= truth[p] <= prev[f"{p}_hi"])
                    old_w[p].append(math.log(prev[f"{p}_hi"] / prev[f"{p}_lo"]))
        if res.stiffness is not None:
            records += 1
            hits["record"] += bool(res.stiffness["lo"] <= truth["stiffness"]
                                   <= res.stiffness["hi"])
        ratios += _old_ratio(res)
    return {"hits": hits, "steps": steps, "records": records, "score_hac": old,
            "score_hac_n": old_n,
            "width": {p: float(np.mean(w)) for p, w in widths.items()},
            "score_hac_width": {p: float(np.mean(w)) if w else math.nan
                                for p, w in old_w.items()},
            "ratio_to_old": float(np.median(ratios)) if ratios else math.nan}


def rate_interval(k: int, n: int) -> tuple[float, float]:
    """Clopper-Pearson 95 % interval of a rate ``k/n`` (exact binomial; Clopper & Pearson,
    Biometrika 26, 404 (1934))."""
    from scipy import stats

    lo = float(stats.beta.ppf(0.025, k, n - k + 1)) if k > 0 else 0.0
    hi = float(stats.beta.ppf(0.975, k + 1, n - k)) if k < n else 1.0
    return lo, hi


def rate_text(k: int, n: int) -> str:
    """``k/n [lo-hi %]``, the rate with its Clopper-Pearson interval (:func:`rate_interval`)."""
    lo, hi = rate_interval(k, n)
    return f"{k}/{n} [{100 * lo:.0f}-{100 * hi:.0f} %]"


def _seeds(args: list[str]) -> range:
    for a in args:
        if a.isdigit():
            return range(int(a))
        if ":" in a and all(x.isdigit() for x in a.split(":")):
            lo, hi = a.split(":")
            return range(int(lo), int(hi))
    return range(40)


def main() -> None:
    seeds = _seeds(sys.argv[1:])
    kinds = [k for k in KINDS if k in sys.argv[1:]] or list(KINDS)
    for kind in kinds:
        t0 = time.process_time()
        c = coverage(kind, seeds)
        h, s = c["hits"], c["steps"]
        rate = rate_text
        parts = [f"{p} {rate(h[key], s)} width {c['width'][key]:.3f}"
                 for p, key in (("k", "stiffness"), ("a", "a"), ("b", "b"), ("Dc", "dc"))]
        line = f"{kind} seeds {seeds.start}:{seeds.stop}: " + ", ".join(parts)
        if c["records"]:
            line += f"; record's k {rate(h['record'], c['records'])}"
        print(line + f"; free k's se / score-HAC's (median) {c['ratio_to_old']:.2f}  "
              f"({time.process_time() - t0:.0f} s CPU)", flush=True)
        o, on, ow = c["score_hac"], c["score_hac_n"], c["score_hac_width"]
        print("   the score HAC alone (before; a held k exact): " + ", ".join(
            f"{p} {rate(o[key], on[key])} width {ow[key]:.3f}" for p, key in
            (("k", "stiffness"), ("a", "a"), ("b", "b"), ("Dc", "dc")) if ow[key] == ow[key]),
            flush=True)


if __name__ == "__main__":
    main()
