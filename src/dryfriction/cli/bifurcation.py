"""``dryfriction bifurcation``: the nature of the onset of stick-slip by normal form
(:func:`dryfriction.app.hopf.bifurcation`); a thin wrapper: parse, call, print."""

from __future__ import annotations

import json

import typer
from rich.table import Table
from rich.text import Text

from ..app.options import OPTIONS
from .common import FORCE_HELP, app, cli_errors, lazy_progress_bar, print_whole, say

_O = OPTIONS["bifurcation"]


@app.command()
@cli_errors
def bifurcation(
    protocol: str = typer.Argument(..., help="A rate-and-state protocol (model.law = 'rsf'): "
                                             "its friction law, damping and mass are used; or "
                                             "a trap-model one (law = 'cv', 0 < direct, "
                                             "alpha < 0.1716): its model, a spring drive's "
                                             "mass and damping."),
    velocities: str = typer.Option(..., "--velocities", metavar="V1,V2,...",
                                   help="Load velocities, comma-separated: m/s for "
                                        "rate-and-state, reduced u = V t0/a0 [a0/t0] for a "
                                        "trap-model protocol."),
    out_dir: str = typer.Option(..., "--out", metavar="DIR",
                                help="Folder for bifurcation.csv, bifurcation.json and "
                                     "bifurcation.png."),
    check: bool = typer.Option(_O["check"].default, "--check", help="Check each nature by direct "
                               "simulation (settled cycles, or the unstable cycle by "
                               "bisection; at most 12 velocities; rate-and-state "
                               "~5-30 s each; the trap model by its ensemble on the "
                               "protocol's track, minutes each, refused above 30 "
                               "estimated CPU-minutes)."),
    json_out: bool = typer.Option(False, "--json", help="Print the result as JSON."),
    figure: bool = typer.Option(_O["figure"].default, "--figure/--no-figure",
                                help="Draw bifurcation.png."),
    force: bool = typer.Option(_O["force"].default, "--force", help=FORCE_HELP),
) -> None:
    """Critical stiffness, frequency and first Lyapunov coefficient l1 of steady sliding at
    each velocity: the Hopf bifurcation's nature (supercritical l1 < 0, subcritical l1 > 0,
    degenerate l1 = 0)."""
    from ..app.hopf import bifurcation as run

    with lazy_progress_bar("bifurcation", unit="velocities") as update:
        report = run(protocol, velocities, out_dir, check=check, figure=figure, force=force,
                     report=say, progress=lambda done, total: update(done, total)).report
    rows = report["rows"]
    if json_out:
        from ..io.files import to_jsonable

        print(json.dumps(to_jsonable(report), indent=2))
        return
    what = "trap model" if report["law"] == "trap" else f"{report['law']} law"
    table = Table(title=Text(f"Hopf point of steady sliding, {what}"))
    from ..io.units import header

    for col in rows[0]:
        table.add_column(Text(header(col, report["units"][col])))
    for r in rows:
        table.add_row(*(Text(f"{v:.5g}" if isinstance(v, float) else str(v))
                        for v in r.values()))
    print_whole(table)
