"""The direct effect in the ensemble drivers (:mod:`dryfriction.theory.direct`).

The trap population (:mod:`dryfriction.ensemble.population`,
:mod:`dryfriction.ensemble.kernel`) is the athermal one; the friction force is ``g(V)`` times
its force, ``V`` the slider's present velocity (ours, the prefactor reading of
:mod:`dryfriction.theory.direct`). These helpers are what :mod:`dryfriction.ensemble.driving`
needs for that; each is the identity (or 1, or None) when ``model.direct == 0``, so the
athermal drivers run their unchanged code.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..theory.direct import strength_ratio, strength_slope
from .population import Ensemble, Initial, Observables, TrapModel

__all__ = ["VelocityScale", "velocity_scale", "with_strength", "apply_strength",
           "initial_velocity", "creep_substeps", "inertial_velocity", "drift"]

SUBSTEP_SLIP: float = 0.25
"""Largest load-point travel per quasi-static creep step, in trap spacings (ours): the step must
resolve the sawtooth of the population force, or a regular track sampled at a multiple of its
spacing locks the slider onto one phase of it (a stroboscopic fixed point)."""


@dataclass(frozen=True)
class VelocityScale:
    """``X -> g((X - X0)/dt)``, the junction strength of a step of length ``dt`` from ``X0``
    to ``X`` (:func:`~dryfriction.theory.direct.strength_ratio`), and its slope in ``X``."""

    x0: float
    dt: float
    direct: float
    v_ref: float

    def __call__(self, x: float) -> float:
        return strength_ratio((x - self.x0) / self.dt, self.direct, self.v_ref)

    def slope(self, x: float) -> float:
        """``d g((X - X0)/dt) / dX = g'(V)/dt`` (``inf`` where ``g'`` overflows at ``V = 0``)."""
        return strength_slope((x - self.x0) / self.dt, self.direct, self.v_ref) / self.dt


def velocity_scale(ens: Ensemble, dt: float) -> VelocityScale | None:
    """``X -> g((X - X0)/dt)`` for the step of length ``dt`` that starts at the present ``X0``;
    None without the direct effect (the athermal jumps then run unchanged)."""
    m = ens.model
    if m.direct == 0.0:
        return None
    return VelocityScale(ens.x, dt, m.direct, m.v_ref)


def with_strength(ens: Ensemble, o: Observables, v: float) -> Observables:
    """The observables with the junction strength at velocity ``v`` applied: force and
    stiffness times ``g(v)``; ``o`` itself without the direct effect."""
    m = ens.model
    if m.direct == 0.0:
        return o
    return apply_strength(o, strength_ratio(v, m.direct, m.v_ref))


def apply_strength(o: Observables, g: float) -> Observables:
    """The observables with force and stiffness times the junction strength ``g``."""
    # not dataclasses.replace: the inertial slider calls this every step, and replace costs
    # tens of microseconds
    return Observables(force=g * o.force, stiffness=g * o.stiffness, n_active=o.n_active,
                       mean_age=o.mean_age, births=o.births, spinodal=o.spinodal,
                       exits=o.exits, next_event=o.next_event)


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


# ---------------------------------------------------------------- the inertial slider


def _inverse_strength(y: float, direct: float, v_ref: float) -> float:
    """``V >= 0`` with ``g(V) = y >= 0``: ``V = V_c sinh(y/A)``, ``V_c = 2 V_ref e^{-1/A}``;
    from logarithms where ``sinh`` or ``e^{1/A}`` would overflow."""
    z = y / direct
    if z > 20.0:  # 2 sinh z = e^z to 4e-18
        return v_ref * math.exp(z - 1.0 / direct)
    return 2.0 * v_ref * math.exp(-1.0 / direct) * math.sinh(z)


def _damping_rate(model: TrapModel, v: float, force: float) -> float:
    """``d(g F)/dV = g'(V) F`` for ``F > 0`` (else 0), ``g'`` from
    :func:`~dryfriction.theory.direct.strength_slope` (infinite at rest when ``A/V_c``
    overflows)."""
    if force <= 0.0:
        return 0.0
    return force * strength_slope(v, model.direct, model.v_ref)


def _implicit_velocity(model: TrapModel, c: float, m_eff: float, f_eff: float
                       ) -> tuple[float, float]:
    """Root ``(V, g(V))`` of ``m_eff V + f_eff g(V) = c`` for ``m_eff, f_eff > 0``.

    Solved for ``y = g(V)``, which is well conditioned at any speed (``V`` near rest is
    ``~ e^{-1/A}``-small, where ``g`` is what the force needs to the last bit). ``m_eff V(y) +
    f_eff y`` is odd, increasing and convex for ``y > 0``, so Newton from an upper bound
    (``c/f_eff``, or ``g(c/m_eff)``) descends monotonically onto the root.
    """
    if c == 0.0:
        return 0.0, 0.0
    A, vr = model.direct, model.v_ref
    vc = 2.0 * vr * math.exp(-1.0 / A)
    s, c = math.copysign(1.0, c), abs(c)
    y = min(c / f_eff, strength_ratio(c / m_eff, A, vr))
    v = _inverse_strength(y, A, vr)
    for _ in range(200):
        h = m_eff * v + f_eff * y - c
        if h <= 0.0:
            break
        step = h / (m_eff * math.hypot(v, vc) / A + f_eff)  # dV/dy = sqrt(V^2 + V_c^2)/A
        y -= step
        v = _inverse_strength(y, A, vr)
        if step <= 1e-15 * y:
            break
    return s * v, s * y


def inertial_velocity(model: TrapModel, v: float, r: float, dt: float, mass: float,
                      damping: float, spring: float, force: float) -> tuple[float, float]:
    """Velocity and junction strength at the end of one inertial step with the direct effect.

    The slider obeys ``M V' = R = S - eta V - g(V) F`` (``S`` the spring force, ``F`` the
    population's). The position has already moved by the explicit Verlet step; ``S`` and ``F``
    are those at its end. The velocity takes the theta-step ``M (V1 - V) = dt [(1 - theta) R
    + theta R(V1)]``, implicit in ``V1`` (ours):

    * friction and damping relax the velocity at the rate ``c/M``, ``c = eta + g'(V) F`` with
      ``g' = A/sqrt(V^2 + V_c^2)``, which near rest reaches ``A e^{1/A}/(2 V_ref)``: no
      explicit step can follow it, and the trapezoid (theta = 1/2, velocity Verlet, second
      order) multiplies that mode by ``(1 - z/2)/(1 + z/2) -> -1`` for ``z = c dt/M >> 1``,
      flipping the velocity, hence the friction's sign, every step;
    * so theta = 1/2 where ``z <= 2`` at both ends of the step (the mode resolved), and
      backward Euler (theta = 1, L-stable: the mode's factor ``1/(1 + z)`` stays in ``(0, 1)``)
      where it is stiffer. There the velocity is slaved to the force balance ``S = eta V +
      g(V) F`` of the sticking slider (its creep), which backward Euler solves at the step's
      end; the order drops to one only over the ``M/c`` transient.

    The explicit position step stays stable: the slow (creep) root of the linearised slider,
    ``-(K + g k_c)/c``, is at most the oscillation frequency ``sqrt((K + g k_c)/M)`` (its bound
    where the two roots merge), which the step already resolves.

    With ``F <= 0`` the friction ``-g(V) F`` does not resist the motion (nothing stiff, and
    the implicit equation may have several roots): the velocity takes the explicit predictor
    of the athermal scheme.

    Parameters
    ----------
    model : TrapModel
        With ``direct > 0``.
    v, r : float
        Velocity ``a0/t0`` and total force ``M V'`` (``F_el``) at the start of the step.
    dt, mass, damping : float
        Step ``t0``, ``M``, ``eta``.
    spring, force : float
        Spring force and population force (``F_el``) at the end of the step.

    Returns
    -------
    v1, g1 : float
        Velocity and junction strength ``g(v1)`` at the end of the step (``g1`` carried, not
        recomputed: near rest ``v1`` may underflow while ``g1`` is the force balance's).
    """
    A, vr = model.direct, model.v_ref
    if force <= 0.0:
        vp = v + r / mass * dt
        g = strength_ratio(vp, A, vr)
        return v + 0.5 * (r + spring - g * force - damping * vp) / mass * dt, g

    def stiff(u: float) -> bool:
        return dt * (damping + _damping_rate(model, u, force)) > 2.0 * mass

    def solve(theta: float) -> tuple[float, float]:
        c = mass * v + dt * ((1.0 - theta) * r + theta * spring)
        return _implicit_velocity(model, c, mass + dt * theta * damping, dt * theta * force)

    if not stiff(v):
        v1, g1 = solve(0.5)
        if not stiff(v1):
            return v1, g1
    return solve(1.0)


def drift(model: TrapModel, v: float, dt: float, mass: float, damping: float, force: float
          ) -> float:
    """Weight ``w`` of the acceleration in the position step ``dX = V dt + w a dt^2`` (ours).

    Verlet's ``w = 1/2`` assumes the acceleration ``a`` lasts the step; with the direct effect
    it relaxes at the rate ``c/M`` (:func:`inertial_velocity`), within a tiny fraction of the
    step near rest. For ``a' = -(c/M) a`` the exact weight is ``phi2(z) = (e^{-z} - 1 + z)/z^2``,
    ``z = c dt/M``: ``1/2 - z/6 + ...`` (the same order as Verlet where ``z`` is small) and
    ``~ 1/z`` where it is large, so that a slider released out of balance (at rest, where
    ``g(0) = 0``) moves by ``R dt/c``, what the slaved velocity carries, not by ``R dt^2/2M``.
    """
    z = (_damping_rate(model, v, force) + damping) * dt / mass
    if z < 1e-3:
        return 0.5 - z / 6.0 + z * z / 24.0
    return (math.expm1(-z) + z) / (z * z) if math.isfinite(z) else 0.0
