"""The module paths of release 0.1 (a flat package), kept for one release.

``import dryfriction.trap`` still works and gives the names of :mod:`dryfriction.theory.trap`,
with a ``DeprecationWarning``; the old paths go in 0.3. The finder is consulted only after the
ordinary ones, so it costs nothing for the new paths.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import warnings
from collections.abc import Sequence
from types import ModuleType

MOVED: dict[str, str] = {
    "trap": "theory.trap", "creep": "theory.creep", "static": "theory.static",
    "steady": "theory.steady", "dieterich": "theory.dieterich",
    "stability": "theory.stability", "units": "theory.units",
    "ensemble": "ensemble.population", "driving": "ensemble.driving",
    "rsf_driving": "rsf.driving",
    "protocol": "io.protocol", "data": "records.data", "sweep": "sweeps.sweep",
    "stickslip": "analysis.stickslip", "rsf_view": "analysis.rsf_view",
    "plotting": "plots.paper", "figures": "plots.report",
    # release 0.2: io/ split by concern (issue 26 item 3)
    **{f"io.{m}": f"records.{m}" for m in (
        "lab", "labsteps", "labforms", "data", "detection", "segmentation", "placement",
        "artifacts", "hinge_kernel")},
    **{f"io.{m}": f"sweeps.{m}" for m in ("sweep", "cluster", "cf")},
}
"""Old module (under ``dryfriction.``) -> its new home. ``dryfriction.rsf`` and
``dryfriction.io`` are packages now; ``dryfriction.rsf.RateState`` still works. The records
and sweeps modules of ``dryfriction.io`` moved to ``dryfriction.records`` and
``dryfriction.sweeps`` (``dryfriction.io.lab`` -> ``dryfriction.records.lab``)."""


class MovedModuleFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Import ``dryfriction.OLD`` as a copy of the namespace of its new module."""

    def find_spec(self, fullname: str, path: Sequence[str] | None = None,
                  target: ModuleType | None = None) -> importlib.machinery.ModuleSpec | None:
        prefix, _, old = fullname.partition(".")
        if prefix != "dryfriction" or old not in MOVED:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def exec_module(self, module: ModuleType) -> None:
        new = "dryfriction." + MOVED[module.__name__.partition(".")[2]]
        warnings.warn(f"{module.__name__} has moved to {new}; the old path will be removed in "
                      "dryfriction 0.3", DeprecationWarning, stacklevel=2)
        real = importlib.import_module(new)
        module.__dict__.update({k: v for k, v in vars(real).items()
                                if k not in ("__name__", "__spec__", "__loader__")})
