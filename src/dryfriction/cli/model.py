"""Commands over the closed-form theory: trap, static, steady, stability (parse, call one
workflow of :mod:`dryfriction.app.theory`, print)."""

from __future__ import annotations

from typing import Annotated, Any

import typer
import typer.core

from ..app.options import OPTIONS
from .common import app, cli_errors, columns, emit, many, one_of, renamed

_TRAP, _STA, _STE, _STB = (OPTIONS[k] for k in ("trap", "static", "steady", "stability"))


def _print(done: Any, json_out: bool) -> None:
    """A :class:`dryfriction.app.theory.TableOutcome` as JSON or as a table with units."""
    from ..io.units import THEORY_UNITS

    if json_out:
        emit(done.as_dict(), True, done.title)
    else:
        columns(done.title, done.params, done.columns, done.units, THEORY_UNITS, done.notes)


@app.command()
@cli_errors
def trap(
    alpha: float = typer.Option(_TRAP["alpha"].default, help="Reduced trap stiffness "
                                "kappa a^2/(6 Phi0), dimensionless, > 0 (>= 1: no pinning, "
                                "no friction)."),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """All single-trap constants and the pinning regime (see dryfriction model,
    section 1)."""
    from ..app.theory import no_pinning_display
    from ..app.theory import trap as run

    done = run(alpha)
    summary = done.as_dict() if json_out else done.params
    if not json_out and alpha >= 1.0:
        summary = no_pinning_display(summary)
    emit(summary, json_out, done.title, done.as_dict()["units"])


CREEP_HELP = "Creep law: log (eq. 17) or eyring-nabarro (exact, eqs. 15-16)."
CREEP_CHOICES = one_of(_STA["creep"].choices)
DIRECT_HELP = ("Direct effect A = kT/(sigma_s0 v*), dimensionless, 0 <= A <= 1: junction "
               "strength 1 + A ln(V/V_ref) (Eyring, asinh-regularised); 0: the athermal model.")
V_REF_HELP = ("Reference velocity u_ref = V_ref t0/a0 of the direct effect [a0/t0], > 0 "
              "(was --v-ref, the name fit gives its value in m/s).")
_U_REF_WHY = "reduced, a0/t0; --v-ref is m/s in fit"


def _v_ref_alias() -> Any:
    return typer.Option(None, "--v-ref", hidden=True, help="Deprecated: --u-ref.")

_SI_HELP = {
    "t0": "Creep time t0 [s], > 0: with it, times are in seconds (theory.units.PhysicalScales).",
    "a0": "Contact radius a0 [m], > 0: with it and --t0, velocities are in m/s.",
    "mu_el": "Elastic friction level F_el/W, 0 < mu_el <= 10: with it, friction is the "
             "coefficient F/W (default: friction in F_el).",
}


@app.command(cls=many("--T", "--t-w"))
@cli_errors
def static(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, dimensionless, >= 0.")],
    T: Annotated[list[float] | None, typer.Option(
        "--T", help="Waiting times T = t_w/t0 [t0], >= 0: --T 1 10 100 (or --T 1 --T 10)."
    )] = None,
    t_w: Annotated[list[float] | None, typer.Option(
        "--t-w", help="Waiting times t_w [s], >= 0, instead of --T; needs --t0."
    )] = None,
    alpha: float = typer.Option(_STA["alpha"].default, "--alpha",
                                help="Trap stiffness, dimensionless, 0 < alpha < 1."),
    load: float = typer.Option(
        _STA["load"].default, "--load", help="Tangential force during the wait [F_el], "
        "-1 < f_w < 1; with --hold position a reversed load down to the value that puts "
        "the population's edge at -a0 (-0.674 at alpha = 0.13)."
    ),
    hold: str = typer.Option(
        _STA["hold"].default, "--hold", metavar=one_of(_STA["hold"].choices),
        help="Loaded wait: position (slider held) or force (force held, the slider creeps)."
    ),
    creep: str = typer.Option(_STA["creep"].default, "--creep", metavar=CREEP_CHOICES,
                              help=CREEP_HELP),
    t0: float = typer.Option(_STA["t0"].default, "--t0", help=_SI_HELP["t0"]),
    mu_el: float = typer.Option(_STA["mu_el"].default, "--mu-el", help=_SI_HELP["mu_el"]),
    direct: float = typer.Option(_STA["direct"].default, "--direct", help=DIRECT_HELP),
    v_ref: float = typer.Option(_STA["v_ref"].default, "--u-ref", help=V_REF_HELP),
    v_ref_old: float | None = _v_ref_alias(),
    pull_velocity: float = typer.Option(_STA["pull_velocity"].default, "--pull-velocity",
                                        help="Slip rate of the pull, a0/t0, > 0; required "
                                        "with --direct > 0."),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Static friction mu_s = F_s/F_el after waiting T = t_w/t0 (eq. 27, our reading); with
    --t-w and --t0 (and --mu-el) in SI units: t_w in seconds, mu_s = F_s/W."""
    from ..app.theory import static as run

    v_ref = renamed("--v-ref", "--u-ref", _U_REF_WHY, v_ref_old, v_ref, _STA["v_ref"].default)
    _print(run(eps, T, t_w, alpha=alpha, load=load, hold=hold, creep=creep, t0=t0,
               mu_el=mu_el, direct=direct, v_ref=v_ref, pull_velocity=pull_velocity),
           json_out)


@app.command(cls=many("--u", "--V"))
@cli_errors
def steady(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, dimensionless, >= 0.")],
    u: Annotated[list[float] | None, typer.Option(
        "--u", help="Reduced velocities u = V t0/a0 [a0/t0], > 0: --u 0.1 1 10 (or --u 0.1 "
        "--u 1)."
    )] = None,
    V: Annotated[list[float] | None, typer.Option(
        "--V", help="Sliding velocities V [m/s], > 0, instead of --u; needs --a0 and --t0."
    )] = None,
    alpha: float = typer.Option(_STE["alpha"].default, "--alpha",
                                help="Trap stiffness, dimensionless, 0 < alpha < 1."),
    creep: str = typer.Option(_STE["creep"].default, "--creep", metavar=CREEP_CHOICES,
                              help=CREEP_HELP),
    a0: float = typer.Option(_STE["a0"].default, "--a0", help=_SI_HELP["a0"]),
    t0: float = typer.Option(_STE["t0"].default, "--t0", help=_SI_HELP["t0"]),
    mu_el: float = typer.Option(_STE["mu_el"].default, "--mu-el", help=_SI_HELP["mu_el"]),
    direct: float = typer.Option(_STE["direct"].default, "--direct", help=DIRECT_HELP),
    v_ref: float = typer.Option(_STE["v_ref"].default, "--u-ref", help=V_REF_HELP),
    v_ref_old: float | None = _v_ref_alias(),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Steady dynamic friction mu_d = F_d/F_el at reduced velocity u = V/V* (eq. 34); with
    --V, --a0 and --t0 (and --mu-el) in SI units: V in m/s, mu_d = F_d/W."""
    from ..app.theory import steady as run

    v_ref = renamed("--v-ref", "--u-ref", _U_REF_WHY, v_ref_old, v_ref, _STE["v_ref"].default)
    _print(run(eps, u, V, alpha=alpha, creep=creep, a0=a0, t0=t0, mu_el=mu_el,
               direct=direct, v_ref=v_ref), json_out)


@app.command(cls=many("--u"))
@cli_errors
def stability(
    eps: Annotated[float, typer.Option("--eps", help="Creep parameter S/Y, dimensionless, >= 0.")],
    u: Annotated[list[float], typer.Option(
        "--u", help="Reduced velocities V t0/a0, > 0: --u 0.1 1 10 (or --u 0.1 --u 1)."
    )],
    alpha: float = typer.Option(_STB["alpha"].default, "--alpha",
                                help="Trap stiffness, dimensionless, 0 < alpha < 1."),
    mass: float = typer.Option(_STB["mass"].default, "--M", help="Slider mass M "
                               "[F_el t0^2/a0], >= 0; needs --eta > 0 (ill posed "
                               "without). Was --mass, the name rsf gives a mass in s^2/m."),
    damping: float = typer.Option(_STB["damping"].default, "--eta",
                                  help="Viscous damping eta [F_el t0/a0], >= 0. Was "
                                  "--damping, the name rsf gives a damping in s/m."),
    mass_old: float | None = typer.Option(None, "--mass", hidden=True,
                                          help="Deprecated: --M."),
    damping_old: float | None = typer.Option(None, "--damping", hidden=True,
                                             help="Deprecated: --eta."),
    creep: str = typer.Option(_STB["creep"].default, "--creep", metavar=CREEP_CHOICES,
                              help=CREEP_HELP),
    direct: float = typer.Option(_STB["direct"].default, "--direct", help=DIRECT_HELP),
    v_ref: float = typer.Option(_STB["v_ref"].default, "--u-ref", help=V_REF_HELP),
    v_ref_old: float | None = _v_ref_alias(),
    json_out: bool = typer.Option(False, "--json", help="Machine-readable output."),
) -> None:
    """Critical stiffness K_c (F_el/a0) and onset frequency (1/t0) of steady sliding.

    Columns: K_c, the largest spring stiffness at which steady sliding is unstable;
    omega_c, the angular frequency of the oscillation at that onset; forward_stiffness
    and backward_stiffness, the stiffness the steady contact population opposes to a
    sudden small shift of the slider forward and backward (forward is the lower: the
    oldest contacts break at once); dmu_d_du, the slope of steady friction against
    velocity; K_c_rsf (with --eps > 0), the critical stiffness of the rate-and-state
    law fitted to the model's slow response (Rice and Ruina 1983).
    """
    from ..app.theory import stability as run

    v_ref = renamed("--v-ref", "--u-ref", _U_REF_WHY, v_ref_old, v_ref, _STB["v_ref"].default)
    mass = renamed("--mass", "--M", "reduced, F_el t0^2/a0; --mass is s^2/m in rsf", mass_old,
                   mass, _STB["mass"].default)
    damping = renamed("--damping", "--eta", "reduced, F_el t0/a0; --damping is s/m in rsf",
                      damping_old, damping, _STB["damping"].default)
    _print(run(eps, u, alpha=alpha, mass=mass, damping=damping, creep=creep, direct=direct,
               v_ref=v_ref), json_out)
