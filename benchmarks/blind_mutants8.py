"""An eighth blind mutant set for issue 25's "Done when" (fresh: >= 30, killed >= 90 %).

Written against main at commit fec9ca327da6 (2026-11-27) by a reviewer (helper ``blind8``,
branch ``blind8``) who read, of ``src/dryfriction``: theory/dieterich.py, theory/units.py,
theory/static.py, theory/steady.py, theory/trap.py, theory/stability.py (parts),
ensemble/driving.py, ensemble/result.py, ensemble/thermal.py, ensemble/interface.py (parts),
ensemble/population.py (parts), rsf/law.py, rsf/driving.py, rsf/result.py, io/protocol.py,
io/units.py, records/data.py, records/lab.py, records/labsteps.py, records/segmentation.py,
records/artifacts.py, fit/elastic.py, fit/cvtail.py, fit/joint.py, fit/lawchoice.py,
fit/lawcolumns.py, fit/statistics.py, fit/steps.py, fit/identify.py, fit/experiment.py,
fit/machine.py, fit/models.py (parts), fit/cvseries.py (parts), analysis/stickslip.py,
analysis/catalogue.py, analysis/fronts.py (parts), analysis/hopf_table.py,
analysis/interface_sweep.py, plots/summary.py, plots/steps.py, app/ratestate.py,
app/interface_outputs.py, app/options.py, app/records.py (parts), cli/records.py,
sweeps/sweep.py, sweeps/cluster.py, results.py, program.py, validation.py (mostly by grep
for formulas, then the functions around them); but neither ``tests/mutants.py``, nor any file
under ``tests/`` (only their names, ``ls -R tests/``), nor docs/quality.md, nor the MUTANTS
lists of ``benchmarks/blind_mutants.py`` ... ``blind_mutants7.py`` (nor blind_mutants7.py at
all), nor any other worktree or branch. Of ``blind_mutants6.py``: its docstring, its
test-choice helpers and its runner (copied here); by a slip, while paging to its runner, its
last five mutants (lines 300-336: app trend default, cli table digits, static pull velocity,
sweep logspace, program slip sign) were also seen; none is repeated here. Of
``blind_mutants.py``: its test-choice lists and its runner functions. The test files of each
mutant were chosen by their names. This list was committed before any mutant was run. Each
mutant is an exact text replacement whose original occurs exactly once in its file; each
changes some output for some reasonable input (said in its description), none is meant to be
equivalent.

Run (from the repository root, one mutant at a time)::

    .venv/bin/python benchmarks/blind_mutants8.py --check             # originals unique
    .venv/bin/python benchmarks/blind_mutants8.py --no-whole          # chosen files only
    .venv/bin/python benchmarks/blind_mutants8.py --no-whole NAME ... # some

For each mutant: apply, ``pytest -x -q -p no:cacheprovider --timeout 300`` on its chosen
files, killed/survived, restore (always: :func:`benchmarks.blind_mutants.run_one`). The first
failing test of each kill is rerun on the unmutated tree. Results are appended to
``$TMPDIR/blind_mutants8_results.jsonl``.

The list was committed as a049cb7 before any mutant ran. Measured on a049cb7 (main fec9ca3
plus this file; 2026-11-27, 07:42-07:53 UTC, 2 shared cores), chosen files only
(``--no-whole``, 424 s of pytest in all): **36 of 40 killed (90.0 %, Clopper-Pearson 95 %
76.3-97.2 %)**. Every kill's first failing test passed when rerun on the unmutated tree
(``validation_lo_open_ignored``'s node id has a space in its parameter, which the runner's
rerun cuts, "runner-error": rerun by hand, ``pytest tests/test_validation.py -k
check_range_both_edges_open_and_closed`` on the unmutated tree, 4 passed). None of the 40 is
thought equivalent (each survivor's change checked by hand below). The whole-suite pass of
the survivors was not run here (the lead's).

Killed (36): trap_contact_stiffness_paper_H0, static_first_order_log_not_log1p,
steady_low_slope_direct0_factor_2, dieterich_asymptotic_moments_swapped,
stability_dforce_plus_factor_2, verlet_velocity_euler, ensemble_applied_force_no_mu_el,
interface_eigenvalue_fixed_ends, law_psi2_uses_dc, law_hopf_frequency_bare_a,
rsf_drive_stress0_no_damping, rsf_hermite_h11_sign, protocol_rsf_damping_mass_swapped,
lab_normal_unit_swapped, data_day_factor_typo, segmentation_rss_uncentred,
elastic_se_ar1_inverted, lawchoice_delta_bic_from_aic_min, cvtail_next_force_no_mu_el,
hac_bandwidth_qs_constant, identify_record_k_se_full_width,
experiment_step_normal_whole_window, machine_slope_extreme_up_only,
stickslip_floor_radius_not_squared, stickslip_summarise_force_no_mu_el,
catalogue_alpha_err_no_minus_1, catalogue_right_edge_strict, plot_summary_label_first_normal,
plot_step_residual_sign, app_stickslip_no_kick, interface_outputs_speed_bounds_swapped,
cli_records_normal_scale_swapped, sweep_lin_axis_no_endpoint, results_mean_mu_unweighted,
program_segment_index_left, validation_lo_open_ignored.

Survived their chosen files (4), with what a test would have to check; each checked by hand
on a copy of the tree with the mutant applied, outside the tests (original -> mutated):

* ``units_segments_normal_stress_pa`` (io/units.py; chosen tests/io/test_output_units.py,
  tests/records/test_segments_csv.py, tests/io/test_units_headers.py): segments.csv of a
  record with a normal-stress column, its header's unit against its values:
  write_segments_csv of two segments at 2e7 Pa (normal_unit "Pa") writes
  ``normal_stress[MPa]`` with 20 -> ``normal_stress[Pa]`` with 20.
* ``artifacts_reset_fix_off_by_one`` (records/artifacts.py; chosen
  tests/records/test_artifacts_generic.py, tests/records/test_lab.py): find_resets on a line
  with one reset, the corrected displacement on both sides of the jump against the line: 200
  samples 0.1 s apart, 2 um/s, noise 1e-9 m, x[101:] -= 5e-4 m; corrected minus line at
  sample 100 is -3.2e-10 m -> +5.0e-4 m (a one-sample spike; samples 99, 101, 102 unchanged).
* ``steps_robust_stderr_no_delta`` (fit/steps.py; chosen tests/fit/test_steps.py,
  tests/fit/test_reported_definitions.py, tests/fit/test_hac.py): robust_estimates of a
  ``log`` parameter: stderr = value x se(ln p) (delta method), the lo/hi of the same row
  being exp(ln p -+ z se): a0 = 3e-7 m with se(ln a0) = 0.2 gives stderr 6e-8 m -> 0.2. The
  user reads it in fit.json's cv_fits[i].robust.parameters and in the terminal's "+-" of the
  trap-model fit of a record (``fit --run-cv``, ``--errors hac``).
* ``fronts_threshold_last_segment`` (analysis/fronts.py; chosen tests/analysis/test_fronts.py,
  tests/analysis/test_fronts_helpers.py, tests/app/test_interface_outputs.py):
  default_threshold of a program whose last segment is not its fastest: segments 2 then 1
  a0/t0 give 20 -> 10 (the docstring: THRESHOLD_FACTOR times the largest velocity).

Second pass (the lead, 2026-11-27, 07:57-08:03 UTC, the machine otherwise idle): the four
survivors applied together through the whole default suite of f08c056 (this list merged into
main; no test written after the list existed): ``pytest -n 2 --dist loadfile --timeout 600
tests/``, 12 failed, 4069 passed in 374 s. The 12 failing tests passed when rerun unmutated
(12 passed); each was rerun under each survivor alone, and every survivor fails some of them:

* units_segments_normal_stress_pa: tests/records/test_lab.py,
  tests/records/test_change_interval.py, tests/records/test_detect.py (3 tests);
* artifacts_reset_fix_off_by_one: tests/records/test_detect.py (2: the zoo's rates),
  tests/records/test_change_interval.py, tests/records/test_change_choice.py (3);
* steps_robust_stderr_no_delta: tests/fit/test_reported.py, tests/fit/test_cvfit.py;
* fronts_threshold_last_segment: tests/analysis/test_fronts_generic.py.

So against the whole suite: **40 of 40 killed (100 %, Clopper-Pearson 95 % 91.2-100 %)**.
Of the killing tests only tests/records/test_change_choice.py was written in the same stop
(by a developer who had not seen this list, before it existed); the first three survivors are
killed without it.
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
T_STATIC = ["tests/theory/test_static.py", "tests/theory/test_invariants.py"]
T_STEADY = ["tests/theory/test_steady.py", "tests/theory/test_direct.py"]
T_DIET = ["tests/theory/test_dieterich.py"]
T_STAB = ["tests/theory/test_stability.py", "tests/theory/test_nyquist_generic.py",
          "tests/theory/test_response_bounds.py"]
T_INERTIA = ["tests/ensemble/test_direct_inertia.py", "tests/ensemble/test_invariants_steppers.py"]
T_ENSRES = ["tests/ensemble/test_results_summary.py", "tests/ensemble/test_result_sampling.py",
            "tests/ensemble/test_drives.py"]
T_IFACE = ["tests/ensemble/test_interface.py", "tests/ensemble/test_interface_estimate.py",
           "tests/ensemble/test_interface_generic.py"]
T_LAW = ["tests/rsf/test_rsf.py", "tests/rsf/test_law_edges.py", "tests/fit/test_state_laws.py"]
T_HOPF = ["tests/rsf/test_rsf.py", "tests/analysis/test_rsf_hopf.py", "tests/rsf/test_law_edges.py"]
T_RSFDRIVE = ["tests/rsf/test_rsf.py", "tests/rsf/test_routes.py", "tests/rsf/test_invariants.py"]
T_RSFRES = ["tests/rsf/test_result_pieces.py", "tests/rsf/test_rsf.py"]
T_PROTO = ["tests/io/test_protocol.py", "tests/cli/test_rsf_protocol.py",
           "tests/io/test_protocol_defaults.py"]
T_UNITS = ["tests/io/test_output_units.py", "tests/records/test_segments_csv.py",
           "tests/io/test_units_headers.py"]
T_LAB = ["tests/records/test_lab.py", "tests/records/test_labforms_units.py",
         "tests/plots/test_record_figure_data.py"]
T_DATA = ["tests/io/test_data.py", "tests/io/test_invariants_units.py",
          "tests/records/test_labforms_units.py"]
T_SEG = ["tests/records/test_segmentation_long.py", "tests/records/test_records_helpers.py",
         "tests/records/test_hinge_generic.py"]
T_ART = ["tests/records/test_artifacts_generic.py", "tests/records/test_lab.py"]
T_ELASTIC = ["tests/fit/test_elastic.py", "tests/fit/test_elastic_estimators.py"]
T_LAWCHOICE = ["tests/fit/test_lawchoice_choose.py", "tests/fit/test_lawcolumns.py"]
T_CVTAIL = ["tests/fit/test_cvtail.py", "tests/fit/test_cvfit.py"]
T_HAC = ["tests/fit/test_hac.py", "tests/fit/test_invariants_estimators.py"]
T_STEPS = ["tests/fit/test_steps.py", "tests/fit/test_reported_definitions.py",
           "tests/fit/test_hac.py"]
T_IDENT = ["tests/fit/test_identify.py", "tests/fit/test_identify_definitions.py",
           "tests/fit/test_stiffness_record_merge.py", "tests/fit/test_kcoverage.py"]
T_EXPER = ["tests/fit/test_experiment.py", "tests/fit/test_levels_generic.py"]
T_MACHINE = ["tests/fit/test_fit.py", "tests/fit/test_machine_generic.py",
             "tests/fit/test_onemachine_generic.py"]
T_FLOOR = ["tests/analysis/test_granular_floor.py", "tests/analysis/test_stickslip.py"]
T_SS = ["tests/analysis/test_stickslip.py", "tests/analysis/test_stickslip_force.py",
        "tests/analysis/test_stickslip_measures.py"]
T_CATAL = ["tests/analysis/test_fronts.py", "tests/analysis/test_fronts_generic.py",
           "tests/analysis/test_interface_sweep.py"]
T_EDGE = ["tests/analysis/test_fronts.py", "tests/analysis/test_fronts_helpers.py",
          "tests/analysis/test_fronts_generic.py"]
T_THR = ["tests/analysis/test_fronts.py", "tests/analysis/test_fronts_helpers.py",
         "tests/app/test_interface_outputs.py"]
T_PLOTSUM = ["tests/plots/test_summary_figure_data.py", "tests/plots/test_figure_text.py"]
T_PLOTSTEP = ["tests/plots/test_step_figure_data.py", "tests/plots/test_plots.py"]
T_RSFAPP = ["tests/app/test_rsf_workflow.py", "tests/cli/test_rsf_peer_case.py",
            "tests/app/test_workflows.py"]
T_IFOUT = ["tests/app/test_interface_outputs.py", "tests/app/test_interface_outputs_generic.py"]
T_CLIREC = ["tests/cli/test_records_table.py", "tests/cli/test_cli.py"]
T_SWEEP = ["tests/sweeps/test_sweep_spec.py", "tests/sweeps/test_sweep.py",
           "tests/sweeps/test_axis_units.py"]
T_RESULTS = ["tests/ensemble/test_results_summary.py", "tests/test_simulator_shape.py",
             "tests/rsf/test_summary_path.py"]
T_PROGRAM = ["tests/test_program.py", "tests/io/test_protocol.py"]
T_VALID = ["tests/test_validation.py", "tests/cli/test_bad_values.py"]

# ----------------------------------------------------------------------------- the mutants
# (name, file under src/dryfriction, original, mutated, why plausible, test files)
MUTANTS: list[tuple[str, str, str, str, str, list[str]]] = [
    # ---- theory/ (5)
    ("trap_contact_stiffness_paper_H0", "theory/trap.py",
     "return self.maxwell_jump / self.H0 if self.pinned else math.inf",
     "return self.maxwell_jump / self.H0_paper if self.pinned else math.inf",
     "the contact stiffness with the paper's closed form of H0, valid only in very strong "
     "pinning: Trap(0.3).contact_stiffness (strong pinning, alpha > 3 - 2 sqrt 2) changes",
     T_TRAP),
    ("static_first_order_log_not_log1p", "theory/static.py",
     "return 1.0 + eps * np.log1p(T) * _static_slope_per_eps_loose(alpha)",
     "return 1.0 + eps * np.log(T) * _static_slope_per_eps_loose(alpha)",
     "the first-order static friction with ln T (the large-T asymptote) instead of "
     "ln(1 + T): static_friction_first_order at T = 2 uses ln 2 instead of ln 3, -inf at T = 0",
     T_STATIC),
    ("steady_low_slope_direct0_factor_2", "theory/steady.py",
     "return -1.5 * eps * np.ones_like(mu)",
     "return -3.0 * eps * np.ones_like(mu)",
     "d mu/d ln u of the low-velocity form without the 1/2 of (eps/2)(-3 ln u + K1) in the "
     "athermal branch: steady_log_slope_low_velocity at direct = 0 gives -3 eps, not -1.5 eps",
     T_STEADY),
    ("dieterich_asymptotic_moments_swapped", "theory/dieterich.py",
     "dyn = 4.0 * _forward_moment_loose(1, alpha) + 3.0 * _forward_moment_loose(0, alpha)",
     "dyn = 3.0 * _forward_moment_loose(1, alpha) + 4.0 * _forward_moment_loose(0, alpha)",
     "the coefficients of the first and zeroth moments swapped in C_inf: "
     "dieterich_constant_asymptotic(0.13) changes", T_DIET),
    ("stability_dforce_plus_factor_2", "theory/stability.py",
     "return 6.0 * alpha * (1.0 - alpha / np.sqrt(disc))",
     "return 6.0 * alpha * (1.0 - 2.0 * alpha / np.sqrt(disc))",
     "f_+'(w) with the chain-rule factor of d sqrt(disc)/dw counted twice: the linear "
     "response (Z(lambda), critical stiffness) of the steady state changes", T_STAB),
    # ---- ensemble/ (3)
    ("verlet_velocity_euler", "ensemble/driving.py",
     "V = V + 0.5 * (a + a_new) * dt",
     "V = V + a_new * dt",
     "the inertial slider's velocity update with the new acceleration only (semi-implicit "
     "Euler, first order) instead of velocity Verlet's average: an inertial spring run's "
     "v(t) changes, the error per halving of dt drops by 2 instead of 4", T_INERTIA),
    ("ensemble_applied_force_no_mu_el", "ensemble/result.py",
     "self.mu_el * f_applied, *events))",
     "f_applied, *events))",
     "the recorder's applied force column in reduced units (F/F_el) instead of friction "
     "units: a force-ramp run at mu_el = 0.45 reports the applied load 1/0.45 too high",
     T_ENSRES),
    ("interface_eigenvalue_fixed_ends", "ensemble/interface.py",
     "return 4.0 * math.sin(math.pi * (n - 1) / (2 * n)) ** 2 if n > 1 else 0.0",
     "return 4.0 * math.sin(math.pi * n / (2 * (n + 1))) ** 2 if n > 1 else 0.0",
     "the largest coupling eigenvalue of a chain with fixed ends instead of the free chain: "
     "coupling_eigenvalue_max at n = 4 gives 3.618 instead of 3.414 (time step, estimates)",
     T_IFACE),
    # ---- rsf/ (4)
    ("law_psi2_uses_dc", "rsf/law.py",
     "psi = psi + self.b2 * np.log(self.v0 * np.asarray(theta2, float) / self.dc2)",
     "psi = psi + self.b2 * np.log(self.v0 * np.asarray(theta2, float) / self.dc)",
     "the second state variable's term normalised by the first Dc: friction of a two-state "
     "law (dc2 != dc) shifted by b2 ln(dc2/dc)", T_LAW),
    ("law_hopf_frequency_bare_a", "rsf/law.py",
     "return v / self.dc * math.sqrt((self.b - ap) / ap)",
     "return v / self.dc * math.sqrt((self.b - ap) / self.a)",
     "the Hopf frequency's denominator a instead of a' = a + eta V: hopf_frequency with "
     "damping > 0 too high", T_HOPF),
    ("rsf_drive_stress0_no_damping", "rsf/driving.py",
     "stress0 = float(model.friction(v_init, theta_init, theta2_init)) + damping * v_init",
     "stress0 = float(model.friction(v_init, theta_init, theta2_init))",
     "the initial spring stress without the radiation-damping term: a steady run with "
     "damping > 0 (inertial form) starts out of balance and decelerates", T_RSFDRIVE),
    ("rsf_hermite_h11_sign", "rsf/result.py",
     "h11 = s * s * (s - 1)",
     "h11 = s * s * (1 - s)",
     "the fourth cubic Hermite basis function with the wrong sign: values at t_eval between "
     "solver steps wrong where the slope at the right end is not 0", T_RSFRES),
    # ---- io/ (2)
    ("protocol_rsf_damping_mass_swapped", "io/protocol.py",
     'drive = d.build(SpringSlider, _segments(d), stiffness, d.number("damping", 0.0),\n'
     '                    d.number("mass", 0.0))',
     'drive = d.build(SpringSlider, _segments(d), stiffness, d.number("mass", 0.0),\n'
     '                    d.number("damping", 0.0))',
     "a rate-and-state protocol's drive.damping and drive.mass passed in each other's place: "
     "a TOML with damping = 0.5 only runs a massive undamped slider", T_PROTO),
    ("units_segments_normal_stress_pa", "io/units.py",
     '"normal_stress": "MPa", "normal_force": "kN",',
     '"normal_stress": "Pa", "normal_force": "kN",',
     "segments.csv's header normal_stress[Pa] while the values are written in MPa",
     T_UNITS),
    # ---- records/ (4)
    ("lab_normal_unit_swapped", "records/lab.py",
     'normal_unit = "" if normal is None else ("N" if kinds["normal"] == "force" else "Pa")',
     'normal_unit = "" if normal is None else ("Pa" if kinds["normal"] == "force" else "N")',
     "a record's normal_unit says N for a stress column (MPa) and Pa for a force (kN): the "
     "tables and figures show MPa values as kN and the reverse", T_LAB),
    ("data_day_factor_typo", "records/data.py",
     '"d": 86400.0,',
     '"d": 8640.0,',
     "a day as 8640 s: a time column in d (or a velocity in um/d) read 10x off", T_DATA),
    ("segmentation_rss_uncentred", "records/segmentation.py",
     "r = xs[a:b] - mean - slope * (t[a:b] - t[a:b].mean())",
     "r = xs[a:b] - mean - slope * t[a:b]",
     "the residual of a stretch's line with its intercept taken at t = 0 instead of at the "
     "mean time: rss of a sloped stretch away from t = 0 is large, the pruning of the "
     "segmentation changes", T_SEG),
    ("artifacts_reset_fix_off_by_one", "records/artifacts.py",
     "fix[i + 1:] -= np.linalg.lstsq(A, x[a:b], rcond=None)[0][2]",
     "fix[i:] -= np.linalg.lstsq(A, x[a:b], rcond=None)[0][2]",
     "a displacement reset's offset also subtracted from the sample before the jump: the "
     "corrected record has a spike of one sample at each reset", T_ART),
    # ---- fit/ (8)
    ("elastic_se_ar1_inverted", "fit/elastic.py",
     "se = math.sqrt(s2 / sxx * (1.0 + rho) / (1.0 - rho))",
     "se = math.sqrt(s2 / sxx * (1.0 - rho) / (1.0 + rho))",
     "the AR(1) variance factor of a loading slope inverted: on correlated noise the "
     "stiffness_lo/hi interval of an elastic loading narrows instead of widening", T_ELASTIC),
    ("lawchoice_delta_bic_from_aic_min", "fit/lawchoice.py",
     '"delta_bic": cand[L]["bic"] - bmin,',
     '"delta_bic": cand[L]["bic"] - amin,',
     "delta BIC of each state law taken from the smallest AIC (copy slip): the delta_bic "
     "column is off by bmin - amin", T_LAWCHOICE),
    ("cvtail_next_force_no_mu_el", "fit/cvtail.py",
     "force = level / model.mu_el",
     "force = level",
     "the next segment's starting force from the steady level without dividing by mu_el: "
     "a trap-model series at mu_el != 1 starts each later segment off its steady state",
     T_CVTAIL),
    ("hac_bandwidth_qs_constant", "fit/statistics.py",
     "return int(min(max(math.ceil(1.1447 * (alpha * n) ** (1.0 / 3.0)), 1), n // 2))",
     "return int(min(max(math.ceil(1.3221 * (alpha * n) ** (1.0 / 3.0)), 1), n // 2))",
     "Andrews' constant of the quadratic-spectral kernel (1.3221) in the Bartlett bandwidth: "
     "AR(1) rho = 0.5, n = 1000 gives 17 lags instead of 14", T_HAC),
    ("steps_robust_stderr_no_delta", "fit/steps.py",
     '"stderr": val * se if spec.log else se,',
     '"stderr": se,',
     "the robust standard error of a log-parametrised parameter (dc, stiffness) left in ln "
     "units: sigma_dc is the relative error instead of metres", T_STEPS),
    ("identify_record_k_se_full_width", "fit/identify.py",
     "est[i] = (math.log(k), math.log(hi / lo) / (2.0 * z))",
     "est[i] = (math.log(k), math.log(hi / lo) / z)",
     "a step's standard error of ln k from its full 95 % width instead of the half width: "
     "the record's one-machine interval twice as wide, k_inconsistent flagged at half the "
     "gaps' significance", T_IDENT),
    ("experiment_step_normal_whole_window", "fit/experiment.py",
     "return float(np.median(np.asarray(sn, float)[i:int(w.i_end)]))",
     "return float(np.median(np.asarray(sn, float)[int(w.i_start):int(w.i_end)]))",
     "a step's normal stress as the median over the whole window instead of from the change "
     "on: a window holding a normal-stress step is put at a mix of the two levels",
     T_EXPER),
    ("machine_slope_extreme_up_only", "fit/machine.py",
     "ext = float(after.max() if va > vb else after.min())",
     "ext = float(after.max())",
     "the loading slope's target extreme always the maximum: after a down-step the stretch "
     "read is wrong (the friction falls): loading_slope_stiffness of a down-step changes",
     T_MACHINE),
    # ---- analysis/ (5)
    ("stickslip_floor_radius_not_squared", "analysis/stickslip.py",
     "r2 = float(model.law.radius(np.array([tau_d]))[0]) ** 2",
     "r2 = float(model.law.radius(np.array([tau_d]))[0])",
     "the granular floor with r_d instead of r_d^2 (eq. 23): granular_floor changes by r_d",
     T_FLOOR),
    ("stickslip_summarise_force_no_mu_el", "analysis/stickslip.py",
     "st = analyse(res.t, res.x, res.v, spring_force(res, drive, model.mu_el), u=u,",
     "st = analyse(res.t, res.x, res.v, spring_force(res, drive), u=u,",
     "the sweep summary analyses the spring force in F_el units while the floor is in "
     "friction units: amplitude, range and mean force off by 1/mu_el at mu_el != 1", T_SS),
    ("catalogue_alpha_err_no_minus_1", "analysis/catalogue.py",
     "err = (alpha - 1.0) / math.sqrt(fit.size)",
     "err = alpha / math.sqrt(fit.size)",
     "the standard error of the magnitude-frequency exponent as alpha/sqrt(n) instead of "
     "(alpha - 1)/sqrt(n) (Clauset et al.): alpha_err too large", T_CATAL),
    ("catalogue_right_edge_strict", "analysis/catalogue.py",
     "return bool(e.elements[-1] >= n_x - 1 - edge_gap)",
     "return bool(e.elements[-1] > n_x - 1 - edge_gap)",
     "an event reaching exactly edge_gap elements from the right (loaded) edge not counted "
     "as touching it: precursors of a right-edge loading lose those events", T_EDGE),
    ("fronts_threshold_last_segment", "analysis/fronts.py",
     "top = max(speeds, default=0.0)",
     "top = speeds[-1] if speeds else 0.0",
     "the default front threshold from the last segment's velocity instead of the largest: "
     "a program 2 -> 1 a0/t0 gets 10 instead of 20 times the loading velocity", T_THR),
    # ---- plots/ (2)
    ("plot_summary_label_first_normal", "plots/summary.py",
     'labels[lv] = level_label(float(np.mean(v)), str(rows[0]["normal_unit"]))',
     'labels[lv] = level_label(float(v[0]), str(rows[0]["normal_unit"]))',
     "a level's legend label from its first step's normal stress instead of the level's "
     "mean: a level of 20 and 21 MPa is labelled 20 MPa instead of 20.5 MPa", T_PLOTSUM),
    ("plot_step_residual_sign", "plots/steps.py",
     "bot.scatter(xv, d.mu - model, **_DATA)",
     "bot.scatter(xv, model - d.mu, **_DATA)",
     "the step figure's residual panel drawn as model minus data: its y data negated",
     T_PLOTSTEP),
    # ---- app/ (2)
    ("app_stickslip_no_kick", "app/ratestate.py",
     "v_init = 1.01 * v1",
     "v_init = v1",
     "the rsf stick-slip case starts exactly at steady state (no 1 % kick): on an unstable "
     "spring the run stays on the unstable steady state for a long time", T_RSFAPP),
    ("interface_outputs_speed_bounds_swapped", "app/interface_outputs.py",
     '"speed_low": np.asarray(rows["low"]),\n        "speed_high": np.asarray(rows["high"])}',
     '"speed_low": np.asarray(rows["high"]),\n        "speed_high": np.asarray(rows["low"])}',
     "fronts.csv's speed_low and speed_high columns written in each other's place", T_IFOUT),
    # ---- cli/ (1)
    ("cli_records_normal_scale_swapped", "cli/records.py",
     'scale, shown = (1e-3, "kN") if unit == "N" else (1e-6, "MPa")',
     'scale, shown = (1e-6, "kN") if unit == "N" else (1e-3, "MPa")',
     "the record-fit table's normal column scaled by the other unit's factor: 20 MPa "
     "printed as 2e+04 MPa", T_CLIREC),
    # ---- sweeps/ (1)
    ("sweep_lin_axis_no_endpoint", "sweeps/sweep.py",
     "return tuple(float(v) for v in np.linspace(start, stop, n))",
     "return tuple(float(v) for v in np.linspace(start, stop, n, endpoint=False))",
     "a {lin = [start, stop, n]} axis without its stop: [0, 1, 3] gives 0, 1/3, 2/3", T_SWEEP),
    # ---- results.py, program.py, validation.py (3)
    ("results_mean_mu_unweighted", "results.py",
     "mean = float(np.trapezoid(mu, t) / span) if span > 0 else float(np.mean(mu))",
     "mean = float(np.mean(mu))",
     "summary's mean_mu as the mean of the samples instead of the time average: a run "
     "sampled non-uniformly (rsf solver steps, every_slip) reports a biased mean", T_RESULTS),
    ("program_segment_index_left", "program.py",
     'i = np.searchsorted(self.times, t, side="right") - 1',
     'i = np.searchsorted(self.times, t, side="left") - 1',
     "the segment of a time on a boundary taken as the one before: program.velocity at a "
     "segment's start gives the previous segment's velocity (and -1 clipped to 0 at t = 0)",
     T_PROGRAM),
    ("validation_lo_open_ignored", "validation.py",
     "bad |= (arr <= lo) if lo_open else (arr < lo)",
     "bad |= arr < lo",
     "an open lower bound checked as closed: a = 0, dc = 0, --a0 0 pass the checks (refused "
     "later or not at all)", T_VALID),
]


# ----------------------------------------------------------------------------- the runner
def main(argv: list[str]) -> int:
    from benchmarks.blind_mutants import run_set  # the runner all sets share

    return run_set(argv, MUTANTS, "blind_mutants8_results.jsonl")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
