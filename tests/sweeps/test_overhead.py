"""The local cluster's serial overhead and parasitic CPU (issue 12): what was cut stays cut.

Each test checks the mechanism that removed a measured cost (docs/performance.md):
Dask's diagnostic callbacks off or slowed in every process of the cluster, the fork server
ended without its interpreter shutdown, and the sweep's result imports done while the fork
server imports, so that ``assemble`` imports nothing.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("distributed")
psutil = pytest.importorskip("psutil")


def _callbacks(dask_worker: object = None, dask_scheduler: object = None) -> dict[str, float]:
    """Periodic callbacks of a Dask server (worker, scheduler or nanny) and their periods."""
    server = dask_worker or dask_scheduler
    return {name: pc.callback_time for name, pc in server.periodic_callbacks.items()}


def test_every_process_of_a_local_cluster_runs_lean() -> None:
    """No profiler, a tick every second and a system monitor every 5 s in the workers (which
    get Dask's settings from their Nanny, in another process), the scheduler and the nannies;
    no glibc trim threshold in a worker's environment; and the sweep's own process keeps
    Dask's defaults and its environment once the cluster is up. A misspelt key
    (``dask.config.set`` accepts any), settings applied after the cluster starts, or settings
    that do not reach the worker processes fail here."""
    import dask

    from dryfriction.sweeps.cluster import close_client, start_client

    trim = "MALLOC_TRIM_THRESHOLD_"
    if trim in os.environ:
        pytest.skip(f"{trim} is set in the environment of the tests")
    default_tick = dask.config.get("distributed.admin.tick.interval")
    client = start_client(None, 1)
    try:
        envs = list(client.run(lambda: dict(os.environ)).values())
        workers = list(client.run(_callbacks).values())
        scheduler = client.run_on_scheduler(_callbacks)
        nannies = [_callbacks(n) for n in client.cluster.workers.values()]
        pids = client.run(os.getpid)
    finally:
        close_client(client, None, [])
    assert all(pid != os.getpid() for pid in pids.values())  # the worker is another process
    assert len(workers) == 1 and len(nannies) == 1
    for where, cbs in [("worker", workers[0]), ("scheduler", scheduler), ("nanny", nannies[0])]:
        assert "profile" not in cbs and "profile-cycle" not in cbs, (where, sorted(cbs))
        assert cbs["tick"] == 1000.0, (where, cbs["tick"])
        assert cbs["monitor"] == 5000.0, (where, cbs["monitor"])
    assert trim not in envs[0] and envs[0]["OPENBLAS_NUM_THREADS"] == "1"
    assert trim not in os.environ  # the Nanny writes its variables here too
    assert dask.config.get("distributed.worker.profile.enabled") is True
    assert dask.config.get("distributed.admin.tick.interval") == default_tick


def _start_marked_server(tmp_path: Path, marker: Path, monkeypatch: pytest.MonkeyPatch) -> int:
    """Start a fork server through :func:`start_fork_server` that preloads a module whose
    ``atexit`` handler touches ``marker``; check it was preloaded; return the server's pid."""
    from multiprocessing import forkserver, get_context

    from dryfriction.sweeps.cluster import start_fork_server

    monkeypatch.setenv("ATEXIT_MARKER", str(marker))  # the server inherits it
    monkeypatch.delitem(sys.modules, "atexit_marker", raising=False)
    (tmp_path / "atexit_marker.py").write_text(
        "import atexit, os, pathlib, sys\n"
        "atexit.register(pathlib.Path(os.environ['ATEXIT_MARKER']).touch)\n"
        "PID = os.getpid()\n"
        "def forked():\n"
        "    sys.exit(0 if PID != os.getpid() else 3)  # imported by the server, not here\n")
    assert start_fork_server(["atexit_marker"])
    import atexit_marker

    child = get_context("forkserver").Process(target=atexit_marker.forked)
    child.start()
    child.join(30)
    assert child.exitcode == 0  # the server did import the module (a failed one is skipped)
    pid = forkserver._forkserver._forkserver_pid
    assert pid is not None
    return pid


def _gone(pid: int) -> bool:
    return not psutil.pid_exists(pid) or psutil.Process(pid).status() == psutil.STATUS_ZOMBIE


def test_the_fork_server_is_ended_without_its_interpreter_shutdown(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Stopping the fork server must not wait for it to shut its interpreter down (0.2 s with
    Dask and SciPy loaded): the ``atexit`` handler of a module it preloaded, which a clean
    shutdown runs (checked first, with multiprocessing's own stop), must not run; and the
    server is gone when the stop returns."""
    from multiprocessing import forkserver

    from dryfriction.sweeps.cluster import fork_server_running, stop_fork_server

    if fork_server_running():
        pytest.skip("another fork server runs in this process")
    # the server imports from its environment's path (CPython 3.11 ignores the sys.path it
    # is sent), and this process from its own
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(
        [str(tmp_path), *filter(None, [os.environ.get("PYTHONPATH")])]))
    monkeypatch.syspath_prepend(str(tmp_path))
    clean = tmp_path / "clean"
    pid = _start_marked_server(tmp_path, clean, monkeypatch)
    forkserver._forkserver._stop()  # the control: a clean stop runs the handler
    stop_fork_server()  # forgets it was ours (nothing left to stop)
    assert _gone(pid) and clean.exists()

    marker = tmp_path / "ours"
    pid = _start_marked_server(tmp_path, marker, monkeypatch)
    stop_fork_server()
    assert _gone(pid)
    assert not fork_server_running()
    assert not marker.exists()


def test_meanwhile_runs_while_the_fork_server_starts_and_an_interrupt_stops_it() -> None:
    """``meanwhile`` is called after the fork server started and before any worker exists;
    Ctrl-C inside it stops the server (nothing is left behind) and reaches the caller."""
    from dryfriction.sweeps.cluster import fork_server_running, start_client

    me = psutil.Process()
    seen: list[tuple[bool, int]] = []

    def meanwhile() -> None:
        workers = [p for p in me.children(recursive=True)
                   if "resource_tracker" not in " ".join(p.cmdline())]
        seen.append((fork_server_running(), len(workers)))
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        start_client(None, 1, meanwhile=meanwhile)
    assert seen == [(True, 1)]  # the server only, no worker yet
    assert not fork_server_running()


def test_assemble_imports_nothing_after_the_warm_up(tmp_path: Path) -> None:
    """After ``_warm_results`` (run while the fork server imports), building and writing the
    sweep's Dataset imports no module: importing xarray alone is not enough (its first
    Dataset imports ``dask.array``, ~0.15 s, its first NetCDF file ``scipy.io``), and what is
    not warmed is paid after the last point. In a fresh process, since this one may have
    imported anything already."""
    code = """
import sys
from dryfriction.sweeps import sweep as sw
spec = sw.parse_sweep({"model": {"eps": 0.04}, "sweep": {"model.eps": [0.02, 0.03]}})
keys = {idx: sw.point_key(spec.protocol(ov), "a") for idx, ov in spec.points()}
out = sys.argv[1]
for idx, ov in spec.points():
    sw.write_json(f"{out}/{keys[idx]}.json", sw._seal({"key": keys[idx], "result": {"x": 1.0}}))
import distributed  # the sweep's process has it (start_client), and xarray's writer uses it
sw._warm_results()
before = set(sys.modules)
ds = sw.assemble(spec, sw.Path(out), keys)
sw.describe(ds, None, protocol="", source="", analysis="a")
sw._write_netcdf(ds, sw.Path(out) / "sweep.nc")
print(sorted(m for m in set(sys.modules) - before if not m.startswith("encodings")))
"""
    import dryfriction

    src = str(Path(dryfriction.__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [src, *filter(None, [os.environ.get("PYTHONPATH")])])}
    r = subprocess.run([sys.executable, "-c", code, str(tmp_path)], capture_output=True,
                       text=True, env=env, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "[]", r.stdout
