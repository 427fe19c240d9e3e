"""Direct simulation of the rate-and-state Hopf point's nature, with the package's
solver (:func:`dryfriction.rsf.driving.simulate`), to check :mod:`.rsf_hopf` (every
procedure here is ours).

* **Supercritical** (:func:`settled_amplitude`, :func:`amplitude_exponent`): below ``k_c``
  two runs start off the predicted cycle (``ln V`` kicked by 0.8 and 1.2 times the predicted
  amplitude, state steady), last at least six relaxation times ``1/(2 beta)`` onto the cycle,
  and are lengthened until the half peak-to-peak ``ln V`` of the last periods and of
  the periods 50 periods earlier differ by less than ``1e-3`` of it and the two runs agree to
  ``2e-3`` (settled); the amplitudes
  at several distances ``d = (k_c - k)/k_c`` give the exponent of ``amp ~ d^beta`` by
  least squares in log-log, with its standard error (1/2 for a Hopf point).
* **Subcritical or degenerate** (:func:`basin_threshold`): above ``k_c``, starts
  ``V = V* e^delta`` (state steady at ``V*``) decay or grow; bisection on ``delta`` between
  a decaying and a growing start brackets the stable manifold of the unstable cycle. A run
  *grows* when its last-period amplitude exceeds the first's, or when the solver stops on a
  runaway velocity (the quasi-static slip law's finite-time blow-up). The amplitude of the
  unstable cycle is read from the run just below the threshold, at its slowest period (the
  smallest change of amplitude from one period to the next: where it lingers near the cycle).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..program import Segment
from ..rsf.driving import SolverError, simulate
from ..rsf.law import RateState
from ..rsf.spring import RSFInitial, RSFOutput, SpringSlider
from .rsf_hopf import RSFHopf

__all__ = ["period_amplitudes", "settled_amplitude", "settle_two_starts", "amplitude_exponent",
           "basin_threshold", "SETTLE_TOL", "SETTLE_PERIODS", "RELAXATIONS", "START_FACTORS"]

_SAMPLES = 128  # samples per period (ours: the sampled peak misses the true one by
# ~ (pi/128)^2/2 = 3e-4 of the amplitude)
_STEPS = 400  # step budget per period (measured: ~190 with 128 outputs a period; the
# default budget of 1e6 steps stopped runs of more than ~5000 periods)
_MEAN = 5  # periods averaged at each end of the settling comparison (smooths that jitter)
SETTLE_TOL = 1e-3
"""Largest relative change of the amplitude over :data:`SETTLE_PERIODS` of a settled cycle."""
SETTLE_PERIODS = 50
RELAXATIONS = 6
"""Shortest supercritical run, in relaxation times ``1/(2 beta)`` (a start 20 % off the
cycle ends ~5e-4 from it)."""
START_FACTORS = (0.8, 1.2)
"""The two starts of a supercritical check, in units of the normal form's amplitude."""


def period_amplitudes(model: RateState, hopf: RSFHopf, k: float, delta: float, periods: int,
                      damping: float = 0.0, mass: float = 0.0, rtol: float = 1e-9
                      ) -> np.ndarray:
    """Half peak-to-peak of ``ln(V/V*)`` in each linear period ``2 pi/omega_c`` of a run at
    stiffness ``k`` started at ``V = V* e^delta`` with the state steady at ``V*``.

    Parameters
    ----------
    model : RateState
    hopf : RSFHopf
        The Hopf point (its ``velocity`` ``V*``, m/s, and ``frequency``, rad/s).
    k : float
        Spring stiffness, 1/m per unit normal force.
    delta : float
        Initial kick ``ln(V/V*)``.
    periods : int
        Run length in linear periods.
    damping, mass : float
        ``eta/sigma`` (s/m) and ``m`` (s^2/m) per unit normal force.
    rtol : float
        Solver tolerance.

    Returns
    -------
    ndarray
        One amplitude per period (dimensionless).

    Raises
    ------
    SolverError
        A runaway velocity, or the solver's step budget.
    """
    v = hopf.velocity
    period = 2 * math.pi / hopf.frequency
    t = np.linspace(0.0, periods * period, periods * _SAMPLES + 1)
    r = simulate(model, SpringSlider([Segment(v, duration=t[-1])], k, damping, mass),
                 RSFInitial(v=v * math.exp(delta), theta=model.dc / v,
                            theta2=None if model.dc2 is None else model.dc2 / v),
                 RSFOutput(t_eval=t, rtol=rtol, max_steps=max(1_000_000, _STEPS * periods)))
    lnv = np.log(r.v / v)[1:].reshape(periods, _SAMPLES)
    return 0.5 * np.ptp(lnv, axis=1)


def settled_amplitude(model: RateState, hopf: RSFHopf, distance: float,
                      damping: float = 0.0, mass: float = 0.0, max_periods: int = 24000,
                      starts: tuple[float, float] = START_FACTORS) -> dict[str, Any]:
    """The settled cycle below ``k_c`` at ``k = k_c (1 - distance)`` (module docstring).

    Two runs start at ``starts`` times the normal form's amplitude (one below it, one above),
    each at least :data:`RELAXATIONS` relaxation times ``1/(2 beta)`` long, doubled (up to
    ``max_periods`` linear periods) until both change by less than :data:`SETTLE_TOL` over
    :data:`SETTLE_PERIODS` periods *and* they end within ``2 SETTLE_TOL`` of each other
    (ours: a slowly relaxing run meets the first condition long before it arrives, e.g. 0.983
    of the cycle changing by 6.7e-4 over 50 periods with a relaxation time of 1300 periods;
    the second does not let the answer be the start's).

    Returns
    -------
    dict
        ``distance``; ``amplitude``, the mean of the two runs' last 5 periods (half
        peak-to-peak ``ln V``); ``change``, the larger relative change over 50 periods;
        ``spread``, the two runs' relative difference; ``periods``; ``relaxations``, the run
        length in relaxation times; ``settled``, both conditions met.
    """
    k = hopf.k_c * (1.0 - distance)
    start = hopf.amp_coef * math.sqrt(distance) if math.isfinite(hopf.amp_coef) else 0.05
    # the amplitude's deviation from the cycle relaxes as exp(-2 beta t): 1/(2 beta) is
    # relax periods, beta = 2 pi growth_slope distance per period
    relax = (1 / (4 * math.pi * hopf.growth_slope * distance) if hopf.growth_slope > 0
             else 0.0)
    r = settle_two_starts(
        lambda s, p: period_amplitudes(model, hopf, k, s, p, damping, mass), start, relax,
        max_periods, starts)
    return {"distance": distance, **r}


def settle_two_starts(run: Callable[[float, int], np.ndarray], start: float, relax: float,
                      max_periods: int, starts: tuple[float, float] = START_FACTORS
                      ) -> dict[str, Any]:
    """The settling logic of :func:`settled_amplitude` for any simulator (ours).

    Parameters
    ----------
    run : callable
        ``run(start_size, periods) -> amplitudes``, one per linear period.
    start : float
        The normal form's amplitude; the runs start at ``starts`` times it.
    relax : float
        The relaxation time ``1/(2 beta)`` of the amplitude, in periods (0: unknown).
    max_periods : int
        Longest run.

    Returns
    -------
    dict
        ``amplitude`` (mean of the two runs' last 5 periods), ``change``, ``spread``,
        ``periods``, ``relaxations``, ``settled`` (:func:`settled_amplitude`).
    """
    periods = int(min(max_periods, max(4 * SETTLE_PERIODS, math.ceil(RELAXATIONS * relax))))
    while True:
        ends, changes = [], []
        for f in starts:
            amps = run(f * start, periods)
            last = float(np.mean(amps[-_MEAN:]))
            before = float(np.mean(amps[-_MEAN - SETTLE_PERIODS:-SETTLE_PERIODS]))
            ends.append(last)
            changes.append(abs(last - before) / max(last, 1e-300))
        amp = float(np.mean(ends))
        spread = float(np.ptp(ends)) / max(amp, 1e-300)
        change = max(changes)
        ok = change < SETTLE_TOL and spread < 2 * SETTLE_TOL
        if ok or periods >= max_periods:
            return {"amplitude": amp, "change": change, "spread": spread, "periods": periods,
                    "relaxations": periods / relax if relax > 0 else math.inf,
                    "settled": bool(ok)}
        periods = min(max_periods, 2 * periods)


def amplitude_exponent(rows: list[dict[str, Any]]) -> tuple[float, float, float]:
    """``(beta, stderr, coefficient)`` of ``amplitude = coefficient distance^beta`` by least
    squares in log-log over the settled rows (those of :func:`settled_amplitude` with
    ``settled``, or of :func:`basin_threshold` with a finite ``amplitude``; NaN with fewer
    than 3)."""
    ok = [(r["distance"], r["amplitude"]) for r in rows
          if r.get("settled", True) and math.isfinite(r["amplitude"]) and r["amplitude"] > 0]
    if len(ok) < 3:
        return math.nan, math.nan, math.nan
    d, a = np.log(np.array(ok)).T
    coef, cov = np.polyfit(d, a, 1, cov=True)
    return float(coef[0]), float(math.sqrt(cov[0, 0])), float(math.exp(coef[1]))


def _grows(model: RateState, hopf: RSFHopf, k: float, delta: float, periods: int,
           damping: float, mass: float) -> tuple[bool, np.ndarray | None]:
    try:
        amps = period_amplitudes(model, hopf, k, delta, periods, damping, mass)
    except SolverError as exc:
        if exc.v > 1e3 * hopf.velocity:  # a runaway slip velocity: it grows
            return True, None
        raise  # the step budget, not the dynamics: not a verdict
    return bool(amps[-1] > amps[0]), amps


def basin_threshold(model: RateState, hopf: RSFHopf, distance: float, damping: float = 0.0,
                    mass: float = 0.0, periods: int | None = None, delta_max: float = 2.0,
                    steps: int = 14) -> dict[str, Any]:
    """Bisection of the basin of steady sliding above ``k_c``, at ``k = k_c (1 + distance)``
    (module docstring).

    Returns ``{"distance", "delta_lo", "delta_hi", "amplitude"}``: the largest decaying and
    the smallest growing kick found (``delta_hi`` NaN: every kick up to ``delta_max``
    decayed) and the unstable cycle's amplitude (half peak-to-peak ``ln V``; NaN if none)."""
    k = hopf.k_c * (1.0 + distance)
    if periods is None:  # three e-foldings of the linear rate, at least 60 periods
        periods = int(min(2000, max(60, math.ceil(3 / (2 * math.pi * hopf.growth_slope
                                                          * distance)))))
    lo, hi = 0.0, delta_max
    grows, _ = _grows(model, hopf, k, hi, periods, damping, mass)
    if not grows:
        return {"distance": distance, "delta_lo": hi, "delta_hi": math.nan,
                "amplitude": math.nan}
    best: np.ndarray | None = None
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        g, amps = _grows(model, hopf, k, mid, periods, damping, mass)
        if g:
            hi = mid
        else:
            lo, best = mid, amps
    amp = math.nan
    if best is not None:
        slow = int(np.argmin(np.abs(np.diff(best))))
        amp = float(best[slow])
    return {"distance": distance, "delta_lo": lo, "delta_hi": hi, "amplitude": amp}
