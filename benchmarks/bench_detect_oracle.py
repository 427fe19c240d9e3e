"""An oracle for the zoo's change times (issue 23): is max(one sample, 0.5 s) attainable?

For records drawn as the zoo draws its up/down records (``tests/records_zoo.py``: v1 of 0.1 to
50 um/s, slides of 150-400 um and 60-2500 s, the zoo's sampling rate), with the zoo's relative
velocity wander (Ornstein-Uhlenbeck, 8 % rms, 3 s; optionally its machine oscillation too),
0.17 um white noise and a 20 nm quantum, the change time is estimated by the maximum-likelihood
hinge GIVEN THE TRUE NOISE MODEL: the exact Gaussian likelihood of the displacement on +-120 s
(sampled at <= 8 Hz) with the integrated-OU covariance of the true parameters, maximised over
the change time (0.02-s grid, +-15 s) with free offset and velocities (generalised least
squares). With the machine oscillation added, the likelihood still knows only the OU
wander (an oracle for the red-only rows alone). No detector knows more; the fraction it
places within max(one sample, 0.5 s) is what the zoo's levels allow (an estimate from an ML
oracle, not a proven bound).

Run: ``python -m benchmarks bench_detect_oracle [N]`` (N records per case, default 50; seeded).
"""

from __future__ import annotations

import math
import os
import sys
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import numpy as np  # noqa: E402
from scipy.linalg import solve_triangular  # noqa: E402

import records_zoo as z  # noqa: E402


def draw(rng: np.random.Generator, ratio: float, up: bool) -> tuple[float, ...]:
    """A zoo up/down record's v1, v2 (m/s), durations (s) and sampling rate (Hz), drawn
    as ``records_zoo._program`` and ``make_record`` draw them."""
    v1 = 10 ** rng.uniform(-7.0, -4.3)
    v2 = v1 * ratio if up else v1 / ratio
    def dur(v: float) -> float:
        return float(np.clip(rng.uniform(150e-6, 400e-6) / v, 60.0, 2500.0))

    d1, d2 = dur(v1), dur(v2)
    fs = float(np.clip(max(200.0 / min(d1, d2), 2.0 * max(v1, v2) / 1e-6 / 10.0), 1.0, 100.0))
    fs = float(min((1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0),
                   key=lambda f: abs(math.log(f / fs)) if f >= fs else 1e9))
    return v1, v2, d1, d2, fs


def one(rng: np.random.Generator, ratio: float, up: bool, wob: bool, W: float = 120.0
        ) -> tuple[float, float, float, float] | None:
    """|ML change time - true| (s), the tolerance (s), v1 and the sampling rate of one
    simulated record (module docstring)."""
    v1, v2, d1, d2, fs = draw(rng, ratio, up)
    t = np.arange(0.0, d1 + d2, 1 / fs)
    t0 = d1
    vc = np.where(t >= t0, v2, v1)
    eps = z._ou(t, z.RED_TAU, z.RED_RMS, rng)
    if wob:
        for amp, per in z.WOBBLE:
            eps += amp * np.sin(2 * np.pi * t / per + rng.uniform(0, 2 * np.pi))
    vt = vc * (1 + eps)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (vt[1:] + vt[:-1]) * np.diff(t))])
    x += rng.normal(0, z.WHITE, t.size)
    x = np.round(x / z.QUANTUM) * z.QUANTUM
    m = np.abs(t - t0) <= W
    idx = np.flatnonzero(m)
    k = max(1, int(math.ceil(fs / 8.0)))
    idx = idx[::k]
    tt, xx = t[idx], x[idx]
    # covariance: D_i = sum_{j<=i} w_j eps_j, w = v dt, on the (<= 8 Hz) samples used
    full = idx
    tf = t[full]
    dtf = np.full(tf.size, k / fs)
    w = vc[full] * dtf
    S_eps = z.RED_RMS**2 * np.exp(-np.abs(tf[:, None] - tf[None, :]) / z.RED_TAU)
    if full.size > 30000:
        return None
    C = np.cumsum(np.cumsum(w[:, None] * S_eps * w[None, :], axis=0), axis=1)
    sub = np.arange(idx.size)
    C = C + (z.WHITE**2 + z.QUANTUM**2 / 12) * np.eye(sub.size)
    L = np.linalg.cholesky(C)

    def wi(a: np.ndarray) -> np.ndarray:
        return solve_triangular(L, a, lower=True)

    y = wi(xx - xx.mean())
    base = wi(np.column_stack([np.ones_like(tt), tt - t0]))
    grid = t0 + np.arange(-15.0, 15.0001, 0.02)
    H = np.maximum(tt[:, None] - grid[None, :], 0.0)
    Hw = wi(H)
    rss = []
    for j in range(grid.size):
        A = np.column_stack([base, Hw[:, j]])
        c, *_ = np.linalg.lstsq(A, y, rcond=None)
        rss.append(np.sum((y - A @ c) ** 2))
    th = grid[int(np.argmin(rss))]
    tol = max(1 / fs, 0.5)
    return abs(th - t0), tol, v1, fs


def main() -> None:
    n = int(sys.argv[-1]) if len(sys.argv) > 1 and sys.argv[-1].isdigit() else 50
    rng = np.random.default_rng(2026)
    for ratio in (1.3, 2.0, 3.0):
        for wob in (False, True):
            res = [r for r in (one(rng, ratio, up, wob) for up in (True, False)
                               for _ in range(n)) if r]
            e = np.array([r[0] for r in res])
            tol = np.array([r[1] for r in res])
            slow = np.array([r[3] <= 2 for r in res])
            ok = e <= tol
            print(f"ratio {ratio} {'red+wobble' if wob else 'red only  '}: oracle within "
                  f"max(1 sample, 0.5 s) on {100 * ok.mean():.0f} % of {ok.size} (sampled <= 2 Hz:"
                  f" {100 * ok[slow].mean() if slow.any() else float('nan'):.0f} % of {slow.sum()};"
                  f" faster: {100 * ok[~slow].mean():.0f} %); error median {np.median(e):.2f} s,"
                  f" 90th percentile {np.percentile(e, 90):.2f} s")


if __name__ == "__main__":
    main()
