"""Physical (SI) units on top of the reduced core.

The core works in the paper's reduced units: lengths in ``a0`` (m), times in ``t0`` (s),
velocities in ``V* = a0/t0`` (m/s), forces in ``F_el`` (eq. 12). A friction experiment reports a
friction coefficient ``F/W`` for a normal load ``W``; the model's elastic friction level
``mu_el = F_el/W`` is then the one extra number that maps ``F/F_el`` onto it. Every conversion is
explicit and every field says its unit.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..validation import FRICTION_MAX, Array, check_broadcast, check_range, check_scalar
from .model import TRAP_PARAMETERS, TrapModel, takes_model
from .static import static_friction, static_friction_over_eps
from .steady import steady_friction, steady_friction_over_eps

__all__ = ["PhysicalScales", "friction_level", "static_friction_si", "steady_friction_si"]


@dataclass(frozen=True)
class PhysicalScales:
    """The scales that turn reduced results into SI ones.

    Parameters
    ----------
    a0 : float
        Contact radius after the initial plastic crushing, m (``> 0``).
    t0 : float
        Plastic creep time of eq. 18, s (``> 0``).
    mu_el : float
        Elastic friction level ``F_el / W`` (dimensionless, ``0 < mu_el <= FRICTION_MAX``).
    normal_load : float, optional
        Normal load ``W``, N (``> 0``); needed only to express forces in newtons.
    """

    a0: float
    t0: float
    mu_el: float = 1.0
    normal_load: float | None = None

    def __post_init__(self) -> None:
        check_scalar("a0", self.a0, 0.0, lo_open=True)
        check_scalar("t0", self.t0, 0.0, lo_open=True)
        check_scalar("mu_el", self.mu_el, 0.0, FRICTION_MAX, lo_open=True)
        if self.normal_load is not None:
            check_scalar("normal_load", self.normal_load, 0.0, lo_open=True)

    @property
    def velocity_scale(self) -> float:
        """``V* = a0/t0``, m/s."""
        return self.a0 / self.t0

    @property
    def elastic_force(self) -> float:
        """``F_el = mu_el W``, N."""
        if self.normal_load is None:
            raise ValueError("normal_load (N) is needed to express forces in newtons")
        return self.mu_el * self.normal_load

    def reduced_velocity(self, V: ArrayLike) -> Array:
        """``u = V/V*`` from ``V`` in m/s."""
        return check_range("V", V, 0.0, lo_open=True) / self.velocity_scale

    def reduced_time(self, t: ArrayLike) -> Array:
        """``T = t/t0`` from ``t`` in s."""
        return check_range("t", t, 0.0) / self.t0

    def reduced_length(self, x: ArrayLike) -> Array:
        """``x/a0`` from ``x`` in m."""
        return check_range("x", x) / self.a0

    def friction_coefficient(self, mu_reduced: ArrayLike) -> Array:
        """``F/W = mu_el * F/F_el``."""
        return self.mu_el * np.asarray(mu_reduced, float)

    def force(self, mu_reduced: ArrayLike) -> Array:
        """``F`` in N from ``F/F_el``."""
        return self.elastic_force * np.asarray(mu_reduced, float)

    def memory_length(self, C: ArrayLike) -> Array:
        """Dieterich length ``D0 = C a0`` in m (eq. 36)."""
        return np.asarray(C, float) * self.a0


@contextmanager
def _in_reduced_units(meaning: str) -> Iterator[None]:
    """Say what the reduced variable of a core range error is in SI (``T = t_w/t0, ...``)."""
    try:
        yield
    except ValueError as exc:
        raise ValueError(f"{exc} ({meaning})") from None


def _static_si_loose(
    t_w: ArrayLike,
    eps: float,
    scales: PhysicalScales,
    alpha: float = 0.13,
    creep: str = "log",
    load: float = 0.0,
    direct: float = 0.0,
    v_ref: float = 1e-6,
    pull_velocity: float | None = None,
) -> Array:
    """:func:`static_friction_si` with the parameters loose (its old form): static friction
    coefficient ``F_s/W`` after waiting ``t_w`` seconds (eq. 27).

    ``load`` is the tangential force during the wait as a fraction of ``F_el`` (``[0, 1)``).
    With the direct effect (``direct = A > 0``) the threshold depends on the pull's slip rate
    ``pull_velocity`` (m/s, required then); ``v_ref`` is the reference velocity in m/s.
    """
    check_broadcast(t_w=t_w, eps=eps)
    T = scales.reduced_time(t_w)
    u_ref, u_pull = 1.0, None
    if direct:
        u_ref = float(scales.reduced_velocity(check_scalar("v_ref", v_ref, 0.0, lo_open=True)))
        if pull_velocity is not None:
            u_pull = float(scales.reduced_velocity(
                check_scalar("pull_velocity", pull_velocity, 0.0, lo_open=True)))
    model = TrapModel(alpha, creep=creep, direct=direct, v_ref=u_ref)
    with _in_reduced_units(f"T = t_w/t0, t0 = {scales.t0:g} s"):
        mu = static_friction_over_eps(model, T, eps, load=load, pull_velocity=u_pull)
    return scales.friction_coefficient(mu)


def _steady_si_loose(
    V: ArrayLike, eps: float, scales: PhysicalScales, alpha: float = 0.13, creep: str = "log",
    direct: float = 0.0, v_ref: float = 1e-6,
) -> Array:
    """:func:`steady_friction_si` with the parameters loose (its old form): steady dynamic
    friction coefficient ``F_d/W`` at sliding velocity ``V`` in m/s (eq. 34).

    ``direct`` is the direct-effect coefficient ``A`` (dimensionless, :mod:`.direct`) and
    ``v_ref`` its reference velocity in m/s (``> 0``; it enters only when ``direct > 0``).
    """
    check_broadcast(V=V, eps=eps)
    u = scales.reduced_velocity(V)
    u_ref = 1.0
    if direct:
        u_ref = float(scales.reduced_velocity(check_scalar("v_ref", v_ref, 0.0, lo_open=True)))
    model = TrapModel(alpha, creep=creep, direct=direct, v_ref=u_ref)
    with _in_reduced_units(f"u = V/V*, V* = a0/t0 = {scales.velocity_scale:g} m/s"):
        mu = steady_friction_over_eps(model, u, eps)
    return scales.friction_coefficient(mu)


def friction_level(model: TrapModel, scales: PhysicalScales) -> float:
    """The one ``mu_el = F_el/W`` of a model expressed in SI: ``model.mu_el`` and
    ``scales.mu_el`` are the same number given twice, so where one is left at its default (1)
    the other is used, and two different values are refused (one line, before any work)."""
    default = TRAP_PARAMETERS["mu_el"].default
    if model.mu_el == scales.mu_el or scales.mu_el == default:
        return model.mu_el
    if model.mu_el == default:
        return scales.mu_el
    raise ValueError(f"mu_el = {model.mu_el:g} (model) and mu_el = {scales.mu_el:g} (scales) "
                     "differ: the elastic friction level F_el/W is one number; give it in one "
                     "of them")


@takes_model(_static_si_loose,
             "static_friction_si(t_w, eps, scales, alpha, creep, load, direct, v_ref, "
             "pull_velocity)",
             "static_friction_si(model, t_w, scales, load=..., pull_velocity=..., hold=...)")
def static_friction_si(model: TrapModel, t_w: ArrayLike, scales: PhysicalScales, *,
                       load: float = 0.0, pull_velocity: float | None = None,
                       hold: str = "position") -> Array:
    """Static friction coefficient ``F_s/W`` of ``model`` after waiting ``t_w`` seconds
    (eq. 27; :func:`dryfriction.theory.static.static_friction` in SI).

    Parameters
    ----------
    model : TrapModel
        The trap model; its ``v_ref`` is reduced (``a0/t0``), as everywhere: from a reference
        velocity in m/s, ``model.replace(v_ref=float(scales.reduced_velocity(V_ref)))``.
    t_w : array_like
        Waiting time, s (``>= 0``).
    scales : PhysicalScales
        ``a0`` (m), ``t0`` (s) and the friction level ``mu_el`` (:func:`friction_level`).
    load : float
        Tangential force during the wait as a fraction of ``F_el`` (``-1 < load < 1``).
    pull_velocity : float, optional
        Slip rate of the pull, m/s; required when ``model.direct > 0``.
    hold : {"position", "force"}
        How a loaded contact is held during the wait (:func:`.static.static_friction`).

    Returns
    -------
    ndarray
        ``F_s/W = mu_el mu_s``, the shape of ``t_w``.
    """
    mu_el = friction_level(model, scales)
    T = scales.reduced_time(t_w)
    u_pull = None
    if model.direct > 0.0 and pull_velocity is None:
        raise ValueError("pull_velocity is required when direct > 0 (the threshold depends on "
                         "how fast it is pulled): a slip rate in m/s, > 0")
    if pull_velocity is not None:
        u_pull = float(scales.reduced_velocity(
            check_scalar("pull_velocity", pull_velocity, 0.0, lo_open=True)))
    with _in_reduced_units(f"T = t_w/t0, t0 = {scales.t0:g} s"):
        mu = static_friction(model, T, load=load, pull_velocity=u_pull, hold=hold)
    return mu_el * mu


@takes_model(_steady_si_loose,
             "steady_friction_si(V, eps, scales, alpha, creep, direct, v_ref)",
             "steady_friction_si(model, V, scales)")
def steady_friction_si(model: TrapModel, V: ArrayLike, scales: PhysicalScales) -> Array:
    """Steady dynamic friction coefficient ``F_d/W`` of ``model`` at sliding velocity ``V`` in
    m/s (eq. 34; :func:`dryfriction.theory.steady.steady_friction` in SI).

    ``scales`` gives ``V* = a0/t0`` (m/s) and the friction level ``mu_el``
    (:func:`friction_level`); ``model.v_ref`` is reduced (``a0/t0``), as everywhere: from a
    reference velocity in m/s, ``model.replace(v_ref=float(scales.reduced_velocity(V_ref)))``.
    Returns ``F_d/W = mu_el mu_d``, the shape of ``V``.
    """
    mu_el = friction_level(model, scales)
    u = scales.reduced_velocity(V)
    with _in_reduced_units(f"u = V/V*, V* = a0/t0 = {scales.velocity_scale:g} m/s"):
        mu = steady_friction(model, u)
    return mu_el * mu
