"""CF metadata of a sweep's ``sweep.nc``: what every variable is and its unit, the class names,
and the protocol the sweep ran (CF conventions 1.8: ``long_name``, ``units``, ``flag_values``,
``flag_meanings``; global ``Conventions``, ``title``, ``source``, ``history``).

Sweeps run the trap model, whose numbers are in the paper's reduced units: lengths in ``a0``,
times in ``t0``, forces in ``F_el``. Those are written as the ``units`` strings (``"a0/t0"``,
``"F_el/a0"``): they are not UDUNITS units, and the global attribute ``units_note`` says so;
friction coefficients (``mu_el F/F_el``) and other pure numbers are ``"1"``.
"""

from __future__ import annotations

import datetime
from collections.abc import Mapping
from typing import Any

import numpy as np

__all__ = ["KEY_UNITS", "VariableInfo", "describe"]

VariableInfo = Mapping[str, Any]
"""Attributes of one variable: ``long_name``, ``units`` and, for a class, ``flag_values`` and
``flag_meanings``."""

KEY_UNITS: dict[str, str] = {
    "alpha": "1", "eps": "1", "mu_el": "1", "traps_per_a0": "1/a0", "seed": "1",
    "initial_velocity": "a0/t0", "initial_force": "F_el", "stiffness": "F_el/a0",
    "mass": "F_el t0^2/a0", "damping": "F_el t0/a0", "velocity": "a0/t0", "slip": "a0",
    "duration": "t0", "rate": "F_el/t0", "hold": "t0", "max_force": "F_el", "every": "t0",
    "every_slip": "a0", "transient": "a0", "floor": "1", "rel_threshold": "1",
    "coupling": "F_el/a0", "edge_stiffness": "F_el/a0", "n_elements": "1",
    "normal_spread": "1", "density_spread": "1", "quasi_static_rate": "a0/t0",
    "threshold": "a0/t0", "min_elements": "1", "after": "t0", "edge_gap": "1",
    "stick_fraction": "1", "cv_periodic": "1",
}
"""Unit of a protocol value by its key's last part (``drive.segments.0.velocity``: a0/t0)."""

UNITS_NOTE = ("reduced units of the trap model: a0 the contact radius, t0 the creep time, F_el "
              "the elastic friction force (not UDUNITS units); '1' a pure number or a friction "
              "coefficient mu_el F/F_el")


def _leaf(key: str) -> str:
    return key.rsplit(".", 1)[-1]


def describe(ds: Any, variables: Mapping[str, VariableInfo] | None = None, *,
             protocol: str = "", source: str = "", analysis: str = "") -> Any:
    """Give ``ds`` (a sweep's :class:`xarray.Dataset`) its CF attributes, in place.

    Parameters
    ----------
    ds : xarray.Dataset
        Coordinates named by dotted protocol keys, data variables named by the runner.
    variables : mapping, optional
        Variable name -> attributes (:data:`VariableInfo`), from the runner's module
        (``analysis.stickslip.SWEEP_VARIABLES``, ``analysis.linear.SWEEP_VARIABLES``). A
        variable not listed gets its name as ``long_name`` and no unit.
    protocol : str
        The protocol's text (the global attribute ``protocol``).
    source, analysis : str
        The protocol file and the analysis run on each point.

    Returns
    -------
    xarray.Dataset
        ``ds``.
    """
    from .. import __version__

    variables = variables or {}
    for key in ds.coords:
        ds[key].attrs.update(long_name=f"protocol value {key}")
        if _leaf(str(key)) in KEY_UNITS:
            ds[key].attrs["units"] = KEY_UNITS[_leaf(str(key))]
    for name in ds.data_vars:
        info = dict(variables.get(str(name), {"long_name": str(name)}))
        if "flag_values" in info:  # the type of the variable itself (NaN marks a failed point)
            info["flag_values"] = np.asarray(info["flag_values"], dtype=ds[name].dtype)
        ds[name].attrs.update(info)
    ds["error"].attrs.update(long_name="error of a failed point (empty where it succeeded)")
    now = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%dT%H:%M:%SZ")
    ds.attrs.update(
        Conventions="CF-1.8",
        title=f"dryfriction parameter sweep ({analysis or 'unknown analysis'})",
        source=f"dryfriction {__version__}; protocol {source or '(unnamed)'}",
        history=f"{now} dryfriction sweep", analysis=analysis, protocol=protocol,
        units_note=UNITS_NOTE,
    )
    return ds
