"""The models a fit can use: the trap model (:class:`CVModel`) and rate-and-state friction
(:class:`RSFModel`), their fitted parameters (:class:`ParamSpec`), time-series predictions
(:func:`cv_series`, :func:`rsf_series`) and data-driven starting points.

A model knows its parameters for each combination of data kinds, predicts the data, says which
scale of a parameter the data probe directly (for identifiability) and proposes starts; the
least squares, statistics and orchestration live in :mod:`.problem`, :mod:`.statistics` and
:mod:`.engine` (see the package docstring).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..records.data import Dataset, SeriesData, StaticData, SteadyData
from ..rsf.driving import RSFOutput, SpringSlider, simulate
from ..rsf.law import RateState
from ..rsf.spring import check_spring
from ..theory.dieterich import dieterich_constant_asymptotic
from ..theory.model import TRAP_PARAMETERS, TRAPS_PER_A0, OldTheoryFormWarning, TrapModel
from ..theory.static import static_friction_first_order
from ..theory.steady import athermal_steady_weakens, steady_friction_first_order
from ..theory.units import static_friction_si, steady_friction_si
from ..validation import DIRECT_MAX, Array, check_choice, check_scalar
from .cvseries import cv_series as _old_cv_series
from .cvseries import fitted_scales, fitted_trap, series_run
from .laws import (
    FIT_LAWS,
    INITIAL_STATES,
    initial_specs,
    initial_state,
    law_guess,
    law_specs,
    rate_state,
)
from .loadpoint import load_program
from .machine import load_point_displacement, loading_slope_stiffness

__all__ = [
    "ParamSpec",
    "CVModel",
    "RSFModel",
    "Model",
    "SeriesModel",
    "rsf_series",
    "cv_series",
    "machine_stiffness",
    "load_point_displacement",
    "loading_slope_stiffness",
    "data_kinds",
]


SeriesModel = Callable[[Mapping[str, float], SeriesData], Array]
"""A time-series model: ``(parameter values, data) -> predicted friction at data.t``."""


@dataclass(frozen=True)
class ParamSpec:
    """One fitted parameter.

    Parameters
    ----------
    name : str
        Name (``eps``, ``t0``, ...).
    unit : str
        Unit ("" for dimensionless).
    log : bool
        Fitted as ``ln p`` (a positive scale).
    lo, hi : float
        Search bounds in the parameter's own units.
    physical : (bool, bool)
        Whether ``lo``/``hi`` stands for a physical limit the parameter cannot pass (``eps``,
        ``a``, ``b`` at 1e-6 for 0; the direct effect's ``0 <= A``), not only the search's
        reach: a profile limit reached with another parameter there is the model's, not the
        search's (:func:`.statistics.profile_interval`'s ``pinned``).
    """

    name: str
    unit: str
    log: bool
    lo: float
    hi: float
    physical: tuple[bool, bool] = (False, False)

    def to_internal(self, p: float) -> float:
        return math.log(p) if self.log else float(p)

    def from_internal(self, th: float) -> float:
        if not self.log:
            return float(th)
        return math.exp(th) if th < 709.0 else math.inf  # a huge Wald bound, not an error

    @property
    def bounds(self) -> tuple[float, float]:
        return self.to_internal(self.lo), self.to_internal(self.hi)

    def within(self, p: float) -> float:
        """``p`` put within the search bounds ``[lo, hi]`` (a data-driven guess may lie
        outside them: a flat record's loading slope gives a stiffness below 1 1/m)."""
        return float(np.clip(p, self.lo, self.hi))


def data_kinds(datasets: Sequence[Dataset]) -> frozenset[str]:
    """The kinds of the data sets ("static", "steady", "series"): they choose the parameters."""
    return frozenset(d.kind for d in datasets)


def _linear_scan(y: Array, w: Array, basis: Callable[[float], Array], grid: Array
                 ) -> list[tuple[float, float, float, float]]:
    """For each grid value ``g``: weighted LS fit ``y = A + B basis(g)``; ``(cost, g, A, B)``."""
    out = []
    for g in grid:
        X = np.column_stack([np.ones_like(y), basis(float(g))]) * w[:, None]
        coef, *_ = np.linalg.lstsq(X, y * w, rcond=None)
        r = X @ coef - y * w
        out.append((float(r @ r), float(g), float(coef[0]), float(coef[1])))
    out.sort()
    return out


def _window(xs: Sequence[Array]) -> tuple[float, float] | None:
    pos = np.concatenate([np.ravel(x) for x in xs]) if xs else np.zeros(0)
    pos = pos[pos > 0]
    return (float(pos.min()), float(pos.max())) if pos.size else None


def _weights(d: Dataset) -> Array:
    return np.ones(len(d)) if d.sigma is None else 1.0 / d.sigma


# -- the testing machine of a time series, the same for both models (issue 10; issue 11)
def machine_stiffness(setting: float | str, values: Mapping[str, float]) -> float:
    """The machine stiffness (1/m) of a series model: fitted (``"fit"``) or fixed."""
    return values["stiffness"] if setting == "fit" else float(setting)


def _machine_specs(kinds: frozenset[str], stiffness: float | str, trend: bool
                   ) -> tuple[ParamSpec, ...]:
    extra: tuple[ParamSpec, ...] = ()
    if "series" in kinds and stiffness == "fit":
        extra += (ParamSpec("stiffness", "1/m", True, 1.0, 1e10),)
    if "series" in kinds and trend:
        extra += (ParamSpec("trend", "1/m", False, -1e6, 1e6),)
    return extra


def _machine_guess(series: Sequence[SeriesData], stiffness: float | str, trend: bool
                   ) -> dict[str, float]:
    extra: dict[str, float] = {}
    if series and stiffness == "fit":
        try:
            extra["stiffness"] = loading_slope_stiffness(series[0])
        except ValueError:  # no usable loading slope: a stiff start
            extra["stiffness"] = 1e4 / max(float(np.mean(series[0].mu)), 1e-3)
    if series and trend:
        extra["trend"] = 0.0
    return extra


def _old_cv_form(first: Any, old: tuple[Any, ...], loose: dict[str, Any],
                 given: dict[str, Any]) -> tuple[TrapModel | None, dict[str, Any]]:
    """The old loose form of :class:`CVModel` (``alpha``, ``creep``, ``direct`` as its own
    fields, by position or keyword): warn, and give the held trap model and the rest."""
    args = ((first,) if first is not None else ()) + old
    if isinstance(first, TrapModel) and loose.keys() & {"alpha", "creep", "direct"}:
        name = sorted(loose.keys() & {"alpha", "creep", "direct"})[0]
        raise TypeError(f"CVModel(TrapModel(...), {name}=...): {name} is the trap model's; "
                        f"give it to the TrapModel")
    if isinstance(first, TrapModel) or len(args) > len(_OLD_POSITIONS):
        raise TypeError("CVModel takes the trap model, then keywords: CVModel(TrapModel("
                        "alpha=..., creep=..., direct=...), traps_per_a0=..., v_ref=..., ...)")
    by_position = dict(zip(_OLD_POSITIONS, args, strict=False))
    unknown = set(loose) - {"alpha", "creep", "direct"}
    if unknown:
        raise TypeError(f"CVModel got an unexpected keyword argument {sorted(unknown)[0]!r}")
    twice = set(by_position) & set(loose)
    if twice:
        raise TypeError(f"CVModel got multiple values for argument {sorted(twice)[0]!r}")
    fields = {**given, **{k: v for k, v in by_position.items() if k in given}}
    trap_fields = {k: v for k, v in {**by_position, **loose}.items()
                   if k in ("alpha", "creep", "direct")}
    warnings.warn("CVModel(alpha, creep, ..., direct=...) is the old form (one more release): "
                  "use CVModel(TrapModel(alpha=..., creep=..., direct=...), ...), with a "
                  "dryfriction.TrapModel", OldTheoryFormWarning, stacklevel=3)
    return TrapModel(**trap_fields), fields


def _machine_note(stiffness: float | str, trend: bool) -> str:
    mach = ("fitted stiffness" if stiffness == "fit" else "kinematic"
            if math.isinf(float(stiffness)) else f"k = {float(stiffness):g} 1/m")
    return f"{mach} machine" + (", linear trend in load-point displacement" if trend else "")


_OLD_POSITIONS = ("alpha", "creep", "series", "traps_per_a0", "diff_step", "direct", "v_ref",
                  "stiffness", "trend", "sample_slip", "max_nfev", "progress", "steady_tail")
"""CVModel's fields in the order of its old generated constructor (``CVModel(alpha, creep,
...)``), for the old positional form."""

_HELD_DEFAULTS = ("eps", "mu_el", "v_ref")
"""The fields of a fit's held :class:`TrapModel` that the fit sets, so that they must be left
at their defaults: ``eps`` and ``mu_el`` are fitted, the reduced ``v_ref`` follows the fitted
``a0/t0`` from :attr:`CVModel.v_ref` (m/s)."""


@dataclass(frozen=True, init=False)
class CVModel:
    """The Caroli–Velický trap model for fitting (SI; module docstring): a family of
    :class:`~dryfriction.theory.model.TrapModel`, the held ``trap`` with the fitted ``eps``,
    ``mu_el`` (and ``direct``), at the fitted scales ``a0``, ``t0``
    (:meth:`trap_model`).

    ``CVModel(TrapModel(alpha=0.11, creep="eyring-nabarro", direct=0.02), v_ref=1e-6)``.

    Parameters
    ----------
    trap : TrapModel
        The held part (default ``TrapModel()``): ``alpha`` and ``creep`` fixed; ``direct``:
        ``0``, the athermal model; ``> 0``, the direct-effect coefficient ``A`` (parameter
        ``direct``, dimensionless, ``0 <= A <= 1``; :mod:`dryfriction.theory.direct`) is
        fitted, started from this value (hold it with ``fix={"direct": ...}``); steady and
        time-series data only (static data carry no pull velocity). Its ``eps``, ``mu_el`` and
        ``v_ref`` are the fit's to set, so they must be left at their defaults (refused
        otherwise: give ``eps``, ``mu_el`` to :func:`.engine.fit` as ``start`` or ``fix``, and
        ``v_ref`` here, in m/s).
    series : callable, optional
        Time-series model ``(values, SeriesData) -> mu``; default (``None``): :func:`cv_series`
        with this model.
    traps_per_a0 : float
        Track density of the ensemble for time series.
    v_ref : float
        Reference velocity of the direct effect, m/s, fixed (``> 0``): with ``A`` free it is
        degenerate with ``mu_el`` (``mu_el (1 + A ln(V/V_ref))``), so it cannot be fitted. The
        member's is reduced, ``v_ref / (a0/t0)`` (:meth:`trap_model`).
    stiffness : float or "fit"
        Time series: machine stiffness per unit normal force, 1/m (``inf``, the default: the
        kinematic machine, as before); ``"fit"``: a free parameter ``stiffness`` (``ln k``),
        as :class:`RSFModel`. A finite one drives the ensemble's quasi-static slider
        through a spring (:mod:`.cvseries`).
    trend : bool
        Time series: a free linear trend in load-point displacement, as :class:`RSFModel`.
    sample_slip : float, optional
        Time series: sample the ensemble every this many ``a0`` of slip, whatever the data's
        sampling (:func:`cv_series`); ``None``: at the data's interval (as before).
    steady_tail : bool
        Time series on a spring, without holds: the steady tail of each segment is not
        simulated (:mod:`.cvtail`; the record fit).
    max_nfev : int, optional
        Cap on the model evaluations of one minimisation (default: scipy's ``100 p``).
    progress : callable, optional
        Called with no argument after each time-series run (a progress display).
    diff_step : float
        Relative step (in ``ln`` of the parameters) of the finite-difference Jacobian for time
        series: the ensemble's friction is a staircase in the parameters, one step per trap
        death that moves across a sample (module docstring), so the step must span many of
        them (ours; 0.03 at the default density). With it the optimiser stops at a relative
        change of 1e-6 in cost or parameters (1e-12 otherwise), which the staircase never
        lets it reach.

    Notes
    -----
    The old form, the trap fields loose (``CVModel(alpha, creep, ..., direct=...)``, by
    position or keyword), builds the same model for one more release and warns
    (:class:`~dryfriction.theory.model.OldTheoryFormWarning`).
    """

    trap: TrapModel
    series: SeriesModel | None
    traps_per_a0: float
    diff_step: float
    v_ref: float
    stiffness: float | str
    trend: bool
    sample_slip: float | None
    max_nfev: int | None
    progress: Callable[[], None] | None = field(compare=False, repr=False)
    name: str = field(default="cv", init=False)
    steady_tail: bool = False

    def __init__(self, trap: TrapModel | None = None, *old: Any,
                 series: SeriesModel | None = None,
                 traps_per_a0: float = TRAPS_PER_A0.default,  # type: ignore[assignment]
                 diff_step: float = 0.03, v_ref: float = 1e-6, stiffness: float | str = math.inf,
                 trend: bool = False, sample_slip: float | None = None,
                 max_nfev: int | None = None, progress: Callable[[], None] | None = None,
                 steady_tail: bool = False, **loose: Any) -> None:
        given = dict(series=series, traps_per_a0=traps_per_a0, diff_step=diff_step,
                     v_ref=v_ref, stiffness=stiffness, trend=trend, sample_slip=sample_slip,
                     max_nfev=max_nfev, progress=progress, steady_tail=steady_tail)
        if trap is not None and not isinstance(trap, TrapModel) or old or loose:
            trap, given = _old_cv_form(trap, old, loose, given)
        for name, value in given.items():
            object.__setattr__(self, name, value)
        object.__setattr__(self, "trap", TrapModel() if trap is None else trap)
        object.__setattr__(self, "name", "cv")
        self.__post_init__()

    def __post_init__(self) -> None:
        if not isinstance(self.trap, TrapModel):
            raise ValueError(f"trap = {self.trap!r} is not allowed: a dryfriction.TrapModel")
        for name in _HELD_DEFAULTS:
            if getattr(self.trap, name) != TRAP_PARAMETERS[name].default:
                raise ValueError(
                    f"trap.{name} = {getattr(self.trap, name):g} is not allowed: the fit sets "
                    f"it, so the held TrapModel leaves it at {TRAP_PARAMETERS[name].default:g}"
                    + (" (give v_ref to CVModel, in m/s)" if name == "v_ref" else
                       " (give it to fit() as start= or fix=)"))
        check_scalar("v_ref", self.v_ref, 0.0, lo_open=True)
        if isinstance(self.stiffness, str):
            check_choice("stiffness", self.stiffness, ("fit",))
        else:
            object.__setattr__(self, "stiffness", check_spring(self.stiffness)[0])
        if not isinstance(self.trend, (bool, np.bool_)):
            raise ValueError(f"trend = {self.trend!r} is not allowed: true or false")
        if self.sample_slip is not None:
            check_scalar("sample_slip", self.sample_slip, 0.0, 1.0, lo_open=True)
        if self.max_nfev is not None and not (isinstance(self.max_nfev, int)
                                              and self.max_nfev >= 1):
            raise ValueError(f"max_nfev = {self.max_nfev!r} is not allowed: an integer >= 1")

    @property
    def alpha(self) -> float:
        """The held trap stiffness (``trap.alpha``)."""
        return self.trap.alpha

    @property
    def creep(self) -> str:
        """The held creep law (``trap.creep``)."""
        return self.trap.creep

    @property
    def direct(self) -> float:
        """``trap.direct``: 0, the athermal model; ``> 0``, ``A`` is fitted, from this start."""
        return self.trap.direct

    def trap_model(self, values: Mapping[str, float] | None = None, /,
                   **fitted: float) -> TrapModel:
        """The member of this family at fitted values (SI, as :meth:`parameters` names them):
        the held :attr:`trap` with ``eps``, ``mu_el`` and ``direct`` (0 where the family is
        athermal), its ``v_ref`` the reduced ``v_ref / (a0/t0)`` (or ``v_ref / vstar``) of
        this ``v_ref`` in m/s (:func:`.cvseries.fitted_trap`, the one place it is converted).

        ``cv.trap_model(r.values)`` for a fit result ``r``, or
        ``cv.trap_model(eps=0.03, mu_el=0.5, direct=0.02, a0=1e-6, t0=0.4)``."""
        return fitted_trap(self.trap, self.v_ref, {**(values or {}), **fitted})

    def options(self) -> dict[str, Any]:
        opts: dict[str, Any] = {"alpha": self.alpha, "creep": self.creep}
        if self.direct:  # the athermal options unchanged, as fit.json always wrote them
            opts["v_ref"] = self.v_ref
        if self.stiffness != math.inf or self.trend:  # likewise for the kinematic machine
            opts.update(stiffness=self.stiffness, trend=bool(self.trend),
                        sample_slip=self.sample_slip, traps_per_a0=self.traps_per_a0)
        if self.steady_tail:
            opts["steady_tail"] = True
        return opts

    def parameters(self, kinds: frozenset[str]) -> tuple[ParamSpec, ...]:
        eps = ParamSpec("eps", "", True, 1e-6, 1.0, (True, False))  # 1e-6: no ageing
        mu_el = ParamSpec("mu_el", "", True, 1e-3, 10.0)
        t0 = ParamSpec("t0", "s", True, 1e-12, 1e9)
        if self.direct and "static" in kinds:
            raise ValueError("the direct effect (direct) cannot be fitted to static data: the "
                             "threshold depends on the pull velocity, which a t_w,mu_s file "
                             "does not give; fit steady or time-series data")
        extra = (ParamSpec("direct", "", False, 0.0, DIRECT_MAX, (True, False)),) \
            if self.direct else ()
        if kinds == {"static"}:
            return eps, t0, mu_el
        if kinds == {"steady"}:
            return eps, ParamSpec("vstar", "m/s", True, 1e-15, 1e6), mu_el, *extra
        return (eps, t0, ParamSpec("a0", "m", True, 1e-15, 1.0), mu_el, *extra,
                *_machine_specs(kinds, self.stiffness, self.trend))

    def notes(self, kinds: frozenset[str]) -> list[str]:
        n = [f"alpha = {self.alpha:g} fixed; creep law {self.creep}"]
        if kinds == {"steady"}:
            n.append("steady data depend on a0 and t0 only through V* = a0/t0 (eq. 34): "
                     "vstar is fitted, a0 and t0 are not determined separately")
        if kinds == {"static"}:
            n.append("static data do not depend on a0 (eq. 27): a0 is not determined")
        if self.direct:
            n.append(f"direct effect A fitted, v_ref = {self.v_ref:g} m/s fixed (degenerate "
                     "with mu_el)")
        if "series" in kinds and (self.stiffness != math.inf or self.trend):
            n.append(f"time series simulated on a {_machine_note(self.stiffness, self.trend)}")
        return n

    def allowed_trend(self, kind: str) -> tuple[int, str] | None:
        """The sign the model allows for a data kind's curve against ``ln x``, and why (``None``:
        either sign). Static friction grows with the hold time for every ``eps > 0`` (eq. 27:
        the aged contacts' threshold rises as ``a_r(t_w/t0)`` grows, eq. 17). The athermal
        model's steady friction (eq. 34, no direct effect) falls with velocity at every ``eps``
        and ``u`` for this ``alpha`` and creep law where
        :func:`~dryfriction.theory.steady.athermal_steady_weakens` finds so (``alpha <= 0.3``:
        faster sliding, younger traps, eq. 35); with the direct effect fitted it may rise."""
        if kind == "static":
            return 1, ("the trap model's static friction grows with hold time (ageing, eq. 27, "
                       "eps > 0)")
        if kind == "steady" and not self.direct and athermal_steady_weakens(self.alpha,
                                                                              self.creep):
            return -1, (f"the athermal trap model's steady friction (eq. 34, alpha = "
                        f"{self.alpha:g}, {self.creep} creep) falls with velocity at every eps "
                        "and V: faster sliding leaves the traps younger, less aged (eq. 35: "
                        "d mu_d/d ln V -> -(3/2) eps at low V); --direct A lets it rise")
        return None

    def predict(self, v: Mapping[str, float], d: Dataset, x: Array | None = None) -> Array:
        x = d.x if x is None else x
        if d.kind == "static":
            return static_friction_si(self.trap_model(v), x, fitted_scales(v))
        if d.kind == "steady":
            return steady_friction_si(self.trap_model(v), x, fitted_scales(v))
        assert isinstance(d, SeriesData)
        if self.series is not None:
            return self.series(v, d)
        mu = cv_series(self, v, d)
        if self.progress is not None:
            self.progress()
        return mu

    def data_window(self, name: str, datasets: Sequence[Dataset]) -> tuple[float, float] | None:
        """Values of a time or velocity scale that the data probe directly (see
        :func:`.statistics.classify`)."""
        if name == "t0":
            return _window([d.x for d in datasets if isinstance(d, StaticData)])
        if name == "vstar":
            return _window([d.x for d in datasets if isinstance(d, SteadyData)])
        return None

    def derived(self, v: Mapping[str, float]) -> dict[str, tuple[float, str]]:
        out: dict[str, tuple[float, str]] = {}
        if "a0" in v:
            out["vstar"] = (v["a0"] / v["t0"], "m/s")
            out["D0"] = (dieterich_constant_asymptotic(self.trap.athermal) * v["a0"], "m")
        return out

    # -- starting points ---------------------------------------------------------------
    def _static_scan(self, d: StaticData) -> list[tuple[float, float, float, float]]:
        tpos = d.t_w[d.t_w > 0]
        lo, hi = (tpos.min(), tpos.max()) if tpos.size else (1.0, 1.0)
        grid = np.geomspace(lo * 1e-5, hi * 10.0, 25)
        unit = self.trap_model(eps=1.0, direct=0.0)  # eps = 1: the first order's slope per eps
        return _linear_scan(d.mu_s, _weights(d),
                            lambda t0: static_friction_first_order(unit, d.t_w / t0) - 1.0,
                            grid)

    def _steady_scan(self, d: SteadyData) -> list[tuple[float, float, float, float]]:
        grid = np.geomspace(d.V.min() * 1e-2, d.V.max() * 1e5, 25)
        unit = self.trap_model(eps=1.0, direct=0.0)  # eps = 1: the first order's slope per eps
        return _linear_scan(d.mu_d, _weights(d),
                            lambda vs: steady_friction_first_order(unit, d.V / vs) - 1.0,
                            grid)

    def guesses(self, datasets: Sequence[Dataset]) -> list[dict[str, float]]:
        out = self._athermal_guesses(datasets)
        extra = _machine_guess([d for d in datasets if isinstance(d, SeriesData)],
                               self.stiffness, self.trend)
        if self.direct:
            extra["direct"] = self.direct
        return [{**g, **extra} for g in out]

    def _athermal_guesses(self, datasets: Sequence[Dataset]) -> list[dict[str, float]]:
        def ok(A: float, B: float) -> tuple[float, float]:
            A = A if A > 0 else float(np.mean(np.concatenate([d.y for d in datasets])))
            return A, min(max(B / A, 1e-4), 0.5)

        st = [d for d in datasets if isinstance(d, StaticData)]
        sd = [d for d in datasets if isinstance(d, SteadyData)]
        s_scan = self._static_scan(st[0]) if st else []
        d_scan = self._steady_scan(sd[0]) if sd else []
        out: list[dict[str, float]] = []
        if st and not sd:
            for _, t0, A, B in (s_scan[0], s_scan[len(s_scan) // 2]):
                mu_el, eps = ok(A, B)
                out.append({"eps": eps, "t0": t0, "mu_el": mu_el})
        elif sd and not st:
            for _, vs, A, B in (d_scan[0], d_scan[len(d_scan) // 2]):
                mu_el, eps = ok(A, B)
                out.append({"eps": eps, "vstar": vs, "mu_el": mu_el})
        elif st and sd:
            (_, t0, A1, B1), (_, vs, A2, B2) = s_scan[0], d_scan[0]
            m1, e1 = ok(A1, B1)
            m2, e2 = ok(A2, B2)
            out.append({"eps": math.sqrt(e1 * e2), "t0": t0, "a0": vs * t0,
                        "mu_el": math.sqrt(m1 * m2)})
            out.append({"eps": e1, "t0": t0, "a0": vs * t0, "mu_el": m1})
        else:
            se = [d for d in datasets if isinstance(d, SeriesData)]
            if se:
                out.extend(self._series_guesses(se[0]))
            else:
                out.append({"eps": 0.02, "t0": 1.0, "a0": 1e-6, "mu_el": 0.5})
        return out

    def _series_guesses(self, d: SeriesData) -> list[dict[str, float]]:
        """Starts for a time series (ours): ``mu_el`` from the mean friction, ``eps`` from the
        steady levels at the ends of the stretches (eq. 35: ``d mu/d ln V = -(3/2) eps
        mu_el``), ``a0`` from the slip over which the friction changes after a step (the
        memory, about ``(1 + y_c) a0``), ``V* = a0/t0`` from a few multiples of the mean
        velocity."""
        dur, vel = d.segments()
        mu_el = float(np.mean(d.mu))
        ends = []
        t_rel = d.t - d.t[0]
        bounds = np.concatenate([[0.0], np.cumsum(dur)])
        for i in range(len(dur)):
            k = int(np.searchsorted(t_rel, bounds[i + 1], side="left")) - 1
            ends.append(float(d.mu[max(k, 0)]))
        eps = 0.02
        pos = vel > 0
        if np.sum(pos) >= 2 and np.ptp(np.log(vel[pos])) > 0:
            slope = float(np.polyfit(np.log(vel[pos]), np.array(ends)[pos], 1)[0])
            eps = min(max(-slope / (1.5 * mu_el), 1e-3), 0.3)
        yc = self.trap.trap.y_c
        slip = float(np.sum(dur * vel))
        a0 = max(slip / max(len(dur), 1) / (2.0 * (1.0 + yc)), 1e-12)
        vm = float(np.exp(np.mean(np.log(vel[pos])))) if np.any(pos) else 1.0
        return [{"eps": eps, "t0": a0 / (f * vm), "a0": a0, "mu_el": mu_el}
                for f in (1.0, 0.1, 10.0)]


def cv_series(model: CVModel | Mapping[str, float], *args: Any, **kwargs: Any) -> Array:
    """The trap model's friction along a measured load program (the CV time-series model):
    ``cv_series(model, values, data)``, as :func:`rsf_series`.

    The member of ``model`` at ``values`` (:meth:`CVModel.trap_model`) starts in steady
    sliding at ``v_load[0]`` and is driven by the data's program
    (:func:`.cvseries.series_run`), kinematically or through the machine's spring (``model
    .stiffness``, ``values["stiffness"]`` where fitted, 1/m), on a regular track of
    ``model.traps_per_a0`` pairs per ``a0``, sampled every ``model.sample_slip`` a0 where set,
    without the steady tails where ``model.steady_tail``; plus ``values["trend"] * x_lp``
    (:func:`load_point_displacement`) where ``values`` has a trend.

    Parameters
    ----------
    model : CVModel
        The fitted family. The old form ``cv_series(values, data, alpha, creep,
        traps_per_a0, every_slip, max_samples, stiffness, sample_slip, steady_tail)`` warns
        (:class:`~dryfriction.theory.model.OldTheoryFormWarning`) for one more release.
    values : mapping
        ``eps`` (dimensionless), ``t0`` (s), ``a0`` (m), ``mu_el`` (dimensionless); ``direct``
        where the model fits it; ``stiffness`` (1/m), ``trend`` (1/m) where fitted.
    data : SeriesData
        Times (s) and load velocities (m/s).
    every_slip : float, keyword
        Largest slip between samples, ``a0`` (default 0.01).
    max_samples : int, keyword
        Budget of samples (default 200 000): more is an error.

    Returns
    -------
    ndarray
        Friction coefficient ``F/W`` at ``data.t``.
    """
    if not isinstance(model, CVModel):
        return _old_cv_series(model, *args, **kwargs)
    return _cv_series(model, *args, **kwargs)


def _cv_series(model: CVModel, values: Mapping[str, float], data: SeriesData, *,
               every_slip: float = 0.01, max_samples: int = 200_000) -> Array:
    if "v_ref" in values:  # the old form's place for it: here it would be silently unused
        raise ValueError("v_ref is not a fitted value: it is the model's, CVModel(v_ref=...), "
                         "in m/s")
    run = {k: v for k, v in values.items() if k != "trend"}
    mu = series_run(run, data, lambda: model.trap_model(run), (model.trap, model.v_ref),
                    model.traps_per_a0, every_slip, max_samples,
                    machine_stiffness(model.stiffness, values), model.sample_slip,
                    model.steady_tail)
    if "trend" in values:
        return mu + values["trend"] * load_point_displacement(data)
    return mu


def rsf_series(model: RSFModel, values: Mapping[str, float], data: SeriesData) -> Array:
    """Rate-and-state friction along a measured load program (the RSF time-series model).

    The slider starts in steady sliding at ``v_load[0]``; the program is the data's
    piecewise-constant ``v_load`` (:meth:`SeriesData.segments`), or the measured load point's
    where the data carry one (``data.drive``, :mod:`.loadpoint`); the returned friction is the
    spring force per unit normal force (what a load cell measures), at the data's times,
    from :func:`dryfriction.rsf.simulate` with the model's stiffness
    (``values["stiffness"]`` where it is fitted), damping and state law, plus the linear trend
    ``values["trend"] * x_lp`` in the load-point displacement ``x_lp`` from the first sample
    (:func:`load_point_displacement`) where the model has one (``trend=True``). A program
    with a hold (``v_load = 0``) uses the regularised law. Integration tolerance ``rtol = 1e-9``.
    """
    assert model.v0 is not None
    prog, te, hold = load_program(data)
    params = rate_state(model.state_law, values, model.v0, model.regularized or hold)
    k = machine_stiffness(model.stiffness, values)
    res = simulate(params, SpringSlider(prog, k, model.damping),
                   initial_state(model.initial, values, float(prog.velocities[0])),
                   RSFOutput(t_eval=te, rtol=1e-9, max_steps=200_000))
    mu = np.asarray(res.stress, float)
    if model.trend:
        mu = mu + values["trend"] * load_point_displacement(data)
    return mu


def v0_note(v0: float, unit: str = "m/s") -> str:
    """The fit's note on its fixed reference velocity ``V0`` (Dieterich 1979), in ``unit``: m/s
    for a fit in SI, ``a0/t0`` where the caller reports the fit in reduced units
    (:func:`dryfriction.analysis.rsf_view.fit_rsf_twin`)."""
    return f"v0 = {v0:g} {unit} fixed (reference velocity)"


@dataclass(frozen=True)
class RSFModel:
    """Rate-and-state friction for fitting (SI; module docstring).

    Parameters
    ----------
    v0 : float, optional
        Reference velocity, m/s, fixed. For static (healing) data it is also the sliding and
        reloading velocity of the hold tests, and must be given. Otherwise it defaults to the
        first load velocity of a time series or the geometric mean of the steady velocities.
    state_law : {"ageing", "slip", "prz", "nagata", "ageing2"}
        State evolution law (:mod:`.laws`; static data need the ageing law: the slip law does
        not heal at rest).
    stiffness : float or {"fit", "slope"}
        Machine stiffness per unit normal force for time series, 1/m; ``inf``: kinematic;
        ``"fit"``: a free parameter ``stiffness`` (fitted in ``ln k``); ``"slope"``: fixed from
        the elastic loading slope of the data (:func:`loading_slope_stiffness`, in
        :meth:`resolve`).
    trend : bool
        Time series: add a free linear trend ``mu += trend * x_lp`` (``trend`` in 1/m, per m
        of load-point displacement ``x_lp`` from the first sample; the usual detrending of
        velocity-step analysis, done inside the fit so that its uncertainty is counted).
    damping : float
        Radiation damping ``eta/sigma`` for time series, s/m.
    regularized : bool
        Regularised (``asinh``) law, needed for holds on a kinematic machine.
    series : callable
        Time-series model; default :func:`rsf_series`.
    initial : {"steady", "free"}
        Time series: start in steady sliding, or from a fitted state ``state0`` (:mod:`.laws`).
    """

    v0: float | None = None
    state_law: str = "ageing"
    stiffness: float | str = math.inf
    damping: float = 0.0
    regularized: bool = False
    series: Callable[[RSFModel, Mapping[str, float], SeriesData], Array] = rsf_series
    trend: bool = False
    initial: str = "steady"
    name: str = field(default="rsf", init=False)

    def __post_init__(self) -> None:
        if self.v0 is not None:
            object.__setattr__(self, "v0", check_scalar("v0", self.v0, 0.0, lo_open=True))
        check_choice("state_law", self.state_law, FIT_LAWS)
        check_choice("initial", self.initial, INITIAL_STATES)
        if isinstance(self.stiffness, str):
            check_choice("stiffness", self.stiffness, ("fit", "slope"))
            # a fitted spring is finite: the damping check needs a finite stiffness
            _, eta, _ = check_spring(1.0, self.damping)
        else:
            k, eta, _ = check_spring(self.stiffness, self.damping)
            object.__setattr__(self, "stiffness", k)
        object.__setattr__(self, "damping", eta)
        if not isinstance(self.trend, (bool, np.bool_)):
            raise ValueError(f"trend = {self.trend!r} is not allowed: true or false")

    def options(self) -> dict[str, Any]:
        return {"v0": self.v0, "state_law": self.state_law, "stiffness": self.stiffness,
                "damping": self.damping, "regularized": self.regularized,
                "trend": bool(self.trend), **({"initial": self.initial}
                                              if self.initial != "steady" else {})}

    def resolve(self, datasets: Sequence[Dataset]) -> RSFModel:
        """Fill in ``v0`` from the data where it may be (see the class docstring)."""
        kinds = data_kinds(datasets)
        if "static" in kinds and self.state_law != "ageing":
            raise ValueError("static (healing) data need the ageing law: with the slip law "
                             "the state does not evolve at rest and mu_s does not grow")
        series = [d for d in datasets if isinstance(d, SeriesData)]
        if self.stiffness == "slope":
            if not series:
                raise ValueError("stiffness = 'slope' needs a time series (the loading slope "
                                 "after a velocity change)")
            return dataclasses.replace(self, stiffness=loading_slope_stiffness(series[0]))\
                .resolve(datasets)
        if self.v0 is not None:
            return self
        if "static" in kinds:
            raise ValueError("rate-and-state static (healing) data need v0 (--v0): the "
                             "sliding and reloading velocity of the hold tests, m/s")
        if series:
            v0 = float(series[0].v_load[0])
        else:
            v0 = float(np.exp(np.mean(np.log(np.concatenate([d.x for d in datasets])))))
        return dataclasses.replace(self, v0=v0)

    def parameters(self, kinds: frozenset[str]) -> tuple[ParamSpec, ...]:
        mu0 = ParamSpec("mu0", "", False, -5.0, 5.0)
        a = ParamSpec("a", "", True, 1e-6, 1.0, (True, False))  # 1e-6 for 0
        b = ParamSpec("b", "", True, 1e-6, 1.0, (True, False))
        dc = ParamSpec("dc", "m", True, 1e-12, 1.0)
        if kinds == {"steady"}:
            return mu0, ParamSpec("a_minus_b", "", False, -1.0, 1.0)
        if kinds == {"static"}:
            return mu0, b, dc
        extra = (*law_specs(self.state_law), *initial_specs(self.initial))
        return (mu0, a, b, dc, *(ParamSpec(*e) for e in extra),
                *_machine_specs(kinds, self.stiffness, self.trend))

    def notes(self, kinds: frozenset[str]) -> list[str]:
        n = [v0_note(self.v0)]
        if kinds == {"steady"}:
            n.append("steady-state data determine only a - b and mu0 (mu_ss = mu0 + (a - b) "
                     "ln(V/V0), Ruina 1983): a, b and Dc separately need transients")
        if kinds == {"static"}:
            n.append("static (healing) data determine mu0, b and Dc (mu_s = mu0 + b ln(1 + "
                     "t_w V0/Dc), ageing law, infinitely stiff reload at V0) but not a")
        if "series" in kinds:
            n.append(f"time series simulated with {self.state_law} law, "
                     f"{_machine_note(self.stiffness, self.trend)}")
        return n

    def allowed_trend(self, kind: str) -> tuple[int, str] | None:
        """As :meth:`CVModel.allowed_trend`: healing ``mu_s = mu0 + b ln(1 + t_w V0/Dc)`` grows with
        the hold time for every ``b > 0`` (ageing law, Ruina 1983)."""
        if kind == "static":
            return 1, ("rate-and-state healing, mu0 + b ln(1 + t_w V0/Dc) with b > 0, grows "
                       "with hold time")
        return None

    def _params(self, v: Mapping[str, float]) -> RateState:
        assert self.v0 is not None
        if "a_minus_b" in v:  # only a - b enters the steady state: any a, b with that difference
            b = max(0.0, -v["a_minus_b"]) + 1.0
            return RateState(v["a_minus_b"] + b, b, 1.0, v["mu0"], self.v0)
        return rate_state(self.state_law, {"a": 1.0, **v}, self.v0, self.regularized)

    def predict(self, v: Mapping[str, float], d: Dataset, x: Array | None = None) -> Array:
        x = d.x if x is None else x
        if d.kind == "steady":
            return self._params(v).steady_state_friction(x)
        if d.kind == "static":
            assert self.v0 is not None
            return self._params(v).hold_peak_friction(x, self.v0)
        assert isinstance(d, SeriesData)
        return self.series(self, v, d)

    def data_window(self, name: str, datasets: Sequence[Dataset]) -> tuple[float, float] | None:
        """Slips that the data probe directly, for ``dc`` (see :func:`.statistics.classify`)."""
        if name != "dc" or self.v0 is None:
            return None
        slips = [self.v0 * d.x for d in datasets if isinstance(d, StaticData)]
        for d in datasets:
            if isinstance(d, SeriesData):
                dur, vel = d.segments()
                slips.append(np.array([float(np.min(np.diff(d.t))) * float(vel.max()),
                                       float(np.sum(dur * vel))]))
        return _window(slips)

    def derived(self, v: Mapping[str, float]) -> dict[str, tuple[float, str]]:
        if "a" in v and "b" in v:
            return {"a_minus_b": (v["a"] - v["b"], "")}
        return {}

    def guesses(self, datasets: Sequence[Dataset]) -> list[dict[str, float]]:
        assert self.v0 is not None
        v0 = self.v0
        st = [d for d in datasets if isinstance(d, StaticData)]
        sd = [d for d in datasets if isinstance(d, SteadyData)]
        se = [d for d in datasets if isinstance(d, SeriesData)]
        amb, mu0 = 0.0, float(np.mean(np.concatenate([d.y for d in datasets])))
        if sd:
            s = _linear_scan(sd[0].mu_d, _weights(sd[0]), lambda _: np.log(sd[0].V / v0),
                             np.array([0.0]))[0]
            mu0, amb = s[2], s[3]
        b, dcs = 0.01, [1e-6, 1e-5]
        if st:
            d = st[0]
            tpos = d.t_w[d.t_w > 0]
            lo, hi = (tpos.min(), tpos.max()) if tpos.size else (1.0, 1.0)
            scan = _linear_scan(d.mu_s, _weights(d), lambda dc: np.log1p(d.t_w * v0 / dc),
                                np.geomspace(lo * v0 * 1e-5, hi * v0 * 10.0, 25))
            mu0 = scan[0][2] if not sd else mu0
            b = min(max(scan[0][3], 1e-4), 0.5)
            dcs = [scan[0][1], scan[len(scan) // 2][1]]
        kinds = data_kinds(datasets)
        if kinds == {"steady"}:
            return [{"mu0": mu0, "a_minus_b": amb}]
        if kinds == {"static"}:
            return [{"mu0": mu0, "b": b, "dc": dc} for dc in dcs]
        out = []
        if se:
            d0 = se[0]
            dur, vel = d0.segments()
            slip = float(np.sum(dur * vel))
            mu0 = float(d0.mu[0]) - amb * math.log(float(d0.v_load[0]) / v0) if not sd else mu0
            if not st:
                dcs = list(np.geomspace(slip / 300.0, slip / 10.0, 3))
        extra = _machine_guess(se, self.stiffness, self.trend)
        for dc in dcs:
            for a in ((0.005, 0.02) if se and not st else (max(b + amb, 1e-4),)):
                g = {"mu0": mu0, "a": a, "b": max(a - amb, 1e-4), "dc": float(dc), **extra}
                out.append({**g, **law_guess(self.state_law, self.initial, g)})
        return out


Model = CVModel | RSFModel
