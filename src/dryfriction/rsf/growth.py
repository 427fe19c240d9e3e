"""The RSF driver beside an unstable steady state (issue 14; ours).

An L-stable method (RODAS4) stepping over an unstable mode damps it: started 1e-9 off an unstable
steady state it took one 1000 s step and reported steady sliding. :func:`growth_limit` keeps every
step within ``EFOLD`` e-folding times of a growing mode of the Jacobian (compiled, called by the
driver); :func:`unstable_start` and :func:`warn_unstable` tell the user when a run starts at, or
beside, a linearly unstable steady state.
"""

from __future__ import annotations

import math
import warnings

import numba as nb
import numpy as np

from .law import RateState
from .spring import SpringSlider

__all__ = ["EFOLD", "NEAR_STEADY", "UnstableStartWarning", "below", "growth_limit",
           "unstable_start", "warn_unstable"]

EFOLD = 1.0
"""Most e-folding times of an unstable mode one step may span."""


class UnstableStartWarning(RuntimeWarning):
    """The run starts at, or beside, a linearly unstable steady state (the summary's
    ``unstable_start`` says the same; the command line reports it there only)."""


@nb.njit(cache=True)
def below(jac, s: float, sq) -> bool:
    """Every eigenvalue of ``jac`` has real part ``< s`` (Routh-Hurwitz, ours).

    The characteristic polynomial of ``M = jac - s I`` from the power sums ``tr M^k``
    (Newton's identities); for the 1-4 unknowns of the driver Hurwitz's conditions are
    explicit. No eigenvalue solver and no allocation (``sq`` is scratch for ``M^2``): this
    runs at every large step and must cost a few dozen flops.
    """
    n = jac.shape[0]
    p1 = 0.0
    for i in range(n):
        p1 += jac[i, i] - s
    for i in range(n):
        for j in range(n):
            acc = 0.0
            for q in range(n):
                acc += (jac[i, q] - (s if i == q else 0.0)) * (jac[q, j] - (s if q == j else 0.0))
            sq[i, j] = acc
    p2 = p3 = p4 = 0.0
    for i in range(n):
        p2 += sq[i, i]
        for j in range(n):
            p3 += sq[i, j] * (jac[j, i] - (s if i == j else 0.0))
            p4 += sq[i, j] * sq[j, i]
    e1 = p1
    e2 = (e1 * p1 - p2) / 2.0
    e3 = (e2 * p1 - e1 * p2 + p3) / 3.0
    e4 = (e3 * p1 - e2 * p2 + e1 * p3 - p4) / 4.0
    a1, a2, a3, a4 = -e1, e2, -e3, e4
    if n == 1:
        return a1 > 0.0
    if n == 2:
        return a1 > 0.0 and a2 > 0.0
    if n == 3:
        return a1 > 0.0 and a3 > 0.0 and a1 * a2 > a3
    return a1 > 0.0 and a3 > 0.0 and a4 > 0.0 and a1 * a2 * a3 > a3 * a3 + a1 * a1 * a4


@nb.njit(cache=True)
def growth_limit(jac, h: float, sq) -> float:
    """``h`` reduced (halved) until no eigenvalue of ``jac`` grows by more than
    ``EFOLD`` e-foldings in one step: an L-stable method would otherwise damp an unstable
    mode it steps over (a run started beside an unstable steady state stayed there)."""
    n = jac.shape[0]
    norm = 0.0
    for i in range(n):
        row = 0.0
        for q in range(n):
            row += abs(jac[i, q])
        norm = max(norm, row)
    # |Re lambda| <= ||J||: steps that short need no test
    while h * norm > EFOLD and not below(jac, EFOLD / h, sq):
        h *= 0.5
    return h


# a start within this relative distance (in V and theta) of the first segment's steady state
# is "at" it: the linear theory, not the start, decides what happens
NEAR_STEADY = 1e-3


def unstable_start(model: RateState, drive: SpringSlider, v: float, theta: float,
                    theta2: float | None) -> dict[str, float] | None:
    """The growth rate (1/s) when the run starts at, or beside, a linearly unstable steady
    state of its first segment; ``None`` otherwise (kinematic machine, a start away from the
    steady state, a stable one)."""
    vl = float(drive.program.velocities[0])
    if drive.kinematic or not vl > 0.0:
        return None
    off = [abs(math.log(v / vl)), abs(math.log(theta * vl / model.dc))]
    if theta2 is not None and model.dc2 is not None:
        off.append(abs(math.log(theta2 * vl / model.dc2)))
    if max(off) > NEAR_STEADY:
        return None
    from .driving import linear_stability  # driving imports this module

    try:
        growth = float(np.max(linear_stability(model, vl, drive.stiffness, drive.damping,
                                               drive.mass).real))
    except (ValueError, np.linalg.LinAlgError):  # a Jacobian out of floating point (a ~ 1e-308)
        return None
    if not growth > 0.0:
        return None
    return {"growth_rate_per_s": growth, "load_velocity": vl, "perturbation": v / vl - 1.0}


def warn_unstable(info: dict[str, float]) -> None:
    g, vl, dv = info["growth_rate_per_s"], info["load_velocity"], info["perturbation"]
    what = ("exactly there: only rounding errors seed the instability, so when it sets in "
            "is arbitrary" if dv == 0.0 else
            f"with the relative velocity perturbation {dv:.3g}, which grows as e^(t/"
            f"{1.0 / g:.3g} s)")
    warnings.warn(
        f"the run starts at steady sliding at V = {vl:g} m/s, which is linearly unstable on "
        f"this spring (growth rate {g:.3g} 1/s): it starts {what}; seed the stick-slip with "
        "v_init = V (1 + perturbation), e.g. 1.01 V", UnstableStartWarning, stacklevel=3)
