"""dryfriction: the Caroli-Velicky elasto-plastic model of dry friction.

Reduced units throughout the core: lengths in ``a0``, times in ``t0``, forces in ``F_el``
(eq. 12). :mod:`dryfriction.units` converts from SI.
"""

from .creep import CreepMaterial, EyringNabarroCreep, LogCreep, creep_law
from .dieterich import (
    dieterich_constant_asymptotic,
    dieterich_constant_least_squares,
    dieterich_constant_local,
)
from .program import Segment, VelocityProgram
from .rsf import RateState
from .rsf_driving import RSFResult, SolverError, simulate_rsf
from .rsf_driving import linear_stability as rsf_linear_stability
from .static import loaded_edge, pull_force, static_friction, static_friction_first_order
from .steady import (
    steady_friction,
    steady_friction_first_order,
    steady_friction_low_velocity,
    steady_profile,
)
from .trap import ALPHA0, Regime, Trap, regime
from .units import PhysicalScales, static_friction_si, steady_friction_si

__all__ = [
    "ALPHA0",
    "Regime",
    "Trap",
    "regime",
    "LogCreep",
    "EyringNabarroCreep",
    "CreepMaterial",
    "creep_law",
    "Segment",
    "VelocityProgram",
    "RateState",
    "RSFResult",
    "SolverError",
    "simulate_rsf",
    "rsf_linear_stability",
    "static_friction",
    "static_friction_first_order",
    "loaded_edge",
    "pull_force",
    "steady_friction",
    "steady_friction_first_order",
    "steady_friction_low_velocity",
    "steady_profile",
    "dieterich_constant_asymptotic",
    "dieterich_constant_least_squares",
    "dieterich_constant_local",
    "PhysicalScales",
    "static_friction_si",
    "steady_friction_si",
]

__version__ = "0.1.0"
