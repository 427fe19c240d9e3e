"""Parameter sweeps: Cartesian grids of protocol keys run as independent tasks on Dask.

A protocol file (TOML) gains a ``[sweep]`` table naming dotted keys of the protocol and their
values::

    [sweep]
    "drive.stiffness" = {log = [0.01, 1.0, 9]}
    "drive.segments.0.velocity" = [0.01, 0.1, 1.0]
    "model.eps" = {lin = [0.01, 0.05, 5]}

Each grid point is the protocol with those keys replaced; a *runner* (a picklable function
``protocol dict -> {name: number}``) turns it into summary figures. Points run as independent
tasks on ``dask.distributed``: a local cluster (one single-threaded worker process per core)
by default, or an existing scheduler when one machine is not enough.

Resumable: every finished point is written to ``OUT/points/<id>.json`` (atomically) as soon as
it finishes; re-running the same sweep reads those and computes only the rest. A point that
raises is recorded with its error and does not stop the sweep. The result is an
:class:`xarray.Dataset` with the swept keys as dimensions and the summary figures as variables,
written to ``OUT/sweep.nc`` (NetCDF, whole or not at all).
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
import os
import tempfile
import traceback
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from itertools import product
from pathlib import Path
from typing import Any

import numpy as np

from .files import check_output_dir, write_json

__all__ = [
    "SweepAxis",
    "SweepSpec",
    "parse_sweep",
    "set_dotted",
    "get_dotted",
    "run_sweep",
    "MAX_POINTS",
    "load_sweep",
]

MAX_POINTS = 2000
"""Largest grid run without ``confirm=True`` (``--yes`` on the command line)."""

Runner = Callable[[dict[str, Any]], Mapping[str, float]]


def _split(key: str) -> list[str | int]:
    return [int(p) if p.isdigit() else p for p in key.split(".")]


def get_dotted(tree: Mapping[str, Any], key: str) -> Any:
    """Value at a dotted key (``"drive.segments.0.velocity"``); ``KeyError`` if absent."""
    node: Any = tree
    for part in _split(key):
        if isinstance(part, int):
            if not isinstance(node, list) or part >= len(node):
                raise KeyError(key)
            node = node[part]
        else:
            if not isinstance(node, Mapping) or part not in node:
                raise KeyError(key)
            node = node[part]
    return node


def set_dotted(tree: Mapping[str, Any], key: str, value: Any) -> dict[str, Any]:
    """A deep copy of ``tree`` with the dotted key replaced (the key must exist)."""
    get_dotted(tree, key)
    out = copy.deepcopy(dict(tree))
    parts = _split(key)
    node: Any = out
    for part in parts[:-1]:
        node = node[part]
    node[parts[-1]] = value
    return out


@dataclass(frozen=True)
class SweepAxis:
    """One swept key and its values."""

    key: str
    values: tuple[Any, ...]


def _axis_values(key: str, spec: Any) -> tuple[Any, ...]:
    if isinstance(spec, list):
        if not spec:
            raise ValueError(f"[sweep] {key!r}: empty list of values")
        return tuple(spec)
    if isinstance(spec, Mapping) and len(spec) == 1 and next(iter(spec)) in ("log", "lin"):
        kind, args = next(iter(spec.items()))
        if not (isinstance(args, list) and len(args) == 3):
            raise ValueError(f"[sweep] {key!r}: {kind} needs [start, stop, n]")
        start, stop, n = args
        if not (isinstance(n, int) and n >= 1):
            raise ValueError(f"[sweep] {key!r}: n = {n!r} must be an integer >= 1")
        if kind == "log":
            if not (start > 0 and stop > 0):
                raise ValueError(f"[sweep] {key!r}: log range needs start, stop > 0")
            return tuple(float(v) for v in np.geomspace(start, stop, n))
        return tuple(float(v) for v in np.linspace(start, stop, n))
    raise ValueError(
        f"[sweep] {key!r}: values must be a list, {{log = [start, stop, n]}} or "
        "{lin = [start, stop, n]}"
    )


@dataclass(frozen=True)
class SweepSpec:
    """A base protocol (without its ``[sweep]`` table) and the swept axes."""

    base: Mapping[str, Any]
    axes: tuple[SweepAxis, ...]

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(a.values) for a in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    def points(self) -> Iterator[tuple[tuple[int, ...], dict[str, Any]]]:
        """``(index, overrides)`` for every grid point, in C order."""
        for idx in product(*(range(n) for n in self.shape)):
            yield idx, {a.key: a.values[i] for a, i in zip(self.axes, idx, strict=True)}

    def protocol(self, overrides: Mapping[str, Any]) -> dict[str, Any]:
        out = dict(self.base)
        for k, v in overrides.items():
            out = set_dotted(out, k, v)
        return out


def parse_sweep(protocol: Mapping[str, Any], source: str = "protocol") -> SweepSpec:
    """Split a protocol dict into its base and its ``[sweep]`` axes, checking every key."""
    if "sweep" not in protocol or not isinstance(protocol["sweep"], Mapping):
        raise ValueError(f"{source}: no [sweep] table")
    table = protocol["sweep"]
    if not table:
        raise ValueError(f"{source}: [sweep] names no keys")
    base = {k: v for k, v in protocol.items() if k != "sweep"}
    axes = []
    for key, spec in table.items():
        try:
            get_dotted(base, key)
        except KeyError:
            raise ValueError(
                f"{source}: [sweep] key {key!r} is not in the protocol (dotted keys name "
                "existing entries, e.g. 'drive.stiffness' or 'drive.segments.0.velocity')"
            ) from None
        axes.append(SweepAxis(key, _axis_values(key, spec)))
    return SweepSpec(base, tuple(axes))


def point_id(overrides: Mapping[str, Any]) -> str:
    """Stable identifier of a grid point (hash of its overrides)."""
    text = json.dumps(overrides, sort_keys=True, default=float)
    return hashlib.sha1(text.encode()).hexdigest()[:16]


def _run_point(runner: Runner, protocol: dict[str, Any]) -> dict[str, Any]:
    """Run one point; exceptions become a recorded error (the sweep goes on)."""
    try:
        result = runner(protocol)
        return {"result": {k: float(v) for k, v in result.items()}}
    except Exception as exc:  # noqa: BLE001 - every failure is recorded, none stops the sweep
        return {"error": f"{type(exc).__name__}: {exc}", "traceback": traceback.format_exc()}


def _client(scheduler: str | None, n_workers: int | None) -> Any:
    from dask.distributed import Client, LocalCluster

    if scheduler is not None:
        try:
            return Client(scheduler, timeout="10s")
        except OSError as exc:
            raise ValueError(f"--scheduler {scheduler}: cannot reach it ({exc})") from None
    n = n_workers or os.cpu_count() or 1
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    return Client(cluster)


def run_sweep(
    spec: SweepSpec,
    runner: Runner,
    out: str | os.PathLike[str],
    *,
    scheduler: str | None = None,
    n_workers: int | None = None,
    confirm: bool = False,
    progress: Callable[[int, int], None] | None = None,
) -> Any:
    """Run every grid point not already stored under ``out`` and return the Dataset.

    Parameters
    ----------
    spec : SweepSpec
        Base protocol and axes (:func:`parse_sweep`).
    runner : callable
        Picklable ``protocol dict -> {name: number}``, run on the workers.
    out : path
        Results folder: ``points/`` (one JSON per finished point) and ``sweep.nc``.
    scheduler : str, optional
        Address of an existing Dask scheduler; default: a local cluster.
    n_workers : int, optional
        Workers of the local cluster (default: one per core).
    confirm : bool
        Needed for grids larger than :data:`MAX_POINTS`.
    progress : callable, optional
        ``progress(done, total)`` after each finished point.
    """
    if spec.size > MAX_POINTS and not confirm:
        raise ValueError(
            f"the grid has {spec.size} points, more than {MAX_POINTS}: confirm with --yes"
        )
    if n_workers is not None and n_workers < 1:
        raise ValueError(f"n_workers = {n_workers} is out of range: allowed >= 1")
    out = check_output_dir(out)
    points_dir = out / "points"
    todo = []
    done = 0
    for idx, ov in spec.points():
        if (points_dir / f"{point_id(ov)}.json").exists():
            done += 1
        else:
            todo.append((idx, ov))
    if progress:
        progress(done, spec.size)
    if todo:
        client = _client(scheduler, n_workers)
        points_dir.mkdir(parents=True, exist_ok=True)
        try:
            from dask.distributed import as_completed

            futures = {
                client.submit(_run_point, runner, spec.protocol(ov), pure=False): (idx, ov)
                for idx, ov in todo
            }
            for fut in as_completed(futures):
                idx, ov = futures[fut]
                record = {"index": list(idx), "overrides": ov, **fut.result()}
                write_json(points_dir / f"{point_id(ov)}.json", record)
                done += 1
                if progress:
                    progress(done, spec.size)
        finally:
            cluster = getattr(client, "cluster", None)
            client.close()
            if scheduler is None and cluster is not None:
                cluster.close()
    ds = assemble(spec, points_dir)
    _write_netcdf(ds, out / "sweep.nc")
    return ds


def assemble(spec: SweepSpec, points_dir: Path) -> Any:
    """Build the Dataset from the stored points (NaN and an error message where one failed)."""
    import xarray as xr

    records = {}
    for _, ov in spec.points():
        path = points_dir / f"{point_id(ov)}.json"
        records[point_id(ov)] = json.loads(path.read_text())
    names = sorted({k for r in records.values() for k in r.get("result", {})})
    dims = [a.key for a in spec.axes]
    data = {n: np.full(spec.shape, np.nan) for n in names}
    errors = np.full(spec.shape, "", dtype=object)
    for idx, ov in spec.points():
        rec = records[point_id(ov)]
        for n in names:
            data[n][idx] = rec.get("result", {}).get(n, np.nan)
        errors[idx] = rec.get("error", "")
    coords = {a.key: list(a.values) for a in spec.axes}
    ds = xr.Dataset({n: (dims, v) for n, v in data.items()}, coords=coords)
    ds["error"] = (dims, errors.astype(str))
    ds.attrs["n_failed"] = int(np.sum(errors != ""))
    return ds


def _write_netcdf(ds: Any, path: Path) -> None:
    """NetCDF through xarray's SciPy engine (no extra library), via a temporary file."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    try:
        ds.to_netcdf(tmp, engine="scipy")
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def load_sweep(path: str | os.PathLike[str]) -> Any:
    """Read a ``sweep.nc`` back as an :class:`xarray.Dataset` (loaded into memory)."""
    import xarray as xr

    with xr.open_dataset(path, engine="scipy") as ds:
        return ds.load()
