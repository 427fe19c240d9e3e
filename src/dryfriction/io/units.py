"""Units of what the package writes: one convention, the same it reads, declared once as data.

The convention:

* **CSV**: the unit in the column's header, after the name, in square brackets: ``dc[m]``,
  ``t[t0]``, ``mu[1]`` (``1``: dimensionless, as SI and CF write it). This is the form the
  CSV reader takes (:mod:`dryfriction.records.data`: ``t_w[min]``, ``V[um/s]``). A column that
  holds no quantity (a label, a flag, an index, words) has a bare name and is declared so
  here (:data:`LABEL`).
* **JSON**: a top-level ``"units"`` object, key name -> unit, declaring every number of the
  document wherever its key occurs (``{"dc": "m", "a": "1", ...}``); an object that carries a
  ``"unit"`` of its own (a fitted parameter: ``{"value": ..., "unit": "m", "stderr": ...}``)
  declares its numbers itself. Not ``name[unit]`` keys: a key is how a program reads JSON
  (``doc["dc"]``), and the unit is metadata beside the name, as NetCDF's ``units`` attribute
  and the ``units`` object summary.json has always carried for its time series' columns.
  Where both speak, the ``units`` object is the declaration (an elastic loading's ``t_start``
  is in s beside its ``unit`` 1/m, that of its stiffness).
* **NetCDF** (sweep.nc): a ``units`` attribute on every variable (CF).
* **Tables**: ``name[unit]`` in the header, as the CSV header (:func:`header`); a figure's
  title that prints a value gives it with its unit (``a0 = 8.266e-07 m``).

A unit string may carry a short reading after it in parentheses (``"1/m (per unit normal
force)"``); a CSV header takes the unit alone (:func:`csv_unit`).

Reading back: :func:`read_rows` takes a CSV of ours by its bare names, in the new headers and
in the bare headers written before (kept for one release, CHANGELOG.md).
"""

from __future__ import annotations

import csv
import os
import re
from collections.abc import Iterator, Mapping
from typing import Any

from ..results import DIMENSIONLESS  # one spelling for the Python results and the files

__all__ = ["DIMENSIONLESS", "LABEL", "Units", "header", "split_header", "csv_unit",
           "labelled", "with_units", "read_rows", "undeclared", "STEP_UNITS", "RECORD_FIT_UNITS",
           "SUMMARY_UNITS", "FIT_UNITS", "COMPARE_UNITS", "SEGMENT_UNITS",
           "REPRODUCE_UNITS", "BIFURCATION_UNITS", "TRAP_BIFURCATION_UNITS", "SNAPSHOT_UNITS",
           "RECORD_UNITS", "THEORY_UNITS", "INTERFACE_SUMMARY_UNITS", "INTERFACE_LOAD_UNITS"]

LABEL = None
"""The "unit" of a column that holds no quantity: words, flags, an index (written bare)."""

Units = Mapping[str, "str | None"]
"""Name -> unit (:data:`DIMENSIONLESS` for a pure number, :data:`LABEL` for no quantity)."""

_HEADER = re.compile(r"^\s*([^\[\]]*?)\s*(?:\[\s*([^\[\]]*?)\s*\])?\s*$")


def csv_unit(unit: str) -> str:
    """The unit alone, without its reading in parentheses: ``"1/m (per unit normal force)"``
    -> ``"1/m"``; an empty unit (older tables' dimensionless) -> ``"1"``."""
    u = unit.split(" (", 1)[0].strip()
    return u or DIMENSIONLESS


def header(name: str, unit: str | None) -> str:
    """``name[unit]`` (the convention of this module), or the bare name of a label."""
    return name if unit is None else f"{name}[{csv_unit(unit)}]"


def split_header(text: str) -> tuple[str, str | None]:
    """``"dc[m]"`` -> ``("dc", "m")``; a bare ``"kind"`` -> ``("kind", None)``."""
    m = _HEADER.match(text)
    if m is None:
        return text.strip(), None
    return m.group(1).strip(), m.group(2)


def labelled(columns: Mapping[str, Any], units: Units) -> dict[str, Any]:
    """The columns with their headers in the form ``name[unit]`` (labels bare).

    Raises
    ------
    ValueError
        If a column has no declared unit: every column a user keeps carries its unit.
    """
    missing = [n for n in columns if n not in units]
    if missing:
        raise ValueError(f"no unit declared for the column(s) {', '.join(missing)} "
                         "(dryfriction.io.units)")
    return {header(n, units[n]): v for n, v in columns.items()}


def with_units(doc: Mapping[str, Any], *tables: Units) -> dict[str, Any]:
    """``doc`` with its ``"units"`` object completed by ``tables`` (the JSON convention of
    this module), which win over what ``doc`` declared; an empty unit there (the older
    tables' dimensionless) becomes ``"1"``."""
    units: dict[str, str | None] = {}
    for table in (doc.get("units") or {}, *tables):
        units.update({k: (v or DIMENSIONLESS) if v is not None else None
                      for k, v in table.items()})
    return {**doc, "units": units}


def read_rows(path: str | os.PathLike[str]) -> list[dict[str, str]]:
    """The rows of a CSV file this package wrote, keyed by bare column name: the headers
    ``name[unit]`` and, from files written before the units went into the headers, bare
    ``name`` (read for one release). Lines starting with ``#`` are skipped."""
    with open(path, encoding="utf-8", newline="") as fh:
        lines = [ln for ln in fh if not ln.startswith("#")]
    reader = csv.reader(lines)
    names = [split_header(h)[0] for h in next(reader)]
    return [dict(zip(names, row, strict=True)) for row in reader]


def _leaves(obj: Any, key: str, unit_here: bool) -> Iterator[tuple[str, Any]]:
    """``(key, number)`` for every number of a JSON document not declared by an object's
    own ``unit``; the key of an item of a list, or of an entry keyed by a file path, is its
    container's."""
    if isinstance(obj, Mapping):
        own = isinstance(obj.get("unit"), str)
        for k, v in obj.items():
            name = k if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_.]*", str(k)) else key
            yield from _leaves(v, name, own)
    elif isinstance(obj, (list, tuple)):
        for v in obj:
            yield from _leaves(v, key, unit_here)
    elif isinstance(obj, (int, float)) and not isinstance(obj, bool) and not unit_here:
        yield key, obj


def undeclared(doc: Mapping[str, Any], units: Units | None = None) -> list[str]:
    """The keys of the numbers of a JSON document whose unit is declared nowhere: not in
    ``units`` (default: the document's own ``"units"`` object) nor by an object's ``unit``."""
    table = doc.get("units") if units is None else units
    table = table if isinstance(table, Mapping) else {}
    return sorted({k for k, _ in _leaves({k: v for k, v in doc.items() if k != "units"}, "",
                                         False) if k not in table})


def _with_bounds(base: Mapping[str, str | None], *suffixes: str,
                 prefixes: tuple[str, ...] = ()) -> dict[str, str | None]:
    """``base`` and, for each quantity in it, ``name + suffix`` and ``prefix + name`` in the
    same unit (``dc_lo``, ``sigma_dc``)."""
    out = dict(base)
    for name, unit in base.items():
        if unit is None:
            continue
        out.update({name + s: unit for s in suffixes})
        out.update({p + name: unit for p in prefixes})
    return out


_RSF_PARAMETERS: dict[str, str | None] = {
    "a": DIMENSIONLESS, "b": DIMENSIONLESS, "a_minus_b": DIMENSIONLESS, "mu0": DIMENSIONLESS,
    "dc": "m", "b_over_dc": "1/m", "stiffness": "1/m (per unit normal force)",
    "trend": "1/m (friction per metre of load-point displacement)",
    "state0": "1 (ln(theta0 V/Dc))", "c": DIMENSIONLESS, "b2": DIMENSIONLESS, "dc2": "m",
}

STEP_UNITS: dict[str, str | None] = {
    **_with_bounds(_RSF_PARAMETERS, "_lo", "_hi", prefixes=("sigma_",)),
    "index": LABEL, "kind": LABEL, "t_change": "s", "v_before": "m/s", "v_after": "m/s",
    "rms": "1 (friction)", "noise": "1 (friction)", "white_noise": "1 (friction)",
    "peak_residual": "1 (friction: data minus model at the peak)",
    "n": "1 (samples)", "success": LABEL, "errors": LABEL,
    "resid_rho1": "1 (lag-1 autocorrelation of the residuals)",
    "hac_lags": "1 (samples)", "slip_before": "m", "slip_after": "m", "flags": LABEL,
    "t_change_lo": "s (95 % interval of t_change)", "t_change_hi": "s (95 % interval of t_change)",
    "normal": "Pa (N where the record gives a force: column normal_unit)",
    "normal_unit": LABEL, "normal_level": LABEL, "hold": "s", "intervals": LABEL,
    "state_law": LABEL, "initial": LABEL, "aic": DIMENSIONLESS, "bic": DIMENSIONLESS,
}
"""steps.csv (a laboratory record's per-step fit, SI; :data:`dryfriction.fit.steps.STEP_COLUMNS`).
``trend`` is the friction's slope in load-point displacement; ``stiffness`` the machine's per
unit normal force."""

SEGMENT_UNITS: dict[str, str | None] = {
    "segment": LABEL, "kind": LABEL, "t_start": "s", "t_end": "s",
    "t_from_first": "s (the segment's start from the record's first sample)",
    "duration": "s", "velocity": "m/s", "velocity_um": "um/s", "i_start": LABEL,
    "i_end": LABEL, "samples": DIMENSIONLESS,
    "confidence": "1 (the velocity change over its scatter)",
    "t_start_lo": "s (95 % interval of the change at the start, record time)",
    "t_start_hi": "s (95 % interval of the change at the start, record time)",
    "t_start_placed": LABEL,
    "t_start_p": "1 (probability that the change lies within max(1 sample, 0.5 s) of t_start;"
                 " empty where its interval reaches the end of the times searched)",
    "normal_stress": "MPa", "normal_force": "kN",
}
"""segments.csv (the load program of a record: ``record --out``, a record's ``fit``)."""

RECORD_FIT_UNITS: dict[str, str | None] = {
    **STEP_UNITS,
    **{k: v for k, v in SEGMENT_UNITS.items() if k in ("t_start", "t_end", "velocity",
                                                      "i_start", "i_end", "confidence",
                                                      "duration")},
    "t_given": "s", "sigma_t_change": "s", "start_lo": "s", "start_hi": "s",
    "consistent": LABEL,
    "start_p": SEGMENT_UNITS["t_start_p"],
    "displacement_noise": "m", "level": LABEL, "steps": LABEL, "step": LABEL,
    "rise": "1 (friction)", "mean_normal": "Pa",
    "aicc": DIMENSIONLESS, "delta_aic": DIMENSIONLESS, "delta_bic": DIMENSIONLESS,
    "resid_rho1": DIMENSIONLESS, "velocity": "m/s", "normal_level": LABEL,
    "alpha": DIMENSIONLESS, "eps": DIMENSIONLESS, "t0": "s", "a0": "m", "direct": DIMENSIONLESS,
    "v_ref": "m/s", "traps_per_a0": "1/a0",
}
"""fit.json of a laboratory record: the rows of steps.csv, the segments, the measured drive's
changes (the one machine's stiffness carries its own ``unit``)."""

RECORD_UNITS: dict[str, str | None] = {
    **RECORD_FIT_UNITS, "rows": DIMENSIONLESS, "first_line": LABEL, "time_span_s": "s",
    "resets_s": "s", "rate_changes_s": "s", "gaps_s": "s", "normal_changes_s": "s",
    "t_normal_change": "s", "normal_before": "Pa (N where the record gives a force)",
    "normal_after": "Pa (N where the record gives a force)", "velocity_read": "m/s",
}
"""``record --json``: the record as read, its load program and its steps (SI)."""

SUMMARY_UNITS: dict[str, dict[str, str | None]] = {
    "cv": {"samples": DIMENSIONLESS, "duration": "t0", "peak_mu": DIMENSIONLESS,
           "peak_t": "t0", "peak_x": "a0", "final_mu": DIMENSIONLESS,
           "mean_mu": DIMENSIONLESS, "slip": "a0", "path_length": "a0", "v_max": "a0/t0",
           "births": DIMENSIONLESS, "spinodal": DIMENSIONLESS, "exits": DIMENSIONLESS,
           "alpha": DIMENSIONLESS, "eps": DIMENSIONLESS, "mu_el": "1 (F_el/W)",
           "traps_per_a0": "1/a0", "velocity": "a0/t0", "force": "F_el",
           "t": "t0", "time": "t0", "duration_t0": "t0", "stiffness": "F_el/a0",
           "mass": "F_el t0^2/a0", "damping": "F_el t0/a0", "seed": LABEL,
           "direct": DIMENSIONLESS, "v_ref": "a0/t0", "wall_s": "s", "rate": "F_el/t0",
           "load": "F_el", "x": "a0", "dt": "t0", "every": "t0", "snapshots": "t0",
           "u": "a0/t0", "x_pull": "a0", "f": "F_el", "hold": "t0",
           # the force drive's threshold and the spring drive's slips (a second new user
           # found them without units)
           "max_force": "F_el", "threshold_mu": "1 (friction: F/W with mu_el, else F/F_el)",
           "threshold_t": "t0", "slip_event_threshold": "a0", "slip_events": DIMENSIONLESS,
           "largest_sample_slip": "a0"},
    "rsf": {"samples": DIMENSIONLESS, "duration": "s", "peak_mu": DIMENSIONLESS,
            "peak_t": "s", "peak_x": "m", "final_mu": DIMENSIONLESS,
            "mean_mu": DIMENSIONLESS, "slip": "m", "path_length": "m", "v_max": "m/s",
            "steps": DIMENSIONLESS, "rejected_steps": DIMENSIONLESS,
            "rhs_evaluations": DIMENSIONLESS, "stiffness_per_m": "1/m",
            "damping_s_per_m": "s/m", "mass_s2_per_m": "s^2/m", "rtol": DIMENSIONLESS,
            "critical_stiffness_per_m": "1/m", "a": DIMENSIONLESS, "b": DIMENSIONLESS,
            "b2": DIMENSIONLESS, "c": DIMENSIONLESS, "mu0": DIMENSIONLESS, "dc": "m",
            "dc2": "m", "v0": "m/s", "wall_s": "s", "velocity": "m/s", "v1": "m/s",
            "v2": "m/s", "t1": "s", "t2": "s", "hold": "s", "v_init": "m/s",
            "stiffness": "1/m", "damping": "s/m", "mass": "s^2/m", "dt": "s",
            "every": "s", "t": "s", "time": "s", "rate": "1/s", "theta0": "s",
            "x": "m", "v": "m/s"},
}
"""summary.json of ``simulate`` (a trap-model run: reduced units; a rate-and-state one: SI)
and of ``rsf``: the run's summary and the parameters it ran with."""

FIT_UNITS: dict[str, str | None] = {
    "status": LABEL, "nfev": DIMENSIONLESS, "aic": DIMENSIONLESS, "aicc": DIMENSIONLESS,
    "bic": DIMENSIONLESS, "chi2": DIMENSIONLESS, "reduced_chi2": DIMENSIONLESS,
    "cost": DIMENSIONLESS, "minus_2_log_likelihood": DIMENSIONLESS, "p_value": DIMENSIONLESS,
    "runs_test_p": DIMENSIONLESS, "noise_sigma": "1 (friction)",
    "rms_residual": "1 (friction)", "max_abs_residual": "1 (friction)",
    "mean_residual": "1 (friction)", "n": DIMENSIONLESS, "dof": DIMENSIONLESS,
    "free_parameters": DIMENSIONLESS, "k": "1 (free parameters)", "matrix": DIMENSIONLESS,
    "v0": "m/s", "damping": "s/m", "stiffness": "1/m", "alpha": DIMENSIONLESS,
    "traps_per_a0": "1/a0", "direct": DIMENSIONLESS, "v_ref": "m/s",
    "delta_aic": DIMENSIONLESS, "delta_bic": DIMENSIONLESS, "weight": DIMENSIONLESS,
    "akaike_weight": DIMENSIONLESS, "statistic": DIMENSIONLESS, "df": DIMENSIONLESS,
    "p": DIMENSIONLESS, "evidence_ratio": DIMENSIONLESS, "lr": DIMENSIONLESS,
    "delta_chi2": DIMENSIONLESS, "separate_chi2": DIMENSIONLESS,
}
"""fit.json of the project's CSV files (``fit DATA.csv``), beyond the fitted parameters (each
of which carries its ``unit``: the table is completed with them, :func:`fit_units`)."""

COMPARE_UNITS: dict[str, str | None] = {
    "a": DIMENSIONLESS, "b": DIMENSIONLESS, "a_minus_b": DIMENSIONLESS,
    "mu0": "1 (friction in F_el: times mu_el for F/W)", "dc_a0": "a0", "dc": "a0",
    "v0_a0_per_t0": "a0/t0", "rms_residual": "1 (friction)", "rms": "1 (friction)",
    "max_abs": "1 (friction)", "samples": DIMENSIONLESS,
}
"""compare.json (reduced units: the trap model's run and its rate-and-state twin)."""

REPRODUCE_UNITS: dict[str, str | None] = {
    "T": "t0", "mu_s": "1 (F_s/F_el)", "u": "a0/t0", "mu_d": "1 (F_d/F_el)",
    "alpha": DIMENSIONLESS, "alpha0": DIMENSIONLESS, "eps": DIMENSIONLESS,
    # the single trap (docs/model.md §1): positions in trap radii a, forces in Phi0/a
    "y_c": "a (trap radius)", "z_c": "a (trap radius)", "death_point": "a (trap radius)",
    "maxwell_point": "a (trap radius)", "one_plus_y_c": "a (trap radius)",
    "f_c": "Phi0/a", "f_max": "Phi0/a", "maxwell_jump": "Phi0/a", "H0": "Phi0",
    "H1": "Phi0", "H0_paper_formula": "Phi0", "contact_stiffness": "F_el/a (kappa_c a/F_el)",
    "static_slope_per_eps": DIMENSIONLESS, "dynamic_slope_per_eps": DIMENSIONLESS,
    "dieterich_eps": DIMENSIONLESS, "dieterich_C_asymptotic": "1 (D0/a0)",
    "dieterich_C_least_squares": "1 (D0/a0)",
    "dieterich_C_paper": "1 (D0/a0)", "dieterich_C_local": "1 (D0/a0)",
    "u_min": "a0/t0", "u_max": "a0/t0", "n": DIMENSIONLESS,
    "C_asymptotic": "1 (D0/a0)", "C_least_squares": "1 (D0/a0)",
    "C_paper": "1 (D0/a0)",
    "dieterich_paper_vs_asymptotic_max_gap": "1 (friction in F_el)",
    "radius_ratio": DIMENSIONLESS, "threshold_shift_p_c": "a (trap radius)",
    "death_point_p_d": "a (trap radius)",
    "mu_s_at_T_0.01": DIMENSIONLESS, "mu_s_at_T_100": DIMENSIONLESS,
    "mu_d_at_u_0.01": DIMENSIONLESS, "mu_d_at_u_100": DIMENSIONLESS,
    "eps_values": DIMENSIONLESS, "max_abs_radius_ratio": DIMENSIONLESS,
    "max_abs_mu_s": DIMENSIONLESS, "max_abs_mu_d": DIMENSIONLESS,
    "max_abs_mu_s_eps_0.01": DIMENSIONLESS, "max_abs_mu_d_eps_0.01": DIMENSIONLESS,
    "load": "F_el", "edge_d_w": "a (trap radius)", "mu_s_T_1": DIMENSIONLESS,
    "mu_s_T_100": DIMENSIONLESS, "secant_slope_per_eps_T_1_to_100": DIMENSIONLESS,
}
"""reproduce: static_friction.csv, steady_friction.csv and summary.json (reduced units)."""

THEORY_UNITS: dict[str, str | None] = {
    **{k: v for k, v in REPRODUCE_UNITS.items() if k not in ("mu_s", "mu_d")},
    "mass": "F_el t0^2/a0", "damping": "F_el t0/a0", "direct": DIMENSIONLESS,
    "v_ref": "a0/t0 (the option --u-ref)", "load": "F_el", "t0": "s", "a0": "m",
    "mu_el": "1 (F_el/W)", "pull_velocity": "a0/t0",
}
"""The inputs of trap, static, steady and stability (``--json``; their columns carry their
own units: :class:`dryfriction.app.theory.TableOutcome`) and the trap's constants."""

BIFURCATION_UNITS: dict[str, str | None] = {
    "nature": LABEL, "note": LABEL, "check": LABEL, "damping": "s/m", "mass": "s^2/m",
    "velocity": "m/s", "K_c": "1/m", "frequency": "rad/s",
    "l1": DIMENSIONLESS, "relative_l1": DIMENSIONLESS, "amp_coef": DIMENSIONLESS,
}
"""bifurcation.json's numbers beside its columns (whose units it carries in ``units``)."""

TRAP_BIFURCATION_UNITS: dict[str, str | None] = {
    "nature": LABEL, "damping": "F_el t0/a0", "mass": "F_el t0^2/a0",
    "velocity": "a0/t0", "K_c": "F_el/a0", "frequency": "rad/t0",
    "l1": "1/a0^2 (the slip component of the eigenvector of unit modulus)",
    "relative_l1": DIMENSIONLESS,
    "check": LABEL, "check_distance": "1 (|K - K_c|/K_c of the amplitude ratio)",
    "check_exponent": DIMENSIONLESS, "check_exponent_err": DIMENSIONLESS,
    "check_amp_ratio": DIMENSIONLESS,
    "check_threshold": "F_el (half peak-to-peak spring force of the last decaying start)",
    "check_K_c_shift": "1 ((K_c,sim - K_c)/K_c from the amplitude squared linear in d)",
    "check_traps_per_a0": "1/a0",
}
"""bifurcation.json and bifurcation.csv of a trap-model protocol (reduced units:
:mod:`dryfriction.analysis.trap_hopf`)."""

SNAPSHOT_UNITS: dict[str, str | None] = {
    "p": "a0 (the pair's elastic stretch)", "branch": "1 (+1 or -1)", "age": "t0",
    "radius": "a0", "force": "1 (the pair's share of the friction, as mu)",
}
"""snapshot_*.csv of a trap-model run (the pairs in contact at the snapshot's time)."""


_WORK = "F_el a0"
INTERFACE_LOAD_UNITS: dict[str, str | None] = {
    "t": "t0", "load": "F_el", "load_point": "a0", "mean_slip": "a0", "max_slip_rate": "a0/t0",
    "work_load": _WORK, "elastic_energy": _WORK, "kinetic_energy": _WORK,
    "work_friction": _WORK, "work_damping": _WORK, "work_quasi_static": _WORK,
    "energy_residual": _WORK,
}
"""load.csv of ``simulate`` for an ``[interface]`` protocol: the loading and the
energy balance over time (reduced; ``F_el`` is one block's)."""

INTERFACE_SUMMARY_UNITS: dict[str, str | None] = {
    **SUMMARY_UNITS["cv"],
    "n_elements": DIMENSIONLESS, "n_samples": DIMENSIONLESS, "t_end": "t0", "max_slip": "a0",
    "max_slip_rate": "a0/t0", "final_load": "F_el", "energy_residual_max": _WORK,
    "energy_work_load_max": _WORK, "coupling": "F_el/a0", "edge_stiffness": "F_el/a0",
    "normal_spread": DIMENSIONLESS, "density_spread": DIMENSIONLESS, "slip": "a0",
    "duration": "t0", "load_point_start": "a0", "steps": DIMENSIONLESS,
    "trap_updates": DIMENSIONLESS, "cpu_s": "s", "threads": DIMENSIONLESS, "dt_max": "t0",
    "cover_a0": "a0", "x": "element", "quasi_static_rate": "a0/t0",
    "quasi_static_steps": DIMENSIONLESS, "handovers": DIMENSIONLESS,
}
"""summary.json of ``simulate`` for an ``[interface]`` protocol (reduced units,
``F_el`` one block's)."""
