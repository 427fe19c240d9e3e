"""``dryfriction bifurcation``: the nature of the onset of stick-slip by normal form
(:mod:`dryfriction.analysis.hopf_table`); a thin wrapper: parse, call, write, print."""

from __future__ import annotations

import json

import typer
from rich.table import Table
from rich.text import Text

from .common import FORCE_HELP, app, cli_errors, print_whole, say


@app.command()
@cli_errors
def bifurcation(
    protocol: str = typer.Argument(..., help="A rate-and-state protocol (model.law = 'rsf'): "
                                             "its friction law, damping and mass are used."),
    velocities: str = typer.Option(..., "--velocities", metavar="V1,V2,...",
                                   help="Load velocities, m/s, comma-separated."),
    out_dir: str = typer.Option(..., "--out", metavar="DIR",
                                help="Folder for bifurcation.csv, bifurcation.json and "
                                     "bifurcation.png."),
    check: bool = typer.Option(False, "--check", help="Check each nature by direct "
                               "simulation (settled cycles, or the unstable cycle by "
                               "bisection; at most 12 velocities, ~5-30 s each)."),
    json_out: bool = typer.Option(False, "--json", help="Print the result as JSON."),
    figure: bool = typer.Option(True, "--figure/--no-figure", help="Draw bifurcation.png."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
) -> None:
    """Critical stiffness, frequency and first Lyapunov coefficient l1 of steady sliding at
    each velocity: the Hopf bifurcation's nature (supercritical l1 < 0, subcritical l1 > 0,
    degenerate l1 = 0)."""
    from ..analysis.hopf_table import MAX_CHECKED, bifurcation_table, parse_velocities
    from ..io.files import check_output_dir, output_directory, write_csv, write_json
    from ..io.protocol import RSFProtocol, load_protocol

    vs = parse_velocities(velocities)
    if check and len(vs) > MAX_CHECKED:
        raise ValueError(f"--velocities: {len(vs)} values with --check: allowed at most "
                         f"{MAX_CHECKED}")
    proto = load_protocol(protocol)
    if not isinstance(proto, RSFProtocol):
        raise ValueError(f"{protocol}: model.law = 'cv' is not allowed here: the normal form "
                         "is computed for rate-and-state (law = 'rsf'); the trap model's is "
                         "not done (docs/hopf.md)")
    check_output_dir(out_dir, force=force)
    report = bifurcation_table(proto, vs, check)
    report["protocol"] = protocol
    rows = report["rows"]
    with output_directory(out_dir, command="bifurcation", force=force, inputs=[protocol],
                          report=say) as tmp:
        write_csv(tmp / "bifurcation.csv", {k: [r[k] for r in rows] for k in rows[0]})
        write_json(tmp / "bifurcation.json", report)
        if figure:
            from ..plots.hopf import plot_bifurcation
            from ..plots.style import save_figure

            fig, _ = plot_bifurcation(report, f"{report['law']} law, {protocol}")
            save_figure(fig, tmp / "bifurcation.png", "png")
    if json_out:
        from ..io.files import to_jsonable

        print(json.dumps(to_jsonable(report), indent=2))
        return
    table = Table(title=Text(f"Hopf point of steady sliding, {report['law']} law"))
    for col in rows[0]:
        unit = report["units"][col]
        table.add_column(Text(f"{col} [{unit.split(' ')[0]}]" if unit else col))
    for r in rows:
        table.add_row(*(Text(f"{v:.5g}" if isinstance(v, float) else str(v))
                        for v in r.values()))
    print_whole(table)
