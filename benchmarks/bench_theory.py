"""Speed of the analytic results (issue: 1000-point grids, goal <= 5 ms each on one core,
and >= 200x faster than per-point adaptive ``scipy.integrate.quad``).

Run: ``python -m benchmarks bench_theory`` (pins itself to one thread of BLAS; NumPy's
elementwise work is single-threaded anyway).
"""

from __future__ import annotations

import math
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from scipy.integrate import quad  # noqa: E402
from scipy.optimize import brentq  # noqa: E402

from benchmarks.timing import best_time  # noqa: E402
from dryfriction.theory.model import TrapModel  # noqa: E402
from dryfriction.theory.static import static_friction  # noqa: E402
from dryfriction.theory.steady import steady_friction  # noqa: E402
from dryfriction.theory.trap import Trap, force_plus  # noqa: E402

EPS, ALPHA = 0.04, 0.13
GRID = np.logspace(-4, 4, 1000)
MODEL = TrapModel(ALPHA, EPS)


def quad_static(T: float) -> float:
    """Per-point adaptive quadrature of eq. 27 (the naive route)."""
    trap = Trap(ALPHA)
    r = math.sqrt(1 + EPS * math.log1p(T))
    yc = trap.y_c
    a = quad(lambda y: float(force_plus(y, ALPHA)), -1, -1 + r * yc)[0]
    b = quad(lambda y: float(force_plus(y, ALPHA)), yc - 1 / r, yc)[0]
    return (a + r**3 * b) / trap.H0


def quad_steady(u: float) -> float:
    """Per-point adaptive quadrature of eq. 34 in y, with brentq for the death point."""
    trap = Trap(ALPHA)

    def r(y: float) -> float:
        return math.sqrt(1 + EPS * math.log1p((y + 1) / u))

    yd = brentq(lambda y: y / r(y) - trap.y_c, trap.y_c, 10 * trap.y_c + 10)
    val = quad(lambda y: r(y) ** 2 * float(force_plus(y / r(y), ALPHA)), -1, yd, limit=200)[0]
    return val / trap.H0


def main() -> None:
    sub = GRID[::50]  # the naive route is timed on 20 points and scaled to 1000
    rows = []
    for name, fast, slow in (
        ("static_friction", lambda: static_friction(MODEL, GRID), quad_static),
        ("steady_friction", lambda: steady_friction(MODEL, GRID), quad_steady),
    ):
        t_fast = best_time(fast)
        t0 = time.perf_counter()
        naive = np.array([slow(x) for x in sub])
        t_slow = (time.perf_counter() - t0) / len(sub) * len(GRID)
        lib = fast()[::50]
        rows.append((name, t_fast, t_slow, np.max(np.abs(lib / naive - 1))))
    print(f"1000-point grid, eps = {EPS}, alpha = {ALPHA}, x in [1e-4, 1e4] "
          "(goal <= 5 ms, >= 200x)")
    for name, tf, ts, diff in rows:
        print(f"  {name:16s} {tf * 1e3:8.3f} ms   quad per point {ts * 1e3:9.1f} ms   "
              f"speed-up {ts / tf:8.0f}x   max rel. diff vs quad {diff:.1e}")
    t_en = best_time(lambda: steady_friction(MODEL.replace(creep="eyring-nabarro"), GRID), 3, 1)
    t_strong = best_time(lambda: static_friction(MODEL.replace(alpha=0.5), GRID), 3, 2)
    print(f"  steady_friction, Eyring-Nabarro creep: {t_en * 1e3:.1f} ms")
    print("  static_friction, strong pinning (alpha = 0.5, interior search): "
          f"{t_strong * 1e3:.1f} ms")


if __name__ == "__main__":
    main()
