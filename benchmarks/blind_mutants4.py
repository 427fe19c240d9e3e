"""A fourth blind mutant set for issue 25's "Done when" (fresh: >= 30, killed >= 90 %).

Written against main at commit 3b88a7441b15f254902c79252ef4aa6f57a2468a (2026-11-27) by a
reviewer (branch ``blind4``) who read ``src/dryfriction`` (app/interface_outputs.py,
app/theory.py, app/ratestate.py, app/runs.py, records/data.py, records/lab.py,
records/labsteps.py, ensemble/interface.py, ensemble/interface_result.py, analysis/fronts.py,
analysis/catalogue.py, analysis/trap_hopf.py, analysis/trap_hopf_check.py, io/units.py,
io/spacetime.py, io/files.py (write_csv), theory/model.py, theory/units.py, fit/statistics.py,
fit/steps.py, rsf/law.py, rsf/spring.py, plots/fronts.py) but neither ``tests/mutants.py``,
nor any file under ``tests/``, nor the MUTANTS lists of ``benchmarks/blind_mutants.py``,
``blind_mutants2.py`` and ``blind_mutants3.py`` (only their runners and blind_mutants3's
docstring, reused here). The test files of each mutant were chosen by their names
(``ls -R tests/``). This list was committed before any mutant was run. Each mutant is an exact
text replacement whose original occurs exactly once in its file.

Run (from the repository root, one mutant at a time)::

    .venv/bin/python benchmarks/blind_mutants4.py --check             # originals unique
    .venv/bin/python benchmarks/blind_mutants4.py --no-whole          # chosen files only
    .venv/bin/python benchmarks/blind_mutants4.py --no-whole NAME ... # some

For each mutant: apply, ``pytest -x -q -p no:cacheprovider --timeout 300`` on its chosen
files, killed/survived, restore (always: :func:`benchmarks.blind_mutants.run_one`). The first
failing test of each kill is rerun on the unmutated tree. Results are appended to
``$TMPDIR/blind_mutants4_results.jsonl``. The survivors then go together through one run of
the whole default suite, each failing test rerun with each survivor alone.

The list was committed as c151fe8 before any mutant ran. Measured on 3b88a74 (2026-11-27,
2 shared cores at a load of ~13): 28 of 40 killed by their chosen files (70.0 %, Clopper-Pearson
95 % 53.5-83.4 %). ``files_csv_6_digits`` first read as killed, but by
``tests/io/test_io.py::test_ctrl_c_during_the_commit_is_delivered_after_it``, which also failed
unmutated in the runner's rerun (timing under load; it passes alone): rerun, it survived its
files, so it is counted a survivor. ``lab_repeated_time_accepted``'s failing node holds spaces
(the runner's rerun got no test): rerun in full, the kill stands (the test passes unmutated).
Second pass: the 12 survivors applied together, the whole default suite once (34.5 min: 10
failed, 2632 passed), each failing test rerun unmutated (all 10 pass) and under each survivor
alone: ``model_mu_el_zero_allowed`` (tests/ensemble/test_population.py::
test_model_rejects_bad_parameters[kwargs3-mu_el]) and ``files_csv_6_digits`` (7 tests:
tests/cli/test_bifurcation.py x2, tests/fit/test_experiment.py, tests/fit/test_identify.py,
tests/fit/test_steps.py::test_command_record_writes_steps, tests/plots/test_reproduce.py x2)
are killed; the two Ctrl-C tests (tests/io/test_io.py, tests/sweeps/test_sweep.py) failed only
under load, under no survivor alone. Whole suite: 30 of 40 killed (75.0 %, 58.8-87.3 %), under
the 90 % of the "Done when". No survivor is equivalent (each changes an output for some input);
the ten, with what a test would have to check:

* ``fronts_lengths_forward_cell`` (analysis/fronts.py): element_lengths on a NON-uniform x
  (``[0, 1, 3]`` -> ``[1, 1.5, 2]``), or an event's extent/moment there; every test grid is
  uniform, where the gap to the next element equals the cell.
* ``catalogue_right_edge_off_by_one`` (analysis/catalogue.py): precursors(edge="right",
  edge_gap=0) with an event ending on the last element; the simulator side-loads only the left
  edge, and the right branch is not exercised at its boundary.
* ``traphopf_amplitude_no_2`` (analysis/trap_hopf.py): TrapHopf.slip_amplitude against the
  half peak-to-peak of a simulated cycle near K_c (or the normal-form 2 sqrt(-beta/(omega l1))).
* ``interface_load_mean`` (ensemble/interface.py): uniform loading with N > 1: result.load ==
  sum_i K_p (P - x_i) (load.csv's declared total); at N = 1 mean == sum.
* ``interface_spread_one_sided`` (ensemble/interface.py): the blocks' normal/density factors
  with a spread straddle 1 (min < 1 < max, mean ~ 1 for large N).
* ``app_fronts_csv_low_high_swapped`` (app/interface_outputs.py): fronts.csv has speed_low <=
  speed <= speed_high where finite.
* ``app_edge_gap_default_0`` (app/interface_outputs.py): a side-loaded ``simulate`` whose edge
  block creeps below the threshold keeps its precursors (or the default edge_gap = 1 checked).
* ``data_tw_zero_refused`` (records/data.py): a static CSV with t_w = 0 is read (0 is the
  steady level), not refused.
* ``labsteps_samples_plus_one`` (records/labsteps.py): segments.csv's ``samples`` equals
  ``i_end - i_start`` (and sums to the record's rows).
* ``plotfronts_ccdf_slope`` (plots/fronts.py): the magnitude-frequency figure's fitted line has
  log-log slope 1 - alpha (the cumulative count's), read from the drawn line's data.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

# ----------------------------------------------------------------------------- test choice
# by file name only (ls -R tests/), never by their content
T_SPACETIME = ["tests/io/test_spacetime.py"]
T_OUTUNITS = ["tests/io/test_output_units.py", "tests/records/test_lab.py"]
T_FILES = ["tests/io/test_io.py", "tests/io/test_file_safety.py"]
T_FRONTS = ["tests/analysis/test_fronts.py"]
T_FRONTS_APP = ["tests/analysis/test_fronts.py", "tests/app/test_interface_outputs.py"]
T_CATALOGUE = ["tests/analysis/test_fronts.py", "tests/app/test_interface_outputs.py"]
T_TRAPHOPF = ["tests/analysis/test_trap_hopf.py"]
T_INTERFACE = ["tests/ensemble/test_interface.py"]
T_INTERFACE_APP = ["tests/ensemble/test_interface.py", "tests/app/test_interface_outputs.py"]
T_APP_IFACE = ["tests/app/test_interface_outputs.py", "tests/cli/test_interface_simulate.py"]
T_APP_THEORY = ["tests/cli/test_bad_values.py", "tests/app/test_refusals.py",
                "tests/theory/test_units.py"]
T_DATA = ["tests/io/test_data.py", "tests/io/test_invariants_units.py"]
T_LAB = ["tests/records/test_lab.py", "tests/io/test_invariants_units.py"]
T_LABSTEPS = ["tests/records/test_lab.py", "tests/records/test_segmentation_long.py"]
T_MODEL = ["tests/theory/test_model_objects.py", "tests/cli/test_bad_values.py"]
T_UNITS = ["tests/theory/test_units.py", "tests/theory/test_dieterich.py"]
T_STAT = ["tests/fit/test_fit.py", "tests/fit/test_invariants_estimators.py",
          "tests/fit/test_reported_definitions.py", "tests/fit/test_hac.py"]
T_STEPS = ["tests/fit/test_steps.py", "tests/fit/test_invariants_estimators.py",
           "tests/fit/test_reported_definitions.py"]
T_LAW = ["tests/rsf/test_rsf.py", "tests/rsf/test_invariants.py",
         "tests/rsf/test_reported_numbers.py"]
T_SPRING = ["tests/rsf/test_rsf.py", "tests/rsf/test_routes.py"]
T_PLOTFRONTS = ["tests/plots/test_fronts_figures.py"]

# ----------------------------------------------------------------------------- the mutants
# (name, file under src/dryfriction, original, mutated, why plausible, test files)
MUTANTS: list[tuple[str, str, str, str, str, list[str]]] = [
    # ---------------------------------------------------------------- io (3)
    ("spacetime_x_units_of_t", "io/spacetime.py",
     '"x": ("x", x_, {"units": str(units["x"])})',
     '"x": ("x", x_, {"units": str(units["t"])})',
     "copy-paste: the x coordinate of fields.nc carries the time's unit attribute",
     T_SPACETIME),
    ("units_segment_force_N", "io/units.py",
     '"normal_stress": "MPa", "normal_force": "kN",',
     '"normal_stress": "MPa", "normal_force": "N",',
     "segments.csv's normal-force header says N while the values are written in kN",
     T_OUTUNITS),
    ("files_csv_6_digits", "io/files.py",
     "w.writerow([repr(float(v)) if isinstance(v, (float, np.floating)) else v for v in row])",
     'w.writerow([f"{float(v):.6g}" if isinstance(v, (float, np.floating)) else v '
     "for v in row])",
     "write_csv rounds to 6 significant digits instead of full precision (round trips lose "
     "digits)", T_FILES),
    # ---------------------------------------------------------------- analysis/fronts (4)
    ("fronts_crossing_wrong_end", "analysis/fronts.py",
     "return t0 + (level - v0) / (v1 - v0) * (t1 - t0)",
     "return t0 + (v1 - level) / (v1 - v0) * (t1 - t0)",
     "the threshold crossing interpolated from the wrong end of the sample interval "
     "(arrival times off by a fraction of a sample, exact when the crossing is mid-way)",
     T_FRONTS),
    ("fronts_lengths_forward_cell", "analysis/fronts.py",
     "return 0.5 * (left + right)",
     "return right",
     "element length = the gap to the next element instead of the Voronoi cell (identical "
     "on a uniform grid; extent and moment wrong on a non-uniform one)", T_FRONTS),
    ("fronts_normal_load_times_mu_el", "analysis/fronts.py",
     "return float(np.asarray(result.x).size) / mu_el",
     "return float(np.asarray(result.x).size) * mu_el",
     "normal load N F_el/mu_el written N F_el mu_el (same at mu_el = 1; precursor ratios "
     "off by mu_el^2 otherwise)", T_FRONTS_APP),
    ("fronts_cut_off_by_one", "analysis/fronts.py",
     "cut=bool(rows.start == 0 or rows.stop == n_t)",
     "cut=bool(rows.start == 0 or rows.stop == n_t - 1)",
     "an event touching the last sample is not flagged cut (slice stop vs last index)",
     T_FRONTS),
    # ---------------------------------------------------------------- analysis/catalogue (4)
    ("catalogue_mle_log10", "analysis/catalogue.py",
     "logs = np.log(fit / lo) if fit.size else fit",
     "logs = np.log10(fit / lo) if fit.size else fit",
     "Clauset's MLE with log10 instead of ln (alpha - 1 off by ln 10)", T_CATALOGUE),
    ("catalogue_count_left", "analysis/catalogue.py",
     'count = np.searchsorted(-desc, -desc, side="right").astype(float)',
     'count = np.searchsorted(-desc, -desc, side="left").astype(float)',
     "N(>= M) off by one (0, 1, 2, ... and ties get the smallest count)", T_CATALOGUE),
    ("catalogue_ratio_at_start", "analysis/catalogue.py",
     "ratio=np.array([e.load_arrest / normal for e in arrested]),",
     "ratio=np.array([e.load_start / normal for e in arrested]),",
     "precursor ratio taken at the event's start instead of its arrest", T_CATALOGUE),
    ("catalogue_right_edge_off_by_one", "analysis/catalogue.py",
     "return bool(e.elements[-1] >= n_x - 1 - edge_gap)",
     "return bool(e.elements[-1] >= n_x - edge_gap)",
     "right-edge touch test off by one (edge_gap = 0 keeps no right-edge event)",
     T_CATALOGUE),
    # ---------------------------------------------------------------- analysis/trap_hopf (3)
    ("traphopf_amplitude_no_2", "analysis/trap_hopf.py",
     "return 2.0 * math.sqrt(r) if r > 0 else math.nan",
     "return math.sqrt(r) if r > 0 else math.nan",
     "the cycle's half peak-to-peak slip without the factor 2 of the normal form "
     "(r = 2 sqrt(-beta/(omega l1)))", T_TRAPHOPF),
    ("traphopf_l1_norm_modulus", "analysis/trap_hopf.py",
     "l1x = pt.l1 / abs(pt.q[0]) ** 2",
     "l1x = pt.l1 / abs(pt.q[0])",
     "l1 normalised by |q_x| instead of |q_x|^2 (units 1/a0 instead of 1/a0^2)",
     T_TRAPHOPF),
    ("traphopf_Fss_no_damping", "analysis/trap_hopf.py",
     "self.F_ss = self.g_u * self.mu_age_ss + self.damping * u",
     "self.F_ss = self.g_u * self.mu_age_ss",
     "the steady spring force without the damping term eta u (zero at eta = 0)",
     T_TRAPHOPF),
    # ---------------------------------------------------------------- ensemble (4)
    ("interface_load0_sum", "ensemble/interface.py",
     "load0 = float(np.sum(f)) / ks if side else float(f.sum() / n) / kp",
     "load0 = float(np.sum(f)) / ks if side else float(f.sum()) / kp",
     "uniform plate starts at sum F_i/K_p instead of mean F_i/K_p (same at N = 1)",
     T_INTERFACE),
    ("interface_load_mean", "ensemble/interface.py",
     "load[j] = float(np.sum(kp * (lp - x)))",
     "load[j] = float(np.mean(kp * (lp - x)))",
     "uniform loading's load is the mean spring force, not the total the units declare",
     T_INTERFACE_APP),
    ("interface_spread_one_sided", "ensemble/interface.py",
     "xi = rng.uniform(-1.0, 1.0, size=(2, n))",
     "xi = rng.uniform(0.0, 1.0, size=(2, n))",
     "spreads drawn in [1, 1 + s] instead of 1 +- s (mean load biased up)", T_INTERFACE),
    ("interface_residual_no_initial", "ensemble/interface_result.py",
     "return (e[\"work_load\"] - (stored - stored[0]) - e[\"work_friction\"]",
     "return (e[\"work_load\"] - stored - e[\"work_friction\"]",
     "energy residual without subtracting the initial stored energy (the plate starts "
     "stretched)", T_INTERFACE),
    # ---------------------------------------------------------------- app (3)
    ("app_fronts_csv_low_high_swapped", "app/interface_outputs.py",
     '"speed_low": np.asarray(rows["low"]),\n        "speed_high": np.asarray(rows["high"])}',
     '"speed_low": np.asarray(rows["high"]),\n        "speed_high": np.asarray(rows["low"])}',
     "fronts.csv's speed_low and speed_high columns swapped", T_APP_IFACE),
    ("app_edge_gap_default_0", "app/interface_outputs.py",
     "transient: float = 0.0, edge_gap: int = 1,",
     "transient: float = 0.0, edge_gap: int = 0,",
     "default edge gap 0: the events next to the creeping edge block drop out of "
     "precursors.csv", T_APP_IFACE),
    ("app_theory_vrange_inverted", "app/theory.py",
     "u = V / vstar",
     "u = V * vstar",
     "--V's range check converts m/s to a0/t0 the wrong way (wrong refusals)",
     T_APP_THEORY),
    # ---------------------------------------------------------------- records (6)
    ("data_day_transposed", "records/data.py",
     '"d": 86400.0,',
     '"d": 84600.0,',
     "a day typed 84600 s (digit transposition)", T_DATA),
    ("data_tw_zero_refused", "records/data.py",
     'if c == "t_w" and x < 0.0:',
     'if c == "t_w" and x <= 0.0:',
     "a waiting time of 0 (the steady level) refused", T_DATA),
    ("lab_normal_unit_swapped", "records/lab.py",
     'normal_unit = "" if normal is None else ("N" if kinds["normal"] == "force" else "Pa")',
     'normal_unit = "" if normal is None else ("Pa" if kinds["normal"] == "force" else "N")',
     "the record's normal unit label inverted (force said Pa, stress said N)", T_LAB),
    ("lab_repeated_time_accepted", "records/lab.py",
     "dec = np.flatnonzero(np.diff(t) <= 0.0)",
     "dec = np.flatnonzero(np.diff(t) < 0.0)",
     "a repeated time stamp accepted (refusal boundary < vs <=)", T_LAB),
    ("labsteps_kN_factor", "records/labsteps.py",
     'return "normal force", "kN", 1e-3',
     'return "normal force", "kN", 1e3',
     "N -> kN factor inverted in segments.csv and the table", T_LABSTEPS),
    ("labsteps_samples_plus_one", "records/labsteps.py",
     "{s.i_end - s.i_start},{conf}",
     "{s.i_end - s.i_start + 1},{conf}",
     "segments.csv's samples column off by one (inclusive end)", T_LABSTEPS),
    # ---------------------------------------------------------------- theory (2)
    ("model_mu_el_zero_allowed", "theory/model.py",
     'Parameter("mu_el", 1.0, 0.0, FRICTION_MAX, lo_open=True,',
     'Parameter("mu_el", 1.0, 0.0, FRICTION_MAX, lo_open=False,',
     "mu_el = 0 accepted (zero friction, division by mu_el downstream)", T_MODEL),
    ("units_dieterich_length_inverted", "theory/units.py",
     "return np.asarray(C, float) * self.a0",
     "return np.asarray(C, float) / self.a0",
     "D0 = C a0 written C / a0 (unit conversion inverted)", T_UNITS),
    # ---------------------------------------------------------------- fit/statistics (4)
    ("stat_t_one_sided", "fit/statistics.py",
     "float(stats.t.ppf(0.975, dof))",
     "float(stats.t.ppf(0.95, dof))",
     "the 95 % two-sided Student quantile taken one-sided (intervals too narrow)", T_STAT),
    ("stat_runs_var_n_plus_1", "fit/statistics.py",
     "var = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n - 1.0))",
     "var = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n + 1.0))",
     "Wald-Wolfowitz variance with n + 1 for n - 1 (p-value off for short series)", T_STAT),
    ("stat_aicc_sign", "fit/statistics.py",
     "(2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else math.inf)",
     "(2 * k * (k + 1) / (n - k + 1) if n - k - 1 > 0 else math.inf)",
     "AICc's correction with n - k + 1 for n - k - 1", T_STAT),
    ("stat_F_df2_joint_p", "fit/statistics.py",
     "df2 = n - sep_p",
     "df2 = n - p",
     "the F test's denominator dof from the joint fit's parameters", T_STAT),
    # ---------------------------------------------------------------- fit/steps (3)
    ("steps_noise_dof_1", "fit/steps.py",
     "return float(math.sqrt(r @ r / (mu.size - 2)))",
     "return float(math.sqrt(r @ r / (mu.size - 1)))",
     "steady noise about a fitted line with n - 1 instead of n - 2 dof", T_STEPS),
    ("steps_sigma_a_minus_b_sign", "fit/steps.py",
     'se_of(grad("a") - grad("b"))',
     'se_of(grad("a") + grad("b"))',
     "sigma(a - b) by the delta method with the gradient of a + b (covariance sign lost)",
     T_STEPS),
    ("steps_window_from_prev_start", "fit/steps.py",
     "i0 = (change[k - 1] + change[k]) // 2",
     "i0 = change[k - 1]",
     "a step's window starts at the previous change instead of half-way", T_STEPS),
    # ---------------------------------------------------------------- rsf (3)
    ("rsf_hold_theta2_no_heal", "rsf/law.py",
     "th2 = None if self.dc2 is None else self.dc2 / v + heal",
     "th2 = None if self.dc2 is None else self.dc2 / v",
     "the second state variable does not heal during a hold (two-state laws only)", T_LAW),
    ("rsf_kc_mass_a_not_ap", "rsf/law.py",
     "return (self.b - ap) / self.dc * (1.0 + mass * v * v / (ap * self.dc))",
     "return (self.b - ap) / self.dc * (1.0 + mass * v * v / (self.a * self.dc))",
     "k_c's inertial term with a instead of a' = a + eta V (same without damping)", T_LAW),
    ("rsf_init_theta2_dc", "rsf/spring.py",
     "theta2 = model.dc2 / v if self.theta2 is None else self.theta2",
     "theta2 = model.dc / v if self.theta2 is None else self.theta2",
     "the second state's steady start uses Dc instead of Dc2", T_SPRING),
    # ---------------------------------------------------------------- plots (1)
    ("plotfronts_ccdf_slope", "plots/fronts.py",
     "(m / mf.m_min) ** (1.0 - mf.alpha)",
     "(m / mf.m_min) ** (-mf.alpha)",
     "the magnitude-frequency figure draws the density's slope -alpha on the cumulative "
     "count (whose slope is 1 - alpha)", T_PLOTFRONTS),
]


# ----------------------------------------------------------------------------- the runner
def main(argv: list[str]) -> int:
    from benchmarks.blind_mutants import run_set  # the runner all sets share

    return run_set(argv, MUTANTS, "blind_mutants4_results.jsonl")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
