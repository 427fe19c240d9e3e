"""Fit the trap model or rate-and-state friction to measured friction, with honest errors.

Models (SI units; friction coefficients ``F/W``):

* ``"cv"`` — the Caroli–Velický trap model (:class:`CVModel`), ``alpha`` fixed (0.13 by
  default). Static data ``mu_s(t_w) = mu_el static_friction(t_w/t0, eps)`` (eq. 27) fix ``eps``,
  ``t0`` (s) and ``mu_el``; steady data ``mu_d(V) = mu_el steady_friction(V/V*, eps)`` (eq. 34)
  fix ``eps``, ``V* = a0/t0`` (m/s) and ``mu_el``; together they fix ``eps, t0, a0, mu_el``
  (``a0`` in m) with one parameter set. Both go through :mod:`dryfriction.units`.
* ``"rsf"`` — rate-and-state friction (:class:`RSFModel`), ``v0`` fixed and reported. Steady
  data give only ``a - b`` and ``mu0`` (``mu_ss = mu0 + (a - b) ln(V/V0)``, Ruina 1983); static
  (healing) data give ``mu0, b, Dc`` through
  :meth:`dryfriction.rsf.RateState.hold_peak_friction` (``mu0 + b ln(1 + t_w V0/Dc)``, ageing
  law, reload at ``V0``; Beeler, Tullis & Weeks 1994; Marone 1998) and nothing about ``a``;
  time series (velocity steps, slide-hold-slide) give ``a, b, Dc, mu0`` through
  :func:`dryfriction.rsf_driving.simulate_rsf`.

Time-series models are callables ``(values, data) -> predicted friction``
(:data:`SeriesModel`); the rate-and-state one is :func:`rsf_series`, the trap model's is
:func:`cv_series` (the ensemble simulator :func:`dryfriction.driving.simulate` with the data's
load program as a kinematic :class:`~dryfriction.driving.VelocityDrive`, through
:class:`~dryfriction.units.PhysicalScales`). The ensemble's friction is a sum over discrete
traps, so it is a fine staircase in the parameters (a trap dies at a sample): its Jacobian is
taken with a larger difference step (:attr:`CVModel.diff_step`).

Method (ours, standard weighted least squares):

* residuals ``r_i = (y_i - f_i)/sigma_i`` with the data's uncertainties when every file gives
  them, otherwise ``sigma_i = 1`` and one common noise level estimated from the fit;
* :func:`scipy.optimize.least_squares` (trust-region reflective, bounds), positive scales fitted
  as ``ln p``; starts from linearised least-squares scans of the data (first-order eq. 28a and
  the first-order eq. 34 are linear in ``(mu_el, mu_el eps)`` at fixed ``t0`` or ``V*``; the RSF
  forms are linear in ``(mu0, b)`` at fixed ``Dc``) plus any start given;
* covariance ``C = s^2 (J^T J)^+`` of the fitted (log) parameters from a central-difference
  Jacobian, ``s^2 = 1`` with given uncertainties, ``s^2 = RSS/(n - p)`` without; intervals
  ``theta +- q sqrt(C_ii)`` mapped back (asymmetric for log parameters; ``q`` = 1.96, or
  Student t with ``n - p`` degrees of freedom when the noise level is estimated);
* a profile likelihood for every free parameter: the cost minimised over the others along a
  path in that parameter, the 95 % interval where ``2 (cost - cost_min)/s^2`` reaches 3.84
  (chi-square, one degree of freedom). A side that never reaches it inside the search bounds is
  reported open ("only bounded above by ..."), and no error bar is given for that parameter;
* goodness of fit (chi-square test with given uncertainties; per-data-set RMS residuals and a
  runs test on the residual signs), AIC/BIC for model comparison, and, for joint fits, a test
  that one parameter set explains every data set (the joint fit against separate fits: a
  chi-square difference test with given uncertainties, an F test without).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import stats
from scipy.optimize import least_squares

from .io.data import Dataset, SeriesData, StaticData, SteadyData
from .program import Segment
from .rsf.driving import RSFOutput, SolverError, SpringSlider, simulate_rsf
from .rsf.law import STATE_LAWS, RateState
from .rsf.spring import check_spring
from .theory.dieterich import dieterich_constant_asymptotic
from .theory.static import static_friction_first_order
from .theory.steady import steady_friction_first_order
from .theory.trap import Trap
from .theory.units import PhysicalScales, static_friction_si, steady_friction_si
from .validation import check_choice, check_scalar

__all__ = [
    "ParamSpec",
    "CVModel",
    "RSFModel",
    "SeriesModel",
    "rsf_series",
    "cv_series",
    "ParameterEstimate",
    "FitResult",
    "fit",
    "fit_static",
    "fit_steady",
    "fit_joint",
    "compare_models",
    "plot_fit",
    "PROFILE_THRESHOLD",
]

Array = NDArray[np.float64]

SeriesModel = Callable[[Mapping[str, float], SeriesData], Array]
"""A time-series model: ``(parameter values, data) -> predicted friction at data.t``."""

PROFILE_THRESHOLD: float = float(stats.chi2.ppf(0.95, 1))
"""Rise of ``chi^2`` (3.84) that bounds a 95 % profile-likelihood interval (one parameter) with
given uncertainties; with the noise level estimated the threshold is ``t_{0.975, n-p}^2``."""

_Z95: float = float(stats.norm.ppf(0.975))


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
    """

    name: str
    unit: str
    log: bool
    lo: float
    hi: float

    def to_internal(self, p: float) -> float:
        return math.log(p) if self.log else float(p)

    def from_internal(self, th: float) -> float:
        if not self.log:
            return float(th)
        return math.exp(th) if th < 709.0 else math.inf  # a huge Wald bound, not an error

    @property
    def bounds(self) -> tuple[float, float]:
        return self.to_internal(self.lo), self.to_internal(self.hi)


# ----------------------------------------------------------------------------- time series
def cv_series(values: Mapping[str, float], data: SeriesData, alpha: float = 0.13,
              creep: str = "log", traps_per_a0: float = 1000.0, every_slip: float = 0.01,
              max_samples: int = 200_000) -> Array:
    """The trap model's friction along a measured load program (the CV time-series model).

    The ensemble starts in steady sliding at ``v_load[0]`` and the slider follows the data's
    piecewise-constant ``v_load`` (:meth:`SeriesData.segments`) kinematically (the machine is
    taken as infinitely stiff), in reduced units through
    ``PhysicalScales(a0, t0, mu_el)``. It is sampled at least every ``every_slip`` a0 of slip
    and at the data's own sampling interval (in slip without holds; in time, so that ageing
    during a hold is followed, with holds), and read at the data's times by linear
    interpolation.

    Parameters
    ----------
    values : mapping
        ``eps`` (dimensionless), ``t0`` (s), ``a0`` (m), ``mu_el`` (dimensionless).
    data : SeriesData
        Times (s) and load velocities (m/s).
    alpha : float
        Trap stiffness (fixed).
    creep : {"log", "eyring-nabarro"}
    traps_per_a0 : float
        Density of the regular track (accuracy about ``1/traps_per_a0`` relative).
    every_slip : float
        Largest slip between samples, ``a0``.
    max_samples : int
        Budget: more samples than this is an error (a trial ``t0`` far too small makes the
        program very long in ``t0``).

    Returns
    -------
    ndarray
        Friction coefficient ``F/W`` at ``data.t``.
    """
    from .ensemble.driving import Output, VelocityDrive, simulate
    from .ensemble.population import Initial, Track, TrapModel

    sc = PhysicalScales(values["a0"], values["t0"], values["mu_el"])
    dur, vel = data.segments()
    u = vel / sc.velocity_scale
    T = dur / sc.t0
    prog = [Segment(float(ui), float(Ti)) for ui, Ti in zip(u, T, strict=True)]
    dt_data = float(np.min(np.diff(data.t))) / sc.t0 if len(data.t) > 1 else float(np.sum(T))
    u_max = float(np.max(u))
    if np.all(u > 0):  # no holds: sample in slip (the state is exact at every sample)
        ds_data = float(np.min(np.diff(data.t) * data.v_load[1:])) / sc.a0 \
            if len(data.t) > 1 else every_slip
        output = Output(every_slip=min(every_slip, max(ds_data, 1e-6)))
        n = float(np.sum(u * T)) / output.every_slip  # type: ignore[operator]
    else:  # holds: sample in time, so that ageing during the hold is followed
        output = Output(every=min(dt_data, every_slip / u_max) if u_max > 0 else dt_data)
        n = float(np.sum(T)) / output.every  # type: ignore[operator]
    if n > max_samples:
        raise ValueError(f"{data.source}: the trap-model series would need {n:.3g} samples "
                         f"(> {max_samples}) for t0 = {values['t0']:.3g} s, a0 = "
                         f"{values['a0']:.3g} m")
    model = TrapModel(alpha, values["eps"], creep, values["mu_el"])
    res = simulate(model, Track(traps_per_a0), Initial("steady", velocity=float(u[0])),
                   VelocityDrive(prog), output)
    return np.interp((data.t - data.t[0]) / sc.t0, res.t, res.mu)


def _kinds(datasets: Sequence[Dataset]) -> frozenset[str]:
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


@dataclass(frozen=True)
class CVModel:
    """The Caroli–Velický trap model for fitting (SI; module docstring).

    Parameters
    ----------
    alpha : float
        Reduced trap stiffness, fixed (0.13 in the paper).
    creep : {"log", "eyring-nabarro"}
        Ageing law (eq. 17 or eqs. 15-16).
    series : callable, optional
        Time-series model ``(values, SeriesData) -> mu``; default (``None``): :func:`cv_series`
        with this ``alpha``, ``creep`` and ``traps_per_a0``.
    traps_per_a0 : float
        Track density of the ensemble for time series.
    diff_step : float
        Relative step (in ``ln`` of the parameters) of the finite-difference Jacobian for time
        series: the ensemble's friction is a staircase in the parameters, one step per trap
        death that moves across a sample (module docstring), so the step must span many of
        them (ours; 0.03 at the default density). With it the optimiser stops at a relative
        change of 1e-6 in cost or parameters (1e-12 otherwise), which the staircase never
        lets it reach.
    """

    alpha: float = 0.13
    creep: str = "log"
    series: SeriesModel | None = None
    traps_per_a0: float = 1000.0
    diff_step: float = 0.03
    name: str = field(default="cv", init=False)

    def __post_init__(self) -> None:
        check_scalar("alpha", self.alpha, 0.0, 1.0, lo_open=True, hi_open=True)
        check_choice("creep", self.creep, ("log", "eyring-nabarro"))

    def options(self) -> dict[str, Any]:
        return {"alpha": self.alpha, "creep": self.creep}

    def parameters(self, kinds: frozenset[str]) -> tuple[ParamSpec, ...]:
        eps = ParamSpec("eps", "", True, 1e-6, 1.0)
        mu_el = ParamSpec("mu_el", "", True, 1e-3, 10.0)
        t0 = ParamSpec("t0", "s", True, 1e-12, 1e9)
        if kinds == {"static"}:
            return eps, t0, mu_el
        if kinds == {"steady"}:
            return eps, ParamSpec("vstar", "m/s", True, 1e-15, 1e6), mu_el
        return eps, t0, ParamSpec("a0", "m", True, 1e-15, 1.0), mu_el

    def notes(self, kinds: frozenset[str]) -> list[str]:
        n = [f"alpha = {self.alpha:g} fixed; creep law {self.creep}"]
        if kinds == {"steady"}:
            n.append("steady data depend on a0 and t0 only through V* = a0/t0 (eq. 34): "
                     "vstar is fitted, a0 and t0 are not determined separately")
        if kinds == {"static"}:
            n.append("static data do not depend on a0 (eq. 27): a0 is not determined")
        return n

    def _scales(self, v: Mapping[str, float]) -> PhysicalScales:
        if "a0" in v:
            return PhysicalScales(v["a0"], v["t0"], v["mu_el"])
        if "vstar" in v:  # t0 = 1 s: only a0/t0 matters for steady data
            return PhysicalScales(v["vstar"] * 1.0, 1.0, v["mu_el"])
        return PhysicalScales(1.0, v["t0"], v["mu_el"])  # a0 does not enter eq. 27

    def predict(self, v: Mapping[str, float], d: Dataset, x: Array | None = None) -> Array:
        x = d.x if x is None else x
        if d.kind == "static":
            return static_friction_si(x, v["eps"], self._scales(v), self.alpha, self.creep)
        if d.kind == "steady":
            return steady_friction_si(x, v["eps"], self._scales(v), self.alpha, self.creep)
        assert isinstance(d, SeriesData)
        if self.series is not None:
            return self.series(v, d)
        return cv_series(v, d, self.alpha, self.creep, self.traps_per_a0)

    def data_window(self, name: str, datasets: Sequence[Dataset]) -> tuple[float, float] | None:
        """Values of a time or velocity scale that the data probe directly (see _classify)."""
        if name == "t0":
            return _window([d.x for d in datasets if isinstance(d, StaticData)])
        if name == "vstar":
            return _window([d.x for d in datasets if isinstance(d, SteadyData)])
        return None

    def derived(self, v: Mapping[str, float]) -> dict[str, tuple[float, str]]:
        out: dict[str, tuple[float, str]] = {}
        if "a0" in v:
            out["vstar"] = (v["a0"] / v["t0"], "m/s")
            out["D0"] = (dieterich_constant_asymptotic(self.alpha) * v["a0"], "m")
        return out

    # -- starting points ---------------------------------------------------------------
    def _static_scan(self, d: StaticData) -> list[tuple[float, float, float, float]]:
        tpos = d.t_w[d.t_w > 0]
        lo, hi = (tpos.min(), tpos.max()) if tpos.size else (1.0, 1.0)
        grid = np.geomspace(lo * 1e-5, hi * 10.0, 25)
        return _linear_scan(d.mu_s, _weights(d),
                            lambda t0: static_friction_first_order(d.t_w / t0, 1.0, self.alpha)
                            - 1.0, grid)

    def _steady_scan(self, d: SteadyData) -> list[tuple[float, float, float, float]]:
        grid = np.geomspace(d.V.min() * 1e-2, d.V.max() * 1e5, 25)
        return _linear_scan(d.mu_d, _weights(d),
                            lambda vs: steady_friction_first_order(d.V / vs, 1.0, self.alpha)
                            - 1.0, grid)

    def guesses(self, datasets: Sequence[Dataset]) -> list[dict[str, float]]:
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
        yc = Trap(self.alpha).y_c
        slip = float(np.sum(dur * vel))
        a0 = max(slip / max(len(dur), 1) / (2.0 * (1.0 + yc)), 1e-12)
        vm = float(np.exp(np.mean(np.log(vel[pos])))) if np.any(pos) else 1.0
        return [{"eps": eps, "t0": a0 / (f * vm), "a0": a0, "mu_el": mu_el}
                for f in (1.0, 0.1, 10.0)]


def rsf_series(model: RSFModel, values: Mapping[str, float], data: SeriesData) -> Array:
    """Rate-and-state friction along a measured load program (the RSF time-series model).

    The slider starts in steady sliding at ``v_load[0]``; the program is the data's
    piecewise-constant ``v_load`` (:meth:`SeriesData.segments`); the returned friction is the
    spring force per unit normal force (what a load cell measures), at the data's times,
    from :func:`dryfriction.rsf_driving.simulate_rsf` with the model's stiffness, damping and
    state law. Integration tolerance ``rtol = 1e-9``.
    """
    assert model.v0 is not None
    params = RateState(values["a"], values["b"], values["dc"], values["mu0"], model.v0,
                       state_law=model.state_law,  # type: ignore[arg-type]
                       regularized=model.regularized)
    dur, vel = data.segments()
    prog = [Segment(float(v), float(t)) for v, t in zip(vel, dur, strict=True)]
    te = np.clip(data.t - data.t[0], 0.0, float(np.sum(dur)))
    res = simulate_rsf(params, SpringSlider(prog, model.stiffness, model.damping),
                       output=RSFOutput(t_eval=te, rtol=1e-9, max_steps=200_000))
    return np.asarray(res.stress, float)


@dataclass(frozen=True)
class RSFModel:
    """Rate-and-state friction for fitting (SI; module docstring).

    Parameters
    ----------
    v0 : float, optional
        Reference velocity, m/s, fixed. For static (healing) data it is also the sliding and
        reloading velocity of the hold tests, and must be given. Otherwise it defaults to the
        first load velocity of a time series or the geometric mean of the steady velocities.
    state_law : {"ageing", "slip"}
        State evolution law (static data need the ageing law: the slip law does not heal at
        rest).
    stiffness : float
        Machine stiffness per unit normal force for time series, 1/m; ``inf``: kinematic.
    damping : float
        Radiation damping ``eta/sigma`` for time series, s/m.
    regularized : bool
        Regularised (``asinh``) law, needed for holds on a kinematic machine.
    series : callable
        Time-series model; default :func:`rsf_series`.
    """

    v0: float | None = None
    state_law: str = "ageing"
    stiffness: float = math.inf
    damping: float = 0.0
    regularized: bool = False
    series: Callable[[RSFModel, Mapping[str, float], SeriesData], Array] = rsf_series
    name: str = field(default="rsf", init=False)

    def __post_init__(self) -> None:
        if self.v0 is not None:
            object.__setattr__(self, "v0", check_scalar("v0", self.v0, 0.0, lo_open=True))
        check_choice("state_law", self.state_law, STATE_LAWS)
        k, eta, _ = check_spring(self.stiffness, self.damping)
        object.__setattr__(self, "stiffness", k)
        object.__setattr__(self, "damping", eta)

    def options(self) -> dict[str, Any]:
        return {"v0": self.v0, "state_law": self.state_law, "stiffness": self.stiffness,
                "damping": self.damping, "regularized": self.regularized}

    def resolve(self, datasets: Sequence[Dataset]) -> RSFModel:
        """Fill in ``v0`` from the data where it may be (see the class docstring)."""
        kinds = _kinds(datasets)
        if "static" in kinds and self.state_law != "ageing":
            raise ValueError("static (healing) data need the ageing law: with the slip law "
                             "the state does not evolve at rest and mu_s does not grow")
        if self.v0 is not None:
            return self
        if "static" in kinds:
            raise ValueError("rate-and-state static (healing) data need v0 (--v0): the "
                             "sliding and reloading velocity of the hold tests, m/s")
        series = [d for d in datasets if isinstance(d, SeriesData)]
        if series:
            v0 = float(series[0].v_load[0])
        else:
            v0 = float(np.exp(np.mean(np.log(np.concatenate([d.x for d in datasets])))))
        return dataclasses.replace(self, v0=v0)

    def parameters(self, kinds: frozenset[str]) -> tuple[ParamSpec, ...]:
        mu0 = ParamSpec("mu0", "", False, -5.0, 5.0)
        a = ParamSpec("a", "", True, 1e-6, 1.0)
        b = ParamSpec("b", "", True, 1e-6, 1.0)
        dc = ParamSpec("dc", "m", True, 1e-12, 1.0)
        if kinds == {"steady"}:
            return mu0, ParamSpec("a_minus_b", "", False, -1.0, 1.0)
        if kinds == {"static"}:
            return mu0, b, dc
        return mu0, a, b, dc

    def notes(self, kinds: frozenset[str]) -> list[str]:
        n = [f"v0 = {self.v0:g} m/s fixed (reference velocity)"]
        if kinds == {"steady"}:
            n.append("steady-state data determine only a - b and mu0 (mu_ss = mu0 + (a - b) "
                     "ln(V/V0), Ruina 1983): a, b and Dc separately need transients")
        if kinds == {"static"}:
            n.append("static (healing) data determine mu0, b and Dc (mu_s = mu0 + b ln(1 + "
                     "t_w V0/Dc), ageing law, infinitely stiff reload at V0) but not a")
        if "series" in kinds:
            mach = "kinematic" if math.isinf(self.stiffness) else f"k = {self.stiffness:g} 1/m"
            n.append(f"time series simulated with {self.state_law} law, {mach} machine")
        return n

    def _params(self, v: Mapping[str, float]) -> RateState:
        assert self.v0 is not None
        if "a_minus_b" in v:  # only a - b enters the steady state: any a, b with that difference
            b = max(0.0, -v["a_minus_b"]) + 1.0
            return RateState(v["a_minus_b"] + b, b, 1.0, v["mu0"], self.v0)
        return RateState(v.get("a", 1.0), v["b"], v["dc"], v["mu0"], self.v0,
                         state_law=self.state_law,  # type: ignore[arg-type]
                         regularized=self.regularized)

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
        """Slips that the data probe directly, for ``dc`` (see _classify)."""
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
        kinds = _kinds(datasets)
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
        for dc in dcs:
            for a in ((0.005, 0.02) if se and not st else (max(b + amb, 1e-4),)):
                out.append({"mu0": mu0, "a": a, "b": max(a - amb, 1e-4), "dc": float(dc)})
        return out


Model = CVModel | RSFModel


# ----------------------------------------------------------------------------- results
@dataclass(frozen=True)
class ParameterEstimate:
    """One parameter of a fit.

    Attributes
    ----------
    name, unit : str
    value : float
        Best-fit value (or the fixed value). Where ``identifiability`` is not "identified" it is
        one point of a flat valley and means little: read ``profile_95``.
    fixed : bool
        Held fixed by the user.
    stderr : float or None
        Standard error from the Jacobian (delta method for log parameters); ``None`` when the
        parameter is fixed or not identified.
    interval_95 : tuple or None
        Wald 95 % interval (``theta +- q se`` in the fitted variable, mapped back; ``q`` the
        normal 97.5 % quantile with given uncertainties, Student t with ``n - p`` otherwise).
    profile_95 : tuple or None
        95 % profile-likelihood interval; ``None`` on a side the data do not bound within the
        search range (then ``search_bounds`` says how far it was searched).
    identifiability : str
        "identified", "identified (nonlinear: use profile_95)", "bounded above only",
        "bounded below only", "not identified", "poorly determined (Jacobian; no profile)",
        or "fixed".
    note : str
        A sentence saying the same in words.
    """

    name: str
    unit: str
    value: float
    fixed: bool = False
    stderr: float | None = None
    interval_95: tuple[float, float] | None = None
    profile_95: tuple[float | None, float | None] | None = None
    search_bounds: tuple[float, float] | None = None
    identifiability: str = "identified"
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)


@dataclass(frozen=True)
class FitResult:
    """The outcome of :func:`fit` (every field is also in :meth:`to_dict` / ``fit.json``).

    ``success`` is False when the optimiser did not converge (``message`` says why) or a
    parameter sits on its search bound; the values are then not to be trusted.
    """

    model: str
    options: dict[str, Any]
    parameters: tuple[ParameterEstimate, ...]
    free: tuple[str, ...]
    correlation: Array
    derived: dict[str, dict[str, Any]]
    success: bool
    status: int
    message: str
    nfev: int
    starts: tuple[dict[str, Any], ...]
    sigma_given: bool
    goodness: dict[str, Any]
    per_dataset: tuple[dict[str, Any], ...]
    information: dict[str, float]
    consistency: dict[str, Any] | None
    notes: tuple[str, ...]
    sources: tuple[str, ...]
    fitted_model: Model = field(repr=False)

    @property
    def values(self) -> dict[str, float]:
        """Best-fit (and fixed) values by name."""
        return {p.name: p.value for p in self.parameters}

    def __getitem__(self, name: str) -> ParameterEstimate:
        for p in self.parameters:
            if p.name == name:
                return p
        raise KeyError(name)

    def predict(self, data: Dataset, x: Array | None = None) -> Array:
        """The fitted model at the data's abscissae (or at ``x``, not for time series)."""
        return self.fitted_model.predict(self.values, data, x)

    def to_dict(self) -> dict[str, Any]:
        return {
            "model": self.model,
            "options": self.options,
            "success": self.success,
            "status": self.status,
            "message": self.message,
            "nfev": self.nfev,
            "parameters": {p.name: {k: v for k, v in p.to_dict().items() if k != "name"}
                           for p in self.parameters},
            "correlation": {"names": list(self.free), "matrix": self.correlation},
            "derived": self.derived,
            "uncertainties_given": self.sigma_given,
            "goodness_of_fit": self.goodness,
            "per_dataset": list(self.per_dataset),
            "information_criteria": self.information,
            "consistency": self.consistency,
            "identifiability_notes": list(self.notes),
            "data_files": list(self.sources),
            "starts": list(self.starts),
        }


# ----------------------------------------------------------------------------- the engine
class _Problem:
    """Residuals of a model on data sets, in the fitted (internal) variables."""

    def __init__(self, model: Model, datasets: Sequence[Dataset], specs: Sequence[ParamSpec],
                 fixed: Mapping[str, float]) -> None:
        self.model, self.datasets, self.specs = model, list(datasets), list(specs)
        self.fixed = dict(fixed)
        self.sigma_given = all(d.sigma is not None for d in datasets)
        self.w = [1.0 / d.sigma if self.sigma_given else np.ones(len(d))  # type: ignore[operator]
                  for d in datasets]
        self.n = sum(len(d) for d in datasets)
        self.p = len(specs)
        self.failures = 0

    def values(self, theta: Array) -> dict[str, float]:
        v = dict(self.fixed)
        v.update({s.name: s.from_internal(t) for s, t in zip(self.specs, theta, strict=True)})
        return v

    def split(self, theta: Array) -> list[Array]:
        v = self.values(theta)
        out = []
        for d, w in zip(self.datasets, self.w, strict=True):
            try:
                f = self.model.predict(v, d)
            except (SolverError, ValueError):
                # the simulator or a range check failed for these trial parameters (ours):
                # a large penalty makes the trust region step back
                self.failures += 1
                f = d.y + 10.0 / w
            out.append((d.y - f) * w)
        return out

    def residuals(self, theta: Array) -> Array:
        r = np.concatenate(self.split(theta))
        return np.where(np.isfinite(r), r, 1e6)

    @property
    def bounds(self) -> tuple[Array, Array]:
        lo, hi = zip(*(s.bounds for s in self.specs), strict=True)
        return np.array(lo), np.array(hi)

    def diff_step(self) -> float | None:
        if not any(isinstance(d, SeriesData) for d in self.datasets):
            return None
        return float(getattr(self.model, "diff_step", 1e-5))

    def solve(self, theta0: Array, free: NDArray[np.bool_] | None = None,
              max_nfev: int | None = None) -> tuple[Array, float, Any]:
        """Minimise over the ``free`` entries of theta (all by default) from ``theta0``."""
        lo, hi = self.bounds
        free = np.ones(self.p, bool) if free is None else free
        theta0 = np.clip(theta0, lo, hi)
        if not np.any(free):
            r = self.residuals(theta0)
            return theta0, 0.5 * float(r @ r), None
        full = theta0.copy()

        def res(x: Array) -> Array:
            full[free] = x
            return self.residuals(full)

        x0 = np.clip(theta0[free], lo[free] + 1e-12, hi[free] - 1e-12)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            tol = 1e-12 if self.diff_step() in (None, 1e-5) else 1e-6  # staircase: see CVModel
            sol = least_squares(res, x0, bounds=(lo[free], hi[free]), method="trf",
                                x_scale="jac", ftol=tol, xtol=tol, gtol=1e-10,
                                diff_step=self.diff_step(),
                                max_nfev=max_nfev or 200 * (int(free.sum()) + 1))
        out = theta0.copy()
        out[free] = sol.x
        return out, float(sol.cost), sol

    def jacobian(self, theta: Array) -> Array:
        """Central-difference Jacobian of the residuals in the internal variables."""
        ds = self.diff_step()
        h0 = (ds if ds > 1e-5 else 1e-4) if ds else 1e-6
        lo, hi = self.bounds
        J = np.empty((self.n, self.p))
        for j in range(self.p):
            h = h0 * max(1.0, abs(theta[j]))
            tp, tm = theta.copy(), theta.copy()
            tp[j] = min(theta[j] + h, hi[j])
            tm[j] = max(theta[j] - h, lo[j])
            J[:, j] = (self.residuals(tp) - self.residuals(tm)) / (tp[j] - tm[j])
        return J


def _wald_se(prob: _Problem, theta: Array, s2: float) -> Array:
    """Jacobian standard errors of the internal variables (``inf`` where singular)."""
    S, Vt = np.linalg.svd(prob.jacobian(theta), full_matrices=False)[1:]
    keep = S > S[0] * 1e-10 if S.size and S[0] > 0 else np.zeros_like(S, bool)
    inv = np.where(keep, 1.0 / np.where(keep, S, 1.0) ** 2, np.inf)
    with np.errstate(invalid="ignore"):
        var = (Vt.T**2 * inv).sum(axis=1) * s2
    return np.sqrt(np.where(np.isfinite(var), var, np.inf))


def _runs_test(r: Array) -> float | None:
    """Two-sided p-value of the Wald–Wolfowitz runs test on the signs of ``r`` (in order)."""
    s = np.sign(r[r != 0])
    n1, n2 = int(np.sum(s > 0)), int(np.sum(s < 0))
    if n1 == 0 or n2 == 0 or n1 + n2 < 6:
        return None
    runs = 1 + int(np.sum(s[1:] != s[:-1]))
    n = n1 + n2
    mean = 2.0 * n1 * n2 / n + 1.0
    var = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n - 1.0))
    if var <= 0:
        return None
    return float(2.0 * stats.norm.sf(abs(runs - mean) / math.sqrt(var)))


def _information(cost: float, n: int, p: int, sigma_given: bool) -> dict[str, float]:
    """AIC, AICc and BIC from the Gaussian likelihood (constants dropped consistently)."""
    if sigma_given:
        m2ll, k = 2.0 * cost, p
    else:  # noise level estimated: -2 ln L = n ln(RSS/n) + const, one more parameter
        m2ll, k = n * math.log(max(2.0 * cost, 1e-300) / n), p + 1
    aicc = m2ll + 2 * k + (2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else math.inf)
    return {"n": n, "k": k, "minus_2_log_likelihood": m2ll, "aic": m2ll + 2 * k,
            "aicc": aicc, "bic": m2ll + k * math.log(n)}


def _fmt(x: float, unit: str) -> str:
    return f"{x:.3g}" + (f" {unit}" if unit else "")


def _profile(prob: _Problem, theta: Array, cost: float, s2: float, j: int, se: float,
             thr: float = PROFILE_THRESHOLD,
             ) -> tuple[float | None, float | None, float, float, tuple[Array, float] | None]:
    """95 % profile interval of parameter ``j`` (internal variable); ``None`` for open sides.

    Walks away from the optimum in each direction with steps starting near the Jacobian
    standard error and doubling while the profile stays flat, re-minimising over the other
    parameters from the previous point, until ``2 (cost - cost_min)/s^2`` exceeds the
    threshold (then bisects the crossing) or the search bound is reached.
    """
    spec = prob.specs[j]
    lo_b, hi_b = spec.bounds
    free = np.ones(prob.p, bool)
    free[j] = False
    better: tuple[Array, float] | None = None
    ends: list[float | None] = []
    reached: list[float] = []
    max_step = 2.3 if spec.log else 50.0 * (se if math.isfinite(se) and se > 0 else 1.0)
    for direction in (-1.0, 1.0):
        bound = lo_b if direction < 0 else hi_b
        step = se if math.isfinite(se) and se > 0 else 0.1
        step = min(max(step, 1e-3 if spec.log else 1e-9), max_step)
        prev_t, prev_d = theta.copy(), 0.0
        crossing: float | None = None
        for _ in range(60):
            x = prev_t[j] + direction * step
            at_bound = (x - bound) * direction >= 0
            t_try = prev_t.copy()
            t_try[j] = bound if at_bound else x
            t_new, c_new, _ = prob.solve(t_try, free)
            d = 2.0 * (c_new - cost) / s2
            if d < -0.05 and (better is None or c_new < better[1]):
                better = (t_new, c_new)
            if d >= thr:
                a_t, b_t = prev_t, t_new  # bisect the crossing
                a_d = prev_d
                for _ in range(6):
                    m = a_t.copy()
                    m[j] = 0.5 * (a_t[j] + b_t[j])
                    m, c_m, _ = prob.solve(m, free)
                    d_m = 2.0 * (c_m - cost) / s2
                    if d_m >= thr:
                        b_t = m
                    else:
                        a_t, a_d = m, d_m
                crossing = 0.5 * (a_t[j] + b_t[j])
                del a_d
                break
            if at_bound:
                break
            if d < thr / 8:
                step = min(2.0 * step, max_step)
            prev_t, prev_d = t_new, d
        ends.append(crossing)
        reached.append(float(t_try[j]))
    return ends[0], ends[1], reached[0], reached[1], better


_FAR = math.log(1e3)
"""A profile limit more than this far (in ln p) outside the data window counts as open."""


def _classify(s: ParamSpec, th: float, se: float, lo_c: float | None, hi_c: float | None,
              r_lo: float, r_hi: float, window: tuple[float, float] | None = None,
              z: float = _Z95) -> tuple[str, str]:
    """Identifiability label and sentence from a parameter's profile (internal variables).

    ``window`` is the range of the parameter the data probe directly (for ``t0`` the waiting
    times, for ``V*`` the velocities, for ``Dc`` the slips ``V0 t_w``). A profile limit more
    than three decades outside it rests only on the model's higher-order curvature (e.g.
    ``t0`` far below the shortest waiting time, where eq. 27 is log-linear in ``t_w``): that
    side is reported as practically open, with the far limit quoted (ours).
    """
    u = f" {s.unit}" if s.unit else ""
    f = s.from_internal
    far_lo = lo_c is not None and window is not None and math.log(window[0]) - lo_c > _FAR
    far_hi = hi_c is not None and window is not None and hi_c - math.log(window[1]) > _FAR
    open_lo, open_hi = lo_c is None or far_lo, hi_c is None or far_hi
    if not open_lo and not open_hi:
        assert lo_c is not None and hi_c is not None
        if math.isfinite(se) and se > 0:
            off = max(abs(th - z * se - lo_c), abs(th + z * se - hi_c))
            if off > 0.2 * z * se:
                return ("identified (nonlinear: use profile_95)",
                        f"{s.name}: the 95 % profile interval [{_fmt(f(lo_c), s.unit)}, "
                        f"{_fmt(f(hi_c), s.unit)}] differs from the Jacobian one: use it")
        return "identified", ""

    def far_side(c: float | None, reached: float) -> str:
        if c is None:
            return f"searched to {f(reached):.3g}{u} without reaching the 95 % limit"
        return (f"the 95 % profile limit {f(c):.3g}{u} is more than three decades outside "
                "the range the data probe and "
                "rests only on the model's higher-order curvature")

    if open_lo and not open_hi:
        assert hi_c is not None
        return ("bounded above only",
                f"{s.name} is only bounded above by {_fmt(f(hi_c), s.unit)} (95 % profile "
                f"likelihood); the data do not bound it from below ({far_side(lo_c, r_lo)})")
    if open_hi and not open_lo:
        assert lo_c is not None
        return ("bounded below only",
                f"{s.name} is only bounded below by {_fmt(f(lo_c), s.unit)} (95 % profile "
                f"likelihood); the data do not bound it from above ({far_side(hi_c, r_hi)})")
    return ("not identified",
            f"{s.name} is not determined by the data: below, {far_side(lo_c, r_lo)}; above, "
            f"{far_side(hi_c, r_hi)}")



def _prepare(datasets: Dataset | Iterable[Dataset], model: str | Model, alpha: float,
             creep: str, v0: float | None, state_law: str, stiffness: float,
             regularized: bool) -> tuple[list[Dataset], Model]:
    if isinstance(datasets, (StaticData, SteadyData, SeriesData)):
        datasets = [datasets]
    ds = list(datasets)
    if not ds:
        raise ValueError("no data sets to fit")
    for d in ds:
        if not isinstance(d, (StaticData, SteadyData, SeriesData)):
            raise ValueError(f"{d!r} is not a StaticData, SteadyData or SeriesData")
    if isinstance(model, str):
        check_choice("model", model, ("cv", "rsf"))
        m: Model = (CVModel(alpha, creep) if model == "cv"
                    else RSFModel(v0, state_law, stiffness, regularized=regularized))
    else:
        m = model
    if isinstance(m, RSFModel):
        m = m.resolve(ds)
    return ds, m


def fit(
    datasets: Dataset | Iterable[Dataset],
    model: str | Model = "cv",
    *,
    alpha: float = 0.13,
    creep: str = "log",
    v0: float | None = None,
    state_law: str = "ageing",
    stiffness: float = math.inf,
    regularized: bool = False,
    fix: Mapping[str, float] | None = None,
    start: Mapping[str, float] | None = None,
    multistart: bool = True,
    profile: bool = True,
    consistency: bool = True,
) -> FitResult:
    """Fit ``model`` to one or more data sets with one parameter set.

    Parameters
    ----------
    datasets : data set or iterable of them
        :class:`~dryfriction.data.StaticData`, :class:`~dryfriction.data.SteadyData`,
        :class:`~dryfriction.data.SeriesData` (SI units), e.g. from
        :func:`dryfriction.data.read_csv`.
    model : {"cv", "rsf"} or CVModel or RSFModel
        The trap model or rate-and-state friction. The keyword options below build the model
        from a name and are ignored for a model object.
    alpha, creep : float, str
        Trap model: fixed trap stiffness and creep law.
    v0, state_law, stiffness, regularized : float, str, float, bool
        Rate-and-state: reference velocity (m/s; for static data the hold tests' sliding
        velocity), state law, machine stiffness (1/m, ``inf`` kinematic) and regularised law
        for time series.
    fix : mapping, optional
        Parameters held fixed, by name (units of the parameter: ``t0`` in s, ``a0`` in m, ...).
    start : mapping, optional
        A starting point (any subset of the free parameters; the rest from the data). With
        ``multistart=False`` it is the only start.
    multistart : bool
        Also start from the data-driven guesses and keep the best fit.
    profile : bool
        Profile-likelihood intervals and identifiability (slower: about 20 fits a parameter).
    consistency : bool
        For several data sets, also fit each alone and test whether one parameter set explains
        all of them.

    Returns
    -------
    FitResult

    Raises
    ------
    ValueError
        Bad input: unknown parameter names, too few points for the free parameters, data
        kinds the model cannot use, uncertainties in some files but not all.
    """
    ds, m = _prepare(datasets, model, alpha, creep, v0, state_law, stiffness, regularized)
    kinds = _kinds(ds)
    specs_all = m.parameters(kinds)
    names = [s.name for s in specs_all]
    fix = dict(fix or {})
    for k in list(fix) + list(start or {}):
        if k not in names:
            raise ValueError(f"unknown parameter {k!r} for model {m.name} with "
                             f"{'+'.join(sorted(kinds))} data: the parameters are "
                             f"{', '.join(names)}")
    for s in specs_all:
        if s.name in fix:
            fix[s.name] = check_scalar(s.name, fix[s.name], s.lo if s.log else None,
                                       lo_open=s.log)
    specs = [s for s in specs_all if s.name not in fix]
    has_sigma = [d.sigma is not None for d in ds]
    if any(has_sigma) and not all(has_sigma):
        with_s = [d.source for d in ds if d.sigma is not None]
        without = [d.source for d in ds if d.sigma is None]
        raise ValueError(f"uncertainty columns in {', '.join(with_s)} but not in "
                         f"{', '.join(without)}: give them in every file or in none")
    n = sum(len(d) for d in ds)
    p = len(specs)
    need = p + (0 if all(has_sigma) else 1)
    if n < need:
        raise ValueError(f"{', '.join(d.source for d in ds)}: {n} points for {p} free "
                         f"parameters ({', '.join(s.name for s in specs)}): need at least {need}"
                         + ("" if all(has_sigma) else " (one more than the parameters, to "
                            "estimate the noise level)"))
    prob = _Problem(m, ds, specs, fix)

    # ---- starts
    starts_in: list[tuple[str, dict[str, float]]] = []
    guesses = m.guesses(ds)
    if start is not None:
        base = dict(guesses[0])
        base.update(start)
        starts_in.append(("given", base))
    if multistart or start is None:
        starts_in += [(f"data guess {i + 1}", g) for i, g in enumerate(guesses)]
    best: tuple[Array, float, Any] | None = None
    starts_out: list[dict[str, Any]] = []
    for label, g in starts_in:
        th0 = np.array([s.to_internal(float(np.clip(g[s.name], s.lo, s.hi))) for s in specs])
        th, cost, sol = prob.solve(th0)
        ok = sol is None or sol.status > 0
        starts_out.append({"start": label, "from": {s.name: g[s.name] for s in specs},
                           "cost": cost, "converged": ok,
                           "nfev": 0 if sol is None else int(sol.nfev),
                           "message": "" if sol is None else sol.message})
        if best is None or cost < best[1]:
            best = (th, cost, sol)
    assert best is not None
    theta, cost, sol = best
    status = 1 if sol is None else int(sol.status)
    message = "no free parameters" if sol is None else str(sol.message)
    success = status > 0 and math.isfinite(cost)
    nfev = sum(int(st["nfev"]) for st in starts_out)
    notes: list[str] = list(m.notes(kinds))
    if prob.failures and success:
        r_final = prob.residuals(theta)  # penalised at the optimum means the model failed there
        prob.failures = 0
        prob.residuals(theta)
        if prob.failures:
            success = False
            message = "the model could not be evaluated at the final parameters"
        del r_final
    if not success:
        notes.append(f"the fit did not converge: {message}")

    # ---- profiles first: a profile that finds a lower cost restarts from there
    profiles: dict[int, tuple[float | None, float | None, float, float]] = {}
    dof = n - p
    # 95 % quantile: normal with given uncertainties, Student t with the noise estimated
    z = _Z95 if prob.sigma_given or dof <= 0 else float(stats.t.ppf(0.975, dof))
    if profile and success and p:
        for _ in range(3):
            s2_try = 1.0 if prob.sigma_given else (2.0 * cost / dof if dof > 0 else math.nan)
            if not math.isfinite(s2_try):
                break
            se0 = _wald_se(prob, theta, s2_try)
            profiles, improved = {}, None
            for j in range(p):
                lo_c, hi_c, r_lo, r_hi, better = _profile(prob, theta, cost, s2_try, j,
                                                          float(se0[j]), z * z)
                if better is not None:
                    improved = better
                    break
                profiles[j] = (lo_c, hi_c, r_lo, r_hi)
            if improved is None:
                break
            theta, cost, _ = prob.solve(improved[0])
            notes.append("a profile found a better optimum than the starts did: the fit was "
                         "restarted from there")
            profiles = {}

    # ---- covariance
    s2 = 1.0 if prob.sigma_given else (2.0 * cost / dof if dof > 0 else math.nan)
    if p:
        J = prob.jacobian(theta)
        U, S, Vt = np.linalg.svd(J, full_matrices=False)
        keep = S > S[0] * 1e-10 if S.size and S[0] > 0 else np.zeros_like(S, bool)
        inv = np.where(keep, 1.0 / np.where(keep, S, 1.0) ** 2, np.inf)
        with np.errstate(invalid="ignore"):
            cov = (Vt.T * inv) @ Vt * s2 if np.all(keep) else np.full((p, p), np.inf)
        if not np.all(keep):
            notes.append("the Jacobian is singular: some parameter combinations are not "
                         "determined by the data at all")
        se = np.sqrt(np.abs(np.diag(cov)))
        with np.errstate(invalid="ignore", divide="ignore"):
            corr = cov / np.outer(se, se)
    else:
        se = np.zeros(0)
        corr = np.zeros((0, 0))
    corr = np.asarray(corr, float)
    corr.setflags(write=False)

    # ---- parameters
    lo_b, hi_b = prob.bounds if p else (np.zeros(0), np.zeros(0))
    estimates: list[ParameterEstimate] = []
    for s in specs_all:
        if s.name in fix:
            estimates.append(ParameterEstimate(s.name, s.unit, fix[s.name], fixed=True,
                                               identifiability="fixed", note="held fixed"))
            continue
        j = specs.index(s)
        val = s.from_internal(theta[j])
        sej = float(se[j])
        wald = None
        stderr = None
        if math.isfinite(sej):
            wald = (s.from_internal(theta[j] - z * sej), s.from_internal(theta[j] + z * sej))
            stderr = val * sej if s.log else sej
        ident = "identified"
        note = ""
        at_bound = min(theta[j] - lo_b[j], hi_b[j] - theta[j]) < 1e-6 * max(1.0, abs(theta[j]))
        prof: tuple[float | None, float | None] | None = None
        searched: tuple[float, float] | None = None
        if j in profiles:
            lo_c, hi_c, r_lo, r_hi = profiles[j]
            prof = (None if lo_c is None else s.from_internal(lo_c),
                    None if hi_c is None else s.from_internal(hi_c))
            searched = (s.from_internal(r_lo), s.from_internal(r_hi))
            ident, note = _classify(s, theta[j], sej, lo_c, hi_c, r_lo, r_hi,
                                    m.data_window(s.name, ds), z)
        elif not math.isfinite(sej) or (s.log and sej > 2.0):
            ident = "poorly determined (Jacobian; no profile)"
            note = (f"{s.name}: the Jacobian gives a relative error of {sej:.3g} in ln "
                    f"{s.name}; run with the profile to see what the data bound")
        if ident.startswith(("bounded", "not", "poorly")):
            stderr, wald = None, None
            notes.append(note)
        elif note:
            notes.append(note)
        if at_bound:
            notes.append(f"{s.name} = {_fmt(val, s.unit)} sits on its search bound "
                         f"[{s.lo:g}, {s.hi:g}]: the data push it out of the allowed range")
            if ident == "identified":
                success = False
        estimates.append(ParameterEstimate(s.name, s.unit, val, False, stderr, wald, prof,
                                           searched, ident, note))

    # ---- derived quantities (delta method in the internal variables)
    derived: dict[str, dict[str, Any]] = {}
    vals = prob.values(theta)
    unbounded = {e.name for e in estimates if e.identifiability.startswith(("bounded", "not",
                                                                              "poorly"))}
    for name, (dval, unit) in m.derived(vals).items():
        entry: dict[str, Any] = {"value": dval, "unit": unit, "stderr": None}
        if p and np.all(np.isfinite(se)):
            g = np.zeros(p)
            for j in range(p):
                h = 1e-6 * max(1.0, abs(theta[j]))
                tp, tm = theta.copy(), theta.copy()
                tp[j] += h
                tm[j] -= h
                g[j] = (m.derived(prob.values(tp))[name][0]
                        - m.derived(prob.values(tm))[name][0]) / (2 * h)
            entry["stderr"] = float(math.sqrt(max(g @ cov @ g, 0.0)))
        if unbounded:
            entry["note"] = f"depends on {', '.join(sorted(unbounded))}, which the data do not fix"
        derived[name] = entry
    # the data-fixed combinations: level and slope of each curve at the data's centre
    for d in ds:
        if isinstance(d, SeriesData):
            continue
        xc = float(np.exp(np.mean(np.log(d.x[d.x > 0])))) if np.any(d.x > 0) else 1.0
        xs = np.array([xc / 1.01, xc, xc * 1.01])
        f = m.predict(vals, d, xs)
        derived[f"{d.y_name} at {d.x_name} = {xc:.3g} {d.x_unit} ({d.source})"] = {
            "value": float(f[1]), "unit": ""}
        derived[f"d {d.y_name}/d ln {d.x_name} there ({d.source})"] = {
            "value": float((f[2] - f[0]) / (2 * math.log(1.01))), "unit": ""}

    # ---- goodness of fit
    parts = prob.split(theta)
    chi2 = 2.0 * cost
    goodness: dict[str, Any] = {"n": n, "free_parameters": p, "dof": dof,
                                "cost": cost, "noise_sigma": math.sqrt(s2) if s2 == s2 else None}
    if prob.sigma_given:
        goodness.update(chi2=chi2, reduced_chi2=chi2 / dof if dof > 0 else None,
                        p_value=float(stats.chi2.sf(chi2, dof)) if dof > 0 else None)
        if dof > 0 and stats.chi2.sf(chi2, dof) < 0.01:
            notes.append(f"chi2 = {chi2:.4g} for {dof} degrees of freedom (p = "
                         f"{stats.chi2.sf(chi2, dof):.2g}): the model does not describe the "
                         "data within their stated uncertainties")
    else:
        goodness.update(rms_residual=math.sqrt(2.0 * cost / n),
                        note="no uncertainties given: the noise level is estimated from the "
                             "residuals, so there is no absolute goodness-of-fit test")
    per: list[dict[str, Any]] = []
    for d, r, w in zip(ds, parts, prob.w, strict=True):
        raw = r / w
        order = np.argsort(d.x, kind="stable")
        entry2: dict[str, Any] = {
            "source": d.source, "kind": d.kind, "n": len(d),
            "rms_residual": float(np.sqrt(np.mean(raw**2))),
            "mean_residual": float(np.mean(raw)), "max_abs_residual": float(np.max(np.abs(raw))),
            "runs_test_p": _runs_test(r[order]),
        }
        if prob.sigma_given:
            entry2["chi2"] = float(r @ r)
        if entry2["runs_test_p"] is not None and entry2["runs_test_p"] < 0.01:
            notes.append(f"{d.source}: the residuals have too few sign changes (runs test p = "
                         f"{entry2['runs_test_p']:.2g}): a systematic misfit")
        per.append(entry2)
    info = _information(cost, n, p, prob.sigma_given)

    # ---- one parameter set for every data set?
    cons: dict[str, Any] | None = None
    if consistency and len(ds) > 1 and success:
        cons = _consistency(ds, m, fix, prob.sigma_given, cost, p, n)
        if cons.get("p_value") is not None and cons["p_value"] < 0.01:
            notes.append(f"one parameter set does not explain all the data sets: the joint fit "
                         f"is worse than separate fits ({cons['test']}, p = "
                         f"{cons['p_value']:.2g})")

    if not success and "did not converge" not in " ".join(notes):
        notes.append("the fit is not reliable (see the parameters on their bounds)")
    return FitResult(
        model=m.name, options=m.options(), parameters=tuple(estimates),
        free=tuple(s.name for s in specs), correlation=corr, derived=derived, success=success,
        status=status, message=message, nfev=nfev, starts=tuple(starts_out),
        sigma_given=prob.sigma_given, goodness=goodness, per_dataset=tuple(per),
        information=info, consistency=cons, notes=tuple(dict.fromkeys(notes)),
        sources=tuple(d.source for d in ds), fitted_model=m,
    )


def _consistency(ds: list[Dataset], m: Model, fix: Mapping[str, float], sigma_given: bool,
                 cost: float, p: int, n: int) -> dict[str, Any]:
    """Joint fit against separate fits of each data set (a Chow-type test, ours)."""
    sep_cost, sep_p = 0.0, 0
    for d in ds:
        specs = [s for s in m.parameters(_kinds([d])) if s.name not in fix]
        fx = {k: v for k, v in fix.items() if k in {s.name for s in m.parameters(_kinds([d]))}}
        if len(d) <= len(specs):
            return {"test": "not run", "reason": f"{d.source} has too few points to fit alone"}
        r = fit(d, m, fix=fx, profile=False, consistency=False)
        if not r.success:
            return {"test": "not run", "reason": f"the separate fit of {d.source} failed"}
        sep_cost += float(r.goodness["cost"])
        sep_p += len(r.free)
    df1 = sep_p - p
    if df1 <= 0:
        return {"test": "not run", "reason": "the joint fit has as many parameters as the "
                                             "separate fits"}
    delta = 2.0 * (cost - sep_cost)
    if sigma_given:
        pv = float(stats.chi2.sf(max(delta, 0.0), df1))
        return {"test": "chi-square difference", "delta_chi2": delta, "df": df1, "p_value": pv,
                "separate_chi2": 2.0 * sep_cost}
    df2 = n - sep_p
    if df2 <= 0:
        return {"test": "not run", "reason": "too few points for the F test"}
    F = (max(delta, 0.0) / df1) / (2.0 * sep_cost / df2)
    return {"test": "F", "F": F, "df": [df1, df2], "p_value": float(stats.f.sf(F, df1, df2)),
            "separate_rss": 2.0 * sep_cost, "joint_rss": 2.0 * cost}


def fit_static(data: StaticData, model: str | Model = "cv", **kwargs: Any) -> FitResult:
    """Fit static friction against waiting time (:func:`fit` with one StaticData)."""
    if not isinstance(data, StaticData):
        raise ValueError(f"{data!r} is not StaticData")
    return fit([data], model, **kwargs)


def fit_steady(data: SteadyData, model: str | Model = "cv", **kwargs: Any) -> FitResult:
    """Fit steady friction against velocity (:func:`fit` with one SteadyData)."""
    if not isinstance(data, SteadyData):
        raise ValueError(f"{data!r} is not SteadyData")
    return fit([data], model, **kwargs)


def fit_joint(static: StaticData, steady: SteadyData, model: str | Model = "cv",
              **kwargs: Any) -> FitResult:
    """Fit static and steady data with one parameter set (:func:`fit`)."""
    if not isinstance(static, StaticData) or not isinstance(steady, SteadyData):
        raise ValueError("fit_joint needs a StaticData and a SteadyData")
    return fit([static, steady], model, **kwargs)


def compare_models(results: Sequence[FitResult]) -> dict[str, Any]:
    """Compare fits of different models to the same data: residuals, AIC, BIC.

    ``delta_aic``/``delta_bic`` are relative to the best model; Akaike weights
    ``exp(-delta_aic/2)`` normalised. Differences below 2 do not favour either model.
    """
    srcs = {r.sources for r in results}
    if len(srcs) != 1:
        raise ValueError("model comparison needs fits to the same data files")
    aic = np.array([r.information["aic"] for r in results])
    bic = np.array([r.information["bic"] for r in results])
    w = np.exp(-(aic - aic.min()) / 2.0)
    w /= w.sum()
    out: dict[str, Any] = {}
    for r, da, db, wi in zip(results, aic - aic.min(), bic - bic.min(), w, strict=True):
        out[r.model] = {"success": r.success, "free_parameters": len(r.free),
                        "aic": r.information["aic"], "bic": r.information["bic"],
                        "delta_aic": float(da), "delta_bic": float(db), "akaike_weight": float(wi),
                        "rms_residual": [pd["rms_residual"] for pd in r.per_dataset]}
    best = results[int(np.argmin(aic))].model
    gap = np.sort(aic)[1] - aic.min() if len(aic) > 1 else math.inf
    out["verdict"] = (f"{best} is preferred (delta AIC = {gap:.3g})" if gap > 2 else
                      f"the data do not distinguish the models (delta AIC = {gap:.3g} < 2)")
    return out


# ----------------------------------------------------------------------------- figure
def plot_fit(result: FitResult, datasets: Sequence[Dataset], path: Any) -> None:
    """``fit.png``: each data set with the fitted curve (top) and the residuals (bottom)."""
    from matplotlib.figure import Figure

    from .plots.paper import save_png

    k = len(datasets)
    fig = Figure(figsize=(4.6 * k, 5.6), layout="constrained")
    axes = fig.subplots(2, k, sharex="col", squeeze=False, height_ratios=[3, 1.3])
    for i, d in enumerate(datasets):
        top, bot = axes[0, i], axes[1, i]
        f = result.predict(d)
        if isinstance(d, SeriesData):
            xs, fs = d.x, f
        else:
            pos = d.x[d.x > 0]
            lo = pos.min() if pos.size else 1e-3
            xs = np.geomspace(lo / 1.5, d.x.max() * 1.5, 200)
            fs = result.predict(d, xs)
        err = d.sigma
        top.errorbar(d.x, d.y, yerr=err, fmt="o", ms=3.5, lw=0.8, label="data")
        top.plot(xs, fs, "-", lw=1.4, label=f"{result.model} fit")
        bot.errorbar(d.x, d.y - f, yerr=err, fmt="o", ms=3.0, lw=0.8)
        bot.axhline(0.0, color="k", lw=0.6)
        if not isinstance(d, SeriesData):
            top.set_xscale("log")
        top.set_ylabel(d.y_name)
        top.set_title(str(d.source).split("/")[-1], fontsize=9)
        top.legend(fontsize=8)
        bot.set_ylabel("residual")
        bot.set_xlabel(f"{d.x_name} ({d.x_unit})")
    status = "" if result.success else "  [NOT CONVERGED]"
    fig.suptitle(", ".join(f"{p.name} = {p.value:.4g}" for p in result.parameters) + status,
                 fontsize=8)
    save_png(fig, path)
