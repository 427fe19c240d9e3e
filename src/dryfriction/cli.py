"""The ``dryfriction`` command line: thin wrappers that parse, call one library function, print.

Bad input (any ``ValueError`` from the library's checks, a bad path) becomes one line on
standard error and exit code 2.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Callable
from typing import Any, TypeVar

import typer
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


def main() -> None:
    """Console-script entry point."""
    app()


if __name__ == "__main__":
    main()
