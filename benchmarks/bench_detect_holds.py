"""Holds and slow slides under an apparatus' wander: rates of the detection (issue 23).

An independent forward model, apart from the artifact zoo (``tests/records_zoo.py``): from an
outside review of stop 52 (helper-90), which found where two rules for holds under a position
wander read genuine slow slides as holds (the rules were reverted). A piecewise-constant
commanded velocity ``v(t)`` is driven through a servo whose speed wanders by a relative
Ornstein-Uhlenbeck factor (``v (1 + s(t))``, 1-5 %, 3-30 s), integrated to a displacement, and
the load point's position wanders by an OU of 20-300 nm (3-30 s); the transducer adds a drift
of 1-2 um over the record (a random walk or a slow sine), white noise of 0.1-0.2 um, and a
quantum of 20-500 nm; 1-20 Hz. Five program families:

- ``A``: a slow stretch (0.03-0.3 um/s for 10-120 s) between slides of 1-10 um/s, a hold after
  it in half of them;
- ``B``: a down-step of ratio 10-30 for 20-150 s, then a hold of 10-1000 s, then a slide;
- ``C``: a very slow slide (0.01-0.1 um/s for 120-600 s) between slides of 0.3-3 um/s, a hold
  after it in half of them;
- ``D``: slide-hold-slides with one to four holds of 10-1000 s;
- ``E``: steps of ratio 1.3-3 beside holds of 10-300 s;
- ``F``: records mostly at rest: one to three holds of 300-3000 s between slides of 30-200 s,
  at 0.1-30 um/s (log-uniform; from a second review, stop 53, helper-91);
- ``G``: a step of ratio 1.3-30 whose slower side fills the record (800-2500 s beside 40-200
  s at the faster speed; slow then fast, fast then slow, or fast-slow-fast).
- ``H``: a laboratory's slide-hold-slide series, long and sampled fast: holds of 1, 3, 10,
  30, 100, 300, 1000 and 3000 s in order (the first three always, each longer one in
  three of four records), between slides of 50-150 s at 1-30 um/s (log-uniform), sampled
  at 10-200 Hz up to ``MAX_ROWS_H`` rows: blocks of the detector's search last 0.5-2.7 s,
  so its 1-s and 3-s holds are shorter than three of them (``SHORT_SEARCH``).

Each record is written, read back and detected; scored per commanded stretch (1 s trimmed at
each end): a hold is *missed* where less than 90 % of it is reported at velocity 0, a slide is
*read as a hold* where any of it is. Prints, per family: records, holds missed, slides read as
holds, records with the right number of segments.

Run: ``python -m benchmarks bench_detect_holds [FAMILY ...] [N]`` (the families named, default
all; N records per family, default 60; seeds 0 to N - 1, each family's draws from
``default_rng(1000003 * ord(family) + seed)``).
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from dryfriction.records.lab import detect_program, read_record  # noqa: E402

UM = 1e-6
FAMILIES = ("A", "B", "C", "D", "E", "F", "G", "H")
MAX_ROWS = 25_000  # a long program is sampled slower, not cut
MAX_ROWS_H = 400_000  # family H: a long record sampled fast, as laboratories record one


def _ou(rng: np.random.Generator, n: int, dt: float, tau: float, sd: float) -> np.ndarray:
    """A stationary Ornstein-Uhlenbeck series of ``n`` samples ``dt`` apart (rms ``sd``)."""
    a = np.exp(-dt / tau)
    kicks = rng.normal(0.0, sd * np.sqrt(1.0 - a * a), n)
    out = np.empty(n)
    out[0] = rng.normal(0.0, sd)
    for i in range(1, n):
        out[i] = a * out[i - 1] + kicks[i]
    return out


def _log_uniform(r: np.random.Generator, lo: float, hi: float) -> float:
    """One draw, uniform in ``log`` between ``lo`` and ``hi``."""
    return float(np.exp(r.uniform(np.log(lo), np.log(hi))))


def program(family: str, r: np.random.Generator) -> list[tuple[float, float]]:
    """The commanded program of a family: (duration s, velocity m/s) of each stretch."""
    if family == "A":
        v1, vs = float(r.choice([1, 3, 10])) * UM, float(r.choice([0.03, 0.1, 0.3])) * UM
        p = [(100.0, v1), (float(r.choice([10, 20, 40, 60, 120])), vs), (100.0, v1)]
        return p + ([(float(r.choice([30, 100, 300])), 0.0), (80.0, v1)] if r.random() < 0.5
                    else [])
    if family == "B":
        v1, ratio = float(r.choice([1, 3, 10])) * UM, float(r.uniform(10, 30))
        return [(100.0, v1), (float(r.choice([20, 40, 80, 150])), v1 / ratio),
                (float(r.choice([10, 30, 100, 300, 1000])), 0.0), (100.0, v1)]
    if family == "C":
        v1, vs = float(r.choice([0.3, 1, 3])) * UM, float(r.uniform(0.01, 0.1)) * UM
        p = [(80.0, v1), (float(r.choice([120, 240, 400, 600])), vs), (80.0, v1)]
        return p + ([(float(r.choice([30, 100, 300])), 0.0), (80.0, v1)] if r.random() < 0.5
                    else [])
    if family == "D":
        v1 = float(r.choice([1, 3, 10])) * UM
        p = [(float(r.uniform(40, 120)), v1)]
        for _ in range(int(r.integers(1, 5))):
            p += [(float(r.choice([10, 30, 100, 300, 1000])), 0.0), (float(r.uniform(40, 120)), v1)]
        return p
    if family == "E":
        v1, ratio = float(r.choice([0.3, 1, 3, 10])) * UM, float(r.uniform(1.3, 3))
        v2 = v1 * ratio if r.random() < 0.5 else v1 / ratio
        p = [(60.0, v1), (float(r.uniform(20, 80)), v2), (float(r.choice([10, 30, 100, 300])), 0.0),
             (float(r.uniform(20, 80)), v2), (60.0, v1)]
        if r.random() < 0.5:
            p.insert(1, (float(r.choice([10, 30, 100])), 0.0))
        return p
    if family == "F":
        v1 = _log_uniform(r, 0.1, 30.0) * UM
        p = [(float(r.uniform(30, 200)), v1)]
        for _ in range(int(r.integers(1, 4))):
            p += [(_log_uniform(r, 300.0, 3000.0), 0.0),
                  (float(r.uniform(30, 200)), v1)]
        return p
    if family == "G":
        ratio = _log_uniform(r, 1.3, 30.0)
        vs = _log_uniform(r, 0.1, 3.0) * UM
        slow, fast = (float(r.uniform(800, 2500)), vs), (float(r.uniform(40, 200)), vs * ratio)
        kind = int(r.integers(0, 3))
        return [slow, fast] if kind == 0 else [fast, slow] if kind == 1 else [fast, slow, fast]
    if family == "H":
        v1 = _log_uniform(r, 1.0, 30.0) * UM
        p = [(float(r.uniform(50, 150)), v1)]
        for h in (1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0):
            if h <= 10.0 or r.random() < 0.75:
                p += [(h, 0.0), (float(r.uniform(50, 150)), v1)]
        return p
    raise ValueError(f"family = {family!r} is not one of {FAMILIES}")


def record(family: str, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[float]]:
    """Times (s), displacement (m), stretch edges (s) and velocities (m/s) of one record."""
    r = np.random.default_rng(1000003 * ord(family) + seed)
    prog = program(family, r)
    fs = float(r.choice([10, 20, 50, 100, 200] if family == "H" else [1, 2, 4, 5, 10, 20]))
    noise, wander = float(r.uniform(0.1, 0.2)) * UM, float(r.uniform(20, 300)) * 1e-9
    wtau, servo = float(r.uniform(3, 30)), float(r.uniform(0.01, 0.05))
    stau = float(r.uniform(3, 30))
    drift, quant = float(r.uniform(1, 2)) * UM, float(r.choice([20, 50, 100, 200, 500])) * 1e-9
    walk = r.choice(["walk", "sine"]) == "walk"
    total = sum(d for d, _ in prog)
    fs = min(fs, max(1.0, float(int((MAX_ROWS_H if family == "H" else MAX_ROWS) / total))))
    rng = np.random.default_rng(seed)
    dt = 1.0 / fs
    t = np.arange(0.0, total, dt)
    edges = np.cumsum([0.0] + [d for d, _ in prog])
    v = np.asarray([vel for _, vel in prog])[np.clip(np.searchsorted(edges, t, side="right") - 1,
                                                    0, len(prog) - 1)]
    v = v * (1.0 + _ou(rng, t.size, dt, stau, servo))
    x = np.concatenate([[0.0], np.cumsum(v[:-1] * dt)]) + _ou(rng, t.size, dt, wtau, wander)
    if walk:
        w = np.cumsum(rng.normal(0.0, 1.0, t.size))
        x += w / (np.std(w) + 1e-30) * drift / 2.0
    else:
        x += drift / 2.0 * np.sin(2 * np.pi * t / total * rng.uniform(0.5, 1.5)
                                  + rng.uniform(0, 2 * np.pi))
    x = np.round((x + rng.normal(0.0, noise, t.size)) / quant) * quant
    return t, x, edges, [vel for _, vel in prog]


def score(segments: tuple, t: np.ndarray, edges: np.ndarray, vels: list[float]
          ) -> tuple[int, int, int, bool]:
    """(holds, holds missed, slides read as holds, segment count right) of one detection."""
    held = np.zeros(t.size, bool)
    for s in segments:
        if s.velocity == 0.0:
            held[s.i_start:s.i_end] = True
    holds = missed = wrong = 0
    for k, vel in enumerate(vels):
        m = (t >= edges[k] + 1.0) & (t <= edges[k + 1] - 1.0)
        if not m.any():
            continue
        share = float(held[m].mean())
        if vel == 0.0:
            holds += 1
            missed += share < 0.9
        else:
            wrong += share > 0.0
    return holds, missed, wrong, len(segments) == len(vels)


def main() -> None:
    n = int(sys.argv[-1]) if len(sys.argv) > 1 and sys.argv[-1].isdigit() else 60
    chosen = [a for a in sys.argv[1:] if a in FAMILIES] or list(FAMILIES)
    print(f"{'family':8s}{'records':>8s}{'holds missed':>16s}{'slides as holds':>18s}"
          f"{'count right':>13s}")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "rec.txt"
        for fam in chosen:
            holds = missed = wrong = right = 0
            for seed in range(n):
                t, x, edges, vels = record(fam, seed)
                rows = "\n".join(f"{a:.4f}\t{b * 1e3:.9f}\t0.6\t10.0" for a, b in zip(t, x,
                                                                                strict=True))
                path.write_text("Time (s)\tLP_disp (mm)\tmu\tSigma_n (MPa)\n" + rows + "\n")
                h, mi, wr, ok = score(detect_program(read_record(path)).segments, t, edges, vels)
                holds, missed, wrong, right = holds + h, missed + mi, wrong + wr, right + ok
            print(f"{fam:8s}{n:8d}{f'{missed} of {holds}':>16s}{wrong:>18d}"
                  f"{f'{right} of {n}':>13s}", flush=True)


if __name__ == "__main__":
    main()
