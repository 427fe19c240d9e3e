"""Drive rate-and-state friction (:class:`~dryfriction.rsf.RateState`) through a velocity program.

The slider is pulled through a spring of stiffness ``k`` (1/m, per unit normal force: the
rsfmodel convention) whose far end (the load point) follows a
:class:`~dryfriction.program.VelocityProgram` in m/s and s::

    k (x_load(t) - x) = mu(V, theta) + eta V + m dV/dt

with quasi-dynamic radiation damping ``eta`` (``eta/sigma``, s/m; Rice 1993) and the mass
per unit normal force ``m`` (s^2/m). ``k = inf`` is the infinitely stiff (kinematic) machine:
the slider moves with the load point, ``V = V_load(t)``.

Integration (ours): the unknowns are ``ln V``, ``ln theta_i`` (and, with inertia, the spring
force ``tau = k (x_load - x) + const``), so that velocities over tens of decades keep their
relative accuracy and stay positive. Quasi-statically (``m = 0``) the force balance is
differentiated in time::

    d ln V/dt = [k (V_load - V) - sum_i (dmu/dln theta_i) d ln theta_i/dt]
                / (dmu/dln V + eta V)

and the slider position is recovered exactly from the force balance. With inertia,
``d ln V/dt = (tau - mu - eta V)/(m V)`` and ``dtau/dt = k (V_load - V)``. The state laws in
log form are ``d ln theta/dt = 1/theta - V/Dc`` (ageing) and ``-(V/Dc) ln(V theta/Dc)`` (slip).

The stiff system is integrated segment by segment (the load velocity is constant within a
segment) by the L-stable, stiffly accurate 6-stage Rosenbrock method RODAS4 of order 4(3)
(Hairer & Wanner 1996, *Solving ODEs II*, §IV.7, coefficients of their code RODAS), with the
exact Jacobian (:mod:`.stepper`: one source, interpreted for a small job and Numba-compiled
for a large one). The local error per step is held below
``rtol`` in ``ln V`` and ``ln theta`` (a relative error in ``V`` and ``theta``) and below
``rtol * a`` in the spring force. Values between steps (``t_eval``) come from cubic Hermite
interpolation of the log variables (ours).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from ..program import Segment, VelocityProgram
from ..results import check_physical
from ..simulation import OldSimulatorFormWarning, check_parts
from ..validation import Array
from .growth import unstable_start, warn_unstable
from .law import RateState
from .resources import check_rsf_run
from .result import (
    RSFResult,
    build_result,
    force_balance_is_ill_conditioned,
    hermite,
    slip_by_quadrature,
)
from .spring import RSFInitial, RSFOutput, SpringSlider
from .stability import linear_stability
from .stepper import INERTIAL, KINEMATIC, QUASISTATIC, integrate, param_vector

__all__ = ["RSFInitial", "RSFOutput", "RSFResult", "SolverError", "SpringSlider", "simulate",
           "simulate_rsf", "linear_stability"]


class SolverError(RuntimeError):
    """The integration could not be carried to the end (the message says why).

    Attributes
    ----------
    t : float
        Time (s) reached.
    v : float
        Slip velocity (m/s) there (``nan`` for the kinematic machine).
    """

    def __init__(self, message: str, t: float = math.nan, v: float = math.nan) -> None:
        super().__init__(message)
        self.t = t
        self.v = v


_LEGACY = ("stiffness", "damping", "mass", "v_init", "theta_init", "theta2_init", "rtol", "t_eval",
           "max_steps")


def simulate(
    model: RateState,
    drive: SpringSlider,
    initial: RSFInitial | None = None,
    output: RSFOutput | None = None,
) -> RSFResult:
    """Run rate-and-state friction on a spring slider through a load-point velocity program
    (the rate-and-state ``dryfriction.simulate``, :mod:`dryfriction.simulation`).

    Parameters
    ----------
    model : RateState
        Friction law and parameters.
    drive : SpringSlider
        Load-point program (m/s, s), stiffness (1/m; ``inf``: kinematic machine), damping and
        mass.
    initial : RSFInitial, optional
        Initial slip velocity and state; default steady sliding at the first load velocity.
    output : RSFOutput, optional
        Output times, tolerance and step budget; default every accepted step, ``rtol = 1e-7``.

    Returns
    -------
    RSFResult

    Raises
    ------
    ValueError
        Bad input (named parameter, value and allowed range), before any work.
    SolverError
        The integration failed (step-size underflow: e.g. an unbounded slip velocity below
        the critical stiffness without damping; or the step budget ran out).
    """
    check_parts("rsf", drive=drive, initial=initial, output=output)
    if not isinstance(drive, SpringSlider):
        raise ValueError(f"drive = {drive!r} is not allowed: a SpringSlider (load-point program "
                         "in m/s and s; stiffness inf for the kinematic machine)")
    if not isinstance(model, RateState):
        raise ValueError(f"model = {model!r} is not a RateState")
    initial = RSFInitial() if initial is None else initial
    output = RSFOutput() if output is None else output
    if not isinstance(initial, RSFInitial):
        raise ValueError(f"initial = {initial!r} is not an RSFInitial")
    if not isinstance(output, RSFOutput):
        raise ValueError(f"output = {output!r} is not an RSFOutput")
    drive.check_model(model)
    v_init, theta_init, theta2_init = initial.resolve(model, drive)
    check_rsf_run(model, drive, output)
    prog = drive.program
    te = output.times(prog)
    stiffness, damping, mass = drive.stiffness, drive.damping, drive.mass

    mode = KINEMATIC if drive.kinematic else (INERTIAL if mass > 0.0 else QUASISTATIC)
    ns = model.n_state
    lnth = [math.log(theta_init)] + ([math.log(theta2_init)] if theta2_init is not None else [])
    stress0 = float(model.friction(v_init, theta_init, theta2_init)) + damping * v_init
    if mode == KINEMATIC:
        y0 = np.array(lnth)
        w = np.ones(ns)
    elif mode == QUASISTATIC:
        y0 = np.array([math.log(v_init), *lnth])
        w = np.ones(ns + 1)
    else:
        y0 = np.array([math.log(v_init), *lnth, stress0])
        w = np.array([1.0] * (ns + 1) + [model.a])
    p = param_vector(model, stiffness, damping, mass, mode)
    unstable = unstable_start(model, drive, v_init, theta_init, theta2_init)
    if unstable is not None:
        warn_unstable(unstable)

    try:
        T, Y, F, SEG, stats, status, t_fail, y_fail = integrate(
            y0, p, prog.times, prog.velocities, output.rtol, w, output.max_steps
        )
    except ZeroDivisionError:  # a rate overflowed, so the step size became 0 (a, dc ~ 1e-308)
        v_top = float(np.max(np.abs(prog.velocities)))
        raise SolverError(f"the integration failed: the step size fell to zero, the rates "
                          f"overflow floating point (a = {model.a:g}, dc = {model.dc:g}, load "
                          f"velocity up to {v_top:g} m/s)") from None
    if status != 0:
        v_fail = math.nan if mode == KINEMATIC else math.exp(min(float(y_fail[0]), 709.0))
        raise SolverError(_failure_message(status, mode, t_fail, y_fail, model, stiffness,
                                           damping, output.max_steps), float(t_fail), v_fail)
    x = x_quad = None
    travel = float(prog.positions[-1] - prog.positions[0])
    quad_rounding = 0.0
    if mode == INERTIAL:
        # the quadrature's Hermite slopes d ln V/dt = (tau - mu - eta V)/(m V) carry the
        # rounding of that difference, 4 eps |tau|/(m V) (ours); it moves x by up to about
        # 0.6 eps |tau| h^2/m a step whatever rtol (stiff, overdamped slider: 1e-6 of the slip)
        quad_rounding = (4.0 * np.finfo(float).eps * float(np.max(np.abs(Y[:, -1])))
                         * float(np.sum(np.diff(T) ** 2)) / mass)
    if mode != KINEMATIC:
        # int V dt: the position of a soft spring, a check of the force balance's otherwise
        x_quad = slip_by_quadrature(T, Y, F, prog.x0)
        if te is not None:  # at the output times, as x is
            x_quad = hermite(T, x_quad[:, None], np.exp(Y[:, :1]), te)[:, 0]
        if force_balance_is_ill_conditioned(model, stiffness, output.rtol, stress0, travel):
            x = x_quad
    if te is not None:
        Y, SEG = hermite(T, Y, F, te), np.asarray(prog.segment_index(te))
        T = te.copy()
    res = build_result(T, Y, SEG, prog, model, kinematic=mode == KINEMATIC,
                       inertial=mode == INERTIAL, stiffness=stiffness, damping=damping,
                       mass=mass, rtol=output.rtol, stress0=stress0, stats=stats, x=x)
    if unstable is not None:
        res.meta["unstable_start"] = unstable
    _check_bounds(res, travel, None if x_quad is None else float(x_quad[-1] - x_quad[0]),
                  quad_rounding)
    return res


def simulate_rsf(
    model: RateState,
    drive: SpringSlider | VelocityProgram | Iterable[Segment | Mapping[str, float]],
    initial: RSFInitial | None = None,
    output: RSFOutput | None = None,
    **legacy: Any,
) -> RSFResult:
    """Deprecated: the old name of :func:`simulate`, for one release.

    ``simulate_rsf(model, drive, initial, output)`` is :func:`simulate` with a warning
    (:class:`~dryfriction.simulation.OldSimulatorFormWarning`); so is the older keyword form
    ``simulate_rsf(params, program, stiffness=..., damping=..., mass=..., v_init=...,
    theta_init=..., theta2_init=..., rtol=..., t_eval=..., max_steps=...)``.
    """
    if not isinstance(drive, SpringSlider) or legacy:
        drive, initial, output = _from_legacy(drive, initial, output, legacy)
    else:
        warnings.warn(
            "simulate_rsf(model, drive, initial, output) is deprecated and will be removed in "
            "the next release: use simulate(model, drive, initial, output) (dryfriction.simulate "
            "for either law)", OldSimulatorFormWarning, stacklevel=2)
    return simulate(model, drive, initial, output)


def _check_bounds(res: RSFResult, travel: float, slip_integral: float | None,
                  quad_rounding: float = 0.0) -> None:
    """:func:`dryfriction.results.check_physical` for a rate-and-state run: on a spring the
    slip velocity is ``exp(ln V) > 0``, so the slider never moves back, and the slip is at
    most the load-point travel plus the stretch the spring can give back,
    ``(stress0 - min stress)/k``, and it equals ``int V dt`` (``slip_integral``, from the
    solver's steps); the tolerance is 100 times the solver's error in position (ours: ``rtol``
    of the path, whatever the spring), plus ``quad_rounding`` (m), the quadrature's rounding
    bound with inertia."""
    if math.isinf(res.stiffness):  # the kinematic machine: x is the load point's, exactly
        check_physical("rate-and-state run", res.t, res.x, res.v, res.mu, unit="m")
        return
    path = float(np.sum(np.abs(np.diff(res.x))))
    tol = 100.0 * res.rtol * (abs(travel) + path + res.params.dc) + quad_rounding
    give_back = (float(res.stress[0]) - float(np.min(res.stress))) / res.stiffness
    # ours: the slider slides forward (V > 0) throughout, so friction resists it, F/W >= 0.
    # The regularised law is >= 0 by itself; the classic law's ln(V/V0) has no lower bound,
    # and a negative value means it was used outside its domain (outside24: --mu0 -1 or
    # --v0 1e-300 reported mu = -2.8 with exit 0)
    p = res.params
    why = None if p.regularized else (
        "friction below 0 on a slider that slides forward means that the law mu0 + "
        "a ln(V/V0) + b ln(V0 theta/Dc) is outside its domain here "
        f"(mu0 = {p.mu0:g}, V0 = {p.v0:g} m/s); check mu0 and v0, or use the regularised law "
        "(--regularized; regularized = true in a protocol's [model])")
    check_physical("rate-and-state run", res.t, res.x, res.v, res.mu, unit="m", forward=True,
                   tol=tol, slip_max=travel + give_back, slip_integral=slip_integral,
                   mu_min=0.0, mu_why=why)


def _from_legacy(program: Any, initial: Any, output: Any, legacy: dict[str, Any]
                 ) -> tuple[SpringSlider, RSFInitial, RSFOutput]:
    """The old keyword form of :func:`simulate_rsf` as the frozen objects (with a warning)."""
    unknown = sorted(set(legacy) - set(_LEGACY))
    if unknown:
        raise TypeError(f"simulate_rsf() got unexpected keyword argument(s) {', '.join(unknown)}")
    if isinstance(program, SpringSlider) or initial is not None or output is not None:
        raise ValueError(
            "simulate_rsf(model, drive, initial, output) takes SpringSlider, RSFInitial and "
            f"RSFOutput: give {', '.join(sorted(legacy))} through them, not as keywords"
        )
    warnings.warn(
        "simulate_rsf(params, program, stiffness=..., ...) is deprecated and will be removed "
        "in the next release: use simulate(model, SpringSlider(program, stiffness, "
        "damping, mass), RSFInitial(v, theta, theta2), RSFOutput(every|t_eval, rtol, "
        "max_steps))", OldSimulatorFormWarning, stacklevel=3)
    g = legacy.get
    te = g("t_eval")
    return (
        SpringSlider(program, g("stiffness", math.inf), g("damping", 0.0), g("mass", 0.0)),
        RSFInitial(g("v_init"), g("theta_init"), g("theta2_init")),
        RSFOutput(t_eval=None if te is None else np.asarray(te, float), rtol=g("rtol", 1e-7),
                  max_steps=g("max_steps", 1_000_000)),
    )


def _failure_message(status: int, mode: int, t: float, y: Array, params: RateState,
                     stiffness: float, damping: float, max_steps: int) -> str:
    where = f"at t = {t:.6g} s"
    if mode != KINEMATIC:
        where += f" (slip velocity V = {math.exp(min(y[0], 709.0)):.3g} m/s)"
    if status == 2:
        return f"the integration needed more than max_steps = {max_steps} steps {where}"
    msg = f"the integration failed {where}: the step size fell below the rounding limit"
    if mode == QUASISTATIC and damping == 0.0:
        msg += (
            f"; the slip velocity runs away: without radiation damping the quasi-static slider "
            f"(k = {stiffness:.4g} 1/m) reaches unbounded velocity in finite time, below the "
            "critical stiffness or, with the slip law, after a large enough velocity jump even "
            "above it (Gu, Rice, Ruina & Tse 1984) - add damping (eta/sigma, s/m) or mass"
        )
    return msg
