"""Sweeps as processes (issue 12): the local cluster leaves nothing behind when the command
returns, and a sweep runs through a Dask scheduler and worker started outside the command."""

from __future__ import annotations

import os
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

from sweep_protocols import spring_sweep

psutil = pytest.importorskip("psutil")

PROTO = spring_sweep('"drive.stiffness" = [0.04, 0.05, 0.06, 0.07]\n')


def _env(**extra: str) -> dict[str, str]:
    """The environment of a child: it imports the package under test, whatever the cwd."""
    import dryfriction

    src = str(Path(dryfriction.__file__).resolve().parents[1])
    path = os.pathsep.join([src, *filter(None, [os.environ.get("PYTHONPATH")])])
    return {**os.environ, "PYTHONPATH": path, **extra}


def _marked(mark: str) -> list[psutil.Process]:
    """Live processes whose environment carries ``mark`` (every descendant of a process
    inherits it, even one that was re-parented after its parent exited)."""
    found = []
    for p in psutil.process_iter():
        try:
            if p.status() != psutil.STATUS_ZOMBIE and p.environ().get("DRYFRICTION_TEST") == mark:
                found.append(p)
        except (psutil.NoSuchProcess, psutil.AccessDenied):
            continue
    return found


@pytest.mark.slow
@pytest.mark.ci
def test_sweep_with_two_workers_leaves_no_process_behind(tmp_path: Path) -> None:
    proto = tmp_path / "p.toml"
    proto.write_text(PROTO)
    mark = uuid.uuid4().hex
    proc = subprocess.Popen(
        [sys.executable, "-m", "dryfriction.cli", "sweep", str(proto), "--out",
         str(tmp_path / "o"), "--workers", "2"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path,
        env=_env(DRYFRICTION_TEST=mark))
    seen: set[int] = set()
    try:
        while proc.poll() is None:  # the workers did exist (the check below can fail)
            seen |= {p.pid for p in _marked(mark) if p.pid != proc.pid}
            time.sleep(0.2)
        so, se = proc.communicate(timeout=10)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, se
    assert "4 points, 0 failed" in so
    assert len(seen) >= 2, "no worker process was ever seen"
    left = _marked(mark)
    for p in left:  # clean up before failing, so that one failure does not leak into others
        p.kill()
    assert not left, [" ".join(p.cmdline()) for p in left]


def _scheduler_address(path: Path, proc: subprocess.Popen[bytes],
                       timeout: float = 60.0) -> str:
    """The address a scheduler started with ``--port 0 --scheduler-file path`` wrote: the
    system picks a free port as it binds (a port chosen here and bound later could be taken
    meanwhile by another test of a parallel run)."""
    import json

    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        assert proc.poll() is None, "the scheduler exited"
        try:
            return str(json.loads(path.read_text())["address"])
        except (OSError, ValueError, KeyError):
            time.sleep(0.1)
    raise AssertionError(f"no scheduler address in {path} after {timeout} s")


@pytest.mark.slow
def test_sweep_through_an_external_scheduler_and_worker(tmp_path: Path) -> None:
    """How a user with a cluster runs it: ``dask scheduler`` and ``dask worker`` started by
    hand, the sweep sent with ``--scheduler``; the command leaves them running."""
    from dask.distributed import Client

    proto = tmp_path / "p.toml"
    proto.write_text(PROTO)
    env = _env()
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL, "env": env,
             "cwd": tmp_path}
    scheduler = subprocess.Popen(
        [sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
         "--port", "0", "--scheduler-file", str(tmp_path / "scheduler.json"),
         "--no-dashboard"], **quiet)
    worker = None
    try:
        address = _scheduler_address(tmp_path / "scheduler.json", scheduler)
        worker = subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_worker", address, "--nthreads", "1",
             "--nworkers", "1", "--no-dashboard", "--host", "127.0.0.1"], **quiet)
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(1, timeout=60)
        r = subprocess.run(
            [sys.executable, "-m", "dryfriction.cli", "sweep", str(proto), "--out",
             str(tmp_path / "o"), "--scheduler", address],
            capture_output=True, text=True, cwd=tmp_path, env=env, timeout=240)
        assert r.returncode == 0, r.stderr
        assert "4 points, 0 failed" in r.stdout
        assert scheduler.poll() is None and worker.poll() is None  # not ours to stop
        from dryfriction.sweeps.sweep import load_sweep

        ds = load_sweep(tmp_path / "o" / "sweep.nc")
        assert ds["class"].shape == (4,) and int(ds.attrs["n_failed"]) == 0
    finally:
        for p in (worker, scheduler):
            if p is not None and p.poll() is None:
                p.terminate()
        for p in (worker, scheduler):
            if p is not None:
                try:
                    p.wait(timeout=30)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()


def _worker_state(module: str) -> tuple[int, bool, str | None]:
    return os.getppid(), module in sys.modules, os.environ.get("OPENBLAS_NUM_THREADS")


@pytest.mark.slow
def test_local_workers_are_forked_warm_and_the_fork_server_is_stopped() -> None:
    """Workers start from the fork server with the runner's module already imported (a
    spawned worker, or a server without the preload list, would not have it before its first
    task), with one BLAS thread each, and closing stops the server: nothing of ours is left."""
    from dryfriction.sweeps.cluster import (
        close_client,
        fork_server_running,
        start_client,
        stop_fork_server,
    )

    # a module nothing else imports, standing for the runner's module
    me = psutil.Process()
    client = start_client(None, 2, preload=["colorsys"])
    try:
        assert fork_server_running()
        states = list(client.run(_worker_state, "colorsys").values())
        tree = {p: " ".join(p.cmdline()) for p in me.children(recursive=True)}
    finally:
        close_client(client, None, [])
    assert len(states) == 2
    assert all(ppid != os.getpid() for ppid, _, _ in states)  # not children of the sweep
    assert all(warm for _, warm, _ in states), states
    assert all(blas == "1" for _, _, blas in states), states
    assert not fork_server_running()
    stop_fork_server()  # a second stop does nothing
    # the server and the two workers it forked (a fork keeps the command line)
    assert sum("forkserver" in cmd for cmd in tree.values()) == 3
    _, alive = psutil.wait_procs(list(tree), timeout=10)
    left = [tree[p] for p in alive if "resource_tracker" not in tree[p]]
    assert not left, left


@pytest.mark.slow
def test_forked_workers_give_the_serial_results(tmp_path: Path) -> None:
    """The stick-slip summaries of a 2-worker sweep are those of the runner called here,
    point by point, bit for bit: a worker forked from the warm server computes the same."""
    import tomllib

    from dryfriction.analysis.stickslip import stick_slip_summary
    from dryfriction.sweeps.sweep import parse_sweep, run_sweep

    spec = parse_sweep(tomllib.loads(PROTO))
    ds = run_sweep(spec, stick_slip_summary, tmp_path / "o", n_workers=2)
    assert int(ds.attrs["n_failed"]) == 0
    for idx, ov in spec.points():
        ref = stick_slip_summary(spec.protocol(ov))
        for name, value in ref.items():
            got = float(ds[name].values[idx])
            assert got == value or (got != got and value != value), (ov, name, got, value)
