"""The trap model seen through rate-and-state friction (the analysis is ours).

Run the standard rate-and-state experiments on the trap ensemble (reduced units, kinematic
loading: the ensemble's :class:`~dryfriction.ensemble.driving.VelocityDrive` prescribes the slider's
motion, which is an infinitely stiff machine) and fit rate-and-state friction
(:class:`~dryfriction.rsf.RateState`, ageing and slip laws) to what comes out with the least
squares of :mod:`dryfriction.fit`:

* two velocity steps from steady sliding at ``u0``: ``u0 -> f u0`` and ``u0 -> u0/f``; the
  friction time series are fitted as time series (:func:`dryfriction.fit.rsf_series`,
  kinematic machine, steady state at ``u0`` first);
* slide-hold-slide: steady sliding at ``u0``, a stationary hold of ``t_h``, reloading at
  ``u0``; the peak friction against ``t_h`` is fitted with the healing law
  ``mu_ss(u0) + b ln(1 + u0 t_h/Dc)`` (:meth:`dryfriction.rsf.RateState.hold_peak_friction`;
  Beeler, Tullis & Weeks 1994), which needs the ageing law: the slip law does not heal at rest.

The fit works in SI units (its search bounds are SI): the reduced units are mapped onto
``a0 = 1 um``, ``t0 = 1 s``, ``mu_el = 1`` (:data:`SCALES`), and the results are reported back in
reduced units: ``a``, ``b``, ``mu0`` in units of ``F_el`` (friction ``F/F_el``), ``Dc`` in ``a0``,
``V0 = u0`` in ``a0/t0``. Any other choice of scales gives the same reduced numbers.

What the trap model is expected to show (and :func:`trap_model_as_rsf` measures):

* **no direct velocity effect**: the ensemble's friction is a continuous function of slip and
  time, so a velocity step leaves it unchanged at the instant of the step (rate-and-state jumps
  by ``a ln f``). The fitted ``a`` goes to (nearly) zero; at high frequency the model's response
  to a forward shift is even softening (:func:`dryfriction.theory.stability.shift_stiffness`);
* **a finite memory**: a trap lives over a slip ``1 + p_d`` (eq. 29; ``p_d = y_c a_r``, about
  ``(1 + y_c) a0`` for small ``eps``), after which the population present at the step is
  entirely renewed; the transient ends there, it is not an exponential in slip. The shape is
  measured by the slips ``x50``, ``x90``, ``x99`` at which 50, 90, 99 % of the change is done:
  ``x99/x90 = 2`` for an exponential, close to 1 for a transient that ends;
* the steady state: ``a - b`` from the fit equals the slope of the exact steady friction
  :func:`dryfriction.theory.steady.steady_friction` (eq. 34) over the steps, ``u dmu_d/du``;
* the independent **linear prediction**
  :func:`dryfriction.theory.linear_stability.effective_rsf`: the ``a``, ``b``, ``Dc`` that
  match the model's slow linear response (``Z(lambda)`` to third order).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..ensemble.driving import Output, SimulationResult, VelocityDrive, simulate
from ..ensemble.population import Initial, Track, TrapModel
from ..fit import FitResult, RSFModel, fit
from ..fit.models import v0_note
from ..program import Segment, VelocityProgram
from ..records.data import SeriesData, StaticData
from ..rsf.driving import RSFInitial, RSFOutput, SpringSlider
from ..rsf.driving import simulate as simulate_rate_state
from ..rsf.law import RateState
from ..theory.linear_stability import effective_rsf
from ..theory.model import TRAPS_PER_A0, takes_model
from ..theory.stability import shift_stiffness
from ..theory.steady import steady_friction
from ..theory.trap import Trap
from ..theory.units import PhysicalScales
from ..validation import Array, check_scalar

__all__ = [
    "SCALES",
    "RSFTwin",
    "RSFView",
    "trap_series",
    "hold_peaks",
    "fit_rsf_twin",
    "rsf_twin_series",
    "transient_shape",
    "trap_model_as_rsf",
    "Comparison",
    "compare_protocol",
]


SCALES = PhysicalScales(a0=1e-6, t0=1.0, mu_el=1.0)
"""The SI scales the reduced runs are expressed in for the fit (any choice gives the same
reduced results; these keep ``Dc`` well inside the fitter's SI search bounds)."""


def _program(segments: Sequence[Segment | dict[str, float]] | VelocityProgram
             ) -> VelocityProgram:
    return segments if isinstance(segments, VelocityProgram) else VelocityProgram(segments)


def trap_series(model: TrapModel, track: Track, u_init: float,
                program: Sequence[Segment | dict[str, float]] | VelocityProgram,
                every_slip: float = 0.02, source: str = "trap model"
                ) -> tuple[SimulationResult, SeriesData]:
    """Run the ensemble from steady sliding at ``u_init`` through a kinematic program.

    Parameters
    ----------
    model, track : TrapModel, Track
        The traps (``mu_el`` is the unit of the friction) and their density.
    u_init : float
        Velocity of the initial steady population, ``a0/t0``.
    program : sequence of segments or VelocityProgram
        The slider's velocity program, reduced units (``a0/t0``, ``t0``, ``a0``).
    every_slip : float
        Sampling interval in slip, ``a0``.
    source : str
        Name of the data set.

    Returns
    -------
    result : SimulationResult
        The run (reduced units).
    data : SeriesData
        The same friction as a time series in SI through :data:`SCALES` (``t`` in s,
        ``v_load`` in m/s, ``mu = F/F_el``), with the velocity changes on samples.
    """
    prog = _program(program)
    res = simulate(model, VelocityDrive(prog), Initial("steady", velocity=u_init, track=track),
                   Output(every_slip=every_slip))
    vl = prog.velocity(res.t)  # right-continuous: a change is on the sample at the boundary
    data = SeriesData(res.t * SCALES.t0, vl * SCALES.velocity_scale, res.mu / model.mu_el,
                      source=source)
    return res, data


def hold_peaks(model: TrapModel, track: Track, u0: float, holds: Sequence[float],
               every_slip: float = 0.002) -> Array:
    """Peak friction (``F/F_el``) on reloading at ``u0`` after stationary holds (kinematic).

    Steady sliding at ``u0``, a hold of ``t_h`` (``t0``), then sliding at ``u0`` for
    ``2 (1 + y_c)`` a0 (longer than the memory); the largest sampled friction.
    """
    yc = Trap(model.alpha).y_c
    out = []
    for th in holds:
        res = simulate(model, VelocityDrive([Segment(0.0, float(th)),
                                             Segment(u0, slip=2.0 * (1.0 + yc))]),
                       Initial("steady", velocity=u0, track=track), Output(every_slip=every_slip))
        out.append(float(np.max(res.mu)) / model.mu_el)
    return np.asarray(out)


@dataclass(frozen=True)
class RSFTwin:
    """Rate-and-state parameters fitted to the trap model (reduced units; module docstring).

    Attributes
    ----------
    state_law : str
        "ageing" or "slip".
    data : str
        What was fitted ("steps" or "steps+holds").
    a, b, mu0 : float
        Units ``F_el`` (friction ``F/F_el``).
    dc : float
        Units ``a0``.
    v0 : float
        Reference velocity ``u0``, ``a0/t0``.
    stderr : dict
        Jacobian standard errors (same units; ``None`` where not determined).
    rms : dict
        RMS residual per data set (``F_el``).
    success : bool
        The fit converged with every parameter inside its bounds.
    notes : tuple of str
        The fitter's identifiability and goodness-of-fit notes.
    """

    state_law: str
    data: str
    a: float
    b: float
    dc: float
    mu0: float
    v0: float
    stderr: dict[str, float | None]
    rms: dict[str, float]
    success: bool
    notes: tuple[str, ...] = ()

    @property
    def params(self) -> RateState:
        """The twin as :class:`RateState` in reduced units (``a0``, ``t0``)."""
        return RateState(self.a, self.b, self.dc, self.mu0, self.v0,
                         state_law=self.state_law)  # type: ignore[arg-type]

    def to_dict(self) -> dict[str, Any]:
        return {"state_law": self.state_law, "data": self.data, "a": self.a, "b": self.b,
                "dc_a0": self.dc, "mu0": self.mu0, "v0_a0_per_t0": self.v0,
                "a_minus_b": self.a - self.b, "stderr": dict(self.stderr),
                "rms_residual": dict(self.rms), "success": self.success,
                "notes": list(self.notes)}


def _twin_from_fit(r: FitResult, law: str, what: str, u0: float) -> RSFTwin:
    v = r.values
    scale = {"a": 1.0, "b": 1.0, "mu0": 1.0, "dc": 1.0 / SCALES.a0}
    se: dict[str, float | None] = {}
    for p in r.parameters:
        se[p.name] = None if p.stderr is None else p.stderr * scale[p.name]
    # the fit ran in SI through SCALES (v0 = u0 * velocity_scale m/s); the twin is reported in
    # reduced units, so is its reference velocity: u0 a0/t0
    si = v0_note(u0 * SCALES.velocity_scale)
    notes = tuple(v0_note(u0, "a0/t0") if n == si else n for n in r.notes)
    return RSFTwin(law, what, v["a"], v["b"], v["dc"] / SCALES.a0, v["mu0"], u0, se,
                   {d["source"]: d["rms_residual"] for d in r.per_dataset}, r.success,
                   notes)


def fit_rsf_twin(series: Sequence[SeriesData], u0: float, state_law: str = "ageing",
                 peaks: StaticData | None = None, progress: Any = None) -> RSFTwin:
    """Fit rate-and-state (kinematic machine, ``V0 = u0``) to trap-model transients.

    Parameters
    ----------
    series : sequence of SeriesData
        Time series in SI through :data:`SCALES` (from :func:`trap_series`), each starting in
        steady sliding.
    u0 : float
        Reference velocity, ``a0/t0``; also the sliding and reloading velocity of ``peaks``.
    state_law : {"ageing", "slip"}
    peaks : StaticData, optional
        Slide-hold-slide peaks against hold time (s), ageing law only.
    progress : callable, optional
        The fit's ``progress(done, total, what)`` (:data:`dryfriction.fit.progress.FitProgress`).

    Returns
    -------
    RSFTwin
        In reduced units.
    """
    u0 = check_scalar("u0", u0, 0.0, lo_open=True)
    ds: list[Any] = list(series) + ([peaks] if peaks is not None else [])
    r = fit(ds, RSFModel(v0=u0 * SCALES.velocity_scale, state_law=state_law),
            profile=False, consistency=False, progress=progress)
    return _twin_from_fit(r, state_law, "steps+holds" if peaks is not None else "steps", u0)


def rsf_twin_series(params: RateState, program: VelocityProgram, t: Array,
                    u_init: float | None = None) -> Array:
    """Friction of a rate-and-state twin (reduced units) on a kinematic program, at times ``t``.

    Steady state at ``u_init`` (default the first velocity) first. Holds are exact: on a
    kinematic machine the slider does not move, the ageing law's state grows by the hold time
    (``dtheta/dt = 1`` at ``V = 0``; Dieterich 1979), the slip law's does not change (Ruina
    1983), and the friction, ``ln V`` at ``V = 0``, is undefined: NaN there. Sliding stretches
    run through :func:`dryfriction.rsf.driving.simulate`.
    """
    t = np.asarray(t, float)
    out = np.full(t.shape, np.nan)
    v = float(program.velocities[0]) if u_init is None else float(u_init)
    if not v > 0:
        raise ValueError("the program starts with a hold: give u_init (> 0)")
    theta = params.dc / v
    bounds = program.times
    for i, seg in enumerate(program.segments):
        t0, t1 = bounds[i], bounds[i + 1]
        inside = (t >= t0) & (t <= t1)
        if seg.velocity == 0.0:
            if params.state_law == "ageing":
                theta += t1 - t0
            continue
        if seg.velocity < 0.0:
            raise ValueError("backward motion is not supported by the rate-and-state twin")
        te = np.clip(t[inside] - t0, 0.0, t1 - t0)
        res = simulate_rate_state(params, SpringSlider([Segment(seg.velocity, t1 - t0)]),
                                  RSFInitial(theta=theta),
                                  RSFOutput(t_eval=np.union1d(te, [t1 - t0]), rtol=1e-9))
        if te.size:
            out[inside] = np.interp(te, res.t, res.mu)
        theta = float(res.theta[-1])
    return out


def transient_shape(x: Array, mu: Array, x_step: float) -> dict[str, float]:
    """Slips after a velocity step at which 50 % and 90 % of the friction change is done.

    ``x`` and ``mu`` after the step (the last value is taken as the new steady state).
    Returns ``x50``, ``x90``, ``x99`` (``a0`` from the step), ``x90/x50`` (3.32 for an
    exponential in slip, 1.8 for a straight line) and ``x99/x90`` (2 for an exponential, 1.1
    for a straight line; close to 1 for any transient that ends at a finite slip; ours).
    """
    sel = x >= x_step
    xs, ms = x[sel] - x_step, mu[sel]
    total = ms[-1] - ms[0]
    frac = (ms - ms[0]) / total if total != 0 else np.zeros_like(ms)
    out = {}
    for name, q in (("x50", 0.5), ("x90", 0.9), ("x99", 0.99)):
        k = int(np.argmax(frac >= q))
        if k == 0:
            out[name] = float("nan")
            continue
        f0, f1 = frac[k - 1], frac[k]
        out[name] = float(xs[k - 1] + (q - f0) / (f1 - f0) * (xs[k] - xs[k - 1]))
    out["x90_over_x50"] = out["x90"] / out["x50"]
    out["x99_over_x90"] = out["x99"] / out["x90"]
    return out


@dataclass(frozen=True)
class RSFView:
    """How well rate-and-state describes the trap model (from :func:`trap_model_as_rsf`).

    Units are reduced: friction in ``F_el``, slips and ``Dc`` in ``a0``, times in ``t0``.
    :meth:`to_dict` holds everything; the attributes are the headline numbers.
    """

    eps: float
    alpha: float
    creep: str
    u0: float
    factor: float
    traps_per_a0: float
    holds: tuple[float, ...]
    twins: dict[str, RSFTwin]
    steady: dict[str, float]
    linear: dict[str, float]
    steps: dict[str, dict[str, Any]]
    shs: dict[str, Any]
    memory: dict[str, float]
    findings: tuple[str, ...] = field(default=())
    direct: float = 0.0
    v_ref: float = 1.0

    def to_dict(self) -> dict[str, Any]:
        return {
            "units": "reduced: friction F/F_el, slips and Dc in a0, times in t0, V in a0/t0",
            "eps": self.eps, "alpha": self.alpha, "creep": self.creep, "direct": self.direct,
            "v_ref": self.v_ref, "u0": self.u0,
            "step_factor": self.factor, "traps_per_a0": self.traps_per_a0,
            "holds_t0": list(self.holds),
            "fits": {k: v.to_dict() for k, v in self.twins.items()},
            "steady": dict(self.steady), "linear_prediction": dict(self.linear),
            "steps": {k: dict(v) for k, v in self.steps.items()}, "slide_hold_slide": self.shs,
            "memory": dict(self.memory), "findings": list(self.findings),
        }


def _trap_model_as_rsf_loose(
    eps: float = 0.04,
    alpha: float = 0.13,
    u0: float = 0.1,
    factor: float = 10.0,
    holds: Sequence[float] = (1.0, 10.0, 100.0, 1000.0, 10000.0),
    traps_per_a0: float = TRAPS_PER_A0.default,  # type: ignore[assignment]
    creep: str = "log",
    every_slip: float = 0.02,
) -> RSFView:
    """:func:`trap_model_as_rsf` with the model's parameters loose (its old form): the athermal
    model ``TrapModel(alpha, eps, creep)``."""
    check_scalar("eps", eps, 0.0, lo_open=True)
    return trap_model_as_rsf(TrapModel(alpha, eps, creep), u0, factor, holds, traps_per_a0,
                             every_slip)


@takes_model(_trap_model_as_rsf_loose,
             "trap_model_as_rsf(eps, alpha, u0, factor, holds, traps_per_a0, creep, every_slip)",
             "trap_model_as_rsf(model, u0, factor, holds, traps_per_a0, every_slip)")
def trap_model_as_rsf(
    model: TrapModel,
    u0: float = 0.1,
    factor: float = 10.0,
    holds: Sequence[float] = (1.0, 10.0, 100.0, 1000.0, 10000.0),
    traps_per_a0: float = TRAPS_PER_A0.default,  # type: ignore[assignment]
    every_slip: float = 0.02,
) -> RSFView:
    """Fit rate-and-state to the trap model's velocity steps and slide-hold-slide.

    Parameters
    ----------
    model : TrapModel
        The trap model, ``model.eps > 0``; the whole model runs (with its direct effect, when
        ``model.direct > 0``); ``model.mu_el`` does not enter: friction is ``F/F_el``.
    u0 : float
        Reference velocity ``V t0/a0`` (steady sliding before each test; ``V0`` of the fit).
    factor : float
        Step size: steps ``u0 -> factor u0`` and ``u0 -> u0/factor`` (``> 1``).
    holds : sequence of float
        Hold times of slide-hold-slide, ``t0``.
    traps_per_a0 : float
        Density of the (regular) track. ``1000`` gives the steady friction to about ``1e-3``
        (checked against eq. 34 in the tests) at a fraction of a second per run.
    every_slip : float
        Sampling of the step transients, ``a0``.

    Returns
    -------
    RSFView
        Fits with the ageing law (steps; steps + hold peaks) and the slip law (steps), their
        residuals, the transient shapes, the hold peaks against the laws' predictions, the
        steady slope of eq. 34 and the linear prediction of
        :func:`dryfriction.theory.linear_stability.effective_rsf`.
    """
    eps, alpha, creep = model.eps, model.alpha, model.creep
    check_scalar("eps", eps, 0.0, lo_open=True)
    model = model.replace(mu_el=1.0)  # the view is in F/F_el: mu_el does not enter
    u0 = check_scalar("u0", u0, 0.0, lo_open=True)
    factor = check_scalar("factor", factor, 1.0, lo_open=True)
    track = Track(traps_per_a0)
    yc = Trap(alpha).y_c
    pre = 0.5  # a0 of steady sliding before each step
    post = 2.0 * (1.0 + yc)  # a0 after the step: twice the memory

    steps: dict[str, dict[str, Any]] = {}
    series: list[SeriesData] = []
    runs: list[tuple[str, float, SimulationResult, SeriesData]] = []
    for u1 in (factor * u0, u0 / factor):
        name = f"step {u0:g} -> {u1:g}"
        prog = VelocityProgram([Segment(u0, slip=pre), Segment(u1, slip=post)])
        res, data = trap_series(model, track, u0, prog, every_slip, name)
        series.append(data)
        runs.append((name, u1, res, data))

    twins = {
        "ageing": fit_rsf_twin(series, u0, "ageing"),
        "slip": fit_rsf_twin(series, u0, "slip"),
    }
    peaks = hold_peaks(model, track, u0, holds)
    peak_data = StaticData(np.asarray(holds) * SCALES.t0, peaks, source="hold peaks")
    twins["ageing_with_holds"] = fit_rsf_twin(series, u0, "ageing", peak_data)

    lin = effective_rsf(u0, model)
    lin_twin = RateState(lin["a"], lin["b"], lin["dc"], float(steady_friction(model, u0)), u0)
    for name, u1, res, _data in runs:
        i_step = int(np.argmax(res.t > pre / u0 + 1e-12))  # first sample after the step
        entry: dict[str, Any] = {
            "u_after": u1,
            "mu_before": float(res.mu[i_step - 1]),
            "mu_end": float(res.mu[-1]),
            "jump_first_sample": float(res.mu[i_step] - res.mu[i_step - 1]),
            "first_sample_slip": float(res.x[i_step] - res.x[i_step - 1]),
            "shape_trap": transient_shape(res.x, res.mu, pre),
        }
        prog = VelocityProgram([Segment(u0, slip=pre), Segment(u1, slip=post)])
        for law in ("ageing", "slip"):
            tw = twins[law]
            f = rsf_twin_series(tw.params, prog, res.t)
            entry[f"shape_rsf_{law}"] = transient_shape(res.x, f, pre)
            entry[f"rms_rsf_{law}"] = float(np.sqrt(np.mean((f - res.mu) ** 2)))
        f = rsf_twin_series(lin_twin, prog, res.t)
        entry["rms_rsf_linear_prediction"] = float(np.sqrt(np.mean((f - res.mu) ** 2)))
        entry["direct_effect_rsf_ageing"] = twins["ageing"].a * math.log(u1 / u0)
        steps[name] = entry

    mu_u0 = float(steady_friction(model, u0))
    shs: dict[str, Any] = {"holds_t0": list(holds), "peak_mu": peaks.tolist(),
                           "mu_ss_u0": mu_u0}
    for law, key in (("ageing", "ageing"), ("slip", "slip"), ("ageing_with_holds",
                                                              "ageing_with_holds")):
        pred = twins[key].params.hold_peak_friction(np.asarray(holds), u0)
        shs[f"predicted_{law}"] = pred.tolist()
        shs[f"rms_{law}"] = float(np.sqrt(np.mean((pred - peaks) ** 2)))
    pred = lin_twin.hold_peak_friction(np.asarray(holds), u0)
    shs["predicted_linear_prediction"] = pred.tolist()
    shs["rms_linear_prediction"] = float(np.sqrt(np.mean((pred - peaks) ** 2)))
    lt = np.log(np.asarray(holds))
    shs["healing_rate_dmu_dlnt"] = float(np.polyfit(lt[-3:], peaks[-3:], 1)[0]) \
        if len(holds) >= 3 else float("nan")

    h = 1e-4
    slope = float((steady_friction(model, u0 * (1 + h))
                   - steady_friction(model, u0 * (1 - h))) / (2 * h))
    chord = float((steady_friction(model, factor * u0)
                   - steady_friction(model, u0 / factor)) / (2 * math.log(factor)))
    steady = {"mu_d_u0": mu_u0, "u_dmu_du_at_u0": slope, "chord_slope_over_steps": chord,
              "eq35_slope": -1.5 * eps}
    fwd, bwd = shift_stiffness(u0, model)
    linear = {"a": lin["a"], "b": lin["b"], "dc": lin["dc"], "a_minus_b": lin["a"] - lin["b"],
              "forward_shift_stiffness": fwd, "backward_shift_stiffness": bwd}
    memory = {"one_plus_yc": 1.0 + yc}

    ta = twins["ageing"]
    findings = (
        ("no direct effect: the friction moves by " if model.direct == 0.0
         else f"direct effect A = {model.direct:g}: the friction moves by ")
        + f"{steps[runs[0][0]]['jump_first_sample']:.2g} "
        f"over the first sample after the step u0 -> {factor:g} u0, where rate-and-state jumps "
        f"by a ln f; the fitted a = {ta.a:.3g} is {ta.a / ta.b:.2g} b",
        f"a - b = {ta.a - ta.b:.4g} (ageing law) against the chord slope of eq. 34 over the steps "
        f"{chord:.4g} and the local u dmu_d/du = {slope:.4g}",
        f"b = {ta.b:.4g} = {ta.b / eps:.3g} eps; the linear prediction gives b = {lin['b']:.4g} "
        f"({lin['b'] / eps:.3g} eps) and b - a = {lin['b'] - lin['a']:.4g}",
        f"Dc = {ta.dc:.3g} a0 (ageing), {twins['slip'].dc:.3g} a0 (slip), "
        f"{twins['ageing_with_holds'].dc:.3g} a0 (ageing, steps + holds); linear prediction "
        f"{lin['dc']:.3g} a0; the transient ends after about (1 + y_c) = {1 + yc:.3g} a0",
        "the transient is not exponential in slip: it ends after a finite slip, x99 = "
        + ", ".join(f"{v['shape_trap']['x99']:.3g}" for v in steps.values())
        + f" a0 (1 + y_c = {1 + yc:.3g}); x99/x90 = "
        + ", ".join(f"{v['shape_trap']['x99_over_x90']:.2f}" for v in steps.values())
        + " (exponential 2, straight line 1.1)",
        f"hold peaks: rms misfit {shs['rms_ageing']:.3g} (ageing, steps fit), "
        f"{shs['rms_ageing_with_holds']:.3g} (ageing, joint fit), {shs['rms_slip']:.3g} (slip "
        "law: no healing at rest)",
    )
    return RSFView(eps, alpha, creep, u0, factor, traps_per_a0, tuple(float(x) for x in holds),
                   twins, steady, linear, steps, shs, memory, findings, model.direct,
                   model.v_ref)


@dataclass(frozen=True)
class Comparison:
    """A trap-model protocol run with the trap model and with its fitted rate-and-state twin.

    Attributes
    ----------
    t, x : ndarray
        Sample times (``t0``) and slider positions (``a0``) of the trap-model run.
    mu_trap, mu_rsf : ndarray
        Friction ``mu_el F/F_el`` of the trap model and of the twin (NaN during kinematic
        holds, where rate-and-state friction is undefined).
    twin : RSFTwin
        The twin's parameters (reduced units; friction in ``F_el``).
    calibration : str
        "own program" (fitted to this run) or "standard" (velocity steps and slide-hold-slide
        at the protocol's first sliding velocity, :func:`trap_model_as_rsf`).
    mu_el : float
        The protocol's ``mu_el`` (the twin's ``a``, ``b``, ``mu0`` are multiplied by it).
    """

    t: Array
    x: Array
    mu_trap: Array
    mu_rsf: Array
    twin: RSFTwin
    calibration: str
    mu_el: float
    notes: tuple[str, ...] = ()

    @property
    def misfit(self) -> dict[str, float]:
        """RMS and largest absolute difference (friction units) where the twin is defined."""
        ok = np.isfinite(self.mu_rsf)
        d = self.mu_rsf[ok] - self.mu_trap[ok]
        return {"rms": float(np.sqrt(np.mean(d * d))) if d.size else float("nan"),
                "max_abs": float(np.max(np.abs(d))) if d.size else float("nan"),
                "samples": int(d.size)}

    def to_dict(self) -> dict[str, Any]:
        tw = self.twin.to_dict()
        return {
            "units": "reduced: t in t0, slip and dc in a0, v0 in a0/t0; a, b, mu0 as friction "
                     "coefficients (times mu_el)",
            "calibration": self.calibration,
            "state_law": self.twin.state_law,
            "a": self.mu_el * self.twin.a, "b": self.mu_el * self.twin.b,
            "dc_a0": self.twin.dc, "mu0": self.mu_el * self.twin.mu0,
            "v0_a0_per_t0": self.twin.v0, "fit": tw, "misfit": self.misfit,
            "notes": list(self.notes),
        }


def compare_protocol(proto: Any, state_law: str = "ageing",
                     progress: Any = None) -> Comparison:
    """Run a trap-model protocol and its rate-and-state twin on the same program.

    The twin is fitted to the run itself when the protocol starts in steady sliding at its
    first velocity and never holds (kinematic steps: the clean comparison); otherwise it is the
    standard calibration of :func:`trap_model_as_rsf` at the first sliding velocity (ageing
    law: steps + hold peaks; slip law: steps). Only velocity drives (kinematic machines) are
    supported: a spring drive would need the twin on a spring in reduced units, not done yet.

    Parameters
    ----------
    proto : dryfriction.io.protocol.Protocol
        A trap-model protocol with ``drive.kind = "velocity"``.
    state_law : {"ageing", "slip"}

    Returns
    -------
    Comparison
    """
    from ..io.protocol import InterfaceProtocol, Protocol

    if isinstance(proto, InterfaceProtocol):  # a cv protocol too: say what compare lacks
        raise ValueError(f"{proto.source}: compare does not take an extended-interface protocol "
                         "(an [interface] table): it runs one trap-model slider (model.law = "
                         "'cv', no [interface] table) next to its rate-and-state twin")
    if not isinstance(proto, Protocol):
        raise ValueError(f"{getattr(proto, 'source', 'protocol')}: compare runs a trap-model "
                         "protocol (model.law = 'cv') next to its rate-and-state twin")
    if not isinstance(proto.drive, VelocityDrive):
        kind = "force" if type(proto.drive).__name__ == "ForceDrive" else "spring"
        raise ValueError(f"{proto.source}: drive.kind = {kind!r} is not supported by compare: "
                         "it needs drive.kind = 'velocity' (the kinematic machine)")
    if state_law not in ("ageing", "slip"):
        raise ValueError(f"state_law = {state_law!r} is not allowed: ageing or slip")
    prog = proto.drive.program
    vel = prog.velocities
    if np.any(vel < 0):
        raise ValueError(f"{proto.source}: drive.segments: backward motion is not supported by "
                         "the rate-and-state twin")
    if not np.any(vel > 0):
        raise ValueError(f"{proto.source}: drive.segments: the program never slides")
    model = proto.model

    shown = [0.0]

    def step(done: float, what: str) -> None:
        # never backwards: the fit's estimate of its total grows as it goes
        shown[0] = max(shown[0], done)
        if progress is not None:
            progress(shown[0], 100.0, what)

    # progress(percent, 100, stage): the trap model's run to 20 %, the twin's fit to 95 % (its
    # evaluations over the fit's own estimate of their total), the twin's run to 100 %: the
    # shares measured on examples/velocity_step.toml (0.7 s, 4-5 s, 0.3 s)
    res = proto.run(progress=lambda f: step(20.0 * f, "trap model"))
    step(20.0, "rate-and-state twin")
    init = proto.initial
    u_first = float(vel[vel > 0][0])
    notes: list[str] = []
    own = init.kind == "steady" and bool(np.all(vel > 0)) and init.velocity == vel[0]
    if own:
        u0 = float(vel[0])
        data = SeriesData(res.t * SCALES.t0, prog.velocity(res.t) * SCALES.velocity_scale,
                          res.mu / model.mu_el, source=proto.source)
        twin = fit_rsf_twin([data], u0, state_law, progress=lambda d, n, w: step(
            20.0 + 75.0 * min(d / max(n, 1), 1.0), f"rate-and-state twin, {w}"))
        calibration = "own program"
    else:
        u0 = float(init.velocity) if init.kind == "steady" else u_first
        view = trap_model_as_rsf(model, u0)
        twin = view.twins["ageing_with_holds" if state_law == "ageing" else "slip"]
        calibration = "standard"
        notes.append(f"twin from the standard calibration at u0 = {u0:g} (velocity steps x10 and "
                     "/10, slide-hold-slide peaks): the protocol does not start in steady "
                     "sliding at its first velocity or it holds")
    if init.kind != "steady":
        notes.append(f"the trap model starts from initial = {init.kind!r}; rate-and-state has "
                     f"no such state: the twin starts in steady sliding at u = {u0:g}")
    if np.any(vel == 0):
        notes.append("during holds on a kinematic machine rate-and-state friction (ln V) is "
                     "undefined: the twin is not drawn there; its state ages (ageing law) or "
                     "not (slip law) and the reload starts from there")
    step(95.0, "the twin's run")
    mu_rsf = model.mu_el * rsf_twin_series(twin.params, prog, res.t, u_init=u0)
    step(100.0, "done")
    return Comparison(res.t, res.x, res.mu, mu_rsf, twin, calibration, model.mu_el,
                      tuple(notes))
