"""The ``dryfriction`` command line: thin wrappers that parse, call one library function, print.

Bad input (any ``ValueError`` from the library's checks, a bad path) becomes one line on
standard error and exit code 2.

One module per command group (:mod:`.model`, :mod:`.runs`, :mod:`.fitting`, :mod:`.record`,
:mod:`.sweeps`); :mod:`.common` holds the app and the one-line error handling.

The package itself imports nothing heavy: the console script forks its painter (:mod:`.painter`)
first, and ``app`` (Typer, Rich, every command) is imported on first use.
"""

import sys
from typing import Any

__all__ = ["app", "main", "COMMAND_MODULES"]

COMMAND_MODULES: dict[str, str] = {
    "examples": "examples", "model": "examples",
    "trap": "model", "static": "model", "steady": "model", "stability": "model",
    "fit": "fitting", "record": "record",
    "reproduce": "runs", "rsf": "runs", "simulate": "runs", "compare": "runs",
    "sweep": "sweeps", "phase-diagram": "sweeps", "bifurcation": "bifurcation",
}
"""Command name -> the module that registers it on :data:`.common.app`: :func:`main` imports
only the one a command line names (the other command modules and what they import
were a third of a ``simulate --no-figure``'s start-up); help, ``--version`` and an unknown name
get every command (:mod:`.commands`). Kept complete by ``tests/test_startup.py``."""


def __getattr__(name: str) -> Any:
    if name == "app":
        from .commands import app

        globals()["app"] = app
        return app
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def main(argv: list[str] | None = None) -> int:
    """Console-script entry point: runs the app and returns the exit status.

    Click's usage errors (unknown option or command, missing or ill-typed value) become one
    line ``error: ...`` on standard error and status 2, like the library's own errors (Click
    would print a usage box). ``--help`` and a bare ``dryfriction`` still print the help.

    Ctrl-C and SIGTERM become exceptions, so every temporary file and folder is removed on the
    way out; an interrupted command ends with status 130 (SIGINT) or 143 (SIGTERM) and one line
    on standard error, whatever the command (its own ``interrupted: ...`` line where it kept
    something, else ``error: interrupted (...)``). An interrupt is never swallowed: one that a
    library swallowed (raised inside a finaliser, say) still turns a finished run's status 0
    into 130. Within a compiled (Numba) call the handlers only record the signal, which is
    acted on when the call returns (:mod:`dryfriction.interrupts`).

    Parameters
    ----------
    argv : list of str, optional
        Arguments without the program name; default ``sys.argv[1:]``. Only without it (the
        console script, ``python -m dryfriction.cli``) may a painter process be forked to draw
        the figure (:mod:`.painter`).
    """
    import os
    import signal

    from . import painter

    # the figures import matplotlib without docstring tables nobody here reads (dryfriction.plots)
    os.environ.setdefault("DRYFRICTION_LEAN_MATPLOTLIB", "1")
    # one BLAS thread unless the user asks for more: the commands' linear algebra is small (fits
    # of a few parameters), and an idle BLAS thread spins on a core that the painter, the
    # figure pool or a sweep's workers need (issue 12); read when NumPy loads, so only set
    # in a process that has not loaded it (not in a test or notebook calling main())
    if "numpy" not in sys.modules:
        os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
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
        with painter.painting(sys.argv[1:] if argv is None else None):
            code = _run(argv)
    except BrokenPipeError:
        # the reader of our output went away (``| head``): stop quietly, as a pipe expects
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        code = 141
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else int(exc.code is not None)
    except KeyboardInterrupt:  # raised outside the app, or by a handler not ours
        code = 130
    finally:
        signal.signal(signal.SIGINT, previous[0])
        signal.signal(signal.SIGTERM, previous[1])
    if code == 130 and not interrupted:  # Click's Abort, or Typer's Exit(130) on Ctrl-C
        interrupted.append(signal.SIGINT)
    if interrupted and code != 141:
        # one line, unless the command said its own (what it kept); Typer turns Ctrl-C into a
        # silent Exit(130), so this is the line of most interrupted commands
        last = interrupted[-1]
        said = _said_interrupted()
        if not said:
            _error_line(f"interrupted ({'Ctrl-C' if last == signal.SIGINT else 'SIGTERM'})")
        code = 128 + last
    if argv is None:
        # the process ends now: spare the interpreter's final full collection the objects
        # that exist (0.1-0.2 s with matplotlib and SciPy loaded, issue 12); every file of the
        # command is written and closed by now, and everything is still freed by the OS
        import gc

        gc.freeze()
    return code


def _run(argv: list[str] | None) -> int:
    """The app without Click's standalone mode: usage errors become one line."""
    import typer

    from .common import error_line

    app = _app_for(sys.argv[1:] if argv is None else argv)
    try:
        rv = app(args=argv, prog_name="dryfriction", standalone_mode=False)
    except typer.Abort:  # Ctrl-C, as Click reports it: main() says the one line
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


def _app_for(argv: list[str]) -> Any:
    """The app to run ``argv`` (without the program name): a stand-in set as this module's
    ``app`` (a test's), else the app with at least the command ``argv`` names registered."""
    if "app" in globals():  # loaded in full already, or a stand-in
        return globals()["app"]
    module = COMMAND_MODULES.get(argv[0]) if argv else None
    if module is None:  # help, --version, a name that is no command: every command
        return sys.modules[__name__].app
    import importlib

    importlib.import_module(f"{__name__}.{module}")
    from .common import app

    return app


def _said_interrupted() -> bool:
    """Whether the command said its own interruption line (and forget it: main() may run
    again in this process)."""
    from .common import INTERRUPTION_SAID

    said = bool(INTERRUPTION_SAID)
    INTERRUPTION_SAID.clear()
    return said


def _error_line(message: str) -> None:
    from .common import error_line

    error_line(message)
