"""Driving the trap ensemble: velocity programs, force ramps, a spring-pulled slider
(docs/model.md §6).

Reduced units: lengths ``a0``, times ``t0``, forces ``F_el``; stiffness ``F_el/a0``, mass
``F_el t0^2/a0``, damping ``F_el t0/a0``. The reported friction is ``mu = mu_el F/F_el``.

One orchestrating call, ``simulate(model, drive, initial, output)`` (the shape of both laws,
:mod:`dryfriction.simulation`), composes small frozen objects: a
:class:`~dryfriction.ensemble.population.TrapModel`, a drive (:class:`VelocityDrive`,
:class:`ForceDrive` or :class:`SpringDrive`, :mod:`.drives`), an
:class:`~dryfriction.ensemble.population.Initial` population on its
:class:`~dryfriction.ensemble.population.Track`, and an :class:`Output` sampling.

Integrators (ours)
------------------
* **Prescribed motion** (:class:`VelocityDrive`). ``X(t)`` is piecewise linear, so the state at
  any sampling time is exact: births are interpolated to the instant ``p = -1`` is crossed and a
  trap dies at the first sample after its ``w`` passes the spinodal. A hold is one step, however
  long (ageing is a function of time; ``|w|`` only shrinks at fixed ``p``). Steps end on every
  segment boundary and requested snapshot time. The reported peak is the largest *sampled*
  force: sample finely (``every_slip``) to resolve it.
* **Quasi-static slider** (:class:`ForceDrive`, and :class:`SpringDrive` with ``mass = 0``). At
  each sampling time the ages are advanced at fixed ``X``, then the slider jumps, ages frozen, to
  the next stable equilibrium of ``A - K X = F(X)`` (``K`` = spring stiffness, 0 under force
  control) in the direction of the unbalanced force. The jump goes event by event: between two
  spinodals ``F(X)`` is continuous (entries and zero-force exits are continuous), so each stretch
  is checked at its end and the root found inside it (:mod:`.balance`). The force just before
  each spinodal is the local peak, so the static threshold is exact up to the steps of the applied
  force, at most ``RAMP_FORCE_STEP`` whatever the sampling. Under force control, a jump longer
  than the reach of every trap in contact plus one full fresh population (``1 + max(1, y_c)``) is
  a runaway: no equilibrium is left, and the run stops there. A force hold sampled in slip is
  stepped on a geometric grid of the age (:func:`.result.force_hold_grid`): the threshold depends
  on the creep back meanwhile.
* **Inertial slider** (:class:`SpringDrive`, ``mass > 0``):
  ``M X'' = K (X_pull - X) - F - eta X'`` by velocity Verlet with the force evaluated exactly
  from positions and ages each step; ``dt <= 0.05 * 2 pi sqrt(M / (K + k_c))`` (``k_c`` the
  fresh contact stiffness, eqs. 13-14), ``dt <= M/eta`` (the damping enters the velocity
  predictor explicitly, unstable for ``eta dt/M > 2``: an overdamped slider blew up) and a slip
  per step ``<= 1/(4 lambda)`` so each trap death is resolved.

Direct effect (``model.direct = A > 0``, :mod:`dryfriction.theory.direct`; ours)
---------------------------------------------------------------------------------
The friction force is ``g(V) F(X, ages)``: the population's force (the compiled kernel,
unchanged) times the junction strength at the slider's present velocity ``V``.

* **Prescribed motion**: ``V`` is the velocity of the segment that ends at the sample (holds:
  ``g(0) = 0``, the regularised form); a velocity step multiplies the force at once by
  ``g(V2)/g(V1)``. The first sample uses the first segment's velocity.
* **Quasi-static slider** (force drive, spring drive with ``mass = 0``): the force now depends
  on the velocity, so there are no jumps: within a step ``[t0, t1]`` the slider moves from
  ``X0`` to the ``X`` where ``A - K X = g((X - X0)/(t1 - t0)) F(X)`` (backward Euler in the
  velocity, ages at ``t1``, like quasi-static rate-and-state). With ``g(0) = 0`` the left side
  decides the direction and the same stretch-by-stretch bracketing and root as the jumps
  finds the first root. A root farther than the reach of the contacts (force drive) is still
  reported as a runaway. The spring drive takes several such steps per sample, each covering
  at most a quarter of the trap spacing of load-point travel (:mod:`.thermal`): a coarser step
  sees the population's sawtooth at one phase only and, on a regular track sampled at a
  multiple of its spacing, locks onto it. The force drive takes one step per sample.
* **Inertial slider**: ``M V' = K (X_pull - X) - eta V - g(V) F``, stiff near rest (``g'`` up
  to ``A e^{1/A}/(2 V_ref)``): :func:`.thermal.inertial_velocity`, :func:`.thermal.drift`.

Interruption: with ``on_interrupt="partial"`` a Ctrl-C (``KeyboardInterrupt``) ends the run at
the last completed step and the result is marked ``partial``.
"""

from __future__ import annotations

import functools
import inspect
import math
import time as _time
import warnings
from collections.abc import Callable, Iterator
from dataclasses import asdict, replace
from typing import Any

import numpy as np

from ..results import check_physical
from ..simulation import OldSimulatorFormWarning, check_parts
from ..validation import check_choice, check_scalar
from .balance import add_events, equilibrate, events
from .drives import MASS_MIN, STIFFNESS_MAX, Drive, ForceDrive, SpringDrive, VelocityDrive
from .population import Ensemble, Initial, Track, TrapModel
from .resources import check_run
from .result import (
    COLUMNS,
    Output,
    Recorder,
    SimulationResult,
    check_snapshots,
    position_function,
    segment_grid,
)
from .thermal import (
    apply_strength,
    creep_substeps,
    drift,
    inertial_velocity,
    initial_velocity,
    velocity_scale,
    with_strength,
)

__all__ = [
    "Drive",
    "MASS_MIN",
    "STIFFNESS_MAX",
    "VelocityDrive",
    "ForceDrive",
    "SpringDrive",
    "Output",
    "SimulationResult",
    "COLUMNS",
    "simulate",
    "continue_spring",
]

Progress = Callable[[float], None]


RAMP_FORCE_STEP: float = 0.005
"""Largest increase of the applied force (``F_el``) between two equilibria of a force ramp
(ours): a coarser sampling is stepped internally. The threshold then no longer depends on the
sampling: with the static-threshold example it agrees to 3e-8 with the sampling's force step
0.0035 F_el (every_slip = 0.005)."""


# ---------------------------------------------------------------- helpers


def _progress_caller(progress: Progress | None, total: float) -> Callable[[float], None]:
    if progress is None or not (total > 0):
        return lambda _t: None
    last = [0.0]

    def call(t: float) -> None:
        now = _time.monotonic()
        if now - last[0] > 0.05:
            last[0] = now
            progress(min(1.0, t / total))

    return call


def _lattice(ens: Ensemble) -> float | None:
    """The trap spacing (``a0``) of a regular track, which the sampling must not alias."""
    return ens.track.spacing if ens.track.layout == "regular" else None


def _max_reach(ens: Ensemble) -> float:
    """Slip (``a0``) after which every trap now in contact has surely left it, frozen ages."""
    age = ens.t - ens.oldest_birth
    return max(1.0, ens.y_c) * float(ens.radius(age)) + 1.0


# ---------------------------------------------------------------- the drivers


def _run_velocity(ens: Ensemble, drive: VelocityDrive, output: Output, rec: Recorder,
                  tick: Callable[[float], None], info: dict[str, Any]) -> None:
    prog = drive.program
    grid = segment_grid(prog, output, _lattice(ens))
    xs = prog.position(grid)
    snaps = list(output.snapshots)
    # velocity of the segment that holds each step's midpoint, all at once (a lookup per
    # step cost a sixth of a small ensemble's run); a step starts where the last one ended
    t_prev = np.concatenate(([ens.t], grid[1:-1]))
    k = np.searchsorted(prog.times, 0.5 * (t_prev + grid[1:]), side="right") - 1
    vs = prog.velocities[np.clip(k, 0, len(prog.segments) - 1)].tolist()
    for t1, x1, v in zip(grid[1:].tolist(), xs[1:].tolist(), vs, strict=True):
        o = ens.advance(x1, t1)
        rec.add(ens, with_strength(ens, o, v), v, events=events(o))
        while snaps and snaps[0] <= t1 + 1e-12:
            snaps.pop(0)
            rec.snap(ens)
        tick(t1)


def _run_force(ens: Ensemble, drive: ForceDrive, output: Output, rec: Recorder,
               tick: Callable[[float], None], info: dict[str, Any]) -> None:
    f0 = ens.observe().force
    if output.every is not None:
        dt_ramp = output.every
    else:
        dt_ramp = float(output.every_slip) * ens.model.trap.contact_stiffness / drive.rate
    hold_grid = output.hold_times(drive.hold)
    snaps = list(output.snapshots)
    threshold, t_threshold, runaway = f0, math.nan, False

    def times() -> Iterator[float]:
        h = drive.hold
        if h > 0:
            yield from (float(t) for t in hold_grid)
        j = 1
        while True:
            yield h + j * dt_ramp
            j += 1

    for t1 in times():
        f_app = f0 + drive.rate * max(0.0, t1 - drive.hold)
        x_before, t_before = ens.x, ens.t
        # the ramp in steps of at most RAMP_FORCE_STEP, whatever the sampling: one coarse
        # step would age the contacts at the last equilibrium for the whole sample interval
        # before the force is applied, and the threshold would grow with every_slip (issue 24)
        ramp = drive.rate * (t1 - max(t_before, drive.hold))
        n_sub = max(1, math.ceil(ramp / RAMP_FORCE_STEP)) if ramp > 0.0 else 1
        # every substep must move the clock (check_run's rounding limit, at the substeps'
        # start: the runaway comes within ~threshold/RAMP_FORCE_STEP of them, long before t1)
        n_sub = min(n_sub, max(1, int((t1 - t_before) / (1e-12 * max(1.0, t_before)))))
        ev, jump_ev = (0, 0, 0), (0, 0, 0)
        j = 0
        while True:
            j += 1
            tj = t1 if j >= n_sub else t_before + (t1 - t_before) * (j / n_sub)
            fj = f_app if j >= n_sub else f0 + drive.rate * max(0.0, tj - drive.hold)
            t_sub = ens.t
            ev = add_events(ev, events(ens.advance(ens.x, tj)))
            max_slip = _max_reach(ens) + max(1.0, ens.y_c) + 1.0 + 2.0 * ens.track.spacing
            extreme, runaway, sub_ev = equilibrate(ens, fj, 0.0, max_slip,
                                                   velocity_scale(ens, tj - t_sub))
            jump_ev = add_events(jump_ev, sub_ev)
            threshold = max(threshold, extreme)
            if runaway or j >= n_sub or fj >= drive.max_force:
                break
        if runaway:
            t_threshold = tj
            break
        if j < n_sub:  # the safety stop within the sample: it ends the run here
            t1, f_app = tj, fj
        o = ens.observe()
        v = (ens.x - x_before) / (t1 - t_before)
        rec.add(ens, with_strength(ens, o, v), v, f_applied=f_app, events=add_events(ev, jump_ev))
        while snaps and snaps[0] <= t1 + 1e-12:
            snaps.pop(0)
            rec.snap(ens)
        tick(t1)
        if f_app >= drive.max_force:
            break
    info.update({
        "threshold_mu": ens.model.mu_el * threshold,
        "threshold_t": t_threshold,
        "runaway": runaway,
    })


def _run_spring(ens: Ensemble, drive: SpringDrive, output: Output, rec: Recorder,
                tick: Callable[[float], None], info: dict[str, Any], *,
                velocity: float = 0.0, spring_force: float | None = None) -> None:
    """Spring drive from the ensemble's present state (time ``ens.t``, position ``ens.x``).

    The load point starts where the spring pulls with ``spring_force`` (default: the present
    friction force, i.e. at rest in equilibrium); an inertial slider starts at ``velocity``.
    The program's time 0 is ``ens.t`` (0 for :func:`simulate`).
    """
    prog = drive.program
    K = drive.stiffness
    o = ens.observe()
    t_start = ens.t
    x_pull0 = ens.x + (o.force if spring_force is None else spring_force) / K
    grid = segment_grid(prog, output, _lattice(ens))
    xp = x_pull0 + (prog.position(grid) - prog.x0)
    grid = grid + t_start
    snaps = list(output.snapshots)
    jumps: list[float] = []
    if drive.mass == 0.0:
        xp_prev = float(xp[0])
        for t1, xp1 in zip(grid[1:], xp[1:], strict=True):
            x_before, t_before = ens.x, ens.t
            n, ev = creep_substeps(ens, float(xp1) - xp_prev), (0, 0, 0)
            for j in range(1, n + 1):  # n = 1 (one jump) without the direct effect
                tj = float(t1) if j == n else t_before + (float(t1) - t_before) * j / n
                xj = float(xp1) if j == n else xp_prev + (float(xp1) - xp_prev) * j / n
                x_sub, t_sub = ens.x, ens.t
                ev = add_events(ev, events(ens.advance(ens.x, tj)))
                _, _, jump_ev = equilibrate(ens, K * xj, K, 1e9, velocity_scale(ens, tj - t_sub))
                ev = add_events(ev, jump_ev)
            xp_prev = float(xp1)
            jumps.append(ens.x - x_before)
            o = ens.observe()
            v = (ens.x - x_sub) / (tj - t_sub)  # the last step's: the velocity g is taken at
            rec.add(ens, with_strength(ens, o, v), v, x_pull=float(xp1), events=ev)
            while snaps and snaps[0] <= t1 - t_start + 1e-12:
                snaps.pop(0)
                rec.snap(ens)
            tick(float(t1))
    else:
        M, eta = drive.mass, drive.damping
        k_c = ens.model.trap.contact_stiffness
        dt_osc = 0.05 * 2.0 * math.pi * math.sqrt(M / (K + k_c))
        if eta > 0.0:  # the damping is explicit in the Verlet predictor: stable for eta dt/M < 2
            dt_osc = min(dt_osc, M / eta)
        dx_max = 0.25 * ens.track.spacing
        V = float(velocity)
        F, f_pop = with_strength(ens, o, V).force, o.force
        direct = ens.model.direct > 0.0
        position = position_function(prog)

        def pull(t: float) -> float:
            return x_pull0 + position(t - t_start) - prog.x0

        def accel(x: float, v: float, f: float, t: float) -> float:
            xpl = pull(t)
            return (K * (xpl - x) - f - eta * v) / M

        a = accel(ens.x, V, F, t_start)
        for t1, xp1 in zip(grid[1:], xp[1:], strict=True):
            x_before, ev = ens.x, (0, 0, 0)
            while ens.t < t1:
                dt = min(dt_osc, float(t1) - ens.t)
                if V != 0.0:
                    dt = min(dt, dx_max / abs(V))
                if t1 - (ens.t + dt) < 1e-12 * max(1.0, t1):
                    dt = float(t1) - ens.t
                w = drift(ens.model, V, dt, M, eta, f_pop) if direct else 0.5
                x_new = ens.x + V * dt + w * a * dt * dt
                t_new = float(t1) if dt == float(t1) - ens.t else ens.t + dt
                ob = ens.advance(x_new, t_new)
                ev = add_events(ev, events(ob))
                if direct:  # implicit in V: the junction strength is stiff near rest
                    f_pop = ob.force
                    V, g = inertial_velocity(ens.model, V, M * a, dt, M, eta,
                                             K * (pull(t_new) - x_new), f_pop)
                    ob = apply_strength(ob, g)
                    a = accel(x_new, V, ob.force, t_new)
                else:
                    a_new = accel(x_new, V + a * dt, ob.force, t_new)
                    V = V + 0.5 * (a + a_new) * dt
                    a = a_new
                o = ob
            jumps.append(ens.x - x_before)
            rec.add(ens, o, V, x_pull=float(xp1), events=ev)
            while snaps and snaps[0] <= t1 - t_start + 1e-12:
                snaps.pop(0)
                rec.snap(ens)
            tick(float(t1))
    thr = 0.5  # a0: a slip that renews a good part of the contacts (ours)
    j = np.abs(np.asarray(jumps))
    info.update({
        "slip_event_threshold": thr,
        "slip_events": int(np.sum(j > thr)) if drive.mass == 0.0 else _count_slips(rec, thr),
        "largest_sample_slip": float(j.max()) if j.size else 0.0,
    })


def _count_slips(rec: Recorder, thr: float) -> int:
    """Slip events of an inertial run (ours): maximal runs of samples whose velocity exceeds
    three times the mean slider velocity and that slide more than ``thr`` in total."""
    if len(rec.rows) < 3:
        return 0
    a = np.array([(r[0], r[1], r[2]) for r in rec.rows])
    t, x, v = a[:, 0], a[:, 1], a[:, 2]
    v_mean = abs(x[-1] - x[0]) / (t[-1] - t[0]) if t[-1] > t[0] else 0.0
    fast = v > 3.0 * v_mean
    count, start = 0, -1
    for i in range(len(fast) + 1):
        f = bool(fast[i]) if i < len(fast) else False
        if f and start < 0:
            start = max(i - 1, 0)
        elif not f and start >= 0:
            if x[min(i, len(x) - 1)] - x[start] > thr:
                count += 1
            start = -1
    return count


# ---------------------------------------------------------------- the orchestrating call


def simulate(
    model: TrapModel,
    drive: Drive,
    initial: Initial,
    output: Output,
    *,
    progress: Progress | None = None,
    on_interrupt: str = "raise",
) -> SimulationResult:
    """Run the trap ensemble under a drive and sample it (the trap model's
    ``dryfriction.simulate``, :mod:`dryfriction.simulation`).

    Parameters
    ----------
    model : TrapModel
        Traps, creep law, direct effect.
    drive : VelocityDrive, ForceDrive or SpringDrive
        What moves the slider.
    initial : Initial
        Initial population (made at ``t = 0``, ``X = 0``) and its ``track`` (pair positions).
    output : Output
        Sampling.
    progress : callable, optional
        Called with the fraction of the run done (0..1), at most every 50 ms.
    on_interrupt : {"raise", "partial"}
        On ``KeyboardInterrupt``: re-raise, or stop and return the samples so far with
        ``info["partial"] = True``.

    Returns
    -------
    SimulationResult
        The first sample is the initial state at ``t = 0``.

    Raises
    ------
    ValueError
        Bad input, or a run whose samples, pairs and snapshots would not fit the memory limit
        (:func:`dryfriction.validation.memory_limit`), before any work.

    Notes
    -----
    The old form ``simulate(model, track, initial, drive, output)`` still works for one
    release and warns (:class:`~dryfriction.simulation.OldSimulatorFormWarning`).
    """
    check_parts("cv", drive=drive, initial=initial, output=output)
    if not isinstance(initial, Initial):
        raise ValueError(f"initial = {initial!r} is not allowed: an Initial (the population "
                         "and its track)")
    if initial.track is None:
        raise ValueError("initial.track is missing: the run needs the pairs' positions, e.g. "
                         "Initial('rest', track=Track(traps_per_a0=100))")
    if not isinstance(output, Output):
        raise ValueError(f"output = {output!r} is not allowed: an Output (every or every_slip)")
    track = initial.track
    check_choice("on_interrupt", on_interrupt, ("raise", "partial"))
    if isinstance(drive, ForceDrive):
        horizon = drive.hold + drive.max_force / drive.rate
        total = drive.hold + 2.0 / drive.rate
    elif isinstance(drive, (VelocityDrive, SpringDrive)):
        horizon = total = drive.program.total_time
    else:
        raise ValueError(f"drive = {drive!r} is not allowed: VelocityDrive, ForceDrive or "
                         "SpringDrive")
    check_snapshots(drive, output)
    if model.direct and not isinstance(drive, ForceDrive):
        back = [i for i, v in enumerate(drive.program.velocities) if v < 0.0]
        if back:  # g(V) is odd and the population's force changes sign with V already, so
            # the product would keep the forward sign (tests/ensemble/test_invariants.py)
            raise ValueError(
                f"segments[{back[0]}].velocity = {drive.program.velocities[back[0]]:g} is out "
                "of range with the direct effect: allowed >= 0 (sliding back is modelled only "
                "for the athermal model, direct = 0)")
    check_run(model, track, initial, drive, output)
    ens = Ensemble(model, track, initial, x0=0.0, age_horizon=min(horizon, 1e12))
    rec = Recorder(model.mu_el)
    v0 = initial_velocity(model, initial, float(drive.program.velocities[0])
                          if isinstance(drive, VelocityDrive) else None)
    o = with_strength(ens, ens.observe(), v0)
    spring = isinstance(drive, SpringDrive)  # it starts in steady sliding at v0 (damper too)
    f_spring0 = o.force + drive.damping * v0 if spring else math.nan  # type: ignore[union-attr]
    x_pull0 = ens.x + f_spring0 / drive.stiffness if spring else math.nan  # type: ignore
    f_app0 = o.force if isinstance(drive, ForceDrive) else math.nan
    rec.add(ens, o, v0, x_pull=x_pull0, f_applied=f_app0)
    # with the direct effect the spring balances the friction at v0, an inertial slider at v0
    extra = {"spring_force": f_spring0, **({"velocity": v0} if drive.mass > 0.0 else {})
             } if model.direct and spring else {}  # type: ignore[union-attr]
    if output.snapshots and output.snapshots[0] == 0.0:
        rec.snap(ens)
        output = Output(output.every, output.every_slip, output.snapshots[1:])
    info: dict[str, Any] = {"partial": False, "regime": model.trap.regime.value}
    tick = _progress_caller(progress, total)
    runner = {VelocityDrive: _run_velocity, ForceDrive: _run_force, SpringDrive: _run_spring}
    try:
        runner[type(drive)](ens, drive, output, rec, tick, info, **extra)  # type: ignore
    except KeyboardInterrupt:
        if on_interrupt == "raise":
            raise
        info["partial"] = True
    if progress is not None:
        progress(1.0)
    if isinstance(drive, ForceDrive) and not info["partial"]:
        # a ramp ends at its runaway, which no check can place before the run: say which
        # snapshots it did not reach rather than drop them silently
        late = [s for s in output.snapshots if s > ens.t + 1e-12]
        if late:
            info["snapshots_not_reached"] = late
    res = rec.result(info)
    # the one bounds check of both laws (results.check_physical): finite, time forward
    check_physical("trap-model run", res.t, res.x, res.v, res.mu, unit="a0")
    model_d = asdict(model)
    if model.direct == 0.0:  # the athermal model's record, as before the direct effect
        del model_d["direct"], model_d["v_ref"]
    info["parameters"] = {
        "model": model_d,
        "track": asdict(track),  # on its own, as before the track moved into the initial
        "initial": {k: v for k, v in asdict(initial).items() if k != "track"},
        "drive": _describe(drive),
    }
    return res


def _old_form(model: TrapModel, track: Track, initial: Initial, drive: Drive, output: Output,
              *, progress: Progress | None = None, on_interrupt: str = "raise") -> None:
    """The signature of the old form (in an earlier version), to bind a call against."""


_NEW_FORM, _OLD_FORM = inspect.signature(simulate), inspect.signature(_old_form)


def _accepting_old_form(run: Callable[..., SimulationResult]) -> Callable[..., SimulationResult]:
    """``run`` that also takes the old form ``(model, track, initial, drive, output)``, in any
    mix of positions and keywords, and warns (one release, CHANGELOG.md)."""

    @functools.wraps(run)
    def simulate(*args: Any, **kwargs: Any) -> SimulationResult:
        try:
            _NEW_FORM.bind(*args, **kwargs)
        except TypeError as exc:
            try:
                old = _OLD_FORM.bind(*args, **kwargs).arguments
            except TypeError:
                raise TypeError(f"simulate(): {exc}") from None
            warnings.warn(
                "simulate(model, track, initial, drive, output) is deprecated and will be "
                "removed in the next release: use simulate(model, drive, Initial(..., "
                "track=track), output), or dryfriction.simulate for either law",
                OldSimulatorFormWarning, stacklevel=2)
            initial = old["initial"]
            if isinstance(initial, Initial):
                initial = initial_with_track(initial, old["track"])
            options = {k: old[k] for k in ("progress", "on_interrupt") if k in old}
            return run(old["model"], old["drive"], initial, old["output"], **options)
        return run(*args, **kwargs)

    return simulate


simulate = _accepting_old_form(simulate)


def initial_with_track(initial: Initial, track: Track) -> Initial:
    """``initial`` on ``track`` (the old form's separate track); a different track already
    set is refused rather than silently replaced."""
    if initial.track is None:
        return replace(initial, track=track)
    if initial.track != track:
        raise ValueError(f"track = {track!r} is given twice, differently: initial.track = "
                         f"{initial.track!r}; give it once, in Initial(..., track=...)")
    return initial


def continue_spring(
    ensemble: Ensemble,
    drive: SpringDrive,
    output: Output,
    *,
    velocity: float = 0.0,
    spring_force: float | None = None,
) -> SimulationResult:
    """Go on pulling an existing ensemble with a spring drive (continuation, ours).

    The run starts from the ensemble's present state (its time, position and population; the
    ensemble is advanced in place, so successive calls continue one another), with the slider
    at ``velocity`` (``a0/t0``; inertial drive only) and the spring pulling with
    ``spring_force`` (``F_el``; default the present friction force, i.e. equilibrium). Keeping
    the spring force and the velocity of the previous run's end while changing ``stiffness``
    is a continuation in ``K`` with the mechanical state unchanged.

    Parameters
    ----------
    ensemble : Ensemble
        Population to drive (mutated).
    drive : SpringDrive
        Spring, mass, damping and load-point program (its time 0 is ``ensemble.t``).
    output : Output
        Sampling; snapshot times are counted from the start of this run.
    velocity : float
        Initial slider velocity, ``a0/t0``; must be 0 when ``drive.mass == 0``.
    spring_force : float, optional
        Initial spring force, ``F_el``.

    Returns
    -------
    SimulationResult
        The first sample is the state at the start (time ``ensemble.t``).
    """
    if not isinstance(drive, SpringDrive):
        raise ValueError(f"drive = {drive!r} is not allowed: a SpringDrive")
    velocity = check_scalar("velocity", velocity)
    if drive.mass == 0.0 and velocity != 0.0:
        raise ValueError(f"velocity = {velocity:g} is not allowed with mass = 0: the "
                         "quasi-static slider has no velocity state; allowed 0")
    if spring_force is not None:
        spring_force = check_scalar("spring_force", spring_force)
    check_run(ensemble.model, ensemble.track, ensemble.initial, drive, output)
    rec = Recorder(ensemble.model.mu_el)
    o = ensemble.observe()
    if drive.mass > 0.0:  # the friction at the starting velocity (direct effect)
        o = with_strength(ensemble, o, velocity)
    f_spring = o.force if spring_force is None else spring_force
    rec.add(ensemble, o, velocity, x_pull=ensemble.x + f_spring / drive.stiffness)
    info: dict[str, Any] = {"partial": False, "regime": ensemble.model.trap.regime.value}
    _run_spring(ensemble, drive, output, rec, lambda _t: None, info, velocity=velocity,
                spring_force=f_spring)
    return rec.result(info)


def _describe(drive: Drive) -> dict[str, Any]:
    d: dict[str, Any] = {"kind": {VelocityDrive: "velocity", ForceDrive: "force",
                                  SpringDrive: "spring"}[type(drive)]}
    for k, v in asdict(drive).items():
        if k == "program":
            continue
        d[k] = v
    prog = getattr(drive, "program", None)
    if prog is not None:
        d["segments"] = [{k: v for k, v in asdict(s).items() if v is not None}
                         for s in prog.segments]
    return d
