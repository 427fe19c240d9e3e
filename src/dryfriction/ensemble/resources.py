"""How much memory a trap-ensemble run will hold, estimated before any work.

:func:`check_run` is called by :func:`~dryfriction.ensemble.driving.simulate` and by the protocol
parser, so that a run that cannot fit is refused in one line before anything is allocated. All
arithmetic is in floats: an absurd input gives an estimate of ``inf``, never an
``OverflowError``.

The per-item costs were measured with :mod:`tracemalloc` (peak over a run, NumPy 2, CPython
3.12) and rounded up:

* a sample costs about 456 bytes: the recorder's row (a tuple of 11 Python floats), the
  sampling grid and the columns it becomes;
* a pair in the buffer around the slider costs 17 bytes held: position (8), birth time (8) and
  state (1). The initial population is placed in chunks and a move of the buffer carries over
  only the pairs in contact, so neither holds two buffers at once: the peak of a run is about
  16 bytes per pair of the estimate below (which counts a little more than the buffer holds);
  it was 58 in an earlier version (68 bytes per pair at the start-up of a steady population);
* a snapshot holds 6 float arrays over the traps in contact.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..validation import check_memory, check_time
from .drives import CLOCK_MAX, ForceDrive, SpringDrive
from .population import Initial, Track, TrapModel
from .result import FORCE_HOLD_LOG_STEP, Output, sample_interval
from .thermal import SUBSTEP_SLIP

__all__ = ["BYTES_PER_SAMPLE", "BYTES_PER_TRAP", "CLOCK_MAX", "RunEstimate", "check_run",
           "estimate_run", "estimate_work"]

SECONDS_PER_CALL = 15e-6
"""Seconds of one call of the compiled kernel with the Python around it, without its pairs
(measured 16-25 us on spring drives with ~750 traps in contact, less the pairs' share)."""
SECONDS_PER_PAIR = 10e-9
"""Seconds per trap in contact per kernel call (measured 13-18 ns)."""
SECONDS_PER_PLACED_PAIR = 4e-8
"""Seconds per pair of the buffer to place the initial population (``Ensemble._place_initial``,
once per run; measured 2e-8 at 1e5 and 4.6e-8 at 1e6 pairs per ``a0``, steady start: 0.06 s
and 1.43 s of CPU). Without it a run of 1e6 pairs per ``a0`` was estimated at 3.5 s for 5.3 s
of CPU."""

BYTES_PER_SAMPLE = 480.0
"""Peak bytes per recorded sample (measured 456)."""
MAX_SAMPLES = 2e6
"""Most samples one run records (ours): past this the run is refused before any work, however
much memory there is, because recording and writing them is what takes the time (about 13 µs
a sample on the development machine: 2e6 samples are half a minute and a CSV of ~200 MB)."""
BYTES_PER_TRAP = 18.0
"""Peak bytes per estimated pair in the buffer (measured 15-16)."""
BYTES_PER_SNAPSHOT_TRAP = 6 * 8.0
"""Bytes per trap in contact in one snapshot (six float arrays)."""

_MAX_REACH = 1e3  # a0: the cap population.Ensemble puts on the initial reach


@dataclass(frozen=True)
class RunEstimate:
    """What a run will hold at its peak.

    Attributes
    ----------
    samples : float
        Recorded samples (an upper bound; ``inf`` if it overflows).
    traps : float
        Pairs in the buffer that follows the slider.
    active : float
        Traps in contact (what a snapshot records).
    snapshots : int
        Population snapshots requested.
    """

    samples: float
    traps: float
    active: float
    snapshots: int

    @property
    def sample_bytes(self) -> float:
        return self.samples * BYTES_PER_SAMPLE

    @property
    def trap_bytes(self) -> float:
        return self.traps * BYTES_PER_TRAP

    @property
    def snapshot_bytes(self) -> float:
        return self.snapshots * self.active * BYTES_PER_SNAPSHOT_TRAP

    @property
    def total_bytes(self) -> float:
        return self.sample_bytes + self.trap_bytes + self.snapshot_bytes


def _reach(model: TrapModel, initial: Initial, horizon: float) -> float:
    """Slip (a0) ahead of the slider over which traps can be in contact (as population.py)."""
    D = max(1.0, model.trap.y_c)
    law = model.law
    reach = D * float(law.radius(min(max(horizon, 1.0), 1e12)))
    if initial.kind == "steady":
        r = D
        for _ in range(100):
            r = min(D * float(law.radius((r + 1.0) / float(initial.velocity or 1.0))), _MAX_REACH)
        reach = max(reach, r)
    return min(reach, _MAX_REACH) + 1.0


def estimate_run(model: TrapModel, track: Track, initial: Initial, drive: object,
                 output: Output) -> RunEstimate:
    """Estimate the samples and pairs a run of :func:`~.driving.simulate` will hold.

    Parameters
    ----------
    model, track, initial, drive, output
        As :func:`~.driving.simulate` takes them (``drive`` a velocity, force or spring drive).

    Returns
    -------
    RunEstimate
    """
    D = max(1.0, model.trap.y_c)
    step_slip = 0.0
    if isinstance(drive, ForceDrive):
        horizon = drive.hold + drive.max_force / drive.rate
        if output.every is not None:
            samples = (drive.hold + drive.max_force / drive.rate) / output.every
        else:
            k_c = model.trap.contact_stiffness
            # the hold on its geometric grid (result.force_hold_grid), then the ramp
            samples = (2.0 + math.log1p(drive.hold) / FORCE_HOLD_LOG_STEP
                       + drive.max_force / (float(output.every_slip) * k_c))
        step_slip = 2.0 * D + 2.0  # a jump stops within the reach (driving._max_reach)
    else:
        program = drive.program  # type: ignore[attr-defined]
        horizon = program.total_time
        samples = 0.0
        for seg in program.segments:
            # segment_grid's count, in floats: no OverflowError before the refusal
            n = max(1.0, seg.time / sample_interval(seg.velocity, output))
            samples += n
            step_slip = max(step_slip, abs(seg.velocity) * seg.time / n)
    samples += 2.0 + len(output.snapshots)
    reach = _reach(model, initial, horizon)
    margin = 8.0 + 2.0 * D  # population.Ensemble._margin
    lam = track.traps_per_a0
    traps = lam * (2.0 * (reach + margin + 2.0) + step_slip) + 4.0
    if track.layout == "random":
        traps += 2.0 * 1024  # whole blocks
    active = lam * (reach + 1.0) + 2.0
    return RunEstimate(samples, traps, active, len(output.snapshots))


def estimate_work(model: TrapModel, track: Track, drive: object, est: RunEstimate
                  ) -> tuple[float, float, str]:
    """``(calls, seconds, kind)``: a lower bound of the kernel calls a run makes, their time,
    and what sets it (``"samples"``, ``"events"`` or ``"steps"``).

    The bound (ours): a velocity drive makes one call a sample; force control at least two
    (the creep at fixed position, the jump); the quasi-static spring two per sample and creep
    step (:data:`.thermal.SUBSTEP_SLIP` of the spacing with the direct effect) and one per
    event, every trap passed entering and leaving contact once (``2 lambda`` events per ``a0``
    of load-point travel); the inertial spring one per time step, at least the duration over
    the longest step ``min(0.05 * 2 pi sqrt(M/(K + k_c)), M/eta)``, and at least the travel over the
    longest slip of a step, ``spacing/4`` (:mod:`.driving`). Each call costs
    :data:`SECONDS_PER_CALL` plus :data:`SECONDS_PER_PAIR` per trap in contact
    (``est.active``); placing the initial population adds :data:`SECONDS_PER_PLACED_PAIR` per
    pair of the buffer (``est.traps``). Floats throughout.
    """
    lam = track.traps_per_a0
    # the sampling steps: the estimate's samples less its allowance for the first and last
    # sample, the snapshots and a part step per segment
    segments = 0 if isinstance(drive, ForceDrive) else len(drive.program.segments)  # type: ignore
    steps = max(est.samples - 2.0 - est.snapshots - segments, 1.0)
    calls, kind = steps, "samples"
    if isinstance(drive, ForceDrive):
        calls = 2.0 * steps
    elif isinstance(drive, SpringDrive):
        prog = drive.program
        travel = float(sum(abs(s.velocity) * s.time for s in prog.segments))
        if drive.mass == 0.0:
            sub = travel * lam / SUBSTEP_SLIP if model.direct > 0.0 else 0.0
            events = 2.0 * lam * travel
            calls = 2.0 * (steps + sub) + events
            kind = "events" if events > 2.0 * (steps + sub) else "samples"
        else:
            k_c = model.trap.contact_stiffness
            dt = 0.05 * 2.0 * math.pi * math.sqrt(drive.mass / (drive.stiffness + k_c))
            if drive.damping > 0.0:
                dt = min(dt, drive.mass / drive.damping)
            calls = max(prog.total_time / dt, travel * lam / 0.25)
            kind = "steps"
    seconds = calls * (SECONDS_PER_CALL + SECONDS_PER_PAIR * est.active)
    return calls, seconds + SECONDS_PER_PLACED_PAIR * est.traps, kind


def _check_clock(model: TrapModel, drive: object, qualified: bool) -> None:
    """Refuse a run longer than :data:`CLOCK_MAX`, naming the key that makes it so long (a
    force drive refuses its own hold and rate when it is made: it has no program)."""
    d = "drive." if qualified else ""
    if not hasattr(drive, "program"):
        return
    segs = drive.program.segments  # type: ignore[attr-defined]
    total = float(sum(s.time for s in segs))
    if not total > CLOCK_MAX:
        return
    i = max(range(len(segs)), key=lambda j: segs[j].time)
    raise ValueError(f"{d}segments[{i}] (velocity {segs[i].velocity:g} a0/t0) makes the run last "
                     f"{total:.3g} t0, over the {CLOCK_MAX:.3g} t0 (2^46) within which its "
                     "clock resolves the traps' ages (to 1/64 t0); raise the velocity or "
                     "shorten the segment")


def check_run(model: TrapModel, track: Track, initial: Initial, drive: object, output: Output,
              *, qualified: bool = False) -> RunEstimate:
    """Refuse a run whose estimate is over :func:`dryfriction.validation.memory_limit`, whose
    duration is over :data:`CLOCK_MAX`, or whose work (:func:`estimate_work`) is over
    :func:`dryfriction.validation.time_limit`.

    Parameters
    ----------
    qualified : bool
        Name the keys as a protocol file spells them (``output.every``,
        ``ensemble.traps_per_a0``) rather than as the API's arguments.

    Raises
    ------
    ValueError
        One line with the estimate, the limit and the key to change; the key named is that of
        the largest part of the estimate.
    """
    if isinstance(drive, ForceDrive) and output.every_slip is not None:
        # the ramp's time step; below the rounding of the run's clock the ramp cannot advance
        dt = float(output.every_slip) * model.trap.contact_stiffness / drive.rate
        if not dt > 1e-12 * max(1.0, drive.hold):
            key = ("drive." if qualified else "") + "rate"
            raise ValueError(
                f"{key} = {drive.rate:g} is out of range with every_slip = "
                f"{output.every_slip:g}: the force step of one sample takes {dt:.1e} t0, below "
                f"the clock's rounding at t = {drive.hold:g}; lower {key} or raise every_slip")
    est = estimate_run(model, track, initial, drive, output)
    out = "output." if qualified else ""
    lam_key = ("ensemble." if qualified else "") + "traps_per_a0"
    parts = {"samples": est.sample_bytes, "traps": est.trap_bytes,
             "snapshots": est.snapshot_bytes}
    worst = max(parts, key=lambda k: parts[k] if not math.isnan(parts[k]) else math.inf)
    if worst == "samples":
        key = "every" if output.every is not None else "every_slip"
        value = output.every if output.every is not None else output.every_slip
        what = f"{out}{key} = {value:g} gives {est.samples:.1e} samples"
        hint = f"raise {out}{key} (or shorten the drive)"
    elif worst == "traps":
        what = (f"{lam_key} = {track.traps_per_a0:g} keeps {est.traps:.1e} pairs around the "
                "slider")
        hint = f"lower {lam_key}"
    else:
        what = (f"{out}snapshots: {est.snapshots} snapshots of {est.active:.1e} traps in "
                "contact")
        hint = f"ask for fewer {out}snapshots or lower {lam_key}"
    check_memory(what, est.total_bytes, hint)
    if est.samples > MAX_SAMPLES:
        key = "every" if output.every is not None else "every_slip"
        value = output.every if output.every is not None else output.every_slip
        raise ValueError(f"{out}{key} = {value:g} gives {est.samples:.1e} samples, over the "
                         f"{MAX_SAMPLES:.0e} one run records (minutes of recording and a CSV "
                         f"of ~{est.samples * 100 / 1e9:.2g} GB); raise {out}{key} (or shorten "
                         "the drive)")
    _check_clock(model, drive, qualified)
    calls, seconds, kind = estimate_work(model, track, drive, est)
    pair_bound = SECONDS_PER_PAIR * est.active > SECONDS_PER_CALL \
        or SECONDS_PER_PLACED_PAIR * est.traps > 0.5 * seconds  # the placement dominates
    if kind == "steps":
        what = (f"{('drive.' if qualified else '')}mass = {drive.mass:g} over "  # type: ignore
                f"{drive.program.total_time:.3g} t0 of drive needs {calls:.1e} "  # type: ignore
                f"time steps of {est.active:.0f} traps in contact")
        d = "drive." if qualified else ""
        hint = (f"shorten {d}segments (or raise their velocity), raise {d}mass"
                + (f" or lower {lam_key}" if pair_bound else ""))
    elif kind == "events" or pair_bound:
        what = (f"{lam_key} = {track.traps_per_a0:g} gives {calls:.1e} kernel calls over "
                f"{est.active:.0f} traps in contact")
        hint = f"lower {lam_key} (or shorten the drive)"
    else:
        key = "every" if output.every is not None else "every_slip"
        value = output.every if output.every is not None else output.every_slip
        what = f"{out}{key} = {value:g} gives {calls:.1e} kernel calls"
        hint = f"raise {out}{key} (or shorten the drive)"
    check_time(what, seconds, hint)
    return est
