"""Protocol files: TOML -> validated, frozen simulation parameters (the only module that parses).

A protocol has four tables; unknown tables or keys are errors, not ignored::

    [model]                      # TrapModel
    alpha = 0.13                 # optional, 0 < alpha < 1
    eps = 0.04                   # required, >= 0
    creep = "log"                # optional: "log" | "eyring-nabarro"
    mu_el = 1.0                  # optional, 0 < mu_el <= 10
    direct = 0.0                 # optional, 0 <= A <= 1: direct effect
    v_ref = 1.0                  # optional, a0/t0, > 0: its reference velocity

    [ensemble]                   # Track and Initial
    traps_per_a0 = 1000          # required, > 0
    layout = "regular"           # optional: "regular" | "random"
    seed = 1                     # required for layout = "random"
    initial = "rest"             # required: "rest" | "loaded" | "steady"
    initial_force = 0.5          # loaded only (units F_el, -1 < f < 1)
    initial_velocity = 1.0       # steady only (units a0/t0, > 0)

    [drive]
    kind = "velocity"            # required: "velocity" | "force" | "spring"
    segments = [{velocity = 1.0, slip = 5.0}, {velocity = 0.0, duration = 100.0}]
    # force:  rate (F_el/t0, > 0, required), hold (t0, >= 0), max_force (F_el, > 0)
    # spring: stiffness (F_el/a0, > 0), mass (F_el t0^2/a0, >= 0), damping (F_el t0/a0, >= 0),
    #         segments (the load-point program)

    [output]
    every_slip = 0.01            # exactly one of every (t0) and every_slip (a0)
    snapshots = [10.0, 20.0]     # optional, times in t0

Rate-and-state friction runs through the same files, in SI units, with
``law = "rsf"`` in ``[model]`` and no ``[ensemble]`` table::

    [model]                      # RateState (dryfriction.rsf)
    law = "rsf"                  # default "cv": the trap model above
    state_law = "ageing"         # optional: "ageing" | "slip"
    a = 0.005                    # required, > 0
    b = 0.01                     # required, >= 0
    dc = 1e-5                    # required, m, > 0
    mu0 = 0.6                    # required
    v0 = 1e-6                    # required, m/s, > 0
    # optional: b2, dc2 (second state variable), regularized (true: asinh law, V = 0 allowed)

    [drive]                      # dryfriction.rsf.SpringSlider
    kind = "spring"              # required: "velocity" (kinematic machine) | "spring"
                                 # ("force" is the trap model's only)
    segments = [{velocity = 1e-6, duration = 10.0}, {velocity = 1e-5, slip = 1e-4}]
    stiffness = 1e3              # spring: required, 1/m per unit normal force (inf: kinematic)
    damping = 0.0                # spring: optional, eta/sigma, s/m
    mass = 0.0                   # spring: optional, s^2/m per unit normal force
    v_init = 1.01e-6             # optional, m/s: initial slip velocity (state at steady state
                                 # for it); default the first segment's velocity

    [output]                     # optional table
    every = 0.01                 # optional, s: sampling interval (default: every solver step)
    rtol = 1e-7                  # optional: the solver's local tolerance

An extended interface (a chain of trap-model blocks,
:mod:`dryfriction.ensemble.interface`) adds an ``[interface]`` table to the trap model's
``[model]`` and ``[ensemble]`` (every block's track and initial population), with drive kinds
of its own::

    [interface]                  # InterfaceModel
    n_elements = 64              # required, integer >= 1
    coupling = 4.0               # required, k_c between neighbours, F_el/a0, >= 0
    mass = 1.0                   # required, per block, F_el t0^2/a0, >= 1e-6
    damping = 0.1                # optional, per block, F_el t0/a0, >= 0
    disorder = "independent"     # optional: "independent" | "identical" (all on block 0's)
    normal_spread = 0.1          # optional, 0 <= s < 1: per-block normal load 1 +- s
    density_spread = 0.0         # optional, 0 <= s < 1: per-block trap density 1 +- s
    quasi_static_rate = 0.01     # optional, a0/t0, >= 0: event-driven loading below it (0: off)
    multirate = true             # optional: every block's contacts on its own clock (false)

    [drive]                      # InterfaceDrive
    kind = "side"                # required: "uniform" (top plate) | "side" (edge spring)
    edge_stiffness = 0.5         # side: required, F_el/a0, > 0
    stiffness = 0.0              # uniform: required (> 0); side: optional, to a fixed plate
    segments = [{velocity = 0.01, slip = 20.0}]   # the moving load point's program

    [output]
    every = 0.5                  # exactly one of every (t0) and every_slip (a0); no snapshots

Every error names the file, the table and key (``table.key``), and what is allowed, and is
raised before any work starts. (Errors avoid square brackets around names, which the terminal's
markup would swallow.)
"""

from __future__ import annotations

import math
import os
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..program import Segment, VelocityProgram
from ..rsf.law import RateState
from ..rsf.resources import check_rsf_run
from ..rsf.spring import RSFInitial, RSFOutput, SpringSlider
from ..validation import check_scalar
from .textfile import HEAD_BYTES, check_text

if TYPE_CHECKING:
    # the trap model's classes import the compiled ensemble kernel (Numba) and SciPy, and the
    # rate-and-state solver imports Numba: each is imported where a run of its law needs it,
    # so that parsing a protocol of the other law (or a sweep's grid) does not pay for it
    from ..ensemble.driving import Drive, Output, SimulationResult, SpringDrive
    from ..ensemble.interface import InterfaceDrive, InterfaceModel
    from ..ensemble.interface_result import InterfaceResult
    from ..ensemble.population import Initial, Track, TrapModel
    from ..rsf.result import RSFResult

__all__ = [
    "InterfaceProtocol",
    "Protocol",
    "RSFProtocol",
    "STICKSLIP_KEYS",
    "load_protocol",
    "parse_protocol",
    "protocol_from_dict",
    "pulling_velocity",
    "spring_point",
    "stickslip_options",
    "option_table",
]

LAWS: tuple[str, ...] = ("cv", "rsf")
_RSF_TABLES = ("model", "drive", "output")
_RSF_MODEL_KEYS = ("law", "state_law", "a", "b", "dc", "mu0", "v0", "b2", "dc2", "regularized")
_RSF_DRIVE_KEYS = {
    "velocity": ("segments", "v_init"),
    "spring": ("segments", "stiffness", "damping", "mass", "v_init"),
}

_TABLES = ("model", "ensemble", "drive", "output")
_DRIVE_KEYS = {
    "velocity": ("segments",),
    "force": ("rate", "hold", "max_force"),
    "spring": ("stiffness", "mass", "damping", "segments"),
}
_REQUIRED_DRIVE = {
    "velocity": ("segments",),
    "force": ("rate",),
    "spring": ("stiffness", "mass", "segments"),
}


@dataclass(frozen=True)
class Protocol:
    """A validated protocol: everything :func:`dryfriction.ensemble.driving.simulate` needs
    (``track`` is ``initial.track``, kept on its own for the readers of the protocol)."""

    model: TrapModel
    track: Track
    initial: Initial
    drive: Drive
    output: Output
    source: str = "<string>"

    def run(
        self,
        progress: Callable[[float], None] | None = None,
        on_interrupt: str = "raise",
    ) -> SimulationResult:
        """Run the simulation (see :func:`dryfriction.ensemble.driving.simulate`)."""
        from ..ensemble.driving import simulate

        return simulate(self.model, self.drive, self.initial, self.output, progress=progress,
                        on_interrupt=on_interrupt)


@dataclass(frozen=True)
class RSFProtocol:
    """A validated rate-and-state protocol (SI units): what
    :func:`dryfriction.rsf.driving.simulate` needs.

    Attributes
    ----------
    params : RateState
        Friction law and parameters.
    drive : dryfriction.rsf.spring.SpringSlider
        Load-point program and machine (``stiffness = inf``: kinematic).
    initial : dryfriction.rsf.spring.RSFInitial
        Initial slip velocity (state at steady state for it).
    output : dryfriction.rsf.spring.RSFOutput
        Sampling interval and solver tolerance.
    """

    params: RateState
    drive: SpringSlider
    initial: RSFInitial = RSFInitial()
    output: RSFOutput = RSFOutput()
    source: str = "<string>"

    @property
    def law(self) -> str:
        return "rsf"

    @property
    def program(self) -> VelocityProgram:
        return self.drive.program

    @property
    def stiffness(self) -> float:
        return self.drive.stiffness

    @property
    def damping(self) -> float:
        return self.drive.damping

    @property
    def mass(self) -> float:
        return self.drive.mass

    def run(self) -> RSFResult:
        """Run :func:`dryfriction.rsf.driving.simulate`; a failed integration is a
        ``ValueError`` naming the protocol file and the cause."""
        from ..rsf.driving import SolverError, simulate

        try:
            return simulate(self.params, self.drive, self.initial, self.output)
        except (SolverError, ValueError) as exc:
            raise ValueError(f"{self.source}: {exc}") from None


class _Table:
    """Typed access to one TOML table; every error names source, table and key."""

    def __init__(self, source: str, name: str, data: Any) -> None:
        self.source, self.name = source, name
        if not isinstance(data, Mapping):
            self.fail(f"{name} must be a table, got {type(data).__name__}")
        self.data = dict(data)

    def fail(self, msg: str) -> None:
        raise ValueError(f"{self.source}: {msg}")

    def where(self, key: str) -> str:
        return f"{self.name}.{key}"

    def allow(self, keys: tuple[str, ...]) -> None:
        unknown = sorted(set(self.data) - set(keys))
        if unknown:
            self.fail(f"unknown key(s) {', '.join(self.name + '.' + k for k in unknown)}: allowed "
                      f"{', '.join(keys)}")

    def number(self, key: str, default: float | None = None, required: bool = False
               ) -> float | None:
        if key not in self.data:
            if required:
                self.fail(f"{self.where(key)} is missing: a number is required")
            return default
        v = self.data[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            self.fail(f"{self.where(key)} = {v!r} has the wrong type: a number is required")
        if not math.isfinite(float(v)):
            self.fail(f"{self.where(key)} = {v!r} is not allowed: a finite number")
        return float(v)

    def integer(self, key: str) -> int | None:
        if key not in self.data:
            return None
        v = self.data[key]
        if isinstance(v, bool) or not isinstance(v, int):
            self.fail(f"{self.where(key)} = {v!r} has the wrong type: an integer is required")
        return int(v)

    def string(self, key: str, default: str | None = None, required: bool = False
               ) -> str | None:
        if key not in self.data:
            if required:
                self.fail(f"{self.where(key)} is missing: a string is required")
            return default
        v = self.data[key]
        if not isinstance(v, str):
            self.fail(f"{self.where(key)} = {v!r} has the wrong type: a string is required")
        return v

    def build(self, what: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
        """Call a validating constructor, prefixing its message with source and table."""
        try:
            return what(*args, **kwargs)
        except ValueError as exc:
            raise ValueError(f"{self.source}: in {self.name}: {exc}") from None


def _segments(tab: _Table) -> VelocityProgram:
    raw = tab.data.get("segments")
    if raw is None:
        tab.fail(f"{tab.where('segments')} is missing: a list of "
                 "{velocity = ..., duration = ...} or {velocity = ..., slip = ...}")
    if not isinstance(raw, list) or not raw:
        tab.fail(f"{tab.where('segments')} = {raw!r} is not allowed: a non-empty list of tables")
    segs = []
    for i, item in enumerate(raw):
        sub = _Table(tab.source, f"{tab.name}.segments[{i}]", item)
        sub.allow(("velocity", "duration", "slip"))
        v = sub.number("velocity", required=True)
        d = sub.number("duration")
        s = sub.number("slip")
        segs.append(sub.build(Segment, v, d, s))
    return tab.build(VelocityProgram, segs)


def parse_protocol(text: str, source: str = "<string>"
                   ) -> Protocol | RSFProtocol | InterfaceProtocol:
    """Parse and validate a protocol given as TOML text; ``source`` names it in errors."""
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{source}: malformed TOML: {exc}") from None
    return protocol_from_dict(doc, source)


def protocol_from_dict(doc: Mapping[str, Any], source: str = "<protocol>"
                       ) -> Protocol | RSFProtocol | InterfaceProtocol:
    """Validate a protocol already read into nested dicts (e.g. one point of a sweep).

    ``model.law = "rsf"`` gives an :class:`RSFProtocol`, an ``[interface]`` table an
    :class:`InterfaceProtocol`, otherwise a :class:`Protocol`.
    """
    if not isinstance(doc, Mapping):
        raise ValueError(f"{source}: a protocol must be a table of tables")
    model_tab = doc.get("model")
    law = model_tab.get("law", "cv") if isinstance(model_tab, Mapping) else "cv"
    if law not in LAWS:
        raise ValueError(f"{source}: model.law = {law!r} is not allowed: choose one of "
                         f"{', '.join(LAWS)}")
    if law == "rsf":
        return _rsf_protocol(doc, source)
    if "interface" in doc:
        return _interface_protocol(doc, source)
    from ..ensemble.driving import ForceDrive, Output, SpringDrive, VelocityDrive
    from ..ensemble.resources import check_run
    from ..ensemble.result import check_snapshots

    _check_tables(doc, _TABLES, source)

    model = _trap_model(doc, source)
    track, initial = _population(doc, source)

    d = _Table(source, "drive", doc["drive"])
    kind = _drive_kind(d, "cv")
    extra = sorted(set(d.data) - {"kind", *_DRIVE_KEYS[kind]})
    if extra:
        others = {k for kk, keys in _DRIVE_KEYS.items() if kk != kind for k in keys}
        why = "applies to another kind" if set(extra) <= others else "is unknown"
        d.fail(f"drive key(s) {', '.join(extra)} {why}: kind = {kind!r} allows "
               f"{', '.join(('kind', *_DRIVE_KEYS[kind]))}")
    for key in _REQUIRED_DRIVE[kind]:
        if key not in d.data:
            d.fail(f"{d.where(key)} is missing: required for kind = {kind!r}")
    drive: Drive
    if kind == "velocity":
        drive = d.build(VelocityDrive, _segments(d))
    elif kind == "force":
        drive = d.build(ForceDrive, rate=d.number("rate"), hold=d.number("hold", 0.0),
                        max_force=d.number("max_force", 10.0))
    else:
        drive = d.build(SpringDrive, stiffness=d.number("stiffness"), mass=d.number("mass"),
                        damping=d.number("damping", 0.0), program=_segments(d))

    if kind == "force" and initial.kind == "loaded" and \
            drive.max_force <= float(initial.force or 0.0):
        # the ramp would stop at its first sample, before any ramp (found by the fuzz: the
        # figure of such a run failed with a NumPy error)
        d.fail(f"drive.max_force = {drive.max_force:g} is out of range: allowed more than "
               f"ensemble.initial_force = {initial.force:g} F_el, where the ramp starts")
    o = _Table(source, "output", doc["output"])
    o.allow(("every", "every_slip", "snapshots"))
    snaps = o.data.get("snapshots", [])
    if not isinstance(snaps, list) or any(
        isinstance(s, bool) or not isinstance(s, (int, float)) for s in snaps
    ):
        o.fail(f"{o.where('snapshots')} = {snaps!r} has the wrong type: a list of times (t0)")
    output = o.build(Output, every=o.number("every"), every_slip=o.number("every_slip"),
                     snapshots=tuple(float(s) for s in snaps))
    try:  # snapshots within the run, and the memory it would hold, before any work
        check_snapshots(drive, output, qualified=True)
        check_run(model, track, initial, drive, output, qualified=True)
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None
    return Protocol(model, track, initial, drive, output, source)


def _trap_model(doc: Mapping[str, Any], source: str) -> TrapModel:
    """The ``[model]`` table of a trap-model protocol."""
    from ..theory.model import TrapModel

    m = _Table(source, "model", doc["model"])
    m.allow(("law", "alpha", "eps", "creep", "mu_el", "direct", "v_ref"))
    return m.build(  # type: ignore[no-any-return]
        TrapModel,
        alpha=m.number("alpha", 0.13),
        eps=m.number("eps", required=True),
        creep=m.string("creep", "log"),
        mu_el=m.number("mu_el", 1.0),
        direct=m.number("direct", 0.0),
        v_ref=m.number("v_ref", 1.0),
    )


def _population(doc: Mapping[str, Any], source: str) -> tuple[Track, Initial]:
    """The ``[ensemble]`` table: the track and the initial population on it."""
    from ..ensemble.population import Initial, Track

    e = _Table(source, "ensemble", doc["ensemble"])
    e.allow(("traps_per_a0", "layout", "seed", "initial", "initial_force", "initial_velocity"))
    track = e.build(
        Track,
        traps_per_a0=e.number("traps_per_a0", required=True),
        layout=e.string("layout", "regular"),
        seed=e.integer("seed"),
    )
    initial = e.build(
        Initial,
        kind=e.string("initial", required=True),
        force=e.number("initial_force"),
        velocity=e.number("initial_velocity"),
        track=track,
    )
    return track, initial


_SWEEP_TABLES = ("sweep", "stickslip", "catalogue")
"""Tables of a sweep protocol that ``dryfriction sweep`` takes off before each point is read
as a protocol (:mod:`dryfriction.app.sweeps`)."""


def _tables_hint(unknown: list[str], tables: tuple[str, ...]) -> str:
    """What an unknown table may have meant (ours; a new user's ``[modle]`` was answered with
    a list that left out the tables other kinds of protocol take): the closest allowed name,
    and where the other kinds' tables belong."""
    import difflib

    said = []
    for name in unknown:
        known = (*tables, *(() if "ensemble" not in tables else ("interface",)))
        close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
        if close:
            said.append(f"[{name}]: did you mean [{close[0]}]?")
    other = [t for t in unknown if t in _SWEEP_TABLES]
    if other:
        said.append(f"[{'], ['.join(other)}] {'belongs' if len(other) == 1 else 'belong'} "
                    "to a sweep protocol, run with dryfriction sweep")
    if "interface" not in tables and "interface" in unknown:
        said.append("[interface] is for the trap model (model.law = 'cv')")
    if "ensemble" in tables and "interface" not in tables and not any(
            "interface" in x for x in said):
        said.append("an [interface] table makes it an extended-interface protocol")
    return " (" + "; ".join(said) + ")" if said else ""


def _check_tables(doc: Mapping[str, Any], tables: tuple[str, ...], source: str,
                  missing_hint: str = "") -> None:
    """Exactly ``tables`` at the top of a protocol file: one line naming an unknown or a
    missing table (``missing_hint`` said after the missing one)."""
    unknown = sorted(set(doc) - set(tables))
    if unknown:
        raise ValueError(f"{source}: unknown table(s) {', '.join(unknown)}: allowed "
                         f"{', '.join(tables)}{_tables_hint(unknown, tables)}")
    for t in tables:
        if t not in doc:
            raise ValueError(f"{source}: table '{t}' is missing{missing_hint}")


_INTERFACE_TABLES = ("model", "ensemble", "interface", "drive", "output")
_INTERFACE_KEYS = ("n_elements", "coupling", "mass", "damping", "disorder", "normal_spread",
                   "density_spread", "quasi_static_rate", "multirate")
_INTERFACE_DRIVE_KEYS = {
    "uniform": ("kind", "stiffness", "segments"),
    "side": ("kind", "stiffness", "edge_stiffness", "segments"),
}


@dataclass(frozen=True)
class InterfaceProtocol:
    """A validated extended-interface protocol: a chain of trap-model blocks
    (:mod:`dryfriction.ensemble.interface`), reduced units.

    Tables: ``[model]`` (the traps' law), ``[ensemble]`` (every block's track density, layout,
    seed and initial population), ``[interface]`` (``n_elements``, ``coupling``, ``mass``,
    ``damping``, ``disorder``, ``normal_spread``, ``density_spread``,
    ``quasi_static_rate``, ``multirate``), ``[drive]`` (``kind =
    "uniform"`` with ``stiffness`` and ``segments``, or ``kind = "side"`` with ``edge_stiffness``,
    optional ``stiffness`` and ``segments``), ``[output]`` (``every`` or ``every_slip``).
    """

    model: InterfaceModel
    initial: Initial
    drive: InterfaceDrive
    output: Output
    source: str = "<string>"

    @property
    def track(self) -> Track:
        assert self.initial.track is not None
        return self.initial.track

    def run(self, progress: Callable[[float], None] | None = None,
            on_interrupt: str = "raise") -> InterfaceResult:
        """Run :func:`dryfriction.ensemble.interface.simulate_interface`."""
        from ..ensemble.interface import simulate_interface

        return simulate_interface(self.model, self.drive, self.initial, self.output,
                                  on_interrupt=on_interrupt)


def _interface_protocol(doc: Mapping[str, Any], source: str) -> InterfaceProtocol:
    """The branch of :func:`protocol_from_dict` for a file with an ``[interface]`` table."""
    from ..ensemble.interface import InterfaceDrive, InterfaceModel, check_interface
    from ..ensemble.result import Output

    _check_tables(doc, _INTERFACE_TABLES, source,
                  f" (an [interface] protocol has {', '.join(_INTERFACE_TABLES)})")
    trap = _trap_model(doc, source)
    if trap.direct != 0.0:  # a [model] key: named there, not in [interface] (InterfaceModel's)
        raise ValueError(f"{source}: model.direct = {trap.direct:g} is not allowed with an "
                         "[interface] table: allowed 0 (the chain's blocks have no direct "
                         "effect yet)")
    _, initial = _population(doc, source)
    i = _Table(source, "interface", doc["interface"])
    i.allow(_INTERFACE_KEYS)
    n = i.integer("n_elements")
    if n is None:
        i.fail("interface.n_elements is missing: an integer is required")
    model = i.build(InterfaceModel, trap, n_elements=n,
                    coupling=i.number("coupling", required=True),
                    mass=i.number("mass", required=True), damping=i.number("damping", 0.0),
                    disorder=i.string("disorder", "independent"),
                    normal_spread=i.number("normal_spread", 0.0),
                    density_spread=i.number("density_spread", 0.0),
                    quasi_static_rate=i.number("quasi_static_rate", 0.0),
                    multirate=i.data.get("multirate", False))
    d = _Table(source, "drive", doc["drive"])
    kinds = ", ".join(repr(k) for k in _INTERFACE_DRIVE_KEYS)
    kind = d.string("kind", required=True)
    if kind not in _INTERFACE_DRIVE_KEYS:
        d.fail(f"drive.kind = {kind!r} is not allowed with an [interface] table: choose one "
               f"of {kinds} (uniform loading from the top plate, or side loading)")
    assert kind is not None
    d.allow(_INTERFACE_DRIVE_KEYS[kind])
    drive = d.build(InterfaceDrive, kind,
                    stiffness=d.number("stiffness", required=kind == "uniform") or 0.0,
                    program=_segments(d),
                    edge_stiffness=d.number("edge_stiffness", required=kind == "side") or 0.0)
    o = _Table(source, "output", doc["output"])
    o.allow(("every", "every_slip"))
    output = o.build(Output, every=o.number("every"), every_slip=o.number("every_slip"))
    try:  # memory, samples and time before any work
        check_interface(model, drive, initial, output)
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None
    return InterfaceProtocol(model, initial, drive, output, source)


def _rsf_protocol(doc: Mapping[str, Any], source: str) -> RSFProtocol:
    """The ``law = "rsf"`` branch of :func:`protocol_from_dict` (SI units)."""
    unknown = sorted(set(doc) - set(_RSF_TABLES))
    if unknown:
        why = " (the ensemble table applies to law = 'cv')" if "ensemble" in unknown else ""
        raise ValueError(f"{source}: table(s) {', '.join(unknown)} not allowed with "
                         f"model.law = 'rsf'{why}: allowed {', '.join(_RSF_TABLES)}"
                         f"{_tables_hint([u for u in unknown if u != 'ensemble'], _RSF_TABLES)}")
    for t in ("model", "drive"):
        if t not in doc:
            raise ValueError(f"{source}: table '{t}' is missing")
    m = _Table(source, "model", doc["model"])
    m.allow(_RSF_MODEL_KEYS)
    for key in ("a", "b", "dc", "mu0", "v0"):
        m.number(key, required=True)
    for key in ("b2", "dc2"):
        m.number(key)
    m.string("state_law")
    if "regularized" in m.data and not isinstance(m.data["regularized"], bool):
        m.fail(f"{m.where('regularized')} = {m.data['regularized']!r} has the wrong type: "
               "true or false")
    params = m.build(RateState.from_mapping, m.data)

    d = _Table(source, "drive", doc["drive"])
    kind = _drive_kind(d, "rsf")
    keys = _RSF_DRIVE_KEYS[kind]
    extra = sorted(set(d.data) - {"kind", *keys})
    if extra:
        d.fail(f"drive key(s) {', '.join(extra)} not allowed: kind = {kind!r} with model.law = "
               f"'rsf' allows {', '.join(('kind', *keys))}")
    stiffness = math.inf
    if kind == "spring":
        if "stiffness" not in d.data:
            d.fail("drive.stiffness is missing: required for kind = 'spring' (1/m; kind = "
                   "'velocity' is the kinematic machine)")
        raw = d.data["stiffness"]
        stiffness = raw if raw == math.inf else d.number("stiffness")
    drive = d.build(SpringSlider, _segments(d), stiffness, d.number("damping", 0.0),
                    d.number("mass", 0.0))
    initial = d.build(RSFInitial, v=d.number("v_init"))

    o = _Table(source, "output", doc.get("output", {}))
    o.allow(("every", "rtol"))
    output = o.build(RSFOutput, every=o.number("every"), rtol=o.number("rtol", 1e-7))
    d.build(drive.check_model, params)
    d.build(initial.resolve, params, drive)
    try:  # the memory a run would hold, before any work
        check_rsf_run(params, drive, output, qualified=True)
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None
    return RSFProtocol(params, drive, initial, output, source)


def _drive_kind(d: _Table, law: str) -> str:
    """``drive.kind``, required and the same grammar for both laws: ``velocity`` (kinematic
    program), ``spring`` (spring slider), ``force`` (force ramp, trap model only)."""
    kinds = ", ".join(repr(k) for k in _DRIVE_KEYS)
    if "kind" not in d.data:
        hint = (" (rate-and-state files without it: add kind = 'spring' with drive.stiffness, "
                "or kind = 'velocity' for the kinematic machine)" if law == "rsf" else "")
        d.fail(f"drive.kind is missing: a string is required, one of {kinds}{hint}")
    kind = d.string("kind")
    if kind not in _DRIVE_KEYS:
        d.fail(f"drive.kind = {kind!r} is not allowed: choose one of {kinds}")
    assert kind is not None
    if law == "rsf" and kind not in _RSF_DRIVE_KEYS:
        d.fail(f"drive.kind = {kind!r} is not allowed with model.law = 'rsf' (force control is "
               "for the trap model): choose 'velocity' (kinematic) or 'spring'")
    return kind


def load_protocol(path: str | os.PathLike[str]) -> Protocol | RSFProtocol | InterfaceProtocol:
    """Read and validate a protocol file (TOML). Errors name the file and the key."""
    p = Path(path)
    try:
        raw = p.read_bytes()
        check_text(raw[:HEAD_BYTES], str(p))  # gzip, UTF-16: named, not "malformed TOML"
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise ValueError(f"{p}: malformed TOML: not UTF-8 text") from None
    except OSError as exc:
        raise ValueError(f"{p}: cannot read the protocol: {exc.strerror}") from None
    return parse_protocol(text, str(p))


# ------------------------------------------------------------------ [stickslip] sweep points

STICKSLIP_KEYS = ("transient", "stick_fraction", "rel_threshold", "floor", "follow_velocity")
"""Keys of the ``[stickslip]`` table (the stick-slip analysis; see
:func:`dryfriction.analysis.stickslip.stick_slip_summary`)."""


def pulling_velocity(drive: SpringDrive) -> float:
    """The load velocity of a spring drive's last segment (what a sweep point pulls at)."""
    return float(drive.program.segments[-1].velocity)


_STICKSLIP_RANGES: dict[str, tuple[float, float | None, bool, bool]] = {
    # key: (lo, hi, lo_open, hi_open), as validation.check_scalar takes them
    "transient": (0.0, None, False, False),
    "stick_fraction": (0.0, 1.0, True, False),
    "rel_threshold": (0.0, 1.0, True, True),
    "floor": (0.0, None, True, False),
}


def option_table(table: Any, name: str, keys: tuple[str, ...], source: str, *,
                 ranges: Mapping[str, tuple[float, float | None, bool, bool]],
                 whole: Mapping[str, int] | None = None,
                 flags: tuple[str, ...] = ()) -> dict[str, Any]:
    """Check an options table of a sweep protocol (``[stickslip]``, ``[catalogue]``): its
    keys, types and ranges, declared as data; return it as a dict.

    Parameters
    ----------
    table : mapping or None
        The table; ``None`` means no table (every default: ``{}``).
    name : str
        The table's name, in every message (``name.key``).
    keys : tuple of str
        The keys allowed, in the order the messages list them.
    source : str
        Where the table comes from, put in front of every message.
    ranges : mapping
        ``key -> (lo, hi, lo_open, hi_open)`` of a number, as
        :func:`dryfriction.validation.check_scalar` takes them.
    whole : mapping, optional
        ``key -> lowest value`` of a whole number (an integer value, ``1.0`` included).
    flags : tuple of str
        Keys that are booleans.

    Raises
    ------
    ValueError
        One line: an unknown key, a value of the wrong type (a TOML boolean is an int to
        Python: refused where a number is meant, rather than read true as 1), a number out of
        its range; the message names ``name.key`` and the allowed range.
    """
    if table is None:
        return {}
    if not isinstance(table, Mapping):
        raise ValueError(f"{source}: [{name}] must be a table of {', '.join(keys)}")
    unknown = sorted(str(k) for k in set(table) - set(keys))
    if unknown:
        raise ValueError(f"{source}: unknown key(s) "
                         f"{', '.join(name + '.' + k for k in unknown)}: "
                         f"allowed {', '.join(keys)}")
    whole = whole or {}
    opts: dict[str, Any] = {}
    for key, value in table.items():
        where = f"{name}.{key}"
        if key in flags:
            if not isinstance(value, bool):
                raise ValueError(f"{source}: {where} = {value!r} is not allowed: true or false")
            opts[key] = value
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ValueError(f"{source}: {where} = {value!r} is not a number")
        if key in whole:
            low = whole[key]
            if not math.isfinite(value) or value != int(value) or value < low:
                raise ValueError(f"{source}: {where} = {value!r} is out of range: allowed a "
                                 f"whole number >= {low}")
            opts[key] = int(value)
            continue
        lo, hi, lo_open, hi_open = ranges[key]
        try:
            opts[key] = check_scalar(where, value, lo, hi, lo_open=lo_open, hi_open=hi_open)
        except ValueError as exc:
            raise ValueError(f"{source}: {exc}") from None
    return opts


def stickslip_options(table: Any, source: str = "protocol") -> dict[str, Any]:
    """Check a ``[stickslip]`` table (keys, types and ranges: :data:`STICKSLIP_KEYS`, the
    ranges of ``_STICKSLIP_RANGES``, ``follow_velocity`` a boolean) and return it as a dict
    (:func:`option_table`).

    Raises
    ------
    ValueError
        For an unknown key, a value that is not a number (or, for ``follow_velocity``, not a
        boolean) or a number out of its range; the message names ``stickslip.<key>``.
    """
    return option_table(table, "stickslip", STICKSLIP_KEYS, source, ranges=_STICKSLIP_RANGES,
                        flags=("follow_velocity",))


def spring_point(protocol: Mapping[str, Any], source: str = "sweep point",
                 analysis: str = "stick-slip") -> tuple[Protocol, dict[str, Any]]:
    """Parse a spring-slider sweep point completely, without running it.

    Returns the parsed :class:`Protocol` (after ``follow_velocity``) and the checked
    ``[stickslip]`` options; raises ``ValueError`` for anything the sweep runners
    (:func:`dryfriction.analysis.stickslip.stick_slip_summary`,
    :func:`dryfriction.analysis.linear.linear_summary`) would refuse at run time: a bad
    ``[stickslip]`` table, a rate-and-state protocol, a drive that is not a spring, a last
    segment that does not pull and, for ``analysis = "stick-slip"``, a ``transient`` not shorter
    than the load-point travel.
    """
    doc = dict(protocol)
    opts = stickslip_options(doc.pop("stickslip", None), source)
    model_tab = doc.get("model", {})
    if isinstance(model_tab, Mapping) and model_tab.get("law", "cv") == "rsf":
        raise ValueError(f"{source}: model.law = 'rsf': sweeps of rate-and-state protocols "
                         "are not supported yet (stick-slip summaries and --linear need the "
                         "trap model)")
    ens = dict(doc.get("ensemble", {}))
    drive_tab = doc.get("drive", {})
    segs = drive_tab.get("segments") if isinstance(drive_tab, Mapping) else None
    last = segs[-1] if isinstance(segs, list) and segs else None
    pull = last.get("velocity") if isinstance(last, Mapping) else None
    # only a number is followed: anything else (a sweep that set the segments to [1, 2] or a
    # velocity to [0.1]) is left to protocol_from_dict, which names the key and the type
    if opts.get("follow_velocity", True) and ens.get("initial") == "steady" and \
            isinstance(pull, (int, float)) and not isinstance(pull, bool):
        ens["initial_velocity"] = float(pull)
        doc["ensemble"] = ens
    proto = protocol_from_dict(doc, source)
    if isinstance(proto, RSFProtocol):  # unreachable after the check above; kept for types
        raise ValueError(f"{source}: rate-and-state sweeps are not supported yet")
    from ..ensemble.driving import SpringDrive

    if not isinstance(proto.drive, SpringDrive):
        raise ValueError(f"{source}: drive.kind must be 'spring' for a stick-slip or "
                         "linear-stability sweep")
    u = pulling_velocity(proto.drive)
    if u <= 0.0:
        raise ValueError(f"{source}: the last segment's velocity {u:g} must be > 0 to pull")
    if analysis != "stick-slip":
        return proto, opts
    positions = proto.drive.program.positions
    travel = float(positions[-1] - positions[0])
    if opts.get("transient", 0.0) >= travel:
        raise ValueError(f"{source}: stickslip.transient = {opts['transient']:g} a0 is out of "
                         f"range: allowed less than the load-point travel {travel:g} a0")
    return proto, opts
