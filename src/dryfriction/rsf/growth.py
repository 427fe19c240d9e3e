"""The RSF driver beside an unstable steady state (ours).

An L-stable method (RODAS4) stepping over an unstable mode damps it: started 1e-9 off an unstable
steady state it took one 1000 s step and reported steady sliding. :func:`growth_limit` keeps every
step within ``EFOLD`` e-folding times of a growing mode of the Jacobian (it lives in
:mod:`.stepper`, which runs it interpreted or compiled with its other kernels: one source file,
so that an edit invalidates Numba's cache of the stepper that inlines it; re-exported here).
:func:`unstable_start` and :func:`warn_unstable` tell the user when a run starts at, or beside,
a linearly unstable steady state.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .law import RateState
from .spring import SpringSlider
from .stability import linear_stability
from .stepper import EFOLD, below, growth_limit

__all__ = ["EFOLD", "NEAR_STEADY", "UnstableStartWarning", "below", "growth_limit",
           "unstable_start", "warn_unstable"]


class UnstableStartWarning(RuntimeWarning):
    """The run starts at, or beside, a linearly unstable steady state (the summary's
    ``unstable_start`` says the same; the command line reports it there only)."""


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
    try:
        growth = float(np.max(linear_stability(model, vl, drive.stiffness, drive.damping,
                                               drive.mass).real))
    except (ValueError, ArithmeticError, np.linalg.LinAlgError):
        # a Jacobian out of floating point (a ~ 1e-308), or none (a c + eta V = 0: a fit's
        # trial point at a = 0 on pure noise divided by zero here)
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
