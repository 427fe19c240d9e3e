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


@app.command()
@cli_errors
def simulate(
    protocol: str = typer.Argument(..., help="Protocol file (TOML), see dryfriction.protocol."),
    out: str = typer.Option(..., "--out", help="Results folder (written whole or not at all)."),
    json_out: bool = typer.Option(False, "--json", help="Print the summary as JSON."),
) -> None:
    """Run the trap ensemble under a protocol (spec §6): timeseries.csv, summary.json, .png.

    Ctrl-C stops the run and writes the samples so far as a complete result marked
    ``"partial": true`` in summary.json (exit code 130); an interrupt while writing leaves
    nothing.
    """
    import time
    from pathlib import Path

    from .io import check_output_dir, output_directory, write_csv, write_json
    from .protocol import load_protocol

    proto = load_protocol(protocol)  # every check before any work
    check_output_dir(out)

    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    started = time.monotonic()
    bar: dict[str, Any] = {}

    def progress(fraction: float) -> None:
        if not err.is_terminal or time.monotonic() - started < 1.0:
            return
        if not bar:
            p = Progress(TextColumn("simulate"), BarColumn(), TimeElapsedColumn(),
                         console=err, transient=True)
            p.start()
            bar["p"], bar["task"] = p, p.add_task("simulate", total=1.0)
        bar["p"].update(bar["task"], completed=fraction)

    try:
        result = proto.run(progress=progress, on_interrupt="partial")
    finally:
        if bar:
            bar["p"].stop()
    summary = result.summary()
    summary["protocol"] = str(Path(protocol))

    import matplotlib

    matplotlib.use("Agg")
    from .plotting import timeseries_figure

    with output_directory(out) as tmp:
        write_csv(tmp / "timeseries.csv", result.to_dict())
        write_json(tmp / "summary.json", summary)
        fig, _ = timeseries_figure(result)
        fig.savefig(tmp / "timeseries.png", dpi=120)
        for i, snap in enumerate(result.snapshots):
            cols = {k: v for k, v in snap.items() if k not in ("t", "x")}
            write_csv(tmp / f"snapshot_{i:03d}_t{snap['t']:.6g}.csv", cols)
    brief = {k: v for k, v in summary.items() if not isinstance(v, dict)}
    emit(brief if not json_out else summary, json_out, f"simulate {protocol} -> {out}")
    if result.partial:
        err.print("[bold yellow]interrupted:[/] partial result written", highlight=False)
        raise typer.Exit(130)


def main() -> None:
    """Console-script entry point."""
    app()


if __name__ == "__main__":
    main()
