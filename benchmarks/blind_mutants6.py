"""A sixth blind mutant set for issue 25's "Done when" (fresh: >= 30, killed >= 90 %).

Written against main at commit 3c2cfc3d376656f39383184db181ca195e217285 (2026-11-27) by a
reviewer (branch ``blind6``) who read ``src/dryfriction`` (theory/direct.py, theory/units.py,
theory/creep.py, theory/hopf.py, theory/static.py, theory/steady.py, theory/trap.py (parts),
ensemble/interface.py, ensemble/thermal.py, ensemble/population.py, rsf/law.py, rsf/spring.py,
rsf/stepper.py, rsf/stability.py, io/protocol.py, io/files.py, io/spacetime.py, io/units.py,
records/data.py, records/lab.py, records/labsteps.py, records/segmentation.py,
records/detection.py, fit/statistics.py, fit/steps.py, fit/loadpoint.py, fit/engine.py,
fit/identify.py, fit/models.py (parts), analysis/stickslip.py, analysis/bifurcation.py,
analysis/rsf_hopf.py, analysis/rsf_view.py, analysis/fronts.py, plots/record.py,
plots/fronts.py, plots/runs.py, plots/steps.py, app/ratestate.py, app/fitting.py,
app/theory.py, app/runs.py, cli/common.py, cli/model.py, sweeps/sweep.py, program.py) but
neither ``tests/mutants.py``, nor any file under ``tests/`` (only their names, ``ls -R
tests/``), nor the MUTANTS lists of ``benchmarks/blind_mutants.py`` ... ``blind_mutants5.py``,
nor docs/quality.md, nor any other worktree; of ``blind_mutants4.py`` only its docstring, its
test-choice helpers and its runner (reused here), of ``blind_mutants.py`` only its runner
functions. The test files of each mutant were chosen by their names. This list was committed
before any mutant was run. Each mutant is an exact text replacement whose original occurs
exactly once in its file; each changes some output for some reasonable input (said in its
description), none is meant to be equivalent.

Run (from the repository root, one mutant at a time)::

    .venv/bin/python benchmarks/blind_mutants6.py --check             # originals unique
    .venv/bin/python benchmarks/blind_mutants6.py --no-whole          # chosen files only
    .venv/bin/python benchmarks/blind_mutants6.py --no-whole NAME ... # some

For each mutant: apply, ``pytest -x -q -p no:cacheprovider --timeout 300`` on its chosen
files, killed/survived, restore (always: :func:`benchmarks.blind_mutants.run_one`). The first
failing test of each kill is rerun on the unmutated tree. Results are appended to
``$TMPDIR/blind_mutants6_results.jsonl``.

The list was committed as 37b0c7e before any mutant ran. Measured on 3c2cfc3 (the list's
commit's parent; 2026-11-27, 05:32-05:38 UTC, 2 shared cores), chosen files only
(``--no-whole``, 272 s of pytest in all): **24 of 32 killed (75.0 %, Clopper-Pearson 95 %
56.6-88.5 %)**. Every kill's first failing test passed when rerun on the unmutated tree.
``program_slip_time_signed`` is killed at the collection of tests/test_program.py (a
module-level program with a backward slip segment is refused: the mutant's own behaviour; the
package and ``dryfriction --help`` still import). The whole-suite pass of the survivors was not
run here (the lead's).

One survivor is an equivalent mutant, a mistake of this list: ``loadpoint_hinge_jacobian_
swapped``. With the intercept column in the Jacobian, the swapped tau column ``-v2 [t<tau] -
v1 [t>tau]`` equals minus the right one plus a constant, a reparametrisation that leaves
``cov[3, 3]`` unchanged (checked: sigma_t_change equal to 1e-14 relative on a 1 -> 10 um/s
hinge). Without it: 24 of 31 (77.4 %, 58.9-90.4 %). Either way, under the 90 % of the "Done
when".

Killed (24): direct_ratio_no_2, units_mu_el_wrong_side, creep_tv_log_eps_sign,
hopf_amplitude_no_2, interface_coupling_energy_no_half, thermal_inverse_big_z_factor_2,
snapshot_force_one_radius, spring_theta2_uses_dc, protocol_pull_first_segment,
lab_hr_as_minutes, labsteps_kN_factor_inverted, detection_extrapolation_exponent,
runs_test_mean_no_plus_1, steady_noise_dof_1, engine_log_slope_log10,
stickslip_stick_fraction_shift, rsf_hopf_dc_ratio_inverted, rsf_view_healing_short_holds,
fronts_normal_load_times_mu_el, app_shs_reload_at_v2, app_record_fit_trend_default_off,
cli_table_6_digits, sweep_log_axis_logspace, program_slip_time_signed.

Survived their chosen files (8), with what a test would have to check (the non-equivalence of
the first four checked by hand on the mutated tree, outside the tests):

* ``law_prz_hold_heal_1`` (rsf/law.py): RateState(state_law="prz").hold_peak_friction against
  mu(v, Dc/v + t_hold/2) (PRZ at rest: dtheta/dt = 1/2); mutated, a=0.01 b=0.015 Dc=1e-5
  v=1e-6 t_hold=100 s gives 0.63597 instead of 0.62688.
* ``json_inf_not_null`` (io/files.py): to_jsonable(inf) is None / a summary.json with an
  infinite value (stiffness = inf) parses with a strict JSON reader (json.loads(...,
  parse_constant=raise)).
* ``bifurcation_hysteresis_d0_excluded`` (analysis/bifurcation.py): classify() on a scan whose
  way up oscillates at d = 0 only: subcritical, hysteresis_d [0.0] (mutated: supercritical, []).
* ``cli_static_pull_velocity_dropped`` (cli/model.py): ``dryfriction static --eps 0.02 --T 10
  --direct 0.02 --pull-velocity 1`` prints mu_s (1.051345781); mutated it refuses.
* ``ftest_rss_factor_2`` (fit/statistics.py): consistency_test's F against its definition
  ((RSS_joint - RSS_sep)/df1)/(RSS_sep/df2) with RSS = 2 cost, at generic costs.
* ``loadpoint_hinge_jacobian_swapped`` (fit/loadpoint.py): equivalent (above); no test can.
* ``plot_record_program_no_t0`` (plots/record.py): the record figure of a record starting at
  t != 0: the load-program segments' x data start at 0 like the measured velocity's.
* ``plot_fronts_floor_10`` (plots/fronts.py): the space-time map's array floor (and colour-bar
  label) at log10(threshold/100).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

# ----------------------------------------------------------------------------- test choice
# by file name only (ls -R tests/), never by their content
T_DIRECT = ["tests/theory/test_direct.py", "tests/ensemble/test_direct_inertia.py"]
T_UNITS = ["tests/theory/test_units.py"]
T_CREEP = ["tests/theory/test_creep.py", "tests/theory/test_creep_edges.py"]
T_HOPF = ["tests/theory/test_hopf.py"]
T_IFACE = ["tests/ensemble/test_interface.py", "tests/ensemble/test_interface_generic.py"]
T_INERTIA = ["tests/ensemble/test_direct_inertia.py", "tests/ensemble/test_invariants_steppers.py"]
T_SNAP = ["tests/ensemble/test_snapshot_force.py", "tests/ensemble/test_population.py"]
T_LAW = ["tests/rsf/test_law_edges.py", "tests/rsf/test_state_rate.py", "tests/rsf/test_rsf.py"]
T_SPRING = ["tests/rsf/test_rsf.py", "tests/rsf/test_routes.py"]
T_SPRINGPT = ["tests/io/test_spring_point.py", "tests/io/test_protocol.py"]
T_JSON = ["tests/io/test_output_units.py", "tests/io/test_io.py"]
T_LAB = ["tests/records/test_labforms_units.py", "tests/io/test_invariants_units.py",
         "tests/records/test_lab.py"]
T_SEGCSV = ["tests/records/test_segments_csv.py", "tests/records/test_lab.py"]
T_DETECT = ["tests/records/test_detect.py", "tests/records/test_change_interval.py"]
T_STAT = ["tests/fit/test_statistics_generic.py", "tests/fit/test_statistics_edges.py",
          "tests/fit/test_reported_definitions.py"]
T_STEPS = ["tests/fit/test_steps.py", "tests/fit/test_invariants_estimators.py",
           "tests/fit/test_steady_level.py"]
T_LOADPT = ["tests/fit/test_loadpoint.py", "tests/fit/test_load_program.py"]
T_ENGINE = ["tests/fit/test_fit.py", "tests/fit/test_reported.py"]
T_SS = ["tests/analysis/test_stickslip_measures.py", "tests/analysis/test_stickslip.py"]
T_RSFHOPF = ["tests/analysis/test_rsf_hopf.py"]
T_BIF = ["tests/analysis/test_bifurcation.py", "tests/cli/test_bifurcation.py"]
T_VIEW = ["tests/analysis/test_rsf_view.py", "tests/analysis/test_rsf_twin.py"]
T_FRONTS = ["tests/analysis/test_fronts_generic.py", "tests/analysis/test_fronts.py",
            "tests/app/test_interface_outputs_generic.py"]
T_PLOTREC = ["tests/plots/test_reported_artists.py", "tests/plots/test_plots.py"]
T_PLOTFRONTS = ["tests/plots/test_fronts_figures.py"]
T_RSFAPP = ["tests/app/test_rsf_workflow.py", "tests/app/test_reload_time.py"]
T_FITAPP = ["tests/app/test_fit_dispatch.py", "tests/app/test_fit_option_edges.py"]
T_CLI = ["tests/cli/test_cli.py", "tests/test_tables.py"]
T_CLISTATIC = ["tests/cli/test_cli.py", "tests/cli/test_bad_values.py"]
T_SWEEP = ["tests/sweeps/test_sweep_spec.py", "tests/sweeps/test_axis_units.py"]
T_PROGRAM = ["tests/test_program.py", "tests/io/test_protocol.py"]

# ----------------------------------------------------------------------------- the mutants
# (name, file under src/dryfriction, original, mutated, why plausible, test files)
MUTANTS: list[tuple[str, str, str, str, str, list[str]]] = [
    # ---- theory/ (4)
    ("direct_ratio_no_2", "theory/direct.py",
     "lx = math.log(abs(v) / (2.0 * v_ref)) + 1.0 / direct",
     "lx = math.log(abs(v) / v_ref) + 1.0 / direct",
     "strength_ratio's fast scalar copy drops the 2 of V_c = 2 V_ref e^{-1/A}: g(V) off by "
     "A ln 2 for V >> V_c (ensemble runs with direct > 0, e.g. A = 0.02: force 1.4 % high), "
     "junction_strength (the array form) stays right", T_DIRECT),
    ("units_mu_el_wrong_side", "theory/units.py",
     "if model.mu_el == scales.mu_el or scales.mu_el == default:",
     "if model.mu_el == scales.mu_el or model.mu_el == default:",
     "friction_level tests the wrong object's default: TrapModel() with PhysicalScales("
     "mu_el=0.6) returns mu_el = 1 (static/steady_friction_si 1/0.6 too high)", T_UNITS),
    ("creep_tv_log_eps_sign", "theory/creep.py",
     "log_t = 1.0 / eps - math.log(eps) + math.log(gap)",
     "log_t = 1.0 / eps + math.log(eps) + math.log(gap)",
     "T_v = (e^{1/eps}/eps)[E1(1) - E1(1/eps)] with eps multiplied instead of divided: "
     "max_age of the Eyring-Nabarro law off by eps^2 (eps = 0.05: T_v 400x too small)", T_CREEP),
    ("hopf_amplitude_no_2", "theory/hopf.py",
     "amp = 2 * np.abs(point.q) * math.sqrt(ratio) if ratio > 0",
     "amp = np.abs(point.q) * math.sqrt(ratio) if ratio > 0",
     "the normal form's x ~ x0 + 2 Re(z q) read as x0 + Re(z q): the limit-cycle amplitude "
     "near a supercritical Hopf point half of the true one", T_HOPF),
    # ---- ensemble/ (3)
    ("interface_coupling_energy_no_half", "ensemble/interface.py",
     "+ 0.5 * kc * float(np.sum(np.diff(x) ** 2)))",
     "+ kc * float(np.sum(np.diff(x) ** 2)))",
     "the coupling springs' elastic energy without its 1/2: load.csv's elastic_energy and "
     "energy_residual wrong for N > 1 with coupling once the blocks' slips differ", T_IFACE),
    ("thermal_inverse_big_z_factor_2", "ensemble/thermal.py",
     "return v_ref * math.exp(z - 1.0 / direct)",
     "return 2.0 * v_ref * math.exp(z - 1.0 / direct)",
     "V(g) for y/A > 20 copies the 2 of V_c into 2 sinh z = e^z (the 2s then do not cancel): "
     "the inertial slider with direct > 0 (g ~ 1, A = 0.02: z = 50) slides twice too fast at "
     "a given force", T_INERTIA),
    ("snapshot_force_one_radius", "ensemble/population.py",
     '"force": r * r * f}', '"force": r * f}',
     "a snapshot's per-pair force loses one a_r factor (eq. 23 scales as a_r^2): wrong for "
     "aged pairs with eps > 0 (snapshots' force column, its sum no longer the run's force)",
     T_SNAP),
    # ---- rsf/ (2)
    ("law_prz_hold_heal_1", "rsf/law.py",
     '{"ageing": 1.0, "prz": 0.5, "slip": 0.0}',
     '{"ageing": 1.0, "prz": 1.0, "slip": 0.0}',
     "PRZ at rest heals at dtheta/dt = 1 (ageing's rate) instead of 1/2 (theta = theta'/2 "
     "convention): hold_peak_friction of state_law='prz' b ln 2 too high at long holds", T_LAW),
    ("spring_theta2_uses_dc", "rsf/spring.py",
     "theta2 = model.dc2 / v if self.theta2 is None else self.theta2",
     "theta2 = model.dc / v if self.theta2 is None else self.theta2",
     "the second state variable's steady default uses Dc instead of Dc2: a two-state run "
     "(dc2 != dc) starts out of steady state (friction jumps at t = 0 by b2 ln(dc/dc2))",
     T_SPRING),
    # ---- io/ (2)
    ("protocol_pull_first_segment", "io/protocol.py",
     "return float(drive.program.segments[-1].velocity)",
     "return float(drive.program.segments[0].velocity)",
     "pulling_velocity reads the first segment: a sweep point whose drive starts with a slow "
     "(or hold) segment pulls at the wrong velocity (K_c, steady initial state, stick-slip "
     "normalisation)", T_SPRINGPT),
    ("json_inf_not_null", "io/files.py",
     "return x if math.isfinite(x) else None",
     "return x if not math.isnan(x) else None",
     "to_jsonable only maps NaN to null: an infinite value (stiffness = inf, a speed_high "
     "= inf) is written as the non-JSON token Infinity in summary.json/fit.json", T_JSON),
    # ---- records/ (3)
    ("lab_hr_as_minutes", "records/lab.py",
     '"hr": 3600.0}', '"hr": 60.0}',
     "the record reader's 'hr' alias given a minute's value: a record with time[hr] (or a "
     "velocity in um/hr) is read 60x off", T_LAB),
    ("labsteps_kN_factor_inverted", "records/labsteps.py",
     'return "normal force", "kN", 1e-3', 'return "normal force", "kN", 1e3',
     "N -> kN multiplied instead of divided: segments.csv's normal force column of a record "
     "in N (force, not stress) 1e6x too large; the stress branch (Pa -> MPa) is right",
     T_SEGCSV),
    ("detection_extrapolation_exponent", "records/detection.py",
     "q[-1] * np.sqrt(T[-1] / d)", "q[-1] * (T[-1] / d)",
     "the fluctuation level beyond the longest measured scale falls as T^-1 instead of the "
     "random walk's T^-1/2: a stretch longer than the longest scale gets a too small scatter "
     "(relative_at/absolute_at/scatter for durations > scales[-1])", T_DETECT),
    # ---- fit/ (5)
    ("runs_test_mean_no_plus_1", "fit/statistics.py",
     "mean = 2.0 * n1 * n2 / n + 1.0", "mean = 2.0 * n1 * n2 / n",
     "Wald-Wolfowitz expected runs without its + 1: the runs-test p-value biased (white "
     "residuals of n = 50 give p well below the uniform's median; runs_test_p in fit.json)",
     T_STAT),
    ("ftest_rss_factor_2", "fit/statistics.py",
     "F = (max(delta, 0.0) / df1) / (2.0 * sep_cost / df2)",
     "F = (max(delta, 0.0) / df1) / (sep_cost / df2)",
     "the separate fits' cost (RSS/2) taken as RSS in the F test's denominator: F halved, "
     "the joint-vs-separate p-value too large (joint fits accepted too often)", T_STAT),
    ("steady_noise_dof_1", "fit/steps.py",
     "return float(math.sqrt(r @ r / (mu.size - 2)))",
     "return float(math.sqrt(r @ r / (mu.size - 1)))",
     "steady_noise about a fitted line divided by n - 1 (one dof) instead of n - 2: sigma low "
     "by sqrt((n-2)/(n-1)) (n = 10: 5.7 %)", T_STEPS),
    ("loadpoint_hinge_jacobian_swapped", "fit/loadpoint.py",
     "np.where(tt < tau, -v1, -v2)", "np.where(tt < tau, -v2, -v1)",
     "the corner's Jacobian column takes the slopes of the wrong sides: sigma_t_change of a "
     "placed change wrong whenever v1 != v2 (a step from 1 to 10 um/s: off by ~10x)",
     T_LOADPT),
    ("engine_log_slope_log10", "fit/engine.py",
     "(2 * math.log(1.01))", "(2 * math.log10(1.01))",
     "the derived d y/d ln x uses log10 in the denominator: reported slope 1/ln 10 = 0.434x "
     "the true one (fit.json's derived 'd mu_s/d ln t_w there')", T_ENGINE),
    # ---- analysis/ (5)
    ("stickslip_stick_fraction_shift", "analysis/stickslip.py",
     "stick_frac = float(np.sum(dt[slow[1:]]) / span)",
     "stick_frac = float(np.sum(dt[slow[:-1]]) / span)",
     "each step's duration credited to the sample that starts it, not the one that ends it "
     "(the docstring's convention): stick fraction wrong on a non-uniform time grid or where "
     "the first/last sample sticks", T_SS),
    ("rsf_hopf_dc_ratio_inverted", "analysis/rsf_hopf.py",
     "delta = 1.0 if i == 0 else m.dc / float(m.dc2)",
     "delta = 1.0 if i == 0 else m.dc2 / float(m.dc)",
     "the second state variable's rate in the reduced system uses Dc2/Dc instead of Dc/Dc2: "
     "the Hopf point (K_c, omega) of a two-state model with dc2 != dc is wrong", T_RSFHOPF),
    ("bifurcation_hysteresis_d0_excluded", "analysis/bifurcation.py",
     'if r["d"] <= 0.0 and r["amplitude"] > thr',
     'if r["d"] < 0.0 and r["amplitude"] > thr',
     "the hysteresis distances exclude d = 0 (K = K_c exactly): a scan whose way up still "
     "oscillates at d = 0 and nowhere below is called supercritical instead of subcritical",
     T_BIF),
    ("rsf_view_healing_short_holds", "analysis/rsf_view.py",
     "np.polyfit(lt[-3:], peaks[-3:], 1)", "np.polyfit(lt[:3], peaks[:3], 1)",
     "the healing rate d mu/d ln t fitted over the three shortest holds instead of the three "
     "longest (default five holds 1..1e4 t0): a different, non-asymptotic slope", T_VIEW),
    ("fronts_normal_load_times_mu_el", "analysis/fronts.py",
     "return float(np.asarray(result.x).size) / mu_el",
     "return float(np.asarray(result.x).size) * mu_el",
     "the interface's total normal load N F_el/mu_el computed as N F_el mu_el: the applied "
     "shear as a friction coefficient (load/normal) off by mu_el^2 when mu_el != 1", T_FRONTS),
    # ---- plots/ (2)
    ("plot_record_program_no_t0", "plots/record.py",
     "ax.plot([s.t_start - t0, s.t_end - t0], [s.velocity * 1e6] * 2",
     "ax.plot([s.t_start, s.t_end], [s.velocity * 1e6] * 2",
     "the record figure's load-program segments drawn at record time while the measured "
     "velocity is drawn from t0: shifted by t0 for a record not starting at t = 0", T_PLOTREC),
    ("plot_fronts_floor_10", "plots/fronts.py",
     "floor = threshold / 100.0", "floor = threshold / 10.0",
     "the space-time map's colour floor at threshold/10 instead of /100 (the docstring's): "
     "slip rates between threshold/100 and threshold/10 drawn at the floor", T_PLOTFRONTS),
    # ---- app/ (2)
    ("app_shs_reload_at_v2", "app/ratestate.py",
     "segs = [Segment(v1, t1), Segment(0.0, hold), Segment(v1, t2)]",
     "segs = [Segment(v1, t1), Segment(0.0, hold), Segment(v2, t2)]",
     "slide-hold-slide reloads at --v2 instead of --v1: with --v2 != --v1 the peak and the "
     "series differ (the protocol the docstring describes: v1, hold, v1 again)", T_RSFAPP),
    ("app_record_fit_trend_default_off", "app/fitting.py",
     'trend=True if o["trend"] is None else o["trend"]',
     'trend=False if o["trend"] is None else o["trend"]',
     "a record fit's default trend term switched off: fits of a drifting record biased, "
     "fit.json without the trend parameter unless --trend is given", T_FITAPP),
    # ---- cli/ (2)
    ("cli_table_6_digits", "cli/common.py",
     'table.add_row(*(f"{float(v):.10g}" for v in row))',
     'table.add_row(*(f"{float(v):.6g}" for v in row))',
     "the terminal table of static/steady/stability printed with 6 significant digits "
     "instead of 10: mu values differing in the 7th digit print the same", T_CLI),
    ("cli_static_pull_velocity_dropped", "cli/model.py",
     "mu_el=mu_el, direct=direct, v_ref=v_ref, pull_velocity=pull_velocity),",
     "mu_el=mu_el, direct=direct, v_ref=v_ref),",
     "dryfriction static forgets to pass --pull-velocity on: with --direct > 0 the command "
     "refuses (pull_velocity required) although the user gave it", T_CLISTATIC),
    # ---- sweeps/ (1)
    ("sweep_log_axis_logspace", "sweeps/sweep.py",
     "np.geomspace(start, stop, n)", "np.logspace(start, stop, n)",
     "a {log = [start, stop, n]} axis built with logspace (start/stop read as exponents): "
     "{log = [0.1, 10, 3]} gives 1.26, 1e5.5, 1e10 instead of 0.1, 1, 10", T_SWEEP),
    # ---- program.py (1)
    ("program_slip_time_signed", "program.py",
     "return self.slip / abs(self.velocity)", "return self.slip / self.velocity",
     "a slip-given segment's duration from the signed velocity: a backward segment "
     "(velocity < 0, slip > 0) gets a negative duration and the program is refused", T_PROGRAM),
]


# ----------------------------------------------------------------------------- the runner
def main(argv: list[str]) -> int:
    from benchmarks.blind_mutants import run_set  # the runner all sets share

    return run_set(argv, MUTANTS, "blind_mutants6_results.jsonl")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
