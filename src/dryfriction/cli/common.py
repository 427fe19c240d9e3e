"""What every command shares: the app, one-line errors, printing."""

from __future__ import annotations

import functools
import json
import re
import time
import warnings
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any, TypeVar

import typer
import typer.core

if TYPE_CHECKING:
    from rich.table import Table

from ..io.files import to_jsonable

# Plain Click help (no Rich markup): Rich would take the bracketed words of the help texts
# (``[sweep]``, ``V[um/s]``, the units ``[a0/t0]``) as markup and drop them, and it labels every
# flag ``<bool>`` as if it took a value.
app = typer.Typer(
    add_completion=False,
    rich_markup_mode=None,
    no_args_is_help=True,
    context_settings={"help_option_names": ["-h", "--help"]},
    help="The Caroli-Velicky elasto-plastic model of dry friction (reduced units: a0, t0, F_el).",
)


class _Console:
    """A Rich console made at its first use: a command that prints only JSON (``simulate
    --json``) does not import Rich (a tenth of rsfmodel's whole velocity step)."""

    def __init__(self, **options: Any) -> None:
        self._options = options

    def __getattr__(self, name: str) -> Any:
        return getattr(self.real(), name)

    def real(self) -> Any:
        """The Rich console itself: what Rich's own machinery takes (a progress bar enters
        it as a context manager, which this stand-in is not)."""
        console = self.__dict__.get("_console")
        if console is None:
            from rich.console import Console

            console = self.__dict__["_console"] = Console(**self._options)
        return console


err: Any = _Console(stderr=True)
out: Any = _Console()

F = TypeVar("F", bound=Callable[..., Any])


def _print_version(value: bool) -> None:
    if value:
        from .. import __version__

        print(f"dryfriction {__version__}")
        raise typer.Exit(0)


@app.callback()
def _root(
    version: bool = typer.Option(False, "--version", callback=_print_version, is_eager=True,
                                 help="Print the version and exit."),
) -> None:
    """The Caroli-Velicky elasto-plastic model of dry friction (reduced units: a0, t0, F_el)."""


def error_line(message: str) -> None:
    """Print ``error: message`` as one line; the message is plain text (``[drive]`` is not
    Rich markup)."""
    err.print("[bold red]error:[/] ", end="", highlight=False)
    err.print(message, markup=False, highlight=False, soft_wrap=True)


INTERRUPTION_SAID: list[bool] = []
"""Non-empty once this command has said, in its one line, that it was interrupted
(:func:`say_interrupted`): :func:`dryfriction.cli.main` then adds no line of its own."""


def say_interrupted(message: str) -> None:
    """The command's one line on an interrupt (``interrupted: ...``, what was kept); the caller
    then exits with 130. Without it, :func:`dryfriction.cli.main` says ``error: interrupted``."""
    err.print(f"[bold yellow]interrupted:[/] {message}", highlight=False, soft_wrap=True)
    INTERRUPTION_SAID.append(True)


def cli_errors(fn: F) -> F:
    """Turn the library's ``ValueError``/``OSError`` into one line and exit code 2."""

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        from ..rsf.growth import UnstableStartWarning

        try:
            with warnings.catch_warnings():
                # said in the run's summary (unstable_start); a printed warning would be a
                # second line beside a refusal's one
                warnings.simplefilter("ignore", UnstableStartWarning)
                return fn(*args, **kwargs)
        except BrokenPipeError:
            raise  # the reader went away (``| head``): not an error of the input
        except (ValueError, OSError) as exc:
            error_line(option_named(str(exc)))
            raise typer.Exit(2) from None

    return wrapper  # type: ignore[return-value]


_LEADING_NAME = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?= = | is )")


def option_named(message: str) -> str:
    """The library's message with its leading parameter name (``v_ref = -1 is out of range``)
    given as the option the user typed (``--v-ref = -1 ...``), where the running command has
    that option: the library's checks name their Python parameter, the user knows only the
    command line. Any other message is returned
    unchanged (a protocol's ``FILE: in model: ...``, a name that is not an option here)."""
    match = _LEADING_NAME.match(message)
    from typer._click.globals import get_current_context  # the Click that Typer vendors

    ctx = get_current_context(silent=True)
    if match is None or ctx is None:
        return message
    from ..app.options import OPTIONS

    declared = OPTIONS.get(ctx.info_name or "", {}).get(match.group(1))
    # the flag the option table gives the parameter (--u-ref for v_ref in static), else the
    # parameter's name as a flag
    option = (declared.flag.split("/")[0] if declared is not None
              else "--" + match.group(1).replace("_", "-"))
    if not any(option in param.opts for param in ctx.command.params):
        return message
    return option + message[match.end():]


FORMAT_HELP = "Figure file format: png, pdf or svg (vector)."
FORMAT_CHOICES = "[png|pdf|svg]"


def one_of(choices: tuple[str, ...]) -> str:
    """The metavar that lists an option's choices in ``--help``: ``[cv|rsf]``."""
    return "[" + "|".join(choices) + "]"


def renamed(old: str, new: str, why: str, old_value: Any, value: Any, default: Any) -> Any:
    """The value of an option renamed in this release: ``new``'s, or the deprecated ``old``
    name's (with a warning on standard error; kept for one release, CHANGELOG.md)."""
    if old_value is None:
        return value
    if value != default:
        raise ValueError(f"{old} and {new} are one option: give {new} only")
    say(f"warning: {old} is deprecated here, use {new} ({why}); {old} will be removed in the "
        "next release")
    return old_value


DPI_HELP = "Resolution of the figures in dots per inch, 50-1200 (default 150; 300 for print)."
FIGURE_HELP = ("Draw the figure; --no-figure skips it, and matplotlib's start-up with it "
               "(a previous run's figure in --out is removed, like any file it no longer "
               "writes).")


FORCE_HELP = ("Write into a folder that holds other files too: they are kept (one whose name "
               "collides with a result is renamed NAME.~1~); nothing is deleted.")


def say(line: str) -> None:
    """One plain-text line on standard error (what was done to files already there)."""
    err.print(line, markup=False, highlight=False, soft_wrap=True)


def compile_notice(rsf: bool = False) -> None:
    """One line on standard error when this run will compile the solvers first (a fresh
    install that skipped ``make``'s warm-up, or edited kernels), so a pause is not silent.

    A rate-and-state run (``rsf``) compiles only if it is large enough to leave the
    interpreted solver (:mod:`dryfriction.rsf.stepper`): its notice is said then, if at all."""
    from ..warm import missing_kernel_caches

    def notice(kernel: str | None = None) -> None:
        missing = missing_kernel_caches()
        if missing and (kernel is None or kernel in missing):
            say("note: first run after installing: compiling the solvers once (about 15 s; "
                "`python -m dryfriction.warm` does it ahead of time)")

    if not rsf:
        notice()
        return
    from ..rsf import stepper

    stepper.compile_hook = lambda: notice("rsf/stepper.py")


PROGRESS_EVERY_S = 10.0
"""Without a terminal (a log file, a pipe, CI): one progress line at most this often, the first
after this long, so that a job of a few seconds prints nothing and a long one is not silent."""

Update = Callable[..., None]
"""``update(done, total=None, what=None)``: work done so far, the total (``None``: unchanged;
an estimate may grow) and what is being done now."""


@contextmanager
def lazy_progress_bar(label: str, total: float | None = None,
                      unit: str = "") -> Iterator[Update]:
    """:func:`progress_bar`, opened at the first update only: a run that reports no progress
    (a rate-and-state protocol) does not import Rich's progress machinery."""
    from contextlib import ExitStack

    with ExitStack() as stack:
        bar: list[Update] = []

        def update(done: float, new_total: float | None = None, what: str | None = None) -> None:
            if not bar:
                bar.append(stack.enter_context(progress_bar(label, total, unit)))
            bar[0](done, new_total, what)

        yield update


@contextmanager
def progress_bar(label: str, total: float | None = None, unit: str = "",
                 delay: float = 1.0) -> Iterator[Update]:
    """Progress with the elapsed time and an estimate of the time left, on standard error.

    On a terminal: a Rich bar (removed when done) that appears after ``delay`` seconds, so
    that a quick run draws none. Otherwise one plain line every :data:`PROGRESS_EVERY_S`
    seconds (``label: what 12/40 unit (30 %), 25 s elapsed, about 58 s left``). Standard
    output is never touched: a ``--json`` or table on it stays clean.

    Parameters
    ----------
    label : str
        What runs (``fit``, ``sweep``).
    total : float, optional
        Units of work in all (``None``: not known yet; no estimate of the time left).
    unit : str
        What is counted (``points``, ``evaluations``), shown after the counts.
    delay : float
        Seconds before the terminal bar appears.

    Yields
    ------
    callable
        ``update(done, total=None, what=None)``.
    """
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    started = time.monotonic()
    state: dict[str, Any] = {"total": total, "what": "", "last": started}
    bar: dict[str, Any] = {}
    counts = "{task.completed:.0f}/{task.total:.0f}" + (f" {unit}" if unit else "")

    def update(done: float, new_total: float | None = None, what: str | None = None) -> None:
        if new_total is not None:
            state["total"] = new_total
        if what is not None:
            state["what"] = what
        now = time.monotonic()
        tot = state["total"]
        if err.is_terminal:
            if not bar:
                if now - started < delay or tot is None:  # no total: nothing to draw yet
                    return
                p = Progress(TextColumn("{task.description}"), BarColumn(),
                             TextColumn(counts), TimeElapsedColumn(), TextColumn("left"),
                             TimeRemainingColumn(), console=err.real(), transient=True)
                p.start()
                bar["p"], bar["task"] = p, p.add_task(label, total=tot)
            desc = f"{label}: {state['what']}" if state["what"] else label
            bar["p"].update(bar["task"], completed=done, total=tot, description=desc)
            return
        if now - state["last"] < PROGRESS_EVERY_S:
            return
        state["last"] = now
        elapsed = now - started
        line = f"{label}: " + (f"{state['what']} " if state["what"] else "")
        if tot:
            line += f"{done:.0f}/{tot:.0f}" + (f" {unit}" if unit else "")
            line += f" ({100 * done / tot:.0f} %), {elapsed:.0f} s elapsed"
            if done > 0:
                line += f", about {elapsed * max(tot - done, 0) / done:.0f} s left"
        else:
            line += f"{done:.0f}" + (f" {unit}" if unit else "") + f", {elapsed:.0f} s elapsed"
        say(line)

    try:
        yield update
    finally:
        if bar:
            bar["p"].stop()


def emit(result: dict[str, Any], as_json: bool, title: str,
         units: dict[str, str | None] | None = None) -> None:
    """Print ``result`` as JSON (``--json``) or as a table, each number's name with its unit
    from ``units`` as ``name[unit]`` (:mod:`dryfriction.io.units`)."""
    if as_json:
        print(json.dumps(to_jsonable(result), indent=2))
        return
    from rich.table import Table
    from rich.text import Text

    from ..io.units import header

    units = units or {}
    table = Table(title=Text(title), show_header=False)
    for k, v in result.items():
        number = isinstance(v, (int, float)) and not isinstance(v, bool)
        name = header(k, units[k]) if number and units.get(k) is not None else k
        table.add_row(Text(name), Text(f"{v:.10g}" if isinstance(v, float) else str(v)))
    print_whole(table)


def print_whole(table: Table) -> None:
    """Print ``table`` at its natural width, never cut to the console's (80 columns when the
    output is a pipe or a file): a number cut to ``0.072482…`` is no number."""
    natural = out.measure(table, options=out.options.update_width(100_000)).maximum
    if natural <= out.width:
        out.print(table)
    else:  # ``print(width=...)`` cannot go beyond the console's width: a wider console can
        from rich.console import Console

        Console(width=natural).print(table, crop=False)


class _ManyValues(typer.core.TyperCommand):
    """A command whose list options take several values after one flag: ``--T 1 10 100``.

    Before Click parses, ``--T 1 10 100`` is rewritten to ``--T 1 --T 10 --T 100``: every token
    after a listed flag that reads as a number (``-1``, ``1e3``, ``nan`` included, so that the
    library's range checks see it) is taken as another value. Repeating the flag also works.
    Click's own usage errors (missing option, not a number) are printed as one line, exit 2.
    """

    many: tuple[str, ...] = ()

    def parse_args(self, ctx: Any, args: list[str]) -> list[str]:
        expanded: list[str] = []
        i = 0
        while i < len(args):
            tok = args[i]
            expanded.append(tok)
            i += 1
            if tok == "--":
                expanded += args[i:]
                break
            if tok in self.many and i < len(args):
                expanded.append(args[i])  # the first value, whatever it is: Click checks it
                i += 1
                while i < len(args) and _is_number(args[i]):
                    expanded += [tok, args[i]]
                    i += 1
        try:
            return super().parse_args(ctx, expanded)
        except typer.TyperException as exc:  # Click's UsageError and its kin (exit code 2)
            if getattr(exc, "exit_code", None) != 2:
                raise
            message = exc.format_message()  # type: ignore[attr-defined]
            error_line(message)
            raise typer.Exit(2) from None


def _is_number(tok: str) -> bool:
    try:
        float(tok)
    except ValueError:
        return False
    return True


def many(*flags: str) -> type[_ManyValues]:
    return type("ManyValues", (_ManyValues,), {"many": flags})


def unit_after(unit: str | None) -> str:
    """`` unit`` to write after a value, nothing for a dimensionless one or none (a new user
    read ``a0 = 1e-06``, the joint fit's ``dc = 1.1e-05`` and a cv fit's ``t0 = 0.01``
    without units)."""
    from ..io.units import DIMENSIONLESS, csv_unit

    u = csv_unit(unit) if unit else DIMENSIONLESS
    return "" if u == DIMENSIONLESS else f" {u}"


def columns(title: str, params: dict[str, Any], cols: dict[str, Any],
            units: dict[str, str] | None = None,
            param_units: Mapping[str, str | None] | None = None,
            notes: Sequence[str] = ()) -> None:
    """Print ``params`` on one line, then ``cols`` as a table of numbers, whole.

    Parameters
    ----------
    title : str
        What the table is.
    params : dict
        The inputs common to every row.
    cols : dict
        Column name -> values (equal lengths).
    units : dict, optional
        Column name -> unit, shown in the header as ``name[unit]`` (the CSV headers'
        convention, :mod:`dryfriction.io.units`).
    param_units : mapping, optional
        Parameter name -> unit, said after each value of the first line (a new user read
        ``a0 = 1e-06, t0 = 0.01`` without units); a dimensionless one is written bare.
    notes : sequence of str
        Lines said after the table, each as ``note: ...``.
    """
    from ..io.units import header

    units = units or {}
    pu = param_units or {}
    out.print(f"{title}: " + ", ".join(f"{k} = {v}{unit_after(pu.get(k))}"
                                       for k, v in params.items()),
              markup=False, highlight=False, soft_wrap=True)
    from rich.table import Table
    from rich.text import Text

    table = Table()
    for name in cols:
        # a Text header: ``[a0/t0]`` is a unit, not Rich markup
        table.add_column(Text(header(name, units.get(name))), justify="right", no_wrap=True)
    for row in zip(*cols.values(), strict=True):
        table.add_row(*(f"{float(v):.10g}" for v in row))
    print_whole(table)
    for note in notes:
        out.print(f"note: {note}", markup=False, highlight=False, soft_wrap=True)
