"""A second blind mutant set for issue 25's "Done when" (fresh: >= 30, killed >= 90 %).

Written against main at commit af8a8af09d3f1ae5a4d46907018d0334c9b80b56 (2026-11-26) by a
reviewer (branch ``blind2``) who read ``src/dryfriction``, docs and the README but neither
``tests/mutants.py``, nor any file under ``tests/``, nor the list of
``benchmarks/blind_mutants.py`` (only its runner, reused here). The test files of each mutant
were chosen by their names (``ls tests/``). This list was committed before any mutant was run.
Each mutant is an exact text replacement whose original occurs exactly once in its file.

Run (from the repository root, one mutant at a time)::

    .venv/bin/python benchmarks/blind_mutants2.py            # all, survivors then whole suite
    .venv/bin/python benchmarks/blind_mutants2.py NAME ...   # some
    .venv/bin/python benchmarks/blind_mutants2.py --check    # originals unique, nothing run
    .venv/bin/python benchmarks/blind_mutants2.py --no-whole          # chosen files only
    .venv/bin/python benchmarks/blind_mutants2.py --whole-only NAME   # whole suite only

For each mutant: apply, ``pytest -x -q -p no:cacheprovider --timeout 300`` on its chosen
files, killed/survived, restore (always; :func:`benchmarks.blind_mutants.run_one` restores the
file, its mtime and its ``__pycache__``/Numba cache entries). A survivor is run once against
the whole default suite. The first failing test of each kill is rerun on the unmutated tree.
Results are appended to ``$TMPDIR/blind_mutants2_results.jsonl``.

Measured at af8a8af with its flat ``tests/`` layout; after the merge that moved the records
modules and put the tests in a folder per package, :func:`benchmarks.blind_mutants.resolve`
maps each mutant to the new paths (a test file gone under its old name: its package's test
folder).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

# ----------------------------------------------------------------------------- test choice
# by file name only (ls tests/), never by their content
T_DIRECT = ["tests/test_direct.py", "tests/test_direct_inertia.py",
            "tests/test_invariants_theory.py", "tests/test_independent_reference.py"]
T_CREEP = ["tests/test_creep.py", "tests/test_units.py", "tests/test_invariants_theory.py"]
T_STEADY = ["tests/test_steady.py", "tests/test_direct.py", "tests/test_invariants_theory.py",
            "tests/test_independent_reference.py"]
T_STATIC = ["tests/test_static.py", "tests/test_dieterich.py", "tests/test_invariants_theory.py"]
T_LAW = ["tests/test_rsf.py", "tests/test_state_laws.py", "tests/test_invariants_rsf.py",
         "tests/test_independent_reference.py"]
T_RSFRES = ["tests/test_rsf.py", "tests/test_rsf_routes.py", "tests/test_invariants_rsf.py"]
T_STEPPER = ["tests/test_rsf.py", "tests/test_state_laws.py", "tests/test_rsf_routes.py",
             "tests/test_invariants_steppers.py"]
T_DATA = ["tests/test_data.py", "tests/test_invariants_units.py", "tests/test_io.py"]
T_LAB = ["tests/test_lab.py", "tests/test_invariants_units.py", "tests/test_records.py"]
T_FILES = ["tests/test_file_safety.py", "tests/test_io.py"]
T_LABSTEPS = ["tests/test_lab.py", "tests/test_records.py", "tests/test_fit_steps.py"]
T_SEG = ["tests/test_detect.py", "tests/test_signals.py", "tests/test_lab.py"]
T_STAT = ["tests/test_fit.py", "tests/test_fit_hac.py", "tests/test_invariants_estimators.py"]
T_STEPS = ["tests/test_fit_steps.py", "tests/test_fit_reported.py",
           "tests/test_invariants_estimators.py"]
T_ENGINE = ["tests/test_fit.py", "tests/test_fit_reported.py", "tests/test_compare.py"]
T_IDENT = ["tests/test_fit_identify.py", "tests/test_fit_reported.py", "tests/test_fit_steps.py"]
T_LOADPOINT = ["tests/test_fit_loadpoint.py", "tests/test_fit_kcoverage.py",
               "tests/test_invariants_estimators.py"]
T_ELASTIC = ["tests/test_fit_elastic.py", "tests/test_invariants_estimators.py"]
T_SS = ["tests/test_stickslip.py", "tests/test_stickslip_measures.py"]
T_BIF = ["tests/test_bifurcation.py"]
T_THERMAL = ["tests/test_direct_inertia.py", "tests/test_invariants_ensemble.py",
             "tests/test_ensemble.py", "tests/test_direct.py"]
T_ENSRES = ["tests/test_ensemble.py", "tests/test_invariants_ensemble.py"]
T_ENSDRV = ["tests/test_driving.py", "tests/test_direct_inertia.py",
            "tests/test_invariants_ensemble.py"]
T_RESULTS = ["tests/test_physical_bounds.py", "tests/test_rsf.py", "tests/test_cli_simulate.py"]
T_PLOTS = ["tests/test_plots.py", "tests/test_figure_formats.py"]
T_PLOTREC = ["tests/test_plots.py", "tests/test_records.py", "tests/test_lab.py"]
T_CLIFIT = ["tests/test_cli.py", "tests/test_records.py", "tests/test_bad_values.py"]
T_CLI = ["tests/test_cli.py", "tests/test_bad_values.py", "tests/test_cli_words.py"]
T_CLIRUN = ["tests/test_cli.py", "tests/test_cli_simulate.py", "tests/test_file_safety.py",
            "tests/test_bad_values.py"]

# ----------------------------------------------------------------------------- the mutants
# (name, file under src/dryfriction, original, mutated, why plausible, test files)
MUTANTS: list[tuple[str, str, str, str, str, list[str]]] = [
    # --- theory
    ("direct_scalar_no_2vref", "theory/direct.py",
     "lx = math.log(abs(v) / (2.0 * v_ref)) + 1.0 / direct",
     "lx = math.log(abs(v) / v_ref) + 1.0 / direct",
     "the scalar twin of g(V) used by the ensemble's solvers forgets the 2 of asinh(V/(2V_ref)"
     " e^{1/A}): every force of a run with the direct effect is off by A ln 2", T_DIRECT),
    ("creep_t0_no_prefactor", "theory/creep.py",
     "return math.exp(-x - math.log(self.edot0) - math.log(x))",
     "return math.exp(-x - math.log(self.edot0))",
     "eq. 18's t0 = 1/(edot0 (Y/S) e^{Y/S}) without its (Y/S) prefactor: t0 off by Y/S = 1/eps",
     T_CREEP),
    ("steady_slope_no_g", "theory/steady.py",
     "+ junction_strength(u, direct, v_ref) * slope",
     "+ slope",
     "d mu/d ln u with the direct effect: the ageing term not multiplied by g(u) (g = 1 only "
     "at u = v_ref)", T_STEADY),
    ("static_slope_sign", "theory/static.py",
     "return (3.0 * trap.H1 + (trap.y_c - 1.0) * f1) / (2.0 * trap.H0)",
     "return (3.0 * trap.H1 + (1.0 - trap.y_c) * f1) / (2.0 * trap.H0)",
     "first-order static slope: sign of the (y_c - 1) boundary term flipped", T_STATIC),
    # --- rsf
    ("rsf_prz_heal_rate", "rsf/law.py",
     '"prz": 0.5', '"prz": 1.0',
     "PRZ law in the theta = theta'/2 convention heals at 1/2 at rest: the closed-form hold "
     "peak takes theta' 's rate 1", T_LAW),
    ("rsf_kc_inertia_a_not_aprime", "rsf/law.py",
     "return (self.b - ap) / self.dc * (1.0 + mass * v * v / (ap * self.dc))",
     "return (self.b - ap) / self.dc * (1.0 + mass * v * v / (self.a * self.dc))",
     "k_c with damping and mass: the inertial factor keeps a instead of a' = a + eta V "
     "(only when both are non-zero)", T_LAW + ["tests/test_stability.py"]),
    ("rsf_hopf_a_not_aprime", "rsf/law.py",
     "return v / self.dc * math.sqrt((self.b - ap) / ap)",
     "return v / self.dc * math.sqrt((self.b - ap) / self.a)",
     "Hopf frequency with damping: denominator a instead of a' = a + eta V",
     T_LAW + ["tests/test_stability.py"]),
    ("rsf_stress_no_damping", "rsf/result.py",
     "stress = mu + damping * v", "stress = mu",
     "quasi-static result: the reported stress (and the slip from the force balance) "
     "without the radiation-damping term eta V", T_RSFRES),
    ("rsf_kc_first_load_velocity", "rsf/result.py",
     "v = float(self.load_velocity[-1]) if self.load_velocity[-1] > 0",
     "v = float(self.load_velocity[0]) if self.load_velocity[0] > 0",
     "summary.json's critical_stiffness_per_m at the first load velocity instead of the final",
     T_RSFRES + ["tests/test_cli_simulate.py"]),
    ("stepper_damping_no_v", "rsf/stepper.py",
     "den = a * c + eta * v", "den = a * c + eta",
     "quasi-dynamic d ln V/dt: the damping's share eta dV/dt = eta V d lnV/dt written without "
     "V (compiled kernel; matters only where eta V is comparable to a)", T_STEPPER),
    ("stepper_prz_no_half", "rsf/stepper.py",
     "return 0.5 * (e - q), -q, -0.5 * (e + q)",
     "return (e - q), -q, -0.5 * (e + q)",
     "compiled PRZ law: the 1/2 of the theta = theta'/2 convention dropped from the rate "
     "(not from its derivatives)", T_STEPPER),
    # --- io
    ("data_day_unit", "io/data.py", '"d": 86400.0,', '"d": 8640.0,',
     "a day as 8640 s (a zero dropped) in the CSV reader's unit table", T_DATA),
    ("lab_hr_unit", "io/lab.py", '"hr": 3600.0}', '"hr": 60.0}',
     "a record's 'hr' time unit read as a minute", T_LAB),
    ("lab_kpa_unit", "io/lab.py", '"kPa": 1e3,', '"kPa": 1e-3,',
     "kPa read as 1e-3 Pa: friction = shear/normal wrong when the two columns carry different "
     "units, the normal stress off by 1e6", T_LAB),
    ("lab_decimal_comma_csv", "io/lab.py",
     'decimal_comma = delim != "," and bool(re.search(r"\\d,\\d", sample))',
     'decimal_comma = bool(re.search(r"\\d,\\d", sample))',
     "decimal-comma detection also on comma-separated files: '1,0.5' becomes '1.0.5'",
     T_LAB),
    ("lab_time_repeat_allowed", "io/lab.py",
     "dec = np.flatnonzero(np.diff(t) <= 0.0)", "dec = np.flatnonzero(np.diff(t) < 0.0)",
     "a repeated time stamp accepted (refusal missing): zero time steps reach the velocity",
     T_LAB),
    ("data_zero_velocity", "io/data.py",
     'if c == "V" and x <= 0.0', 'if c == "V" and x < 0.0',
     "a steady data set with V = 0 accepted (refusal missing): ln V later", T_DATA),
    ("files_confined_dotdot", "io/files.py",
     'all(p not in ("", ".", "..") for p in rel.split("/"))',
     'all(p not in ("", ".") for p in rel.split("/"))',
     "a manifest entry '../victim.txt' counted as ours: a rerun may remove a file outside the "
     "results folder", T_FILES),
    ("files_remove_changed", "io/files.py",
     "if rel in digests or not is_ours(out, rel, digest):",
     "if rel in digests:",
     "a file of the previous run that the user has edited since is removed anyway", T_FILES),
    ("files_csv_precision", "io/files.py",
     "w.writerow([repr(float(v)) if isinstance(v, (float, np.floating)) else v for v in row])",
     'w.writerow([f"{float(v):.6g}" if isinstance(v, (float, np.floating)) else v for v in row])',
     "CSV floats written to 6 significant digits, not full precision", T_FILES + T_DATA[:1]),
    ("labsteps_spec_absolute_t", "io/labsteps.py",
     'return ",".join(f"{s.t_start - t0:.10g}:{s.velocity:.6g}" for s in segments)',
     'return ",".join(f"{s.t_start:.10g}:{s.velocity:.6g}" for s in segments)',
     "the --segments line of segments.csv with absolute times, not from the first sample "
     "(wrong for a record whose clock does not start at 0)", T_LABSTEPS),
    ("labsteps_lead_max", "io/labsteps.py",
     "lead = min(pre_fraction * prev.duration, pre_slip / abs(prev.velocity))",
     "lead = max(pre_fraction * prev.duration, pre_slip / abs(prev.velocity))",
     "a step window reaches back the larger of the two leads, into the previous transient",
     T_LABSTEPS),
    ("seg_block_noise_floor", "io/segmentation.py",
     "sb = max(1.0 / np.sqrt(block), noise_level(xb))",
     "sb = max(1.0, noise_level(xb))",
     "long records (block-averaged): the floor of the averaged noise not divided by "
     "sqrt(block), so small changes are missed in big files only", T_SEG),
    # --- fit
    ("stat_runs_var_n2", "fit/statistics.py",
     "(n * n * (n - 1.0))", "(n * (n - 1.0))",
     "Wald-Wolfowitz variance with n (n - 1) in the denominator instead of n^2 (n - 1)",
     T_STAT),
    ("stat_t_one_sided", "fit/statistics.py",
     "float(stats.t.ppf(0.975, dof))", "float(stats.t.ppf(0.95, dof))",
     "the Student-t 95 % quantile one-sided: every Wald interval without given sigma too narrow",
     T_STAT),
    ("stat_hac_no_dof", "fit/statistics.py",
     "cov = bread @ omega @ bread * (n / (n - p))", "cov = bread @ omega @ bread",
     "HAC sandwich without its small-sample factor n/(n - p)", T_STAT),
    ("stat_bartlett_weight", "fit/statistics.py",
     "omega += (1.0 - lag / (lags + 1.0)) * (g + g.T)",
     "omega += (1.0 - lag / lags) * (g + g.T)",
     "Bartlett weights 1 - l/L instead of 1 - l/(L + 1): the last lag gets weight 0", T_STAT),
    ("stat_f_test_half", "fit/statistics.py",
     "F = (max(delta, 0.0) / df1) / (2.0 * sep_cost / df2)",
     "F = (max(delta, 0.0) / df1) / (sep_cost / df2)",
     "the consistency F test forgets cost = RSS/2 in the denominator", T_STAT),
    ("steps_sigma_amb_sign", "fit/steps.py",
     'se_of(grad("a") - grad("b"))', 'se_of(grad("a") + grad("b"))',
     "sigma of a - b with the covariance term of the wrong sign (the error of a + b)", T_STEPS),
    ("steps_noise_dof", "fit/steps.py",
     "return float(math.sqrt(r @ r / (mu.size - 2)))",
     "return float(math.sqrt(r @ r / mu.size))",
     "steady noise about a fitted line without removing its two degrees of freedom", T_STEPS),
    ("engine_rms_half_cost", "fit/engine.py",
     "goodness.update(rms_residual=math.sqrt(2.0 * cost / n),",
     "goodness.update(rms_residual=math.sqrt(cost / n),",
     "fit.json's rms_residual from cost = RSS/2 read as RSS", T_ENGINE),
    ("engine_reduced_chi2_n", "fit/engine.py",
     "reduced_chi2=chi2 / dof if dof > 0 else None",
     "reduced_chi2=chi2 / n if dof > 0 else None",
     "reduced chi-square over n instead of n - p", T_ENGINE),
    ("engine_akaike_no_half", "fit/engine.py",
     "w = np.exp(-(aic - aic.min()) / 2.0)", "w = np.exp(-(aic - aic.min()))",
     "Akaike weights exp(-delta AIC) instead of exp(-delta AIC / 2)", T_ENGINE),
    ("engine_dlnx_step", "fit/engine.py",
     '"value": float((f[2] - f[0]) / (2 * math.log(1.01))), "unit": ""}',
     '"value": float((f[2] - f[0]) / (2 * 0.01)), "unit": ""}',
     "derived d y/d ln x with the relative step 0.01 for ln(1.01) and the non-symmetric "
     "points x/1.01, x*1.01 (0.5 % off)", T_ENGINE),
    ("results_no_identifiability_column", "fit/results.py",
     '            "identifiability": self.identifiability,\n', "",
     "the parameter table (to_records, the CSV/dataframe) without its identifiability column",
     T_ENGINE + ["tests/test_cli.py"]),
    ("identify_amb_no_chain", "fit/identify.py",
     'g_amb[names.index("a")], g_amb[names.index("b")] = vals["a"], -vals["b"]',
     'g_amb[names.index("a")], g_amb[names.index("b")] = 1.0, -1.0',
     "the delta-method gradient of a - b in the fitted log variables without the chain rule: "
     "steps.csv's a_minus_b_lo/_hi wrong", T_IDENT),
    ("identify_misfit_flag_dropped", "fit/identify.py",
     '        words.append("misfit")\n', "",
     "the misfit word not written to steps.csv's flags (the notes still say it)", T_IDENT),
    ("loadpoint_noise_no_sqrt2", "fit/loadpoint.py",
     "noise = float(1.4826 * np.median(np.abs(d - np.median(d))) / math.sqrt(2.0))",
     "noise = float(1.4826 * np.median(np.abs(d - np.median(d))))",
     "sample noise from first differences without the /sqrt 2", T_LOADPOINT),
    ("loadpoint_change_time_half", "fit/loadpoint.py",
     "var += (bread @ J.T @ (0.5 * (moved[0] - moved[1]))) ** 2",
     "var += (bread @ J.T @ (moved[0] - moved[1])) ** 2",
     "the change-time error's central difference without its 1/2 (that share of the variance "
     "x4)", T_LOADPOINT),
    ("elastic_se_white", "fit/elastic.py",
     "se = math.sqrt(s2 / sxx * (1.0 + rho) / (1.0 - rho))",
     "se = math.sqrt(s2 / sxx)",
     "the elastic slope's error without the AR(1) widening (white-noise formula)", T_ELASTIC),
    # --- analysis
    ("stickslip_force_no_mu_el", "analysis/stickslip.py",
     "spring_force(res, drive, model.mu_el), u=u,",
     "spring_force(res, drive), u=u,",
     "summarise analyses the spring force in F_el while the floor is in mu_el F_el "
     "(amplitudes off by mu_el)", T_SS),
    ("bif_hysteresis_down_leg", "analysis/bifurcation.py",
     'hyst = [r["d"] for r in scan["up"] if r["d"] <= 0.0',
     'hyst = [r["d"] for r in scan["down"] if r["d"] <= 0.0',
     "hysteresis looked for on the way down (which starts from the stable side) instead of "
     "the way up: a subcritical Hopf classified supercritical", T_BIF),
    # --- ensemble
    ("thermal_inverse_no_2", "ensemble/thermal.py",
     "return 2.0 * v_ref * math.exp(-1.0 / direct) * math.sinh(z)",
     "return v_ref * math.exp(-1.0 / direct) * math.sinh(z)",
     "the velocity from a junction strength g: the 2 of V_c = 2 V_ref e^{-1/A} dropped in "
     "the small-g branch only (creep below the crossover)", T_THERMAL),
    ("ensres_snapshot_no_mu_el", "ensemble/result.py",
     's["force"] = s["force"] * ens.force_scale * self.mu_el',
     's["force"] = s["force"] * ens.force_scale',
     "snapshot per-trap forces not multiplied by mu_el (the time series is)", T_ENSRES),
    ("ensdrv_spring0_no_damping", "ensemble/driving.py",
     "f_spring0 = o.force + drive.damping * v0 if spring",
     "f_spring0 = o.force if spring",
     "the spring's initial stretch balances friction only, not friction + eta V0: a start "
     "off the steady state with damping", T_ENSDRV),
    # --- shared results
    ("results_path_length_abs", "results.py",
     '"path_length": float(np.sum(np.abs(np.diff(x)))),',
     '"path_length": float(np.abs(np.sum(np.diff(x)))),',
     "summary.json's path_length as |net slip| (abs outside the sum)", T_RESULTS),
    # --- plots
    ("plot_fit_residual_sign", "plots/fits.py",
     "r = y - f", "r = f - y",
     "fit figure's residual panel drawn as model - data", T_PLOTS),
    ("plot_fit_no_status", "plots/fits.py",
     'status = "" if result.success else "  [NOT CONVERGED]"', 'status = ""',
     "a fit that did not converge drawn without saying so in its title", T_PLOTS),
    ("plot_record_normal_scale", "plots/record.py",
     'unit, scale = ("MPa", 1e-6) if record.normal_unit == "Pa" else ("kN", 1e-3)',
     'unit, scale = ("MPa", 1e-3) if record.normal_unit == "Pa" else ("kN", 1e-3)',
     "record figure's normal stress panel labelled MPa but scaled by 1e-3 (kPa)", T_PLOTREC),
    # --- cli
    ("cli_exit_1_on_bad_input", "cli/common.py",
     "            error_line(option_named(str(exc)))\n            raise typer.Exit(2) from None",
     "            error_line(option_named(str(exc)))\n            raise typer.Exit(1) from None",
     "bad input exits 1, not 2", T_CLI),
    ("cli_fit_wald_interval_printed", "cli/fitting.py",
     "iv = p.profile_95 or p.interval_95", "iv = p.interval_95 or p.profile_95",
     "the fit table prints the Wald interval where a profile interval exists", T_CLIFIT),
    ("cli_fit_vref_unchecked", "cli/fitting.py",
     '    check_scalar("--v-ref", v_ref, V_MIN, V_MAX)\n', "",
     "--v-ref not checked before work (refusal missing or late, naming v_ref)", T_CLIFIT),
    ("cli_fit_no_exit_on_failure", "cli/fitting.py",
     "                  soft_wrap=True)\n        raise typer.Exit(1)",
     "                  soft_wrap=True)",
     "a fit that did not converge exits 0", T_CLIFIT),
    ("cli_rsf_out_checked_late", "app/ratestate.py",  # the rsf workflow moved to app/
     "    if out is not None:\n        check_output_dir(out, force=force)\n"
     "    if on_start is not None:\n        on_start()",
     "    if on_start is not None:\n        on_start()",
     "rsf: a bad --out refused only after the run (work done first)", T_CLIRUN),
]


# ----------------------------------------------------------------------------- the runner
def main(argv: list[str]) -> int:
    from benchmarks.blind_mutants import run_set  # the runner all sets share

    return run_set(argv, MUTANTS, "blind_mutants2_results.jsonl")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
