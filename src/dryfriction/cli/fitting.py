"""The fit command: measured friction against the trap model or rate-and-state."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

import typer
import typer.core
from rich.table import Table

from ..io.files import to_jsonable
from .common import FORCE_HELP, app, cli_errors, err, out, say
from .model import CREEP_HELP


@app.command("fit")
@cli_errors
def fit_command(
    data: Annotated[list[Path], typer.Argument(help="CSV files: t_w,mu_s (static), V,mu_d "
                                               "(steady) or t,v_load,mu (time series); units "
                                               "in the header, e.g. V[um/s].")],
    out_dir: Annotated[Path, typer.Option("--out", help="Results folder: fit.json, fit.png "
                                          "(written whole or not at all; new, empty, or "
                                          "written by this program before).")],
    model: str = typer.Option("cv", "--model", help="cv (trap model) or rsf (rate-and-state)."),
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness (cv), fixed."),
    creep: str = typer.Option("log", "--creep", help=CREEP_HELP),
    fix: Annotated[list[str] | None, typer.Option(
        "--fix", help="Hold a parameter fixed: --fix t0=0.01 (SI units; repeatable).")] = None,
    v0: float = typer.Option(None, "--v0", help="rsf: reference velocity V0, m/s (for static "
                             "data: the hold tests' sliding velocity; required then)."),
    state_law: str = typer.Option("ageing", "--state-law", help="rsf: ageing or slip."),
    stiffness: float = typer.Option(float("inf"), "--stiffness", help="rsf time series: "
                                    "machine stiffness per unit normal force, 1/m; inf: "
                                    "kinematic."),
    regularized: bool = typer.Option(False, help="rsf: regularised law (holds, kinematic)."),
    traps_per_a0: float = typer.Option(1000.0, "--traps-per-a0", help="cv time series: "
                                       "density of the simulated ensemble (accuracy about its "
                                       "inverse; cost grows with it)."),
    direct: float = typer.Option(0.0, "--direct", help="cv: fit the direct effect A "
                                 "(0 <= A <= 1), started from this value; 0: the athermal "
                                 "model. Hold it with --fix direct=A."),
    v_ref: float = typer.Option(1e-6, "--v-ref", help="cv with --direct: reference velocity "
                                "of the direct effect, m/s, fixed."),
    profile: bool = typer.Option(True, help="Profile-likelihood intervals and identifiability."),
    compare: bool = typer.Option(True, help="Also fit the other model and compare (AIC/BIC)."),
    json_out: bool = typer.Option(False, "--json", help="Print fit.json to standard output."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
) -> None:
    """Fit the trap model (cv) or rate-and-state (rsf) to measured friction; writes fit.json
    (values, uncertainties, correlations, identifiability, goodness of fit, AIC/BIC) and
    fit.png (data, fitted curve, residuals)."""
    from ..fit import compare_models, fit
    from ..io.data import read_csv
    from ..io.files import check_output_dir, output_directory, write_json
    from ..plots.fits import plot_fit
    from ..validation import check_choice

    check_choice("model", model, ("cv", "rsf"))
    check_output_dir(out_dir, force=force)
    fixed: dict[str, float] = {}
    for item in fix or []:
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise ValueError(f"--fix {item!r}: expected name=value, e.g. --fix t0=0.01")
        try:
            fixed[name.strip()] = float(value)
        except ValueError:
            raise ValueError(f"--fix {item!r}: {value!r} is not a number") from None
    datasets = [read_csv(p) for p in data]
    opts: dict[str, Any] = dict(alpha=alpha, creep=creep, v0=v0, state_law=state_law,
                                stiffness=stiffness, regularized=regularized)
    from ..fit import CVModel

    chosen: Any = (CVModel(alpha, creep, traps_per_a0=traps_per_a0, direct=direct, v_ref=v_ref)
                   if model == "cv" else model)
    try:
        result = fit(datasets, chosen, fix=fixed, profile=profile, **opts)
    except NotImplementedError as exc:
        raise ValueError(str(exc)) from None
    report = result.to_dict()
    if compare:
        other = "rsf" if model == "cv" else "cv"
        try:
            alt = fit(datasets, other, profile=False, consistency=False, **opts)
            report["comparison"] = compare_models([result, alt])
        except (ValueError, NotImplementedError) as exc:
            report["comparison"] = {"not_run": f"{other}: {exc}"}
    with output_directory(out_dir, command="fit", force=force, inputs=data,
                          report=say) as tmp:
        write_json(tmp / "fit.json", report)
        plot_fit(result, datasets, tmp / "fit.png")
    if json_out:
        print(json.dumps(to_jsonable(report), indent=2))
    else:
        table = Table(title=f"{model} fit of {', '.join(str(p) for p in data)}")
        for col in ("parameter", "value", "+-", "95 % interval", "identifiability"):
            table.add_column(col)
        for p in result.parameters:
            iv = p.profile_95 or p.interval_95
            ivs = "" if iv is None else ("[" + ", ".join("open" if x is None else f"{x:.4g}"
                                                          for x in iv) + "]")
            table.add_row(f"{p.name} ({p.unit})" if p.unit else p.name, f"{p.value:.6g}",
                          "" if p.stderr is None else f"{p.stderr:.2g}", ivs, p.identifiability)
        out.print(table)
        for note in result.notes:
            out.print(f"- {note}", highlight=False, soft_wrap=True)
        if "comparison" in report and "verdict" in report["comparison"]:
            out.print(f"comparison: {report['comparison']['verdict']}", highlight=False)
        out.print(f"wrote {out_dir}/fit.json, fit.png", highlight=False)
    if not result.success:
        err.print(f"[bold red]fit did not converge:[/] {result.message}", highlight=False,
                  soft_wrap=True)
        raise typer.Exit(1)
