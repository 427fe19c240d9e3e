"""Commands over the closed-form theory: trap, static, steady, stability."""

from __future__ import annotations

from typing import Annotated

import numpy as np
import typer
import typer.core

from .common import app, cli_errors, columns, emit, many


@app.command()
@cli_errors
def trap(
    alpha: float = typer.Option(0.13, help="Reduced trap stiffness kappa a^2/(6 Phi0), > 0."),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """All single-trap constants and the pinning regime (docs/model.md §1)."""
    from ..theory.trap import Trap

    emit(Trap(alpha).summary(), json_out, f"trap, alpha = {alpha:g}")


CREEP_HELP = "Creep law: log (eq. 17) or eyring-nabarro (exact, eqs. 15-16)."


@app.command(cls=many("--T"))
@cli_errors
def static(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, >= 0.")],
    T: Annotated[list[float], typer.Option(
        "--T", help="Waiting times t_w/t0, >= 0: --T 1 10 100 (or --T 1 --T 10)."
    )],
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness, 0 < alpha < 1."),
    load: float = typer.Option(
        0.0, "--load", help="Tangential force during the wait, units F_el, -1 < f_w < 1."
    ),
    hold: str = typer.Option(
        "position", "--hold", help="Loaded wait: 'position' (slider held) or 'force' (force "
        "held, the slider creeps)."
    ),
    creep: str = typer.Option("log", "--creep", help=CREEP_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Static friction mu_s = F_s/F_el after waiting T = t_w/t0 (eq. 27, our reading)."""
    from ..theory.static import static_friction

    mu = static_friction(np.asarray(T, float), eps, alpha, creep, load, hold)
    params = {"eps": eps, "alpha": alpha, "load": load, "hold": hold, "creep": creep}
    if json_out:
        emit({**params, "T": list(T), "mu_s": mu}, True, "static")
    else:
        columns("static friction", params, {"T": T, "mu_s": mu})


@app.command(cls=many("--u"))
@cli_errors
def steady(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, >= 0.")],
    u: Annotated[list[float], typer.Option(
        "--u", help="Reduced velocities V t0/a0, > 0: --u 0.1 1 10 (or --u 0.1 --u 1)."
    )],
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness, 0 < alpha < 1."),
    creep: str = typer.Option("log", "--creep", help=CREEP_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Steady dynamic friction mu_d = F_d/F_el at reduced velocity u = V/V* (eq. 34)."""
    from ..theory.steady import steady_friction

    mu = steady_friction(np.asarray(u, float), eps, alpha, creep)
    params = {"eps": eps, "alpha": alpha, "creep": creep}
    if json_out:
        emit({**params, "u": list(u), "mu_d": mu}, True, "steady")
    else:
        columns("steady friction", params, {"u": u, "mu_d": mu})


LOAD_MAX = 1e12
"""Largest mass, damping (reduced units) or duration (s) the commands accept: far beyond any
experiment, and small enough that products with the other inputs stay finite."""


@app.command(cls=many("--u"))
@cli_errors
def stability(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, >= 0.")],
    u: Annotated[list[float], typer.Option(
        "--u", help="Reduced velocities V t0/a0, > 0: --u 0.1 1 10 (or --u 0.1 --u 1)."
    )],
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness, 0 < alpha < 1."),
    mass: float = typer.Option(0.0, "--mass", help="Slider mass M, F_el t0^2/a0, >= 0."),
    damping: float = typer.Option(0.0, "--damping", help="Viscous damping eta, F_el t0/a0."),
    creep: str = typer.Option("log", "--creep", help=CREEP_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Critical stiffness K_c (F_el/a0) and onset frequency (1/t0) of steady sliding."""
    from ..analysis.rsf_stability import rsf_stability_prediction
    from ..theory.stability import critical_stiffness
    from ..theory.steady import check_steady_inputs
    from ..validation import check_scalar

    check_steady_inputs(np.asarray(u, float), eps, alpha, creep)
    check_scalar("mass", mass, 0.0, LOAD_MAX)
    check_scalar("damping", damping, 0.0, LOAD_MAX)
    res = [critical_stiffness(v, eps, alpha, creep, mass, damping) for v in u]
    twins = ([rsf_stability_prediction(v, eps, alpha, creep, mass, damping) for v in u]
             if eps > 0 else [])
    params = {"eps": eps, "alpha": alpha, "mass": mass, "damping": damping, "creep": creep}
    cols = {
        "u": list(u),
        "K_c": [r.critical_stiffness for r in res],
        "omega_c": [r.omega for r in res],
        "forward_stiffness": [r.forward_stiffness for r in res],
        "backward_stiffness": [r.backward_stiffness for r in res],
        "dmu_d_du": [r.velocity_slope for r in res],
    }
    if twins:  # rate-and-state with the model's effective a, b, Dc (Rice & Ruina 1983)
        cols["K_c_rsf"] = [t["K_c"] for t in twins]
    if json_out:
        emit({**params, **cols}, True, "stability")
    else:
        columns("linear stability of steady sliding", params, cols)
