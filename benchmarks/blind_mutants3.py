"""A third blind mutant set for issue 25's "Done when" (fresh: >= 30, killed >= 90 %).

Written against main at commit db1575fc430247b616eefe14f5dcf7f7a4208435 (2026-11-26) by a
reviewer (branch ``blind3``) who read ``src/dryfriction`` (today's app/, records/, sweeps/,
simulation.py, theory/model.py, theory/linear_stability.py, theory/hopf.py,
analysis/rsf_hopf.py and the older layers) but neither ``tests/mutants.py``, nor any file
under ``tests/``, nor the lists of ``benchmarks/blind_mutants.py`` and
``benchmarks/blind_mutants2.py`` (only their runners, reused here). The test files of each
mutant were chosen by their names (``ls -R tests/``). This list was committed before any
mutant was run. Each mutant is an exact text replacement whose original occurs exactly once
in its file.

Run (from the repository root, one mutant at a time)::

    .venv/bin/python benchmarks/blind_mutants3.py --no-whole          # chosen files only
    .venv/bin/python benchmarks/blind_mutants3.py --no-whole NAME ... # some
    .venv/bin/python benchmarks/blind_mutants3.py --check             # originals unique
    .venv/bin/python benchmarks/blind_mutants3.py --no-whole --wider  # second pass (WIDER)
    .venv/bin/python benchmarks/blind_mutants3.py                     # survivors: whole suite too

For each mutant: apply, ``pytest -x -q -p no:cacheprovider --timeout 300`` on its chosen
files, killed/survived, restore (always: :func:`benchmarks.blind_mutants.run_one`). The first
failing test of each kill is rerun on the unmutated tree. Results are appended to
``$TMPDIR/blind_mutants3_results.jsonl``.

Measured on db1575f (2026-11-26): 25 of 36 killed by their chosen files (69.4 %, Clopper-Pearson
95 % 51.9-83.7 %); the second pass (:data:`WIDER`, chosen after the first) kills 2 more
(``labsteps_spec_no_t0``, ``law_prz_heal_1``): 27 of 36 (75.0 %, 57.8-87.9 %). Every kill's first
failing test passes unmutated. No survivor is equivalent; none was run against the whole suite.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

# ----------------------------------------------------------------------------- test choice
# by file name only (ls -R tests/), never by their content
T_LINSTAB = ["tests/theory/test_stability.py", "tests/theory/test_direct.py",
             "tests/theory/test_model_objects.py"]
T_HOPF = ["tests/theory/test_hopf.py"]
T_RSFHOPF = ["tests/analysis/test_rsf_hopf.py"]
T_HOPFTAB = ["tests/analysis/test_rsf_hopf.py", "tests/cli/test_bifurcation.py"]
T_APPHOPF = ["tests/cli/test_bifurcation.py", "tests/app/test_workflows.py"]
T_SIM = ["tests/test_simulator_shape.py"]
T_MODEL = ["tests/theory/test_model_objects.py", "tests/cli/test_bad_values.py"]
T_LABSTEPS = ["tests/records/test_lab.py", "tests/records/test_segmentation_long.py"]
T_DATA = ["tests/io/test_data.py", "tests/io/test_invariants_units.py"]
T_LAB = ["tests/records/test_lab.py", "tests/io/test_invariants_units.py"]
T_ARTIF = ["tests/records/test_detect.py", "tests/records/test_lab.py"]
T_SWEEP = ["tests/sweeps/test_sweep.py"]
T_CF = ["tests/sweeps/test_cf.py", "tests/sweeps/test_sweep.py"]
T_APPTHEORY = ["tests/cli/test_bad_values.py", "tests/theory/test_units.py",
               "tests/cli/test_cli.py"]
T_RATESTATE = ["tests/cli/test_rsf_protocol.py", "tests/cli/test_bad_values.py",
               "tests/cli/test_rsf_peer_case.py"]
T_LAW = ["tests/rsf/test_rsf.py", "tests/rsf/test_invariants.py",
         "tests/fit/test_state_laws.py"]
T_STAT = ["tests/fit/test_fit.py", "tests/fit/test_invariants_estimators.py",
          "tests/fit/test_reported_definitions.py", "tests/fit/test_hac.py"]
T_ENGINE = ["tests/fit/test_fit.py", "tests/fit/test_reported.py",
            "tests/fit/test_reported_definitions.py"]
T_PLOTHOPF = ["tests/plots/test_plots.py", "tests/plots/test_reported_artists.py",
              "tests/cli/test_bifurcation.py"]
T_PLOTREC = ["tests/plots/test_reported_artists.py", "tests/plots/test_plots.py",
             "tests/records/test_lab.py"]
T_DIRECT = ["tests/theory/test_direct.py", "tests/theory/test_stability.py",
            "tests/theory/test_static.py"]

# ----------------------------------------------------------------------------- the mutants
# (name, file under src/dryfriction, original, mutated, why plausible, test files)
MUTANTS: list[tuple[str, str, str, str, str, list[str]]] = [
    # --- theory/linear_stability.py, theory/direct.py
    ("ls_forward_no_g", "theory/linear_stability.py",
     "forward_stiffness=resp.g * (b.A + b.edge) / b.H0",
     "forward_stiffness=(b.A + b.edge) / b.H0",
     "the shift stiffness of the direct-effect model forgets the junction strength g(u) "
     "(the backward one keeps it)", T_LINSTAB),
    ("ls_Z_direct_no_u", "theory/linear_stability.py",
     "return self.g * self.base.Z(lam) + (self.a_direct / self.base.u) * lam",
     "return self.g * self.base.Z(lam) + self.a_direct * lam",
     "Z_A's viscous term a_d/u written a_d lambda (its Taylor derivative keeps /u): K_c of "
     "the direct-effect model wrong at every u != 1", T_LINSTAB),
    ("direct_log_slope_no_sqrt", "theory/direct.py",
     "return direct / np.sqrt(1.0 + np.exp(-2.0 * lx))",
     "return direct / (1.0 + np.exp(-2.0 * lx))",
     "d asinh(e^x)/dx is e^x/sqrt(1+e^2x): the square root dropped; a_direct = A mu_d at "
     "large u still, wrong near the crossover", T_DIRECT),
    # --- theory/hopf.py
    ("hopf_p_no_conj", "theory/hopf.py",
     "p = p / np.conj(np.vdot(p, q))",
     "p = p / np.vdot(p, q)",
     "the left eigenvector normalised with <p,q> instead of its conjugate: <p,q> = "
     "conj(...) != 1, c1 rotated", T_HOPF),
    ("hopf_amp_no_2", "theory/hopf.py",
     "amp = 2 * np.abs(point.q) * math.sqrt(ratio)",
     "amp = np.abs(point.q) * math.sqrt(ratio)",
     "the cycle's half peak-to-peak amplitude from x ~ x0 + Re(z q) (the factor 2 of "
     "2 Re(z q) lost): amplitudes half", T_HOPF),
    ("hopf_h20_omega", "theory/hopf.py",
     "h20 = np.linalg.solve(2j * omega * np.eye(n) - A, b_form(q, q))",
     "h20 = np.linalg.solve(1j * omega * np.eye(n) - A, b_form(q, q))",
     "the second-harmonic resolvent at i omega instead of 2 i omega (singular-ish): l1 wrong",
     T_HOPF),
    ("hopf_fd_cross_sign", "theory/hopf.py",
     "re = c_real(a, c) - c_real(b, c) - 2 * cab(d)",
     "re = c_real(a, c) - c_real(b, c) + 2 * cab(d)",
     "the fd route's complex polarisation with a sign slip in the cross term: method='fd' "
     "gives another l1 than 'complex'", T_HOPF),
    # --- analysis/rsf_hopf.py
    ("rsfhopf_frequency_hz", "analysis/rsf_hopf.py",
     "frequency=point.omega * v / model.dc,",
     "frequency=point.omega * v / model.dc / (2 * math.pi),",
     "the frequency column in Hz while its unit says rad/s", T_RSFHOPF),
    ("rsfhopf_prz_half", "analysis/rsf_hopf.py",
     "r = 0.5 * delta * (np.exp(-y) - np.exp(2 * x + y))",
     "r = delta * (np.exp(-y) - np.exp(2 * x + y))",
     "the PRZ law's factor 1/2 dropped in the reduced field (same steady state, K_c and "
     "omega of PRZ wrong)", T_RSFHOPF),
    ("rsfhopf_delta_inverted", "analysis/rsf_hopf.py",
     "delta = 1.0 if i == 0 else m.dc / float(m.dc2)",
     "delta = 1.0 if i == 0 else float(m.dc2) / m.dc",
     "delta_2 = Dc/Dc2 inverted: two-state-variable K_c and l1 wrong", T_RSFHOPF),
    ("rsfhopf_mass_v1", "analysis/rsf_hopf.py",
     "M = self.mass * self.v**2 / m.dc",
     "M = self.mass * self.v / m.dc",
     "the reduced mass m V*^2/Dc written m V*/Dc: inertial K_c wrong", T_RSFHOPF),
    ("rsfhopf_amp_no_kc", "analysis/rsf_hopf.py",
     "amp = 2 * abs(point.q[0]) * math.sqrt(abs(sigma_k * kc / point.c1.real))",
     "amp = 2 * abs(point.q[0]) * math.sqrt(abs(sigma_k / point.c1.real))",
     "amp_coef per sqrt(|kappa - kappa_c|) instead of per sqrt(relative distance)", T_RSFHOPF),
    # --- analysis/hopf_table.py, app/hopf.py
    ("hopftable_swap_damping_mass", "analysis/hopf_table.py",
     "h = rsf_hopf(model, v, drive.damping, drive.mass)",
     "h = rsf_hopf(model, v, drive.mass, drive.damping)",
     "damping and mass passed in the wrong order", T_HOPFTAB),
    ("hopftable_freq_unit_hz", "analysis/hopf_table.py",
     '"frequency": "rad/s",',
     '"frequency": "Hz",',
     "the CSV/JSON unit of the frequency column says Hz for rad/s", T_HOPFTAB),
    ("apphopf_maxchecked_ge", "app/hopf.py",
     "if check and len(vs) > MAX_CHECKED:",
     "if check and len(vs) >= MAX_CHECKED:",
     "--check refuses exactly MAX_CHECKED velocities (off by one)", T_APPHOPF),
    # --- simulation.py, theory/model.py
    ("sim_refusal_owner", "simulation.py",
     'f"{name} = {type(part).__name__}(...) is {_OWNERS.get(other, other)}, in "',
     'f"{name} = {type(part).__name__}(...) is {_OWNERS.get(law, law)}, in "',
     "the refusal of a part of the other law names the wrong owner", T_SIM),
    ("model_alpha_closed", "theory/model.py",
     'Parameter("alpha", 0.13, ALPHA_MIN, 1.0, hi_open=True,',
     'Parameter("alpha", 0.13, ALPHA_MIN, 1.0,',
     "alpha = 1 (no pinning, no friction) accepted", T_MODEL),
    # --- records/
    ("labsteps_spec_no_t0", "records/labsteps.py",
     'return ",".join(f"{s.t_start - t0:.10g}:{s.velocity:.6g}" for s in segments)',
     'return ",".join(f"{s.t_start:.10g}:{s.velocity:.6g}" for s in segments)',
     "the --segments form written in absolute times, not from the first sample", T_LABSTEPS),
    ("data_day_typo", "records/data.py",
     '"d": 86400.0,',
     '"d": 8640.0,',
     "a day of 8640 s (a typo in the unit table)", T_DATA),
    ("lab_time_line_off", "records/lab.py",
     'i, j, k = int(dec[0]) + 1, idx["time"], roles.index("time")',
     'i, j, k = int(dec[0]), idx["time"], roles.index("time")',
     "the refusal of a non-increasing time names the line before the bad one", T_LAB),
    ("artifacts_reset_off_by_one", "records/artifacts.py",
     "fix[i + 1:] -= np.linalg.lstsq(A, x[a:b], rcond=None)[0][2]",
     "fix[i:] -= np.linalg.lstsq(A, x[a:b], rcond=None)[0][2]",
     "a reset's offset removed from the sample before the jump too", T_ARTIF),
    # --- sweeps/, app/sweeps.py
    ("sweep_logspace", "sweeps/sweep.py",
     "return tuple(float(v) for v in np.geomspace(start, stop, n))",
     "return tuple(float(v) for v in np.logspace(start, stop, n))",
     "{log = [1e-3, 1, 4]} read as exponents (np.logspace)", T_SWEEP),
    ("sweep_key_no_analysis", "sweeps/sweep.py",
     '''return _digest({"format": SWEEP_FORMAT, "version": RESULT_VERSION, "analysis": analysis,
                    "protocol": protocol})[:32]''',
     '''return _digest({"format": SWEEP_FORMAT, "version": RESULT_VERSION,
                    "protocol": protocol})[:32]''',
     "a stored point keyed without its analysis: another analysis' numbers reused", T_SWEEP),
    ("cf_mass_unit", "sweeps/cf.py",
     '"mass": "F_el t0^2/a0"',
     '"mass": "F_el t0/a0"',
     "the NetCDF unit of a swept mass written like the damping's", T_CF),
    # --- app/theory.py, app/ratestate.py
    ("apptheory_range_units", "app/theory.py",
     'f"allowed {U_MIN * vstar:g} to {U_MAX * vstar:g} m/s "',
     'f"allowed {U_MIN / vstar:g} to {U_MAX / vstar:g} m/s "',
     "the refusal of --V states the range in the wrong units", T_APPTHEORY),
    ("apptheory_vstar_inverted", "app/theory.py",
     "vstar = a0 / t0",
     "vstar = t0 / a0",
     "V* = t0/a0: the --V range check at the wrong place", T_APPTHEORY),
    ("ratestate_negative_vmin", "app/ratestate.py",
     "if value != 0.0 and abs(value) < V_MIN:",
     "if value != 0.0 and value < V_MIN:",
     "a negative --v1/--v2 (sliding back) refused as below V_MIN", T_RATESTATE),
    # --- rsf/law.py
    ("law_prz_heal_1", "rsf/law.py",
     'heal = {"ageing": 1.0, "prz": 0.5, "slip": 0.0}[self.state_law] * t_hold',
     'heal = {"ageing": 1.0, "prz": 1.0, "slip": 0.0}[self.state_law] * t_hold',
     "PRZ heals at rest like the ageing law (its rate at rest is 1/2)", T_LAW),
    ("law_kc_mass_a", "rsf/law.py",
     "return (self.b - ap) / self.dc * (1.0 + mass * v * v / (ap * self.dc))",
     "return (self.b - ap) / self.dc * (1.0 + mass * v * v / (self.a * self.dc))",
     "the inertial factor of K_c with a instead of a' = a + eta V", T_LAW),
    # --- fit/
    ("stats_aicc_n_k", "fit/statistics.py",
     "2 * k * (k + 1) / (n - k - 1) if",
     "2 * k * (k + 1) / (n - k) if",
     "AICc's correction with n - k instead of n - k - 1", T_STAT),
    ("stats_t_095", "fit/statistics.py",
     "float(stats.t.ppf(0.975, dof))",
     "float(stats.t.ppf(0.95, dof))",
     "a 90 % interval reported as 95 % (one-sided quantile)", T_STAT),
    ("stats_hac_no_dof", "fit/statistics.py",
     "cov = bread @ omega @ bread * (n / (n - p))",
     "cov = bread @ omega @ bread",
     "the HAC sandwich without its n/(n - p) small-sample factor", T_STAT),
    ("engine_akaike_no_half", "fit/engine.py",
     "w = np.exp(-(aic - aic.min()) / 2.0)",
     "w = np.exp(-(aic - aic.min()))",
     "Akaike weights exp(-delta) instead of exp(-delta/2)", T_ENGINE),
    ("engine_rms_cost", "fit/engine.py",
     "goodness.update(rms_residual=math.sqrt(2.0 * cost / n),",
     "goodness.update(rms_residual=math.sqrt(cost / n),",
     "rms from the cost 0.5 RSS without its factor 2", T_ENGINE),
    # --- plots/
    ("plothopf_l1_absolute", "plots/hopf.py",
     'axes[1].plot(v, [r["relative_l1"] for r in pts], marker, color=colour, ms=5)',
     'axes[1].plot(v, [r["l1"] for r in pts], marker, color=colour, ms=5)',
     "the panel labelled l1/largest term plots l1", T_PLOTHOPF),
    ("plotrecord_velocity_mm", "plots/record.py",
     'ax.plot(tv - t0, v * 1e6, color="0.6"',
     'ax.plot(tv - t0, v * 1e3, color="0.6"',
     "the smoothed velocity in mm/s on an axis labelled um/s", T_PLOTREC),
]


# ----------------------------------------------------------------------------- second pass
# Chosen AFTER the first pass (the list above unchanged): the survivors of their chosen files,
# each against its package's whole test folder(s) by name (``--wider``), still not the whole
# suite. Kept apart so that the first pass's number stays the blind one.
WIDER: dict[str, list[str]] = {
    "hopftable_freq_unit_hz": ["tests/analysis", "tests/cli/test_bifurcation.py",
                               "tests/test_tables.py", "tests/test_docs.py"],
    "apphopf_maxchecked_ge": ["tests/app", "tests/cli/test_bifurcation.py",
                              "tests/cli/test_bad_values.py"],
    "sim_refusal_owner": ["tests/test_simulator_shape.py", "tests/rsf", "tests/cli/test_words.py"],
    "model_alpha_closed": ["tests/theory"],
    "labsteps_spec_no_t0": ["tests/records", "tests/fit/test_steps.py",
                            "tests/plots/test_reported_artists.py"],
    "sweep_logspace": ["tests/sweeps"],
    "cf_mass_unit": ["tests/sweeps"],
    "apptheory_range_units": ["tests/cli/test_bad_values.py", "tests/cli/test_words.py",
                              "tests/cli/test_fuzz.py", "tests/app"],
    "law_prz_heal_1": ["tests/rsf", "tests/fit/test_shs.py", "tests/theory/test_dieterich.py"],
    "plothopf_l1_absolute": ["tests/plots", "tests/cli/test_bifurcation.py"],
    "plotrecord_velocity_mm": ["tests/plots", "tests/records"],
}


# ----------------------------------------------------------------------------- the runner
def main(argv: list[str]) -> int:
    from benchmarks.blind_mutants import run_set  # the runner all sets share

    return run_set(argv, MUTANTS, "blind_mutants3_results.jsonl", wider=WIDER)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
