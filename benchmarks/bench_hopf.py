"""Cost of one first Lyapunov coefficient (issue 28): the generic routine on a 2-D field, and
the rate-and-state Hopf point (critical stiffness by bisection on the eigenvalues, then l1)
quasi-static (2-D) and with mass (3-D); the trap model's Hopf point on its Chebyshev reduction
(:mod:`dryfriction.analysis.trap_hopf`: the Nyquist K_c, the refinement on the Jacobian, l1)
at the resolutions of the checks and of the convergence test.

Run: ``python -m benchmarks bench_hopf`` (one BLAS thread).
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from benchmarks.timing import best_time  # noqa: E402
from dryfriction.analysis.rsf_hopf import SliderField, critical_kappa, rsf_hopf  # noqa: E402
from dryfriction.analysis.trap_hopf import trap_hopf  # noqa: E402
from dryfriction.rsf.law import RateState  # noqa: E402
from dryfriction.theory.hopf import first_lyapunov  # noqa: E402
from dryfriction.theory.model import TrapModel  # noqa: E402

V = 3.1e-6


def main() -> None:
    m = RateState(a=0.011, b=0.016, dc=7.3e-6, mu0=0.6, v0=1.2e-6, state_law="slip")
    mass = 0.1 * m.dc / V**2
    for label, mm in (("quasi-static (2-D)", 0.0), ("with mass (3-D)", mass)):
        fld = SliderField(m, V, 0.0, mm)
        kc = critical_kappa(fld)
        x0 = np.zeros(fld.n)
        for method in ("complex", "fd"):
            t = best_time(lambda fld=fld, kc=kc, x0=x0, method=method: first_lyapunov(
                lambda X: fld(X, kc), x0, method=method), repeat=5, number=5)
            print(f"l1 alone, {label}, {method:7s}: {t * 1e3:7.2f} ms")
        t = best_time(lambda fld=fld: critical_kappa(fld), repeat=3, number=3)
        print(f"critical stiffness, {label}:     {t * 1e3:7.2f} ms")
        t = best_time(lambda mm=mm: rsf_hopf(m, V, 0.0, mm), repeat=3, number=3)
        print(f"rsf_hopf (k_c + l1 + dsigma/dk), {label}: {t * 1e3:7.2f} ms")
    tm = TrapModel(eps=0.04, direct=0.02)
    for n, panels in ((16, 12), (32, 24)):
        for u in (0.01, 1.0):
            t = best_time(lambda n=n, panels=panels, u=u: trap_hopf(
                u, tm, n=n, panels=panels), repeat=2, number=1)
            print(f"trap_hopf, u = {u:g}, n = {n}, {panels} panels (K_c + l1):"
                  f" {t * 1e3:7.1f} ms")


if __name__ == "__main__":
    main()
