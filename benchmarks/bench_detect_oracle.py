"""An oracle for the zoo's change times (issue 23): is max(one sample, 0.5 s) attainable?

For records drawn as the zoo draws its up/down records (``tests/records_zoo.py``: v1 of 0.1 to
50 um/s, slides of 150-400 um and 60-2500 s, the zoo's sampling rate), with the zoo's servo
position error (``de/dt = -e / SERVO_TAU + V eta``, ``eta`` Ornstein-Uhlenbeck; optionally its
machine oscillation too), 0.17 um white noise and a 20 nm quantum, the change time is estimated
by the maximum-likelihood hinge GIVEN THE TRUE NOISE MODEL: the exact Gaussian likelihood of
the displacement on +-60 s (sampled at <= 4 Hz) with the servo error's covariance for the
true parameters and the true velocities on both sides, maximised over the change time (0.02-s
grid, +-15 s) with free offset and velocities (generalised least squares). The covariance (ours,
from the model): ``eta = s sqrt(2/tau_eta) int exp(-(u - r)/tau_eta) dW(r)``, so ``e(t) = int
G(t, r) dW(r)`` with ``G(t, r) = s sqrt(2/tau_eta) int_r^t exp(-(t - u)/tau_s) V(u)
exp(-(u - r)/tau_eta) du`` (closed form for a piecewise-constant ``V``) and ``cov(e(t),
e(t')) = int G(t, r) G(t', r) dr`` (a 0.05-s quadrature in ``r``). With the machine
oscillation added, the likelihood still knows only the servo error (an oracle for the
servo-only rows alone). No detector knows more; the fraction it places within max(one
sample, 0.5 s) is what the zoo's levels allow (an estimate from an ML oracle, not a proven
bound).

Run: ``python -m benchmarks bench_detect_oracle [N]`` (N records per case, default 30; seeded).
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


def _f(t: np.ndarray, r: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """``int_lo^hi exp(-(t - u)/tau_s) exp(-(u - r)/tau_eta) du`` (0 where ``hi <= lo``)."""
    ts, te = z.SERVO_TAU, z.SERVO_ETA_TAU
    k = 1.0 / ts - 1.0 / te
    hi = np.maximum(hi, lo)
    # exp(-t/ts + r/te) (exp(k hi) - exp(k lo)) / k, written as differences of exponents
    return (np.exp(-(t - hi) / ts - (hi - r) / te) - np.exp(-(t - lo) / ts - (lo - r) / te)) / k


def servo_cov(tt: np.ndarray, t0: float, v1: float, v2: float) -> np.ndarray:
    """Covariance of the servo error at times ``tt`` (module docstring), ``V = v1`` before
    ``t0`` and ``v2`` after."""
    r = np.arange(tt[0] - 10.0 * max(z.SERVO_TAU, z.SERVO_ETA_TAU), tt[-1], 0.05)
    T, R = tt[:, None], r[None, :]
    G = v1 * _f(T, R, R, np.minimum(T, t0)) + v2 * _f(T, R, np.maximum(R, t0), T)
    G = np.where(R < T, G, 0.0) * z.SERVO_RMS * np.sqrt(2.0 / z.SERVO_ETA_TAU)
    return (G @ G.T) * 0.05


def one(rng: np.random.Generator, ratio: float, up: bool, wob: bool, W: float = 60.0
        ) -> tuple[float, float, float, float] | None:
    """|ML change time - true| (s), the tolerance (s), v1 and the sampling rate of one
    simulated record (module docstring)."""
    v1, v2, d1, d2, fs = draw(rng, ratio, up)
    t = np.arange(0.0, d1 + d2, 1 / fs)
    t0 = d1
    vc = np.where(t >= t0, v2, v1)
    eps = np.zeros_like(t)
    if wob:
        for amp, per in z.WOBBLE:
            eps += amp * np.sin(2 * np.pi * t / per + rng.uniform(0, 2 * np.pi))
    vt = vc * (1 + eps)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (vt[1:] + vt[:-1]) * np.diff(t))])
    x += z.servo_error(t, vc, rng) + rng.normal(0, z.WHITE, t.size)
    x = np.round(x / z.QUANTUM) * z.QUANTUM
    idx = np.flatnonzero(np.abs(t - t0) <= W)
    k = max(1, int(math.ceil(fs / 4.0)))
    idx = idx[::k]
    tt, xx = t[idx], x[idx]
    C = servo_cov(tt, t0, v1, v2) + (z.WHITE**2 + z.QUANTUM**2 / 12) * np.eye(tt.size)
    L = np.linalg.cholesky(C)

    def wi(a: np.ndarray) -> np.ndarray:
        return solve_triangular(L, a, lower=True)

    y = wi(xx - xx.mean())
    base = wi(np.column_stack([np.ones_like(tt), tt - t0]))
    grid = t0 + np.arange(-15.0, 15.0001, 0.02)
    Hw = wi(np.maximum(tt[:, None] - grid[None, :], 0.0))
    # the RSS of [base, h] for each grid column: project out the base once, then one column
    Qb, _ = np.linalg.qr(base)
    yp = y - Qb @ (Qb.T @ y)
    Hp = Hw - Qb @ (Qb.T @ Hw)
    gain = (Hp.T @ yp) ** 2 / np.einsum("ij,ij->j", Hp, Hp)
    th = grid[int(np.argmax(gain))]
    tol = max(1 / fs, 0.5)
    return abs(th - t0), tol, v1, fs


def main() -> None:
    n = int(sys.argv[-1]) if len(sys.argv) > 1 and sys.argv[-1].isdigit() else 30
    rng = np.random.default_rng(2026)
    for ratio in (1.3, 2.0, 3.0):
        for wob in (False, True):
            res = [r for r in (one(rng, ratio, up, wob) for up in (True, False)
                               for _ in range(n)) if r]
            e = np.array([r[0] for r in res])
            tol = np.array([r[1] for r in res])
            slow = np.array([r[3] <= 2 for r in res])
            ok = e <= tol
            print(f"ratio {ratio} {'servo+wobble' if wob else 'servo only  '}: oracle within "
                  f"max(1 sample, 0.5 s) on {100 * ok.mean():.0f} % of {ok.size} (sampled <= 2 Hz:"
                  f" {100 * ok[slow].mean() if slow.any() else float('nan'):.0f} % of {slow.sum()};"
                  f" faster: {100 * ok[~slow].mean():.0f} %); error median {np.median(e):.2f} s,"
                  f" 90th percentile {np.percentile(e, 90):.2f} s")


if __name__ == "__main__":
    main()
