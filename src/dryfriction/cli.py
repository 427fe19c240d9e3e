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
def rsf(
    case: str = typer.Option("step", help="step (v1 for t1, then v2 for t2), shs (slide-hold-"
                             "slide: v1 for t1, hold for --hold, v1 for t2) or stick-slip "
                             "(v1 for t1)."),
    a: float = typer.Option(0.005, help="Direct effect a, > 0."),
    b: float = typer.Option(0.01, help="Evolution effect b, >= 0."),
    dc: float = typer.Option(1e-5, help="Characteristic slip Dc, m, > 0."),
    mu0: float = typer.Option(0.6, help="Reference friction at V0."),
    v0: float = typer.Option(1e-6, help="Reference velocity V0, m/s, > 0."),
    state_law: str = typer.Option("ageing", help="ageing (Dieterich) or slip (Ruina)."),
    regularized: bool = typer.Option(False, help="Regularised asinh law (needed for holds "
                                     "with --stiffness inf)."),
    stiffness: float = typer.Option(1e3, help="Spring stiffness k per unit normal force, 1/m, "
                                    "> 0; inf for a kinematic machine."),
    damping: float = typer.Option(0.0, help="Radiation damping eta/sigma, s/m, >= 0."),
    mass: float = typer.Option(0.0, help="Mass per unit normal force, s^2/m, >= 0."),
    v1: float = typer.Option(1e-6, help="Load velocity of the first segment, m/s."),
    v2: float = typer.Option(1e-5, help="Load velocity after the step (case step), m/s."),
    t1: float = typer.Option(10.0, help="Duration of the first segment, s."),
    t2: float = typer.Option(30.0, help="Duration of the last segment, s."),
    hold: float = typer.Option(100.0, help="Hold time (case shs), s."),
    v_init: float = typer.Option(None, help="Initial slip velocity, m/s, with the state at "
                                 "steady state for v_init (default v1; 1.01 v1 for "
                                 "stick-slip, since exact steady state never leaves)."),
    rtol: float = typer.Option(1e-7, help="Local error tolerance (relative in V and theta)."),
    out_dir: str = typer.Option(None, "--out", help="Write series.csv, summary.json and "
                                "rsf.png into this folder (whole or not at all)."),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Rate-and-state friction (SI units) through a velocity step, slide-hold-slide or
    stick-slip, on a spring with optional radiation damping and inertia."""
    import math
    import time

    from .io import check_output_dir, output_directory, write_csv, write_json
    from .program import Segment
    from .rsf import RateState
    from .rsf_driving import SolverError, simulate_rsf
    from .validation import check_choice

    check_choice("case", case, ("step", "shs", "stick-slip"))
    params = RateState(a, b, dc, mu0, v0, state_law=state_law,  # type: ignore[arg-type]
                       regularized=regularized)
    if case == "step":
        segs = [Segment(v1, t1), Segment(v2, t2)]
    elif case == "shs":
        segs = [Segment(v1, t1), Segment(0.0, hold), Segment(v1, t2)]
    else:
        segs = [Segment(v1, t1)]
        if v_init is None:
            v_init = 1.01 * v1
    if out_dir is not None:
        check_output_dir(out_dir)
    start = time.perf_counter()
    try:
        theta_init = None if v_init is None else params.dc / v_init
        res = simulate_rsf(params, segs, stiffness=stiffness, damping=damping, mass=mass,
                           v_init=v_init, theta_init=theta_init, rtol=rtol)
    except SolverError as exc:
        raise ValueError(str(exc)) from None
    wall = time.perf_counter() - start
    summary: dict[str, Any] = {
        "case": case,
        "points": len(res.t),
        "steps": res.n_steps,
        "wall_s": wall,
        "mu_initial": float(res.mu[0]),
        "mu_max": float(res.mu.max()),
        "mu_min": float(res.mu.min()),
        "mu_final": float(res.mu[-1]),
        "v_max_m_per_s": float(res.v.max()),
    }
    if params.n_state == 1 and not params.regularized and not math.isinf(stiffness):
        summary["k_c_per_m"] = params.critical_stiffness(max(v1, 1e-300), damping, mass)
    if out_dir is not None:
        with output_directory(out_dir) as tmp:
            write_csv(tmp / "series.csv", res.columns())
            write_json(tmp / "summary.json", {**summary, "params": params.to_dict(),
                                              "stiffness": stiffness, "damping": damping,
                                              "mass": mass, "rtol": rtol})
            _rsf_figure(res, tmp / "rsf.png", f"{case}, {state_law} law")
    emit(summary, json_out, f"rate-and-state, {case}")


def _rsf_figure(res: Any, path: Any, title: str) -> None:
    """Friction and slip velocity against time (Agg backend, no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(7, 5.5), layout="constrained")
    ax1.plot(res.t, res.mu, lw=1.2, label="friction mu")
    ax1.plot(res.t, res.stress, lw=0.8, ls="--", label="spring force / normal force")
    ax1.set_ylabel("mu")
    ax1.legend(fontsize=8)
    ax1.set_title(title)
    ax2.semilogy(res.t, res.v, lw=1.2, label="slip velocity")
    ax2.semilogy(res.t, res.load_velocity, lw=0.8, ls="--", label="load velocity")
    ax2.set_xlabel("t (s)")
    ax2.set_ylabel("V (m/s)")
    ax2.legend(fontsize=8)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main() -> None:
    """Console-script entry point."""
    app()


if __name__ == "__main__":
    main()
