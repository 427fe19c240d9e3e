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

The folder follows the rule of results folders (:mod:`dryfriction.io.files`): only files this
sweep wrote and that are unchanged are ever replaced. Every point's record carries the SHA-256 of
its content, checked before it is reused or taken into ``sweep.nc``; the marker ``sweep.json``
records the SHA-256 of ``sweep.nc`` and of the other outputs (``phase_diagram.png``). An edited
point or output is refused before any work, never overwritten.
"""

from __future__ import annotations

import copy
import fcntl
import hashlib
import json
import math
import os
import traceback
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from itertools import product
from pathlib import Path
from typing import Any

import numpy as np

from ..interrupts import deferred
from ..io.files import (
    atomic_write_bytes,
    check_writable_dir,
    is_ours,
    is_temporary,
    to_jsonable,
    write_json,
)
from ..validation import check_scalar, require_extra
from .cf import describe
from .cluster import CONNECT_TIMEOUT, close_client, probe_scheduler, start_client

__all__ = [
    "SweepAxis",
    "SweepSpec",
    "parse_sweep",
    "set_dotted",
    "get_dotted",
    "run_sweep",
    "MAX_POINTS",
    "MAX_AXIS",
    "load_sweep",
    "point_key",
    "sweep_fingerprint",
    "SweepInterrupted",
    "RESULT_VERSION",
]

MAX_POINTS = 2000
"""Largest grid run without ``confirm=True`` (``--yes`` on the command line)."""
SWEEP_MODULES = ("dask", "distributed", "xarray")  # the optional extra dryfriction[sweep]

MAX_AXIS = 1_000_000
"""Most values one ``{lin|log = [start, stop, n]}`` axis may have: the values are made before
the grid's size is checked against :data:`MAX_POINTS`, so ``n`` itself is bounded."""

Runner = Callable[[dict[str, Any]], Mapping[str, float]]

WORKER_PRELOAD = ("scipy.optimize",)
"""Imported once by the local cluster's fork server besides the runner's module: the package
imports SciPy's root finders only when a point first needs them (a command's start-up does not
pay for them), which costs each worker ~0.2 s of CPU on its first point otherwise."""


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
        # a TOML boolean is an int to Python: true is no count, and no bound either
        if isinstance(n, bool) or not (isinstance(n, int) and 1 <= n <= MAX_AXIS):
            raise ValueError(f"[sweep] {key!r}: n = {n!r} must be an integer in [1, "
                             f"{MAX_AXIS}]")
        for name, value in (("start", start), ("stop", stop)):
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                raise ValueError(f"[sweep] {key!r}: {kind} {name} = {value!r} is not allowed: "
                                 "a finite number")
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
        for other in table:  # "drive.segments" and "drive.segments.0.velocity": which wins?
            if other != key and str(key).startswith(f"{other}."):
                raise ValueError(f"{source}: [sweep] keys {other!r} and {key!r} overlap: the "
                                 "first replaces what the second sets; sweep one of them")
        try:
            axes.append(SweepAxis(key, _axis_values(key, spec)))
        except ValueError as exc:
            raise ValueError(f"{source}: {exc}") from None
    return SweepSpec(base, tuple(axes))


RESULT_VERSION = 3
"""Version of what a stored point means; part of every point's key and of the folder's
fingerprint, so that results of an older format are never read as current ones. Bump it when a
runner's output changes meaning (version 1: points keyed by their overrides only; version 2:
the linear growth rate from 24 Newton starts, NaN or not the rightmost root at some points)."""

SWEEP_FORMAT = "dryfriction-sweep"
"""``format`` of the marker file ``sweep.json`` that says a folder holds one of our sweeps."""

MARKER = "sweep.json"
LOCK = ".sweep.lock"

class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during :func:`run_sweep`; the finished points are stored, the cluster is closed.

    Attributes
    ----------
    stored : int
        Grid points with a stored result (they will not be computed again).
    total : int
        Points of the grid.
    out : pathlib.Path
        The results folder.
    """

    def __init__(self, stored: int, total: int, out: Path) -> None:
        super().__init__(f"{stored} of {total} points stored in {out}")
        self.stored, self.total, self.out = stored, total, out


def _canonical(obj: Any) -> str:
    # TOML can hold dates; everything else is JSON already
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), default=str)


def _digest(obj: Any) -> str:
    return hashlib.sha256(_canonical(obj).encode()).hexdigest()


def analysis_name(runner: Runner) -> str:
    """Default analysis kind of a runner: its importable name (``module.qualname``)."""
    return f"{getattr(runner, '__module__', '?')}.{getattr(runner, '__qualname__', repr(runner))}"


def point_key(protocol: Mapping[str, Any], analysis: str) -> str:
    """Key of a stored point: a hash of everything that determines its result.

    That is the point's full resolved protocol (every table, ``[stickslip]`` included), the
    analysis kind and :data:`RESULT_VERSION`; the grid it belongs to and its index do not
    matter.
    """
    return _digest({"format": SWEEP_FORMAT, "version": RESULT_VERSION, "analysis": analysis,
                    "protocol": protocol})[:32]


def sweep_fingerprint(spec: SweepSpec, analysis: str) -> str:
    """Hash of a whole sweep: base protocol, axes (keys and values, in order), analysis kind
    and :data:`RESULT_VERSION`. A results folder belongs to one fingerprint."""
    return _digest({"format": SWEEP_FORMAT, "version": RESULT_VERSION, "analysis": analysis,
                    "base": spec.base,
                    "axes": [[a.key, list(a.values)] for a in spec.axes]})


def _run_point(runner: Runner, protocol: dict[str, Any]) -> dict[str, Any]:
    """Run one point; exceptions become a recorded error (the sweep goes on)."""
    try:
        result = runner(protocol)
        return {"result": {k: float(v) for k, v in result.items()}}
    except Exception as exc:  # noqa: BLE001 - every failure is recorded, none stops the sweep
        return {"error": f"{type(exc).__name__}: {exc}", "traceback": traceback.format_exc()}


def _recorded(marker: Mapping[str, Any], name: str) -> list[str]:
    """The SHA-256 digests the marker accepts for the output ``name`` (two while it is being
    replaced, so that a run killed between the rename and the marker finds it still ours)."""
    outputs = marker.get("outputs")
    got = outputs.get(name) if isinstance(outputs, Mapping) else None
    return [d for d in got if isinstance(d, str)] if isinstance(got, list) else []


def _foreign_output(out: Path, marker: Mapping[str, Any], name: str) -> bool:
    """Whether ``out/name`` exists and is not an unchanged output of this sweep."""
    return os.path.lexists(out / name) and not any(
        is_ours(out, name, d) for d in _recorded(marker, name))


def _check_folder(out: Path, marker: Mapping[str, Any], outputs: tuple[str, ...] = ()) -> bool:
    """Whether ``out`` already belongs to this sweep; ``ValueError`` if it belongs to another
    one, holds anything else, or holds ``sweep.nc`` or one of ``outputs`` changed since this
    sweep wrote it. Reads only."""
    if not out.exists():
        return False
    path = out / MARKER
    if not path.exists():
        others = sorted(p.name for p in out.iterdir() if p.name != LOCK)
        if others:
            shown = ", ".join(others[:3]) + (", ..." if len(others) > 3 else "")
            raise ValueError(f"--out {out} holds files that are not a dryfriction sweep "
                             f"({shown}): use another --out (nothing in it was changed)")
        return False
    try:
        old = json.loads(path.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError):
        old = None
    if not isinstance(old, dict) or old.get("format") != SWEEP_FORMAT:
        raise ValueError(f"--out {out}: {path.name} is not a dryfriction sweep marker: use "
                         "another --out (nothing in it was changed)")
    if old.get("protocol_hash") == marker["protocol_hash"]:
        if not isinstance(old.get("outputs"), dict):
            raise ValueError(f"--out {out} holds a sweep written by an earlier dryfriction, "
                             "which recorded no hashes of its files: use another --out "
                             "(nothing in it was changed)")
        ours = {MARKER, LOCK, "points", "sweep.nc", *outputs, *old["outputs"]}
        others = sorted(p.name for p in out.iterdir()
                        if p.name not in ours and not is_temporary(p.name))
        if others:  # kept, but a resumed folder is this sweep's alone, like a new one
            shown = ", ".join(others[:3]) + (", ..." if len(others) > 3 else "")
            raise ValueError(f"--out {out} holds files that are not this sweep's ({shown}): "
                             "move them away to resume, or use another --out (nothing in it "
                             "was changed)")
        for name in ("sweep.nc", *outputs):
            if _foreign_output(out, old, name):
                raise ValueError(f"--out {out}: {name} is not the file this sweep wrote "
                                 "(edited since, or not ours: its SHA-256 is not the one in "
                                 f"{MARKER}): move it away or use another --out (nothing in "
                                 "it was changed)")
        return True
    if old.get("version") != marker["version"]:
        why = f"result format {old.get('version')} (this is {marker['version']})"
    elif old.get("analysis") != marker["analysis"]:
        why = f"analysis {old.get('analysis')} (this is {marker['analysis']})"
    else:
        why = f"protocol {old.get('source', '?')} (hash {str(old.get('protocol_hash'))[:12]})"
    raise ValueError(f"--out {out} holds a different sweep ({why}): use another --out or "
                     "remove that folder")


def _claim_folder(out: Path, marker: Mapping[str, Any], outputs: tuple[str, ...] = ()) -> int:
    """Lock ``out`` for this sweep and write its marker; return the lock's file descriptor.

    The lock is ``fcntl.flock`` on ``out/.sweep.lock``: the kernel releases it when the
    process ends, however it ends, so a killed sweep never leaves the folder locked.
    """
    _check_folder(out, marker, outputs)  # before creating anything in a folder not ours
    out.mkdir(exist_ok=True)
    fd = os.open(out / LOCK, os.O_RDWR | os.O_CREAT, 0o666)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise ValueError(f"--out {out}: another sweep is running into this folder (it "
                             f"holds {out / LOCK}): wait for it or use another --out") from None
        # again under the lock: another run may have claimed the folder since the first look
        if not _check_folder(out, marker, outputs):
            write_json(out / MARKER, marker)
    except BaseException:
        os.close(fd)
        raise
    return fd


def _seal(record: Mapping[str, Any]) -> dict[str, Any]:
    """The point's record as stored: with ``sha256``, the hash of the rest of it."""
    plain = to_jsonable(record)
    return {**plain, "sha256": _digest(plain)}


def _load_point(path: Path, key: str) -> dict[str, Any] | None:
    """The record stored at ``path`` for ``key``, checked against the hash recorded in it;
    ``None`` if there is none.

    Raises
    ------
    ValueError
        When a file is there but not as this sweep wrote it (edited since, another key, not a
        regular file): its numbers are never taken into ``sweep.nc`` and it is never
        overwritten.
    """
    if not os.path.lexists(path):
        return None
    rec: Any = None
    if not path.is_symlink():
        try:
            rec = json.loads(path.read_text())
        except (OSError, UnicodeDecodeError, json.JSONDecodeError):
            pass
    if not (isinstance(rec, dict) and rec.get("key") == key and rec.get("sha256") == _digest(
            {k: v for k, v in rec.items() if k != "sha256"})):
        raise ValueError(f"--out {path.parent.parent}: points/{path.name} is not the record "
                         "this sweep wrote (edited since: its content does not match the "
                         "SHA-256 recorded in it): move it away and run the command again "
                         "(that point is then computed again); nothing was changed")
    return rec


def _write_output(out: Path, name: str, data: bytes) -> None:
    """Write ``out/name`` (the folder's lock held) unless a file there is not the one this
    sweep wrote (``ValueError``, the file kept).

    The marker accepts the old and the new SHA-256 while the file is replaced, then only the
    new one: a run killed at any moment leaves a file the marker still calls ours."""
    marker = json.loads((out / MARKER).read_text())
    if _foreign_output(out, marker, name):
        raise ValueError(f"--out {out}: {name} changed during the run and is not the file this "
                         "sweep wrote: it was kept; the points are stored, so move it away and "
                         "run the command again")
    current = [d for d in _recorded(marker, name) if is_ours(out, name, d)]
    new = hashlib.sha256(data).hexdigest()
    outputs = marker.setdefault("outputs", {})
    outputs[name] = [*current, new]
    write_json(out / MARKER, marker)
    atomic_write_bytes(out / name, data)
    outputs[name] = [new]
    write_json(out / MARKER, marker)


def run_sweep(
    spec: SweepSpec,
    runner: Runner,
    out: str | os.PathLike[str],
    *,
    scheduler: str | None = None,
    n_workers: int | None = None,
    confirm: bool = False,
    progress: Callable[[int, int], None] | None = None,
    analysis: str | None = None,
    source: str | None = None,
    protocol_text: str | None = None,
    connect_timeout: float = CONNECT_TIMEOUT,
    variables: Mapping[str, Any] | None = None,
    outputs: Mapping[str, Callable[[Any], bytes]] | None = None,
) -> Any:
    """Run every grid point not already stored under ``out`` and return the Dataset.

    Parameters
    ----------
    spec : SweepSpec
        Base protocol and axes (:func:`parse_sweep`).
    runner : callable
        Picklable ``protocol dict -> {name: number}``, run on the workers.
    out : path
        Results folder: ``sweep.json`` (marker), ``points/`` (one JSON per point) and
        ``sweep.nc``. It belongs to one sweep: a different protocol or analysis is refused,
        the same one resumes; a folder holding anything else is refused, and so is a second
        run while one is running into it (``.sweep.lock``).
    scheduler : str, optional
        Address of an existing Dask scheduler; default: a local cluster.
    n_workers : int, optional
        Workers of the local cluster (default: one per core); not with ``scheduler``.
    confirm : bool
        Needed for grids larger than :data:`MAX_POINTS`.
    progress : callable, optional
        ``progress(done, total)`` after each finished point.
    analysis : str, optional
        Name of what the runner computes, part of every point's key (default:
        :func:`analysis_name` of the runner).
    source : str, optional
        Where the protocol comes from (a file name), kept in ``sweep.json``.
    protocol_text : str, optional
        The protocol as the user wrote it, kept in ``sweep.json`` (default: the parsed
        protocol as JSON).
    connect_timeout : float
        Seconds to wait for ``scheduler`` to answer, ``> 0``.
    variables : mapping, optional
        CF attributes of the runner's results (:func:`dryfriction.sweeps.cf.describe`).
    outputs : mapping, optional
        Further files of the folder, ``{name: dataset -> bytes}`` (``phase_diagram.png``),
        written after ``sweep.nc`` under the same rule: an existing one this sweep did not
        write, or that was edited since, refuses the run before any point.

    Raises
    ------
    ValueError
        Bad arguments, a folder that is not this sweep's, an edited output or stored point, a
        locked folder, an unreachable scheduler; all before any point runs.
    SweepInterrupted
        On Ctrl-C, after the cluster is closed; the finished points are stored.
    """
    require_extra("sweep", SWEEP_MODULES, "a sweep")
    if spec.size > MAX_POINTS and not confirm:
        raise ValueError(
            f"the grid has {spec.size} points, more than {MAX_POINTS}: confirm with --yes"
        )
    if n_workers is not None and n_workers < 1:
        raise ValueError(f"n_workers = {n_workers} is out of range: allowed >= 1")
    if n_workers is not None and scheduler is not None:
        raise ValueError("--workers is for the local cluster: a --scheduler has its own "
                         "workers (give one of the two)")
    connect_timeout = check_scalar("connect_timeout", connect_timeout, 0.0, lo_open=True)
    analysis = analysis or analysis_name(runner)
    out = check_writable_dir(out)
    keys = {idx: point_key(spec.protocol(ov), analysis) for idx, ov in spec.points()}
    marker = {"format": SWEEP_FORMAT, "version": RESULT_VERSION, "analysis": analysis,
              "protocol_hash": sweep_fingerprint(spec, analysis), "source": source or "",
              "protocol": protocol_text or _canonical(
                  {**spec.base, "sweep": {a.key: list(a.values) for a in spec.axes}}),
              "shape": list(spec.shape), "outputs": {}}
    names = tuple(outputs or {})
    _check_folder(out, marker, names)
    if scheduler is not None:  # an unreachable scheduler is bad input: nothing written yet
        probe_scheduler(scheduler, connect_timeout)
    lock = _claim_folder(out, marker, names)
    try:
        ds = _run_locked(spec, runner, out, keys, scheduler, n_workers, progress,
                         connect_timeout)
        describe(ds, variables, protocol=marker["protocol"], source=source or "",
                 analysis=analysis)
        _write_output(out, "sweep.nc", _netcdf_bytes(ds))
        for name, render in (outputs or {}).items():
            _write_output(out, name, render(ds))
        return ds
    finally:
        os.close(lock)  # releases the flock


def _run_locked(spec: SweepSpec, runner: Runner, out: Path, keys: Mapping[tuple[int, ...], str],
                scheduler: str | None, n_workers: int | None,
                progress: Callable[[int, int], None] | None, connect_timeout: float) -> Any:
    points_dir = out / "points"
    todo = []
    done = 0
    for idx, ov in spec.points():  # every stored point checked before any worker starts
        rec = _load_point(points_dir / f"{keys[idx]}.json", keys[idx])
        if rec is not None and "result" in rec:  # a failed one is computed again
            done += 1
        else:
            todo.append((idx, ov))
    if progress:
        progress(done, spec.size)
    if todo:
        try:
            client = start_client(scheduler, n_workers, connect_timeout,
                                  preload=[getattr(runner, "__module__", None) or "__main__",
                                           *WORKER_PRELOAD],
                                  meanwhile=_warm_results)
        except KeyboardInterrupt:
            raise SweepInterrupted(done, spec.size, out) from None
        points_dir.mkdir(exist_ok=True)
        futures: dict[Any, tuple[tuple[int, ...], dict[str, Any]]] = {}
        try:
            from dask.distributed import as_completed

            futures = {
                client.submit(_run_point, runner, spec.protocol(ov), pure=False): (idx, ov)
                for idx, ov in todo
            }
            for fut in as_completed(futures):
                idx, ov = futures[fut]
                try:
                    outcome = fut.result()
                except Exception as exc:  # noqa: BLE001 - a worker lost (killed, out of memory)
                    outcome = {"error": f"{type(exc).__name__}: {exc}"}
                record = {"key": keys[idx], "version": RESULT_VERSION, "index": list(idx),
                          "overrides": ov, "protocol": spec.protocol(ov), **outcome}
                with deferred():  # a Ctrl-C after the write counts the point it stored
                    write_json(points_dir / f"{keys[idx]}.json", _seal(record))
                    if "result" in outcome:
                        done += 1
                if progress:
                    progress(done, spec.size)
        except KeyboardInterrupt:
            close_client(client, scheduler, list(futures))
            raise SweepInterrupted(done, spec.size, out) from None
        close_client(client, scheduler, list(futures))
    return assemble(spec, points_dir, keys)


def _warm_results() -> None:
    """Import what :func:`assemble` and :func:`_write_netcdf` need: xarray, and what xarray
    imports when it builds its first Dataset (``dask.array``, to tell Dask arrays apart) and
    writes its first NetCDF file (SciPy's reader and writer), by doing both in memory.

    Called while the fork server imports (:func:`~dryfriction.sweeps.cluster.start_client`), when
    this process would otherwise wait for it; after the last point it cost ~0.25 s."""
    import xarray as xr

    _netcdf_bytes(xr.Dataset({"x": ("d", np.zeros(1))}, coords={"d": [0.0]}))


def assemble(spec: SweepSpec, points_dir: Path, keys: Mapping[tuple[int, ...], str]) -> Any:
    """Build the Dataset from the stored points (NaN and an error message where one failed).

    ``attrs``: ``n_failed`` (points with an error) and ``points_dir`` (where each failed
    point's record holds its error and traceback). Every record is checked against the hash
    recorded in it (``ValueError`` for an edited one, ``FileNotFoundError`` for a missing one).
    """
    import xarray as xr

    records = {}
    for idx, key in keys.items():
        rec = _load_point(points_dir / f"{key}.json", key)
        if rec is None:
            raise FileNotFoundError(f"{points_dir / key}.json: the point's record is missing")
        records[idx] = rec
    names = sorted({k for r in records.values() for k in r.get("result", {})})
    dims = [a.key for a in spec.axes]
    data = {n: np.full(spec.shape, np.nan) for n in names}
    errors = np.full(spec.shape, "", dtype=object)
    for idx, rec in records.items():
        for n in names:
            data[n][idx] = rec.get("result", {}).get(n, np.nan)
        errors[idx] = rec.get("error", "")
    coords = {a.key: list(a.values) for a in spec.axes}
    ds = xr.Dataset({n: (dims, v) for n, v in data.items()}, coords=coords)
    ds["error"] = (dims, errors.astype(str))
    ds.attrs["n_failed"] = int(np.sum(errors != ""))
    ds.attrs["points_dir"] = str(points_dir)
    return ds


def _write_netcdf(ds: Any, path: Path) -> None:
    """NetCDF through xarray's SciPy engine (no extra library), written whole or not at all."""
    atomic_write_bytes(path, _netcdf_bytes(ds))


def _netcdf_bytes(ds: Any) -> bytes:
    return bytes(ds.to_netcdf(engine="scipy"))


def load_sweep(path: str | os.PathLike[str]) -> Any:
    """Read a ``sweep.nc`` back as an :class:`xarray.Dataset` (loaded into memory).

    ``path`` may be the sweep's results folder (``--out``): its ``sweep.nc`` is read (a new
    user gave the folder and got ``IsADirectoryError``); a missing file is one
    ``FileNotFoundError`` line naming it."""
    import xarray as xr

    p = Path(path)
    if p.is_dir():
        p = p / "sweep.nc"
    if not p.is_file():
        raise FileNotFoundError(f"{p}: no such sweep file (a sweep's --out folder holds "
                                "sweep.nc once the sweep has finished)")
    with xr.open_dataset(p, engine="scipy") as ds:
        return ds.load()
