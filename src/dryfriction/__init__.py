"""dryfriction: the Caroli-Velicky elasto-plastic model of dry friction.

Reduced units throughout the core: lengths in ``a0``, times in ``t0``, forces in ``F_el``
(eq. 12). :mod:`dryfriction.theory.units` converts from SI.

The package is layered, each layer importing only those below it::

    cli/        the command line
    plots/      every figure (the only matplotlib user)
    analysis/   stick-slip, the trap model seen through rate-and-state
    fit/        models, statistics, the fitting engine
    records/    measured records and data sets         sweeps/  parameter sweeps on Dask
    io/         files and results folders, protocol files (the only parser)
    ensemble/   the trap population and its drives      rsf/  rate-and-state laws and solver
    theory/     the model's equations
    program.py, validation.py

The names below are loaded on first use, so ``import dryfriction`` is cheap.
"""

from __future__ import annotations

import importlib
import sys
from typing import Any

from ._compat import MovedModuleFinder

__version__ = "0.1.0"

_PUBLIC: dict[str, str] = {
    # theory
    "ALPHA0": "theory.trap", "Regime": "theory.trap", "Trap": "theory.trap",
    "regime": "theory.trap",
    "LogCreep": "theory.creep", "EyringNabarroCreep": "theory.creep",
    "CreepMaterial": "theory.creep", "creep_law": "theory.creep",
    "static_friction": "theory.static", "static_friction_first_order": "theory.static",
    "loaded_edge": "theory.static", "pull_force": "theory.static",
    "steady_friction": "theory.steady", "steady_friction_first_order": "theory.steady",
    "steady_friction_low_velocity": "theory.steady", "steady_profile": "theory.steady",
    "static_friction_over_eps": "theory.static", "steady_friction_over_eps": "theory.steady",
    "dieterich_constant_asymptotic": "theory.dieterich",
    "dieterich_constant_least_squares": "theory.dieterich",
    "dieterich_constant_local": "theory.dieterich",
    "critical_stiffness": "theory.linear_stability", "effective_rsf": "theory.linear_stability",
    "TrapModel": "theory.model", "OldTheoryFormWarning": "theory.model",
    "InterfaceModel": "ensemble.interface", "InterfaceDrive": "ensemble.interface",
    "InterfaceResult": "ensemble.interface_result",
    "PhysicalScales": "theory.units", "static_friction_si": "theory.units",
    "steady_friction_si": "theory.units",
    # programs
    "Segment": "program", "VelocityProgram": "program",
    # simulators (simulate, below, runs either law) and the parts a run composes (a second
    # new user found the docs' Initial, Track and SpringSlider importable only from inner
    # modules)
    "Result": "simulation",
    "Initial": "ensemble.population", "Track": "ensemble.population",
    "VelocityDrive": "ensemble.drives", "ForceDrive": "ensemble.drives",
    "SpringDrive": "ensemble.drives", "Output": "ensemble.result",
    "SpringSlider": "rsf.spring", "RSFInitial": "rsf.spring", "RSFOutput": "rsf.spring",
    "RateState": "rsf.law", "RateStateModel": "rsf.law",
    "RSFResult": "rsf.driving", "SolverError": "rsf.driving", "simulate_rsf": "rsf.driving",
    # files, fitting
    "load_protocol": "io.protocol", "read_csv": "records.data",
    "fit": "fit",
}
_RENAMED = {"rsf_linear_stability": ("rsf.driving", "linear_stability")}

__all__ = sorted([*_PUBLIC, *_RENAMED, "__version__", "simulate"])


def simulate(*args: Any, **kwargs: Any) -> Any:
    """Run either law: ``simulate(model, drive, initial, output) -> Result``.

    Dispatches on the model's type (:mod:`dryfriction.simulation` lists the parts of each):

    * a ``TrapModel`` runs :func:`dryfriction.ensemble.driving.simulate` (reduced units;
      ``initial`` is an ``Initial`` with its ``track``; keywords ``progress``,
      ``on_interrupt``) and returns a ``SimulationResult``;
    * an ``InterfaceModel`` (a chain of trap-model blocks) runs
      :func:`dryfriction.ensemble.interface.simulate_interface` with an ``InterfaceDrive`` and
      returns an ``InterfaceResult`` (space-time fields);
    * a ``RateState`` runs :func:`dryfriction.rsf.driving.simulate` (SI; ``initial`` and
      ``output`` optional) and returns an ``RSFResult``.

    A part of the other law (its numbers in the other units) is refused in one line. The old
    trap-model form ``simulate(model, track, initial, drive, output)`` still works for one
    release and warns.

    Raises
    ------
    ValueError
        ``model`` is neither, or a part does not fit it, before any work.
    """
    model = args[0] if args else kwargs.get("model")
    # imported here: ``import dryfriction`` stays cheap, and a run imports its law's solver only
    from .rsf.law import RateState

    if isinstance(model, RateState):
        from .rsf.driving import simulate as run
    else:
        from .ensemble.interface import InterfaceModel
        from .theory.model import TrapModel

        if isinstance(model, InterfaceModel):
            from .ensemble.interface import simulate_interface as run
        elif not isinstance(model, TrapModel):
            raise ValueError(f"model = {model!r} is not allowed: a TrapModel (the trap model, "
                             "reduced units), an InterfaceModel (a chain of its blocks) or a "
                             "RateState (rate-and-state, SI)")
        else:
            from .ensemble.driving import simulate as run
    return run(*args, **kwargs)


def __getattr__(name: str) -> Any:
    if name in _PUBLIC:
        module = importlib.import_module(f".{_PUBLIC[name]}", __name__)
        value = module if name == "fit" else getattr(module, name)
    elif name in _RENAMED:
        where, attr = _RENAMED[name]
        value = getattr(importlib.import_module(f".{where}", __name__), attr)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return __all__


if not any(isinstance(f, MovedModuleFinder) for f in sys.meta_path):
    sys.meta_path.append(MovedModuleFinder())
