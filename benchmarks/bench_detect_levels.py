"""Are the artifact zoo's levels the shared record's? (issue 23)

The relative scatter of a stretch's velocity against the window duration ``T``: least-squares
slopes of adjacent windows of ``T``, the robust spread (1.4826 MAD) of their differences over
sqrt 2, over the velocity (white noise included, not subtracted). On the shared sepiolite
record (``examples/data/lab``: 0.2 um/s, then 2 um/s from sample 16451, 7.35 Hz) and on load
points generated as ``tests/records_zoo.py`` generates them (0.2 and 2 um/s, 7.4 Hz, 1000 s,
the zoo's white noise and quantum; eight seeded draws, median) with its servo position error
alone, its machine oscillation alone, both (what the zoo calibrates on the record: the ratio
to the record's row at the same velocity is printed), both with servo bursts, and the stress
family's velocity random walk (``walk``).

Run: ``python -m benchmarks bench_detect_levels``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import records_zoo as z  # noqa: E402

SHARED = (Path(__file__).resolve().parents[1] / "examples" / "data" / "lab"
          / "sepiolite_velstep_0.2-2um_s.txt")
SCALES = (2.0, 5.0, 10.0, 20.0, 40.0, 80.0)


def relative_scatter(t: np.ndarray, x: np.ndarray, v: float, T: float) -> float:
    """Spread of adjacent windows' slope differences / sqrt 2 / ``v`` (module docstring)."""
    w = np.floor((t - t[0]) / T).astype(int)
    s = []
    for k in range(int(w.max())):
        m = w == k
        if m.sum() >= 3:
            tt = t[m] - t[m].mean()
            s.append(float(tt @ x[m]) / float(tt @ tt))
    d = np.diff(np.asarray(s))
    return 1.4826 * float(np.median(np.abs(d - np.median(d)))) / np.sqrt(2.0) / v


def record_rows() -> dict[float, list[float]]:
    """The shared record's relative slope scatter at :data:`SCALES`, at 0.2 and 2 um/s."""
    d = np.loadtxt(SHARED, skiprows=1)
    t, x = d[:, 0], d[:, 1] * 1e-6
    return {2e-7: [relative_scatter(t[2000:16451], x[2000:16451], 2e-7, T) for T in SCALES],
            2e-6: [relative_scatter(t[16751:], x[16751:], 2e-6, T) for T in SCALES]}


def zoo_row(arts: tuple[str, ...], v0: float, draws: int = 8) -> np.ndarray:
    """The zoo's relative slope scatter at :data:`SCALES` (median of ``draws`` seeded load
    points at ``v0`` m/s, 7.4 Hz, 1000 s, with the artifacts ``arts``)."""
    rng = np.random.default_rng(7)
    res = []
    for _ in range(draws):
        tt = np.arange(0.0, 1000.0, 1 / 7.4)
        eps = np.zeros_like(tt)
        if "walk" in arts:
            eps += z._ou(tt, z.WALK_TAU, z.WALK_RMS, rng)
        if "wobble" in arts:
            for amp, per in z.WOBBLE:
                eps += amp * np.sin(2 * np.pi * tt / per + rng.uniform(0, 2 * np.pi))
        if "bursts" in arts:
            for _b in range(int(rng.integers(3, 9))):
                s, w = float(rng.uniform(0, 1000.0)), float(rng.uniform(0.5, 3.0))
                eps += np.where((tt >= s) & (tt < s + w), rng.choice([-0.12, 0.12]), 0.0)
        vt = v0 * (1 + eps)
        xx = np.concatenate([[0], np.cumsum(0.5 * (vt[1:] + vt[:-1]) * np.diff(tt))])
        if "red" in arts:
            xx += z.servo_error(tt, np.full(tt.size, v0), rng)
        xx = np.round((xx + rng.normal(0, z.WHITE, tt.size)) / z.QUANTUM) * z.QUANTUM
        res.append([relative_scatter(tt, xx, v0, T) for T in SCALES])
    return np.median(res, axis=0)


def main() -> None:
    rows = record_rows()
    head = " ".join(f"{f'T={T:g} s':>8}" for T in SCALES)
    print(f"{'relative slope scatter':<34} {head}")
    for name, v in (("shared record, 0.2 um/s", 2e-7), ("shared record, 2 um/s", 2e-6)):
        print(f"{name:<34} " + " ".join(f"{q:8.3f}" for q in rows[v]))
    worst = 0.0
    for v0, arts in ((2e-6, ()), (2e-6, ("red",)), (2e-6, ("wobble",)),
                     (2e-6, ("red", "wobble")), (2e-6, ("red", "wobble", "bursts")),
                     (2e-6, ("walk", "wobble")), (2e-7, ("red", "wobble"))):
        med = zoo_row(arts, v0)
        name = f"zoo, {v0 * 1e6:g} um/s, " + ("+".join(arts) or "white noise only")
        print(f"{name:<34} " + " ".join(f"{q:8.3f}" for q in med))
        if arts == ("red", "wobble"):
            ratio = med / np.asarray(rows[v0])
            if v0 > 1e-6:
                worst = max(worst, float(np.max(np.maximum(ratio, 1 / ratio))))
            print(f"{'  zoo / record':<34} " + " ".join(f"{q:8.2f}" for q in ratio))
    print(f"zoo (red+wobble) against the record at 2 um/s: within a factor {worst:.2f} at "
          f"every scale of {SCALES[0]:g}-{SCALES[-1]:g} s")

if __name__ == "__main__":
    main()
