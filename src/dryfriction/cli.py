"""The ``dryfriction`` command line: thin wrappers that parse, call one library function, print.

Bad input (any ``ValueError`` from the library's checks, a bad path) becomes one line on
standard error and exit code 2.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, TypeVar

import numpy as np
import typer
import typer.core
from rich.console import Console
from rich.table import Table

from .io import to_jsonable

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="The Caroli-Velicky elasto-plastic model of dry friction (reduced units: a0, t0, F_el).",
)
err = Console(stderr=True)
out = Console()

F = TypeVar("F", bound=Callable[..., Any])


@app.callback()
def _root() -> None:
    """The Caroli-Velicky elasto-plastic model of dry friction (reduced units: a0, t0, F_el)."""


def cli_errors(fn: F) -> F:
    """Turn the library's ``ValueError``/``OSError`` into one line and exit code 2."""

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return fn(*args, **kwargs)
        except (ValueError, OSError) as exc:
            err.print(f"[bold red]error:[/] {exc}", highlight=False, soft_wrap=True)
            raise typer.Exit(2) from None

    return wrapper  # type: ignore[return-value]


def emit(result: dict[str, Any], as_json: bool, title: str) -> None:
    """Print ``result`` as JSON (``--json``) or as a table."""
    if as_json:
        print(json.dumps(to_jsonable(result), indent=2))
        return
    table = Table(title=title, show_header=False)
    for k, v in result.items():
        table.add_row(k, f"{v:.10g}" if isinstance(v, float) else str(v))
    out.print(table)


@app.command()
@cli_errors
def trap(
    alpha: float = typer.Option(0.13, help="Reduced trap stiffness kappa a^2/(6 Phi0), > 0."),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """All single-trap constants and the pinning regime (spec §1)."""
    from .trap import Trap

    emit(Trap(alpha).summary(), json_out, f"trap, alpha = {alpha:g}")


# --------------------------------------------------------------------------------------------
# static, steady, reproduce
# --------------------------------------------------------------------------------------------


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
            err.print(f"[bold red]error:[/] {message}", highlight=False, soft_wrap=True)
            raise typer.Exit(2) from None


def _is_number(tok: str) -> bool:
    try:
        float(tok)
    except ValueError:
        return False
    return True


def _many(*flags: str) -> type[_ManyValues]:
    return type("ManyValues", (_ManyValues,), {"many": flags})


def _columns(title: str, params: dict[str, Any], cols: dict[str, Any]) -> None:
    out.print(f"{title}: " + ", ".join(f"{k} = {v}" for k, v in params.items()), highlight=False)
    table = Table()
    for name in cols:
        table.add_column(name, justify="right")
    for row in zip(*cols.values(), strict=True):
        table.add_row(*(f"{float(v):.10g}" for v in row))
    out.print(table)


_CREEP_HELP = "Creep law: log (eq. 17) or eyring-nabarro (exact, eqs. 15-16)."


@app.command(cls=_many("--T"))
@cli_errors
def static(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, >= 0.")],
    T: Annotated[list[float], typer.Option(
        "--T", help="Waiting times t_w/t0, >= 0: --T 1 10 100 (or --T 1 --T 10)."
    )],
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness, 0 < alpha < 1."),
    load: float = typer.Option(
        0.0, "--load", help="Tangential force during the wait, units F_el, 0 <= f_w < 1."
    ),
    creep: str = typer.Option("log", "--creep", help=_CREEP_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Static friction mu_s = F_s/F_el after waiting T = t_w/t0 (eq. 27, our reading)."""
    from .static import static_friction

    mu = static_friction(np.asarray(T, float), eps, alpha, creep, load)
    params = {"eps": eps, "alpha": alpha, "load": load, "creep": creep}
    if json_out:
        emit({**params, "T": list(T), "mu_s": mu}, True, "static")
    else:
        _columns("static friction", params, {"T": T, "mu_s": mu})


@app.command(cls=_many("--u"))
@cli_errors
def steady(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, >= 0.")],
    u: Annotated[list[float], typer.Option(
        "--u", help="Reduced velocities V t0/a0, > 0: --u 0.1 1 10 (or --u 0.1 --u 1)."
    )],
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness, 0 < alpha < 1."),
    creep: str = typer.Option("log", "--creep", help=_CREEP_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Steady dynamic friction mu_d = F_d/F_el at reduced velocity u = V/V* (eq. 34)."""
    from .steady import steady_friction

    mu = steady_friction(np.asarray(u, float), eps, alpha, creep)
    params = {"eps": eps, "alpha": alpha, "creep": creep}
    if json_out:
        emit({**params, "u": list(u), "mu_d": mu}, True, "steady")
    else:
        _columns("steady friction", params, {"u": u, "mu_d": mu})


@app.command(cls=_many())
@cli_errors
def reproduce(
    out_dir: Annotated[Path, typer.Option("--out", help="Results folder (created or replaced).")],
) -> None:
    """The paper's six figures, the data behind them, summary.json and report.html."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    from .figures import reproduce as run
    from .io import check_output_dir

    check_output_dir(out_dir)  # fail on a bad --out before importing matplotlib
    with Progress(
        TextColumn("{task.description}"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
        TimeElapsedColumn(), console=err, disable=not err.is_terminal, transient=True,
    ) as bar:
        task = bar.add_task("reproduce", total=None)

        def progress(done: int, total: int, what: str) -> None:
            bar.update(task, completed=done, total=total, description=what)

        summary = run(out_dir, progress)
    out.print(
        f"wrote {out_dir}/: fig1-6.png, static_friction.csv, steady_friction.csv, "
        f"summary.json, report.html (C_inf = {summary['dieterich_C_asymptotic']:.4f}, "
        f"C_LS = {summary['dieterich_C_least_squares']:.4f})",
        highlight=False, soft_wrap=True,
    )


def main() -> None:
    """Console-script entry point."""
    app()


if __name__ == "__main__":
    main()
