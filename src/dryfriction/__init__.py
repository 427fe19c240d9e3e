"""dryfriction: the Caroli-Velicky elasto-plastic model of dry friction.

Reduced units throughout the core: lengths in ``a0``, times in ``t0``, forces in ``F_el``
(eq. 12). :mod:`dryfriction.units` converts from SI.
"""

from .creep import CreepMaterial, EyringNabarroCreep, LogCreep, creep_law
from .program import Segment, VelocityProgram
from .trap import ALPHA0, Regime, Trap, regime

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
]

__version__ = "0.1.0"
