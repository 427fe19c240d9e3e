"""Space-time fields of an extended interface on disk: NetCDF through xarray
when it is installed (the optional extra ``dryfriction[sweep]``), else a compressed NumPy
``.npz`` with the same arrays, the units as a JSON string.

The NetCDF file holds one variable per field on the dimensions ``(t, x)`` (a 1-D field on
``t`` alone), each with its ``units`` attribute, coordinates ``t`` and ``x`` with theirs, and the
given global attributes. It is written with xarray's SciPy engine (NetCDF 3, no extra library)
in float32 when ``compact`` (half the size; 7 significant digits, enough for maps and fronts,
not for differences of large slips), whole or not at all.
"""

from __future__ import annotations

import io
import json
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..validation import check_memory
from .files import atomic_write_bytes

__all__ = ["FieldsFile", "write_fields", "read_fields", "has_xarray"]


@dataclass(frozen=True)
class FieldsFile:
    """What :func:`write_fields` wrote: the path, its format (``"netcdf"`` or ``"npz"``) and, for
    the fallback, the one line that says why (empty otherwise)."""

    path: Path
    format: str
    note: str


def has_xarray() -> bool:
    """Whether xarray can be imported (looked up without importing it)."""
    import importlib.util

    try:
        return importlib.util.find_spec("xarray") is not None
    except (ImportError, ValueError):
        return False


def _checked(t: ArrayLike, x: ArrayLike, fields: Mapping[str, ArrayLike]
             ) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    t_, x_ = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
    if t_.ndim != 1 or t_.size == 0:
        raise ValueError(f"t must be a non-empty 1-D array, got shape {t_.shape}")
    if x_.ndim != 1 or x_.size == 0:
        raise ValueError(f"x must be a non-empty 1-D array, got shape {x_.shape}")
    if not fields:
        raise ValueError("fields is empty: give at least one field")
    out = {}
    for name, value in fields.items():
        a = np.asarray(value, dtype=float)
        if a.shape not in ((t_.size, x_.size), (t_.size,)):
            raise ValueError(f"field {name} has shape {a.shape}, but (len(t), len(x)) = "
                             f"{(t_.size, x_.size)} (or (len(t),) for a load)")
        out[str(name)] = a
    return t_, x_, out


def write_fields(path: str | os.PathLike[str], t: ArrayLike, x: ArrayLike,
                 fields: Mapping[str, ArrayLike], units: Mapping[str, str], *,
                 attrs: Mapping[str, Any] | None = None, compact: bool = True,
                 netcdf: bool | None = None) -> FieldsFile:
    """Write the space-time fields, as NetCDF when xarray is installed, else as ``.npz``.

    Parameters
    ----------
    path : path
        File to write (``.nc``); the fallback replaces the suffix by ``.npz``.
    t, x : array_like
        Sample times [``units['t']``] and element positions [``units['x']``].
    fields : mapping
        Field name -> array of shape (len(t), len(x)), or (len(t),) (the load).
    units : mapping
        Unit of ``t``, ``x`` and of every field, by name (``"a0/t0"``, ``"m/s"``).
    attrs : mapping, optional
        Global attributes (numbers or strings).
    compact : bool
        Store the fields in float32 (the coordinates stay float64).
    netcdf : bool, optional
        Force (True) or refuse (False) NetCDF; default: NetCDF when xarray is installed.

    Returns
    -------
    FieldsFile
    """
    t_, x_, data = _checked(t, x, fields)
    missing = [n for n in ("t", "x", *data) if n not in units]
    if missing:
        raise ValueError(f"units names no unit for {', '.join(missing)}")
    dtype = np.float32 if compact else np.float64
    need = 2.0 * sum(a.size for a in data.values()) * np.dtype(dtype).itemsize
    check_memory("writing the space-time fields", need, "record fewer samples")
    use_netcdf = has_xarray() if netcdf is None else netcdf
    path = Path(path)
    if use_netcdf:
        import xarray as xr

        ds = xr.Dataset(
            {n: (("t", "x") if a.ndim == 2 else ("t",), a.astype(dtype),
                 {"units": str(units[n])}) for n, a in data.items()},
            coords={"t": ("t", t_, {"units": str(units["t"])}),
                    "x": ("x", x_, {"units": str(units["x"])})},
            attrs={str(k): v for k, v in (attrs or {}).items()})
        atomic_write_bytes(path, bytes(ds.to_netcdf(engine="scipy")))
        return FieldsFile(path, "netcdf", "")
    target = path.with_suffix(".npz")
    buf = io.BytesIO()
    np.savez_compressed(buf, t=t_, x=x_, **{n: a.astype(dtype) for n, a in data.items()},
                        units=np.array(json.dumps({k: str(v) for k, v in units.items()})),
                        attrs=np.array(json.dumps(dict(attrs or {}), default=str)))
    atomic_write_bytes(target, buf.getvalue())
    return FieldsFile(target, "npz", f"xarray is not installed: wrote the fields as {target.name}"
                                     " (NumPy .npz) instead of NetCDF; pip install "
                                     "'dryfriction[sweep]' for NetCDF")


def read_fields(path: str | os.PathLike[str]) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    """Read a file of :func:`write_fields` back: arrays by name (``t``, ``x``, the fields) and
    units by name."""
    path = Path(path)
    if path.suffix == ".npz":
        with np.load(path, allow_pickle=False) as f:
            arrays = {k: f[k] for k in f.files if k not in ("units", "attrs")}
            units = json.loads(str(f["units"]))
        return arrays, units
    import xarray as xr

    with xr.open_dataset(path, engine="scipy") as ds:
        ds = ds.load()
    arrays = {str(k): np.asarray(ds[k].values) for k in (*ds.coords, *ds.data_vars)}
    units = {str(k): str(ds[k].attrs.get("units", "")) for k in (*ds.coords, *ds.data_vars)}
    return arrays, units
