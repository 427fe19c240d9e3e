"""Compile the Numba kernels once, at install time: ``python -m dryfriction.warm``.

The kernels are compiled with ``cache=True``: the machine code is written next to the sources
(``__pycache__/*.nbi``, ``*.nbc``) and later processes load it instead of compiling (about 12 s
of CPU otherwise, paid by the first real run). ``make`` runs this module after installing,
so no user meets that pause. Numba keys its cache on the source file's path and timestamp: a
changed source is recompiled on its next use (and by the next ``make``, which reinstalls when
``pyproject.toml`` changes; run this module again after editing a kernel by hand).

Each run below is tiny and goes through the same public path as a command (the protocol
parser), so that every specialisation a command compiles is the one compiled here: the
trap-model kernel for each creep law and each kind of drive, and the rate-and-state solver
(one compiled kernel for every state law, which it takes as a parameter: two laws are run
here), one and two state variables, kinematic and spring machines, sampled and
every-step output, and its linear stability. A small rate-and-state run is interpreted
(:mod:`dryfriction.rsf.stepper`); here every one runs compiled, so that a large one finds the
compiled kernels cached.
"""

from __future__ import annotations

import os
import time
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any

__all__ = ["KERNEL_MODULES", "WARM_PROTOCOLS", "main", "missing_kernel_caches", "warm"]

KERNEL_MODULES: tuple[str, ...] = ("ensemble/kernel.py", "rsf/stepper.py")
"""The modules holding functions Numba compiles with ``cache=True``, relative to the package
(the rate-and-state kernels are compiled lazily, by :func:`dryfriction.rsf.stepper.compiled`)."""

_TRAP_MODEL = {"alpha": 0.13, "eps": 0.04}
_TRAP_ENSEMBLE = {"traps_per_a0": 20, "initial": "rest"}
_RSF_MODEL = {"law": "rsf", "a": 0.005, "b": 0.01, "dc": 1e-5, "mu0": 0.6, "v0": 1e-6}
_STEP = [{"velocity": 1e-6, "duration": 1.0}, {"velocity": 1e-5, "duration": 1.0}]

WARM_PROTOCOLS: tuple[Mapping[str, Any], ...] = (
    # the trap model: each creep law (the log law has a closed form, the others a table) and
    # each drive
    {"model": _TRAP_MODEL, "ensemble": _TRAP_ENSEMBLE,
     "drive": {"kind": "velocity", "segments": [{"velocity": 1.0, "slip": 0.5}]},
     "output": {"every_slip": 0.1}},
    {"model": {**_TRAP_MODEL, "creep": "eyring-nabarro"}, "ensemble": _TRAP_ENSEMBLE,
     "drive": {"kind": "velocity", "segments": [{"velocity": 1.0, "slip": 0.5}]},
     "output": {"every": 0.1}},
    {"model": _TRAP_MODEL, "ensemble": {**_TRAP_ENSEMBLE, "initial": "steady",
                                        "initial_velocity": 0.1},
     "drive": {"kind": "spring", "stiffness": 0.05, "mass": 1.0, "damping": 0.02,
               "segments": [{"velocity": 0.1, "slip": 0.5}]},
     "output": {"every": 1.0}},
    {"model": _TRAP_MODEL, "ensemble": _TRAP_ENSEMBLE,
     "drive": {"kind": "force", "rate": 0.5, "max_force": 0.3}, "output": {"every": 0.1}},
    # the extended interface (issue 29): its chain kernel (one for both loadings)
    {"model": _TRAP_MODEL, "ensemble": {**_TRAP_ENSEMBLE, "layout": "random", "seed": 1},
     "interface": {"n_elements": 2, "coupling": 1.0, "mass": 1.0},
     "drive": {"kind": "side", "edge_stiffness": 0.5,
               "segments": [{"velocity": 0.1, "slip": 0.2}]},
     "output": {"every": 1.0}},
    # rate-and-state: both laws, a second state variable, the regularised law, both machines,
    # sampled and every-step output
    {"model": _RSF_MODEL, "drive": {"kind": "velocity", "segments": _STEP}},
    {"model": {**_RSF_MODEL, "state_law": "slip", "b2": 0.002, "dc2": 1e-4},
     "drive": {"kind": "spring", "stiffness": 1e3, "segments": _STEP},
     "output": {"every": 0.1}},
    {"model": {**_RSF_MODEL, "regularized": True},
     "drive": {"kind": "spring", "stiffness": 250.0, "damping": 0.5, "mass": 1e-3,
               "segments": _STEP}},
)


def warm() -> float:
    """Run every protocol of :data:`WARM_PROTOCOLS` (compiling what is not cached yet) and the
    rate-and-state linear stability; return the wall time in seconds."""
    from .io.protocol import protocol_from_dict
    from .rsf.driving import linear_stability
    from .rsf.law import RateState
    from .rsf.stepper import interpreted_steps

    start = time.perf_counter()
    with warnings.catch_warnings():
        # the tiny stick-slip protocol starts at its (unstable) steady state on purpose: only
        # the compilation matters here, not the run's advice
        warnings.simplefilter("ignore", RuntimeWarning)
        with interpreted_steps(0):
            for i, doc in enumerate(WARM_PROTOCOLS):
                protocol_from_dict(doc, f"warm-up protocol {i}").run()
    linear_stability(RateState(0.005, 0.01, 1e-5, 0.6, 1e-6), 1e-6, 1e3)
    # the load-program detector's kernels (records/hinge_kernel.py, small: about 5 s to
    # compile in all, so it is not in KERNEL_MODULES' notice), each with the argument types
    # the detector gives it (segmentation.kernel_input: writable float64 arrays)
    import numpy as np

    from .records import hinge_kernel as hk
    from .records.segmentation import best_hinge

    t, x = np.linspace(0.0, 1.0, 16), np.zeros(16)
    best_hinge(t, x, 3, 0.0)
    hk.window_pairs(t, x, x, 0.5, 0.0, 0.0, 0.0)
    hk.stretch_residuals(t, x, np.array([0, 8, 16], np.int64), np.zeros(2))
    d, dt, lo, hi, _, _, _ = hk.reset_increments(t, x)
    hk.reset_jumps(d, dt, lo, hi, 0.0, 0.0)
    hk.row_medians(np.zeros((2, 4)))
    hk.fluctuation_scales(t, x, x, np.array([0.5]), np.array([0.005]), 0.0, 0.0, 3.0, 1e-3,
                          6, 2.0)
    return time.perf_counter() - start


def missing_kernel_caches(package_dir: str | os.PathLike[str] | None = None) -> list[str]:
    """The kernel modules (of :data:`KERNEL_MODULES`) with no compiled cache newer than their
    source: a command that runs one of them will compile first (about 15 s of CPU, once).

    Looks where Numba writes the cache: ``__pycache__`` beside the source, or under
    ``NUMBA_CACHE_DIR`` when that is set (where Numba's layout mirrors the source path, so
    any index file named after the module counts). Cheap: a few ``stat`` calls, no import of
    Numba. A module whose cache cannot be found (another cache location) is reported missing,
    which costs only a notice.
    """
    root = Path(package_dir) if package_dir is not None else Path(__file__).resolve().parent
    extra = os.environ.get("NUMBA_CACHE_DIR")
    missing = []
    for rel in KERNEL_MODULES:
        src = root / rel
        try:
            mtime = src.stat().st_mtime
        except OSError:
            continue
        places = [src.parent / "__pycache__"]
        if extra:
            places += [p.parent for p in Path(extra).rglob(f"{src.stem}.*.nbi")]
        fresh = any(p.stat().st_mtime >= mtime
                    for d in places if d.is_dir() for p in d.glob(f"{src.stem}.*.nbi"))
        if not fresh:
            missing.append(rel)
    return missing


def main() -> None:
    """``python -m dryfriction.warm``: compile (or check) the cached kernels, say how long."""
    print(f"dryfriction: compiled kernels ready ({warm():.1f} s)")


if __name__ == "__main__":
    main()
