"""An artifact zoo of laboratory records (issue 23): seeded, generated on demand, never stored.

Each record is a commanded load program (velocity steps up and down of ratio 1.3 to 30, a short
step of a few Dc of slip, slide-hold-slides, a many-step run, or no change at all) driven
through an independent forward model, with the apparatus' artifacts added alone and combined,
and written in one of the reader's dialects.

Forward model (written here, not the package's solver): a quasi-static spring slider with
rate-and-state friction and the ageing law (Dieterich 1979; Ruina 1983), in the variables
``(tau, ln theta)``, integrated by SciPy's ``solve_ivp`` (LSODA)::

    V = V0 exp((tau - mu0 - b ln(V0 theta / Dc)) / a)
    dtau/dt = k (V_load - V),   d ln(theta)/dt = 1/theta - V/Dc

Artifact levels are those measured on the shared sepiolite record
(``examples/data/lab``, 0.2 -> 2 um/s, 7.4 Hz): white displacement noise 0.17 um, a 20 nm
quantum, friction noise 3.5e-4, normal-stress noise 1 kPa on 30 MPa. The load point's own
fluctuations are calibrated on that record's noise spectrum, the relative scatter of the
slopes of adjacent windows of 2 to 80 s (``python -m benchmarks bench_detect_levels`` prints
the record's and the zoo's side by side; at 2 um/s the zoo's servo error with the machine
oscillation is within a factor 1.4 of the record's at every scale of 2-80 s).

The servo (ours; the standard picture of a load point under position feedback, e.g. Ogata,
*Modern Control Engineering*, 5th ed., ch. 5: a type-1 loop tracks a ramp with a bounded
error): the commanded displacement is followed by a position loop, so what wanders is the
*position error* ``e``, a stationary displacement process, not the velocity (whose
integrated wander, a random walk, would grow without bound). A disturbance of the drive
proportional to its speed (a motor's or a screw's ripple: the shared record's wander is the
same fraction of the velocity at 0.2 and 2 um/s) is corrected by the loop with time constant
``SERVO_TAU``::

    de/dt = -e / SERVO_TAU + V_load(t) eta(t),   x = x_commanded + e

``eta`` an Ornstein-Uhlenbeck process of rms ``SERVO_RMS`` and correlation time
``SERVO_ETA_TAU``. Over windows shorter than ``SERVO_TAU`` the velocity wanders as ``eta``
does; over longer ones the slope scatter falls like a bounded displacement's (as ``1/T`` and
faster), as the shared record's does (0.006 and 0.004 of the velocity at 40 and 80 s).
``e`` is continuous through a velocity change (no jump of the load point at a step) and
relaxes to 0 in a hold. The machine oscillation (``wobble``) is a velocity oscillation, a
bounded displacement too. The servo bursts of the issue (3 -> 3.36 -> 3 um/s for 0.5-3 s)
are added as +-12 % velocity excursions of 0.5-3 s.

A harsher **stress family** (:func:`stress_specs`, reported apart from the target rates by
``bench_detect``) replaces the servo error by the zoo's first wander model, an
Ornstein-Uhlenbeck process on the *velocity* (``walk``: 8 % rms, 3 s): its displacement is a
random walk, 5-6 times the shared record's slope scatter at 40-80 s.

Artifacts (names used in :data:`ARTIFACTS`):

* ``red``: the servo's position error (above); ``walk`` (stress family only): a relative
  velocity wander, Ornstein-Uhlenbeck of 8 % rms and 3 s; ``wobble``: the machine
  oscillation, 6 % at 22 s and 4 % at 45 s periods;
  ``bursts``: 3 to 8 servo bursts;
* ``rate``: the sampling rate changes 10-fold (up, or down from >= 10 Hz) at a random time or
  at a change; ``irregular``: sampling intervals jittered by +-30 %; ``gaps``: 1 to 3 missing
  stretches of 5 s to 5 % of the record, at most 60 s (10 s away from the changes): samples not
  written, the load point moving on; across one the displacement grows by the exact integral of
  the velocity with its oscillation and bursts (:func:`_gap_increments`; until stop 42 the
  trapezoid of the gap's two ends, a jump of up to a tenth of the velocity times the gap that
  no apparatus makes);
* ``reset``: the displacement transducer re-zeroed once (a jump with no slip);
  ``drift``: a slow displacement drift of 2 um over the record;
  ``quant``: a coarse quantum of 0.1-0.5 um;
* a velocity column (the ``velocity`` dialect) is the servo's reading: the load point's
  velocity (the servo error's rate included) with 2 % white noise (no reset, drift or
  transducer noise: those are a displacement transducer's);
* ``normal``: the normal stress changes once (10 to 30 MPa, over a 2-10 s ramp), a segment
  boundary the detector must report.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from unittest.mock import patch

import numpy as np
from scipy.integrate import solve_ivp

ARTIFACTS = ("red", "wobble", "bursts", "rate", "irregular", "gaps", "reset", "drift", "quant",
             "normal")
PROGRAMS = ("up", "down", "short", "multi", "shs", "none")
DIALECTS = ("tab_um", "comma_mm", "semicolon_decimal_comma", "space_units_row", "velocity")

WHITE = 0.17e-6  # m, displacement noise (shared record)
QUANTUM = 20e-9  # m (shared record's smallest increment)
SERVO_RMS, SERVO_ETA_TAU, SERVO_TAU = 0.08, 1.0, 3.0  # servo disturbance (1, s), loop (s)
WALK_RMS, WALK_TAU = 0.08, 3.0  # stress family: relative velocity wander (1, s)
WOBBLE = ((0.06, 22.0), (0.04, 45.0))  # (relative amplitude, period s)
MU_NOISE, SN_NOISE = 3.5e-4, 1e3


@dataclass
class ZooRecord:
    """One generated record and its truth (times in s from the first sample)."""

    name: str
    program: str
    artifacts: tuple[str, ...]
    dialect: str
    t: np.ndarray
    x: np.ndarray  # load-point displacement, m
    mu: np.ndarray
    sn: np.ndarray  # Pa
    changes: list[float]  # commanded velocity changes, s
    normal_changes: list[float] = field(default_factory=list)
    normal_ramp: float = 0.0
    v: np.ndarray | None = None  # load-point velocity as a servo reports it, m/s
    velocities: list[float] = field(default_factory=list)  # commanded, m/s, one per stretch
    quantum: float = QUANTUM  # m, the displacement's quantum (``quant``: 0.1-0.5 um)
    # for an oracle that knows them: the relative velocity excursions (machine oscillation and
    # bursts, 1) and the displacement added by the drift and the reset (m)
    eps: np.ndarray | None = None
    x_known: np.ndarray | None = None
    # the servo bursts alone (``bursts``): (start s from the first sample, duration s, relative
    # velocity excursion 1), part of ``eps``; their displacement is :func:`burst_displacement`
    bursts: list[tuple[float, float, float]] = field(default_factory=list)
    # ``int (1 + eps) dt`` from the first sample, s, as the displacement was integrated (the
    # trapezoid, exact across a gap: :func:`_gap_increments`)
    e_int: np.ndarray | None = None

    @property
    def rows(self) -> int:
        return len(self.t)


# ------------------------------------------------------------------------------ forward model
def friction(t: np.ndarray, program: list[tuple[float, float]], *, a: float, b: float,
             dc: float, k: float, mu0: float = 0.6) -> np.ndarray:
    """Friction at times ``t`` under the load program ``[(start s, V_load m/s), ...]``
    (first start 0, first velocity > 0: steady sliding there) from the model above."""
    v0 = program[0][1]

    def rhs(_t: float, y: np.ndarray, vl: float) -> list[float]:
        tau, lth = y
        v = v0 * math.exp((tau - mu0 - b * (math.log(v0 / dc) + lth)) / a)
        return [k * (vl - v), math.exp(-lth) - v / dc]

    y = np.array([mu0, math.log(dc / v0)])
    out = np.empty_like(t)
    starts = [s for s, _ in program] + [max(float(t[-1]), program[-1][0]) + 1.0]
    for (s, vl), e in zip(program, starts[1:], strict=False):
        m = (t >= s) & (t < e)
        sol = solve_ivp(rhs, (s, e), y, method="LSODA", t_eval=t[m], args=(vl,),
                        rtol=1e-8, atol=[1e-10, 1e-8])
        if m.any():
            out[m] = sol.y[0]
        y = sol.y[:, -1] if not m.any() or sol.t[-1] == e else solve_ivp(
            rhs, (float(sol.t[-1]), e), sol.y[:, -1], method="LSODA", args=(vl,),
            rtol=1e-8, atol=[1e-10, 1e-8]).y[:, -1]
    return out


# ------------------------------------------------------------------------------ programs
def _program(kind: str, rng: np.random.Generator, dc: float) -> list[tuple[float, float]]:
    """``[(start s, V m/s)]``: each slide of 150-400 um and 60-2500 s."""
    v1 = 10 ** rng.uniform(-7.0, -4.3)  # 0.1 to 50 um/s
    ratio = float(rng.choice([1.3, 2.0, 3.0, 10.0, 30.0]))

    def dur(v: float) -> float:
        return float(np.clip(rng.uniform(150e-6, 400e-6) / v, 60.0, 2500.0))

    if kind == "none":
        vel = [v1]
    elif kind in ("up", "down"):
        vel = [v1, v1 * ratio if kind == "up" else v1 / ratio]
    elif kind == "short":  # a step of a few Dc, then on to a third velocity
        r = float(rng.choice([3.0, 10.0]))
        vel = [v1, v1 * r, v1]
    elif kind == "multi":
        r = float(rng.choice([3.0, 10.0]))
        v1 = min(v1, 1e-3 / r**2)  # at most 1 mm/s
        vel = [v1 * r**j for j in (0, 1, 2, 1, 0)][: int(rng.integers(3, 6))]
    else:  # shs: slide, hold, slide, longer hold, slide
        vel = [v1, 0.0, v1, 0.0, v1]
    out, t = [], 0.0
    for j, v in enumerate(vel):
        out.append((t, v))
        if v == 0.0:
            t += float(rng.uniform(10.0, 300.0))
        elif kind == "short" and j == 1:
            t += max(float(rng.uniform(4.0, 6.0)) * dc / v, 8.0)  # a few Dc (at least 8 s)
        else:
            t += dur(v)
    out.append((t, float("nan")))  # the end
    return out


def _sample_times(end: float, fs: float, arts: tuple[str, ...], changes: list[float],
                  rng: np.random.Generator) -> tuple[np.ndarray, list[tuple[float, float]]]:
    """The sample times (s) and the gaps cut from them (``(start, end)`` s each)."""
    dt = 1.0 / fs
    cut: list[tuple[float, float]] = []
    if "rate" in arts:
        at = float(rng.choice(changes)) if changes and rng.random() < 0.5 else float(
            rng.uniform(0.2, 0.8) * end)
        f2 = 10.0 if fs < 10.0 or rng.random() < 0.5 else 0.1  # never below 1 Hz
        t = np.concatenate([np.arange(0.0, at, dt), np.arange(at, end, dt / f2)])
    else:
        t = np.arange(0.0, end, dt)
    if "irregular" in arts:
        d = np.diff(t) * rng.uniform(0.7, 1.3, t.size - 1)
        t = np.concatenate([[0.0], np.cumsum(d)])
        t = t[t < end]
    if "gaps" in arts:
        for _ in range(int(rng.integers(1, 4))):
            g = float(rng.uniform(5.0, max(min(60.0, 0.05 * end), 5.0)))
            for _try in range(20):
                s = float(rng.uniform(0.05, 0.9) * end)
                if all(abs(c - s) > 10.0 and abs(c - s - g) > 10.0 and not s < c < s + g
                       for c in changes):
                    t = t[(t < s) | (t > s + g)]
                    cut.append((s, s + g))
                    break
    return t, cut


def _gap_increments(t: np.ndarray, cut: list[tuple[float, float]], phases: list[float],
                    bursts: list[tuple[float, float, float]]) -> tuple[np.ndarray, np.ndarray]:
    """The sample intervals ``i`` (from ``t[i]`` to ``t[i + 1]``, s) that span a gap of ``cut``,
    and the exact integral over each of ``1 + eps`` (s) without the ``walk``: its length, the
    machine oscillation's (:data:`WOBBLE`, ``phases`` its random phases; empty: none) and the
    bursts' (``(start, duration, excursion)``). A gap is samples not written, not another
    motion: the trapezoid of the two ends over 5-60 s (what the other intervals take, a tenth
    of a second to a second) put a jump of up to a tenth of the velocity times the gap into the
    displacement, which the detection rightly read as a reset."""
    # a gap that runs past the last sample only ends the record early
    idx = np.array([k for k in (int(np.searchsorted(t, a)) - 1 for a, _ in cut)
                    if 0 <= k < t.size - 1], dtype=np.int64)
    if idx.size == 0:
        return idx, np.zeros(0)
    a, b = t[idx], t[idx + 1]
    out = b - a
    for (amp, per), ph in zip(WOBBLE, phases, strict=False):
        w = 2.0 * np.pi / per
        out = out + amp * (np.cos(w * a + ph) - np.cos(w * b + ph)) / w
    for s, d, amp in bursts:
        out = out + amp * np.clip(np.minimum(b, s + d) - np.maximum(a, s), 0.0, None)
    return idx, out


def _ou(t: np.ndarray, tau: float, rms: float, rng: np.random.Generator) -> np.ndarray:
    """An Ornstein-Uhlenbeck process sampled at ``t`` (exact AR(1) update)."""
    out = np.empty_like(t)
    out[0] = rng.normal(0.0, rms)
    rho = np.exp(-np.diff(t) / tau)
    e = rng.normal(0.0, 1.0, t.size - 1) * rms * np.sqrt(1.0 - rho**2)
    for i in range(1, t.size):
        out[i] = rho[i - 1] * out[i - 1] + e[i - 1]
    return out


def servo_error(t: np.ndarray, v: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """The load point's position error ``e`` (m) at times ``t`` under the commanded velocity
    ``v`` (m/s): ``de/dt = -e / SERVO_TAU + v eta`` (module docstring), ``eta`` held over each
    interval (exact exponential update), started at its quasi-static value."""
    eta = _ou(t, SERVO_ETA_TAU, SERVO_RMS, rng)
    rho = np.exp(-np.diff(t) / SERVO_TAU)
    drive = v[:-1] * eta[:-1] * SERVO_TAU * (1.0 - rho)
    e = np.empty_like(t)
    e[0] = v[0] * eta[0] * SERVO_TAU
    for i in range(1, t.size):
        e[i] = rho[i - 1] * e[i - 1] + drive[i - 1]
    return e


def step_displacement(t: np.ndarray, vc: np.ndarray, rng: np.random.Generator,
                      wobble: bool = True) -> np.ndarray:
    """The load point's measured displacement (m) at times ``t`` under the commanded velocity
    ``vc`` (m/s), as the oracle's and the small-step tests' records draw it: the machine
    oscillation (:data:`WOBBLE`, random phases) relative to ``vc`` where ``wobble``,
    integrated by the trapezoid, the servo's position error (:func:`servo_error`), the
    transducer's white noise (:data:`WHITE`) and its quantum (:data:`QUANTUM`)."""
    eps = np.zeros_like(t)
    if wobble:
        for amp, per in WOBBLE:
            eps += amp * np.sin(2 * np.pi * t / per + rng.uniform(0, 2 * np.pi))
    vt = vc * (1 + eps)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (vt[1:] + vt[:-1]) * np.diff(t))])
    x += servo_error(t, vc, rng) + rng.normal(0, WHITE, t.size)
    return np.round(x / QUANTUM) * QUANTUM


def make_record(index: int, program: str, artifacts: tuple[str, ...], dialect: str,
                seed: int = 0) -> ZooRecord:
    """The zoo record ``index`` (its own seed: ``seed * 100003 + index``)."""
    rng = np.random.default_rng(seed * 100003 + index)
    dc = float(10 ** rng.uniform(-5.3, -4.7))  # 5 to 20 um
    a = float(rng.uniform(0.005, 0.012))
    b = a + float(rng.uniform(-0.004, 0.003))
    k = 20.0 * b / dc  # stiff enough to stay stable
    prog = _program(program, rng, dc)
    end = prog[-1][0]
    prog = prog[:-1]
    changes = [s for s, _ in prog[1:]]
    shortest = min([e - s for (s, _), (e, _) in zip(prog, prog[1:] + [(end, 0.0)],
                                                    strict=True)])
    # as a lab samples: faster for faster sliding, >= 100 samples in the shortest stretch
    fs = float(np.clip(max(200.0 / shortest, 2.0 * max(v for _, v in prog) / 1e-6 / 10.0),
                       1.0, 100.0))
    fs = float(min((1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0), key=lambda f: abs(
        math.log(f / fs)) if f >= fs else 1e9))
    t, cut = _sample_times(end, fs, artifacts, changes, rng)
    vl = np.zeros_like(t)
    for s, v in prog:
        vl[t >= s] = v
    # the load point's motion: the commanded velocity times (1 + the relative velocity
    # fluctuations), then the servo's position error
    eps = np.zeros_like(t)
    walk = np.zeros_like(t)
    if "walk" in artifacts:
        walk = _ou(t, WALK_TAU, WALK_RMS, rng)
        eps += walk
    phases: list[float] = []
    if "wobble" in artifacts:
        for amp, per in WOBBLE:
            phases.append(float(rng.uniform(0, 2 * np.pi)))
            eps += amp * np.sin(2 * np.pi * t / per + phases[-1])
    bursts: list[tuple[float, float, float]] = []
    if "bursts" in artifacts:
        for _ in range(int(rng.integers(3, 9))):
            s, w = float(rng.uniform(0, end)), float(rng.uniform(0.5, 3.0))
            amp = float(rng.choice([-0.12, 0.12]))
            eps += np.where((t >= s) & (t < s + w), amp, 0.0)
            bursts.append((s, w, amp))
    vt = vl * (1.0 + eps)
    # the load point's displacement, ``int vl (1 + eps)``: the trapezoid over each sample
    # interval, the exact integral over one spanning a gap (:func:`_gap_increments`); ``e_int``
    # is ``int (1 + eps)`` the same way (for an oracle that knows the fluctuations)
    g = 1.0 + eps
    e_inc = 0.5 * (g[1:] + g[:-1]) * np.diff(t)
    inc = 0.5 * (vt[1:] + vt[:-1]) * np.diff(t)
    gi, exact = _gap_increments(t, cut, phases, bursts)
    if gi.size:
        # the velocity's random walk (``walk``) has no closed form: the trapezoid, as elsewhere
        exact = exact + 0.5 * (walk[gi] + walk[gi + 1]) * (t[gi + 1] - t[gi])
        e_inc[gi] = exact
        inc[gi] = vl[gi] * exact  # no change lies in a gap (10 s away from each)
    x = np.concatenate([[0.0], np.cumsum(inc)])
    e_int = np.concatenate([[0.0], np.cumsum(e_inc)])
    if "red" in artifacts:
        e = servo_error(t, vl, rng)
        x += e
        # the servo's velocity reading sees the error's rate too
        vt = vt + np.gradient(e, t)
    x += 1e-3 + rng.normal(0.0, WHITE, t.size)
    x_plain = x.copy()
    if "drift" in artifacts:
        x += 2e-6 * np.sin(np.pi * t / end + rng.uniform(0, np.pi))
    if "reset" in artifacts:
        i = int(rng.integers(t.size // 10, 9 * t.size // 10))
        x[i:] -= x[i] if rng.random() < 0.5 else rng.uniform(-500e-6, 500e-6)
    x_known = x - x_plain
    q = float(rng.uniform(0.1e-6, 0.5e-6)) if "quant" in artifacts else QUANTUM
    x = np.round(x / q) * q
    mu = friction(t, [(s, v) for s, v in prog], a=a, b=b, dc=dc, k=k)
    mu += rng.normal(0.0, MU_NOISE, t.size)
    sn = np.full(t.size, 30e6)
    normal_changes: list[float] = []
    ramp = 0.0
    if "normal" in artifacts:
        # in the longest slide (>= 60 s), 30 to 70 % of the way through it
        bounds = [(s0, e0) for (s0, v0), (e0, _) in zip(prog, prog[1:] + [(end, 0.0)],
                                                       strict=True) if v0 > 0.0]
        s0, e0 = max(bounds, key=lambda b: b[1] - b[0])
        s = s0 + float(rng.uniform(0.3, 0.7)) * (e0 - s0)
        ramp = float(rng.uniform(2.0, 10.0))
        hi = float(rng.choice([10e6, 20e6]))
        sn = 30e6 + (hi - 30e6) * np.clip((t - s) / ramp, 0.0, 1.0)
        normal_changes = [s + 0.5 * ramp]
    sn = sn + rng.normal(0.0, SN_NOISE, t.size)
    # a servo's velocity reading: the load point's, 2 % white noise, the same quantum per s
    v_read = np.round(vt * (1.0 + rng.normal(0.0, 0.02, t.size)) / QUANTUM) * QUANTUM
    return ZooRecord(f"zoo_{index:03d}_{program}_{'+'.join(artifacts) or 'plain'}",
                     program, artifacts, dialect, t + 100.0, x, mu, sn, changes,
                     normal_changes, ramp, v_read, [v for _, v in prog], q, eps, x_known,
                     bursts, e_int)


def burst_velocity(rec: ZooRecord) -> np.ndarray:
    """The servo bursts' part of the load point's velocity (m/s) at ``rec.t``: the commanded
    velocity times their relative excursions (:attr:`ZooRecord.bursts`), as
    :func:`make_record` adds them."""
    t = rec.t - float(rec.t[0])
    eb = np.zeros_like(t)
    for s, w, amp in rec.bursts:
        eb += np.where((t >= s) & (t < s + w), amp, 0.0)
    ch = np.asarray(rec.changes, float)
    vl = np.asarray(rec.velocities, float)[np.searchsorted(ch, t, side="right")]
    return vl * eb


def burst_displacement(rec: ZooRecord) -> np.ndarray:
    """The servo bursts' displacement (m) at ``rec.t``: :func:`burst_velocity` integrated by
    the trapezoid, as :func:`make_record` integrates the velocity."""
    vb = burst_velocity(rec)
    return np.concatenate([[0.0], np.cumsum(0.5 * (vb[1:] + vb[:-1]) * np.diff(rec.t))])


def specs(n: int = 300) -> Iterator[tuple[int, str, tuple[str, ...], str]]:
    """``(index, program, artifacts, dialect)`` of the zoo's first ``n`` records: every
    artifact alone and with none, with every program, then all together, then random
    combinations."""
    singles: list[tuple[str, ...]] = [()] + [(a,) for a in ARTIFACTS]
    rng = np.random.default_rng(12345)
    i = 0
    while i < n:
        block = i // len(PROGRAMS)
        prog = PROGRAMS[i % len(PROGRAMS)]
        if block < len(singles):
            arts = singles[block]
        elif block % 2 == 0:
            arts = ARTIFACTS
        else:
            arts = tuple(a for a in ARTIFACTS if rng.random() < 0.5)
        if prog == "none" and "normal" in arts:
            arts = tuple(a for a in arts if a != "normal") + ("normal",)
        yield i, prog, arts, DIALECTS[i % len(DIALECTS)]
        i += 1


def record_at(index: int) -> ZooRecord:
    """Zoo record ``index``, with the program, artifacts and dialect :func:`specs` gives it."""
    *_, (i, prog, arts, dialect) = specs(index + 1)
    return make_record(i, prog, arts, dialect)


def stress_specs(n: int = 300) -> Iterator[tuple[int, str, tuple[str, ...], str]]:
    """The stress family (module docstring): each of :func:`specs`' first ``n`` records with
    the servo error (``red``) in it, with the velocity random walk (``walk``) instead, from the
    same seed. Not part of the target rates."""
    for i, prog, arts, dialect in specs(n):
        if "red" in arts:
            yield i, prog, tuple("walk" if a == "red" else a for a in arts), dialect


def write(rec: ZooRecord, folder: Path) -> Path:
    """Write ``rec`` in its dialect; returns the path."""
    t, x, mu, sn = rec.t, rec.x, rec.mu, rec.sn
    d = rec.dialect
    path = folder / f"{rec.name}.{'csv' if d == 'comma_mm' else 'txt'}"
    if d == "tab_um":
        head, cols, sep = "Time(s)\tDispl(microns)\tFriction\tEffectiveNormalstress(MPa)", (
            t, x * 1e6, mu, sn / 1e6), "\t"
    elif d == "comma_mm":
        head, cols, sep = "time [s],LP_disp [mm],mu,sigma_n [MPa]", (t, x * 1e3, mu, sn / 1e6), ","
    elif d == "semicolon_decimal_comma":
        head, cols, sep = "Time (s);Load point (um);Friction;Normal stress (MPa)", (
            t, x * 1e6, mu, sn / 1e6), ";"
    elif d == "space_units_row":
        head, cols, sep = "time  lp_disp  friction  normal_stress\ns  um  -  MPa", (
            t, x * 1e6, mu, sn / 1e6), "  "
    else:  # a velocity column, no displacement
        v = rec.v if rec.v is not None else np.gradient(x, t)
        head, cols, sep = "Time(s)\tlp_velocity(um/s)\tFriction\tNormal_stress(MPa)", (
            t, v * 1e6, mu, sn / 1e6), "\t"
    body = np.column_stack(cols)
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(head + "\n")
        lines = [f"{r[0]:.6f}" + sep + sep.join(f"{c:.9g}" for c in r[1:]) for r in body]
        text = "\n".join(lines) + "\n"
        if d == "semicolon_decimal_comma":
            text = text.replace(".", ",")
        fh.write(text)
    return path


# ------------------------------------------------------------------------------ scoring
@dataclass
class Score:
    """How the detection of one record compares with its truth."""

    right: bool
    found: int  # velocity changes detected
    false: int  # detected changes farther than FALSE_WINDOW from any true one
    missed: int
    worst_error: float  # s, largest time error of a matched change
    cpu: float  # s, detection CPU time
    count_right: bool = False  # the right number of velocity and normal-stress changes
    note: str = ""
    # per true change, where the number is right: (ratio of the faster to the slower velocity
    # (inf at a hold), time error s, tolerance s, inside its 95 % interval or None where the
    # detector gave none, placed (Segment.start_placed))
    changes: list[tuple[float, float, float, bool | None, bool]] = field(default_factory=list)
    # the true holds (commanded velocity 0) and those the detection reports at velocity 0
    # (the segment holding each hold's middle): a hold reported at a speed is cut as steps
    holds: tuple[int, int] = (0, 0)


FALSE_WINDOW = 5.0  # s: a detected change farther than this from every true change is false


def one_change_right(recs: list, detect: Callable[[object], object]) -> int:
    """How many of ``recs`` (``(record, true change time s, tolerance s)`` each) ``detect``
    gives exactly one change within its tolerance of the truth (a record's program of two
    segments)."""
    return sum(len(segs) == 2 and abs(segs[1].t_start - tc) <= tol
               for segs, tc, tol in ((detect(r).segments, tc, tol) for r, tc, tol in recs))


def starts_with(recs: list, detect: Callable[[object], object], module: object, name: str,
                values: tuple = (True, False)) -> dict:
    """Each record's segments (first sample, 95 % interval's ends s) as ``detect`` gives them
    with the constant ``module.name`` set to each of ``values`` in turn (restored after)."""
    got = {}
    for value in values:
        with patch.object(module, name, value):
            got[value] = [tuple((s.i_start, s.start_lo, s.start_hi) for s in detect(r).segments)
                          for r in recs]
    return got


def tolerance(t: np.ndarray, at: float) -> float:
    """The larger of one sample (the interval around ``at``) and 0.5 s."""
    i = int(np.clip(np.searchsorted(t, at), 1, len(t) - 1))
    return max(float(t[i] - t[i - 1]), 0.5)


def score(rec: ZooRecord, det: object, cpu: float) -> Score:
    """Compare a :class:`dryfriction.records.detection.Detection` with the truth of ``rec``."""
    segs = det.segments  # type: ignore[attr-defined]
    t0 = float(rec.t[0])
    found = [s.t_start - t0 for p, s in zip(segs, segs[1:], strict=False)
             if s.velocity != p.velocity]
    truth = list(rec.changes)
    t = rec.t - t0
    false = sum(1 for f in found if all(abs(f - c) > FALSE_WINDOW for c in truth))
    missed = sum(1 for c in truth if all(abs(f - c) > FALSE_WINDOW for f in found))
    right = len(found) == len(truth)
    worst = 0.0
    per: list[tuple[float, float, float, bool | None, bool]] = []
    if right:
        segs_at = [s for p, s in zip(segs, segs[1:], strict=False) if s.velocity != p.velocity]
        vel = rec.velocities or [float("nan")] * (len(truth) + 1)
        for j, (f, c, sg) in enumerate(zip(found, truth, segs_at, strict=True)):
            worst = max(worst, abs(f - c))
            tol = tolerance(t, c)
            right &= abs(f - c) <= tol
            lo, hi = getattr(sg, "start_lo", float("nan")), getattr(sg, "start_hi", float("nan"))
            inside = None if not np.isfinite(lo) else bool(lo - t0 <= c <= hi - t0)
            v1, v2 = abs(vel[j]), abs(vel[j + 1])
            ratio = max(v1, v2) / min(v1, v2) if min(v1, v2) > 0 else float("inf")
            per.append((ratio, f - c, tol, inside, bool(getattr(sg, "start_placed", True))))
    nfound = [x - t0 for x in det.normal_changes]  # type: ignore[attr-defined]
    nright = len(nfound) == len(rec.normal_changes) and all(
        abs(f - c) <= 0.5 * rec.normal_ramp + tolerance(t, c)
        for f, c in zip(nfound, rec.normal_changes, strict=True))
    note = "" if nright else f"normal changes {nfound} vs {rec.normal_changes}"
    count = len(found) == len(truth) and len(nfound) == len(rec.normal_changes)
    ends = [0.0, *truth, float(t[-1])]
    mids = [0.5 * (ends[k] + ends[k + 1]) for k, v in enumerate(rec.velocities) if v == 0.0]
    zero = sum(any(s.t_start - t0 <= m < s.t_end - t0 and s.velocity == 0.0 for s in segs)
               for m in mids)
    return Score(right and nright, len(found), false, missed, worst, cpu, count, note, per,
                 (len(mids), zero))


def ou_step(seed: int, v2: float) -> tuple[np.ndarray, np.ndarray, int]:
    """A placement test's record (not the zoo's): 1.3 um/s -> ``v2`` (m/s) at 90 s, sampled at
    8 Hz, the velocity wandering by an 8 % Ornstein-Uhlenbeck relative error of correlation
    time 3 s (exact AR(1) at the sampling step), integrated by the trapezoid rule, plus 0.17 um
    of white displacement noise; and a guess of the change's sample within 3 s of it, all from
    ``np.random.default_rng(seed)``. Returns times (s), displacement (m) and the guess."""
    fs, t_c = 8.0, 90.0
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, 180.0, 1.0 / fs)
    v = np.where(t >= t_c, v2, 1.3e-6)
    rho = np.exp(-1.0 / (fs * 3.0))
    eps = np.empty_like(t)
    eps[0] = rng.normal(0.0, 0.08)
    e = rng.normal(0.0, 0.08 * np.sqrt(1 - rho**2), t.size)
    for i in range(1, t.size):
        eps[i] = rho * eps[i - 1] + e[i]
    vt = v * (1 + eps)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (vt[1:] + vt[:-1]) / fs)])
    x = x + rng.normal(0.0, 0.17e-6, t.size)
    return t, x, int(np.searchsorted(t, t_c + rng.uniform(-3.0, 3.0)))
