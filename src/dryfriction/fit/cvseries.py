"""The trap model's time series along a measured load program (:func:`cv_series`), on a
kinematic or an elastic machine with a trend, and its start from a rate-and-state fit
(:func:`cv_start_from_rsf`).

The machine is the one the rate-and-state record fit uses
(:func:`.models.rsf_series`): a spring of stiffness ``k`` (per unit normal force, 1/m) between
the load point, which follows the data's program, and the slider, which here is the trap
ensemble's quasi-static slider (:class:`dryfriction.ensemble.driving.SpringDrive` with mass 0);
plus the linear trend ``trend * x_lp`` in load-point displacement. In reduced units the spring
is ``K = k a0 / mu_el`` (``F_el/a0``).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping
from typing import Any, Protocol

import numpy as np

from ..program import Segment
from ..records.data import SeriesData
from ..theory.direct import junction_strength
from ..theory.linear_stability import effective_rsf
from ..theory.model import TRAPS_PER_A0, OldTheoryFormWarning, TrapModel
from ..theory.steady import steady_friction
from ..theory.units import PhysicalScales
from ..validation import Array
from .machine import load_point_displacement

__all__ = ["cv_series", "cv_start_from_rsf", "fitted_scales", "fitted_trap", "series_run",
           "TrapFamily"]

_LAST: list[tuple[Any, SeriesData, Array]] = []
"""Memory of the last :data:`MEMORY_RUNS` series before their trend, newest last (ours): the
trend is additive, so a change of the trend alone (its column of the Jacobian, a step along it)
needs no new run; and a record fit asks for the same points again (the trend's column comes
after the others', the covariance's central differences twice: the engine's and the robust
one's, the figure the optimum). Reused only for the same data object (its arrays are
read-only) and the same everything else; replaced as one list, so that threads never see a
half-written entry."""

MEMORY_RUNS = 32
"""Series kept (about 80 kB each for a window of 1e4 samples)."""


def _key(values: Mapping[str, float], *options: Any) -> tuple[Any, ...]:
    # 13 significant digits: a parameter read back through its internal variable
    # (exp(log p), the robust covariance's) is the same point, not a new run
    return (tuple(sorted((k, float(f"{float(v):.13g}")) for k, v in values.items()
                         if k != "trend")), options)


def fitted_scales(values: Mapping[str, float]) -> PhysicalScales:
    """The physical scales of a trap-model fit at fitted ``values`` (SI): ``a0`` (m), ``t0``
    (s), ``mu_el``; from ``vstar`` (m/s) alone with ``t0 = 1`` s (steady data depend on
    ``a0/t0`` only, eq. 34); from ``t0`` alone with ``a0 = 1`` m (static data do not depend on
    ``a0``, eq. 27)."""
    if "a0" in values:
        return PhysicalScales(values["a0"], values["t0"], values["mu_el"])
    if "vstar" in values:  # t0 = 1 s: only a0/t0 matters for steady data
        return PhysicalScales(values["vstar"] * 1.0, 1.0, values["mu_el"])
    return PhysicalScales(1.0, values["t0"], values["mu_el"])  # a0 does not enter eq. 27


def fitted_trap(trap: TrapModel, v_ref: float, values: Mapping[str, float]) -> TrapModel:
    """The member of a fitted family of trap models at ``values`` (ours): ``trap``'s
    ``alpha`` and ``creep`` with the fitted ``eps``, ``mu_el`` (``trap``'s where not given)
    and direct effect ``direct`` (``A``; 0, the athermal model, where not given), whose
    reference velocity ``v_ref`` (m/s) becomes the model's reduced one, ``v_ref / (a0/t0)``
    (or ``v_ref / vstar``), at these values' scales (:func:`fitted_scales`).

    The one place where a fit's ``v_ref`` in m/s meets the model's in ``a0/t0``: the fit moves
    ``a0/t0``, not ``v_ref`` (:class:`dryfriction.fit.CVModel`, whose ``trap_model`` this is).
    """
    if "eps" not in values:
        raise ValueError("eps is not given: a fitted trap model needs its value")
    if trap.direct and "direct" not in values:
        raise ValueError(f"direct is not given: this family fits the direct effect (its start "
                         f"{trap.direct:g}), so a member needs its value")
    mu_el = values.get("mu_el", trap.mu_el)
    direct = values.get("direct", 0.0)
    extra = {"direct": direct}  # the held trap's direct is a start, not the member's
    if direct:
        if "a0" not in values and "vstar" not in values:
            raise ValueError(f"direct = {direct:g} needs the velocity scale (a0 and t0, or "
                             "vstar): v_ref is in m/s, the model's in a0/t0")
        extra = {"direct": direct, "v_ref": float(fitted_scales(
            {**values, "mu_el": mu_el}).reduced_velocity(v_ref))}
    return trap.replace(eps=values["eps"], mu_el=mu_el, **extra)


def cv_series(values: Mapping[str, float], data: SeriesData, alpha: float = 0.13,
              creep: str = "log", traps_per_a0: float = TRAPS_PER_A0.default,  # type: ignore[assignment]
              every_slip: float = 0.01,
              max_samples: int = 200_000, stiffness: float = math.inf,
              sample_slip: float | None = None, steady_tail: bool = False) -> Array:
    """The old loose form of :func:`dryfriction.fit.cv_series` (one more release; warns
    :class:`~dryfriction.theory.model.OldTheoryFormWarning`): ``alpha``, ``creep``, the track
    and the machine loose, ``v_ref`` (m/s) in ``values``. Use ``fit.cv_series(CVModel(
    TrapModel(alpha, creep=creep), traps_per_a0=..., v_ref=..., stiffness=...,
    sample_slip=..., steady_tail=...), values, data)``; it computes exactly this.
    """
    if not isinstance(values, Mapping):  # a CVModel: the new form lives beside CVModel
        raise TypeError("fit.cvseries.cv_series is the old form only: call "
                        "dryfriction.fit.cv_series(model, values, data)")
    warnings.warn("fit.cvseries.cv_series(values, data, alpha, creep, traps_per_a0, ...) is "
                  "the old form (one more release): use fit.cv_series(CVModel(TrapModel(alpha, "
                  "creep=creep), traps_per_a0=..., v_ref=..., stiffness=...), values, data), "
                  "with a dryfriction.TrapModel", OldTheoryFormWarning, stacklevel=2)
    trap = TrapModel(alpha, creep=creep)
    v_ref = values.get("v_ref", 1e-6)
    mu = series_run({k: v for k, v in values.items() if k not in ("trend", "v_ref")}, data,
                    lambda: fitted_trap(trap, v_ref, values), (trap, v_ref), traps_per_a0,
                    every_slip, max_samples, stiffness, sample_slip, steady_tail)
    if "trend" in values:
        return mu + values["trend"] * load_point_displacement(data)
    return mu


def series_run(values: Mapping[str, float], data: SeriesData, model: Callable[[], TrapModel],
               fixed: tuple[Any, ...], traps_per_a0: float, every_slip: float = 0.01,
               max_samples: int = 200_000, stiffness: float = math.inf,
               sample_slip: float | None = None, steady_tail: bool = False) -> Array:
    """The trap model's friction along a measured load program, before any trend (the CV
    time-series model; :func:`dryfriction.fit.cv_series` adds the trend).

    The ensemble starts in steady sliding at ``v_load[0]``; the data's piecewise-constant
    ``v_load`` (:meth:`SeriesData.segments`) drives the slider kinematically
    (``stiffness = inf``, the infinitely stiff machine) or drives the load point of a spring
    ``stiffness`` (module docstring), in reduced units through
    ``PhysicalScales(a0, t0, mu_el)``. It is sampled at least every ``every_slip`` a0 of slip
    and at the data's own sampling interval (in slip without holds; in time, so that ageing
    during a hold is followed, with holds), or, with ``sample_slip``, every ``sample_slip`` a0
    whatever the data's sampling; read at the data's times by linear interpolation.

    Parameters
    ----------
    values : mapping
        ``eps`` (dimensionless), ``t0`` (s), ``a0`` (m), ``mu_el`` (dimensionless); optionally
        ``direct`` (``A``, dimensionless); no ``trend``.
    data : SeriesData
        Times (s) and load velocities (m/s).
    model : callable
        Builds the trap model at ``values`` (:meth:`dryfriction.fit.CVModel.trap_model`);
        called only for a run (not for one remembered, nor before the budget's check).
    fixed : tuple
        What, besides ``values`` and the options, the run depends on (the held trap model and
        ``v_ref``, m/s): the memory's key.
    traps_per_a0 : float
        Density of the regular track (accuracy about ``1/traps_per_a0`` relative).
    every_slip : float
        Largest slip between samples, ``a0``.
    max_samples : int
        Budget: more samples than this is an error (a trial ``t0`` far too small makes the
        program very long in ``t0``).
    stiffness : float
        Machine stiffness per unit normal force, 1/m; ``inf``: kinematic. A spring stiffer than
        :data:`dryfriction.ensemble.driving.STIFFNESS_MAX` (reduced) is the kinematic limit.
    sample_slip : float, optional
        Sample every this many ``a0`` of (load-point) slip instead of at the data's interval:
        the cost no longer grows with the data's sampling rate (the record fit).
    steady_tail : bool
        On a spring, without holds: the steady tail of each segment is not simulated
        (:func:`.cvtail.spring_series`; the record fit).

    Returns
    -------
    ndarray
        Friction coefficient ``F/W`` at ``data.t`` (a copy the caller may change).
    """
    from ..ensemble.driving import STIFFNESS_MAX, Output, SpringDrive, VelocityDrive, simulate
    from ..ensemble.population import Initial, Track

    key = _key(values, *fixed, traps_per_a0, every_slip, max_samples, stiffness, sample_slip,
               steady_tail)
    memory = list(_LAST)
    hit = next((m for m in reversed(memory) if m[0] == key and m[1] is data), None)
    if hit is not None:
        mu = hit[2]
    else:
        sc = PhysicalScales(values["a0"], values["t0"], values["mu_el"])
        dur, vel = data.segments()
        u = vel / sc.velocity_scale
        T = dur / sc.t0
        prog = [Segment(float(ui), float(Ti)) for ui, Ti in zip(u, T, strict=True)]
        dt_data = float(np.min(np.diff(data.t))) / sc.t0 if len(data.t) > 1 else float(np.sum(T))
        u_max = float(np.max(u))
        if sample_slip is not None:
            dt_data, ds_data = math.inf, sample_slip
            every_slip = sample_slip
        else:
            ds_data = float(np.min(np.diff(data.t) * data.v_load[1:])) / sc.a0 \
                if len(data.t) > 1 else every_slip
        if np.all(u > 0):  # no holds: sample in slip (the state is exact at every sample)
            output = Output(every_slip=min(every_slip, max(ds_data, 1e-6)))
            n = float(np.sum(u * T)) / output.every_slip  # type: ignore[operator]
        else:  # holds: sample in time, so that ageing during the hold is followed
            output = Output(every=min(dt_data, every_slip / u_max) if u_max > 0 else dt_data)
            n = float(np.sum(T)) / output.every  # type: ignore[operator]
        if n > max_samples:
            raise ValueError(f"{data.source}: the trap-model series would need {n:.3g} samples "
                             f"(> {max_samples}) for t0 = {values['t0']:.3g} s, a0 = "
                             f"{values['a0']:.3g} m")
        trap = model()
        k_red = stiffness * values["a0"] / values["mu_el"]
        drive = (SpringDrive(k_red, 0.0, prog) if k_red <= STIFFNESS_MAX
                 else VelocityDrive(prog))
        try:
            if steady_tail and isinstance(drive, SpringDrive) and np.all(u > 0):
                from .cvtail import spring_series

                res = spring_series(trap, Track(traps_per_a0), prog, drive.stiffness,
                                    float(output.every_slip))  # type: ignore[arg-type]
            else:
                res = simulate(trap, drive, Initial("steady", velocity=float(u[0]),
                                                     track=Track(traps_per_a0)), output)
        except ValueError as exc:
            if "DRYFRICTION_MEMORY_LIMIT" not in str(exc):
                raise
            # the simulator's hint names its own keys (every_slip, traps_per_a0); a fit has
            # --traps-per-a0 only (issue 24)
            raise ValueError(f"{data.source}: a trap-model run at t0 = {values['t0']:.3g} s, "
                             f"a0 = {values['a0']:.3g} m needs more memory than the limit: "
                             "lower --traps-per-a0 or set DRYFRICTION_MEMORY_LIMIT") from None
        t_res, mu_res = res if isinstance(res, tuple) else (res.t, res.mu)
        mu = np.interp((data.t - data.t[0]) / sc.t0, t_res, mu_res)
        _LAST[:] = (memory + [(key, data, mu)])[-MEMORY_RUNS:]
    return mu.copy()  # the caller may change it; the memory must not


class TrapFamily(Protocol):
    """A fitted family of trap models (:class:`dryfriction.fit.CVModel`): its held trap model
    and the member at fitted values."""

    @property
    def trap(self) -> TrapModel: ...

    def trap_model(self, values: Mapping[str, float] | None = None, /,
                   **fitted: float) -> TrapModel: ...


def cv_start_from_rsf(model: TrapFamily | Mapping[str, float], *args: Any,
                      **kwargs: Any) -> dict[str, float]:
    """A trap-model start from a rate-and-state fit at ``v0``, through the twin (ours):
    ``cv_start_from_rsf(model, rsf, v0, u=1.0)``.

    The twin of steady sliding at reduced velocity ``u = v0 t0/a0``
    (:func:`dryfriction.theory.linear_stability.effective_rsf`: ``a = g a_0 + a_d``,
    ``b = g b_0``, ``Dc`` unchanged, ``a_0, b_0`` in ``F_el``, ``Dc`` in ``a0``, ``g`` the
    junction strength at ``u``, ``a_d ~ A mu_d``) is matched to the fitted ``b``, ``dc``,
    ``mu0`` (and ``a`` with the direct effect): ``mu_el = mu0 / (g mu_d(u))``, ``eps`` scaled
    until ``mu_el g b_0 = b``, ``A = (a/mu_el - g a_0) / mu_d``, ``a0 = dc / Dc``; four
    passes. ``u`` is not fixed by one velocity's ``a, b, Dc`` (the
    twin depends on it only through slow logarithms): it is an input, 1 by default (the
    model's crossover velocity ``a0/t0`` at the first velocity). The machine parameters
    (``stiffness``, ``trend``) are carried over unchanged.

    Parameters
    ----------
    model : CVModel
        The fitted family (:class:`dryfriction.fit.CVModel`): its ``alpha``, ``creep``, and
        whether it fits the direct effect (``model.trap.direct > 0``; ``v_ref`` in m/s). The
        old form ``cv_start_from_rsf(rsf, v0, alpha, creep, direct, v_ref, u)`` warns
        (:class:`~dryfriction.theory.model.OldTheoryFormWarning`) for one more release.
    rsf : mapping
        The rate-and-state fit: ``mu0``, ``a``, ``b`` (dimensionless), ``dc`` (m).
    v0 : float
        Its reference velocity, m/s.
    u : float
        Reduced velocity ``v0 t0/a0`` of the start.

    Returns
    -------
    dict
        ``eps``, ``t0``, ``a0``, ``mu_el`` (and ``direct`` when the model fits it, clipped to
        ``[1e-3, 0.5]``; ``stiffness``, ``trend`` where ``rsf`` has them).
    """
    if isinstance(model, Mapping):
        warnings.warn("fit.cvseries.cv_start_from_rsf(rsf, v0, alpha, creep, direct, v_ref, "
                      "u) is the old form (one more release): use cv_start_from_rsf(CVModel("
                      "TrapModel(alpha, creep=creep, direct=direct), v_ref=v_ref), rsf, v0, u)"
                      ", with a dryfriction.TrapModel", OldTheoryFormWarning, stacklevel=2)
        return _start_from_rsf(model, *args, **kwargs)
    return _start_from_rsf_model(model, *args, **kwargs)


def _start_from_rsf(rsf: Mapping[str, float], v0: float, alpha: float = 0.13,
                    creep: str = "log", direct: float = 0.0, v_ref: float = 1e-6,
                    u: float = 1.0) -> dict[str, float]:
    trap = TrapModel(alpha, creep=creep, direct=direct)
    return _start(lambda v: fitted_trap(trap, v_ref, v), trap.direct, rsf, v0, u)


def _start_from_rsf_model(model: TrapFamily, rsf: Mapping[str, float], v0: float,
                          u: float = 1.0) -> dict[str, float]:
    return _start(model.trap_model, model.trap.direct, rsf, v0, u)


def _start(member: Callable[[Mapping[str, float]], TrapModel], direct: float,
           rsf: Mapping[str, float], v0: float, u: float) -> dict[str, float]:
    eps, mu_el, A, g = 0.02, float(rsf["mu0"]), 0.0, 1.0
    for _ in range(4):
        # the member at a0/t0 = v0/u (so its v_ref is v_ref u/v0): the twin is the athermal
        # population's, times the junction strength g(u)
        model = member({"eps": eps, "direct": A, "vstar": v0 / u})
        tw = effective_rsf(u, model.athermal)
        mu_d = float(steady_friction(model.athermal, u))
        g = float(junction_strength(u, model.direct, model.v_ref)) if A else 1.0
        mu_el = float(rsf["mu0"]) / (g * mu_d)
        eps = min(max(eps * float(rsf["b"]) / (mu_el * g * tw["b"]), 1e-5), 0.5)
        if direct > 0.0:
            A = min(max((float(rsf["a"]) / mu_el - g * tw["a"]) / mu_d, 1e-3), 0.5)
    a0 = float(rsf["dc"]) / tw["dc"]
    out = {"eps": eps, "t0": u * a0 / v0, "a0": a0, "mu_el": mu_el}
    if direct > 0.0:
        out["direct"] = A
    out.update({k: float(rsf[k]) for k in ("stiffness", "trend") if k in rsf})
    return out
