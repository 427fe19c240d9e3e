"""Rate-and-state friction in SI units: the laws (:mod:`.law`), what a run is asked to do
(:mod:`.spring`: :class:`SpringSlider`, :class:`RSFInitial`, :class:`RSFOutput`), the
integrator (:mod:`.driving`: :func:`simulate`, :func:`simulate_rsf` its old name) and what
it returns (:mod:`.result`); the linear stability of steady sliding (:mod:`.stability`).

The solver's kernels - the RODAS4 stepper, its growth-rate step limit and the right-hand side of
the RSF equations, in :mod:`.stepper` (run interpreted for a small job, compiled by Numba for a
large one) - stay one module on purpose: splitting it was measured, and Numba 0.68
first-class functions (passing the equations to the stepper) were 5-17 % slower, while
inlining compiled functions across files breaks Numba's cache invalidation (a changed
equation in one file would not recompile the stepper cached from the other).

``dryfriction.rsf.RateState`` and ``dryfriction.rsf.simulate`` are the public names; they are
loaded on first use, so importing the law does not import the compiled solver.
"""

from __future__ import annotations

import importlib
from typing import Any

_PUBLIC = {
    "RateState": "law", "STATE_LAWS": "law",
    "simulate": "driving", "simulate_rsf": "driving", "RSFResult": "result",
    "SolverError": "driving", "linear_stability": "stability",
    "SpringSlider": "spring", "RSFInitial": "spring", "RSFOutput": "spring",
}
__all__ = sorted(_PUBLIC)


def __getattr__(name: str) -> Any:
    if name in _PUBLIC:
        return getattr(importlib.import_module(f".{_PUBLIC[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
