"""The Dask side of a sweep: start a client (local cluster or existing scheduler), close it.

A local cluster's workers are forked from multiprocessing's fork server, which imports Dask and
the sweep's runner module once, while the sweep's own process imports Dask too; a worker then
starts warm instead of spending a second or more of CPU importing them (with ``spawn``, Dask's
default, every worker imports them itself, and on a two-core machine two workers doing so cost
as much as the points they then compute). The fork server belongs to the sweep that started it
and is stopped with the cluster, so no process outlives the sweep.
"""

from __future__ import annotations

import contextlib
import logging
import os
import signal
import threading
from collections.abc import Callable, Iterator, Mapping, Sequence
from typing import Any

__all__ = ["CONNECT_TIMEOUT", "close_client", "fork_server_running", "probe_scheduler",
           "start_client", "start_fork_server", "stop_fork_server"]

CONNECT_TIMEOUT = 10.0
"""Default seconds to wait for an existing scheduler to answer."""

WORKER_ENVIRON = {"OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
"""Set (unless already set) in the fork server's environment before it imports NumPy, and the
Nanny's ``distributed.nanny.pre-spawn-environ`` (for workers spawned when no fork server
starts): single-threaded workers need them (two workers that each start a BLAS thread per core
would fight over the cores).

Not Dask's ``MALLOC_TRIM_THRESHOLD_=65536``: setting it stops glibc adapting its mmap
threshold, so every array larger than 128 KiB is mapped afresh and unmapped when freed (and
the heap is trimmed often), and a point faults its pages in again and again: on the
benchmark's points a worker used 20 % more CPU with it (5.3-5.6 s against 4.3 s for 32
points). Without it a worker keeps the memory it freed for its next point. (The Nanny would
also write Dask's variables into this process's own environment, for good.)"""

LOCAL_CONFIG = {"distributed.nanny.pre-spawn-environ": WORKER_ENVIRON,
                "distributed.worker.profile.enabled": False,
                "distributed.admin.tick.interval": "1s",
                "distributed.admin.system-monitor.interval": "5s"}
"""Dask settings of a local cluster's scheduler, nannies and workers (a worker gets them from
its Nanny). Besides the environment (:data:`WORKER_ENVIRON`), periodic callbacks that serve
only the dashboard or diagnostics (the statistical profiler samples every worker's stack every
10 ms, the tick checks the event loop every 20 ms, the system monitor reads /proc every 0.5 s):
on a machine with as many workers as cores their CPU is taken from the points. Measured on the
32-point benchmark sweep (about 6 s): a worker's event loop used 0.36-0.49 s of CPU with Dask's
defaults and 0.14 s with these, the sweep process's own event loop (scheduler, nannies) 0.38 s
and 0.20 s."""

_FORK_SERVER = {"owned": False}


def fork_server_running() -> bool:
    """Whether this process has multiprocessing's fork server running (ours or another's)."""
    from multiprocessing import forkserver

    # no public way to ask; CPython's own tests read the same attribute
    return forkserver._forkserver._forkserver_pid is not None


def start_fork_server(preload: Sequence[str] = ()) -> bool:
    """Start multiprocessing's fork server with Dask and ``preload`` imported; return whether
    this call started it (``False``: one was running already, or it could not start).

    Returns at once: the server imports in its own process, while the caller goes on. The
    modules are ``distributed`` and ``preload`` (a module that fails to import is skipped, by
    multiprocessing). Not the main module: the server is never told its path (CPython 3.11),
    and each worker runs a main script again as ``spawn`` does (cheap when what it imports
    is preloaded; a ``-m`` package's ``__main__`` is not run again). A server already running
    (started by other code of this process) is used as it is and left running.
    """
    from multiprocessing import forkserver

    if fork_server_running():
        return False
    forkserver.set_forkserver_preload(["distributed", *preload])
    added = {k: v for k, v in WORKER_ENVIRON.items() if k not in os.environ}
    os.environ.update(added)  # the server inherits the environment when it starts
    # A terminal's Ctrl-C reaches every process of its group. The server ignores SIGINT only
    # once its imports are done (multiprocessing.forkserver.main), and they take a second or
    # more: a Ctrl-C then printed its KeyboardInterrupt traceback above the line that says how
    # to resume (tests/sweeps/test_sweep.py, the interrupt while the cluster starts). So it
    # starts with SIGINT ignored, which it and the workers it forks inherit (an ignored
    # signal stays ignored across exec; the workers ignore it anyway: _QuietWorker). Blocked
    # meanwhile in this process, a Ctrl-C of this moment stays pending (Linux never discards a
    # blocked signal as ignored) and reaches this process's own handler once it is restored;
    # one pending already is discarded by SIG_IGN, so it is raised again. The resource
    # tracker first: starting it unblocks SIGINT on its way out (multiprocessing's own guard)
    from multiprocessing import resource_tracker

    resource_tracker.ensure_running()
    here = threading.current_thread() is threading.main_thread()
    if here:
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        came = signal.SIGINT in signal.sigpending()
        previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        forkserver.ensure_running()
        _FORK_SERVER["owned"] = True  # before a held Ctrl-C is raised: stopped with the rest
    except OSError:
        return False  # the workers are spawned instead: slower, not wrong
    finally:
        for k in added:
            os.environ.pop(k, None)
        if here:
            signal.signal(signal.SIGINT, previous)
            signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
            if came:
                signal.raise_signal(signal.SIGINT)
    return True


def stop_fork_server(timeout: float = 10.0) -> None:
    """Stop the fork server if :func:`start_fork_server` started it (else do nothing).

    Its remaining children (workers a closed cluster should have ended) are waited for
    ``timeout`` seconds and then killed, so that stopping it cannot hang. The server itself is
    ended with SIGTERM: asked to stop, it would shut its interpreter down, with Dask and SciPy
    loaded about 0.2 s that the sweep waits for; it holds nothing that needs cleaning up.
    """
    if not _FORK_SERVER["owned"]:
        return
    _FORK_SERVER["owned"] = False
    from multiprocessing import forkserver

    import psutil

    server = forkserver._forkserver
    pid = server._forkserver_pid
    if pid is None:
        return
    with contextlib.suppress(psutil.Error):
        _, alive = psutil.wait_procs(psutil.Process(pid).children(), timeout=timeout)
        for p in alive:
            p.kill()
        psutil.wait_procs(alive, timeout=timeout)
    with contextlib.suppress(ProcessLookupError):
        os.kill(pid, signal.SIGTERM)  # our child, not yet waited for: the pid is still its
    server._stop()  # closes its "alive" pipe and waits for it; a later sweep starts another


def probe_scheduler(address: str, timeout: float) -> None:
    """Fail within ``timeout`` seconds unless a Dask scheduler answers at ``address``.

    ``Client(address, timeout=...)`` waits forever when something else (an HTTP server, say)
    accepts the connection and never completes Dask's handshake; this bounds the whole
    exchange.
    """
    import asyncio

    from distributed.comm import connect

    async def identity() -> Any:
        comm = await connect(address, timeout=timeout)
        try:
            await comm.write({"op": "identity", "reply": True})
            return await comm.read()
        finally:
            comm.abort()

    try:
        reply = asyncio.run(asyncio.wait_for(identity(), timeout))
    except TimeoutError:
        raise ValueError(f"--scheduler {address}: cannot reach a Dask scheduler there within "
                         f"{timeout:g} s (raise --connect-timeout if it is slow)") from None
    except (OSError, ValueError, TypeError) as exc:
        raise ValueError(f"--scheduler {address}: cannot reach a Dask scheduler there "
                         f"({exc})") from None
    if not (isinstance(reply, Mapping) and reply.get("type") == "Scheduler"):
        raise ValueError(f"--scheduler {address}: cannot reach a Dask scheduler there (it "
                         "answered, but not as a Dask scheduler)")


_QUIET: dict[str, type] = {}


def _quiet_class(name: str) -> type:
    """A scheduler or worker class that serves no HTTP at all.

    ``dashboard_address=None`` only hides the dashboard's pages: the scheduler still listens
    on port 8787 (and each worker on a random port) for its health and metrics routes, and
    reports that server as its ``dashboard`` service. A local sweep needs none of it. Built on
    first use (importing distributed is slow) and reached as ``dryfriction.sweeps.cluster.<name>``
    (module ``__getattr__``), so that the worker processes can unpickle it.
    """
    if name not in _QUIET:
        from distributed import Scheduler, Worker
        from distributed.http.routing import RoutingApplication

        def start_http_server(self: Any, routes: Any, *args: Any, **kwargs: Any) -> None:
            self.http_application = RoutingApplication(routes)  # stopping the node reads it

        base = Scheduler if name == "_QuietScheduler" else Worker
        attrs: dict[str, Any] = {"start_http_server": start_http_server,
                                 "__module__": __name__, "__qualname__": name}
        if base is Worker:
            def __init__(self: Any, *args: Any, **kwargs: Any) -> None:  # noqa: N807
                # a terminal's Ctrl-C reaches every process of its group: the sweep process
                # handles it and closes the cluster; a worker printing its own traceback
                # would only bury the one line that says how to resume
                if threading.current_thread() is threading.main_thread():
                    signal.signal(signal.SIGINT, signal.SIG_IGN)
                base.__init__(self, *args, **kwargs)

            attrs["__init__"] = __init__
        _QUIET[name] = type(name, (base,), attrs)
    return _QUIET[name]


def __getattr__(name: str) -> Any:
    if name in ("_QuietScheduler", "_QuietWorker"):
        return _quiet_class(name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def start_client(scheduler: str | None, n_workers: int | None,
                 connect_timeout: float = CONNECT_TIMEOUT,
                 preload: Sequence[str] = (),
                 meanwhile: Callable[[], object] | None = None) -> Any:
    """A Dask client: on the scheduler at ``scheduler``, or on a new local cluster.

    The local cluster has ``n_workers`` single-threaded worker processes (default: one per
    core), forked from a fork server that has imported Dask and the ``preload`` modules once
    (:func:`start_fork_server`), so a worker starts warm instead of importing them itself;
    the fork server starts before this process imports Dask, so both import at the same time.
    ``meanwhile`` (if given) is called once the fork server is starting and before this
    process starts the cluster: work the caller needs later (imports) then overlaps the
    server's own imports, which no worker can start before.
    Close it with :func:`close_client`. ``KeyboardInterrupt`` if Ctrl-C comes while it
    starts (after closing what was started).
    """
    try:
        if scheduler is None:
            start_fork_server(preload)
        if meanwhile is not None:
            meanwhile()
        return _start(scheduler, n_workers, connect_timeout)
    except BaseException:
        stop_fork_server()  # the one this call started, if any (a Ctrl-C may come as it starts)
        raise


def _start(scheduler: str | None, n_workers: int | None, connect_timeout: float) -> Any:
    import dask
    from dask.distributed import Client, Nanny, SpecCluster

    if scheduler is not None:
        probe_scheduler(scheduler, connect_timeout)
        try:
            return Client(scheduler, timeout=f"{connect_timeout}s")
        except (OSError, TimeoutError) as exc:
            raise ValueError(f"--scheduler {scheduler}: cannot reach it ({exc})") from None
    n = n_workers or os.cpu_count() or 1
    quiet_scheduler, quiet_worker = _quiet_class("_QuietScheduler"), _quiet_class("_QuietWorker")
    # the workers' own logs at CRITICAL only: on a Ctrl-C under load a worker's heartbeat
    # can meet the closing scheduler and log "Failed to communicate with scheduler" with a
    # CommClosedError traceback above the one line that says how to resume (seen in CI at a
    # load of 5); a point's failure reaches the sweep through its future, not these logs
    worker = {"cls": Nanny, "options": {"nthreads": 1, "host": "127.0.0.1",
                                        "worker_class": quiet_worker, "dashboard": False,
                                        "silence_logs": logging.CRITICAL}}
    method = "forkserver" if fork_server_running() else "spawn"
    with (_sigint_held() as caught,
          dask.config.set({"distributed.worker.multiprocessing-method": method,
                           **LOCAL_CONFIG})):
        cluster = SpecCluster(
            scheduler={"cls": quiet_scheduler,
                       "options": {"host": "127.0.0.1", "port": 0, "dashboard": False,
                                   "dashboard_address": None}},
            workers={i: worker for i in range(n)},
            silence_logs=logging.ERROR,
        )
        try:
            client = Client(cluster)
        except BaseException:
            cluster.close()
            raise
    if caught:  # Ctrl-C while starting: stop now, with nothing left behind
        close_client(client, None, [])
        raise KeyboardInterrupt
    return client


@contextlib.contextmanager
def _sigint_held() -> Iterator[list[int]]:
    """Record a Ctrl-C that comes while the cluster starts; yield the list that records it.

    The start must not be cut in the middle (a half-started cluster leaves processes behind),
    and the interrupt must not be lost either: it is recorded here and acted on as soon as the
    start is over (the caller closes the cluster and raises ``KeyboardInterrupt``). The
    workers ignore SIGINT themselves (``_QuietWorker``), so they print no tracebacks. Only
    possible in the main thread; elsewhere a no-op.
    """
    caught: list[int] = []
    if threading.current_thread() is not threading.main_thread():
        yield caught
        return
    previous = signal.signal(signal.SIGINT, lambda signum, frame: caught.append(signum))
    try:
        yield caught
    finally:
        signal.signal(signal.SIGINT, previous)



def close_client(client: Any, scheduler: str | None, futures: list[Any]) -> None:
    """Cancel what is left, close the client and (local) cluster; a second Ctrl-C waits."""
    with _sigint_ignored():
        cluster = getattr(client, "cluster", None)
        with contextlib.suppress(Exception):
            client.cancel(futures)
        with contextlib.suppress(Exception):
            client.close(timeout=10)
        if scheduler is None and cluster is not None:
            cluster.close(timeout=20)
        stop_fork_server()  # after the workers it forked are gone


@contextlib.contextmanager
def _sigint_ignored() -> Iterator[None]:
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


