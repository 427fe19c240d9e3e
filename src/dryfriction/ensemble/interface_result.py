"""What an extended-interface run returns: :class:`InterfaceResult`, space-time fields
of a chain of trap-model blocks (:mod:`dryfriction.ensemble.interface`).

The contract the analysis of the fields (fronts, events, precursors) is written against:

* ``t`` (n_t,) sample times, ``t0``;
* ``x`` (N,) element positions along the interface, in element spacings (``element``);
* ``slip`` (n_t, N) slip of every element from its start, ``a0``;
* ``slip_rate`` (n_t, N) its velocity, ``a0/t0``;
* ``stress`` (n_t, N) shear stress of every element: its friction force, in the single slider's
  reduced unit ``F_el`` *per element* (an element's population at steady sliding carries
  ``mu_d(u) ~ 1``);
* ``load`` (n_t,) the applied shear: the total force of the loading springs on the chain,
  ``F_el`` (one element's ``F_el``; divide by ``N`` for the mean stress);
* ``load_point`` (n_t,) where the driver is: the top plate (uniform loading) or the edge
  spring's end (side loading), ``a0``;
* ``params`` the model and the drive as data (plain dicts), ``units`` a dict name -> unit.

Reduced units throughout (docs/model.md §6): lengths along the slip ``a0``, times ``t0``, forces
``F_el`` per element.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..validation import Array

__all__ = ["INTERFACE_UNITS", "InterfaceResult"]

INTERFACE_UNITS: dict[str, str] = {
    "t": "t0",
    "x": "element",
    "slip": "a0",
    "slip_rate": "a0/t0",
    "stress": "F_el per element",
    "load": "F_el",
    "load_point": "a0",
    "work_load": "F_el a0",
    "elastic_energy": "F_el a0",
    "kinetic_energy": "F_el a0",
    "work_friction": "F_el a0",
    "work_damping": "F_el a0",
    "work_quasi_static": "F_el a0",
}
"""Unit of every field of :class:`InterfaceResult` (``element``: the spacing of the blocks).
``load`` and the energies are the whole chain's, in one element's ``F_el`` (and ``a0``): the
same units as load.csv and summary.json of ``simulate`` (:mod:`dryfriction.io.units`), which
had read "F_el a0 per element" in one and "F_el a0" in the other."""


@dataclass(frozen=True)
class InterfaceResult:
    """Space-time fields of an extended-interface run (module docstring for the contract).

    Attributes
    ----------
    t : ndarray, shape (n_t,)
        Sample times, ``t0``; ``t[0] = 0`` is the initial state.
    x : ndarray, shape (N,)
        Element positions along the interface, ``i + 1/2`` in element spacings.
    slip, slip_rate, stress : ndarray, shape (n_t, N)
        Slip from the start (``a0``), slip rate (``a0/t0``) and friction force (``F_el`` per
        element) of every element at every sample.
    load : ndarray, shape (n_t,)
        Total force of the loading springs on the chain, ``F_el``.
    load_point : ndarray, shape (n_t,)
        Top-plate (uniform loading) or edge-spring end (side loading) displacement, ``a0``.
    params : dict
        The model and the drive as data (``{"interface": ..., "model": ..., "drive": ...}``).
    units : dict
        Field name -> unit (:data:`INTERFACE_UNITS`).
    energy : dict of ndarray
        Cumulative energy terms at every sample, ``F_el a0``: ``work_load`` (work of the loading
        springs on the chain), ``elastic_energy`` (loading and coupling springs),
        ``kinetic_energy``, ``work_friction`` (work done against the contacts),
        ``work_damping``, ``work_quasi_static`` (what the quasi-static phases of an
        event-driven run remove: the kinetic energy and the unbalanced force's work when a
        phase starts; 0 in a dynamic run). The balance ``work_load = delta(elastic + kinetic)
        + work_friction + work_damping + work_quasi_static`` holds to the integrator's order
        (:meth:`energy_residual`).
    info : dict
        Run scalars: step count, trap updates, wall time, ``partial``.
    """

    t: Array
    x: Array
    slip: Array
    slip_rate: Array
    stress: Array
    load: Array
    load_point: Array
    params: dict[str, Any]
    units: dict[str, str] = field(default_factory=lambda: dict(INTERFACE_UNITS))
    energy: dict[str, Array] = field(default_factory=dict)
    info: dict[str, Any] = field(default_factory=dict)

    @property
    def n_elements(self) -> int:
        """Number of elements ``N``."""
        return int(self.x.shape[0])

    @property
    def partial(self) -> bool:
        """The run was interrupted: the samples stop early."""
        return bool(self.info.get("partial", False))

    def energy_residual(self) -> Array:
        """``work_load - delta(elastic + kinetic) - work_friction - work_damping -
        work_quasi_static`` at every
        sample, from the start (``F_el a0``; 0 for an exact integrator)."""
        e = self.energy
        stored = e["elastic_energy"] + e["kinetic_energy"]
        dropped = e.get("work_quasi_static", 0.0)
        return (e["work_load"] - (stored - stored[0]) - e["work_friction"]
                - e["work_damping"] - dropped)

    def summary(self) -> dict[str, Any]:
        """Plain-data summary: sizes, extremes of the fields, the energy balance, units."""
        res = self.energy_residual() if self.energy else np.zeros(1)
        scale = float(np.max(np.abs(self.energy["work_load"]))) if self.energy else 0.0
        return {
            "kind": "interface",
            "n_elements": self.n_elements,
            "n_samples": int(self.t.shape[0]),
            "t_end": float(self.t[-1]),
            "max_slip": float(np.max(self.slip)) if self.slip.size else 0.0,
            "max_slip_rate": float(np.max(self.slip_rate)) if self.slip_rate.size else 0.0,
            "final_load": float(self.load[-1]),
            "energy_residual_max": float(np.max(np.abs(res))),
            "energy_work_load_max": scale,
            "partial": self.partial,
            "units": dict(self.units),
            "params": self.params,
            "info": {k: v for k, v in self.info.items() if k != "partial"},
        }
