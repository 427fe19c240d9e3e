"""A seventh blind mutant set for issue 25's "Done when" (fresh: >= 30, killed >= 90 %).

Written against main at commit 2f2b52cec8c1932546a2623661cda7c2a26e9dad (2026-11-27) by a
reviewer (branch ``blind7``) who read ``src/dryfriction`` (theory/model.py, theory/units.py,
theory/direct.py, theory/dieterich.py, theory/steady.py, ensemble/balance.py,
ensemble/result.py, ensemble/thermal.py (parts), ensemble/interface.py (parts), rsf/law.py,
rsf/growth.py, rsf/stability.py (parts), rsf/result.py, io/units.py, io/protocol.py,
io/files.py, io/spacetime.py (parts), records/data.py (parts), records/lab.py,
records/labsteps.py, records/artifacts.py (parts), records/detection.py (parts),
records/placement.py (parts), fit/statistics.py (parts), fit/elastic.py, fit/machine.py,
fit/cvtail.py (parts), fit/lawcolumns.py (parts), fit/steps.py (parts),
analysis/stickslip.py, analysis/catalogue.py, plots/steps.py, plots/summary.py,
plots/runs.py (parts), app/options.py, app/records.py (parts), app/theory.py (parts),
app/ratestate.py (parts), cli/records.py (parts), cli/common.py (parts), cli/runs.py (parts),
sweeps/sweep.py (parts), sweeps/cf.py, program.py, results.py (parts), validation.py (parts))
but neither ``tests/mutants.py``, nor any file under ``tests/`` (only their names, ``ls -R
tests/``), nor the MUTANTS lists of ``benchmarks/blind_mutants.py`` ... ``blind_mutants6.py``,
nor docs/quality.md, nor any other worktree or branch; of ``blind_mutants6.py`` only its
docstring, its test-choice code and its runner (reused here), of ``blind_mutants.py`` only its
runner functions (``resolve`` ... ``run_set``). The test files of each mutant were chosen by
their names. This list was committed before any mutant was run. Each mutant is an exact text
replacement whose original occurs exactly once in its file; each changes some output for some
reasonable input (said in its description), none is meant to be equivalent.

Run (from the repository root, one mutant at a time)::

    .venv/bin/python benchmarks/blind_mutants7.py --check             # originals unique
    .venv/bin/python benchmarks/blind_mutants7.py --no-whole          # chosen files only
    .venv/bin/python benchmarks/blind_mutants7.py --no-whole NAME ... # some

For each mutant: apply, ``pytest -x -q -p no:cacheprovider --timeout 300`` on its chosen
files, killed/survived, restore (always: :func:`benchmarks.blind_mutants.run_one`). The first
failing test of each kill is rerun on the unmutated tree. Results are appended to
``$TMPDIR/blind_mutants7_results.jsonl``.

The list was committed as c5c72cd before any mutant ran. Measured on c5c72cd (whose source
is that of 2f2b52c; 2026-11-27, 06:42-06:58 UTC, 2 shared cores), chosen files only
(``--no-whole``, 731 s of pytest in all): **32 of 40 killed (80.0 %, Clopper-Pearson 95 %
64.4-90.9 %)**. Every kill's first failing test passed when rerun on the unmutated tree. None
of the 40 is equivalent as far as checked: each survivor was applied to a copy of the source
outside the worktree and changes an output (numbers below). The whole-suite pass of the
survivors was not run here (the lead's). Under the 90 % of the "Done when".

Killed (32): dieterich_asymptotic_4_3_swapped, units_friction_level_ignores_scales,
snapshot_force_no_mu_el, sample_interval_every_slip_times_v, interface_sound_speed_no_sqrt,
rsf_kc_inertia_v_not_squared, rsf_hopf_frequency_bare_a, rsf_unstable_start_theta_no_v,
rsf_stress_damping_at_load_velocity, protocol_v_ref_default_si, files_confined_allows_dotdot,
lab_kpa_as_milli, segments_spec_record_time, detection_confidence_linear_sum,
t_quantile_one_sided, elastic_slope_se_no_ar1, slope_stiffness_factor_inverted,
steps_sigma_a_minus_b_plus, peak_residual_down_step_max, granular_floor_no_mu_el,
stick_threshold_no_u, magnitude_exponent_se_alpha, catalogue_speeds_left_right_swapped,
precursor_right_edge_off_by_one, step_figure_residual_sign, summary_errorbars_swapped,
record_files_normal_unit_dropped, rsf_stick_slip_unperturbed, records_table_kn_scale,
cf_every_slip_unit_t0, program_positions_no_x0, summary_mean_mu_unweighted.

Survived their chosen files (8), with what a test would have to check (each checked by hand
on the mutated copy, outside the tests):

* ``steady_log_slope_one_sided_h`` (theory/steady.py): steady_log_slope(TrapModel(eps=0.05),
  u) against an independent central difference of steady_friction (step 1e-3 in ln u):
  -0.080105, -0.065168, -0.027743 at u = 0.03, 0.3, 3 (mutated -0.160209, -0.130335,
  -0.055486). No other module of the package calls it: the public function alone.
* ``stickslip_fraction_zero_allowed`` (io/protocol.py): stickslip_options({"stick_fraction":
  0}) refused in one line naming stickslip.stick_fraction ("allowed finite and > 0 and <=
  1"); mutated it returns {"stick_fraction": 0.0}.
* ``placement_chi2_one_sided`` (records/placement.py): _chi2_1(0.95) = 3.8415
  (scipy.stats.chi2.ppf(0.95, 1); mutated 2.7055); it sets only profile_interval's ``edge``
  (the profile cut by the times searched), which widens t_start_lo/hi to the search window
  and makes t_start_placed "no": on candidates t = 0..10 s with a quadratic profile peaked at
  6 s and the first candidate 1.6 below the best (log-likelihood), edge True (mutated False).
* ``aicc_denominator_plus_1`` (fit/statistics.py): information_criteria's aicc against AIC +
  2k(k+1)/(n-k-1): cost 0.37, n = 20, p = 3 (k = 4) gives -55.27008 (mutated -55.58381).
* ``step_title_dc_mm`` (plots/steps.py): step_title of a row with dc = 1.7e-5 m reads "Dc =
  17 µm" (mutated "Dc = 0.017 µm").
* ``rsf_v2_default_1e4`` (app/options.py): the documented default of ``rsf --v2`` (1e-5
  m/s) against defaults("rsf"), or ``dryfriction rsf --no-figure --json``: v_max 3.527e-05
  m/s, final_mu 0.588487 (mutated 7.48e-04 m/s, 0.576974).
* ``renamed_option_value_lost`` (cli/common.py): ``dryfriction rsf --case shs --hold 30
  --json`` runs the 30-s hold that ``--hold-time 30`` runs: duration 163.863 s (mutated
  243.979 s: the default 100-s hold, the deprecation warning printed either way).
* ``memory_mib_decimal`` (validation.py): parse_bytes("500MiB") = 500 * 2**20 = 524288000
  (mutated 5e8; memory_limit() with DRYFRICTION_MEMORY_LIMIT=500MiB the same).

Corrections to three descriptions of the list (the mutations themselves are unchanged):
``aicc_denominator_plus_1`` moves aicc by 2k(k+1)/(n-k-1) - 2k(k+1)/(n-k+1) = 0.31 at n = 20,
k = 4, not 2.5; ``placement_chi2_one_sided`` changes the edge flag (above), not the width of
the interval directly; ``slope_stiffness_factor_inverted`` on a 1 -> 10 um/s step gives 0.90
instead of 1.11 times the slope.

Second pass (the lead, 2026-11-27, 07:00-07:37 UTC, 2 shared cores at a load of 6-10): the
eight survivors applied together through the whole default suite of b48a892 (2f2b52c, the
list's base, plus one change to ``fit.steps.series_windows`` and its test; no test written
after the list existed): apply all eight, ``pytest -n 2 --dist loadfile --timeout 300
tests/``, restore. 19 tests failed (1756 s). The two
``tests/test_mutants_list.py`` failures (a listed mutant whose original the blind mutant had
changed) are not counted. The other 17 passed when rerun unmutated (17 passed), and each
was rerun under each survivor alone; every survivor fails at least one of them:

* steady_log_slope_one_sided_h: tests/theory/test_invariants.py (2 cases),
  tests/theory/test_direct.py (4);
* stickslip_fraction_zero_allowed: tests/sweeps/test_sweep.py,
  tests/io/test_stickslip_table_edges.py;
* placement_chi2_one_sided: tests/cli/test_help.py
  (test_the_chi_square_quantile_is_the_squared_normal_one);
* aicc_denominator_plus_1: tests/fit/test_invariants_estimators.py;
* step_title_dc_mm: tests/plots/test_plot_helpers.py, tests/fit/test_identify.py;
* rsf_v2_default_1e4: tests/cli/test_rsf_peer_case.py;
* renamed_option_value_lost: tests/cli/test_help.py (test_old_names_warn_and_still_work);
* memory_mib_decimal: tests/test_validation.py (3 cases).

So against the whole suite: **40 of 40 killed (100 %, Clopper-Pearson 95 % 91.2-100 %)**.
The chosen files undercount again (8 of the 40 kills are by tests in other folders).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

# ----------------------------------------------------------------------------- test choice
# by file name only (ls -R tests/), never by their content
T_STEADY = ["tests/theory/test_steady.py", "tests/theory/test_stability.py",
            "tests/theory/test_independent_reference.py"]
T_DIETERICH = ["tests/theory/test_dieterich.py", "tests/theory/test_old_forms.py"]
T_UNITS = ["tests/theory/test_units.py", "tests/theory/test_model_objects.py"]
T_SNAP = ["tests/ensemble/test_snapshot_force.py", "tests/ensemble/test_population.py"]
T_SAMPLING = ["tests/ensemble/test_result_sampling.py", "tests/ensemble/test_driving.py"]
T_IFACE = ["tests/ensemble/test_interface_generic.py", "tests/ensemble/test_interface.py",
           "tests/analysis/test_fronts_generic.py"]
T_LAW = ["tests/rsf/test_rsf.py", "tests/rsf/test_reported_numbers.py",
         "tests/rsf/test_invariants.py"]
T_HOPF = ["tests/rsf/test_rsf.py", "tests/rsf/test_reported_numbers.py",
          "tests/analysis/test_rsf_hopf.py"]
T_GROWTH = ["tests/rsf/test_rsf.py", "tests/rsf/test_routes.py", "tests/rsf/test_result_pieces.py"]
T_RSFRESULT = ["tests/rsf/test_result_pieces.py", "tests/rsf/test_rsf.py",
               "tests/rsf/test_invariants.py"]
T_PROTOCOL = ["tests/io/test_protocol.py", "tests/io/test_protocol_defaults.py"]
T_SPRINGPT = ["tests/io/test_spring_point.py", "tests/io/test_protocol.py",
              "tests/sweeps/test_sweep_spec.py"]
T_FILES = ["tests/io/test_file_safety.py", "tests/io/test_files_edges.py"]
T_LAB = ["tests/records/test_labforms_units.py", "tests/io/test_invariants_units.py",
         "tests/records/test_lab.py"]
T_SEGCSV = ["tests/records/test_segments_csv.py", "tests/records/test_lab.py"]
T_PLACE = ["tests/records/test_change_interval.py", "tests/records/test_placement.py"]
T_DETECT = ["tests/records/test_detect.py", "tests/records/test_segments_csv.py"]
T_STAT = ["tests/fit/test_reported_definitions.py", "tests/fit/test_statistics_generic.py",
          "tests/fit/test_statistics_edges.py"]
T_ELASTIC = ["tests/fit/test_elastic.py", "tests/fit/test_stiffness_record_merge.py"]
T_MACHINE = ["tests/fit/test_fit.py", "tests/fit/test_machine_generic.py"]
T_STEPS = ["tests/fit/test_steps.py", "tests/fit/test_reported_definitions.py",
           "tests/fit/test_invariants_estimators.py"]
T_PEAK = ["tests/fit/test_peak_residual.py", "tests/fit/test_steps.py"]
T_FLOOR = ["tests/analysis/test_granular_floor.py", "tests/analysis/test_stickslip.py"]
T_SS = ["tests/analysis/test_stickslip_measures.py", "tests/analysis/test_stickslip.py"]
T_CATALOGUE = ["tests/analysis/test_fronts.py", "tests/analysis/test_fronts_generic.py",
               "tests/app/test_interface_outputs.py"]
T_SPEEDS = ["tests/analysis/test_fronts_generic.py", "tests/analysis/test_fronts.py",
            "tests/app/test_interface_outputs_generic.py"]
T_PRECURSORS = ["tests/analysis/test_fronts.py", "tests/analysis/test_fronts_generic.py",
                "tests/analysis/test_fronts_helpers.py", "tests/app/test_interface_outputs.py"]
T_STEPFIG = ["tests/plots/test_step_figure_data.py", "tests/plots/test_plots.py"]
T_SUMMARYFIG = ["tests/plots/test_reported_artists.py", "tests/plots/test_plots.py",
                "tests/fit/test_experiment.py"]
T_STEPTITLE = ["tests/plots/test_figure_text.py", "tests/plots/test_step_figure_data.py"]
T_RSFAPP = ["tests/app/test_rsf_workflow.py", "tests/app/test_workflows.py"]
T_RECORDAPP = ["tests/app/test_record_report.py", "tests/records/test_segments_csv.py",
               "tests/cli/test_records_table.py"]
T_RECTABLE = ["tests/cli/test_records_table.py", "tests/cli/test_reported_outcomes.py"]
T_RENAMED = ["tests/cli/test_cli.py", "tests/cli/test_words.py"]
T_CF = ["tests/sweeps/test_cf.py", "tests/sweeps/test_cf_describe.py",
        "tests/sweeps/test_axis_units.py"]
T_PROGRAM = ["tests/test_program.py", "tests/io/test_protocol.py"]
T_SUMMARY = ["tests/ensemble/test_results_summary.py", "tests/rsf/test_summary_path.py",
             "tests/rsf/test_result_pieces.py"]
T_BYTES = ["tests/theory/test_memory.py", "tests/ensemble/test_run_estimate_bytes.py"]

# ----------------------------------------------------------------------------- the mutants
# (name, file under src/dryfriction, original, mutated, why plausible, test files)
MUTANTS: list[tuple[str, str, str, str, str, list[str]]] = [
    # ------------------------------------------------------------------ theory (3)
    ("steady_log_slope_one_sided_h", "theory/steady.py",
     "slope = (up - dn) / (2.0 * h)",
     "slope = (up - dn) / h",
     "the central difference over 2h divided by h: steady_log_slope (and every d mu/d ln u "
     "built on it, the stability command's K_c) doubled at any u with eps > 0",
     T_STEADY),
    ("dieterich_asymptotic_4_3_swapped", "theory/dieterich.py",
     "dyn = 4.0 * _forward_moment_loose(1, alpha) + 3.0 * _forward_moment_loose(0, alpha)",
     "dyn = 3.0 * _forward_moment_loose(1, alpha) + 4.0 * _forward_moment_loose(0, alpha)",
     "the weights of int (4y + 3) f dy swapped: dieterich_constant_asymptotic(TrapModel(0.13)) "
     "changes (the first and zeroth moments differ)",
     T_DIETERICH),
    ("units_friction_level_ignores_scales", "theory/units.py",
     "    if model.mu_el == default:\n        return scales.mu_el",
     "    if model.mu_el == default:\n        return model.mu_el",
     "mu_el given only in PhysicalScales (0.6) is ignored: steady_friction_si and "
     "static_friction_si return F/F_el instead of 0.6 F/F_el",
     T_UNITS),
    # ------------------------------------------------------------------ ensemble (3)
    ("snapshot_force_no_mu_el", "ensemble/result.py",
     's["force"] = s["force"] * ens.force_scale * self.mu_el',
     's["force"] = s["force"] * ens.force_scale',
     "a snapshot's per-trap force not in friction units: with mu_el = 0.6 the snapshot "
     "forces no longer sum to the recorded mu",
     T_SNAP),
    ("sample_interval_every_slip_times_v", "ensemble/result.py",
     "return float(output.every_slip) / abs(velocity)",
     "return float(output.every_slip) * abs(velocity)",
     "sampling every slip s at velocity u is every s*u instead of s/u: at u = 0.1 the run "
     "records 100x more (u = 10: fewer) rows than output.every_slip asks for",
     T_SAMPLING),
    ("interface_sound_speed_no_sqrt", "ensemble/interface.py",
     "return math.sqrt(self.coupling / self.mass)",
     "return self.coupling / self.mass",
     "the chain's long-wave speed without its square root: with coupling 50, mass 2 it is "
     "25 instead of 5 element spacings per t0 (the front regimes' reference)",
     T_IFACE),
    # ------------------------------------------------------------------ rsf (4)
    ("rsf_kc_inertia_v_not_squared", "rsf/law.py",
     "(1.0 + mass * v * v / (ap * self.dc))",
     "(1.0 + mass * v / (ap * self.dc))",
     "Rice-Ruina's inertial k_c with m V instead of m V^2: critical_stiffness(v=1e-5, "
     "mass=1e3) changes (any v != 1 m/s)",
     T_LAW),
    ("rsf_hopf_frequency_bare_a", "rsf/law.py",
     "return v / self.dc * math.sqrt((self.b - ap) / ap)",
     "return v / self.dc * math.sqrt((self.b - ap) / self.a)",
     "the denominator a instead of a' = a + eta V: hopf_frequency(v, damping > 0) too high",
     T_HOPF),
    ("rsf_unstable_start_theta_no_v", "rsf/growth.py",
     "abs(math.log(theta * vl / model.dc))",
     "abs(math.log(theta / model.dc))",
     "the state's distance from steady state without V: a run started at the steady state "
     "of an unstable spring (V = 1e-6 m/s) is never flagged (no unstable_start, no warning)",
     T_GROWTH),
    ("rsf_stress_damping_at_load_velocity", "rsf/result.py",
     "stress = mu + damping * v",
     "stress = mu + damping * vl",
     "radiation damping on the load-point velocity instead of the slider's: the stress column "
     "(and x from the force balance) wrong during every transient with damping > 0",
     T_RSFRESULT),
    # ------------------------------------------------------------------ io (3)
    ("protocol_v_ref_default_si", "io/protocol.py",
     'v_ref=m.number("v_ref", 1.0),',
     'v_ref=m.number("v_ref", 1e-6),',
     "the SI default (1e-6 m/s) in a reduced-unit protocol: a trap-model run with direct > 0 "
     "and no v_ref has g(u) shifted by A ln(1e6)",
     T_PROTOCOL),
    ("stickslip_fraction_zero_allowed", "io/protocol.py",
     '"stick_fraction": (0.0, 1.0, True, False),',
     '"stick_fraction": (0.0, 1.0, False, False),',
     "the open lower bound closed: stickslip.stick_fraction = 0 (nothing can stick) is "
     "accepted instead of refused in one line",
     T_SPRINGPT),
    ("files_confined_allows_dotdot", "io/files.py",
     'all(p not in ("", ".", "..") for p in rel.split("/"))',
     'all(p not in ("", ".") for p in rel.split("/"))',
     'a manifest entry "../victim.txt" counts as ours: a forged dryfriction.json lets a run '
     "replace or remove a file outside its folder",
     T_FILES),
    # ------------------------------------------------------------------ records (4)
    ("lab_kpa_as_milli", "records/lab.py",
     '"kPa": 1e3,',
     '"kPa": 1e-3,',
     "kPa read as 1e-3 Pa: a record with the normal stress in kPa (and shear in MPa) gets a "
     "friction 1e6 times too large (refused), normal_stress 1e6 too small",
     T_LAB),
    ("segments_spec_record_time", "records/labsteps.py",
     'f"{s.t_start - t0:.10g}:{s.velocity:.6g}"',
     'f"{s.t_start:.10g}:{s.velocity:.6g}"',
     "the --segments form in record time, not from the first sample: for a record starting "
     "at t = 500 s its starts are 500 s late and the first is not 0 (refused when pasted)",
     T_SEGCSV),
    ("placement_chi2_one_sided", "records/placement.py",
     "return float(ndtri(0.5 * (1.0 + level))) ** 2",
     "return float(ndtri(level)) ** 2",
     "the chi-square(1) quantile from a one-sided normal one: 2.71 instead of 3.84 at 95 %, "
     "the change-time intervals (t_start_lo/hi) too narrow",
     T_PLACE),
    ("detection_confidence_linear_sum", "records/detection.py",
     "return np.abs(np.diff(v)) / np.hypot(e[1:], e[:-1])",
     "return np.abs(np.diff(v)) / (e[1:] + e[:-1])",
     "the two stretches' errors added linearly, not in quadrature: every boundary's "
     "confidence up to sqrt 2 too low",
     T_DETECT),
    # ------------------------------------------------------------------ fit (6)
    ("aicc_denominator_plus_1", "fit/statistics.py",
     "2 * k * (k + 1) / (n - k - 1)",
     "2 * k * (k + 1) / (n - k + 1)",
     "AICc's small-sample term over n - k + 1: aicc at n = 20, k = 4 is 2.5 lower",
     T_STAT),
    ("t_quantile_one_sided", "fit/statistics.py",
     "float(stats.t.ppf(0.975, dof))",
     "float(stats.t.ppf(0.95, dof))",
     "the 95 % two-sided Student quantile taken one-sided: every interval without given "
     "sigma is 16 % (large dof) to 50 % too narrow",
     T_STAT),
    ("elastic_slope_se_no_ar1", "fit/elastic.py",
     "se = math.sqrt(s2 / sxx * (1.0 + rho) / (1.0 - rho))",
     "se = math.sqrt(s2 / sxx)",
     "the loading slope's standard error without the AR(1) factor: stiffness_lo/hi of a "
     "reload too narrow by sqrt((1 + rho)/(1 - rho)) when the steady part is correlated",
     T_ELASTIC),
    ("slope_stiffness_factor_inverted", "fit/machine.py",
     "k = slope / (1.0 - vb / va)",
     "k = slope * (1.0 - vb / va)",
     "the creep correction multiplied instead of divided: stiffness = 'slope' on a 1 -> 10 "
     "um/s step 0.81 instead of 1.23 times the slope",
     T_MACHINE),
    ("steps_sigma_a_minus_b_plus", "fit/steps.py",
     '"sigma_a_minus_b": se_of(grad("a") - grad("b")),',
     '"sigma_a_minus_b": se_of(grad("a") + grad("b")),',
     "the standard error of a - b with the covariance's sign wrong (of a + b): a and b are "
     "strongly correlated in a step fit, so sigma_a_minus_b is far off",
     T_STEPS),
    ("peak_residual_down_step_max", "fit/steps.py",
     "j = int(np.argmax(smooth) if up else np.argmin(smooth))",
     "j = int(np.argmax(smooth))",
     "the peak of a down-step is its trough: peak_residual of a 10 -> 1 um/s step taken at "
     "the largest friction instead",
     T_PEAK),
    # ------------------------------------------------------------------ analysis (5)
    ("granular_floor_no_mu_el", "analysis/stickslip.py",
     "return factor * model.mu_el * trap.f_c * r2 / (trap.H0 * traps_per_a0)",
     "return factor * trap.f_c * r2 / (trap.H0 * traps_per_a0)",
     "the default event floor in F_el while the spring force is in mu_el F/F_el: with "
     "mu_el = 0.6 the floor is 1.67 times too large",
     T_FLOOR),
    ("stick_threshold_no_u", "analysis/stickslip.py",
     "slow = v < stick_fraction * u",
     "slow = v < stick_fraction",
     "the sticking threshold in absolute units instead of a fraction of the pulling "
     "velocity: stick_fraction (the measure) wrong at any u != 1",
     T_SS),
    ("magnitude_exponent_se_alpha", "analysis/catalogue.py",
     "err = (alpha - 1.0) / math.sqrt(fit.size)",
     "err = alpha / math.sqrt(fit.size)",
     "Clauset's standard error (alpha - 1)/sqrt n written alpha/sqrt n: at alpha = 1.5 it is "
     "three times too large",
     T_CATALOGUE),
    ("catalogue_speeds_left_right_swapped", "analysis/catalogue.py",
     'for side, k in (("left", 0), ("right", 1)):',
     'for side, k in (("left", 1), ("right", 0)):',
     "the fronts' index order taken the other way: speed_left and speed_right swapped in "
     "catalogue.csv for every asymmetric event",
     T_SPEEDS),
    ("precursor_right_edge_off_by_one", "analysis/catalogue.py",
     "else slice(e.elements[0], n_x))",
     "else slice(e.elements[0] + 1, n_x))",
     "the right-edge precursor length leaves out the event's first element: one element "
     "spacing short for every event from the right edge",
     T_PRECURSORS),
    # ------------------------------------------------------------------ plots (3)
    ("step_figure_residual_sign", "plots/steps.py",
     "bot.scatter(xv, d.mu - model, **_DATA)",
     "bot.scatter(xv, model - d.mu, **_DATA)",
     "the residual panel model minus data: the figure's residuals have the opposite sign "
     "of steps.csv's peak_residual (data minus model)",
     T_STEPFIG),
    ("summary_errorbars_swapped", "plots/summary.py",
     "err = np.vstack([np.where(np.isfinite(lo), y - lo, 0.0),\n"
     "                             np.where(np.isfinite(hi), hi - y, 0.0)])",
     "err = np.vstack([np.where(np.isfinite(hi), hi - y, 0.0),\n"
     "                             np.where(np.isfinite(lo), y - lo, 0.0)])",
     "the lower and upper bar lengths swapped: Dc's asymmetric (log) interval drawn upside "
     "down in the summary figure",
     T_SUMMARYFIG),
    ("step_title_dc_mm", "plots/steps.py",
     "Dc = {_g(row['dc'], 1e6, ' µm')}",
     "Dc = {_g(row['dc'], 1e3, ' µm')}",
     "the step figure's title gives Dc in mm labelled um (1000 times too small)",
     T_STEPTITLE),
    # ------------------------------------------------------------------ app (3)
    ("rsf_v2_default_1e4", "app/options.py",
     '"v2": Option("--v2", 1e-5,',
     '"v2": Option("--v2", 1e-4,',
     "the rsf step's default second velocity a decade off: dryfriction rsf (defaults) steps "
     "1 -> 100 um/s instead of 1 -> 10",
     T_RSFAPP),
    ("record_files_normal_unit_dropped", "app/records.py",
     'write_segments_csv(folder / "segments.csv", segs, float(rec.time[0]), rec.normal_unit)',
     'write_segments_csv(folder / "segments.csv", segs, float(rec.time[0]))',
     "segments.csv of a record whose normal column is a force: normal_stress[MPa] holding "
     "1e-6 N instead of normal_force[kN]",
     T_RECORDAPP),
    ("rsf_stick_slip_unperturbed", "app/ratestate.py",
     "v_init = 1.01 * v1",
     "v_init = v1",
     "the stick-slip case starts exactly at the steady state: only rounding seeds the "
     "instability, so the default run slides steadily (or starts late)",
     T_RSFAPP),
    # ------------------------------------------------------------------ cli (2)
    ("records_table_kn_scale", "cli/records.py",
     'scale, shown = (1e-3, "kN") if unit == "N" else (1e-6, "MPa")',
     'scale, shown = (1e-6, "kN") if unit == "N" else (1e-6, "MPa")',
     "a force record's normal column in the terminal table scaled as MPa but labelled kN: "
     "1000 times too small",
     T_RECTABLE),
    ("renamed_option_value_lost", "cli/common.py",
     '        "next release")\n    return old_value',
     '        "next release")\n    return value',
     "the deprecated option is warned about but its value dropped: dryfriction rsf --case shs "
     "--hold 30 holds 100 s",
     T_RENAMED),
    # ------------------------------------------------------------------ sweeps (1)
    ("cf_every_slip_unit_t0", "sweeps/cf.py",
     '"every_slip": "a0",',
     '"every_slip": "t0",',
     "a swept output.every_slip written with the unit of output.every: sweep.nc's units "
     "attribute t0 for a slip",
     T_CF),
    # ---------------------------------------------- program / results / validation (3)
    ("program_positions_no_x0", "program.py",
     "return self.x0 + np.concatenate([[0.0], np.cumsum([s.displacement for s in self.segments])])",
     "return np.concatenate([[0.0], np.cumsum([s.displacement for s in self.segments])])",
     "the segment boundaries' positions from 0, not x0: position(t) of a program with "
     "x0 = 5 is 5 short",
     T_PROGRAM),
    ("summary_mean_mu_unweighted", "results.py",
     "mean = float(np.trapezoid(mu, t) / span) if span > 0 else float(np.mean(mu))",
     "mean = float(np.mean(mu))",
     "mean_mu as the samples' mean, not the time average: differs on an adaptive (rsf) grid "
     "and at the ends of any grid",
     T_SUMMARY),
    ("memory_mib_decimal", "validation.py",
     '"MIB": 2**20,',
     '"MIB": 1e6,',
     "MiB read as MB: DRYFRICTION_MEMORY_LIMIT=500MiB gives 5.0e8 bytes instead of 5.24e8",
     T_BYTES),
]


# ----------------------------------------------------------------------------- the runner
def main(argv: list[str]) -> int:
    from benchmarks.blind_mutants import run_set  # the runner all sets share

    return run_set(argv, MUTANTS, "blind_mutants7_results.jsonl")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
