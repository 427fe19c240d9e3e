"""Rate-and-state friction in SI units: the laws (:mod:`.law`) and their compiled integrator
(:mod:`.driving`).

``dryfriction.rsf.RateState`` and ``dryfriction.rsf.simulate_rsf`` are the public names; they are
loaded on first use, so importing the law does not import the compiled solver.
"""

from __future__ import annotations

import importlib
from typing import Any

_PUBLIC = {
    "RateState": "law", "STATE_LAWS": "law",
    "simulate_rsf": "driving", "RSFResult": "driving", "SolverError": "driving",
}
__all__ = sorted(_PUBLIC)


def __getattr__(name: str) -> Any:
    if name in _PUBLIC:
        return getattr(importlib.import_module(f".{_PUBLIC[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
