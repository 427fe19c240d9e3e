"""A whole laboratory experiment in one record (issue 23 item 4): velocity steps up and down at
two or three normal stresses, a slide-hold-slide at each, generated on demand from a seed.

Built on :mod:`records_zoo`'s independent forward model (:func:`records_zoo.friction`: a
quasi-static spring slider, rate-and-state friction with the ageing law, SciPy's LSODA), its
artifact levels and its writer; nothing of ``records_zoo`` is changed (its records for its seeds
stay as they are).

The experiment (ours, a typical velocity-stepping protocol): at each normal stress ``sn`` the
load point slides at ``V_1``, steps through ``velocities`` (each slide ``slide`` of load-point
travel), slides, holds ``hold`` s and reslides once at ``hold_velocity``; then the normal stress
ramps to the next level (over ``ramp`` s, in the middle of a slide at the level's last
velocity) and the same program runs again. Each level has its own ``a, b, Dc``
(:data:`LEVELS`) and the machine one stiffness in stress per displacement, ``K`` (Pa/m), so
its stiffness per unit normal stress, the fit's ``k`` (1/m), is ``K / sn``: lower at a higher
normal stress. At the normal-stress change friction is set to the new level's steady state at
the sliding velocity (the generator has no law for the transient a normal-stress change
causes; the detector cuts the record there, so no window holds it).

Sampling as a lab does it when the velocity spans decades: a fixed load-point travel per
sample (``dx``), so a faster slide is sampled faster (a rate change at every step, from
1 Hz at the slowest to 1 kHz at most).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from records_zoo import (
    MU_NOISE,
    QUANTUM,
    SERVO_RMS,
    SN_NOISE,
    WHITE,
    ZooRecord,
    friction,
    servo_error,
)

__all__ = ["Level", "LEVELS", "VELOCITIES", "ExperimentRecord", "make_experiment"]


@dataclass(frozen=True)
class Level:
    """One normal stress and the gouge's rate-and-state parameters there."""

    sn: float  # Pa
    a: float
    b: float
    dc: float  # m


LEVELS = (Level(10e6, 0.0080, 0.0060, 12e-6), Level(20e6, 0.0095, 0.0105, 18e-6),
          Level(30e6, 0.0110, 0.0140, 25e-6))
"""Three levels with different ``a - b`` (velocity strengthening at 10 MPa, weakening above),
``Dc`` 12-25 um."""

VELOCITIES = (1e-6, 3e-6, 10e-6, 30e-6, 100e-6, 300e-6, 10e-6)
"""The velocity program at each level (m/s): 1 -> 3 -> 10 -> 30 -> 100 -> 300 -> 10 um/s, six
steps a level; with the step 10 -> 1 um/s that starts each later level, 20 velocity steps at
three levels."""


@dataclass
class ExperimentRecord(ZooRecord):
    """A generated experiment and its truth."""

    levels: tuple[Level, ...] = ()
    # per velocity step, in time order: (change time s from the first sample, V before, V
    # after, level index)
    steps: list[tuple[float, float, float, int]] = field(default_factory=list)
    holds: list[tuple[float, float]] = field(default_factory=list)  # (start s, duration s)
    machine: float = 0.0  # K, Pa/m


def _program(levels: tuple[Level, ...], velocities: tuple[float, ...], slide: float,
             hold: float, hold_at: int) -> list[tuple[float, float, int]]:
    """``[(start s, V m/s, level)]`` and a final ``(end, nan, -1)``: at each level the
    velocities with a hold after ``velocities[hold_at]`` and a reslide at that velocity; a
    level after the first starts with a slide at the previous level's last velocity (the
    normal stress changes at its start, the velocity does not)."""
    out: list[tuple[float, float, int]] = []
    t = 0.0
    for li in range(len(levels)):
        j = hold_at
        vel = [*velocities[:j + 1], 0.0, velocities[j], *velocities[j + 1:]]
        if li:
            vel.insert(0, velocities[-1])
        for v in vel:
            out.append((t, v, li))
            t += hold if v == 0.0 else slide / v
    out.append((t, float("nan"), -1))
    return out


def make_experiment(seed: int = 0, *, levels: tuple[Level, ...] = LEVELS,
                    velocities: tuple[float, ...] = VELOCITIES, slide: float = 300e-6,
                    hold: float = 30.0, hold_at: int = 2, dx: float = 0.25e-6,
                    red: float = 0.0, ramp: float = 5.0, machine: float = 6e10,
                    dialect: str = "tab_um") -> ExperimentRecord:
    """A whole experiment (module docstring), times from 0 plus 100 s.

    Parameters
    ----------
    seed : int
        The noise's seed.
    levels, velocities : tuple
        Normal stresses with their parameters, and each level's velocity program (m/s).
    slide : float
        Load-point travel of each slide, m.
    hold, hold_at : float, int
        The hold's duration (s) and after which velocity of the program it comes.
    dx : float
        Load-point travel per sample, m (rate 1 Hz to 1 kHz).
    red : float
        The servo's relative velocity disturbance, rms (``records_zoo``'s ``red`` artifact,
        whose position error it scales).
    ramp : float
        Duration of the normal-stress ramp between levels, s.
    machine : float
        The machine's stiffness ``K``, Pa/m (the fit's ``k = K / sn``, 1/m).
    dialect : str
        ``records_zoo.write``'s dialect.
    """
    rng = np.random.default_rng(seed)
    prog = _program(levels, velocities, slide, hold, hold_at)
    end = prog[-1][0]
    body = prog[:-1]
    # sample times: a fixed travel per sample in each slide, 1 Hz in a hold
    pieces = []
    for (s, v, _), (e, _, _) in zip(body, prog[1:], strict=True):
        fs = float(np.clip(v / dx, 1.0, 1000.0)) if v > 0 else 1.0
        piece = s + np.arange(0.0, e - s, 1.0 / fs)
        pieces.append(piece[piece < e])
    t = np.concatenate(pieces)
    vl = np.zeros_like(t)
    for s, v, _ in body:
        vl[t >= s] = v
    x = np.concatenate([[0.0], np.cumsum(0.5 * (vl[1:] + vl[:-1]) * np.diff(t))])
    vt = vl
    if red > 0.0:  # the servo's position error, its disturbance scaled to red (rms)
        x = x + red / SERVO_RMS * servo_error(t, vl, rng)
        vt = np.gradient(x, t)  # what the servo reads: its error's rate included
    x = np.round((x + 1e-3 + rng.normal(0.0, WHITE, t.size)) / QUANTUM) * QUANTUM
    # friction, level by level: each starts in steady state at its first velocity
    mu = np.empty_like(t)
    sn = np.empty_like(t)
    starts = [next(s for s, _, li in body if li == j) for j in range(len(levels))] + [end]
    changes_n: list[float] = []
    for j, lev in enumerate(levels):
        s0, s1 = starts[j], starts[j + 1]
        m = (t >= s0) & (t < s1)
        sub = [(s - s0, v) for s, v, li in body if li == j]
        mu[m] = friction(t[m] - s0, sub, a=lev.a, b=lev.b, dc=lev.dc, k=machine / lev.sn)
        sn[m] = lev.sn
        if j:  # the ramp is centred on the level's start
            prev = levels[j - 1].sn
            w = np.clip((t - (s0 - 0.5 * ramp)) / ramp, 0.0, 1.0)
            near = (t >= s0 - ramp) & (t < s0 + ramp)
            sn[near] = (prev + (lev.sn - prev) * w)[near]
            changes_n.append(s0)
    mu += rng.normal(0.0, MU_NOISE, t.size)
    sn += rng.normal(0.0, SN_NOISE, t.size)
    steps: list[tuple[float, float, float, int]] = []
    holds: list[tuple[float, float]] = []
    changes: list[float] = []
    for (_, v0, _), (s1, v1, l1), (s2, _, _) in zip(body, body[1:], prog[2:], strict=False):
        if v1 == v0:
            continue
        changes.append(s1)
        if v1 == 0.0:
            holds.append((s1, s2 - s1))
        elif v0 != 0.0:
            steps.append((s1, v0, v1, l1))
    rec = ExperimentRecord(f"experiment_{seed}", "experiment", ("red",) if red else (),
                           dialect, t + 100.0, x, mu, sn, changes, changes_n, ramp, vt,
                           levels=tuple(levels), steps=steps, holds=holds, machine=machine)
    return rec
