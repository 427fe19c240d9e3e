"""The trap model on one basalt-like step (issue 30): CPU time of the step and where it goes.

Goal on one core: one step of ``dryfriction fit RECORD --model rsf --run-cv --direct 0.03``
(the trap model with the direct effect: its fit, the engine's covariance, the robust (HAC)
covariance and the figure's curve) in <= 60 s CPU; it was 445 s on the held-out basalt step.
The step is :func:`basalt_step.basalt_step` (3 -> 10 um/s, 10 Hz then 100 Hz, a window of
10166 samples, from an independent rate-and-state model).

Prints: the step's CPU time, model evaluations and forward runs by stage (the evaluations
that the memory of :mod:`dryfriction.fit.cvseries` answered cost no run), the CPU of one
forward run and what it spends it on (cProfile: the compiled kernel, the Python around it,
the force balance of the creep steps, placing the initial populations, reading the series at
the data's times), and the share of the window's load-point travel that is simulated (the
rest is steady tails, :mod:`dryfriction.fit.cvtail`). With ``--slow`` also one forward run
the way it was before (whole window simulated): its CPU and the rms difference of the two
series.

Run: ``python -m benchmarks bench_cv_step`` (about a minute of CPU) or
``python benchmarks/bench_cv_step.py --slow``.
"""

from __future__ import annotations

import cProfile
import os
import pstats
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import numpy as np  # noqa: E402

import dryfriction.fit.cvseries as cvseries  # noqa: E402
import dryfriction.fit.cvtail as cvtail  # noqa: E402
from basalt_step import basalt_step  # noqa: E402
from dryfriction.fit.cvsteps import fit_cv_steps, record_cv_model  # noqa: E402
from dryfriction.fit.steps import fit_steps, step_covariance  # noqa: E402
from dryfriction.records import lab  # noqa: E402
from dryfriction.theory.model import TrapModel  # noqa: E402

DIRECT = 0.03

# cProfile's functions, by what they do (a function counted once, by its own time)
PARTS = {
    "compiled kernel (advance_window)": ("advance_window",),
    "Python around each kernel call": ("_call", "_ensure_cover", "_ensure_ages", "probe",
                                       "observe", "advance", "__init__"),
    "force balance of the creep steps": ("equilibrate", "root_in_bracket", "balance",
                                         "<lambda>", "strength_ratio", "strength_slope",
                                         "__call__", "slope", "velocity_scale", "eff"),
    "placing initial populations": ("_place_initial", "positions", "radius"),
    "reading at the data's times (interp)": ("interp",),
}


def _breakdown(stats: pstats.Stats) -> dict[str, float]:
    out = dict.fromkeys(PARTS, 0.0)
    out["other"] = 0.0
    for (_, _, name), (_, _, tottime, _, _) in stats.stats.items():  # type: ignore[attr-defined]
        part = next((p for p, names in PARTS.items() if name in names), "other")
        out[part] += tottime
    return out


def main() -> None:
    slow = "--slow" in sys.argv
    with tempfile.TemporaryDirectory() as tmp:
        rec = lab.read_record(basalt_step(Path(tmp) / "basalt_like.txt"))
    segs = lab.detect_program(rec).segments
    wins = lab.slice_steps(rec, segs)
    res = fit_steps(rec, wins, segs, profile=False)
    d, r = res.data[0], res.fits[0]
    runs, simulated = [0], [0]
    series = cvtail.spring_series

    def tick() -> None:
        runs[0] += 1

    def counted_series(*args, **kwargs):  # type: ignore[no-untyped-def]
        simulated[0] += 1
        return series(*args, **kwargs)

    cvtail.spring_series = counted_series  # type: ignore[assignment]

    cvseries._LAST.clear()
    stages: list[tuple[str, float, int, int]] = []
    c0 = time.process_time()
    alt = fit_cv_steps([d], [r], record_cv_model(TrapModel(0.13, creep="log", direct=DIRECT),
                                                 progress=tick))[0]
    stages.append(("fit (search and engine covariance)", time.process_time() - c0, runs[0],
                   simulated[0]))
    c1, n1, s1 = time.process_time(), runs[0], simulated[0]
    step_covariance(alt, d, "hac")
    stages.append(("robust (HAC) covariance", time.process_time() - c1, runs[0] - n1,
                   simulated[0] - s1))
    c2, n2, s2 = time.process_time(), runs[0], simulated[0]
    alt.predict(d)
    stages.append(("figure's curve", time.process_time() - c2, runs[0] - n2,
                   simulated[0] - s2))
    total = time.process_time() - c0
    cvtail.spring_series = series  # type: ignore[assignment]
    print(f"basalt-like step, {len(d.t)} samples, trap model with the direct effect: "
          f"{total:.1f} s CPU for the step (goal <= 60; 445 s on the basalt step before)")
    for name, cpu, n, ran in stages:
        print(f"  {name}: {cpu:.1f} s, {n} model evaluations, {ran} of them run (the rest "
              "from the memory of runs)")
    rms = alt.per_dataset[0]["rms_residual"]
    print(f"  fit: success {alt.success} ({alt.message}); rms {rms:.3g}"
          f" (rsf {r.per_dataset[0]['rms_residual']:.3g}); "
          + ", ".join(f"{p.name} = {p.value:.4g}" for p in alt.parameters))

    # one forward run at the optimum, profiled
    vals = {p.name: p.value for p in alt.parameters}
    model = record_cv_model(TrapModel(0.13, creep="log", direct=DIRECT))
    cvseries._LAST.clear()
    travel = [0.0]
    chunk = cvtail.continue_spring

    def counted(*args, **kwargs):  # type: ignore[no-untyped-def]
        out = chunk(*args, **kwargs)
        travel[0] += float(out.x_pull[-1] - out.x_pull[0])
        return out

    cvtail.continue_spring = counted  # type: ignore[assignment]
    c3 = time.process_time()
    model.predict(vals, d)
    one = time.process_time() - c3
    cvtail.continue_spring = chunk  # type: ignore[assignment]
    window = float(np.sum(np.diff(d.t) * d.v_load[1:])) / vals["a0"]
    cvseries._LAST.clear()
    prof = cProfile.Profile()
    prof.enable()
    model.predict(vals, d)
    prof.disable()
    parts = _breakdown(pstats.Stats(prof))
    whole = sum(parts.values())
    print(f"one forward run at the optimum: {one:.2f} s CPU, {travel[0]:.1f} of the window's "
          f"{window:.1f} a0 of load-point travel simulated (the rest: steady tails); under "
          "cProfile, by share:")
    for name, sec in sorted(parts.items(), key=lambda kv: -kv[1]):
        print(f"  {name}: {100 * sec / whole:.0f} %")
    if slow:
        import dataclasses

        old = dataclasses.replace(model, steady_tail=False)
        cvseries._LAST.clear()
        c4 = time.process_time()
        mu_old = old.predict(vals, d)
        t_old = time.process_time() - c4
        mu_new = model.predict(vals, d)
        print(f"the whole window simulated: {t_old:.2f} s CPU a run ({t_old / one:.1f}x); "
              f"rms difference of the series {np.sqrt(np.mean((mu_new - mu_old) ** 2)):.2g}")


if __name__ == "__main__":
    main()
