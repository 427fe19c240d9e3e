"""An extended frictional interface: a chain of trap-model blocks.

Reduced units as the single slider (:mod:`.driving`): lengths along the slip ``a0``, times
``t0``, forces ``F_el`` *per element* (one element's population at steady sliding carries
``mu_d(u) ~ 1``), stiffness ``F_el/a0``, mass ``F_el t0^2/a0``, damping ``F_el t0/a0``; positions
along the interface in element spacings (``element``).

Model
-----
Burridge & Knopoff (BSSA 57, 341 (1967)), every block carrying its own population of the trap
model, as the spring-block models of Trømborg et al. (PNAS 111, 8764 (2014); PRE 92, 012408
(2015)) give each block an explicit population of junctions; the choices are ours.

* ``N`` blocks of mass ``m`` along the interface, block ``i`` at slip ``x_i``, each with the
  single slider's population (:mod:`.population`: ageing by creep, eq. 19; the pair positions of
  its own :class:`~.population.Track`), damping ``eta`` per block, nearest-neighbour springs
  ``k_c`` with free ends::

      m x_i'' = K_p (P(t) - x_i) + k_c (x_{i+1} - 2 x_i + x_{i-1}) + [i = 0] K_s (L(t) - x_0)
                - F_i(x_i, ages) - eta x_i'

* Loading (:class:`InterfaceDrive`): ``uniform``, every block through a leaf spring ``K_p`` from
  a top plate ``P(t)`` that follows the velocity program; or ``side``, block 0 through an edge
  spring ``K_s`` whose end ``L(t)`` follows the program, the blocks optionally tied to a fixed
  top plate by ``K_p``. At ``t = 0`` the blocks are at rest at ``x = 0``; the uniform plate
  starts at ``P(0) = mean_i F_i(0) / K_p`` (the single slider's ``X_pull(0) = F(0)/K``), the edge
  load point at ``L(0) = sum_i F_i(0) / K_s`` (the spring carries the chain's initial friction).
* Disorder (:class:`InterfaceModel`): ``independent`` tracks, block 0 on the track of the
  given seed (so that ``N = 1`` is the single slider on it) and block ``i > 0`` on the seed
  ``SeedSequence([seed, i])``; a regular layout is the same lattice on every block. Or
  ``identical``: every block on block 0's track. Optional spreads, uniform in ``1 +- spread``,
  drawn from ``SeedSequence([seed, 2**32])``: the normal load (the block's force is multiplied
  by it) and the trap density (the block's track has ``lambda (1 + xi)`` pairs per ``a0``, the
  force unit staying the nominal one, so a denser block is stronger).
* Linear stability of uniform steady sliding at ``u`` (ours, from the single slider's): a mode
  ``x_i = u t + xi e^{lambda t} cos(q (i + 1/2))``, ``q = pi k / N`` (the free chain's normal
  modes, eigenvalue ``4 sin^2(q/2)`` of the coupling), obeys the single slider's
  characteristic equation ``m lambda^2 + eta lambda + K_p + 4 k_c sin^2(q/2) + Z(lambda) = 0``
  with the population's response ``Z``
  (:func:`dryfriction.theory.linear_stability.linear_response`).

Numerics (ours)
---------------
Velocity Verlet with the single slider's step rules (:mod:`.driving`), the chain's stiffest mode
in place of the spring: ``dt <= 0.05 * 2 pi sqrt(m / (K_p + K_s + k_c lambda_max + k_contact))``
(``lambda_max = 4 sin^2(pi (N - 1) / 2N)``, the free chain's largest coupling eigenvalue; 0 for
``N = 1``), ``dt <= m/eta``, a slip per step ``<= 1/(4 lambda)`` for the fastest block. All
blocks step together; their contact windows are updated in one compiled loop, parallel over
the blocks (:mod:`.interface_kernel`), by the single slider's own window update, so that one
block pulled uniformly is the single slider's spring drive bit for bit. Every block's pairs are
placed once, covering the slip it can reach (:func:`estimate_interface`); a block that slides
past that cover stops the run with one line.

Threads: the blocks' windows are updated in a ``prange`` from 16 blocks on, with Numba's
threads, except by default on a machine already busy (one-minute load average at least its
cores), where each step's join of the threads waits for a time slice; the numbers are the same
with any number of threads (tests/ensemble/test_interface.py).

Event-driven loading (ours; ``quasi_static_rate = v_qs > 0``): quasi-static loading between
events, dynamic stepping within them, as the event-driven spring-block codes do.

* The dynamics hand over when every block is quiet after a step, ``v_i^2 + (a_i/omega)^2 <
  v_qs^2`` (its slip rate, and the rate its unbalanced force ``m a_i`` would give it within an
  oscillation; ``omega = sqrt((K_p + k_contact)/m)``, the chain's lowest normal mode on fresh
  contacts), and not before one period ``2 pi/omega`` of dynamics.
* A quasi-static step goes to the next sample at once: every block in equilibrium at the new
  time without inertia, ``K_p (P - y_i) + k_c (y_{i+1} - 2 y_i + y_{i-1}) + [i = 0] K_s (L -
  y_0) - F_i(y_i) - eta (y_i - x_i)/dt = 0``, the friction of each window moved to ``y_i`` with
  the contacts aged to the new time (creep over the step, exact as in the dynamics), by
  Newton's method with the windows' own stiffness (:func:`.interface_kernel.settle_chain`).
* A step is taken only if no contact reaches its spinodal on the way, that is, no block's
  force reaches its threshold (the force at which its next contact gives way); else it is
  shortened to just before it, and within one dynamic step of the bound ``dt`` the dynamics
  resume from the last equilibrium, at the quasi-static velocities.

Exact: the loading, the ages and every contact's force at each equilibrium; with ``v_qs = 0``
the run is the dynamic one bit for bit. Neglected: the inertia ``m x''`` during the quiet
phases, that is the chain's residual oscillation when a phase starts, at most ``v_qs/omega``
in slip and ``m N v_qs^2`` in energy (booked in ``work_quasi_static``, so that the energy
balance still closes), and the overshoot of a contact's force drop below ``v_qs`` (each
threshold is handed to the dynamics, but a drop whose ringing stays below ``v_qs`` is let
settle quasi-statically after one period). :data:`QUASI_STATIC_RATE` is the threshold the
checks against the dynamic run were made with (tests/ensemble/test_interface_events.py).

Multirate stepping (ours; ``multirate = True``): the chain keeps its one step for the motion
and the springs, but each block's contact window, the cost, is updated only when that block
needs it: when it is the fastest block, when it passes the next spinodal of its contacts, or
after a quarter trap spacing of its own slip or ``dt_osc`` of time; its friction extrapolated
in between with the window's own stiffness
(:func:`.interface_kernel.advance_chain_multirate`, docs/explanation/interface.md). One block
is the every-step run bit for bit; a chain agrees with it to its chaotic scatter
(tests/ensemble/test_interface_multirate.py).

Not modelled (refused or absent, and said so): the direct effect (``direct > 0`` is refused),
the quasi-static (``mass = 0``) limit, a long-range (thin-slab) elastic kernel, snapshots of
the populations.
"""

from __future__ import annotations

import math
import os
import time as _time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import ClassVar

import numba
import numpy as np
from numpy.typing import ArrayLike

from .. import simulation
from ..interrupts import deferred
from ..program import VelocityProgram
from ..simulation import check_parts
from ..theory.model import TrapModel
from ..theory.trap import Regime
from ..validation import (
    U_MAX,
    U_MIN,
    check_choice,
    check_memory,
    check_range,
    check_scalar,
    check_time,
)
from .drives import MASS_MIN, STIFFNESS_MAX
from .interface_kernel import (
    OUT_SIZE,
    advance_chain,
    advance_chain_multirate,
    probe_chain,
    settle_chain,
)
from .interface_result import INTERFACE_UNITS, InterfaceResult
from .kernel import radius_table
from .population import Ensemble, Initial, Track
from .result import Output, segment_grid

__all__ = ["DISORDERS", "LOADINGS", "InterfaceDrive", "InterfaceEstimate", "InterfaceModel",
           "MAX_ELEMENTS", "MAX_FIELD_VALUES", "QUASI_STATIC_RATE", "element_tracks",
           "estimate_interface", "simulate_interface"]

LOADINGS: tuple[str, ...] = ("uniform", "side")
DISORDERS: tuple[str, ...] = ("independent", "identical")
MAX_ELEMENTS: int = 1 << 20
"""Most blocks accepted (ours): more is refused before any track is drawn."""
MAX_FIELD_VALUES: float = 2e8
"""Most recorded field values (samples x blocks x 3 fields) one run keeps (ours): 4.8 GB of
float64, past which the recording, not the physics, is the run."""
BYTES_PER_PAIR: float = 17.0
"""A pair's position, birth and state (float64, float64, int8)."""
SECONDS_PER_TRAP_UPDATE: float = 2.5e-8
"""One core's time per pair of a contact window in a step (ours, a lower bound measured on the
development machine: ``benchmarks/interface_speed.py``)."""
PARALLEL_MIN_ELEMENTS: int = 16
"""Fewest blocks whose windows are updated in parallel (ours): below it opening and joining a
parallel region every step costs more than the blocks' work."""
QUASI_STATIC_RATE: float = 0.01
"""The quasi-static switch's threshold ``v_qs`` (``a0/t0``) the event-driven checks were made
with (ours; :class:`InterfaceModel` ``quasi_static_rate``): a tenth of the event threshold of
:mod:`dryfriction.analysis.fronts` (10 x the loading velocity) at a loading of 0.01 ``a0/t0``."""
_SEED_SPREAD = 1 << 32  # the spreads' stream, apart from every block's (i < 2**20)


@dataclass(frozen=True)
class InterfaceModel:
    """A chain of ``n_elements`` trap-model blocks (module docstring).

    Parameters
    ----------
    trap : TrapModel
        The law of every block's traps (creep, ``alpha``, ``mu_el``); ``direct`` must be 0.
    n_elements : int
        ``N >= 1`` blocks.
    coupling : float
        ``k_c >= 0``, the spring between neighbours, ``F_el/a0``.
    mass : float
        ``m >= 1e-6`` per block, ``F_el t0^2/a0``.
    damping : float
        ``eta >= 0`` per block, ``F_el t0/a0``.
    disorder : {"independent", "identical"}
        Every block on its own track (block 0 on the seed's), or all on block 0's.
    normal_spread, density_spread : float
        Half-widths ``0 <= s < 1`` of the uniform spreads of the blocks' normal load and trap
        density (need a seed when nonzero).
    quasi_static_rate : float
        ``v_qs >= 0``, ``a0/t0``: the slip rate below which every block must be for the
        loading to advance quasi-statically (event-driven, module docstring); 0 (the default)
        steps the chain dynamically throughout. :data:`QUASI_STATIC_RATE` is the value the
        event-driven checks were made with.
    multirate : bool
        Every block's contact window on its own clock (``False``, the default: every window
        at every step): a window is updated when its block has slipped a quarter trap spacing
        or a step bound's time since its last update, its friction extrapolated to first order
        in between (:func:`.interface_kernel.advance_chain_multirate`; ours, checked against
        the default in tests/ensemble/test_interface_multirate.py).
    """

    law: ClassVar[str] = "cv"
    trap: TrapModel
    n_elements: int
    coupling: float
    mass: float
    damping: float = 0.0
    disorder: str = "independent"
    normal_spread: float = 0.0
    density_spread: float = 0.0
    quasi_static_rate: float = 0.0
    multirate: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.trap, TrapModel):
            raise ValueError(f"trap = {self.trap!r} is not allowed: a TrapModel")
        if self.trap.direct != 0.0:
            raise ValueError(f"direct = {self.trap.direct:g} is not allowed with an interface: "
                             "allowed 0 (the chain's blocks have no direct effect yet)")
        n = self.n_elements
        integer = isinstance(n, (int, np.integer)) and not isinstance(n, bool)
        if not integer or not 1 <= n <= MAX_ELEMENTS:
            raise ValueError(f"n_elements = {n!r} is out of range: allowed an integer 1 to "
                             f"{MAX_ELEMENTS}")
        object.__setattr__(self, "n_elements", int(n))
        object.__setattr__(self, "coupling",
                           check_scalar("coupling", self.coupling, 0.0, STIFFNESS_MAX))
        m = check_scalar("mass", self.mass, MASS_MIN)
        object.__setattr__(self, "mass", m)
        object.__setattr__(self, "damping", check_scalar("damping", self.damping, 0.0))
        check_choice("disorder", self.disorder, DISORDERS)
        for name in ("normal_spread", "density_spread"):
            s = check_scalar(name, getattr(self, name), 0.0, 1.0, hi_open=True)
            object.__setattr__(self, name, s)
        object.__setattr__(self, "quasi_static_rate",
                           check_scalar("quasi_static_rate", self.quasi_static_rate, 0.0, U_MAX))
        if not isinstance(self.multirate, (bool, np.bool_)):
            raise ValueError(f"multirate = {self.multirate!r} is not allowed: true or false")
        object.__setattr__(self, "multirate", bool(self.multirate))

    @property
    def coupling_eigenvalue_max(self) -> float:
        """Largest eigenvalue of the free chain's coupling ``4 sin^2(pi (N-1) / 2N)`` (0 for
        ``N = 1``): the stiffest mode is ``K + k_c`` times it."""
        n = self.n_elements
        return 4.0 * math.sin(math.pi * (n - 1) / (2 * n)) ** 2 if n > 1 else 0.0

    def sound_speed(self) -> float:
        """``sqrt(k_c / m)``, element spacings per ``t0``: the chain's long-wave speed."""
        return math.sqrt(self.coupling / self.mass)


@dataclass(frozen=True)
class InterfaceDrive(simulation.Drive):
    """How the chain is loaded (module docstring).

    Parameters
    ----------
    loading : {"uniform", "side"}
        Every block from a moving top plate, or block 0 from a moving edge spring.
    stiffness : float
        ``K_p``, the leaf spring of every block to the top plate, ``F_el/a0``: ``> 0`` for
        uniform loading, ``>= 0`` for side loading (the plate then stays fixed).
    program : VelocityProgram
        Velocity program of the moving load point (plate or edge), ``a0/t0``.
    edge_stiffness : float
        ``K_s``, the edge spring (side loading, ``> 0``; 0 for uniform).
    """

    law: ClassVar[str] = "cv"
    loading: str
    stiffness: float
    program: VelocityProgram
    edge_stiffness: float = 0.0

    def __post_init__(self) -> None:
        check_choice("loading", self.loading, LOADINGS)
        side = self.loading == "side"
        k = check_scalar("stiffness", self.stiffness, 0.0, STIFFNESS_MAX, lo_open=not side)
        object.__setattr__(self, "stiffness", k)
        if side:
            ks = check_scalar("edge_stiffness", self.edge_stiffness, 0.0, STIFFNESS_MAX,
                              lo_open=True)
        else:
            ks = check_scalar("edge_stiffness", self.edge_stiffness, 0.0, 0.0)
        object.__setattr__(self, "edge_stiffness", ks)
        if not isinstance(self.program, VelocityProgram):
            object.__setattr__(self, "program", VelocityProgram(self.program))
        self.program.check_speeds(U_MIN, U_MAX, "a0/t0")


def _busy() -> bool:
    """The machine's one-minute load average is at least its number of cores (ours)."""
    try:
        return os.getloadavg()[0] >= (os.cpu_count() or 1)
    except OSError:  # pragma: no cover - no load average on this system
        return False


def _element_seed(seed: int, i: int) -> int:
    """Track seed of block ``i``: the given seed for block 0 (so ``N = 1`` is the single slider
    on that track), else a word of ``SeedSequence([seed, i])`` (ours)."""
    if i == 0:
        return int(seed)
    return int(np.random.SeedSequence([int(seed), i]).generate_state(1, np.uint64)[0] >> 1)


def _spreads(model: InterfaceModel, seed: int | None) -> tuple[np.ndarray, np.ndarray]:
    """Per-block factors of the normal load and of the trap density (ones without spread)."""
    n = model.n_elements
    if model.normal_spread == 0.0 and model.density_spread == 0.0:
        return np.ones(n), np.ones(n)
    rng = np.random.default_rng(np.random.SeedSequence([int(seed or 0), _SEED_SPREAD]))
    xi = rng.uniform(-1.0, 1.0, size=(2, n))
    return 1.0 + model.normal_spread * xi[0], 1.0 + model.density_spread * xi[1]


def element_tracks(model: InterfaceModel, track: Track) -> tuple[list[Track], np.ndarray]:
    """The blocks' tracks and the factors of their normal load (module docstring).

    Raises
    ------
    ValueError
        A spread or random independent tracks without a seed.
    """
    spread = model.normal_spread > 0.0 or model.density_spread > 0.0
    if spread and track.seed is None:
        raise ValueError("seed is required with normal_spread or density_spread (the spreads "
                         "are drawn from an explicit seed)")
    normal, density = _spreads(model, track.seed)
    tracks = []
    for i in range(model.n_elements):
        seed = track.seed
        if track.layout == "random" and model.disorder == "independent":
            seed = _element_seed(int(track.seed or 0), i)
        lam = track.traps_per_a0 * float(density[i]) if spread else track.traps_per_a0
        tracks.append(Track(lam, track.layout, seed))
    return tracks, normal


@dataclass(frozen=True)
class InterfaceEstimate:
    """What a run will hold and do, estimated before any allocation."""

    samples: int
    pairs: float
    steps: float
    window: float
    cover: tuple[float, float]
    n_elements: int

    @property
    def field_values(self) -> float:
        """Values of the three recorded fields (slip, slip rate, stress)."""
        return 3.0 * self.samples * self.n_elements

    @property
    def total_bytes(self) -> float:
        """Pairs, the recorded fields and the per-sample scalars (bytes)."""
        return self.pairs * BYTES_PER_PAIR + 8.0 * (self.field_values + 8.0 * self.samples)


def _cover(model: InterfaceModel, drive: InterfaceDrive, initial: Initial) -> tuple[float, float]:
    """Slip range ``[lo, hi]`` (``a0``) every block's pairs are placed for (ours): twice the
    load point's reach, ``2 (L(0) + travel) + 20 a0`` ahead, ``10 a0`` behind. ``L(0)`` is
    estimated from the initial friction (``rest``: 0.05, ``loaded``: its force, ``steady``: 1.5
    ``F_el`` per block) over the loading spring. A block that leaves the range stops the run
    with one line (never silently)."""
    prog = drive.program
    travel = float(np.max(np.abs(prog.positions - prog.x0)))
    f0 = {"rest": 0.05, "loaded": abs(float(initial.force or 0.0)), "steady": 1.5}[initial.kind]
    if drive.loading == "uniform":
        start = f0 / drive.stiffness
    else:
        start = model.n_elements * f0 / drive.edge_stiffness
    return -10.0, 2.0 * (start + travel) + 20.0


def estimate_interface(model: InterfaceModel, drive: InterfaceDrive, initial: Initial,
                       output: Output) -> InterfaceEstimate:
    """Samples, pairs, steps and contact windows of a run (:func:`simulate_interface`), from
    the parameters only (nothing allocated but a few numbers)."""
    track = initial.track
    assert track is not None
    prog = drive.program
    samples = 1
    for seg in prog.segments:
        dt = output.every if output.every is not None else (
            float(output.every_slip) / abs(seg.velocity) if seg.velocity != 0.0 else math.inf)
        samples += max(1, math.ceil(seg.time / dt)) if math.isfinite(dt) else 1
    lo, hi = _cover(model, drive, initial)
    reach = 2.0 * max(1.0, model.trap.trap.y_c) + 12.0  # windows and the population's margin
    pairs = model.n_elements * track.traps_per_a0 * (hi - lo + 2.0 * reach)
    dt = _step(model, drive, 1.0 + model.normal_spread)
    steps = prog.total_time / dt
    window = 2.0 * max(1.0, model.trap.trap.y_c) * track.traps_per_a0 * model.n_elements
    return InterfaceEstimate(samples=samples, pairs=pairs, steps=steps, window=window,
                             cover=(lo, hi), n_elements=model.n_elements)


def _step(model: InterfaceModel, drive: InterfaceDrive, normal_max: float) -> float:
    """The oscillation bound of the time step (module docstring), written as the single
    slider's ``0.05 * 2 pi sqrt(M / (K + k_contact))`` (bit for bit at ``N = 1``);
    ``normal_max`` the largest factor of a block's normal load (its contact stiffness)."""
    k_contact = model.trap.trap.contact_stiffness * normal_max
    stiff = (drive.stiffness + drive.edge_stiffness + model.coupling_eigenvalue_max
             * model.coupling)
    dt = 0.05 * 2.0 * math.pi * math.sqrt(model.mass / (stiff + k_contact))
    if model.damping > 0.0:
        dt = min(dt, model.mass / model.damping)
    return dt


def check_interface(model: InterfaceModel, drive: InterfaceDrive, initial: Initial,
                    output: Output) -> InterfaceEstimate:
    """Refuse, in one line naming the parameter, a run that would not fit in memory, record too
    many values or take longer than the time limit (:func:`dryfriction.validation.time_limit`).
    """
    est = estimate_interface(model, drive, initial, output)
    key = "every" if output.every is not None else "every_slip"
    value = output.every if output.every is not None else output.every_slip
    if est.field_values > MAX_FIELD_VALUES:
        raise ValueError(f"{key} = {value:g} with n_elements = {model.n_elements} records "
                         f"{est.field_values:.1e} field values, over the {MAX_FIELD_VALUES:.0e} "
                         f"one run keeps; raise {key} (or shorten the drive, or fewer elements)")
    field_bytes = 8.0 * est.field_values
    if field_bytes > est.pairs * BYTES_PER_PAIR:
        what = f"{key} = {value:g} records {est.samples} samples of {model.n_elements} elements"
        hint = f"raise {key}"
    else:
        what = (f"traps_per_a0 = {initial.track.traps_per_a0:g} places {est.pairs:.1e} pairs "  # type: ignore[union-attr]
                f"over {est.cover[1] - est.cover[0]:.0f} a0 of slip per element")
        hint = "lower traps_per_a0 or n_elements (or shorten the drive)"
    check_memory(what, est.total_bytes, hint)
    seconds = est.steps * est.window * SECONDS_PER_TRAP_UPDATE
    check_time(f"mass = {model.mass:g} over {drive.program.total_time:.3g} t0 of drive needs "
               f"{est.steps:.1e} steps of {est.window:.1e} traps", seconds,
               "shorten segments, raise mass, lower traps_per_a0 or n_elements")
    return est


def simulate_interface(
    model: InterfaceModel,
    drive: InterfaceDrive,
    initial: Initial,
    output: Output,
    *,
    velocity: ArrayLike = 0.0,
    threads: int | None = None,
    on_interrupt: str = "raise",
    progress: Callable[[float, np.ndarray, dict[str, float]], None] | None = None,
) -> InterfaceResult:
    """Run the chain under its loading and record the space-time fields (module docstring).

    Parameters
    ----------
    model : InterfaceModel
        Blocks, coupling, the traps' law.
    drive : InterfaceDrive
        Uniform or side loading and its velocity program (``a0/t0``).
    initial : Initial
        The population of every block at ``t = 0`` (``rest``, ``loaded``, ``steady``) and the
        ``track`` whose density, layout and seed the blocks' tracks derive from.
    output : Output
        Sampling (``every`` in ``t0`` or ``every_slip`` of the load point in ``a0``); no
        snapshots.
    velocity : float or array_like of shape (N,)
        Initial velocity of the blocks, ``a0/t0`` (default at rest, as the single slider's
        spring drive): a steady population sliding at ``u`` with a velocity pattern seeds the
        chain's modes. The load point then starts where its springs balance the friction and
        the damping of the mean velocity.
    threads : int, optional
        Numba threads for the parallel loop over blocks. Default: Numba's, unless the machine
        is already busy (its one-minute load average at least its cores), where one thread:
        every step joins the threads, and on a shared machine each join waits for a time slice
        (measured on 2 cores, N = 256: two threads 9x slower than one at a load of 13, 5x at
        7.4 with Numba's default OpenMP layer, whose waiting threads spin; at that load
        ``OMP_WAIT_POLICY=PASSIVE`` gave 0.8x and ``NUMBA_THREADING_LAYER=workqueue`` 1.0x).
        The numbers are the same either way.
    on_interrupt : {"raise", "partial"}
        On ``KeyboardInterrupt``: re-raise, or return the samples so far marked partial.
    progress : callable, optional
        Called after every recorded sample with its time (``t0``), the blocks' slip rates
        (``a0/t0``, a copy) and the counts so far (``steps``, ``trap_updates``,
        ``quasi_static_steps``, ``handovers``, ``wall_s``, ``cpu_s``): for a long run's
        progress (``benchmarks/bench_interface.py``).

    Returns
    -------
    InterfaceResult
        Fields at the sampling times, the first sample the initial state.

    Raises
    ------
    ValueError
        Bad input, or a run over the memory, sample or time limits, in one line before any
        work.
    RuntimeError
        A block slid past the slip its pairs were placed for.
    """
    check_parts("cv", drive=drive, initial=initial, output=output)
    if not isinstance(model, InterfaceModel):
        raise ValueError(f"model = {model!r} is not allowed: an InterfaceModel")
    if not isinstance(drive, InterfaceDrive):
        raise ValueError(f"drive = {drive!r} is not allowed: an InterfaceDrive")
    if not isinstance(initial, Initial) or initial.track is None:
        raise ValueError("initial is not allowed: an Initial with its track, e.g. "
                         "Initial('rest', track=Track(traps_per_a0=100, layout='random', seed=1))")
    if not isinstance(output, Output) or output.snapshots:
        raise ValueError("output is not allowed: an Output (every or every_slip) without "
                         "snapshots")
    check_choice("on_interrupt", on_interrupt, ("raise", "partial"))
    if threads is not None:
        threads = int(check_scalar("threads", threads, 1, numba.config.NUMBA_NUM_THREADS))
    v_start = check_range("velocity", velocity, -U_MAX, U_MAX)
    if v_start.ndim and v_start.shape != (model.n_elements,):
        raise ValueError(f"velocity has shape {v_start.shape}: allowed one number or one per "
                         f"element, shape ({model.n_elements},)")
    v_start = np.broadcast_to(v_start, (model.n_elements,))
    tracks, normal = element_tracks(model, initial.track)
    est = check_interface(model, drive, initial, output)
    t_wall, t_cpu = _time.perf_counter(), _time.process_time()
    n = model.n_elements
    tm = model.trap
    prog = drive.program
    horizon = min(prog.total_time, 1e12)
    lo_cov, hi_cov = est.cover
    # every block's pairs, placed as the single slider places them, then packed flat
    sizes, parts, oldest = [], [], 0.0
    lo = np.empty(n, np.int64)
    hi = np.empty(n, np.int64)
    f = np.empty(n)
    fscale = np.empty(n)
    for i, tr in enumerate(tracks):
        ens = Ensemble(tm, tr, initial, x0=0.0, age_horizon=horizon)
        ens.cover(lo_cov, hi_cov)
        parts.append((ens.c, ens.state, ens.birth))
        sizes.append(ens.c.size)
        lo[i], hi[i] = ens.lo, ens.hi
        fscale[i] = ens.force_scale * float(normal[i])
        f[i] = ens.observe().force * float(normal[i])
        oldest = min(oldest, ens.oldest_birth)
        del ens
    off = np.zeros(n + 1, np.int64)
    off[1:] = np.cumsum(sizes)
    c = np.concatenate([p[0] for p in parts])
    state = np.concatenate([p[1] for p in parts])
    birth = np.concatenate([p[2] for p in parts])
    del parts
    h, s_tab, ds_tab, _ = radius_table(tm.law, max(horizon, 1.0) - oldest)
    trap = tm.trap
    kp, ks, kc = drive.stiffness, drive.edge_stiffness, model.coupling
    side = drive.loading == "side"
    v_mean = float(np.mean(v_start))
    if v_mean == 0.0:  # the single slider's X_pull(0) = F(0)/K, bit for bit at N = 1
        load0 = float(np.sum(f)) / ks if side else float(f.sum() / n) / kp
    else:
        damp = n * model.damping * v_mean
        load0 = (float(np.sum(f)) + damp) / ks if side else (float(f.sum() + damp) / n) / kp
    # the sampling of the single slider's spring drive
    lam_min = min(t.traps_per_a0 for t in tracks)
    regular = initial.track.layout == "regular"
    grid = segment_grid(prog, output, 1.0 / lam_min if regular else None)
    n_t = grid.size
    p_times = np.asarray(prog.times, float)
    p_pos = np.asarray(prog.positions, float)
    p_vel = np.asarray(prog.velocities, float)
    x0 = float(prog.x0)

    def load_at(t: float) -> float:
        """``L(t)``, as the kernel's ``load_position`` and the single slider's ``pull``."""
        i = min(max(int(np.searchsorted(p_times, t, side="right")) - 1, 0), p_vel.size - 1)
        return load0 + (float(p_pos[i]) + float(p_vel[i]) * (t - float(p_times[i]))) - x0

    x = np.zeros(n)
    v = np.array(v_start, dtype=float)
    l_start = load_at(0.0)
    a = (kp * ((0.0 if side else l_start) - x) - f - model.damping * v) / model.mass
    if side:
        a[0] = (kp * (0.0 - x[0]) + ks * (l_start - x[0]) - f[0]
                - model.damping * v[0]) / model.mass
    dt_osc = _step(model, drive, float(np.max(normal)))
    dx_max = 0.25 * (1.0 / max(t.traps_per_a0 for t in tracks))  # the single slider's form
    outs = np.zeros((n, OUT_SIZE))
    wfric = np.zeros(n)
    wdamp = np.zeros(n)
    acc = np.zeros(6)  # the kernels' [work_load, steps, updates, overflow]; qs steps, handovers
    wqs = np.zeros(n)
    v_qs = model.quasi_static_rate
    # the lowest normal mode of the chain on fresh contacts, sqrt((K_p + k_contact)/m): the
    # quiet test's oscillation and the least time a dynamic phase lasts (one of its periods)
    omega_qs = math.sqrt((kp + trap.contact_stiffness * float(np.min(normal))) / model.mass)
    t_settle = 2.0 * math.pi / omega_qs
    nxt = np.full(n, np.inf)
    # the multirate kernel's last update of every block: position, time, force, stiffness, path
    xu, tu, fu, ku, path = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    ne, nd = np.full(n, np.inf), np.ones(n)  # its next spinodal, in the direction it moved
    multirate = model.multirate
    slip = np.empty((n_t, n))
    rate = np.empty((n_t, n))
    stress = np.empty((n_t, n))
    load = np.empty(n_t)
    lpos = np.empty(n_t)
    energy = {k: np.empty(n_t) for k in ("work_load", "elastic_energy", "kinetic_energy",
                                         "work_friction", "work_damping",
                                         "work_quasi_static")}

    def record(j: int, t: float) -> None:
        lp = load_at(t)
        slip[j], rate[j], stress[j] = x, v, f
        lpos[j] = lp
        plate = 0.0 if side else lp
        e_el = (0.5 * kp * float(np.sum((plate - x) ** 2))
                + 0.5 * kc * float(np.sum(np.diff(x) ** 2)))
        if side:
            load[j] = ks * (lp - x[0])
            e_el += 0.5 * ks * (lp - x[0]) ** 2
        else:
            load[j] = float(np.sum(kp * (lp - x)))
        energy["work_load"][j] = acc[0]
        energy["elastic_energy"][j] = e_el
        energy["kinetic_energy"][j] = 0.5 * model.mass * float(np.sum(v * v))
        energy["work_friction"][j] = float(np.sum(wfric))
        energy["work_damping"][j] = float(np.sum(wdamp))
        energy["work_quasi_static"][j] = float(np.sum(wqs))

    if threads is not None:
        numba.set_num_threads(threads)
    serial = numba.get_num_threads() == 1 or n < PARALLEL_MIN_ELEMENTS
    if threads is None and not serial:
        serial = _busy()
    record(0, 0.0)
    j_done = 0
    partial = False
    t = 0.0
    args_fixed = (model.mass, model.damping, kp, kc, ks, side, 0.0, load0, p_times, p_pos, p_vel,
                  x0, tm.alpha, trap.y_c, trap.regime is Regime.STRONG, h, s_tab,
                  ds_tab, outs, wfric, wdamp, acc, serial)
    args_settle = (model.mass, model.damping, kp, kc, ks, side, 0.0, load0, p_times, p_pos,
                   p_vel, x0, tm.alpha, trap.y_c, trap.regime is Regime.STRONG, h, s_tab, ds_tab,
                   outs, wfric, wdamp, wqs, acc, serial)
    quasi = False  # the phase: quasi-static loading, or dynamic stepping
    t_min = 0.0  # a dynamic phase lasts at least until then

    args_probe = (tm.alpha, trap.y_c, trap.regime is Regime.STRONG, h, s_tab, ds_tab, outs, xu,
                  tu, fu, ku, path, ne, nd)
    if multirate:
        probe_chain(c, state, birth, off, lo, hi, x, 0.0, fscale, *args_probe)

    def dynamic(t: float, t1: float, t_min: float) -> float:
        """Dynamic steps from ``t`` towards ``t1`` (every window each step, or multirate)."""
        if multirate:
            return advance_chain_multirate(c, state, birth, off, lo, hi, x, v, a, f, fscale, t,
                                           t1, dt_osc, dx_max, *args_fixed, v_qs, omega_qs,
                                           t_min, xu, tu, fu, ku, path, ne, nd,
                                           PARALLEL_MIN_ELEMENTS)
        return advance_chain(c, state, birth, off, lo, hi, x, v, a, f, fscale, t, t1, dt_osc,
                             dx_max, *args_fixed, v_qs, omega_qs, t_min)

    def event_driven(t: float, t1: float) -> float:
        """From ``t`` to the sample ``t1``, alternating the phases (module docstring)."""
        nonlocal quasi, t_min
        while t < t1 and acc[3] == 0.0:
            if quasi:
                t, hit = settle_chain(c, state, birth, off, lo, hi, x, v, a, f, fscale, t, t1,
                                      dt_osc, nxt, *args_settle)
                acc[4] += 1.0
                if hit:
                    quasi = False
                    t_min = t + t_settle
                    acc[5] += 1.0
                    if multirate:  # settle_chain moved the windows
                        probe_chain(c, state, birth, off, lo, hi, x, t, fscale, *args_probe)
            else:
                t = dynamic(t, t1, t_min)
                if t < t1 and acc[3] == 0.0:  # every block quiet
                    quasi = True
                    nxt[:] = np.inf
        return t

    def advance(t: float, t1: float) -> float:
        if v_qs > 0.0:
            return event_driven(t, t1)
        if multirate:
            return dynamic(t, t1, 0.0)
        return advance_chain(c, state, birth, off, lo, hi, x, v, a, f, fscale, t, t1, dt_osc,
                             dx_max, *args_fixed)

    try:
        for j in range(1, n_t):
            t1 = float(grid[j])
            kernel = advance_chain_multirate if multirate else advance_chain
            if kernel.overloads and (v_qs == 0.0 or settle_chain.overloads):
                t = advance(t, t1)
            else:  # the first call loads (or compiles) it: signals held back meanwhile
                with deferred():
                    t = advance(t, t1)
            if acc[3] != 0.0:
                worst = int(np.argmax(np.abs(x)))
                raise RuntimeError(
                    f"element {worst} slid to {x[worst]:.3g} a0 at t = {t:.6g} t0, past the "
                    f"{lo_cov:g}..{hi_cov:g} a0 its pairs were placed for (the cover bound of "
                    "dryfriction.ensemble.interface: twice the load point's reach), a kick or a "
                    "runaway it did not foresee; lower the initial velocity or shorten the drive")
            record(j, t1)
            j_done = j
            if progress is not None:
                progress(t1, v.copy(), {
                    "steps": float(acc[1]), "trap_updates": float(acc[2]),
                    "quasi_static_steps": float(acc[4]), "handovers": float(acc[5]),
                    "wall_s": _time.perf_counter() - t_wall,
                    "cpu_s": _time.process_time() - t_cpu})
    except KeyboardInterrupt:
        if on_interrupt == "raise":
            raise
        partial = True
    keep = j_done + 1
    info = {
        "partial": partial,
        "steps": int(acc[1]),
        "trap_updates": float(acc[2]),
        "wall_s": _time.perf_counter() - t_wall,
        "cpu_s": _time.process_time() - t_cpu,  # every thread of the process
        "threads": 1 if serial else int(numba.get_num_threads()),
        "quasi_static_rate": v_qs,
        "quasi_static_steps": int(acc[4]),
        "handovers": int(acc[5]),
        "dt_max": dt_osc,
        "cover_a0": [lo_cov, hi_cov],
        "regime": trap.regime.value,
    }
    params = {
        "interface": {k: v for k, v in asdict(model).items() if k != "trap"},
        "model": {k: v for k, v in asdict(tm).items() if k not in ("direct", "v_ref")},
        "track": asdict(initial.track),
        "initial": {k: v for k, v in asdict(initial).items() if k != "track"},
        "drive": {"loading": drive.loading, "stiffness": kp, "edge_stiffness": ks,
                  "segments": [{k: v for k, v in asdict(s).items() if v is not None}
                               for s in prog.segments],
                  "load_point_start": load0},
    }
    return InterfaceResult(
        t=grid[:keep].copy(), x=np.arange(n) + 0.5, slip=slip[:keep], slip_rate=rate[:keep],
        stress=stress[:keep], load=load[:keep], load_point=lpos[:keep], params=params,
        units=dict(INTERFACE_UNITS), energy={k: e[:keep] for k, e in energy.items()},
        info=info)
