"""Direct simulation of the trap model's Hopf point (docs/hopf.md): the sign of ``l1`` from
:mod:`.trap_hopf` against runs (every definition here is ours).

Two simulators, both of the quasi-static or inertial spring-slider with the direct effect:

* the reduction itself (:func:`.trap_hopf.simulate`, Radau): checks the normal form's algebra
  and its amplitude against the dynamics it was derived from;
* the package's trap ensemble (:func:`dryfriction.ensemble.driving.continue_spring`, a regular
  track of discrete pairs, the compiled kernel): an independent route, with the lattice's own
  force steps as a noise floor.

The amplitude is the half peak-to-peak spring force of each linear period ``2 pi/omega_c``
(``F_el``). *Supercritical* check: below ``K_c``, at ``K = K_c (1 - d)``, a run long enough
that the amplitude changes by less than :data:`SETTLE_TOL` over :data:`SETTLE_PERIODS`
periods; exponent of ``amplitude ∝ d^beta`` by least squares. *Subcritical* check: above
``K_c``, ``K = K_c (1 + d)``, starts on the critical eigenspace bracketing the predicted
unstable cycle (``examples/trap_hopf_check.py``: 0.8 and 1.25 times it, then bisection steps)
must decay below and grow above it; the unstable cycle's amplitude is the last decaying run's
amplitude where it changes least.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..ensemble.driving import Output, SpringDrive, continue_spring
from ..ensemble.population import Ensemble, Initial, Track
from ..program import Segment, VelocityProgram
from ..theory.model import TRAPS_PER_A0_COARSE, TrapModel
from .trap_hopf import TrapField, TrapHopf, simulate

__all__ = ["SETTLE_TOL", "SETTLE_PERIODS", "reduced_amplitudes", "ensemble_amplitudes",
           "settled", "threshold", "amplitude_exponent"]

SETTLE_TOL = 1e-3
"""Largest relative change of the amplitude over :data:`SETTLE_PERIODS` of a settled cycle."""
SETTLE_PERIODS = 50
_SAMPLES = 64  # samples per linear period


def _kick(fld: TrapField, hop: TrapHopf, K: float, size: float) -> np.ndarray:
    """Steady sliding plus ``Re(q/q_xi)``, scaled to a spring-force excursion ``size``
    (``F_el``): a start on the critical eigenspace."""
    assert hop.point is not None
    q = hop.point.q / hop.point.q[0]
    return fld.steady() + np.real(q) * size / K


def reduced_amplitudes(fld: TrapField, hop: TrapHopf, K: float, size: float,
                       periods: int) -> np.ndarray:
    """Half peak-to-peak spring force (``F_el``) in each linear period of a run of the
    reduction at ``K`` started on the critical eigenspace with excursion ``size``."""
    T = 2 * math.pi / hop.omega
    _, y = simulate(fld, K, _kick(fld, hop, K, size), periods * T,
                    samples=periods * _SAMPLES + 1)
    f = K * y[0, 1:].reshape(periods, _SAMPLES)
    return 0.5 * np.ptp(f, axis=1)


def ensemble_amplitudes(u: float, model: TrapModel, hop: TrapHopf, K: float, kick: float,
                        periods: int, traps_per_a0: float = TRAPS_PER_A0_COARSE,
                        mass: float = 0.0) -> np.ndarray:
    """The same from the trap ensemble, started from the steady population of ``(1 + kick)
    u`` (a state kick, :mod:`.bifurcation`) with the spring balancing it at ``g(u)``."""
    T = 2 * math.pi / hop.omega
    ens = Ensemble(model, Track(traps_per_a0), Initial("steady", velocity=(1 + kick) * u),
                   age_horizon=2 * periods * T + 10 * hop_tau(hop))
    from ..theory.direct import junction_strength

    f0 = ens.observe().force * float(junction_strength(u, model.direct, model.v_ref))
    r = continue_spring(ens, SpringDrive(K, mass, VelocityProgram(
        [Segment(u, duration=periods * T)])), Output(every=T / _SAMPLES), spring_force=f0,
        velocity=u if mass > 0 else 0.0)
    y = K * (r.x_pull - r.x)
    n = (y.size - 1) // _SAMPLES
    return 0.5 * np.ptp(y[1:1 + n * _SAMPLES].reshape(n, _SAMPLES), axis=1)


def hop_tau(hop: TrapHopf) -> float:
    """A period ``2 pi/omega_c`` (``t0``)."""
    return 2 * math.pi / hop.omega


def settled(run: Any, start: float, periods: int, max_periods: int = 6400) -> dict[str, Any]:
    """Run ``run(start, periods) -> amplitudes`` doubling ``periods`` until the mean of the
    last 5 periods differs from that 50 periods earlier by less than :data:`SETTLE_TOL`."""
    while True:
        amps = run(start, periods)
        last = float(np.mean(amps[-5:]))
        before = float(np.mean(amps[-5 - SETTLE_PERIODS:-SETTLE_PERIODS]))
        change = abs(last - before) / max(last, 1e-300)
        if change < SETTLE_TOL or periods >= max_periods:
            return {"amplitude": last, "change": change, "periods": periods,
                    "settled": bool(change < SETTLE_TOL)}
        periods *= 2


def threshold(grows: Any, lo: float, hi: float, steps: int = 10) -> dict[str, Any]:
    """Bisection of ``grows(size) -> (bool, amplitudes)`` between a decaying ``lo`` and a
    growing ``hi``; the unstable cycle's amplitude from the last decaying run."""
    g_hi, _ = grows(hi)
    g_lo, amps_lo = grows(lo)
    if not g_hi or g_lo:
        return {"lo": lo, "hi": hi, "amplitude": math.nan, "bracketed": False}
    best = amps_lo
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        g, amps = grows(mid)
        if g:
            hi = mid
        else:
            lo, best = mid, amps
    slow = int(np.argmin(np.abs(np.diff(best))))
    return {"lo": lo, "hi": hi, "amplitude": float(best[slow]), "bracketed": True}


def amplitude_exponent(d: Any, amp: Any) -> tuple[float, float]:
    """``(beta, stderr)`` of ``amp = c d^beta`` by least squares in log-log (3 points or
    more)."""
    x, y = np.log(np.asarray(d, float)), np.log(np.asarray(amp, float))
    coef, cov = np.polyfit(x, y, 1, cov=True)
    return float(coef[0]), float(math.sqrt(cov[0, 0]))
