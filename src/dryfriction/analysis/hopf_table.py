"""``dryfriction bifurcation``: the nature of the onset of stick-slip of a rate-and-state
protocol at a list of load velocities (the table's layout is ours).

Each row is :func:`.rsf_hopf.rsf_hopf` at one velocity with the protocol's friction law,
damping and mass (the protocol's own stiffness and program are not used: ``K_c`` is what is
sought). With ``check``, each row is also checked by direct simulation
(:mod:`.rsf_hopf_check`):

* supercritical: settled cycles at ``K = K_c (1 - d)``, ``d`` in :data:`CHECK_DISTANCES`; the
  fitted exponent of the amplitude (1/2 expected) with its standard error, and the ratio of
  the simulated amplitude at the smallest ``d`` to the normal form's;
* subcritical: the unstable cycle by bisection at ``K = K_c (1 + d)``, ``d = d1/4, d1/2, d1``
  (``d1 = 0.01`` or where the predicted cycle's half peak-to-peak ``ln V`` is 0.2), the
  exponent of its amplitude against ``d`` with its standard error, and the ratio of its
  amplitude to the normal form's at the smallest ``d``;
* degenerate: the bisection at ``d = 0.01`` with kicks up to ``ln(V/V*) = 2``: either every
  kick decays (as Ranjith & Rice 1999 prove for the ageing law) or a finite threshold is
  found (a global instability, not a small cycle: the slip law, Gu et al. 1984).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from ..ensemble.population import Track
from ..io.protocol import RSFProtocol
from ..io.units import TRAP_BIFURCATION_UNITS
from ..rsf.driving import SolverError
from ..rsf.law import V_MAX
from ..theory.model import TrapModel
from .rsf_hopf import rsf_hopf
from .rsf_hopf_check import amplitude_exponent, basin_threshold, settled_amplitude
from .trap_hopf import ALPHA0, trap_hopf
from .trap_hopf_check import check_cost, check_point

__all__ = ["parse_velocities", "bifurcation_table", "trap_bifurcation_table", "check_trap",
           "UNITS", "MAX_VELOCITIES", "MAX_TRAP_VELOCITIES", "MAX_CHECKED",
           "CHECK_DISTANCES", "TRAP_CHECK_CPU_MAX", "trap_check_cost"]

MAX_VELOCITIES = 400
"""Most velocities in one table (each costs ~10 ms; ours)."""
MAX_CHECKED = 12
"""Most velocities with ``check`` (each check runs ~5-30 s of simulations; ours)."""
CHECK_DISTANCES = (0.005, 0.01, 0.02)
"""Relative distances ``(K_c - K)/K_c`` of the supercritical check's settled cycles."""
SUB_FACTORS = (0.25, 0.5)
"""The subcritical check's further distances, in units of its first one (ours)."""

UNITS = {"velocity": "m/s", "K_c": "1/m (per unit normal force)", "frequency": "rad/s",
         "l1": "1 (reduced coordinates ln V, ln theta, tau/a)", "relative_l1": "1",
         "nature": "", "note": "", "amp_coef": "1 (half peak-to-peak ln V per sqrt(|K - K_c|/K_c))",
         "check": "", "check_distance": "1 (|K - K_c|/K_c of the amplitude ratio)",
         "check_exponent": "1", "check_exponent_err": "1",
         "check_amp_ratio": "1", "check_threshold": "1 (ln V kick)"}
"""The unit of each column of ``bifurcation.csv``."""

MAX_TRAP_VELOCITIES = 40
"""Most velocities in one trap-model table (each :func:`.trap_hopf.trap_hopf` costs ~0.1-1 s;
ours)."""
TRAP_CHECK_CPU_MAX = 1800.0
"""Longest estimated CPU time (s) of a trap-model ``check`` (:func:`trap_check_cost`; ours:
half an hour, a few supercritical velocities on 100 pairs per ``a0``)."""


def parse_velocities(text: str, v_max: float = V_MAX, unit: str = "m/s",
                     most: int = MAX_VELOCITIES) -> list[float]:
    """``"V1,V2,..."`` (``unit``, m/s unless told) as floats, each in ``(0, v_max]``, at most
    ``most``; ``ValueError`` naming ``--velocities`` otherwise."""
    parts = [p.strip() for p in str(text).split(",")]
    out = []
    for p in parts:
        try:
            v = float(p)
        except ValueError:
            raise ValueError(f"--velocities: {p!r} is not a number: allowed a comma-separated "
                             f"list of load velocities in (0, {v_max:g}] {unit}") from None
        if not 0.0 < v <= v_max:
            raise ValueError(f"--velocities: {p} is out of range: allowed (0, {v_max:g}] {unit}")
        out.append(v)
    if not 1 <= len(out) <= most:
        raise ValueError(f"--velocities: {len(out)} values: allowed 1 to {most}")
    return out


def _empty_check() -> dict[str, Any]:
    return {"check": "", "check_distance": math.nan, "check_exponent": math.nan,
            "check_exponent_err": math.nan, "check_amp_ratio": math.nan,
            "check_threshold": math.nan}


def _check(model: Any, h: Any, damping: float, mass: float) -> dict[str, Any]:
    out = _empty_check()
    if h.nature == "supercritical":
        out["check_distance"] = CHECK_DISTANCES[0]
        rows = [settled_amplitude(model, h, d, damping, mass) for d in CHECK_DISTANCES]
        beta, err, _ = amplitude_exponent(rows)
        first = rows[0]
        out.update(check_exponent=beta, check_exponent_err=err,
                   check_amp_ratio=first["amplitude"] / (h.amp_coef * math.sqrt(
                       first["distance"])))
        unsettled = [r["distance"] for r in rows if not r["settled"]]
        out["check"] = ("settled cycles below K_c" if not unsettled else
                        f"NOT settled at d = {unsettled} (exponent from the others)")
    elif h.nature in ("subcritical", "degenerate"):
        # where the predicted unstable cycle is small (half peak-to-peak ln V of 0.2)
        d = min(0.01, (0.2 / h.amp_coef) ** 2) if h.nature == "subcritical" else 0.01
        out["check_distance"] = d
        r = basin_threshold(model, h, d, damping, mass)
        out["check_threshold"] = r["delta_lo"] if math.isfinite(r["delta_hi"]) else math.nan
        if h.nature == "subcritical" and math.isfinite(r["amplitude"]):
            # the unstable branch at d/4, d/2 and d: its exponent (1/2 for a Hopf point;
            # a finite threshold that does not shrink, as the slip law's, would give ~0)
            rows = [basin_threshold(model, h, f * d, damping, mass) for f in SUB_FACTORS]
            beta, err, _ = amplitude_exponent(rows + [r])
            # the ratio and the threshold at the smallest distance, as the supercritical row
            out.update(check_distance=SUB_FACTORS[0] * d, check_exponent=beta,
                       check_exponent_err=err, check_threshold=rows[0]["delta_lo"]
                       if math.isfinite(rows[0]["delta_hi"]) else math.nan)
            out["check_amp_ratio"] = rows[0]["amplitude"] / (h.amp_coef * math.sqrt(
                SUB_FACTORS[0] * d))
            missed = [round(x["distance"], 6) for x in rows if not math.isfinite(x["amplitude"])]
            out["check"] = "unstable cycle by bisection above K_c" + (
                f" (NOT bracketed at d = {missed}: no exponent)" if missed else "")
        elif math.isfinite(r["delta_hi"]):
            out["check"] = "finite kick threshold above K_c"
        else:
            out["check"] = "every kick up to ln(V/V*) = 2 decays above K_c"
    else:
        out["check"] = "not run: no Hopf point" if h.nature == "none" else "not run"
    return out


def bifurcation_table(protocol: RSFProtocol, velocities: list[float], check: bool = False,
                      progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """Rows of the Hopf point's nature at each velocity (module docstring).

    Parameters
    ----------
    protocol : RSFProtocol
        Friction law (``params``) and machine (``drive.damping``, s/m; ``drive.mass``, s^2/m).
    velocities : list of float
        Load velocities, m/s (:func:`parse_velocities`).
    check : bool
        Also simulate each row (at most :data:`MAX_CHECKED` velocities).
    progress : callable, optional
        ``progress(done, total)`` after each velocity (a check takes ~5-30 s).

    Returns
    -------
    dict
        ``{"rows": [...], "units": UNITS, "law", "damping", "mass", "notes"}``.
    """
    if check and len(velocities) > MAX_CHECKED:
        raise ValueError(f"--velocities: {len(velocities)} values with --check: allowed at "
                         f"most {MAX_CHECKED} (each check simulates for ~5-30 s)")
    model, drive = protocol.params, protocol.drive
    rows = []
    for i, v in enumerate(velocities):
        h = rsf_hopf(model, v, drive.damping, drive.mass)
        row = h.as_row()
        if check:
            try:
                row.update(_check(model, h, drive.damping, drive.mass))
            except SolverError as exc:  # said in the row, not a crash of the whole table
                row.update({**_empty_check(), "check": f"simulation failed: {exc}"})
        rows.append(row)
        if progress is not None:
            progress(i + 1, len(velocities))
    notes = ["nature from the sign of the first Lyapunov coefficient l1 (Kuznetsov 2004); "
             "degenerate: |l1| < 1e-8 of its largest term (docs/hopf.md)"]
    if model.regularized:
        notes.append("regularized = true: the standard law is used (equal to it near steady "
                     "sliding to O((V0/V)^2 exp(-2 Psi/a)))")
    return {"rows": rows, "units": {k: UNITS[k] for k in rows[0]}, "law": model.state_law,
            "damping": drive.damping, "mass": drive.mass, "notes": notes}


def check_trap(model: TrapModel, mass: float, damping: float) -> None:
    """``ValueError`` in one line naming the protocol's parameter where
    :func:`.trap_hopf.trap_hopf` does not apply (before any work)."""
    if model.direct == 0.0:
        # a second new user read "no finite K_c" against stability's finite K_c: the
        # athermal slider's K_c is finite, its onset frequency is not (a supremum at omega ->
        # inf), and the normal form is written with the direct effect only
        raise ValueError("model.direct = 0 is not allowed here: the Hopf normal form is "
                         "written for the trap slider with the direct effect; without it the "
                         "massless slider's K_c is reached only as the frequency grows without "
                         "bound (dryfriction stability gives K_c, omega_c = inf); allowed "
                         "0 < direct <= 1")
    if model.alpha >= ALPHA0:
        raise ValueError(f"model.alpha = {model.alpha:g} is not allowed here: the normal form is "
                         f"written for very strong pinning; allowed 0 < alpha < {ALPHA0:.4f}")
    if mass == 0.0 and damping != 0.0:
        raise ValueError(f"drive.damping = {damping:g} is not allowed with drive.mass = 0; "
                         "allowed damping = 0")


def trap_check_cost(hops: list[Any], velocities: list[float], track: Track) -> float:
    """Estimated CPU seconds of the simulated check of every Hopf point in ``hops``
    (:func:`.trap_hopf_check.check_cost`)."""
    return sum(check_cost(h, u, track) for h, u in zip(hops, velocities, strict=True))


def trap_bifurcation_table(model: TrapModel, velocities: list[float], mass: float = 0.0,
                           damping: float = 0.0,
                           progress: Callable[[int, int], None] | None = None, *,
                           track: Track | None = None,
                           cpu_max: float = TRAP_CHECK_CPU_MAX) -> dict[str, Any]:
    """Rows of the Hopf point's nature of the trap model at each pulling velocity: each is
    :func:`.trap_hopf.trap_hopf` with its defaults (reduced units throughout). With a
    ``track``, each row is also checked by the trap ensemble on it
    (:func:`.trap_hopf_check.check_point`: settled cycles below ``K_c``, or the unstable
    cycle by bisection above it), after the estimate of its cost
    (:func:`trap_check_cost`) is found within ``cpu_max`` seconds; else ``ValueError`` in one
    line, before any simulation.

    Parameters
    ----------
    model : TrapModel
        With the direct effect, ``0 < direct``, and ``alpha < ALPHA0`` (:func:`check_trap`).
    velocities : list of float
        Pulling velocities ``u``, ``a0/t0``.
    mass, damping : float
        ``M`` (``F_el t0^2/a0``) and ``eta`` (``F_el t0/a0``).
    progress : callable, optional
        ``progress(done, total)`` after each velocity (and after each check).
    track : Track, optional
        The pairs of the check's ensemble (the protocol's); ``None``: no check.
    cpu_max : float
        Largest estimated CPU seconds of the check.

    Returns
    -------
    dict
        ``{"rows": [...], "units", "law": "trap", "damping", "mass", "notes"}``, the units
        :data:`dryfriction.io.units.TRAP_BIFURCATION_UNITS`.
    """
    check_trap(model, mass, damping)
    rows, hops = [], []
    total = len(velocities) * (2 if track is not None else 1)
    for i, u in enumerate(velocities):
        h = trap_hopf(u, model, mass, damping)
        hops.append(h)
        rows.append({"velocity": u, "K_c": h.K_c, "frequency": h.omega, "l1": h.l1_x,
                     "relative_l1": h.relative_l1, "nature": h.nature})
        if progress is not None:
            progress(i + 1, total)
    if track is not None:
        cost = trap_check_cost(hops, velocities, track)
        if cost > cpu_max:
            raise ValueError(
                f"--check: the trap ensemble's check of these {len(velocities)} velocities "
                f"would take about {cost / 60:.0f} CPU-minutes on {track.traps_per_a0:g} "
                f"pairs per a0; allowed up to {cpu_max / 60:.0f}: give fewer velocities or a "
                "sparser track (ensemble.traps_per_a0)")
        for i, (u, h) in enumerate(zip(velocities, hops, strict=True)):
            rows[i].update(check_point(u, model, h, track, mass, damping))
            if progress is not None:
                progress(len(velocities) + i + 1, total)
    notes = ["trap model, reduced units (a0, t0, F_el): K_c and l1 of the pseudospectral "
             "reduction of the population (dryfriction.analysis.trap_hopf, docs/hopf.md); "
             "nature from the sign of l1; degenerate: |l1| < 1e-8 of its largest term; "
             "none: stable at every stiffness"]
    return {"rows": rows, "units": {k: TRAP_BIFURCATION_UNITS[k] for k in rows[0]},
            "law": "trap", "damping": damping, "mass": mass, "notes": notes}
