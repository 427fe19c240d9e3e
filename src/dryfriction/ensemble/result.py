"""What a trap-ensemble run produces: its sampling (:class:`Output`), the recorder that collects
the samples, and :class:`SimulationResult` (the shared schema of :mod:`dryfriction.results`).

Reduced units: lengths ``a0``, times ``t0``; friction ``mu = mu_el F/F_el``.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from .. import simulation
from ..program import VelocityProgram
from ..results import summarize
from ..validation import Array, check_range, check_scalar
from .population import Ensemble, Observables

__all__ = ["COLUMNS", "UNITS", "Output", "Recorder", "SimulationResult", "sample_interval",
           "position_function",
           "segment_grid", "force_hold_grid", "FORCE_HOLD_LOG_STEP"]


@dataclass(frozen=True)
class Output(simulation.Output):
    """Sampling of the time series: exactly one of ``every`` (``t0``) or ``every_slip`` (``a0``).

    Parameters
    ----------
    every : float, optional
        Sampling interval in time, ``> 0``.
    every_slip : float, optional
        Sampling interval in slip of the slider (velocity drive) or of the load point (spring),
        ``> 0``. Holds of a velocity or spring program are then a single step; a force hold
        (where the slider creeps) is stepped on a geometric grid of the age
        (:func:`force_hold_grid`). Under force control the force step of the ramp is
        ``every_slip`` times the fresh contact stiffness.
    snapshots : tuple of float
        Times (``t0``, ``>= 0``) at which the population is recorded. Velocity and spring
        drives step exactly onto them; under force control (whose ramp ends at an unknown
        time) a snapshot is taken at the first sample at or after the requested time.
    """

    law: ClassVar[str] = "cv"
    every: float | None = None
    every_slip: float | None = None
    snapshots: tuple[float, ...] = ()

    def hold_times(self, hold: float) -> Array:
        """A force hold's sampling times (:func:`force_hold_grid`): every ``every``, or on the
        geometric grid of the age when sampled in slip (the slip barely moves in a hold)."""
        return force_hold_grid(hold, self.every)

    def __post_init__(self) -> None:
        if (self.every is None) == (self.every_slip is None):
            raise ValueError("give exactly one of every (in t0) and every_slip (in a0)")
        if self.every is not None:
            object.__setattr__(self, "every", check_scalar("every", self.every, 0.0, lo_open=True))
        if self.every_slip is not None:
            v = check_scalar("every_slip", self.every_slip, 0.0, lo_open=True)
            object.__setattr__(self, "every_slip", v)
        snaps = check_range("snapshots", np.asarray(self.snapshots, float).ravel(), 0.0)
        object.__setattr__(self, "snapshots", tuple(sorted(float(s) for s in snaps)))


def check_snapshots(drive: Any, output: Output, *, qualified: bool = False) -> None:
    """Refuse a snapshot time after the run's end (it would be dropped silently).

    The end is the program's total time (velocity and spring drives) or, for a force ramp,
    the time it reaches ``max_force`` (a runaway ends it earlier: :func:`simulate` then lists
    the snapshots not reached in ``info["snapshots_not_reached"]``).

    Raises
    ------
    ValueError
        Naming ``snapshots`` (``output.snapshots`` when ``qualified``) and the run's end.
    """
    if not output.snapshots:
        return
    program = getattr(drive, "program", None)
    if program is None:  # a force drive (driving.ForceDrive)
        end = drive.hold + drive.max_force / drive.rate
        what = "the force ramp reaches max_force"
    else:
        end = program.total_time
        what = "the drive's program ends"
    last = output.snapshots[-1]
    if last > end * (1.0 + 1e-12):
        key = ("output." if qualified else "") + "snapshots"
        raise ValueError(f"{key}: the time {last:g} t0 is after the run's end: {what} at "
                         f"t = {end:g} t0; allowed 0 <= snapshot <= {end:g}")


COLUMNS: tuple[str, ...] = (
    "t", "x", "v", "mu", "n_active", "mean_age", "x_pull", "f_applied", "births", "spinodal",
    "exits",
)
UNITS: dict[str, str] = {
    "t": "t0", "x": "a0", "v": "a0/t0", "mu": "", "n_active": "", "mean_age": "t0",
    "x_pull": "a0", "f_applied": "", "births": "", "spinodal": "", "exits": "",
}
"""Unit of every column (reduced; ``f_applied`` is in ``mu`` units, counts are plain)."""


@dataclass
class SimulationResult(simulation.Result):
    """Time series of a run (NumPy arrays, reduced units) and what happened.

    Attributes
    ----------
    t, x, v : ndarray
        Time (``t0``), slider position (``a0``), slider velocity (``a0/t0``).
    mu : ndarray
        Friction ``mu_el F/F_el``.
    n_active, mean_age : ndarray
        Traps in contact and their mean age (``t0``).
    x_pull, f_applied : ndarray
        Load-point position (spring drive; NaN otherwise) and applied force in ``mu`` units
        (force drive; NaN otherwise).
    births, spinodal, exits : ndarray
        Pairs entering contact, spinodal events and pairs leaving contact past the edge of the
        bump (``|w| > 1``) during the step ending at each sample. In very strong pinning a
        spinodal event is a death, so ``births - spinodal - exits`` is the change of
        ``n_active``; in strong pinning it is ``births - exits``.
    snapshots : list of dict
        Population snapshots (``t``, ``x`` and the arrays of :meth:`Ensemble.snapshot`).
    info : dict
        Drive-specific scalars (threshold, runaway, ...), and ``partial``.
    """

    law: ClassVar[str] = "cv"
    t: Array
    x: Array
    v: Array
    mu: Array
    n_active: Array
    mean_age: Array
    x_pull: Array
    f_applied: Array
    births: Array
    spinodal: Array
    exits: Array
    snapshots: list[dict[str, Any]] = field(default_factory=list)
    info: dict[str, Any] = field(default_factory=dict)

    @property
    def partial(self) -> bool:
        return bool(self.info.get("partial", False))

    def to_dict(self) -> dict[str, Array]:
        """The time series as ``{column: array}``: the same as :meth:`columns`."""
        return self.columns()

    def columns(self) -> dict[str, Array]:
        """The time series as ``{column: array}`` (the shared names of
        :mod:`dryfriction.results`, in the order of :data:`COLUMNS`)."""
        return {k: getattr(self, k) for k in COLUMNS}

    def summary(self) -> dict[str, Any]:
        """The shared summary (:func:`dryfriction.results.summarize`, ``law = "cv"``), then the
        event counts (``events``) and :attr:`info` (drive scalars, ``regime``, ``parameters``)."""
        extra: dict[str, Any] = {
            "events": {
                "births": int(np.sum(self.births)),
                "spinodal": int(np.sum(self.spinodal)),
                "exits": int(np.sum(self.exits)),
            },
        }
        extra.update({k: v for k, v in self.info.items() if k != "partial"})
        return summarize("cv", self.t, self.x, self.v, self.mu, UNITS, partial=self.partial,
                         extra=extra)


# ---------------------------------------------------------------- recording


class Recorder:
    """Collects the samples of a run (one row per sample) and its population snapshots."""

    def __init__(self, mu_el: float) -> None:
        self.mu_el = mu_el
        self.rows: list[tuple[float, ...]] = []
        self.snapshots: list[dict[str, Any]] = []

    def add(self, ens: Ensemble, o: Observables, v: float, x_pull: float = math.nan,
            f_applied: float = math.nan, events: tuple[int, int, int] = (0, 0, 0)) -> None:
        """Record a sample; ``events`` = (births, spinodal, exits) since the last one."""
        self.rows.append((ens.t, ens.x, v, self.mu_el * o.force, o.n_active, o.mean_age, x_pull,
                          self.mu_el * f_applied, *events))

    def snap(self, ens: Ensemble) -> None:
        s = ens.snapshot()
        s["force"] = s["force"] * ens.force_scale * self.mu_el  # per-trap share of mu
        self.snapshots.append({"t": ens.t, "x": ens.x, **s})

    def result(self, info: dict[str, Any]) -> SimulationResult:
        a = np.array(self.rows, dtype=float).reshape(-1, len(COLUMNS))
        cols = {k: a[:, i].copy() for i, k in enumerate(COLUMNS)}
        return SimulationResult(**cols, snapshots=self.snapshots, info=info)


def sample_interval(velocity: float, output: Output) -> float:
    """Sampling interval (``t0``) in a segment at ``velocity``; ``inf`` for a hold sampled in
    slip (one step)."""
    if output.every is not None:
        return output.every
    if velocity != 0.0:
        return float(output.every_slip) / abs(velocity)
    return math.inf


FORCE_HOLD_LOG_STEP: float = 0.05
"""Step in ``ln(1 + t/t0)`` of a force hold sampled in slip (``every_slip``), ours. Under a
constant force the slider creeps against the load as the contacts age (about ``0.03 a0`` per
unit of ``ln(1 + t/t0)``, :func:`dryfriction.theory.static.force_hold_shift`), a slip an output
spacing in slip never sees: the hold is stepped on this geometric grid of the age instead, so
each step ages the contacts (and moves the slider) by about as much."""


def force_hold_grid(hold: float, every: float | None = None,
                    log_step: float = FORCE_HOLD_LOG_STEP) -> Array:
    """Sampling times of a force hold of length ``hold`` (``t0``): uniform at most ``every``
    apart when it is given, else on a geometric grid of the age, ``ln(1 + t)`` uniform with at
    most ``log_step`` per step; ends at ``hold``; empty if 0."""
    if hold <= 0.0:
        return np.empty(0)
    if every is not None:
        n = max(1, math.ceil(hold / every - 1e-9))
        return hold * np.arange(1, n + 1) / n
    n = max(1, math.ceil(math.log1p(hold) / log_step - 1e-9))
    grid = np.expm1(math.log1p(hold) * np.arange(1, n + 1) / n)
    grid[-1] = hold  # the ramp starts at the hold's end exactly, not at expm1(log1p(hold))
    return grid


# segments with fewer samples keep their grid exactly (their mean is no statistic; a finer
# step there would be a visible change): from this count on one extra sample in a few
# changes the step by at most ~2 %
_ALIAS_MIN_SAMPLES = 50


def _off_lattice(cells: float, n: int) -> int:
    """Samples for a segment crossing ``cells`` lattice cells in ``n`` equal steps: ``n`` if
    the steps' phases (``k cells / n mod 1``) drift through at least half a period, else the
    least ``n' > n`` whose steps are ``m/n'`` of a period apart with ``gcd(m, n') = 1``, so that
    the ``n'`` samples see ``n'`` evenly spread phases (a whole period, sampled evenly)."""
    step = cells / n
    m = round(step)
    if m < 1 or n < _ALIAS_MIN_SAMPLES or n * abs(step - m) >= 0.5:
        return n
    total = round(cells)
    for extra in range(1, 64):
        k = n + extra
        if math.gcd(total % k, k) == 1:
            return k
    return n


def segment_grid(program: VelocityProgram, output: Output, spacing: float | None = None
                 ) -> Array:
    """Sampling times of a velocity program: every segment boundary plus the output grid.

    ``spacing`` (``a0``): the lattice spacing of a regular track. A sampling step in slip that
    is (nearly) a multiple of it would see the periodic force of steady sliding at one phase
    only, so that the sampled mean is off by up to the sawtooth's amplitude; such a
    segment (of at least 50 samples) gets the fewest extra samples that make the steps visit
    every phase evenly (:func:`_off_lattice`).
    """
    times = [0.0]
    bounds = program.times
    for seg, ta, tb in zip(program.segments, bounds[:-1], bounds[1:], strict=True):
        dt = sample_interval(seg.velocity, output)
        n = max(1, math.ceil(seg.time / dt * (1.0 - 1e-9))) if math.isfinite(dt) else 1
        if spacing is not None and math.isfinite(dt):
            n = _off_lattice(abs(seg.velocity) * seg.time / spacing, n)
        times.extend(ta + (tb - ta) * np.arange(1, n + 1) / n)
    grid = np.asarray(times)
    snaps = [s for s in output.snapshots if s <= grid[-1]]
    return np.union1d(grid, snaps)


def position_function(program: VelocityProgram) -> Callable[[float], float]:
    """``t -> program.position(t)`` for one float, bit for bit the same value, without the
    array work per call (the inertial slider asks for it at every step)."""
    times = [float(v) for v in program.times]
    pos = [float(v) for v in program.positions]
    vel = [float(v) for v in program.velocities]
    last = len(vel) - 1

    def position(t: float) -> float:
        i = min(max(bisect.bisect_right(times, t) - 1, 0), last)  # as segment_index
        return pos[i] + vel[i] * (t - times[i])

    return position
