"""Ctrl-C and SIGTERM never land inside a compiled (Numba) call.

Why. Python runs a signal's handler in the main thread, between bytecodes. A compiled call
runs no bytecode, except where Numba's wrapper calls back into Python: boxing a returned
array unpickles its Python type through ``numba.core.serialize._numba_unpickle``, a Python
function, and a pending handler runs there. A handler that raises (the command line's, or
Python's default ``KeyboardInterrupt``) raises inside the boxing, whose generated code does not
check for the error: the call returns a result with an exception set (``SystemError:
CPUDispatcher(<function _integrate ...>) returned a result with an exception set``) or builds
the array with a NULL type and the process dies with a segmentation fault (measured, gdb:
``_PyErr_CheckSignalsTstate`` called from ``numba_unpickle`` called from the compiled
``_integrate``; exit 139 in 6 of 15 Ctrl-C trials of a long ``rsf`` run).

The same holds while a dispatcher's first call loads its machine code from Numba's cache or
compiles it: llvmlite calls Python through ctypes callbacks, where a raised interrupt is
printed as ``Exception ignored on calling ctypes callback function`` with a traceback, and
then lost (measured: the compile went on for 16 s).

The rule (ours). A compiled call that returns anything but scalars, and every first call of a
dispatcher, runs inside :func:`deferred`: there the handlers of SIGINT and SIGTERM only record
the signal, and on the way out the previous handlers are restored and called, so the interrupt
is raised between compiled calls, in plain Python. A long computation is cut into chunks of a
fraction of a second (the rate-and-state stepper resumes exactly where it stopped:
``rsf/stepper.py``), so the interrupt still comes at once; only a compile (the first run after
installing without ``make``'s warm-up, announced by its own line) holds it back until it ends.
A loaded compiled function that returns only scalars (the trap ensemble's kernel,
:func:`dryfriction.ensemble.kernel.advance_window`) needs no guard: its wrapper calls no Python
code (``tests/cli/test_signals.py`` keeps both halves of the rule).
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Callable, Iterator
from typing import Any

__all__ = ["SIGNALS", "deferred"]

SIGNALS: tuple[int, ...] = (signal.SIGINT, signal.SIGTERM)
"""The signals held back by :func:`deferred`."""

Handler = Callable[[int, Any], Any] | int


@contextlib.contextmanager
def deferred(*, defaults: bool = False) -> Iterator[None]:
    """Within the block SIGINT and SIGTERM are only recorded; on the way out the handlers that
    were in place are restored and called, once per signal received, in arrival order (the
    last one's exception propagates; every handler sees its signal).

    Only handlers that are Python functions are replaced: the default action of SIGTERM and an
    ignored signal never run Python code, and keep their effect. With ``defaults`` a signal
    whose action is the default (SIGTERM in a library user's process) is held back too and
    raised again on the way out, so that it still ends the process, but after the block: a
    critical section that must not be cut (the final moves of a results folder,
    :mod:`dryfriction.io.files`). Outside the main thread (where Python runs no handler) this
    is a no-op. Nested blocks deliver to the outer one.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    previous: dict[int, Handler] = {}
    for s in SIGNALS:
        handler = signal.getsignal(s)
        if callable(handler) or (defaults and handler == signal.SIG_DFL):
            previous[s] = handler
            signal.signal(s, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
        _deliver(list(dict.fromkeys(caught)), previous)


def _deliver(signums: list[int], handlers: dict[int, Handler]) -> None:
    """Call each signal's handler; a raising handler does not keep the later ones from running."""
    if not signums:
        return
    try:
        handler = handlers[signums[0]]
        if callable(handler):
            handler(signums[0], None)
        else:  # the default action, restored: it ends the process now
            signal.raise_signal(signums[0])
    finally:
        _deliver(signums[1:], handlers)
