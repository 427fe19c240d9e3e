"""Commands over the closed-form theory: trap, static, steady, stability."""

from __future__ import annotations

from typing import Annotated, Any

import numpy as np
import typer
import typer.core

from .common import app, cli_errors, columns, emit, many


@app.command()
@cli_errors
def trap(
    alpha: float = typer.Option(0.13, help="Reduced trap stiffness kappa a^2/(6 Phi0), > 0 "
                                "(>= 1: no pinning, no friction)."),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """All single-trap constants and the pinning regime (`dryfriction model`, §1)."""
    import math

    from ..theory.trap import Trap

    summary = Trap(alpha).summary()
    if not json_out and alpha >= 1.0:
        # no pinning (module theory.trap): no spinodal, no jump, no friction; a NaN or inf in
        # the table would read as a failed computation (JSON keeps null)
        summary = {k: ("none (no pinning: alpha >= 1)"
                       if isinstance(v, float) and not math.isfinite(v) else v)
                   for k, v in summary.items()}
    emit(summary, json_out, f"trap, alpha = {alpha:g}")


CREEP_HELP = "Creep law: log (eq. 17) or eyring-nabarro (exact, eqs. 15-16)."
DIRECT_HELP = ("Direct effect A = kT/(sigma_s0 v*), 0 <= A <= 1: junction strength "
               "1 + A ln(V/V_ref) (Eyring, asinh-regularised); 0: the athermal model.")
V_REF_HELP = "Reference velocity V_ref of the direct effect, reduced a0/t0, > 0."


def _direct_params(direct: float, v_ref: float) -> dict[str, float]:
    # printed only with the direct effect, so the athermal output is unchanged
    return {"direct": direct, "v_ref": v_ref} if direct else {}


_SI_HELP = {
    "t0": "Creep time t0 [s], > 0: with it, times are in seconds (theory.units.PhysicalScales).",
    "a0": "Contact radius a0 [m], > 0: with it and --t0, velocities are in m/s.",
    "mu_el": "Elastic friction level F_el/W, 0 < mu_el <= 10: with it, friction is the "
             "coefficient F/W (default: friction in F_el).",
}


def _scales(si_values: str, a0: float | None, t0: float | None, mu_el: float | None,
            need_a0: bool) -> Any:
    """The SI scales of ``--t0``/``--a0``/``--mu-el`` (None when none is given), each checked
    against the reduced or SI values that were given (``si_values``: the SI option, or "")."""
    from ..theory.units import PhysicalScales

    given = [f"--{n}" for n, v in (("a0", a0), ("t0", t0)) if v is not None]
    if not si_values:
        if given:
            raise ValueError(f"{' and '.join(given)} convert(s) SI inputs: give the values in "
                             "SI units (see --help) or drop it")
        return None
    missing = [f"--{n}" for n, v in (("t0", t0), ("a0", a0 if need_a0 else 0.0)) if v is None]
    if missing:
        raise ValueError(f"{si_values} is in SI units: give {' and '.join(missing)} "
                         "(the model's scales) too")
    if a0 is not None and not need_a0:
        raise ValueError("--a0 is not used here (times only need --t0): drop it")
    return PhysicalScales(a0=1.0 if a0 is None else a0, t0=float(t0),  # type: ignore[arg-type]
                          mu_el=1.0 if mu_el is None else mu_el)


def _one_of(reduced: list[float] | None, si: list[float] | None, names: str) -> None:
    """Exactly one of the reduced and the SI values (``names``: "--T or --t-w")."""
    if (reduced is None) == (si is None):
        raise ValueError(f"give one of {names}: " + ("both were given" if reduced is not None
                                                      else "neither was given"))


def _friction_unit(mu_el: float | None) -> str:
    return "F_el" if mu_el is None else "F/W"


@app.command(cls=many("--T", "--t-w"))
@cli_errors
def static(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, >= 0.")],
    T: Annotated[list[float] | None, typer.Option(
        "--T", help="Waiting times T = t_w/t0 [t0], >= 0: --T 1 10 100 (or --T 1 --T 10)."
    )] = None,
    t_w: Annotated[list[float] | None, typer.Option(
        "--t-w", help="Waiting times t_w [s], >= 0, instead of --T; needs --t0."
    )] = None,
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness, 0 < alpha < 1."),
    load: float = typer.Option(
        0.0, "--load", help="Tangential force during the wait [F_el], -1 < f_w < 1."
    ),
    hold: str = typer.Option(
        "position", "--hold", help="Loaded wait: 'position' (slider held) or 'force' (force "
        "held, the slider creeps)."
    ),
    creep: str = typer.Option("log", "--creep", help=CREEP_HELP),
    t0: float = typer.Option(None, "--t0", help=_SI_HELP["t0"]),
    mu_el: float = typer.Option(None, "--mu-el", help=_SI_HELP["mu_el"]),
    direct: float = typer.Option(0.0, "--direct", help=DIRECT_HELP),
    v_ref: float = typer.Option(1.0, "--v-ref", help=V_REF_HELP),
    pull_velocity: float = typer.Option(None, "--pull-velocity", help="Slip rate of the pull, "
                                        "a0/t0, > 0; required with --direct > 0."),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Static friction mu_s = F_s/F_el after waiting T = t_w/t0 (eq. 27, our reading); with
    --t-w and --t0 (and --mu-el) in SI units: t_w in seconds, mu_s = F_s/W."""
    from ..theory.static import static_friction
    from ..theory.units import static_friction_si

    _one_of(T, t_w, "--T or --t-w")
    scales = _scales("--t-w" if t_w is not None else "", None, t0, mu_el, need_a0=False)
    params: dict[str, Any] = {"eps": eps, "alpha": alpha, "load": load, "hold": hold,
                              "creep": creep, **_direct_params(direct, v_ref)}
    if direct:
        params["pull_velocity"] = pull_velocity
    if scales is None:
        if mu_el is not None:
            raise ValueError("--mu-el converts the friction of SI inputs: give --t-w and --t0, "
                             "or drop it")
        mu = static_friction(np.asarray(T, float), eps, alpha, creep, load, direct, v_ref,
                             pull_velocity, hold)
        cols: dict[str, Any] = {"T": list(T or []), "mu_s": mu}
    elif direct:
        raise ValueError("--direct takes reduced inputs (--T, --v-ref and --pull-velocity in "
                         "a0/t0); in SI use dryfriction.theory.units.static_friction_si")
    else:
        mu = static_friction_si(np.asarray(t_w, float), eps, scales, alpha, creep, load)
        params.update(t0=scales.t0, **({} if mu_el is None else {"mu_el": mu_el}))
        cols = {"t_w": list(t_w or []), "mu_s": mu}
    if json_out:
        emit({**params, **cols}, True, "static")
    else:
        units = {"T": "t0", "t_w": "s", "mu_s": _friction_unit(mu_el)}
        columns("static friction", params, cols, units)


def _velocities_in_range(V: np.ndarray, a0: float, t0: float) -> None:
    """``--V`` within the reduced range ``U_MIN <= V t0/a0 <= U_MAX``, refused naming --V
    (and --a0/--t0 when they leave no range): the core's message names ``u``, which the user
    of --V never typed."""
    from ..validation import U_MAX, U_MIN

    vstar = a0 / t0
    if not (np.isfinite(vstar) and vstar > 0.0):
        raise ValueError(f"--a0 {a0:g} m and --t0 {t0:g} s give V* = a0/t0 = {vstar:g} m/s: "
                         "allowed a finite positive ratio")
    u = V / vstar
    bad = ~((u >= U_MIN) & (u <= U_MAX))
    if bad.any():
        v = float(V[np.argmax(bad)])
        raise ValueError(f"--V {v:g} m/s is out of range: with --a0 {a0:g} m and --t0 {t0:g} s "
                         f"allowed {U_MIN * vstar:g} to {U_MAX * vstar:g} m/s "
                         f"(u = V t0/a0 from {U_MIN:g} to {U_MAX:g})")


@app.command(cls=many("--u", "--V"))
@cli_errors
def steady(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, >= 0.")],
    u: Annotated[list[float] | None, typer.Option(
        "--u", help="Reduced velocities u = V t0/a0 [a0/t0], > 0: --u 0.1 1 10 (or --u 0.1 "
        "--u 1)."
    )] = None,
    V: Annotated[list[float] | None, typer.Option(
        "--V", help="Sliding velocities V [m/s], > 0, instead of --u; needs --a0 and --t0."
    )] = None,
    alpha: float = typer.Option(0.13, "--alpha", help="Trap stiffness, 0 < alpha < 1."),
    creep: str = typer.Option("log", "--creep", help=CREEP_HELP),
    a0: float = typer.Option(None, "--a0", help=_SI_HELP["a0"]),
    t0: float = typer.Option(None, "--t0", help=_SI_HELP["t0"]),
    mu_el: float = typer.Option(None, "--mu-el", help=_SI_HELP["mu_el"]),
    direct: float = typer.Option(0.0, "--direct", help=DIRECT_HELP),
    v_ref: float = typer.Option(1.0, "--v-ref", help=V_REF_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Steady dynamic friction mu_d = F_d/F_el at reduced velocity u = V/V* (eq. 34); with
    --V, --a0 and --t0 (and --mu-el) in SI units: V in m/s, mu_d = F_d/W."""
    from ..theory.steady import steady_friction
    from ..theory.units import steady_friction_si

    _one_of(u, V, "--u or --V")
    scales = _scales("--V" if V is not None else "", a0, t0, mu_el, need_a0=True)
    params: dict[str, Any] = {"eps": eps, "alpha": alpha, "creep": creep,
                              **_direct_params(direct, v_ref)}
    if scales is None:
        if mu_el is not None:
            raise ValueError("--mu-el converts the friction of SI inputs: give --V, --a0 and "
                             "--t0, or drop it")
        mu = steady_friction(np.asarray(u, float), eps, alpha, creep, direct, v_ref)
        cols: dict[str, Any] = {"u": list(u or []), "mu_d": mu}
    elif direct:
        raise ValueError("--direct takes reduced inputs (--u and --v-ref in a0/t0); in SI use "
                         "dryfriction.theory.units.steady_friction_si")
    else:
        _velocities_in_range(np.asarray(V, float), scales.a0, scales.t0)
        mu = steady_friction_si(np.asarray(V, float), eps, scales, alpha, creep)
        params.update(a0=scales.a0, t0=scales.t0, **({} if mu_el is None else {"mu_el": mu_el}))
        cols = {"V": list(V or []), "mu_d": mu}
    if json_out:
        emit({**params, **cols}, True, "steady")
    else:
        units = {"u": "a0/t0", "V": "m/s", "mu_d": _friction_unit(mu_el)}
        columns("steady friction", params, cols, units)


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
    mass: float = typer.Option(0.0, "--mass", help="Slider mass M [F_el t0^2/a0], >= 0; "
                               "needs --damping > 0 (ill posed without)."),
    damping: float = typer.Option(0.0, "--damping", help="Viscous damping eta [F_el t0/a0], "
                                  ">= 0."),
    creep: str = typer.Option("log", "--creep", help=CREEP_HELP),
    direct: float = typer.Option(0.0, "--direct", help=DIRECT_HELP),
    v_ref: float = typer.Option(1.0, "--v-ref", help=V_REF_HELP),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Critical stiffness K_c (F_el/a0) and onset frequency (1/t0) of steady sliding."""
    from ..analysis.rsf_stability import rsf_stability_prediction
    from ..theory.linear_stability import critical_stiffness
    from ..theory.model import TrapModel
    from ..theory.steady import check_steady_inputs
    from ..validation import check_scalar

    check_steady_inputs(np.asarray(u, float), eps, alpha, creep)
    check_scalar("mass", mass, 0.0, LOAD_MAX)
    check_scalar("damping", damping, 0.0, LOAD_MAX)
    model = TrapModel(alpha, eps, creep, direct=direct, v_ref=v_ref)
    if mass > 0 and damping == 0 and not direct:  # the direct effect damps like eta (A mu/u)
        raise ValueError(
            f"--mass {mass:g} without --damping is ill posed: with inertia and no damping the "
            "delay at the spinodal edge makes K_c grow with the highest frequency considered, "
            "so no K_c exists; give --damping > 0 (e.g. --damping 0.1) or --direct > 0, or "
            "drop --mass")
    res = [critical_stiffness(v, model, mass, damping) for v in u]
    twins = [rsf_stability_prediction(v, model, mass, damping) for v in u] if eps > 0 else []
    params = {"eps": eps, "alpha": alpha, "mass": mass, "damping": damping, "creep": creep,
              **_direct_params(direct, v_ref)}
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
        units = {"u": "a0/t0", "K_c": "F_el/a0", "omega_c": "1/t0",
                 "forward_stiffness": "F_el/a0", "backward_stiffness": "F_el/a0",
                 "dmu_d_du": "F_el t0/a0", "K_c_rsf": "F_el/a0"}
        columns("linear stability of steady sliding", params, cols, units)
