"""The direct effect in the ensemble drivers (issue 11; :mod:`dryfriction.theory.direct`).

The trap population (:mod:`dryfriction.ensemble.population`,
:mod:`dryfriction.ensemble.kernel`) is the athermal one; the friction force is ``g(V)`` times
its force, ``V`` the slider's present velocity (ours, the prefactor reading of
:mod:`dryfriction.theory.direct`). These helpers are what :mod:`dryfriction.ensemble.driving`
needs for that; each is the identity (or 1, or None) when ``model.direct == 0``, so the
athermal drivers run their unchanged code.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace

from ..theory.direct import strength_ratio
from .population import Ensemble, Initial, Observables, TrapModel

__all__ = ["velocity_scale", "with_strength", "check_direct_mass", "initial_velocity",
           "creep_substeps"]

SUBSTEP_SLIP: float = 0.25
"""Largest load-point travel per quasi-static creep step, in trap spacings (ours): the step must
resolve the sawtooth of the population force, or a regular track sampled at a multiple of its
spacing locks the slider onto one phase of it (a stroboscopic fixed point)."""


def velocity_scale(ens: Ensemble, dt: float) -> Callable[[float], float] | None:
    """``X -> g((X - X0)/dt)`` for the step of length ``dt`` that starts at the present ``X0``;
    None without the direct effect (the athermal jumps then run unchanged)."""
    m = ens.model
    if m.direct == 0.0:
        return None
    x0 = ens.x
    return lambda x: strength_ratio((x - x0) / dt, m.direct, m.v_ref)


def with_strength(ens: Ensemble, o: Observables, v: float) -> Observables:
    """The observables with the junction strength at velocity ``v`` applied: force and
    stiffness times ``g(v)``; ``o`` itself without the direct effect."""
    m = ens.model
    if m.direct == 0.0:
        return o
    g = strength_ratio(v, m.direct, m.v_ref)
    return replace(o, force=g * o.force, stiffness=g * o.stiffness)


def check_direct_mass(model: TrapModel, mass: float) -> None:
    """Refuse an inertial slider with the direct effect (not implemented: the explicit Verlet
    step cannot follow ``g'(V) = A e^{1/A}/(2 V_ref)`` near ``V = 0``)."""
    if model.direct > 0.0 and mass > 0.0:
        raise ValueError(f"mass = {mass:g} is not allowed with direct = {model.direct:g}: the "
                         "inertial slider is not implemented with the direct effect; allowed "
                         "mass = 0 (quasi-static slider)")


def initial_velocity(model: TrapModel, initial: Initial, first_segment: float | None) -> float:
    """Slider velocity of the first sample: 0 without the direct effect (as before); with it,
    the velocity its force is taken at: the first segment's (velocity drive), else the steady
    state's, else 0."""
    if model.direct == 0.0:
        return 0.0
    if first_segment is not None:
        return float(first_segment)
    if initial.kind == "steady" and initial.velocity is not None:
        return float(initial.velocity)
    return 0.0


def creep_substeps(ens: Ensemble, load_travel: float) -> int:
    """Quasi-static creep steps for a load-point travel (:data:`SUBSTEP_SLIP`); 1 without the
    direct effect (one jump per sample, as before)."""
    if ens.model.direct == 0.0:
        return 1
    return max(1, math.ceil(abs(load_travel) / (SUBSTEP_SLIP * ens.track.spacing)))
