"""A drawing process forked when a command that draws a figure starts.

A small command's figure costs more than its solve: importing matplotlib took about 0.4 s of
the 1.3 s of ``dryfriction simulate examples/rsf_velocity_step.toml``. The console script
therefore forks a *painter* before it imports anything heavy: the painter imports the figure
modules on the second core while the command itself imports, validates and solves; the command
then hands the finished result over a pipe and the painter draws and saves the figure.

The command's behaviour is the same with or without a painter: :func:`paint` draws in this
process when there is none (one core, no ``fork``, a process with other threads, a command
called in-process as :func:`dryfriction.cli.main` with arguments, a result too large to send),
when the painter died, or when ``DRYFRICTION_PAINTER=0``. An error raised while drawing is
raised again here. The painter ignores Ctrl-C (the command handles it), exits when its pipe
closes, and :func:`stop` kills and reaps it on every way out of the command, so no process
outlives the command.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import signal
import struct
import threading
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from . import figures

__all__ = ["FIGURE_COMMANDS", "MAX_PAYLOAD", "Painter", "active", "draw_figure", "paint",
           "painting", "start", "stop", "wanted"]

FIGURE_COMMANDS = frozenset({"simulate", "rsf", "compare"})
"""Commands whose figure is most of their time, and which start a painter."""

MAX_PAYLOAD = 64 * 2**20
"""Largest pickled result (bytes) sent to the painter; a larger one is drawn in this process
(no second copy of a big result in memory)."""

ENV = "DRYFRICTION_PAINTER"
"""``"0"`` turns the painter off (the figures are then drawn in the command's own process)."""

_HEADER = struct.Struct("<Q")
_PRELOAD: tuple[Callable[[], object], ...] = (figures.preload,)


@dataclass(frozen=True)
class Painter:
    """A running painter: its process id and the two pipe ends this process holds."""

    pid: int
    jobs: int
    results: int


_CURRENT: list[Painter] = []  # the painter of this process, if any (at most one)


def wanted(argv: Sequence[str]) -> bool:
    """Whether a command line will draw one of the figures a painter speeds up: its command is
    in :data:`FIGURE_COMMANDS` and it asks for neither ``--no-figure`` nor help."""
    if os.environ.get(ENV) == "0" or any(a in ("--no-figure", "--help") for a in argv):
        return False
    command = next((a for a in argv if not a.startswith("-")), None)
    return command in FIGURE_COMMANDS


def start(preload: Sequence[Callable[[], object]] = _PRELOAD) -> Painter | None:
    """Fork a painter that calls each of ``preload`` (imports), then waits for jobs.

    Returns ``None`` (and starts nothing) where a painter cannot help or is not safe: no
    ``fork``, a single core, other threads running in this process (a fork copies only the
    calling thread, and locks another thread holds stay held in the child), or a painter
    already running.
    """
    if _CURRENT or not hasattr(os, "fork") or threading.active_count() > 1:
        return None
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    if (cores or 1) < 2:
        return None
    job_r, job_w = os.pipe()
    res_r, res_w = os.pipe()
    pid = os.fork()
    if pid == 0:  # the painter: never returns into the command's code
        code = 0
        try:
            os.close(job_w)
            os.close(res_r)
            signal.signal(signal.SIGINT, signal.SIG_IGN)
            signal.signal(signal.SIGTERM, signal.SIG_DFL)
            _serve(job_r, res_w, preload)
        except BaseException:  # noqa: BLE001 - nothing may escape into the command's code
            code = 1
        finally:
            os._exit(code)  # no atexit handlers, no flushing of the command's buffers
    os.close(job_r)
    os.close(res_w)
    painter = Painter(pid, job_w, res_r)
    _CURRENT.append(painter)
    return painter


def active() -> Painter | None:
    """The painter of this process, if one is running."""
    return _CURRENT[0] if _CURRENT else None


def stop() -> None:
    """Kill and reap this process's painter (if any); safe to call more than once."""
    while _CURRENT:
        painter = _CURRENT.pop()
        for fd in (painter.jobs, painter.results):
            with contextlib.suppress(OSError):
                os.close(fd)
        with contextlib.suppress(ProcessLookupError):
            os.kill(painter.pid, signal.SIGKILL)
        with contextlib.suppress(ChildProcessError):
            os.waitpid(painter.pid, 0)


@contextlib.contextmanager
def painting(argv: Sequence[str] | None) -> Iterator[Painter | None]:
    """A painter for the command line ``argv`` while the command runs, if it will draw a figure
    (:func:`wanted`); stopped on the way out, whatever happened."""
    painter = start() if argv is not None and wanted(argv) else None
    try:
        yield painter
    finally:
        if painter is not None:
            stop()


def paint(target: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
    """Call ``target`` (a module-level function: it is pickled as its module and name) with the
    arguments, in the painter if one is running, else here; return what it returns, or raise
    what it raised.

    The painter is used only for arguments that pickle to at most :data:`MAX_PAYLOAD` bytes.
    If the painter has died, the call runs here (and the painter is reaped).
    """
    painter = active()
    if painter is not None:
        try:
            payload = pickle.dumps((target, args, kwargs), protocol=pickle.HIGHEST_PROTOCOL)
        except (pickle.PicklingError, TypeError, AttributeError):
            payload = None  # not picklable (a closure, say): drawn here
        if payload is not None and len(payload) <= MAX_PAYLOAD:
            try:
                _send(painter.jobs, payload)
                ok, value = pickle.loads(_receive(painter.results))
            except (OSError, EOFError):
                stop()  # it died: draw here instead
            except BaseException:
                # Ctrl-C while it draws: stop it before the command removes its staging
                # folder, so that it cannot write into it afterwards
                stop()
                raise
            else:
                if ok:
                    return value
                raise value
    return target(*args, **kwargs)


def draw_figure(builder: Callable[..., tuple[Any, Any]], *args: Any, path: Any,
                fmt: str = "png", dpi: int | None = None) -> None:
    """Build a figure with ``builder(*args)`` (one of :mod:`.figures`, returning
    ``(fig, axes)``) and save it to ``path`` with :func:`dryfriction.plots.style.save_figure`,
    in the painter if one is running (:func:`paint`)."""
    paint(render, builder, *args, path=path, fmt=fmt, dpi=dpi)


def render(builder: Callable[..., tuple[Any, Any]], *args: Any, path: Any, fmt: str,
           dpi: int | None) -> None:
    """Build the figure and save it (what :func:`draw_figure` runs, here or in the painter)."""
    from ..plots.style import save_figure

    fig, _ = builder(*args)
    save_figure(fig, path, fmt, dpi)


def _serve(jobs: int, results: int, preload: Sequence[Callable[[], object]]) -> None:
    """The painter's life: import, then run each job until the command closes the pipe.

    Nothing is drawn ahead to warm matplotlib's caches: measured, a warm-up figure cost 0.15 s
    and saved 0.03 s of the real one (its caches are mostly per figure)."""
    for load in preload:
        load()
    while True:
        try:
            message = _receive(jobs)
        except EOFError:
            return
        try:
            target, args, kwargs = pickle.loads(message)
            reply = (True, target(*args, **kwargs))
        except Exception as exc:  # noqa: BLE001 - raised again in the command
            reply = (False, exc)
        try:
            data = pickle.dumps(reply, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception as exc:  # noqa: BLE001 - an error that cannot be pickled
            data = pickle.dumps((False, RuntimeError(f"{type(exc).__name__}: {exc}")))
        _send(results, data)


def _send(fd: int, data: bytes) -> None:
    view = memoryview(_HEADER.pack(len(data)) + data)
    while view:
        view = view[os.write(fd, view):]


def _receive(fd: int) -> bytes:
    (n,) = _HEADER.unpack(_read_exactly(fd, _HEADER.size))
    return _read_exactly(fd, n)


def _read_exactly(fd: int, n: int) -> bytes:
    chunks, left = [], n
    while left:
        chunk = os.read(fd, min(left, 1 << 20))
        if not chunk:
            raise EOFError("pipe closed")
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)
