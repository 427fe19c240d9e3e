"""Direct simulation of the trap model's Hopf point (docs/hopf.md): the sign of ``l1`` from
:mod:`.trap_hopf` against runs (every definition here is ours).

Two simulators, both of the quasi-static or inertial spring-slider with the direct effect:

* the reduction itself (:func:`.trap_hopf.simulate`, Radau): the trap population as a
  continuous density on the track (the limit of infinitely many pairs per ``a0``, while the
  slider moves forward), a deterministic evolution whose friction is the model's; it checks
  the normal form's algebra and its amplitude against the dynamics it was derived from, and
  settles cycles and bisects unstable ones to any precision (:func:`population_check`);
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
from ..ensemble.thermal import SUBSTEP_SLIP
from ..program import Segment, VelocityProgram
from ..theory.model import TRAPS_PER_A0_COARSE, TrapModel
from .rsf_hopf_check import SETTLE_PERIODS, SETTLE_TOL, settle_two_starts
from .trap_hopf import TrapField, TrapHopf, simulate, trap_hopf

__all__ = ["SETTLE_TOL", "SETTLE_PERIODS", "reduced_amplitudes", "ensemble_amplitudes",
           "settled", "threshold", "amplitude_exponent", "cycle_start", "cycle_amplitudes",
           "swing_distance", "check_distances", "check_plan", "check_cost", "check_point",
           "carried_stick_slip", "population_check", "POPULATION_RES"]

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
    last 5 periods differs from that 50 periods earlier by less than :data:`SETTLE_TOL`.

    One start only: a run still relaxing slowly towards the cycle can pass this test long
    before it arrives (its answer then leans towards its start). The check that does not let
    that happen is :func:`.rsf_hopf_check.settle_two_starts` (two starts, >= 6 relaxation
    times), used by :func:`population_check`; this one stays for the ensemble's checks
    (:func:`check_point`), whose amplitude wanders by more than the tolerance anyway."""
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


def cycle_start(u: float, model: TrapModel, hop: TrapHopf, K: float, slip: float,
                track: Track | float, mass: float = 0.0, damping: float = 0.0,
                prep_periods: float = 2.0) -> tuple[Ensemble, float, float]:
    """A trap ensemble on ``track`` (a :class:`Track`, or its pairs per ``a0`` on a regular
    one) whose population has lived through the
    linear cycle ``X(t) = u t + slip sin(omega_c t)`` (``slip`` in ``a0``) for
    ``prep_periods`` periods, and the spring force and slider velocity that continue it.

    The population's history is the cycle's (a trap lives less than one period of slip,
    ``tau_d u < 2 pi u/omega_c``, docs/hopf.md), so the released slider starts on the cycle,
    not on a kick that must first grow through the track's discreteness. The slider is moved
    by :meth:`Ensemble.advance` in steps of a quarter of the trap spacing, as the spring drive
    steps it (:data:`dryfriction.ensemble.thermal.SUBSTEP_SLIP`). At release (ours): the
    spring force ``g(V) F_pop + eta V + M X''`` (the slider's equation of motion on the
    cycle; ``M = 0``: the friction), ``V = X'``.

    Returns
    -------
    (Ensemble, float, float)
        The ensemble (time ``t_prep``), the spring force (``F_el``), the velocity (``a0/t0``).
    """
    from ..theory.direct import junction_strength

    om = hop.omega
    if not slip * om < u:
        raise ValueError(f"slip = {slip:g} a0 is out of range at u = {u:g}: the linear cycle "
                         f"moves backward; allowed slip < u/omega_c = {u / om:g} a0")
    t_prep = prep_periods * 2 * math.pi / om
    trk = track if isinstance(track, Track) else Track(float(track))
    ens = Ensemble(model, trk, Initial("steady", velocity=u), age_horizon=t_prep + 10.0)
    # steps in time whose slip is at most a quarter of the spacing at the cycle's fastest
    n = int(math.ceil(t_prep * (u + slip * om) * trk.traps_per_a0 / SUBSTEP_SLIP))
    for t in np.linspace(0.0, t_prep, n + 1)[1:]:
        ens.advance(u * t + slip * math.sin(om * t), float(t))
    V = u + slip * om * math.cos(om * t_prep)
    accel = -slip * om * om * math.sin(om * t_prep)
    g = float(junction_strength(V, model.direct, model.v_ref))
    return ens, ens.observe().force * g + damping * V + mass * accel, V


def cycle_amplitudes(u: float, model: TrapModel, hop: TrapHopf, K: float, slip: float,
                     periods: int, track: Track | float, mass: float = 0.0,
                     damping: float = 0.0) -> np.ndarray:
    """Half peak-to-peak spring force (``F_el``) per linear period ``2 pi/omega_c`` of the
    spring-pulled trap ensemble (:func:`dryfriction.ensemble.driving.continue_spring`, the
    integrator of ``dryfriction.simulate``'s spring drive) at stiffness ``K``, released from
    the linear cycle of slip amplitude ``slip`` (:func:`cycle_start`)."""
    T = 2 * math.pi / hop.omega
    ens, f0, V = cycle_start(u, model, hop, K, slip, track, mass, damping)
    r = continue_spring(ens, SpringDrive(K, mass, VelocityProgram(
        [Segment(u, duration=periods * T)]), damping), Output(every=T / _SAMPLES),
        spring_force=f0, velocity=V if mass > 0 else 0.0)
    y = K * (r.x_pull - r.x)
    n = (y.size - 1) // _SAMPLES
    return 0.5 * np.ptp(y[1:1 + n * _SAMPLES].reshape(n, _SAMPLES), axis=1)



def carried_stick_slip(u: float, model: TrapModel, hop: TrapHopf, K: float,
                       track: Track | float, periods: tuple[int, int] = (30, 40),
                       grow_at: float = 0.95) -> tuple[np.ndarray, np.ndarray]:
    """Hysteresis above ``K_c`` (ours): stick-slip grown at ``grow_at K_c`` (released from the
    largest forward cycle, :data:`FORWARD`) for ``periods[0]`` linear periods, then carried
    with its mechanical state (spring force, population) to the stiffness ``K`` for
    ``periods[1]``. Returns the per-period amplitudes (``F_el``) of both stages."""
    T = 2 * math.pi / hop.omega
    K1 = grow_at * hop.K_c
    ens, f0, _ = cycle_start(u, model, hop, K1, FORWARD * u / hop.omega, track)

    def run(k: float, n: int, force: float) -> tuple[np.ndarray, float]:
        r = continue_spring(ens, SpringDrive(k, 0.0, VelocityProgram(
            [Segment(u, duration=n * T)])), Output(every=T / _SAMPLES), spring_force=force)
        y = k * (r.x_pull - r.x)
        m = (y.size - 1) // _SAMPLES
        return 0.5 * np.ptp(y[1:1 + m * _SAMPLES].reshape(m, _SAMPLES), axis=1), float(y[-1])

    grown, f_end = run(K1, periods[0], f0)
    carried, _ = run(K, periods[1], f_end)
    return grown, carried


FORWARD = 0.9
"""Largest swing of a start: ``slip omega_c < FORWARD u`` keeps the slider moving forward."""

# ---------------------------------------------------------------- the check of one row

DISTANCES = (0.03, 0.05, 0.08)
"""Relative distances ``(K_c - K)/K_c`` of the supercritical check's settled cycles (ours):
beyond the ~1 % by which the ensemble's own ``K_c`` differs (docs/hopf.md), scaled down
together where the largest would swing the slider beyond :data:`SWING_MAX`."""
SWING_MAX = 0.75
"""Largest velocity swing ``slip omega_c/u`` of the normal form's cycle at a checked
distance (ours): the slider keeps moving forward, where the expansion holds."""
SUB_SWING = 0.5
"""The subcritical check's distance puts the predicted unstable cycle at this swing (ours)."""
SUPER_PERIODS = (60, 240)
"""First and longest run of a supercritical point, in linear periods (doubled between)."""
SUB_PERIODS = (30, 80)
"""Shortest and longest run of a subcritical start (two e-foldings of the linear rate)."""
SUB_STEPS = 3
"""Bisection steps of the subcritical check."""
CPU_PER_SUBSTEP = (6e-5, 1.5e-7)
"""CPU seconds of one spring-drive substep of the ensemble (a quarter of the trap spacing of
load travel), ``c0 + c1 lambda WINDOW`` (ours). With these values the estimate is about twice
what was measured at ``u = 1`` quasi-static (0.29, 0.80 and 2.6 s per period at 100, 200 and
400 pairs/``a0``, a loaded 2-core machine; docs/hopf.md): an upper estimate."""
WINDOW = 7.0
"""Length of track (``a0``) whose pairs a substep touches, an upper bound (ours)."""


def swing_distance(hop: TrapHopf, u: float, swing: float) -> float:
    """Relative distance ``|K - K_c|/K_c`` where the normal form's half peak-to-peak slip is
    ``swing u/omega_c`` (its slip grows as the root of the distance)."""
    d_ref = 0.01
    K = hop.K_c * (1 - d_ref if hop.l1_x < 0 else 1 + d_ref)
    return d_ref * (swing * u / (hop.omega * hop.slip_amplitude(K))) ** 2


def check_distances(hop: TrapHopf, u: float) -> list[float]:
    """The supercritical check's distances: :data:`DISTANCES`, scaled down together so that
    the largest swings the slider by at most :data:`SWING_MAX`."""
    top = swing_distance(hop, u, SWING_MAX)
    scale = min(1.0, top / DISTANCES[-1])
    return [d * scale for d in DISTANCES]


def check_plan(hop: TrapHopf, u: float) -> list[tuple[float, int]]:
    """``(distance, periods)`` of every run the check of one Hopf point may make (the longest
    each may take): settled cycles at :func:`check_distances`, or the bisection's starts."""
    T = 2 * math.pi / hop.omega
    if hop.nature == "supercritical":
        lo, hi = SUPER_PERIODS
        runs = []
        p = lo
        while p <= hi:
            runs.append(p)
            p *= 2
        return [(d, p) for d in check_distances(hop, u) for p in runs]
    if hop.nature == "subcritical":
        d = swing_distance(hop, u, SUB_SWING)
        beta = abs(hop.dbeta_dK) * hop.K_c * d
        periods = int(max(SUB_PERIODS[0], min(SUB_PERIODS[1], 2.0 / (beta * T))))
        return [(d, periods)] * (2 + SUB_STEPS) + [(d, 70)]  # + the carried stick-slip
    return []


def check_cost(hop: TrapHopf, u: float, track: Track) -> float:
    """Estimated CPU seconds of :func:`check_point` (every run at its longest, 2 periods of
    preparation each; :data:`CPU_PER_SUBSTEP`)."""
    plan = check_plan(hop, u)
    if not plan:
        return 0.0
    lam = track.traps_per_a0
    T = 2 * math.pi / hop.omega
    per_period = (u * T * lam / SUBSTEP_SLIP
                  * (CPU_PER_SUBSTEP[0] + CPU_PER_SUBSTEP[1] * lam * WINDOW))
    return float(sum((p + 2) * per_period for _, p in plan))


def check_point(u: float, model: TrapModel, hop: TrapHopf, track: Track, mass: float = 0.0,
                damping: float = 0.0) -> dict[str, Any]:
    """The simulated check of one Hopf point by the trap ensemble (:func:`cycle_amplitudes`):
    the columns of ``bifurcation.csv`` (:mod:`.hopf_table`).

    * supercritical: settled cycles (:func:`settled`) at ``K = K_c (1 - d)``, ``d`` from
      :func:`check_distances`; the exponent of the amplitude against ``d`` with its standard error;
      the ratio to the normal form at the smallest ``d``; the simulated ``K_c`` from the
      amplitude squared, linear in ``d`` (the normal form's law): ``check_K_c_shift``;
    * subcritical: the unstable cycle by bisection of the start (``0.5`` times the normal
      form's unstable cycle and the largest forward start, :data:`FORWARD`) at
      ``K = K_c (1 + d)``: the last decaying start is ``check_threshold``; when every
      start decays (the track's stabilisation near ``K_c``, docs/hopf.md), whether
      stick-slip carried to ``K`` persists (:func:`carried_stick_slip`).
    """
    out: dict[str, Any] = {"check": "", "check_distance": math.nan,
                           "check_exponent": math.nan, "check_exponent_err": math.nan,
                           "check_amp_ratio": math.nan, "check_threshold": math.nan,
                           "check_K_c_shift": math.nan,
                           "check_traps_per_a0": track.traps_per_a0}
    top = FORWARD * u / hop.omega
    if hop.nature == "supercritical":
        ds, amps, unsettled = [], [], []
        for d in check_distances(hop, u):
            K = hop.K_c * (1 - d)
            r = settled(lambda s, p, K=K: cycle_amplitudes(u, model, hop, K, s / K, p, track,
                                                           mass, damping),
                        K * min(hop.slip_amplitude(K), top), SUPER_PERIODS[0],
                        max_periods=SUPER_PERIODS[1])
            ds.append(d)
            amps.append(r["amplitude"])
            if not r["settled"]:
                unsettled.append(round(d, 5))
        beta, err = amplitude_exponent(ds, amps)
        # amplitude^2 = c (d - shift): the normal form's law about the simulated K_c
        coef = np.polyfit(ds, np.square(amps), 1)
        out.update(check_distance=ds[0], check_exponent=beta, check_exponent_err=err,
                   check_amp_ratio=amps[0] / hop.force_amplitude(hop.K_c * (1 - ds[0])),
                   check_K_c_shift=float(coef[1] / coef[0]))
        grew = all(a > 0 for a in amps) and coef[0] > 0
        out["check"] = ("settled cycles below K_c" if grew and not unsettled else
                        f"NOT settled at d = {unsettled}" if grew else
                        "no cycle below K_c")
    elif hop.nature == "subcritical":
        d = swing_distance(hop, u, SUB_SWING)
        K = hop.K_c * (1 + d)
        pred = hop.force_amplitude(K)
        plan = check_plan(hop, u)

        def grows(s: float) -> tuple[bool, np.ndarray]:
            a = cycle_amplitudes(u, model, hop, K, s / K, plan[0][1], track, mass, damping)
            return bool(np.mean(a[-3:]) > np.mean(a[1:4])), a

        r = threshold(grows, 0.5 * pred, K * top, steps=SUB_STEPS)
        out["check_distance"] = d
        if r["bracketed"]:
            out.update(check_threshold=r["lo"], check_amp_ratio=r["amplitude"] / pred,
                       check="unstable cycle by bisection above K_c")
        else:
            # every forward start decays (or grows): is stick-slip carried above K_c kept?
            grown, carried = carried_stick_slip(u, model, hop, K, track)
            kept = bool(np.mean(carried[-5:]) > 0.5 * np.mean(grown[-5:]) > 2 * pred)
            out["check"] = ("unstable cycle NOT bracketed by forward starts; stick-slip "
                            "carried above K_c persists (hysteresis)" if kept else
                            "NOT bracketed, and stick-slip carried above K_c does not persist")
    else:
        out["check"] = "not run: no Hopf point" if hop.nature == "none" else "not run"
    return out


POPULATION_RES = {"n": 12, "panels": 10, "stretch": 2.0}
"""The reduction's resolution in :func:`population_check` (``l1_x`` within 2e-5 of its
``n = 64`` value there, docs/hopf.md)."""


def population_check(u: float, model: TrapModel, distances: Any, mass: float = 0.0,
                     damping: float = 0.0, steps: int = 8, max_periods: int = 1600,
                     res: dict[str, Any] | None = None) -> dict[str, Any]:
    """The Hopf point's nature checked on the continuous trap population (the reduction of
    :class:`.trap_hopf.TrapField` integrated by Radau, :func:`reduced_amplitudes`; every
    procedure here is ours).

    * supercritical: at ``K = K_c (1 - d)`` two runs started on the critical eigenspace at
      0.8 and 1.2 times the normal form's cycle, settled as rate-and-state's
      (:func:`.rsf_hopf_check.settle_two_starts`: each changing < 1e-3 over 50 periods,
      ending within 2e-3 of each other, after >= 6 relaxation times ``1/(2 beta)``);
    * subcritical: at ``K = K_c (1 + d)``, bisection (``steps`` halvings) of the start on the
      critical eigenspace between 0.8 (must decay) and 1.25 (must grow, or leave the forward
      motion the reduction describes) times the normal form's unstable cycle; a run grows when
      its last period's amplitude exceeds its second's, over ``max(20, min(60, 2/(beta T)))``
      periods, or when the solver fails on it (a start large enough to stop the slider leaves
      the reduction; reported in ``hi_by_failure``); the cycle's amplitude is the last
      decaying run's where it changes least.

    Parameters
    ----------
    u : float
        Pulling velocity, ``a0/t0``.
    model : TrapModel
        With the direct effect and very strong pinning.
    distances : sequence of float
        Relative distances ``|K - K_c|/K_c``, in ``(0, 0.1]``.
    mass, damping : float
        ``M`` (``F_el t0^2/a0``) and ``eta`` (``F_el t0/a0``).
    steps : int
        Bisection halvings (subcritical).
    max_periods : int
        Longest supercritical run, linear periods.
    res : dict, optional
        The reduction's resolution (default :data:`POPULATION_RES`).

    Returns
    -------
    dict
        ``u``, ``K_c`` (``F_el/a0``), ``omega`` (``rad/t0``), ``l1_x`` (``1/a0^2``), ``nature``;
        ``rows``: per distance ``d``, ``K``, ``predicted`` (the normal form's half
        peak-to-peak spring force, ``F_el``), ``amplitude`` (simulated, ``F_el``), ``ratio``,
        and ``settled``/``change``/``spread``/``periods`` (supercritical) or
        ``bracketed``/``lo``/``hi`` (the bracketing starts, ``F_el``) and ``hi_by_failure``
        (the growing end is a run on which the solver failed, counted as growth: say so where
        it is reported; subcritical);
        ``exponent``, ``exponent_err`` of the amplitude against ``d`` over the settled or
        bracketed rows (NaN below 3), and ``slip_exponent`` of the slip amplitude
        (force/``K``), whose normal-form value is exactly 1/2.
    """
    from ..validation import check_scalar

    check_scalar("u", u, 0.0, lo_open=True)
    ds = [check_scalar("distances", d, 0.0, 0.1, lo_open=True) for d in distances]
    if not 1 <= steps <= 30:
        raise ValueError(f"steps = {steps} is out of range: allowed 1 to 30")
    r0 = {**POPULATION_RES, **(res or {})}
    hop = trap_hopf(u, model, mass, damping, **r0)
    out: dict[str, Any] = {"u": u, "K_c": hop.K_c, "omega": hop.omega, "l1_x": hop.l1_x,
                           "nature": hop.nature, "rows": []}
    if hop.nature not in ("supercritical", "subcritical"):
        return out
    fld = TrapField(u, model, mass, damping, **r0)
    T = 2 * math.pi / hop.omega
    sign = -1.0 if hop.nature == "supercritical" else 1.0
    for d in ds:
        K = hop.K_c * (1 + sign * d)
        pred = hop.force_amplitude(K)
        beta = abs(hop.dbeta_dK * (K - hop.K_c))  # the linear rate at K (1/t0)
        row: dict[str, Any] = {"d": d, "K": K, "predicted": pred}
        if sign < 0:
            r = settle_two_starts(lambda s, p, K=K: reduced_amplitudes(fld, hop, K, s, p), pred,
                                  1 / (2 * beta * T), max_periods)
            row.update(r)
        else:
            periods = int(max(20, min(60, 2.0 / (beta * T))))
            failed: list[float] = []

            def grows(s: float, K: float = K, periods: int = periods,
                      failed: list[float] = failed) -> tuple[bool, np.ndarray]:
                try:
                    a = reduced_amplitudes(fld, hop, K, s, periods)
                except (RuntimeError, ValueError):  # the solver failed: counted as growth
                    failed.append(s)
                    return True, np.array([s])
                return bool(a[-1] > a[1]), a

            r = threshold(grows, 0.8 * pred, 1.25 * pred, steps=steps)
            row.update(r)
            row["settled"] = r["bracketed"]
            # honest output: a growing end that is a solver failure (the slider leaving the
            # forward motion the reduction describes, or a numerical failure) is an assumption
            row["hi_by_failure"] = r["hi"] in failed
        row["ratio"] = row["amplitude"] / pred
        out["rows"].append(row)
    ok = [r for r in out["rows"] if r["settled"] and math.isfinite(r["amplitude"])]
    out["exponent"] = out["exponent_err"] = out["slip_exponent"] = math.nan
    if len(ok) >= 3:
        dd = [r["d"] for r in ok]
        out["exponent"], out["exponent_err"] = amplitude_exponent(dd, [r["amplitude"] for r in ok])
        out["slip_exponent"] = amplitude_exponent(dd, [r["amplitude"] / r["K"] for r in ok])[0]
    return out
