"""Blind mutants for issue 25's "Done when" (a fresh set written from the source only).

Written by a reviewer who read ``src/dryfriction`` (and docs/model.md) but neither
``tests/mutants.py`` nor any test file; the list below was committed before any of it was run.
Each mutant is an exact text replacement (the original occurs exactly once in its file).

Run (from the repository root, one mutant at a time)::

    .venv/bin/python benchmarks/blind_mutants.py            # all
    .venv/bin/python benchmarks/blind_mutants.py NAME ...   # some
    .venv/bin/python benchmarks/blind_mutants.py --check    # originals unique, nothing run
    .venv/bin/python benchmarks/blind_mutants.py --no-whole          # chosen files only
    .venv/bin/python benchmarks/blind_mutants.py --whole-only NAME   # whole suite only

For each mutant: apply, run pytest on the test files chosen (by their names) for its module
(``-x -q -p no:cacheprovider --timeout 300``), record killed/survived and the time, restore the
file (always, ``try/finally``; the module's ``__pycache__`` entries, Numba's cache included,
and the file's mtime are restored too, so that no recompilation leaks into the next mutant).
A survivor is then run once against the whole default suite (``pytest -x -q tests/``).
Finally the first failing test of every killed mutant is rerun on the unmutated tree, to check
that the kill is the mutant's and not a test failing anyway.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "dryfriction"
PY = str(ROOT / ".venv" / "bin" / "python")

# ----------------------------------------------------------------------------- test choice
T_RSF = ["tests/rsf/test_rsf.py", "tests/rsf/test_invariants.py",
         "tests/theory/test_independent_reference.py"]
T_STEP = ["tests/rsf/test_rsf.py", "tests/rsf/test_routes.py",
          "tests/ensemble/test_invariants_steppers.py",
          "tests/rsf/test_invariants.py", "tests/theory/test_independent_reference.py"]
T_PROG = ["tests/cli/test_rsf_protocol.py", "tests/io/test_protocol.py", "tests/rsf/test_rsf.py"]
T_THEORY = ["tests/theory/test_direct.py", "tests/theory/test_steady.py",
            "tests/theory/test_static.py",
            "tests/theory/test_invariants.py", "tests/theory/test_independent_reference.py"]
T_STAB = ["tests/theory/test_stability.py", "tests/theory/test_direct.py",
          "tests/theory/test_invariants.py",
          "tests/theory/test_independent_reference.py"]
T_DIET = ["tests/theory/test_dieterich.py", "tests/theory/test_invariants.py",
          "tests/theory/test_trap.py"]
T_CREEP = ["tests/theory/test_creep.py", "tests/theory/test_units.py",
           "tests/theory/test_invariants.py"]
T_STAT = ["tests/fit/test_fit.py", "tests/fit/test_hac.py",
          "tests/fit/test_invariants_estimators.py"]
T_STEPS = ["tests/fit/test_steps.py", "tests/fit/test_invariants_estimators.py",
           "tests/fit/test_shs.py"]
T_LAB = ["tests/records/test_lab.py", "tests/io/test_invariants_units.py", "tests/test_tables.py"]
T_DATA = ["tests/io/test_data.py", "tests/io/test_invariants_units.py", "tests/io/test_io.py"]
T_SEG = ["tests/records/test_detect.py", "tests/fit/test_invariants_estimators.py",
         "tests/cli/test_signals.py"]
T_FILES = ["tests/io/test_file_safety.py", "tests/io/test_io.py"]
T_BIF = ["tests/analysis/test_bifurcation.py"]
T_SS = ["tests/analysis/test_stickslip.py"]
T_ENS = ["tests/ensemble/test_direct_inertia.py", "tests/ensemble/test_invariants.py",
         "tests/ensemble/test_population.py"]
T_PLOT = ["tests/plots/test_plots.py", "tests/plots/test_figure_formats.py"]
T_CLI = ["tests/cli/test_cli.py", "tests/test_tables.py", "tests/cli/test_simulate.py"]

# ----------------------------------------------------------------------------- the mutants
# (name, file under src/dryfriction, original, mutated, why plausible, test files)
MUTANTS: list[tuple[str, str, str, str, str, list[str]]] = [
    # --- rsf/law.py
    ("law_ss_forgets_b2", "rsf/law.py",
     "return self.mu0 + (self.a - self.b_total) * np.log(v / self.v0)",
     "return self.mu0 + (self.a - self.b) * np.log(v / self.v0)",
     "steady state written for one state variable; b2 forgotten (two-state laws only)", T_RSF),
    ("law_hold_theta2_not_healed", "rsf/law.py",
     "th2 = None if self.dc2 is None else self.dc2 / v + heal",
     "th2 = None if self.dc2 is None else self.dc2 / v",
     "second state variable left at steady state during the hold", T_RSF),
    ("law_slip_law_sign", "rsf/law.py",
     "return np.where(omega > 0, -omega * np.log(omega), 0.0)",
     "return np.where(omega > 0, omega * np.log(omega), 0.0)",
     "sign of the Ruina slip law", T_RSF),
    ("law_kc_mass_missing_v", "rsf/law.py",
     "(1.0 + mass * v * v / (ap * self.dc))",
     "(1.0 + mass * v / (ap * self.dc))",
     "inertial correction with V instead of V^2 (unit error, invisible at V = 1)", T_RSF),
    ("law_hopf_damping_denominator", "rsf/law.py",
     "return v / self.dc * math.sqrt((self.b - ap) / ap)",
     "return v / self.dc * math.sqrt((self.b - ap) / self.a)",
     "a' = a + eta V substituted in the numerator only (damping regime)", T_RSF),
    # --- rsf/stepper.py
    ("stepper_reg_inertial_ln2", "rsf/stepper.py",
     "mu = a * (lnz + math.log(2.0) + 0.25 * math.exp(-2.0 * lnz))",
     "mu = a * (lnz + 0.25 * math.exp(-2.0 * lnz))",
     "asinh large-argument expansion without ln 2; the kernel's mu enters only inertial runs",
     T_STEP),
    ("stepper_ageing_jac_sign", "rsf/stepper.py",
     "return e - v * invdc, -v * invdc, -e",
     "return e - v * invdc, -v * invdc, e",
     "d(1/theta)/d ln theta sign (Jacobian only: step control and linear_stability)", T_STEP),
    ("stepper_qs_jac_damping", "rsf/stepper.py",
     "dd = a * cp + eta * v",
     "dd = a * cp",
     "derivative of the denominator a c + eta V forgets eta V (Jacobian, damping)", T_STEP),
    ("stepper_inertial_jac_damping", "rsf/stepper.py",
     "jac[0] = (-a * c - eta * v) / mv - f0",
     "jac[0] = (-a * c) / mv - f0",
     "inertial Jacobian forgets the damping term (linear stability with mass and eta)", T_STEP),
    ("stepper_slip_dlnv", "rsf/stepper.py",
     "return -w * lnom, -w * (lnom + 1.0), -w",
     "return -w * lnom, -w * lnom, -w",
     "product rule half done in the slip law's d/d ln V (zero at steady state)", T_STEP),
    # --- rsf/result.py
    ("result_hermite_h11", "rsf/result.py",
     "h11 = s * s * (s - 1)",
     "h11 = s * (s - 1)",
     "Hermite basis typo (only output at t_eval between steps)", T_RSF),
    ("result_quadrature_slopes_unscaled", "rsf/result.py",
     "f0, f1 = F[:-1, 0] * h, F[1:, 0] * h",
     "f0, f1 = F[:-1, 0], F[1:, 0]",
     "Hermite slopes not scaled by the step (soft-spring slip by quadrature)", T_RSF),
    # --- rsf/growth.py
    ("growth_near_steady_min", "rsf/growth.py",
     "if max(off) > NEAR_STEADY:",
     "if min(off) > NEAR_STEADY:",
     "'near steady' tested on the closest variable instead of the farthest", T_RSF),
    # --- program.py
    ("program_backward_slip_time", "program.py",
     "return self.slip / abs(self.velocity)",
     "return self.slip / self.velocity",
     "duration of a slip-specified backward segment (negative velocity)", T_PROG),
    # --- theory
    ("direct_log_slope_exponent", "theory/direct.py",
     "return direct / np.sqrt(1.0 + np.exp(-2.0 * lx))",
     "return direct / np.sqrt(1.0 + np.exp(-lx))",
     "x^-2 written as e^-lx (visible only near V_c, i.e. small x)", T_THEORY),
    ("direct_slope_vc_factor2", "theory/direct.py",
     "log_vc = math.log(2.0 * v_ref) - 1.0 / direct",
     "log_vc = math.log(v_ref) - 1.0 / direct",
     "V_c without its factor 2 in g'(V) (near-rest, ensemble inertia)",
     T_THEORY + ["tests/ensemble/test_direct_inertia.py"]),
    ("direct_jump_not_relative", "theory/direct.py",
     "return np.asarray(mu, float) * (g2 / g1 - 1.0)",
     "return np.asarray(mu, float) * (g2 - g1)",
     "jump mu (g2 - g1) instead of mu (g2/g1 - 1): equal when g1 = 1 (v1 = v_ref)", T_THEORY),
    ("direct_stab_b_without_g", "theory/linear_stability.py",
     "d = self.g * self.base.derivative_at_zero(n)",
     "d = self.base.derivative_at_zero(n)",
     "ageing response (b, a's ageing part) not scaled by the junction strength", T_STAB),
    ("stab_effective_b_u_power", "theory/stability.py",
     "b = u * u * z2 / (2.0 * dc)",
     "b = u * z2 / (2.0 * dc)",
     "u^2 written u in the matched Taylor series (invisible at u = 1)", T_STAB),
    ("dieterich_moment_minus_sign", "theory/dieterich.py",
     "total -= on_plus(-1.0, float(z_plus(-trap.y_c, alpha)), -1.0)",
     "total += on_plus(-1.0, float(z_plus(-trap.y_c, alpha)), -1.0)",
     "(-) branch part of the moment with the wrong sign (strong pinning only)", T_DIET),
    ("dieterich_cinf_coeffs_swapped", "theory/dieterich.py",
     "dyn = 4.0 * _forward_moment_loose(1, alpha) + 3.0 * _forward_moment_loose(0, alpha)",
     "dyn = 3.0 * _forward_moment_loose(1, alpha) + 4.0 * _forward_moment_loose(0, alpha)",
     "coefficients of the two moments swapped in C_inf", T_DIET),
    ("creep_en_dage_product", "theory/creep.py",
     "return np.exp(c) / (1.0 - self.eps * c)",
     "return np.exp(c) * (1.0 - self.eps * c)",
     "dT/dQ of Eyring-Nabarro: product instead of quotient (EN creep only)", T_CREEP + T_THEORY),
    ("creep_t0_log_sign", "theory/creep.py",
     "return math.exp(-x - math.log(self.edot0) - math.log(x))",
     "return math.exp(-x - math.log(self.edot0) + math.log(x))",
     "t0 = 1/(edot0 (Y/S) e^{Y/S}): the Y/S prefactor inverted", T_CREEP),
    ("static_threshold_shift_sign", "theory/static.py",
     "return np.asarray(r, float) * Trap(check_alpha(alpha)).y_c - d_w",
     "return np.asarray(r, float) * Trap(check_alpha(alpha)).y_c + d_w",
     "sign of the loaded-wait edge shift (only with load != 0)", T_THEORY),
    # --- analysis
    ("rsf_twin_hopf_no_damping", "analysis/rsf_stability.py",
     "out[\"omega_c\"] = twin.hopf_frequency(u, damping)",
     "out[\"omega_c\"] = twin.hopf_frequency(u)",
     "the damping not passed on to the Hopf frequency", T_STAB + T_RSF),
    ("linear_chain_without_mass", "analysis/linear.py",
     "chain = delay_chain_limit(resp, stiffness, mass, damping)",
     "chain = delay_chain_limit(resp, stiffness)",
     "mass and damping not passed to the chain limit (inertial regime only)",
     ["tests/theory/test_stability.py", "tests/sweeps/test_sweep.py"]),
    ("bif_hysteresis_strict", "analysis/bifurcation.py",
     "hyst = [r[\"d\"] for r in scan[\"up\"] if r[\"d\"] <= 0.0 and r[\"amplitude\"] > thr",
     "hyst = [r[\"d\"] for r in scan[\"up\"] if r[\"d\"] < 0.0 and r[\"amplitude\"] > thr",
     "K = K_c itself excluded from the hysteresis test", T_BIF),
    ("stickslip_stick_offbyone", "analysis/stickslip.py",
     "stick_frac = float(np.sum(dt[slow[1:]]) / span)",
     "stick_frac = float(np.sum(dt[slow[:-1]]) / span)",
     "each step weighted by the sample that starts it instead of the one that ends it", T_SS),
    ("stickslip_floor_radius_not_squared", "analysis/stickslip.py",
     # the same line after issue 26's model objects (the model carries its creep law)
     "r2 = float(model.law.radius(np.array([tau_d]))[0]) ** 2",
     "r2 = float(model.law.radius(np.array([tau_d]))[0])",
     "radius ratio used where its square (the area) is meant", T_SS),
    # --- fit/statistics.py
    ("stat_runs_var_n_plus_1", "fit/statistics.py",
     "var = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n - 1.0))",
     "var = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n + 1.0))",
     "runs test variance with n + 1 (estimator normalisation)", T_STAT),
    ("stat_aicc_denominator", "fit/statistics.py",
     "2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0",
     "2 * k * (k + 1) / (n - k) if n - k - 1 > 0",
     "AICc small-sample correction with n - k", T_STAT),
    ("stat_hac_recolour_sign", "fit/statistics.py",
     "color = np.linalg.inv(np.eye(p) - At.T)",
     "color = np.linalg.inv(np.eye(p) + At.T)",
     "recolouring (I + A)^-1 instead of (I - A)^-1", T_STAT),
    ("stat_bartlett_weight", "fit/statistics.py",
     "omega += (1.0 - lag / (lags + 1.0)) * (g + g.T)",
     "omega += (1.0 - lag / lags) * (g + g.T)",
     "Bartlett weight 1 - l/L instead of 1 - l/(L+1) (L = 1 drops all lags)", T_STAT),
    ("stat_bandwidth_rate", "fit/statistics.py",
     "math.ceil(1.1447 * (alpha * n) ** (1.0 / 3.0))",
     "math.ceil(1.1447 * (alpha * n) ** (1.0 / 5.0))",
     "quadratic-spectral rate n^(1/5) used with the Bartlett kernel", T_STAT),
    ("stat_chow_joint_denominator", "fit/statistics.py",
     "F = (max(delta, 0.0) / df1) / (2.0 * sep_cost / df2)",
     "F = (max(delta, 0.0) / df1) / (2.0 * cost / df2)",
     "F test's denominator from the joint RSS instead of the separate fits'", T_STAT),
    ("stat_t_one_sided", "fit/statistics.py",
     "return Z95 if sigma_given or dof <= 0 else float(stats.t.ppf(0.975, dof))",
     "return Z95 if sigma_given or dof <= 0 else float(stats.t.ppf(0.95, dof))",
     "one-sided quantile for a two-sided interval (estimated noise only)", T_STAT),
    # --- fit/steps.py
    ("steps_white_noise_no_sqrt2", "fit/steps.py",
     "return float(1.4826 * np.median(np.abs(d - np.median(d))) / math.sqrt(2.0))",
     "return float(1.4826 * np.median(np.abs(d - np.median(d))))",
     "std of first differences taken as the sample std (off by sqrt 2)", T_STEPS),
    ("steps_steady_noise_dof", "fit/steps.py",
     "return float(math.sqrt(r @ r / (mu.size - 2)))",
     "return float(math.sqrt(r @ r / (mu.size - 1)))",
     "one degree of freedom removed for a two-parameter line", T_STEPS),
    ("steps_window_start", "fit/steps.py",
     "i0 = (change[k - 1] + change[k]) // 2",
     "i0 = change[k - 1]",
     "window starts at the previous change (includes its transient) instead of midway",
     T_STEPS),
    ("steps_log_stderr_no_delta", "fit/steps.py",
     "\"stderr\": val * se if spec.log else se,",
     "\"stderr\": se,",
     "delta method forgotten for log-fitted parameters (stderr of ln p reported as of p)",
     T_STEPS),
    # --- io
    ("lab_hr_factor", "records/lab.py",
     "_TIME = {**TIME_UNITS, \"sec\": 1.0, \"hr\": 3600.0}",
     "_TIME = {**TIME_UNITS, \"sec\": 1.0, \"hr\": 60.0}",
     "hours alias given minutes' factor (rare unit)", T_LAB),
    ("lab_MN_factor", "records/lab.py",
     "_FORCE = {\"N\": 1.0, \"kN\": 1e3, \"MN\": 1e6}",
     "_FORCE = {\"N\": 1.0, \"kN\": 1e3, \"MN\": 1e3}",
     "mega-newton factor copied from kN (rare unit)", T_LAB),
    ("data_day_factor", "records/data.py",
     "\"d\": 86400.0,",
     "\"d\": 8640.0,",
     "seconds per day typo (rare unit)", T_DATA),
    ("seg_noise_mad_unscaled", "records/segmentation.py",
     "mad = 1.4826 * float(np.median(np.abs(d2 - np.median(d2))))",
     "mad = float(np.median(np.abs(d2 - np.median(d2))))",
     "MAD not scaled to a Gaussian sigma (hidden by the max with the trimmed RMS?)", T_SEG),
    ("labsteps_kN_scale", "records/labsteps.py",
     # the same factor after the table and segments.csv took it from one helper
     "return \"normal force\", \"kN\", 1e-3",
     "return \"normal force\", \"kN\", 1e3",
     "segments.csv normal force column in the wrong unit factor (force records only)", T_LAB),
    ("files_stale_tmp_of_live_pid", "io/files.py",
     "if m is None or int(m.group(1)) == os.getpid() or _pid_alive(int(m.group(1))):",
     "if m is None or int(m.group(1)) == os.getpid():",
     "file safety: another live run's temporaries removed", T_FILES),
    ("files_confined_dotdot", "io/files.py",
     "all(p not in (\"\", \".\", \"..\") for p in rel.split(\"/\"))",
     "all(p not in (\"\", \".\") for p in rel.split(\"/\"))",
     "file safety: a manifest entry with '..' counts as inside the folder", T_FILES),
    ("files_remove_unchecked", "io/files.py",
     "if rel in digests or not is_ours(out, rel, digest):",
     "if rel in digests:",
     "file safety: an old result changed by the user since is removed anyway", T_FILES),
    # --- ensemble
    ("ens_damping_cap_swapped", "ensemble/driving.py",
     "dt_osc = min(dt_osc, M / eta)",
     "dt_osc = min(dt_osc, eta / M)",
     "stability cap of the explicit damping written upside down (strong damping)", T_ENS),
    ("ens_verlet_predictor_velocity", "ensemble/driving.py",
     "a_new = accel(x_new, V + a * dt, ob.force, t_new)",
     "a_new = accel(x_new, V, ob.force, t_new)",
     "damping force at the new time evaluated with the old velocity", T_ENS),
    ("thermal_inverse_strength_large", "ensemble/thermal.py",
     "return v_ref * math.exp(z - 1.0 / direct)",
     "return 2.0 * v_ref * math.exp(z - 1.0 / direct)",
     "V_c e^z kept instead of V_c e^z / 2 in the large-z branch", T_ENS),
    # --- plots and cli
    ("plots_summary_dc_mm", "plots/summary.py",
     "_SCALE = {\"a_minus_b\": 1.0, \"a\": 1.0, \"b\": 1.0, \"dc\": 1e6}",
     "_SCALE = {\"a_minus_b\": 1.0, \"a\": 1.0, \"b\": 1.0, \"dc\": 1e3}",
     "Dc plotted in mm under a µm label", T_PLOT),
    ("plots_record_time_origin", "plots/record.py",
     "ax.plot(tv - t0, v * 1e6, color=\"0.6\"",
     "ax.plot(tv, v * 1e6, color=\"0.6\"",
     "velocity panel not shifted to the first sample's time (other panels are)", T_PLOT),
    ("cli_steps_table_normal_scale", "cli/records.py",
     "scale, shown = (1e-3, \"kN\") if unit == \"N\" else (1e-6, \"MPa\")",
     "scale, shown = (1e-6, \"kN\") if unit == \"N\" else (1e-3, \"MPa\")",
     "scale factors of the normal column swapped between force and stress", T_CLI),
    ("cli_rsf_v0_default", "app/options.py",  # the rsf command's defaults moved to app/
     "\"v0\": Option(\"--v0\", 1e-6, \"> 0 m/s\"),",
     "\"v0\": Option(\"--v0\", 1e-5, \"> 0 m/s\"),",
     "wrong default reference velocity of the rsf command", T_CLI),
    ("cli_record_vbefore_mm", "cli/record.py",
     "{w.v_before * 1e6:>16.4g}",
     "{w.v_before * 1e3:>16.4g}",
     "v_before printed in mm/s under an um/s header", T_CLI),
]


# ----------------------------------------------------------------------------- the runner
Mutant = tuple[str, str, str, str, str, list[str]]


def resolve(mut: Mutant) -> Mutant:
    """The mutant at today's paths (every set uses it). A set's list is measured at the commit
    its docstring names; since then modules moved (``io/lab.py`` -> ``records/lab.py``, the
    CLI's checks to ``app/``) and the tests went into a folder per package: a moved source is
    found by its file name, else by the one module holding its original text; a test file that
    no longer exists under its flat name is found by its name in a package folder, else
    replaced by the test folder of the mutant's package (``tests/<package>/``)."""
    name, rel, orig, mutated, why, tests = mut
    if not (SRC / rel).exists():
        hits = sorted(p.relative_to(SRC).as_posix() for p in SRC.rglob(Path(rel).name))
        rel = hits[0] if len(hits) == 1 else rel
    if (SRC / rel).exists() and (SRC / rel).read_text().count(orig) == 0:
        hits = sorted(p.relative_to(SRC).as_posix() for p in SRC.rglob("*.py")
                      if p.read_text().count(orig) == 1)
        rel = hits[0] if len(hits) == 1 else rel
    new: list[str] = []
    for t in tests:
        if (ROOT / t).exists():
            new.append(t)
            continue
        hits = sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "tests").rglob(Path(t).name))
        pkg = f"tests/{rel.split('/')[0]}" if "/" in rel else "tests"
        own = [h for h in hits if h.startswith(pkg + "/")]
        new += own or hits[:1] or [pkg]
    return name, rel, orig, mutated, why, list(dict.fromkeys(new))


def check(mutants: list[Mutant] | None = None) -> list[str]:
    """Each original occurs exactly once (at today's paths); each test file exists; names
    unique."""
    mutants = MUTANTS if mutants is None else mutants
    bad = []
    names = [m[0] for m in mutants]
    if len(set(names)) != len(names):
        bad.append("duplicate names")
    for name, rel, orig, mut, _why, tests in map(resolve, mutants):
        n = (SRC / rel).read_text().count(orig)
        if n != 1:
            bad.append(f"{name}: original occurs {n} times in {rel}")
        if orig == mut:
            bad.append(f"{name}: no change")
        bad += [f"{name}: {t} missing" for t in tests if not (ROOT / t).exists()]
    return bad


def _cache_entries(path: Path) -> list[Path]:
    cache = path.parent / "__pycache__"
    if not cache.is_dir():
        return []
    return [p for p in cache.iterdir() if p.name.startswith(path.stem + ".")]


def _pytest(args: list[str], timeout: float) -> tuple[str, float, str]:
    t0 = time.monotonic()
    cmd = [PY, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", "--timeout", "300", *args]
    try:
        p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired as exc:
        out = (exc.stdout or b"").decode() if isinstance(exc.stdout, bytes) else (exc.stdout or "")
        return "timeout", time.monotonic() - t0, out[-2000:]
    dt = time.monotonic() - t0
    out = p.stdout + p.stderr
    if p.returncode == 0:
        return "survived", dt, out[-400:]
    if p.returncode in (4, 5):  # usage error, no tests collected: not a kill
        return "runner-error", dt, out[-400:]
    return "killed", dt, out


def _first_failure(out: str) -> str:
    m = re.search(r"^(?:FAILED|ERROR) (\S+)", out, re.M)
    return m.group(1) if m else ""


def run_one(mut: tuple[str, str, str, str, str, list[str]], whole_timeout: float,
            whole: bool, skip_chosen: bool = False) -> dict:
    name, rel, orig, mutated, why, tests = mut
    path = SRC / rel
    st = path.stat()
    original = path.read_text()
    tmp = Path(tempfile.mkdtemp(prefix="blindmut-"))
    saved = []
    for p in _cache_entries(path):
        shutil.copy2(p, tmp / p.name)
        saved.append(p.name)
    res: dict = {"name": name, "file": rel, "why": why, "tests": tests}
    try:
        assert original.count(orig) == 1, f"{name}: original not unique"
        path.write_text(original.replace(orig, mutated))
        status, dt, out = ("survived", 0.0, "") if skip_chosen else _pytest(tests, timeout=1500)
        res.update(status=status, seconds=round(dt, 1), failing=_first_failure(out),
                   tail=out[-600:] if status != "killed" else "")
        if status == "survived" and whole:
            s2, dt2, out2 = _pytest(["tests/"], timeout=whole_timeout)
            res.update(whole=s2, whole_seconds=round(dt2, 1), whole_failing=_first_failure(out2),
                       whole_tail=out2[-600:])
            if s2 in ("killed", "timeout"):
                res["status"] = "killed(whole)" if s2 == "killed" else "timeout(whole)"
    finally:
        path.write_text(original)
        os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns))
        for p in _cache_entries(path):
            if p.name not in saved:
                p.unlink()
        for nm in saved:
            shutil.copy2(tmp / nm, path.parent / "__pycache__" / nm)
        shutil.rmtree(tmp, ignore_errors=True)
    return res


def run_set(argv: list[str], mutants: list[Mutant], log_name: str,
            wider: dict[str, list[str]] | None = None) -> int:
    """The command line of every set: ``--check``; ``NAME ...`` (in the order given; all by
    default); ``--no-whole`` (chosen files only); ``--whole-only`` (survivors against the
    whole suite); ``--wider`` (a set's second pass: its ``wider`` test choice). Each kill's
    first failing test is rerun on the unmutated tree (the kill must be the mutant's); every
    result is appended to ``$TMPDIR/<log_name>``."""
    bad = check(mutants)
    if bad:
        print("\n".join(bad))
        return 2
    if "--check" in argv:
        print(f"{len(mutants)} mutants, all originals unique")
        return 0
    whole = "--no-whole" not in argv
    skip_chosen = "--whole-only" in argv
    wanted = [a for a in argv if not a.startswith("--")]
    by_name = {m[0]: resolve(m) for m in mutants}
    unknown = [w for w in wanted if w not in by_name]
    if unknown:
        print(f"unknown mutant(s): {', '.join(unknown)}")
        return 2
    todo = [by_name[w] for w in wanted] if wanted else list(by_name.values())
    if "--wider" in argv:
        if wider is None:
            print("--wider: this set has no second test choice")
            return 2
        todo = [(*m[:5], wider[m[0]]) for m in todo if m[0] in wider]
    log = Path(tempfile.gettempdir()) / log_name
    results = []
    for m in todo:
        r = run_one(m, whole_timeout=1800, whole=whole, skip_chosen=skip_chosen)
        if r["status"].startswith("killed"):
            node = r.get("whole_failing") or r.get("failing")
            if node:
                r["baseline_of_failing"] = _pytest([node], timeout=900)[0]
        results.append(r)
        print(f"{r['name']:<38} {r['status']:<14} {r['seconds']:>7.1f}s "
              f"{r.get('failing', '')} [unmutated: {r.get('baseline_of_failing', '')}]",
              flush=True)
        with open(log, "a") as fh:
            fh.write(json.dumps(r) + "\n")
    killed = sum(r["status"].startswith(("killed", "timeout")) for r in results)
    print(f"\nkilled {killed}/{len(results)} = {100.0 * killed / max(len(results), 1):.1f} %")
    return 0


def main(argv: list[str]) -> int:
    return run_set(argv, MUTANTS, "blind_mutants_results.jsonl")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
