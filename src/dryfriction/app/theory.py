"""The closed-form workflows: :func:`trap`, :func:`static`, :func:`steady`, :func:`stability`
(the commands of the same names). Each checks its input (one line naming the option as typed),
evaluates the theory and returns a :class:`TableOutcome`: the parameters and the columns with
their units, which the command line prints as a table or JSON. Moved here from the command line."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .checks import not_applicable
from .options import OPTIONS

__all__ = ["TableOutcome", "trap", "static", "steady", "stability", "LOAD_MAX"]

LOAD_MAX = 1e12
"""Largest mass, damping (reduced units) or duration (s) the workflows accept: far beyond any
experiment, and small enough that products with the other inputs stay finite."""

_TRAP, _STA, _STE, _STB = (OPTIONS[k] for k in ("trap", "static", "steady", "stability"))


@dataclass
class TableOutcome:
    """The values of a closed-form workflow.

    Attributes
    ----------
    title : str
        The table's title.
    params : dict
        The inputs (and, for ``trap``, every constant of the trap).
    columns : dict
        Column name -> values (one per velocity or waiting time); empty for ``trap``.
    units : dict
        Column name -> unit.
    notes : list of str
        What the numbers do not say themselves (a value replaced by its exact limit, a
        column's reading at some rows); the table prints them, the JSON keeps them.
    """

    title: str
    params: dict[str, Any]
    columns: dict[str, Any] = field(default_factory=dict)
    units: dict[str, str] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def as_dict(self) -> dict[str, Any]:
        """The parameters and the columns in one mapping (the ``--json`` output), with the
        ``units`` of every number (:mod:`dryfriction.io.units`) and the ``notes`` if any."""
        from ..io.units import THEORY_UNITS, with_units

        done = with_units({**self.params, **self.columns}, THEORY_UNITS, self.units)
        return {**done, "notes": list(self.notes)} if self.notes else done


def trap(alpha: float = _TRAP["alpha"].default) -> TableOutcome:
    """All single-trap constants and the pinning regime (``dryfriction trap``,
    :meth:`dryfriction.theory.trap.Trap.summary`). ``alpha >= 1``: no pinning; the constants
    that do not exist are ``inf``/``nan`` (``null`` in JSON)."""
    from ..theory.trap import Trap

    return TableOutcome(f"trap, alpha = {alpha:g}", Trap(alpha).summary())


def _direct_params(direct: float, v_ref: float) -> dict[str, float]:
    # given only with the direct effect, so the athermal output is unchanged
    if not direct and v_ref != _STA["v_ref"].default and math.isfinite(v_ref) and v_ref > 0:
        # taken and ignored before (a second new user's --u-ref 2 without --direct); a value
        # out of its own range is refused as such first (by the model's check)
        raise not_applicable("--u-ref", f"{v_ref:g}", "with --direct > 0", "the direct "
                             "effect's reference velocity, a0/t0", "give --direct or drop --u-ref")
    return {"direct": direct, "v_ref": v_ref} if direct else {}


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


def _one_of(reduced: Any, si: Any, names: str) -> None:
    """Exactly one of the reduced and the SI values (``names``: "--T or --t-w")."""
    if (reduced is None) == (si is None):
        raise ValueError(f"give one of {names}: " + ("both were given" if reduced is not None
                                                      else "neither was given"))


def _friction_unit(mu_el: float | None) -> str:
    return "F_el" if mu_el is None else "F/W"


def static(eps: float, T: list[float] | None = None, t_w: list[float] | None = None, *,
           alpha: float = _STA["alpha"].default, load: float = _STA["load"].default,
           hold: str = _STA["hold"].default, creep: str = _STA["creep"].default,
           t0: float | None = _STA["t0"].default, mu_el: float | None = _STA["mu_el"].default,
           direct: float = _STA["direct"].default, v_ref: float = _STA["v_ref"].default,
           pull_velocity: float | None = _STA["pull_velocity"].default) -> TableOutcome:
    """Static friction ``mu_s = F_s/F_el`` after waiting ``T = t_w/t0`` (eq. 27, our reading;
    ``dryfriction static``): :func:`dryfriction.theory.static.static_friction`; with ``t_w``
    (s) and ``t0`` (and ``mu_el``) in SI units, ``mu_s = F_s/W``
    (:func:`dryfriction.theory.units.static_friction_si`). Exactly one of ``T``, ``t_w``."""
    from ..theory.model import TrapModel
    from ..theory.static import static_friction
    from ..theory.units import static_friction_si

    _one_of(T, t_w, "--T or --t-w")
    scales = _scales("--t-w" if t_w is not None else "", None, t0, mu_el, need_a0=False)
    params: dict[str, Any] = {"eps": eps, "alpha": alpha, "load": load, "hold": hold,
                              "creep": creep, **_direct_params(direct, v_ref)}
    if direct:
        params["pull_velocity"] = pull_velocity
    elif pull_velocity is not None:
        raise not_applicable("--pull-velocity", f"{pull_velocity:g}", "with --direct > 0",
                             "without the direct effect the threshold does not depend on how "
                             "fast it is pulled", "give --direct or drop --pull-velocity")
    if scales is None:
        if mu_el is not None:
            raise ValueError("--mu-el converts the friction of SI inputs: give --t-w and --t0, "
                             "or drop it")
        model = TrapModel(alpha, eps, creep, direct=direct, v_ref=v_ref)
        mu = static_friction(model, np.asarray(T, float), load=load,
                             pull_velocity=pull_velocity, hold=hold)
        cols: dict[str, Any] = {"T": list(T or []), "mu_s": mu}
    elif direct:
        raise ValueError("--direct takes reduced inputs (--T, --u-ref and --pull-velocity in "
                         "a0/t0); in SI use dryfriction.theory.units.static_friction_si")
    else:
        mu = static_friction_si(TrapModel(alpha, eps, creep), np.asarray(t_w, float), scales,
                                load=load, hold=hold)
        params.update(t0=scales.t0, **({} if mu_el is None else {"mu_el": mu_el}))
        cols = {"t_w": list(t_w or []), "mu_s": mu}
    units = {"T": "t0", "t_w": "s", "mu_s": _friction_unit(mu_el)}
    return TableOutcome("static friction", params, cols, units)


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


def steady(eps: float, u: list[float] | None = None, V: list[float] | None = None, *,
           alpha: float = _STE["alpha"].default, creep: str = _STE["creep"].default,
           a0: float | None = _STE["a0"].default, t0: float | None = _STE["t0"].default,
           mu_el: float | None = _STE["mu_el"].default, direct: float = _STE["direct"].default,
           v_ref: float = _STE["v_ref"].default) -> TableOutcome:
    """Steady dynamic friction ``mu_d = F_d/F_el`` at reduced velocity ``u = V/V*`` (eq. 34;
    ``dryfriction steady``): :func:`dryfriction.theory.steady.steady_friction`; with ``V``
    (m/s), ``a0`` and ``t0`` (and ``mu_el``) in SI units, ``mu_d = F_d/W``
    (:func:`dryfriction.theory.units.steady_friction_si`). Exactly one of ``u``, ``V``."""
    from ..theory.model import TrapModel
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
        mu = steady_friction(TrapModel(alpha, eps, creep, direct=direct, v_ref=v_ref),
                             np.asarray(u, float))
        cols: dict[str, Any] = {"u": list(u or []), "mu_d": mu}
    elif direct:
        raise ValueError("--direct takes reduced inputs (--u and --u-ref in a0/t0); in SI use "
                         "dryfriction.theory.units.steady_friction_si")
    else:
        _velocities_in_range(np.asarray(V, float), scales.a0, scales.t0)
        mu = steady_friction_si(TrapModel(alpha, eps, creep), np.asarray(V, float), scales)
        params.update(a0=scales.a0, t0=scales.t0, **({} if mu_el is None else {"mu_el": mu_el}))
        cols = {"V": list(V or []), "mu_d": mu}
    units = {"u": "a0/t0", "V": "m/s", "mu_d": _friction_unit(mu_el)}
    return TableOutcome("steady friction", params, cols, units)


def stability(eps: float, u: list[float], *, alpha: float = _STB["alpha"].default,
              mass: float = _STB["mass"].default, damping: float = _STB["damping"].default,
              creep: str = _STB["creep"].default, direct: float = _STB["direct"].default,
              v_ref: float = _STB["v_ref"].default) -> TableOutcome:
    """Critical stiffness ``K_c`` (F_el/a0) and onset angular frequency (rad/t0) of steady sliding
    at each reduced velocity ``u`` (``dryfriction stability``:
    :func:`dryfriction.theory.linear_stability.critical_stiffness`), and for ``eps > 0`` the
    rate-and-state twin's ``K_c`` (Rice & Ruina 1983, with the model's effective a, b, Dc:
    :func:`dryfriction.analysis.rsf_stability.rsf_stability_prediction`)."""
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
            f"--M {mass:g} without --eta is ill posed: with inertia and no damping the "
            "delay at the spinodal edge makes K_c grow with the highest frequency considered, "
            "so no K_c exists; give --eta > 0 (e.g. --eta 0.1) or --direct > 0, or "
            "drop --M")
    res = [critical_stiffness(v, model, mass, damping) for v in u]
    twins = [rsf_stability_prediction(v, model, mass, damping) for v in u] if eps > 0 else []
    params = {"eps": eps, "alpha": alpha, "mass": mass, "damping": damping, "creep": creep,
              **_direct_params(direct, v_ref)}
    notes: list[str] = []
    # a stiffness within rounding of 0 (eps = 0: the forward stiffness A + edge cancels
    # exactly, K_c = 0; a new user read K_c = 1.49e-14 as a value) is 0, said in a note
    k_c, omega, fwd = ([r.critical_stiffness for r in res], [r.omega for r in res],
                       [r.forward_stiffness for r in res])
    rounded = []
    for i, r in enumerate(res):
        floor = ROUNDING * abs(r.backward_stiffness)
        if 0.0 < abs(k_c[i]) <= floor or 0.0 < abs(fwd[i]) <= floor:
            rounded.append(f"{u[i]:g}")
            if abs(k_c[i]) <= floor:
                k_c[i], omega[i] = 0.0, float("nan")
            if abs(fwd[i]) <= floor:
                fwd[i] = 0.0
    if rounded:
        notes.append(f"at u = {', '.join(rounded)} a0/t0 a stiffness within {ROUNDING:g} of "
                     "the backward stiffness (rounding) is shown as 0; K_c = 0: no onset, "
                     "omega_c undefined (NaN)")
    cols = {
        "u": list(u),
        "K_c": k_c,
        "omega_c": omega,
        "forward_stiffness": fwd,
        "backward_stiffness": [r.backward_stiffness for r in res],
        "dmu_d_du": [r.velocity_slope for r in res],
    }
    if twins:  # rate-and-state with the model's effective a, b, Dc (Rice & Ruina 1983)
        # b - a' <= 0 (velocity strengthening): the formula's negative k_c means stable at
        # every stiffness, i.e. K_c = 0 as the model's column says (a new user read -10.17)
        # with the damping, the twin's a' = a + eta u (RateState.critical_stiffness): b - a'
        # <= 0 is stable at every stiffness, whatever the sign of b - a (a second new user
        # read "velocity strengthening (b - a = 0.03776)" where the damping did it)
        cols["K_c_rsf"] = [max(t["K_c"], 0.0) for t in twins]
        stable = [(v, t) for v, t in zip(u, twins, strict=True) if t["K_c"] < 0.0]
        if stable:
            notes.append(
                "K_c_rsf = 0 where the rate-and-state twin is stable at every stiffness, "
                "b - a - eta u <= 0: " + "; ".join(
                    f"u = {v:g} a0/t0: b - a - eta u = {t['b'] - t['a'] - damping * v:.4g} F_el"
                    + (f" (b - a = {t['b'] - t['a']:.4g} F_el: the damping stabilises it)"
                       if t["b"] > t["a"] else " (velocity strengthening)")
                    for v, t in stable))
    units = {"u": "a0/t0", "K_c": "F_el/a0", "omega_c": "rad/t0",
             "forward_stiffness": "F_el/a0", "backward_stiffness": "F_el/a0",
             "dmu_d_du": "F_el t0/a0", "K_c_rsf": "F_el/a0"}
    return TableOutcome("linear stability of steady sliding", params, cols, units, notes)


ROUNDING = 1e-12
"""A stiffness of ``stability`` whose size is at most this fraction of the backward stiffness is
rounding of 0 (ours: at ``eps = 0`` the sums give 1.5e-14 to 4.5e-14 of it; a true ``K_c`` grows
as ``0.75 eps`` of it at u = 1, 7.5e-12 at ``eps = 1e-11``, so below ``eps`` of about 1e-12 the
model's own ``K_c`` is itself at the rounding's level)."""


def no_pinning_display(summary: dict[str, Any]) -> dict[str, Any]:
    """``trap``'s constants for a table: with ``alpha >= 1`` (no pinning, module
    :mod:`dryfriction.theory.trap`) there is no spinodal, no jump, no friction; a NaN or inf in
    the table would read as a failed computation (JSON keeps null)."""
    return {k: ("none (no pinning: alpha >= 1)"
                if isinstance(v, float) and not math.isfinite(v) else v)
            for k, v in summary.items()}
