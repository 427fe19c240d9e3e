"""dryfriction.interrupts.deferred in this process (issue 25; the end-to-end rule is
cli/test_signals.py): inside the block a Python handler only records its signal; on the way out
the handlers are restored and each called in arrival order, a raising one not keeping the
next from running; a default or ignored action is left in place unless ``defaults`` (checked
without raising it: the default action of SIGTERM would end the test run); nested blocks
deliver to the outer one; outside the main thread nothing changes."""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from typing import Any

import pytest

from dryfriction.interrupts import deferred


@pytest.fixture
def handlers() -> Iterator[list[tuple[str, int]]]:
    heard: list[tuple[str, int]] = []
    old = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}

    def on_int(signum: int, frame: Any) -> None:
        heard.append(("int", signum))
        raise KeyboardInterrupt

    def on_term(signum: int, frame: Any) -> None:
        heard.append(("term", signum))

    signal.signal(signal.SIGINT, on_int)
    signal.signal(signal.SIGTERM, on_term)
    try:
        yield heard
    finally:
        for s, h in old.items():
            signal.signal(s, h)


def test_signals_wait_for_the_end_of_the_block_in_arrival_order(handlers) -> None:  # type: ignore[no-untyped-def]
    int_handler = signal.getsignal(signal.SIGINT)
    with pytest.raises(KeyboardInterrupt):
        with deferred():
            signal.raise_signal(signal.SIGTERM)
            signal.raise_signal(signal.SIGINT)
            assert handlers == []  # recorded only
            assert signal.getsignal(signal.SIGINT) is not int_handler
    # both delivered, in the order they came; the raising one did not stop the other
    assert handlers == [("term", signal.SIGTERM), ("int", signal.SIGINT)]
    assert signal.getsignal(signal.SIGINT) is int_handler  # restored
    handlers.clear()
    with pytest.raises(KeyboardInterrupt):
        with deferred():
            signal.raise_signal(signal.SIGINT)
            signal.raise_signal(signal.SIGTERM)
    assert handlers == [("int", signal.SIGINT), ("term", signal.SIGTERM)]


def test_a_nested_block_delivers_to_the_outer_one(handlers) -> None:  # type: ignore[no-untyped-def]
    with deferred():
        with deferred():
            signal.raise_signal(signal.SIGTERM)
        assert handlers == []  # the inner block's "previous" handler is the outer recorder
    assert handlers == [("term", signal.SIGTERM)]


def test_a_default_or_ignored_action_is_replaced_only_with_defaults() -> None:
    old = signal.getsignal(signal.SIGTERM)
    try:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        with deferred():
            assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL
        with deferred(defaults=True):
            assert callable(signal.getsignal(signal.SIGTERM))
        assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        with deferred(defaults=True):
            signal.raise_signal(signal.SIGTERM)  # ignored, inside and after
            assert signal.getsignal(signal.SIGTERM) == signal.SIG_IGN
    finally:
        signal.signal(signal.SIGTERM, old)


def test_outside_the_main_thread_nothing_changes(handlers) -> None:  # type: ignore[no-untyped-def]
    seen: list[Any] = []

    def work() -> None:
        with deferred():
            seen.append(signal.getsignal(signal.SIGINT))

    th = threading.Thread(target=work)
    th.start()
    th.join()
    assert seen == [signal.getsignal(signal.SIGINT)]
