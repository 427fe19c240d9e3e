"""The ``dryfriction`` command line: thin wrappers that parse, call one library function, print.

Bad input (any ``ValueError`` from the library's checks, a bad path) becomes one line on
standard error and exit code 2.

One module per command group (:mod:`.model`, :mod:`.runs`, :mod:`.fitting`, :mod:`.record`,
:mod:`.sweeps`); :mod:`.common` holds the app and the one-line error handling.
"""

from typing import Any

import typer

from . import examples, fitting, model, record, runs, sweeps  # noqa: F401  (registers the commands)
from .common import app, error_line

__all__ = ["app", "main"]


def main(argv: list[str] | None = None) -> int:
    """Console-script entry point: runs the app and returns the exit status.

    Click's usage errors (unknown option or command, missing or ill-typed value) become one
    line ``error: ...`` on standard error and status 2, like the library's own errors (Click
    would print a usage box). ``--help`` and a bare ``dryfriction`` still print the help.

    Ctrl-C and SIGTERM become exceptions, so every temporary file and folder is removed on the
    way out (status 130 and 143). An interrupt is never swallowed: one that a library swallowed
    (raised inside a finaliser, say) still turns a finished run's status 0 into 130.

    Parameters
    ----------
    argv : list of str, optional
        Arguments without the program name; default ``sys.argv[1:]``.
    """
    import os
    import signal
    import sys

    # the figures import matplotlib without docstring tables nobody here reads (dryfriction.plots)
    os.environ.setdefault("DRYFRICTION_LEAN_MATPLOTLIB", "1")
    interrupted: list[int] = []

    def on_sigint(signum: int, frame: Any) -> None:
        interrupted.append(signum)
        raise KeyboardInterrupt

    def on_sigterm(signum: int, frame: Any) -> None:
        interrupted.append(signum)
        raise SystemExit(128 + signum)

    # restored on the way out: main() called in a process that goes on (a test, a notebook)
    # must not leave its handlers behind
    previous = signal.signal(signal.SIGINT, on_sigint), signal.signal(signal.SIGTERM, on_sigterm)
    try:
        code = _run(argv)
    except BrokenPipeError:
        # the reader of our output went away (``| head``): stop quietly, as a pipe expects
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        code = 141
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else int(exc.code is not None)
    except KeyboardInterrupt:
        error_line("interrupted (Ctrl-C)")
        code = 130
    finally:
        signal.signal(signal.SIGINT, previous[0])
        signal.signal(signal.SIGTERM, previous[1])
    last = interrupted[-1] if interrupted else None
    if last == signal.SIGTERM or (last == signal.SIGINT and code == 0):
        error_line(f"interrupted ({'Ctrl-C' if last == signal.SIGINT else 'SIGTERM'})")
        code = 128 + last
    return code


def _run(argv: list[str] | None) -> int:
    """The app without Click's standalone mode: usage errors become one line."""
    try:
        rv = app(args=argv, prog_name="dryfriction", standalone_mode=False)
    except typer.Abort:  # Ctrl-C, as Click reports it
        error_line("interrupted (Ctrl-C)")
        return 130
    except typer.TyperException as exc:  # Click's exceptions (Typer vendors Click)
        ctx = getattr(exc, "ctx", None)
        if type(exc).__name__ == "NoArgsIsHelpError" and ctx is not None:
            print(ctx.get_help())
            return 2
        message = exc.format_message()  # type: ignore[attr-defined]
        if ctx is not None and getattr(exc, "exit_code", 1) == 2:
            message += f" (see {ctx.command_path} --help)"
        error_line(message)
        return int(getattr(exc, "exit_code", 1))
    # without standalone mode a command's typer.Exit(code) comes back as its code
    return rv if isinstance(rv, int) else 0
