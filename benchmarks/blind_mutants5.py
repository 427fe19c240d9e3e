"""A fifth blind mutant set for issue 25's "Done when" (fresh: >= 30, killed >= 90 %).

Written against main at commit 22984f8113da447325b2d0f428245dc3f80fa3f2 (2026-11-27) by a
reviewer (branch ``blind5``) who read parts of ``src/dryfriction``: theory/ (direct.py,
trap.py, static.py, creep.py, stability.py, units.py), ensemble/ (thermal.py, result.py,
driving.py, interface.py, balance.py), rsf/ (stepper.py, law.py, result.py), io/ (units.py,
protocol.py, textfile.py, spacetime.py, files.py), records/ (data.py, lab.py, labsteps.py,
segmentation.py, artifacts.py, placement.py), fit/ (statistics.py, identify.py, engine.py),
analysis/ (stickslip.py, rsf_view.py, catalogue.py, rsf_hopf.py), plots/ (record.py,
report.py), app/ (ratestate.py, records.py, fitting.py, theory.py), cli/ (common.py,
records.py), sweeps/sweep.py, program.py, simulation.py, results.py and validation.py; but
neither ``tests/mutants.py``, nor any file under ``tests/``, nor the MUTANTS lists of
``benchmarks/blind_mutants.py`` .. ``blind_mutants4.py``, nor ``docs/quality.md``. Read of the
other sets: blind_mutants4.py's docstring, test-choice helpers and runner (its layout is
reused here) and blind_mutants.py's runner functions. The test files of each mutant were
chosen by their names only (``ls -R tests/``). This list was committed before any mutant was
run. Each mutant is an exact text replacement whose original occurs exactly once in its file;
each description says which output it changes, and for which input.

Run (from the repository root, one mutant at a time)::

    .venv/bin/python benchmarks/blind_mutants5.py --check             # originals unique
    .venv/bin/python benchmarks/blind_mutants5.py --no-whole          # chosen files only
    .venv/bin/python benchmarks/blind_mutants5.py --no-whole NAME ... # some

For each mutant: apply, ``pytest -x -q -p no:cacheprovider --timeout 300`` on its chosen
files, killed/survived, restore (always: :func:`benchmarks.blind_mutants.run_one`). The first
failing test of each kill is rerun on the unmutated tree. Results are appended to
``$TMPDIR/blind_mutants5_results.jsonl``. The whole-suite second pass of the survivors is the
lead's (on main).

The list was committed as 9e330de before any mutant ran. Chosen-files pass (``--no-whole``) on
9e330de (= main 22984f8 plus this file), 2026-11-27 03:47-04:32 UTC, 2 shared cores at a load
of 7-14: 23 of 40 killed (57.5 %, Clopper-Pearson 95 % 40.9-73.0 %), under the 90 % of the
"Done when". Each kill's first failing test passed on the unmutated tree (the runner's rerun),
except ``textfile_utf32_le_missed``, whose failing node's id holds spaces (the rerun got no
test): tests/io/test_textfile.py run in full unmutated passes (11 passed), so the kill stands.
The whole-suite second pass of the 17 survivors was not run here (the lead's, on main).

Killed (first failing test):

* trap_strong_minus_limits_swapped: tests/theory/test_trap.py::
  test_H0_closed_form_vs_quadrature[0.3]
* direct_log_x_no_2: tests/theory/test_direct.py::test_junction_strength_regularisation
* static_aged_lower_edge_not_scaled: tests/theory/test_static.py::test_precision_against_mpmath_eq27
* creep_max_age_log_eps_sign: tests/theory/test_creep.py::test_laws_differ_at_long_times_only
* stability_mass_term_sign_refined: tests/theory/test_stability.py::
  test_critical_stiffness_separates_growth_from_decay[0.1-1.0-0.05]
* thermal_inverse_strength_large_z_2: tests/ensemble/test_direct_inertia.py::
  test_stiff_spring_and_small_mass_follow_a_velocity_step_like_the_velocity_drive
* interface_coupling_energy_no_half: tests/ensemble/test_interface.py::
  test_energy_balance_per_step_and_per_event[uniform]
* rsf_quadrature_end_slope_unscaled: tests/rsf/test_rsf.py::
  test_velocity_step_peak_tends_to_direct_effect
* rsf_kc_inertial_term_a_not_aprime: tests/rsf/test_rsf.py::
  test_critical_stiffness_and_hopf_frequency
* protocol_rsf_damping_mass_swapped: tests/cli/test_rsf_protocol.py::
  test_stick_slip_example_is_finite_and_periodic
* textfile_utf32_le_missed: tests/io/test_textfile.py::test_each_kind_is_named (a UTF-32 case)
* labsteps_spec_absolute_time: tests/records/test_segments_csv.py::test_every_column_by_hand
* artifacts_reset_step_at_i: tests/records/test_detect.py::test_zoo_subset_rates
* identify_neff_inverted: tests/fit/test_identify.py::test_red_noise_is_not_an_unsteady_start
* engine_log_slope_ln101_as_001: tests/fit/test_reported_definitions.py::
  test_derived_slope_per_ln_velocity_is_the_derivative
* stickslip_stick_fraction_off_by_one: tests/analysis/test_stickslip_measures.py::
  test_stick_fraction_is_its_definition[3]
* granular_floor_radius_not_squared: tests/analysis/test_granular_floor.py::
  test_floor_is_one_death_at_the_spinodal[0.08]
* rsf_view_healing_first_three: tests/analysis/test_rsf_view.py::test_healing_needs_the_ageing_law
* catalogue_mmin_excluded: tests/analysis/test_fronts_generic.py::
  test_power_law_exponent_by_hand_and_scale_free
* rsf_hopf_second_state_ratio_inverted: tests/analysis/test_rsf_hopf.py::
  test_field_follows_the_package_solver[ageing-0.0-0.0-True]
* reload_time_log_not_log1p: tests/app/test_reload_time.py::
  test_reload_time_by_hand_in_both_directions
* sweep_log_axis_logspace: tests/sweeps/test_axis_units.py::
  test_log_axis_runs_from_start_to_stop_in_equal_ratios
* program_segment_index_left: tests/ensemble/test_driving.py::
  test_both_simulators_give_the_same_summary_keys_and_columns

Survived their chosen files (17), none equivalent (each changes the output its description
names), with what a test would have to check:

* hold_grid_log_not_log1p (ensemble/result.py): force_hold_grid(2.0) has 22 points, at most
  log_step apart in ln(1 + t) (a hold under 1 t0 more than one point).
* driving_substep_velocity_from_sample_start (ensemble/driving.py): a quasi-static spring run
  with the direct effect whose samples need several creep substeps, against the same run
  sampled finely (one substep a sample), or the recorded v against the last substep's slip.
* stepper_prz_no_half (rsf/stepper.py): a PRZ velocity step's transient against the
  closed-form/ODE of RateState.state_rate (the decay length of theta, or mu at a given slip).
* protocol_sweep_follows_first_segment (io/protocol.py): a stick-slip sweep protocol with two
  segments of different velocities and initial = "steady": the initial velocity is the last
  segment's.
* labsteps_force_column_factor (records/labsteps.py): a record whose normal column is a force
  (N): segments.csv's normal_force[kN] equals the mean force / 1000.
* placement_widen_multiplies (records/placement.py): placed_probability on a hand-made profile
  (cells, weights) with widen = 2: the mass within tol/2 of ``at``.
* runs_test_variance_n_plus_1 (fit/statistics.py): runs_test against the textbook
  Wald-Wolfowitz mean and variance (2 n1 n2 (2 n1 n2 - n) / (n^2 (n - 1))) on a small sign
  sequence, or against an exact permutation p-value.
* hac_bandwidth_alpha_qs_form (fit/statistics.py): hac_bandwidth on an AR(1) series of known
  rho against Andrews' Bartlett formula 1.1447 (alpha(1) n)^(1/3), alpha(1) = 4 rho^2 /
  ((1 - rho)^2 (1 + rho)^2).
* record_stiffness_halfwidth_as_se (fit/identify.py): record_stiffness on rows with known
  intervals: the standard error of ln k_i is ln(hi/lo)/(2 z), the combined interval's width.
* plot_record_velocity_time_origin (plots/record.py): smoothed_velocity on a record whose time
  starts at t0 != 0 (window times inside the record), or record.png's velocity line data.
* report_secant_ln_t_not_ln_1pt (plots/report.py): the report's secant_slope_per_eps_T_1_to_100
  equals (mu_s(100) - mu_s(1)) / (eps ln(101/2)).
* app_segments_csv_unit_dropped (app/records.py): ``record --out`` (or a record fit) on a
  record with a normal force column: segments.csv has normal_force[kN].
* app_csv_stiffness_default_fit (app/fitting.py): a project-CSV series fit without
  --stiffness runs the kinematic machine (no stiffness parameter in fit.json).
* cli_renamed_returns_new (cli/common.py): ``static --v-ref X`` (deprecated) gives the same
  table as ``--u-ref X``, not the default's.
* cli_steps_table_force_unit (cli/records.py): the printed steps table of a force record shows
  the normal force in kN (value / 1000).
* results_mean_mu_unweighted (results.py): summarize's mean_mu on a non-uniform time grid
  equals the trapezoidal time average (e.g. t = [0, 1, 3], mu = [0, 1, 0] -> 0.5, not 1/3).
* validation_gib_as_gb (validation.py): parse_bytes("8GiB") == 8 * 2**30.

Second pass (the lead, 2026-11-27, main 1321ef1: the suite after this stop's other branches,
strengthen5A, strengthen5B, fastsuite2, hopf5, interface4 and detect4, whose developers had not
seen this set). The 17 survivors, each alone, against the 21 test files strengthen5B and
interface4 added (``/tmp/blind5_new.py``, the shared ``run_one``): 4 killed
(protocol_sweep_follows_first_segment by tests/io/test_spring_point.py,
runs_test_variance_n_plus_1 by tests/fit/test_statistics_edges.py, cli_steps_table_force_unit
by tests/cli/test_records_table.py, results_mean_mu_unweighted by
tests/app/test_simulate_files.py). The other 13 applied together, the whole default suite once
(``pytest -n 2 --dist loadfile tests/``, 6 min 27 s at a load of about 2: 33 failed, 3452
passed), the 33 failing tests rerun unmutated (33 passed) and under each survivor alone: 8 more
killed, each by tests that do not only check the mutant list:
driving_substep_velocity_from_sample_start (tests/fit/test_cvfit.py x3, test_cvtail.py x2,
tests/theory/test_direct.py), stepper_prz_no_half (tests/fit/test_state_laws.py x4,
tests/analysis/test_rsf_hopf.py x2, tests/cli/test_bifurcation.py), labsteps_force_column_factor
(tests/records/test_lab.py), placement_widen_multiplies (tests/records/test_change_interval.py
x3, tests/plots/test_reported_artists.py), hac_bandwidth_alpha_qs_form
(tests/fit/test_invariants_estimators.py, test_shs.py, test_kcoverage.py),
plot_record_velocity_time_origin (tests/records/test_detect.py, tests/plots/test_plot_helpers.py;
also the mutant list's own check), cli_renamed_returns_new (tests/cli/test_help.py),
validation_gib_as_gb (tests/io/test_protocol.py x7, tests/test_validation.py).

Result: **35 of 40 killed (87.5 %, Clopper-Pearson 95 % 73.2-95.8 %)** by the suite of 1321ef1,
under the 90 % of the "Done when". Five survived everything: hold_grid_log_not_log1p,
record_stiffness_halfwidth_as_se, report_secant_ln_t_not_ln_1pt, app_segments_csv_unit_dropped,
app_csv_stiffness_default_fit (what a test would need: above).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

# ----------------------------------------------------------------------------- test choice
# by file name only (ls -R tests/), never by their content
T_TRAP = ["tests/theory/test_trap.py", "tests/theory/test_invariants.py"]
T_DIRECT = ["tests/theory/test_direct.py", "tests/theory/test_steady.py"]
T_STATIC = ["tests/theory/test_static.py", "tests/theory/test_independent_reference.py"]
T_CREEP = ["tests/theory/test_creep.py", "tests/theory/test_creep_generic.py"]
T_STAB = ["tests/theory/test_stability.py"]
T_THERMAL = ["tests/ensemble/test_direct_inertia.py", "tests/ensemble/test_invariants_steppers.py"]
T_HOLDGRID = ["tests/ensemble/test_hold_grid.py", "tests/ensemble/test_driving.py"]
T_DRIVING = ["tests/ensemble/test_driving.py", "tests/ensemble/test_invariants.py"]
T_IFACE = ["tests/ensemble/test_interface.py", "tests/ensemble/test_interface_generic.py"]
T_PRZ = ["tests/rsf/test_state_rate.py", "tests/rsf/test_rsf.py", "tests/rsf/test_invariants.py"]
T_RSFQUAD = ["tests/rsf/test_rsf.py", "tests/rsf/test_routes.py", "tests/rsf/test_invariants.py"]
T_RSFKC = ["tests/rsf/test_rsf.py", "tests/rsf/test_reported_numbers.py",
           "tests/analysis/test_rsf_hopf.py"]
T_PROTO = ["tests/io/test_protocol.py", "tests/cli/test_rsf_protocol.py"]
T_SWEEPPROTO = ["tests/sweeps/test_sweep.py", "tests/io/test_protocol.py",
                "tests/analysis/test_stickslip.py"]
T_TEXT = ["tests/io/test_textfile.py"]
T_SEGCSV = ["tests/records/test_segments_csv.py", "tests/records/test_labforms_units.py"]
T_SEGSPEC = ["tests/records/test_segments_csv.py", "tests/records/test_lab.py"]
T_RESETS = ["tests/records/test_artifacts_generic.py", "tests/records/test_detect.py"]
T_PLACE = ["tests/records/test_placement.py", "tests/records/test_segments_csv.py"]
T_RUNS = ["tests/fit/test_statistics_generic.py", "tests/fit/test_fit.py",
          "tests/fit/test_reported_definitions.py"]
T_HAC = ["tests/fit/test_hac.py", "tests/fit/test_statistics_generic.py"]
T_IDENT = ["tests/fit/test_identify.py", "tests/fit/test_identify_definitions.py"]
T_DERIVED = ["tests/fit/test_fit.py", "tests/fit/test_reported.py",
             "tests/fit/test_reported_definitions.py"]
T_KREC = ["tests/fit/test_identify.py", "tests/fit/test_machine_generic.py",
          "tests/fit/test_onemachine_generic.py"]
T_STICK = ["tests/analysis/test_stickslip.py", "tests/analysis/test_stickslip_measures.py"]
T_FLOOR = ["tests/analysis/test_granular_floor.py", "tests/analysis/test_stickslip.py"]
T_VIEW = ["tests/analysis/test_rsf_view.py", "tests/analysis/test_rsf_twin.py"]
T_CATALOGUE = ["tests/analysis/test_fronts.py", "tests/analysis/test_fronts_generic.py"]
T_RSFHOPF = ["tests/analysis/test_rsf_hopf.py", "tests/analysis/test_hopf_table_edges.py"]
T_PLOTREC = ["tests/plots/test_plots.py", "tests/plots/test_reported_artists.py"]
T_REPORT = ["tests/plots/test_report_html.py", "tests/plots/test_plots.py"]
T_RELOAD = ["tests/app/test_reload_time.py", "tests/app/test_workflows.py"]
T_APPREC = ["tests/records/test_segments_csv.py", "tests/app/test_workflows.py"]
T_APPFIT = ["tests/app/test_fit_option_edges.py", "tests/fit/test_fit.py"]
T_CLIRENAME = ["tests/cli/test_cli.py", "tests/cli/test_bad_values.py"]
T_CLIREC = ["tests/cli/test_cli.py", "tests/cli/test_reported_outcomes.py"]
T_SWEEP = ["tests/sweeps/test_sweep.py", "tests/sweeps/test_axis_units.py"]
T_PROGRAM = ["tests/test_simulator_shape.py", "tests/ensemble/test_driving.py",
             "tests/rsf/test_routes.py"]
T_RESULTS = ["tests/test_simulator_shape.py", "tests/rsf/test_summary_path.py",
             "tests/cli/test_simulate.py"]
T_BYTES = ["tests/ensemble/test_work_estimates.py", "tests/theory/test_memory.py"]

# ----------------------------------------------------------------------------- the mutants
# (name, file under src/dryfriction, original, mutated, why plausible, test files)
MUTANTS: list[tuple[str, str, str, str, str, list[str]]] = [
    # ------------------------------------------------------------------ theory/
    ("trap_strong_minus_limits_swapped", "theory/trap.py",
     "work_minus(yc, xm, alpha)",
     "work_minus(xm, yc, alpha)",
     "integration limits of the (-) branch's work swapped in work_forward: the energy the (-) "
     "branch returns is added instead; H0, H1 and every force in strong pinning "
     "(alpha0 < alpha < 1, e.g. alpha = 0.3) change; very strong pinning (alpha = 0.13) not",
     T_TRAP),
    ("direct_log_x_no_2", "theory/direct.py",
     "return np.log(np.abs(v) / (2.0 * v_ref)) + 1.0 / direct",
     "return np.log(np.abs(v) / v_ref) + 1.0 / direct",
     "asinh argument V e^{1/A}/(2 V_ref) written without the 2 in the array form: "
     "junction_strength shifted by A ln 2 (0.0069 at A = 0.01) at every V, while the scalar "
     "strength_ratio keeps the 2; junction_log_slope changes near V_c",
     T_DIRECT),
    ("static_aged_lower_edge_not_scaled", "theory/static.py",
     "- work_forward((d - 1.0) / r, alpha)",
     "- work_forward(d - 1.0, alpha)",
     "the aged population's rear edge not rescaled by the radius ratio r: pull_force and "
     "mu_s differ at every aged T > 0 (r > 1), e.g. T = 100, eps = 0.05; exact at r = 1",
     T_STATIC),
    ("creep_max_age_log_eps_sign", "theory/creep.py",
     "log_t = 1.0 / eps - math.log(eps) + math.log(gap)",
     "log_t = 1.0 / eps + math.log(eps) + math.log(gap)",
     "prefactor 1/eps of T_v taken as eps (sign of ln eps): the Eyring-Nabarro law's largest "
     "age is eps^2 times too small (max_age(0.1) off by 100), so ages are refused too early "
     "and u_min of the steady branch grows",
     T_CREEP),
    ("stability_mass_term_sign_refined", "theory/stability.py",
     "K = mass * o**2 - float(Z(np.array([1j * o]))[0].real)",
     "K = -mass * o**2 - float(Z(np.array([1j * o]))[0].real)",
     "M (i omega)^2 = -M omega^2 carried with the wrong sign in the brentq refinement of the "
     "Nyquist crossing (the linear estimate keeps it right): critical stiffness with mass > 0 "
     "is too low by 2 M omega^2; mass = 0 unchanged",
     T_STAB),
    # ------------------------------------------------------------------ ensemble/
    ("thermal_inverse_strength_large_z_2", "ensemble/thermal.py",
     "return v_ref * math.exp(z - 1.0 / direct)",
     "return 2.0 * v_ref * math.exp(z - 1.0 / direct)",
     "V = V_c sinh(y/A) for large y/A written as 2 V_ref e^{y/A - 1/A}, forgetting sinh ~ "
     "e^z/2: the inertial slider with the direct effect (y/A > 20, i.e. any sliding with "
     "A < 0.05) solves for a velocity twice too large per strength: v and mu of inertial "
     "runs with direct > 0 change",
     T_THERMAL),
    ("hold_grid_log_not_log1p", "ensemble/result.py",
     "n = max(1, math.ceil(math.log1p(hold) / log_step - 1e-9))",
     "n = max(1, math.ceil(math.log(hold) / log_step - 1e-9))",
     "number of steps of a force hold's geometric grid from ln(hold) instead of ln(1 + hold): "
     "a 2-t0 hold gets 14 samples instead of 22 (a hold under 1 t0 one sample); the grid "
     "is then coarser than log_step in ln(1 + t)",
     T_HOLDGRID),
    ("driving_substep_velocity_from_sample_start", "ensemble/driving.py",
     "v = (ens.x - x_sub) / (tj - t_sub)",
     "v = (ens.x - x_before) / (tj - t_sub)",
     "the velocity at which the strength g is taken from the whole sample's slip over the "
     "last substep's time: with the direct effect and n > 1 creep substeps (a load travel "
     "per sample larger than the substep slip) the recorded mu and v are too large",
     T_DRIVING),
    ("interface_coupling_energy_no_half", "ensemble/interface.py",
     "+ 0.5 * kc * float(np.sum(np.diff(x) ** 2)))",
     "+ kc * float(np.sum(np.diff(x) ** 2)))",
     "elastic energy of the coupling springs without its 1/2: energy.csv's elastic_energy "
     "(and the energy balance) wrong for N > 1 blocks with unequal slips (coupling > 0); "
     "N = 1 and rigid motion unchanged",
     T_IFACE),
    # ------------------------------------------------------------------ rsf/
    ("stepper_prz_no_half", "rsf/stepper.py",
     "return 0.5 * (e - q), -q, -0.5 * (e + q)",
     "return (e - q), -q, -0.5 * (e + q)",
     "PRZ law's d ln theta/dt without its 1/2 (theta = theta'/2 convention lost) in the "
     "compiled stepper: the PRZ transients after a velocity step evolve twice as fast "
     "(steady state unchanged); disagrees with RateState.state_rate",
     T_PRZ),
    ("rsf_quadrature_end_slope_unscaled", "rsf/result.py",
     "f0, f1 = F[:-1, 0] * h, F[1:, 0] * h",
     "f0, f1 = F[:-1, 0] * h, F[1:, 0]",
     "the Hermite slope at the step's end not multiplied by the step: the slip x from the "
     "quadrature of V is wrong wherever ln V changes within a step (spring runs after a "
     "velocity step); constant V unchanged",
     T_RSFQUAD),
    ("rsf_kc_inertial_term_a_not_aprime", "rsf/law.py",
     "(1.0 + mass * v * v / (ap * self.dc))",
     "(1.0 + mass * v * v / (self.a * self.dc))",
     "the inertial factor of k_c with a instead of a' = a + eta V: critical_stiffness wrong "
     "only with both mass > 0 and damping > 0",
     T_RSFKC),
    # ------------------------------------------------------------------ io/
    ("protocol_rsf_damping_mass_swapped", "io/protocol.py",
     'stiffness, d.number("damping", 0.0),\n                    d.number("mass", 0.0))',
     'stiffness, d.number("mass", 0.0),\n                    d.number("damping", 0.0))',
     "SpringSlider's positional damping and mass swapped when read from an rsf protocol: a "
     "protocol with drive.damping or drive.mass runs the other one",
     T_PROTO),
    ("protocol_sweep_follows_first_segment", "io/protocol.py",
     "last = segs[-1] if isinstance(segs, list) and segs else None",
     "last = segs[0] if isinstance(segs, list) and segs else None",
     "a stick-slip sweep's steady initial state follows the first segment's velocity, not "
     "the last (pulling) one: differs for a protocol with several segments",
     T_SWEEPPROTO),
    ("textfile_utf32_le_missed", "io/textfile.py",
     'if head.startswith((b"\\xff\\xfe\\x00\\x00", b"\\x00\\x00\\xfe\\xff")):',
     'if head.startswith((b"\\x00\\x00\\xfe\\xff",)):',
     "only the big-endian UTF-32 byte-order mark checked: a UTF-32-LE file (BOM ff fe 00 00) "
     "is reported as UTF-16 text",
     T_TEXT),
    # ------------------------------------------------------------------ records/
    ("labsteps_force_column_factor", "records/labsteps.py",
     'return "normal force", "kN", 1e-3',
     'return "normal force", "kN", 1e-6',
     "the normal force's factor N -> kN copied from the stress line (Pa -> MPa): a record "
     "whose normal column is a force gets segments.csv's normal_force and the table 1000x "
     "too small",
     T_SEGCSV),
    ("labsteps_spec_absolute_time", "records/labsteps.py",
     'return ",".join(f"{s.t_start - t0:.10g}:{s.velocity:.6g}" for s in segments)',
     'return ",".join(f"{s.t_start:.10g}:{s.velocity:.6g}" for s in segments)',
     "the --segments form of the program with record times instead of times from the first "
     "sample: segments.csv's comment line is wrong for a record whose time does not start "
     "at 0 (and no longer parses back to the same program)",
     T_SEGSPEC),
    ("artifacts_reset_step_at_i", "records/artifacts.py",
     "(np.arange(a, b) > i).astype(float)",
     "(np.arange(a, b) >= i).astype(float)",
     "off by one in the step regressor of a reset's offset fit (the jump is between x[i] and "
     "x[i+1]): the offset removed from a reset record is the line's slope-biased estimate, "
     "the corrected displacement keeps a residual step",
     T_RESETS),
    ("placement_widen_multiplies", "records/placement.py",
     "a, b = at - tol / w, at + tol / w",
     "a, b = at - tol * w, at + tol * w",
     "widening the profile by w taken as widening the tolerance window: t_start_p (and "
     "t_start_placed) too high for every placed change with a profile",
     T_PLACE),
    # ------------------------------------------------------------------ fit/
    ("runs_test_variance_n_plus_1", "fit/statistics.py",
     "/ (n * n * (n - 1.0))",
     "/ (n * n * (n + 1.0))",
     "Wald-Wolfowitz variance of the number of runs with n + 1 instead of n - 1: runs_test_p "
     "slightly off (the z score larger by a relative ~1/n) for every fit with residuals",
     T_RUNS),
    ("hac_bandwidth_alpha_qs_form", "fit/statistics.py",
     "alpha = 4.0 * rho**2 / ((1.0 - rho) ** 2 * (1.0 + rho) ** 2)\n    return int(min(",
     "alpha = 4.0 * rho**2 / (1.0 - rho) ** 4\n    return int(min(",
     "Andrews' alpha(2) (the quadratic-spectral kernel's) used for the Bartlett kernel's "
     "alpha(1) in hac_bandwidth (sample lags): hac_lags too large for rho > 0 (rho = 0.5: "
     "16 vs 1.78, lags x2) and the HAC standard errors change",
     T_HAC),
    ("identify_neff_inverted", "fit/identify.py",
     "n_eff = max(i_ch * (1.0 - rho) / (1.0 + rho), 1.0)",
     "n_eff = max(i_ch * (1.0 + rho) / (1.0 - rho), 1.0)",
     "effective sample count of AR(1) noise inverted: the chance drift is underestimated for "
     "rho > 0 and steps with correlated noise get the 'residuals drift' note falsely",
     T_IDENT),
    ("engine_log_slope_ln101_as_001", "fit/engine.py",
     '"value": float((f[2] - f[0]) / (2 * math.log(1.01))), "unit": ""}',
     '"value": float((f[2] - f[0]) / (2 * 0.01)), "unit": ""}',
     "central difference in ln x with ln(1.01) approximated by 0.01: the derived "
     "'d mu/d ln V there' of a project-CSV fit is 0.5 % too small",
     T_DERIVED),
    ("record_stiffness_halfwidth_as_se", "fit/identify.py",
     "est[i] = (math.log(k), math.log(hi / lo) / (2.0 * z))",
     "est[i] = (math.log(k), math.log(hi / lo) / z)",
     "standard error of ln k from the full width of its 95 % interval over z instead of the "
     "half width: the record's machine stiffness interval twice too wide and inconsistent "
     "steps flagged less often (the weighted mean unchanged)",
     T_KREC),
    # ------------------------------------------------------------------ analysis/
    ("stickslip_stick_fraction_off_by_one", "analysis/stickslip.py",
     "stick_frac = float(np.sum(dt[slow[1:]]) / span) if span > 0 else 0.0",
     "stick_frac = float(np.sum(dt[slow[:-1]]) / span) if span > 0 else 0.0",
     "each slow sample counted for the step that starts at it instead of the one that ends "
     "at it: stick_fraction and stick_time change on a non-uniform grid or where sticking "
     "starts/ends between samples",
     T_STICK),
    ("granular_floor_radius_not_squared", "analysis/stickslip.py",
     "r2 = float(model.law.radius(np.array([tau_d]))[0]) ** 2",
     "r2 = float(model.law.radius(np.array([tau_d]))[0])",
     "the dying trap's force r_d^2 f_+(y_c) (eq. 23) with r_d instead of r_d^2: the default "
     "event floor too small by r_d (> 1 at any u with ageing, e.g. u = 0.01, eps = 0.1)",
     T_FLOOR),
    ("rsf_view_healing_first_three", "analysis/rsf_view.py",
     "np.polyfit(lt[-3:], peaks[-3:], 1)",
     "np.polyfit(lt[:3], peaks[:3], 1)",
     "the healing rate fitted over the three shortest holds instead of the three longest: "
     "healing_rate_dmu_dlnt differs with more than three holds (the curve is not linear in "
     "ln t at short holds)",
     T_VIEW),
    ("catalogue_mmin_excluded", "analysis/catalogue.py",
     "fit = positive[positive >= lo] if math.isfinite(lo) else positive[:0]",
     "fit = positive[positive > lo] if math.isfinite(lo) else positive[:0]",
     "events at the lower cut-off m_min excluded from the power-law MLE (Clauset's x >= "
     "x_min): alpha and n_fit change, always with the default m_min = the smallest moment",
     T_CATALOGUE),
    ("rsf_hopf_second_state_ratio_inverted", "analysis/rsf_hopf.py",
     "delta = 1.0 if i == 0 else m.dc / float(m.dc2)",
     "delta = 1.0 if i == 0 else float(m.dc2) / m.dc",
     "rate factor of the second state variable Dc/Dc2 inverted: the Hopf point (K_c, "
     "frequency, amplitude coefficient) of a two-state law with Dc2 != Dc is wrong",
     T_RSFHOPF),
    # ------------------------------------------------------------------ plots/
    ("plot_record_velocity_time_origin", "plots/record.py",
     "return t[0] + st[ok] / n[ok], v[ok]",
     "return st[ok] / n[ok], v[ok]",
     "smoothed velocity's window times without the record's time origin: for a record not "
     "starting at t = 0 the velocity curve of record.png is shifted by -t[0]",
     T_PLOTREC),
    ("report_secant_ln_t_not_ln_1pt", "plots/report.py",
     "(m100 - m1) / (0.04 * (math.log(101.0) - math.log(2.0)))",
     "(m100 - m1) / (0.04 * math.log(100.0))",
     "secant slope of mu_s against ln t between T = 1 and 100 instead of ln(1 + T): the "
     "report's secant_slope_per_eps_T_1_to_100 (summary.json) ~15 % too small",
     T_REPORT),
    # ------------------------------------------------------------------ app/
    ("reload_time_log_not_log1p", "app/ratestate.py",
     "heal = max(b, 0.0) * math.log1p(hold * speed / dc) + 2.0 * a",
     "heal = max(b, 0.0) * math.log(hold * speed / dc) + 2.0 * a",
     "healing b ln(1 + t_h V/Dc) written b ln(t_h V/Dc): the default --t2 of an shs run is "
     "shorter (short holds: t_h V < Dc gives a negative healing)",
     T_RELOAD),
    ("app_segments_csv_unit_dropped", "app/records.py",
     "write_segments_csv(folder / \"segments.csv\", segs, float(rec.time[0]), rec.normal_unit)",
     "write_segments_csv(folder / \"segments.csv\", segs, float(rec.time[0]))",
     "the record's normal_unit not passed to segments.csv (default Pa): a record whose "
     "normal column is a force writes normal_stress[MPa] with N x 1e-6",
     T_APPREC),
    ("app_csv_stiffness_default_fit", "app/fitting.py",
     'k = parse_stiffness("inf" if value is None else value)',
     'k = parse_stiffness("fit" if value is None else value)',
     "wrong default for the project's CSV fits without --stiffness: the machine stiffness is "
     "fitted instead of kinematic (inf)",
     T_APPFIT),
    # ------------------------------------------------------------------ cli/
    ("cli_renamed_returns_new", "cli/common.py",
     "    return old_value\n",
     "    return value\n",
     "a deprecated option's value dropped after its warning: --v-ref (static/steady) or "
     "--mass (stability) runs with the default of the new option",
     T_CLIRENAME),
    ("cli_steps_table_force_unit", "cli/records.py",
     'scale, shown = (1e-3, "kN") if unit == "N" else (1e-6, "MPa")',
     'scale, shown = (1e-3, "kN") if unit == "kN" else (1e-6, "MPa")',
     "the record's normal_unit compared with the shown unit kN instead of its own N: a force "
     "record's step table prints the normal force x 1e-6 under MPa",
     T_CLIREC),
    # ------------------------------------------------------------------ sweeps/
    ("sweep_log_axis_logspace", "sweeps/sweep.py",
     "return tuple(float(v) for v in np.geomspace(start, stop, n))",
     "return tuple(float(v) for v in np.logspace(start, stop, n))",
     "np.logspace (exponents) for np.geomspace (values): a {log = [0.01, 1, 3]} axis runs "
     "10^0.01 .. 10",
     T_SWEEP),
    # ------------------------------------------------------------------ package top level
    ("program_segment_index_left", "program.py",
     'i = np.searchsorted(self.times, t, side="right") - 1',
     'i = np.searchsorted(self.times, t, side="left") - 1',
     "segment lookup left-continuous: VelocityProgram.velocity at a segment boundary gives "
     "the previous segment's velocity (position unchanged, it is continuous)",
     T_PROGRAM),
    ("results_mean_mu_unweighted", "results.py",
     "mean = float(np.trapezoid(mu, t) / span) if span > 0 else float(np.mean(mu))",
     "mean = float(np.mean(mu))",
     "summary's mean_mu as the plain sample mean instead of the time average: differs on a "
     "non-uniform time grid (segment boundaries, solver steps of rsf runs)",
     T_RESULTS),
    ("validation_gib_as_gb", "validation.py",
     '"GIB": 2**30',
     '"GIB": 1e9',
     "GiB taken as 10^9 bytes: DRYFRICTION_MEMORY=8GiB gives 8e9 instead of 8.59e9 bytes",
     T_BYTES),
]


# ----------------------------------------------------------------------------- the runner
def main(argv: list[str]) -> int:
    from benchmarks.blind_mutants import run_set  # the runner all sets share

    return run_set(argv, MUTANTS, "blind_mutants5_results.jsonl")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
