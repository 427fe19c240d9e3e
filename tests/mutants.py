"""Hand-written mutation testing: does the test suite notice plausible mistakes?

Run from the repository root (``make mutants``; not part of CI)::

    python -m tests.mutants [--list] [--only NAME ...] [--timeout S] [--no-baseline]

Each mutant is one exact text replacement in one source file, with the pytest selection that
should notice it. The runner copies ``src/`` once to a temporary directory, first runs every
selection there unchanged (the *baseline*: a selection that fails without a mutant could not
tell killed from broken, and the run also fills that copy's Numba cache), then, per mutant,
copies the warm tree again, applies the replacement and runs the selection with ``-x -q -p
no:cacheprovider`` and a timeout, ``PYTHONPATH`` pointing at the copy. The working tree is never
touched. A mutant whose original text is not found exactly once is *stale*: an error, reported
as such (the source moved on; update the list).

Exit status 0 only when every mutant applied cleanly, the baseline passed and at least
:data:`REQUIRED_RATE` of the mutants were killed (a timeout counts as killed: the mutant made
the selection hang or crawl, which the run would notice too).
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
REQUIRED_RATE = 0.95
D = "src/dryfriction/"


@dataclass(frozen=True)
class Mutant:
    """One plausible mistake: ``original`` (found exactly once in ``file``) -> ``replacement``;
    ``tests`` are pytest arguments (files, ``-k`` expressions) that should fail with it."""

    name: str
    file: str
    original: str
    replacement: str
    tests: tuple[str, ...]


def _m(name: str, file: str, original: str, replacement: str, *tests: str) -> Mutant:
    return Mutant(name, D + file, original, replacement, tests)


_DRV = "tests/ensemble/test_driving.py"
_RSF = "tests/rsf/test_rsf.py"
_LAB = "tests/records/test_lab.py"
_DIR = "tests/theory/test_direct.py"
_DIN = "tests/ensemble/test_direct_inertia.py"
_FRG = "tests/analysis/test_fronts_generic.py"
_CRG = "tests/theory/test_creep_generic.py"
_MAG = "tests/fit/test_machine_generic.py"
_ARG = "tests/records/test_artifacts_generic.py"
_SSE = "tests/io/test_stickslip_table_edges.py"
_LCG = "tests/fit/test_lawcolumns.py"
_IDD = "tests/fit/test_identify_definitions.py"
_FLG = "tests/records/test_fluctuations_generic.py"
_IOG = "tests/app/test_interface_outputs_generic.py"
_ISW = "tests/analysis/test_interface_sweep.py"
_HTE = "tests/analysis/test_hopf_table_edges.py"

MUTANTS: tuple[Mutant, ...] = (
    # --- the survivors of the earlier measurement (issue 13) --------------------------------
    _m("population: very strong pinning H0 in strong pinning", "ensemble/population.py",
       "self._norm = 1.0 / (track.traps_per_a0 * trap.H0)",
       "self._norm = 1.0 / (track.traps_per_a0 * trap.H0_paper)",
       _DRV, "-k", "strong_pinning"),
    _m("kernel: age restarts at the (+) -> (-) jump", "ensemble/kernel.py",
       "                        if strong:\n                            s = 2\n",
       "                        if strong:\n                            s = 2\n"
       "                            tb = t1\n",
       _DRV, "-k", "strong_pinning"),
    _m("RateState.state_rate: ageing law sign flipped", "rsf/law.py",
       "            return 1.0 - omega", "            return omega - 1.0",
       _RSF, "-k", "state_rate"),
    _m("hold_peak_friction: second state never heals", "rsf/law.py",
       "th2 = None if self.dc2 is None else self.dc2 / v + heal",
       "th2 = None if self.dc2 is None else self.dc2 / v",
       _RSF, "-k", "two_state_hold"),
    _m("RSF spring: slider position with the wrong sign", "rsf/result.py",
       "load - (stress - stress0) / stiffness", "load + (stress - stress0) / stiffness",
       _RSF, "-k", "spring_outputs"),
    _m("RSF spring: quasi-static stress without eta V", "rsf/result.py",
       "        stress = mu + damping * v", "        stress = mu + 0.0 * v",
       _RSF, "-k", "spring_outputs"),
    _m("atomic_write_bytes writes the file directly", "io/files.py",
       "    fd, tmp = _make_temp(path.parent, path.name, directory=False)\n",
       "    fd, tmp = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o666), path\n",
       "tests/io/test_io.py", "-k", "atomic_write"),
    _m("Student-t quantile replaced by 1.96", "fit/statistics.py",
       "return Z95 if sigma_given or dof <= 0 else float(stats.t.ppf(0.975, dof))",
       "return Z95",
       "tests/fit/test_fit.py", "-k", "student_t"),
    _m("HAC covariance: prewhitened scores not recoloured", "fit/statistics.py",
       "    omega = color @ omega_e @ color.T\n", "    omega = omega_e\n",
       "tests/fit/test_hac.py"),
    _m("step intervals: robust inflation ignored", "fit/steps.py",
       "        return self.white if self.robust is None else self.robust\n",
       "        return self.white\n",
       "tests/fit/test_steps.py", "-k", "correlated_noise"),
    # --- trap geometry (theory/trap.py) ----------------------------------------------------
    _m("spinodal y_c with 2 alpha", "theory/trap.py",
       "(1.0 - self.alpha) ** 2 / (4.0 * self.alpha) if self.pinned",
       "(1.0 - self.alpha) ** 2 / (2.0 * self.alpha) if self.pinned",
       "tests/theory/test_trap.py"),
    _m("death point: min instead of max", "theory/trap.py",
       "return max(self.y_c, 1.0)", "return min(self.y_c, 1.0)",
       "tests/theory/test_trap.py", "tests/theory/test_steady.py"),
    _m("spinodal force f_c with y_c + z_c", "theory/trap.py",
       "6.0 * self.alpha * (self.y_c - self.z_c) if self.pinned",
       "6.0 * self.alpha * (self.y_c + self.z_c) if self.pinned",
       _DRV, "-k", "sawtooth"),
    _m("H1: sign of the subtracted work", "theory/trap.py",
       "return self.H0 - float(work_forward(self.y_c - 1.0, self.alpha))",
       "return self.H0 + float(work_forward(self.y_c - 1.0, self.alpha))",
       "tests/theory/test_static.py"),
    # --- creep laws (theory/creep.py) ------------------------------------------------------
    _m("log creep law without eps", "theory/creep.py",
       "        return 1.0 + self.eps * np.asarray(c, float)",
       "        return 1.0 + np.asarray(c, float)",
       "tests/theory/test_creep.py"),
    _m("Eyring-Nabarro radius without eps", "theory/creep.py",
       "        return 1.0 / (1.0 - self.eps * np.asarray(c, float))",
       "        return 1.0 / (1.0 - np.asarray(c, float))",
       "tests/theory/test_creep.py"),
    # --- static and steady friction (theory/static.py, theory/steady.py) -------------------
    _m("eq. 27: r^2 instead of r^3 on the aged traps", "theory/static.py",
       "r**3 * (aged_plus + aged_minus)", "r**2 * (aged_plus + aged_minus)",
       "tests/theory/test_static.py"),
    _m("steady death point: death_point instead of y_c", "theory/steady.py",
       "    alpha, u, eps = check_steady_inputs(u, eps, alpha, creep)\n"
       "    yc = Trap(alpha).y_c\n",
       "    alpha, u, eps = check_steady_inputs(u, eps, alpha, creep)\n"
       "    yc = Trap(alpha).death_point\n",
       _DRV, "-k", "strong_pinning_steady"),
    # --- the ensemble ------------------------------------------------------------------------
    _m("kernel f_+: wrong root of z_+", "ensemble/kernel.py",
       "    z = -0.5 * ((1.0 - alpha) + sd)", "    z = -0.5 * ((1.0 - alpha) - sd)",
       "tests/ensemble/test_population.py"),
    _m("kernel: (-) trap dies at y_c instead of w = 1", "ensemble/kernel.py",
       "                    if w > 1.0:\n                        s = 3",
       "                    if w > yc:\n                        s = 3",
       _DRV, "-k", "strong_pinning"),
    _m("steady initial state: age from p instead of p + 1", "ensemble/population.py",
       "age = np.where(inside, (p + 1.0) / u, 0.0)", "age = np.where(inside, p / u, 0.0)",
       "tests/ensemble/test_population.py", "-k", "steady"),
    _m("driving: velocity of the segment before (off by one)", "ensemble/driving.py",
       "side=\"right\") - 1\n    vs = ", "side=\"right\") - 2\n    vs = ",
       _DRV, "tests/cli/test_simulate.py"),
    _m("roots: a small Newton step taken for convergence unconfirmed", "ensemble/balance.py",
       "if gc == 0.0 or (gc < 0.0) != (g < 0.0):", "if True:",
       _DRV, "-k", "root_in_bracket"),
    _m("roots: Newton step of the wrong sign (bisection only)", "ensemble/balance.py",
       "            step = g / s\n", "            step = -g / s\n",
       _DRV, "-k", "root_in_bracket"),
    _m("roots: slope of the junction strength dropped from the balance", "ensemble/balance.py",
       "return A - K * x - g * o.force, -K - g * o.stiffness - slope",
       "return A - K * x - g * o.force, -K - g * o.stiffness",
       _DRV, "-k", "kernel_passes"),
    # --- programs, rate-and-state --------------------------------------------------------------
    _m("segment_index left-continuous at boundaries", "program.py",
       "i = np.searchsorted(self.times, t, side=\"right\") - 1",
       "i = np.searchsorted(self.times, t, side=\"left\") - 1",
       "tests/io/test_protocol.py", _RSF, "-k", "not reference"),
    _m("RSF friction: direct effect sign", "rsf/law.py",
       "return self._psi(theta, theta2) + self.a * np.log(v / self.v0)",
       "return self._psi(theta, theta2) - self.a * np.log(v / self.v0)",
       _RSF, "-k", "not reference"),
    _m("RSF steady state: b2 left out", "rsf/law.py",
       "return self.mu0 + (self.a - self.b_total) * np.log(v / self.v0)",
       "return self.mu0 + (self.a - self.b) * np.log(v / self.v0)",
       _RSF),
    # --- fitting, files, sweeps --------------------------------------------------------------
    _m("fit: residual variance RSS/(2(n - p))", "fit/engine.py",
       "(2.0 * cost / dof if dof > 0 else math.nan)", "(cost / dof if dof > 0 else math.nan)",
       "tests/fit/test_fit.py", "-k", "estimated_noise"),
    _m("manifest check ignores the format", "io/files.py",
       "if not isinstance(m, dict) or m.get(\"format\") != MANIFEST_FORMAT:",
       "if not isinstance(m, dict):",
       "tests/io/test_io.py", "-k", "manifest"),
    _m("manifest paths not confined to the folder", "io/files.py",
       'return rel != MANIFEST and all(p not in ("", ".", "..") for p in rel.split("/"))',
       "return rel != MANIFEST",
       "tests/io/test_file_safety.py", "-k", "manifest_entry_outside"),
    _m("backup name chosen first, then renamed onto (concurrent runs clobber)", "io/files.py",
       "                    os.link(path, backup, follow_symlinks=False)\n"
       "                    return backup",
       "                    if os.path.lexists(backup):\n"
       "                        raise FileExistsError(backup)\n"
       "                    os.replace(path, backup)\n"
       "                    return backup",
       "tests/io/test_file_safety.py", "-k", "concurrent"),
    _m("stored sweep point reused without checking its hash", "sweeps/sweep.py",
       'rec.get("key") == key and rec.get("sha256") == _digest(\n'
       '            {k: v for k, v in rec.items() if k != "sha256"})):',
       'rec.get("key") == key):',
       "tests/io/test_file_safety.py", "-k", "edited_point"),
    _m("sweep point key leaves out the analysis", "sweeps/sweep.py",
       "return _digest({\"format\": SWEEP_FORMAT, \"version\": RESULT_VERSION, "
       "\"analysis\": analysis,\n                    \"protocol\": protocol})[:32]",
       "return _digest({\"format\": SWEEP_FORMAT, \"version\": RESULT_VERSION,\n"
       "                    \"protocol\": protocol})[:32]",
       "tests/sweeps/test_sweep.py", "-k", "point_key"),
    # --- lab records: the machine and the trend in the RSF fit (issue 10) -------------------
    _m("rsf series: trend applied with the wrong sign", "fit/models.py",
       "mu = mu + values[\"trend\"] * load_point_displacement(data)",
       "mu = mu - values[\"trend\"] * load_point_displacement(data)",
       "tests/fit/test_steps.py", "-k", "forward_model or trend_recovered"),
    _m("rsf series: fitted stiffness unused (kinematic)", "fit/models.py",
       "return values[\"stiffness\"] if setting == \"fit\" else float(setting)",
       "return math.inf",
       "tests/fit/test_steps.py", "-k", "forward_model or kinematic_machine"),
    # --- the trap model on the record's machine (issue 11) ---------------------------------
    _m("cv series: trend dropped", "fit/cvseries.py",
       "return mu + values[\"trend\"] * load_point_displacement(data)", "return mu",
       "tests/fit/test_cvfit.py", "-k", "trend_adds"),
    _m("cv series: spring ignored (kinematic)", "fit/cvseries.py",
       "if k_red <= STIFFNESS_MAX", "if k_red < 0.0",
       "tests/fit/test_cvfit.py", "-k", "kinematic_series"),
    _m("cv series: cached run reused for other parameters", "fit/cvseries.py",
       "hit = next((m for m in reversed(memory) if m[0] == key and m[1] is data), None)",
       "hit = next((m for m in reversed(memory) if m[1] is data), None)",
       "tests/fit/test_cvfit.py", "-k", "trend_adds"),
    _m("slope stiffness: velocity ratio left out", "fit/machine.py",
       "k = slope / (1.0 - vb / va)", "k = slope",
       "tests/fit/test_steps.py", "-k", "slope_stiffness"),
    # --- laboratory records ---------------------------------------------------------------
    _m("lab: microns read as millimetres", "records/lab.py",
       '"micron": 1e-6, "microns": 1e-6}', '"micron": 1e-6, "microns": 1e-3}',
       _LAB, "-k", "units_convert or shared_record_reads"),
    _m("lab: friction as normal over shear", "records/lab.py",
       'friction = vals["shear"] / vals["normal"]', 'friction = vals["normal"] / vals["shear"]',
       _LAB, "-k", "comma_dialect or spaces_units_row"),
    _m("lab: error line numbers off by one", "records/lab.py",
       "return lambda i: first + i", "return lambda i: first + i + 1",
       _LAB, "-k", "every_refusal"),
    _m("lab: hold below 1 % of the fastest velocity", "records/detection.py",
       "floor = hold_velocity if given else 1e-4 * vmax",
       "floor = hold_velocity if given else 1e-2 * vmax",
       _LAB, "-k", "wide_range"),
    _m("lab: no common plateau value", "records/detection.py",
       "            plateau[j] = v\n", "            plateau[j] = vel[j]\n",
       _LAB, "-k", "detects_velocity_steps"),
    _m("lab: step window lead as slip times velocity", "records/labsteps.py",
       "pre_slip / abs(prev.velocity)", "pre_slip * abs(prev.velocity)",
       _LAB, "-k", "slices_slide_hold_slide"),
    # --- identifiability and flags (issue 30) ----------------------------------------------
    _m("identify: runs allowance against independent signs", "fit/identify.py",
       "q_res < 0.5 * q_noise", "q_res < 0.5 * 0.5",
       "tests/fit/test_identify.py", "-k", "shared_record"),
    _m("identify: no test for a transient at all", "fit/identify.py",
       'noise_only = bool(no_transient) and name in ("a", "b", "dc")', "noise_only = False",
       "tests/fit/test_identify.py", "-k", "fit_to_noise"),
    _m("identify: Dc's lower limit at the fastest velocity", "fit/identify.py",
       "dt_after * float(d.v_load[-1])", "dt_after * float(np.max(d.v_load))",
       "tests/fit/test_identify.py", "-k", "velocity_after"),
    _m("identify: a missing error left without its flag", "fit/identify.py",
       "if sig is not None and not math.isfinite(float(sig))",
       "if sig is None and not math.isfinite(float(sig))",
       "tests/fit/test_identify.py", "-k", "nan_sigma"),
    _m("identify: pre-step drift against the noise alone", "fit/identify.py",
       "max(DRIFT_NOISE * noise, 3.0 * chance)", "DRIFT_NOISE * noise",
       "tests/fit/test_identify.py", "-k", "red_noise"),
    _m("fit_steps: a fit worse than the noise not retried", "fit/steps.py",
       "if not r.success or (cold and worse_than_noise(d, rms)):",
       "if not r.success:",
       "tests/fit/test_identify.py", "-k", "astray"),
    _m("summary figure: one standard error for the interval", "fit/experiment.py",
       'val, float(r[f"{name}_lo"]),',
       'val, val - float(r.get(f"sigma_{name}", 0.0)),',
       "tests/fit/test_identify.py", "-k", "agree"),
    # --- the direct effect (issue 11) --------------------------------------------------------
    _m("direct: sign of the rate term flipped (theory)", "theory/direct.py",
       "return np.log(np.abs(v) / (2.0 * v_ref)) + 1.0 / direct",
       "return -np.log(np.abs(v) / (2.0 * v_ref)) + 1.0 / direct",
       _DIR, "-k", "regularisation or aged_population"),
    _m("direct: sign of the rate term flipped (ensemble)", "theory/direct.py",
       "lx = math.log(abs(v) / (2.0 * v_ref)) + 1.0 / direct",
       "lx = -math.log(abs(v) / (2.0 * v_ref)) + 1.0 / direct",
       _DIR, "-k", "velocity_step"),
    _m("direct: g at the load point's velocity, not the slider's", "ensemble/driving.py",
       "K * xj, K, 1e9, velocity_scale(ens, tj - t_sub))",
       "K * xj, K, 1e9, (lambda g: type(\"LoadScale\", (), {\"__call__\": lambda _s, x: g, "
       "\"slope\": lambda _s, x: 0.0})())(velocity_scale(ens, tj - t_sub)(ens.x + "
       "(float(xp1) - xp_prev) / n)) if ens.model.direct else None)",
       _DIR, "-k", "load_point"),
    _m("direct: the velocity drive forgets the junction strength", "ensemble/driving.py",
       "rec.add(ens, with_strength(ens, o, v), v, events=events(o))",
       "rec.add(ens, o, v, events=events(o))",
       _DIR, "-k", "velocity_step"),
    _m("direct: static threshold ignores the pull velocity", "theory/static.py",
       "mu = mu * junction_strength(pull_velocity, direct, v_ref)",
       "mu = mu * junction_strength(1.0, direct, v_ref)",
       _DIR, "-k", "pull_velocity"),
    _m("direct: the instantaneous term enters the response with the wrong sign",
       "theory/linear_stability.py",
       "return self.g * self.base.Z(lam) + (self.a_direct / self.base.u) * lam",
       "return self.g * self.base.Z(lam) - (self.a_direct / self.base.u) * lam",
       _DIR, "-k", "critical_stiffness"),
    _m("direct inertial: g(V) dropped from the inertial force", "ensemble/driving.py",
       "if direct:  # implicit in V: the junction strength is stiff near rest",
       "if False:  # implicit in V: the junction strength is stiff near rest",
       _DIN, "-k", "kinematic_limit or velocity_step or rings_down"),
    _m("direct inertial: friction used without g(V), solved with it", "ensemble/driving.py",
       "ob = apply_strength(ob, g)", "ob = apply_strength(ob, 1.0)",
       _DIN, "-k", "work_of_the_spring"),
    _m("direct inertial: trapezoid even where g'(V) is stiff", "ensemble/thermal.py",
       "    return solve(1.0)\n", "    return solve(0.5)\n",
       _DIN, "-k", "work_of_the_spring or creeps"),
    _m("direct inertial: Verlet's position step where the acceleration relaxes at once",
       "ensemble/driving.py", "w = drift(ens.model, V, dt, M, eta, f_pop) if direct else 0.5",
       "w = 0.5", _DIN, "-k", "creeps"),
    _m("direct inertial: the implicit solve stops at its first guess", "ensemble/thermal.py",
       "        if h <= 0.0:\n            break\n",
       "        if h <= 0.0 or True:\n            break\n",
       _DIN, "-k", "work_of_the_spring or rings_down"),
    _m("direct: the spring drive's rate term with the wrong sign (g -> 2 - g)",
       "ensemble/thermal.py",
       "return strength_ratio((x - self.x0) / self.dt, self.direct, self.v_ref)",
       "return 2.0 - strength_ratio((x - self.x0) / self.dt, self.direct, self.v_ref)",
       "tests/analysis/test_bifurcation.py", "-k", "linear_rate"),
    # --- the edges (issue 14) and the damping check (issue 13) -------------------------------
    _m("inertial slider: damping sign flipped", "ensemble/driving.py",
       "return (K * (xpl - x) - f - eta * v) / M", "return (K * (xpl - x) - f + eta * v) / M",
       _DRV, "-k", "damped_inertial"),
    _m("stability: memory quadrature never refined with |lambda|", "theory/stability.py",
       "level = np.ceil(np.log2(np.where(far, 1.0, need))).astype(int)",
       "level = np.zeros(need.shape, int)",
       "tests/theory/test_stability.py", "-k", "independent"),
    _m("stability: spinodal tail of the endpoint expansion dropped", "theory/stability.py",
       "            out = out + np.exp(-lam * self.tau_d) * sing",
       "            out = out + 0.0 * sing",
       "tests/theory/test_stability.py", "-k", "independent"),
    _m("stability: supremum at infinity without the delay circles' radius", "theory/stability.py",
       "k_inf = -fwd + resp.delay_amplitude", "k_inf = -fwd",
       "tests/theory/test_stability.py", "-k", "supremum"),
    _m("stability: growth rate without the delay chain's seeds", "theory/stability.py",
       "for k in np.unique(np.r_[0:4, np.geomspace(4, 1e4, 18).round()])]",
       "for k in ()]",
       "tests/sweeps/test_cf.py", "-k", "spectrum"),
    _m("stability: chain limit with the wrong sign of ln|c|", "theory/stability.py",
       "return np.inf if c == 0 else float(-np.log(c) / resp.tau_d)",
       "return np.inf if c == 0 else float(np.log(c) / resp.tau_d)",
       "tests/sweeps/test_cf.py", "-k", "spectrum"),
    _m("rsf: no growth-rate step limit", "rsf/stepper.py",
       "limit_growth = p[_MODE] != KINEMATIC", "limit_growth = False",
       _RSF, "-k", "unstable_steady_state"),
    _m("rsf stepper: a run resumed compiled starts with a fresh step size", "rsf/stepper.py",
       "    h = st[_H]\n", "    h = 0.25 * st[_H]\n",
       "tests/rsf/test_routes.py", "-k", "hand_over"),
    _m("static: pairs met during a force hold do not age", "theory/static.py",
       "radii = radius(T - final[3], eps, creep) if final[3].size else np.zeros(0)",
       "radii = np.ones(final[3].size)",
       "tests/theory/test_static.py", "-k", "reversed_load"),
    _m("static: aged traps pushed out at the rear stay aged", "theory/static.py",
       "        rear = max(rear, -r - s)\n", "",
       "tests/theory/test_static.py", "-k", "rear"),
    _m("sampling: commensurate steps kept on one lattice phase", "ensemble/result.py",
       "    if m < 1 or n < _ALIAS_MIN_SAMPLES or n * abs(step - m) >= 0.5:\n        return n",
       "    if True:\n        return n",
       "tests/ensemble/test_population.py", "-k", "alias"),
    _m("stability: delay circles' radius without the edge's delay factor", "theory/stability.py",
       "return abs(self.edge * self.edge_delay) / self.H0", "return abs(self.edge) / self.H0",
       "tests/theory/test_stability.py", "-k", "against_direct_simulation"),
    _m("force drive: a hold sampled in slip done in one step", "ensemble/result.py",
       "return force_hold_grid(hold, self.every)",
       "return force_hold_grid(hold, self.every, math.log1p(hold) + 1.0)",
       _DRV, "-k", "force_hold_sampled"),
    _m("Dieterich's local constant: the creep clock taken for the waiting time",
       "theory/dieterich.py", "lambda law, rr: law.age(law.clock_at_radius(rr))",
       "lambda law, rr: law.clock_at_radius(rr)", "tests/", "-k", "dieterich"),
    _m("painter: a figure job drawn in the command's own process", "cli/painter.py",
       "    if painter is not None:\n        try:\n            payload",
       "    if False:\n        try:\n            payload",
       "tests/cli/test_painter.py"),
    _m("painter: left running when the command fails", "cli/painter.py",
       "        if painter is not None:\n            stop()",
       "        if painter is None:\n            stop()",
       "tests/cli/test_painter.py"),
    _m("SHS: a slide-hold-slide window cut at the hold's end (no reslide)", "records/labsteps.py",
       'StepWindow(len(out), "shs", i0, after.i_end,', 'StepWindow(len(out), "shs", i0, cur.i_end,',
       "tests/fit/test_shs.py", "-k", "slice_steps"),
    _m("SHS: a hold taken for a slow slide (no hold threshold)", "records/detection.py",
       "    return np.abs(v) <= (floor if given else np.maximum(\n"
       "        Z_HOLD * fl.scatter(d, 0.0 * v, sxx), floor))",
       "    return np.abs(v) <= (floor if given else 0.0 * v)",
       "tests/fit/test_shs.py", "-k", "detection"),
    _m("SHS: the ageing law does not heal a slider nearly at rest", "rsf/stepper.py",
       "        return e - v * invdc, -v * invdc, -e",
       "        return (e if v > 1e-8 else 0.0) - v * invdc, -v * invdc, -e",
       "tests/fit/test_shs.py", "-k", "forward_model"),
    _m("SHS: an unfinished reslide before a window not noted", "fit/steps.py",
       'if rem > 2.0 * rows[-1]["white_noise"]', 'if rem > 20.0 * rows[-1]["white_noise"]',
       "tests/fit/test_shs.py", "-k", "short_reslides"),
    # issue 25's surviving classes, with the invariant tests that kill them
    _m("invariants: lab velocity unit as length x time", "records/lab.py",
       'return f_len / f_time, "velocity"', 'return f_len * f_time, "velocity"',
       "tests/io/test_invariants_units.py", "-k", "lab_reader_units"),
    _m("invariants: data-set velocity unit as length x time", "records/data.py",
       "return LENGTH_UNITS[parts[0].strip()] / TIME_UNITS[parts[1].strip()]",
       "return LENGTH_UNITS[parts[0].strip()] * TIME_UNITS[parts[1].strip()]",
       "tests/io/test_invariants_units.py", "-k", "series_csv"),
    _m("invariants: RSF twin a without the junction strength g", "theory/linear_stability.py",
       "d = self.g * self.base.derivative_at_zero(n)",
       "d = (self.g if n > 1 else 1.0) * self.base.derivative_at_zero(n)",
       "tests/theory/test_invariants.py", "-k", "direct_twin"),
    _m("invariants: regularised law with V0 for 2 V0", "rsf/law.py",
       "lnz = np.log(av / (2.0 * self.v0)) + psi / self.a",
       "lnz = np.log(av / (self.v0)) + psi / self.a",
       "tests/rsf/test_invariants.py", "-k", "absolute_ruina_level"),
    _m("invariants: stepper's regularised law with ln V0 for ln 2 V0", "rsf/stepper.py",
       "math.log(2.0 * params.v0)", "math.log(params.v0)",
       "tests/rsf/test_invariants.py", "-k", "settles"),
    _m("invariants: noise level over sqrt 2 instead of sqrt 6", "records/segmentation.py",
       "return max(mad, rms) / np.sqrt(6.0)", "return max(mad, rms) / np.sqrt(2.0)",
       "tests/fit/test_invariants_estimators.py", "-k", "noise_level"),
    _m("invariants: white noise over sqrt 6 instead of sqrt 2", "fit/steps.py",
       "np.median(np.abs(d - np.median(d))) / math.sqrt(2.0))",
       "np.median(np.abs(d - np.median(d))) / math.sqrt(6.0))",
       "tests/fit/test_invariants_estimators.py", "-k", "white_noise_and_steady"),
    _m("invariants: Bartlett sum without its transpose term", "fit/statistics.py",
       "omega += (1.0 - lag / (lags + 1.0)) * (g + g.T)",
       "omega += (1.0 - lag / (lags + 1.0)) * (g)",
       "tests/fit/test_invariants_estimators.py", "-k", "definition_at_a_generic_point"),
    _m("invariants: step white covariance with RSS/(2 dof)", "fit/steps.py",
       "white = covariance(J, 2.0 * cost / dof)", "white = covariance(J, cost / dof)",
       "tests/fit/test_invariants_estimators.py", "-k", "engines"),
    _m("invariants: damping dropped from the inertial drift", "ensemble/thermal.py",
       "z = (_damping_rate(model, v, force) + damping) * dt / mass",
       "z = (_damping_rate(model, v, force)) * dt / mass",
       "tests/ensemble/test_invariants_steppers.py", "-k", "drift_weight"),
    _m("invariants: inertial theta-switch at z = 0.5", "ensemble/thermal.py",
       "return dt * (damping + _damping_rate(model, u, force)) > 2.0 * mass",
       "return dt * (damping + _damping_rate(model, u, force)) > 0.5 * mass",
       "tests/ensemble/test_invariants_steppers.py", "-k", "convergence_order or one_step_maps"),
    _m("invariants: bifurcation exponent over the largest distances", "analysis/bifurcation.py",
       'if r["d"] > 0.0 and r["amplitude"] > thr)[:n_fit]',
       'if r["d"] > 0.0 and r["amplitude"] > thr)[-n_fit:]',
       "tests/ensemble/test_invariants_steppers.py", "-k", "exponent"),
    _m("invariants: overdamped inertial step not capped at M/eta", "ensemble/driving.py",
       "            dt_osc = min(dt_osc, M / eta)", "            dt_osc = dt_osc",
       "tests/ensemble/test_invariants_steppers.py", "-k", "damped_limits"),
    _m("invariants: inertial RSF slip check without its rounding bound", "rsf/driving.py",
       "    tol = 100.0 * res.rtol * (abs(travel) + path + res.params.dc) + quad_rounding",
       "    tol = 100.0 * res.rtol * (abs(travel) + path + res.params.dc)",
       "tests/rsf/test_invariants.py", "-k", "settles"),
    _m("drive: the measured load point ignored by the forward model", "fit/loadpoint.py",
       'drive = getattr(data, "drive", None)  # the measured load point (.loadpoint), if any',
       "drive = None", "tests/fit/test_loadpoint.py", "-k", "hang"),
    _m("drive: a change placed only at a sample time", "fit/loadpoint.py",
       "tau = float(best.x) if best.fun <= rss[j] else float(cand[j])",
       "tau = float(cand[j])", "tests/fit/test_loadpoint.py", "-k", "between"),
    _m("drive: a change placed however wide its error", "fit/loadpoint.py",
       "placed = bool(est.sigma < float(t[i] - t[i - 1]))", "placed = True",
       "tests/fit/test_loadpoint.py", "-k", "cannot_place"),
    _m("drive: the transducer's noise kept in the drive", "fit/loadpoint.py",
       "            c = sp(kt - t_ref)\n", "            c = np.interp(kt, ts, resid[lo:hi])\n",
       "tests/fit/test_loadpoint.py", "-k", "servo"),
    _m("drive: the program comparison refitted on the measured drive", "fit/steps.py",
       "rp = fit(plain, r.fitted_model", "rp = fit(d, r.fitted_model",
       "tests/fit/test_loadpoint.py", "-k", "json_and_terminal"),
    _m("elastic: a reload's noise read from its own residuals", "fit/elastic.py",
       "    if calm.size > 3 and np.std(calm) > 0:\n"
       "        rho = float(np.corrcoef(calm[1:], calm[:-1])[0, 1])\n"
       "        s2 = max(s2, float(calm @ calm) / (calm.size - 2))",
       "    if r.size > 3 and np.std(r) > 0:\n"
       "        rho = float(np.corrcoef(r[1:], r[:-1])[0, 1])",
       "tests/fit/test_elastic.py", "-k", "reload_slopes"),
    _m("elastic: the slope against time, not load-point displacement", "fit/elastic.py",
       "est = _slope(x[i0:i0 + n], seg[:n], z, calm)",
       "est = _slope(data.t[i0:i0 + n], seg[:n], z, calm)",
       "tests/fit/test_elastic.py", "-k", "reload_slopes"),
    # --- issue 25 (strengthen): generic points, asymmetric inputs, definitions in the test --
    _m("fronts: an end cell of half its neighbour's gap", "analysis/fronts.py",
       "left = np.concatenate([[gaps[0]], gaps])", "left = np.concatenate([[0.0], gaps])",
       _FRG, "-k", "element_lengths"),
    _m("fronts: the slip from the rate by a rectangle sum", "analysis/fronts.py",
       "steps = 0.5 * (rate[1:] + rate[:-1]) * np.diff(t)[:, None]",
       "steps = rate[1:] * np.diff(t)[:, None]", _FRG, "-k", "trapezoidal"),
    _m("fronts: the moment as the mean slip times the extent", "analysis/fronts.py",
       "moment=float(np.sum(ds * lengths))", "moment=float(np.mean(ds) * lengths.sum())",
       _FRG, "-k", "length_weighted"),
    _m("catalogue: speed_left from the right front", "analysis/catalogue.py",
       'for side, k in (("left", 0), ("right", 1)):',
       'for side, k in (("left", 1), ("right", 0)):', _FRG, "-k", "different_speeds"),
    _m("fronts: t_arrest the arrival at the event's last element", "analysis/fronts.py",
       "float(arrival.max()), float(leave.max())", "float(arrival[-1]), float(leave.max())",
       _FRG, "-k", "different_speeds"),
    _m("precursors: the right edge's length one element short", "analysis/catalogue.py",
       "else slice(e.elements[0], n_x))", "else slice(e.elements[0] + 1, n_x))",
       _FRG, "-k", "mirror"),
    _m("precursors: the right edge's test one element short", "analysis/catalogue.py",
       "return bool(e.elements[-1] >= n_x - 1 - edge_gap)",
       "return bool(e.elements[-1] > n_x - 1 - edge_gap)", _FRG, "-k", "mirror"),
    _m("fronts: the load of the sample after, not interpolated", "analysis/fronts.py",
       "return float(np.interp(time, t, st.load)) if",
       "return float(st.load[np.searchsorted(t, time)]) if", _FRG, "-k", "interpolated"),
    _m("magnitude-frequency: m_min itself left out of the fit", "analysis/catalogue.py",
       "fit = positive[positive >= lo]", "fit = positive[positive > lo]",
       _FRG, "-k", "by_hand_and_scale"),
    _m("magnitude-frequency: logarithms from the smallest fitted moment",
       "analysis/catalogue.py", "logs = np.log(fit / lo) if fit.size else fit",
       "logs = np.log(fit / fit.min()) if fit.size else fit", _FRG, "-k", "by_hand_and_scale"),
    _m("front regimes: classed by the mean speed, not the interval", "analysis/catalogue.py",
       "for lo_, h in zip(lo, hi, strict=True)]", "for lo_, h in zip(r, r, strict=True)]",
       _FRG, "-k", "whole_interval"),
    _m("fronts: default threshold from the signed velocities", "analysis/fronts.py",
       'speeds = [abs(float(s["velocity"]))', 'speeds = [(float(s["velocity"]))',
       _FRG, "-k", "default_threshold"),
    _m("creep: Eyring-Nabarro radius slope without the square", "theory/creep.py",
       "return self.eps / (1.0 - self.eps * np.asarray(c, float)) ** 2",
       "return self.eps / (1.0 - self.eps * np.asarray(c, float))",
       _CRG, "-k", "finite_difference"),
    _m("creep: log law's radius slope without eps", "theory/creep.py",
       "np.full_like(np.asarray(c, float), self.eps)", "np.full_like(np.asarray(c, float), 1.0)",
       _CRG, "-k", "finite_difference"),
    _m("creep: Eyring-Nabarro clock at radius with 1 - 1/r", "theory/creep.py",
       "return (1.0 - 1.0 / np.asarray(r, float) ** 2) / self.eps",
       "return (1.0 - 1.0 / np.asarray(r, float)) / self.eps", _CRG, "-k", "inverts"),
    _m("creep: log law's clock at radius times eps", "theory/creep.py",
       "return (np.asarray(r, float) ** 2 - 1.0) / self.eps",
       "return (np.asarray(r, float) ** 2 - 1.0) * self.eps", _CRG, "-k", "inverts"),
    _m("creep: Eyring-Nabarro range end at 1/eps", "theory/creep.py",
       "else (1.0 - self.eps) / self.eps", "else 1.0 / self.eps", _CRG, "-k", "range_end"),
    _m("machine: load-point displacement from zero time, not t[0]", "fit/machine.py",
       "return np.interp(data.t - data.t[0], edges, x_edges)",
       "return np.interp(data.t, edges, x_edges)", _MAG, "-k", "forwards"),
    _m("hold remnant: healing at the reslide's velocity", "fit/machine.py",
       "v_before = abs(float(v[j0 - 1])) if j0 > 0 else abs(float(v[-1]))",
       "v_before = abs(float(v[-1]))", _MAG, "-k", "different_velocities"),
    _m("hold remnant: the hold one sample short", "fit/machine.py",
       "hold = float(data.t[j1] - data.t[j0])", "hold = float(data.t[j1 - 1] - data.t[j0])",
       _MAG, "-k", "different_velocities"),
    _m("slope stiffness: a decrease's extreme taken as the maximum", "fit/machine.py",
       "ext = float(after.max() if va > vb else after.min())", "ext = float(after.max())",
       _MAG, "-k", "up_and_down"),
    _m("slope stiffness: the level before from the last sample", "fit/machine.py",
       "base = float(np.mean(mu[max(0, i0 - 10):i0])) if i0 > 0 else float(mu[0])",
       "base = float(mu[i0 - 1])", _MAG, "-k", "up_and_down"),
    _m("interface: the stiffest mode of the fixed-ends chain", "ensemble/interface.py",
       "4.0 * math.sin(math.pi * (n - 1) / (2 * n)) ** 2",
       "4.0 * math.sin(math.pi * n / (2 * (n + 1))) ** 2",
       "tests/ensemble/test_interface_generic.py"),
    _m("reload time: the signed velocity in the healing", "app/ratestate.py",
       "math.log1p(hold * speed / dc) + 2.0 * a", "math.log1p(hold * v / dc) + 2.0 * a",
       "tests/app/test_reload_time.py"),
    _m("reload time: the spring's take-up left out", "app/ratestate.py",
       "return max(30.0, min(load + 10.0 * dc / speed, LOAD_MAX))",
       "return max(30.0, min(10.0 * dc / speed, LOAD_MAX))", "tests/app/test_reload_time.py"),
    _m("sampling: only a faster sampling looked for", "records/artifacts.py",
       "np.flatnonzero((ratio > _RATE_FACTOR) | (ratio < 1.0 / _RATE_FACTOR))",
       "np.flatnonzero((ratio < 1.0 / _RATE_FACTOR))", _ARG, "-k", "both_ways"),
    _m("sampling: a rate change placed at its block's start", "records/artifacts.py",
       "changes.append(float(t[j * block + k]))", "changes.append(float(t[(j + 1) * block]))",
       _ARG, "-k", "both_ways"),
    _m("sampling: a rate change needs a factor 2", "records/artifacts.py",
       "_RATE_FACTOR = 1.5  #", "_RATE_FACTOR = 2.0  #", _ARG, "-k", "rate_change_threshold"),
    _m("sampling: a gap reported at its end", "records/artifacts.py",
       "return changes, [float(t[i]) for i in gap]",
       "return changes, [float(t[i + 1]) for i in gap]", _ARG, "-k", "gap_threshold"),
    _m("sampling: a gap over 5 intervals", "records/artifacts.py",
       "gap = np.flatnonzero(dt > 10.0 * np.maximum(",
       "gap = np.flatnonzero(dt > 5.0 * np.maximum(", _ARG, "-k", "gap_threshold"),
    _m("jump excursion: the step not projected off the line's slope", "records/artifacts.py",
       "den = ni - ni**2 / n - ts[ks] ** 2 / sxx", "den = ni - ni**2 / n",
       _ARG, "-k", "re_zeroing"),
    _m("jump excursion: the sample after the jump off by one", "records/artifacts.py",
       "out.append((j, a + int(ks[i]), float(rs[ks[i]] / den[i])))",
       "out.append((j, a + int(ks[i]) - 1, float(rs[ks[i]] / den[i])))",
       _ARG, "-k", "re_zeroing"),
    _m("normal change: the half-way crossing looked for upwards only", "records/artifacts.py",
       "cross = np.flatnonzero(seg >= mid if after > before else seg <= mid)",
       "cross = np.flatnonzero(seg >= mid)", _ARG, "-k", "up_and_down"),
    _m("space-time fields: float32 whatever compact says", "io/spacetime.py",
       "dtype = np.float32 if compact else np.float64", "dtype = np.float32",
       "tests/io/test_spacetime_generic.py"),
    _m("stickslip table: stick_fraction's upper end open", "io/protocol.py",
       '"stick_fraction": (0.0, 1.0, True, False),', '"stick_fraction": (0.0, 1.0, True, True),',
       _SSE, "-k", "edges"),
    _m("stickslip table: rel_threshold's upper end closed", "io/protocol.py",
       '"rel_threshold": (0.0, 1.0, True, True),', '"rel_threshold": (0.0, 1.0, True, False),',
       _SSE, "-k", "edges"),
    _m("stickslip table: a zero floor accepted", "io/protocol.py",
       '"floor": (0.0, None, True, False),', '"floor": (0.0, None, False, False),',
       _SSE, "-k", "edges"),
    _m("stickslip table: a boolean read as a number", "io/protocol.py",
       "if isinstance(value, bool) or not isinstance(value, (int, float)):",
       "if not isinstance(value, (int, float)):", _SSE, "-k", "boolean"),
    _m("law columns: state0's span rule a factor 10, not ln 10", "fit/lawcolumns.py",
       "narrow = finite and hi - lo <= math.log(MAX_SPAN)",
       "narrow = finite and hi - lo <= MAX_SPAN", _LCG, "-k", "two_state"),
    _m("law columns: a log parameter's interval as value +- z se", "fit/lawcolumns.py",
       "lo, hi = ((sp.from_internal(float(theta[j]) - z * se),\n"
       "                   sp.from_internal(float(theta[j]) + z * se))",
       "lo, hi = ((val - z * se,\n                   val + z * se)", _LCG, "-k", "two_state"),
    _m("law columns: the two-state note with a - b + b2", "fit/lawcolumns.py",
       "{row['a_minus_b'] - row['b2']:.4g}", "{row['a_minus_b'] + row['b2']:.4g}",
       _LCG, "-k", "two_state"),
    _m("law columns: Nagata's c = 0 taken as on its search bound", "fit/lawcolumns.py",
       "< _BOUND_REL * max(width, 1.0) if name != \"c\" else",
       "< _BOUND_REL * max(width, 1.0) if True else", _LCG, "-k", "nagata"),
    _m("fit laws: the free start without its state0", "fit/laws.py",
       'theta0 = values["dc"] / v_first * math.exp(values["state0"])',
       'theta0 = values["dc"] / v_first', "tests/fit/test_laws_mapping.py", "-k", "free_start"),
    _m("fit laws: ageing2's second Dc given the first", "fit/laws.py",
       'dc2=values["dc2"] if two else None', 'dc2=values["dc"] if two else None',
       "tests/fit/test_laws_mapping.py", "-k", "lands"),
    _m("fit laws: the second Dc's start at a tenth of Dc", "fit/laws.py",
       'out["dc2"] = 10.0 * guess.get("dc", 1e-5)', 'out["dc2"] = 0.1 * guess.get("dc", 1e-5)',
       "tests/fit/test_laws_mapping.py", "-k", "starting"),
    _m("transient test: F without the residuals' correlation factor", "fit/identify.py",
       "F = (rss0 - rss1) / df1 / (rss1 / (len(d) - p)) * shrink",
       "F = (rss0 - rss1) / df1 / (rss1 / (len(d) - p))", _IDD, "-k", "f_test"),
    _m("transient test: denominator's degrees of freedom n - p", "fit/identify.py",
       "df1, df2 = p - 2, n_eff - p", "df1, df2 = p - 2, len(d) - p", _IDD, "-k", "f_test"),
    _m("misfit: the peak allowance's correlation factor turned over", "fit/identify.py",
       "math.sqrt((1 + rho) / ((1 - rho) * peak_samples))",
       "math.sqrt((1 - rho) / ((1 + rho) * peak_samples))", _IDD, "-k", "allowance"),
    _m("misfit: the allowance from the residuals' correlation", "fit/identify.py",
       "    calm = _calm(d)\n    rho = _tail_rho(d)\n",
       "    calm = _calm(d)\n"
       "    rho = float(np.clip(np.corrcoef(resid[1:], resid[:-1])[0, 1], 0.0, 0.999))\n",
       _IDD, "-k", "allowance"),
    _m("misfit: rms allowance 2 for 1.5", "fit/identify.py",
       'if row["rms"] > MISFIT_RMS * noise:', 'if row["rms"] > 2.0 * noise:',
       _IDD, "-k", "allowance"),
    _m("fit options: --stiffness with the range as >= 0 (zero and NaN accepted)", "app/fitting.py",
       "    if not k > 0:\n        raise ValueError(f\"--stiffness {text!r} is out of range",
       "    if k < 0:\n        raise ValueError(f\"--stiffness {text!r} is out of range",
       "tests/app/test_fit_option_edges.py", "-k", "refused"),
    _m("fit options: a --fix value cut at its last '='", "app/fitting.py",
       'name, sep, value = item.partition("=")', 'name, sep, value = item.rpartition("=")',
       "tests/app/test_fit_option_edges.py", "-k", "fix_pairs"),
    _m("fit options: a --fix with a blank name accepted", "app/fitting.py",
       "if not sep or not name.strip():", "if not sep:",
       "tests/app/test_fit_option_edges.py", "-k", "fix_pairs"),
    _m("with_stderr: only the row scaled", "fit/statistics.py",
       "mat = cov.matrix * np.outer(scale, scale)", "mat = cov.matrix * scale[:, None]",
       "tests/fit/test_statistics_generic.py", "-k", "with_stderr"),
    _m("with_stderr: the variance scaled by se/se_j", "fit/statistics.py",
       "    scale[j] = se / old\n", "    scale[j] = (se / old) ** 0.5\n",
       "tests/fit/test_statistics_generic.py", "-k", "with_stderr"),
    _m("format_value: a blank unit as a trailing space", "fit/statistics.py",
       'return f"{x:.3g}" + (f" {unit}" if unit else "")', 'return f"{x:.3g} {unit}"',
       "tests/fit/test_statistics_generic.py", "-k", "format_value"),
    _m("covariance: the noise variance left out", "fit/statistics.py",
       "else (Vt.T * inv) @ Vt * s2", "else (Vt.T * inv) @ Vt",
       "tests/fit/test_statistics_generic.py", "-k", "inverse_normal"),
    _m("fluctuations: beyond the longest scale the last value kept", "records/detection.py",
       "return np.where(d >= T[-1], q[-1] * np.sqrt(T[-1] / d), out)",
       "return np.where(d >= T[-1], q[-1], out)", _FLG, "-k", "log_log"),
    _m("fluctuations: interpolated linearly in T", "records/detection.py",
       "out = np.exp(np.interp(np.log(d), np.log(T), np.log(np.maximum(q, 1e-300))))",
       "out = np.interp(d, T, q)", _FLG, "-k", "log_log"),
    _m("fluctuations: the servo bound as a lower bound", "records/detection.py",
       "out = np.where(d > self.scales[-1], np.minimum(out, np.sqrt(12.0) * self.lag / d),",
       "out = np.where(d > self.scales[-1], np.maximum(out, np.sqrt(12.0) * self.lag / d),",
       _FLG, "-k", "log_log"),
    _m("fluctuations: white noise over sqrt(Sxx) in the scatter", "records/detection.py",
       "return np.sqrt(self.sigma**2 / np.maximum(sxx, 1e-300)",
       "return np.sqrt(self.sigma**2 / np.sqrt(np.maximum(sxx, 1e-300))",
       _FLG, "-k", "three_variances"),
    _m("held stiffness: the share as own/var", "fit/onemachine.py",
       "out.append((var, min(var / own, 1.0) if own > 0 else 0.0))",
       "out.append((var, min(own / var, 1.0) if own > 0 else 0.0))",
       "tests/fit/test_onemachine_generic.py"),
    _m("held stiffness: standard error from the half-width over 2 z", "fit/onemachine.py",
       'var = (math.log(rec["hi"] / rec["lo"]) / (2.0 * Z)) ** 2',
       'var = (math.log(rec["hi"] / rec["lo"]) / (4.0 * Z)) ** 2',
       "tests/fit/test_onemachine_generic.py"),
    _m("fronts.csv: the position and arrival columns swapped", "app/interface_outputs.py",
       "(e.index, f.direction, f.x[k], f.t[k], f.speed[k],",
       "(e.index, f.direction, f.t[k], f.x[k], f.speed[k],", _IOG, "-k", "fronts_csv"),
    _m("fronts.csv: a speed interval's ends swapped", "app/interface_outputs.py",
       "f.speed_low[k], f.speed_high[k]), strict=True)",
       "f.speed_high[k], f.speed_low[k]), strict=True)", _IOG, "-k", "fronts_csv"),
    _m("fronts: a speed interval's ends from the wrong slowness bounds", "analysis/fronts.py",
       "return 1.0 / s, (1.0 / hi if hi > 0 else math.nan), (1.0 / lo if lo > 0 else math.inf)",
       "return 1.0 / s, (1.0 / lo if lo > 0 else math.nan), (1.0 / hi if hi > 0 else math.inf)",
       _IOG, "-k", "fronts_csv"),
    _m("interface summary: the sound speed sqrt(m/k)", "analysis/fronts.py",
       "return math.sqrt(k / m) if k >= 0 and m > 0 else math.nan",
       "return math.sqrt(m / k) if k > 0 and m > 0 else math.nan", _IOG, "-k", "summary"),
    _m("peak residual: the extreme a maximum after a down step too", "fit/steps.py",
       "up = v[i0] > v[max(i0 - 1, 0)] or v[max(i0 - 1, 0)] == 0.0", "up = True",
       "tests/fit/test_peak_residual.py"),
    _m("peak residual: from the first change to sliding, not the last", "fit/steps.py",
       "    i0 = int(ch[-1]) + 1 if ch.size else 0\n    m = PEAK_SAMPLES",
       "    i0 = int(ch[0]) + 1 if ch.size else 0\n    m = PEAK_SAMPLES",
       "tests/fit/test_peak_residual.py"),
    _m("peak residual: one sample's residual, not the mean", "fit/steps.py",
       "    return float(np.mean(r)), i0 + j + m // 2", "    return float(r[0]), i0 + j + m // 2",
       "tests/fit/test_peak_residual.py"),
    _m("mat names: a velocity's um_s kept with its underscore", "records/labforms.py",
       'unit = m.group(2).replace("_", "/")', "unit = m.group(2)",
       "tests/records/test_labforms_units.py"),
    _m("mat names: ms not read as a unit", "records/labforms.py",
       r'_UNIT_SUFFIX = re.compile(r"^(.+?)_(s|ms|us|min|',
       r'_UNIT_SUFFIX = re.compile(r"^(.+?)_(s|us|min|', "tests/records/test_labforms_units.py"),
    _m("text check: UTF-16's mark tested before UTF-32's", "io/textfile.py",
       '    if head.startswith((b"\\xff\\xfe\\x00\\x00", b"\\x00\\x00\\xfe\\xff")):\n'
       '        raise ValueError(f"{source} is UTF-32 text: save it as UTF-8")\n'
       '    if head.startswith((b"\\xff\\xfe", b"\\xfe\\xff")):\n'
       '        raise ValueError(f"{source} is UTF-16 text: save it as UTF-8")\n',
       '    if head.startswith((b"\\xff\\xfe", b"\\xfe\\xff")):\n'
       '        raise ValueError(f"{source} is UTF-16 text: save it as UTF-8")\n'
       '    if head.startswith((b"\\xff\\xfe\\x00\\x00", b"\\x00\\x00\\xfe\\xff")):\n'
       '        raise ValueError(f"{source} is UTF-32 text: save it as UTF-8")\n',
       "tests/io/test_textfile.py"),
    _m("text check: a mark-less UTF-16 looked for in one byte order", "io/textfile.py",
       "(even.count(0) > 0.4 * len(even) or odd.count(0) > 0.4 * len(odd))",
       "(odd.count(0) > 0.4 * len(odd))", "tests/io/test_textfile.py"),
    _m("granular floor: the radius, not its square", "analysis/stickslip.py",
       "r2 = float(model.law.radius(np.array([tau_d]))[0]) ** 2",
       "r2 = float(model.law.radius(np.array([tau_d]))[0])",
       "tests/analysis/test_granular_floor.py"),
    _m("granular floor: mu_el left out", "analysis/stickslip.py",
       "return factor * model.mu_el * trap.f_c * r2 / (trap.H0 * traps_per_a0)",
       "return factor * trap.f_c * r2 / (trap.H0 * traps_per_a0)",
       "tests/analysis/test_granular_floor.py"),
    _m("velocities: the upper end open", "analysis/hopf_table.py",
       "if not 0.0 < v <= v_max:", "if not 0.0 < v < v_max:", _HTE, "-k", "velocities"),
    _m("velocities: the count's end off by one", "analysis/hopf_table.py",
       "if not 1 <= len(out) <= most:", "if not 1 <= len(out) < most:", _HTE, "-k", "velocities"),
    _m("trap normal form: alpha0 itself accepted", "analysis/hopf_table.py",
       "if model.alpha >= ALPHA0:", "if model.alpha > ALPHA0:", _HTE, "-k", "alpha0"),
    _m("trap normal form: a damping without mass accepted", "analysis/hopf_table.py",
       "if mass == 0.0 and damping != 0.0:", "if mass == 0.0 and damping > 1e-6:",
       _HTE, "-k", "alpha0"),
    _m("RSF state_rate: PRZ without its 1/2", "rsf/law.py",
       "return 0.5 * (1.0 - omega * omega)", "return (1.0 - omega * omega)",
       "tests/rsf/test_state_rate.py"),
    _m("RSF state_rate: the slip law's sign", "rsf/law.py",
       "return np.where(omega > 0, -omega * np.log(omega), 0.0)",
       "return np.where(omega > 0, omega * np.log(omega), 0.0)", "tests/rsf/test_state_rate.py"),
    _m("RSF state_rate: a reverse velocity's rate of its signed value", "rsf/law.py",
       'v = np.abs(check_range("v", v))', 'v = check_range("v", v)',
       "tests/rsf/test_state_rate.py"),
    _m("units: an empty unit written as name[]", "io/units.py",
       "    return u or DIMENSIONLESS\n", "    return u\n", "tests/io/test_units_headers.py"),
    _m("units: a header's unit cut at its first space", "io/units.py",
       'u = unit.split(" (", 1)[0].strip()', 'u = unit.split(" ", 1)[0].strip()',
       "tests/io/test_units_headers.py"),
    _m("segments.csv: a normal change at one velocity called a step", "records/labsteps.py",
       '"normal change" if prev == s.velocity else "step")', '"step")',
       "tests/records/test_segments_csv.py"),
    _m("segments.csv: samples as i_end - i_start + 1", "records/labsteps.py",
       "{s.i_end - s.i_start},{conf}", "{s.i_end - s.i_start + 1},{conf}",
       "tests/records/test_segments_csv.py"),
    _m("segments.csv: the --segments line's times absolute", "records/labsteps.py",
       'return ",".join(f"{s.t_start - t0:.10g}:{s.velocity:.6g}" for s in segments)',
       'return ",".join(f"{s.t_start:.10g}:{s.velocity:.6g}" for s in segments)',
       "tests/records/test_segments_csv.py"),
    _m("hold grid: the count of uniform steps rounded down", "ensemble/result.py",
       "n = max(1, math.ceil(hold / every - 1e-9))", "n = max(1, int(hold / every))",
       "tests/ensemble/test_hold_grid.py"),
    _m("hold grid: a sample at the hold's start", "ensemble/result.py",
       "return hold * np.arange(1, n + 1) / n", "return hold * np.arange(0, n + 1) / n",
       "tests/ensemble/test_hold_grid.py"),
    _m("hold grid: exp for expm1 (every sample one t0 late)", "ensemble/result.py",
       "grid = np.expm1(math.log1p(hold) * np.arange(1, n + 1) / n)",
       "grid = np.exp(math.log1p(hold) * np.arange(1, n + 1) / n)",
       "tests/ensemble/test_hold_grid.py"),
    _m("noise level: the RMS trimmed at the 90 % quantile", "records/segmentation.py",
       "trimmed = a[a <= np.quantile(a, 0.99)]", "trimmed = a[a <= np.quantile(a, 0.9)]",
       "tests/records/test_noise_level_definition.py"),
    _m("steady tail: the drift not capped at DRIFT_BLOCKS", "fit/cvtail.py",
       "drift = d2 * min(left / BLOCK_SLIP, DRIFT_BLOCKS)", "drift = d2 * left / BLOCK_SLIP",
       "tests/fit/test_steady_level.py"),
    _m("steady tail: the first difference ignored", "fit/cvtail.py",
       "return level if max(d1, d2, drift) <= tol else None",
       "return level if max(d2, drift) <= tol else None", "tests/fit/test_steady_level.py"),
    _m("steady tail: the tolerance absolute", "fit/cvtail.py",
       "tol = STEADY_TOL * abs(level)", "tol = STEADY_TOL", "tests/fit/test_steady_level.py"),
    _m("levels: a step without normal value put with the lowest", "fit/experiment.py",
       "            level += 1\n            out[i] = level", "            out[i] = 0",
       "tests/fit/test_levels_generic.py"),
    _m("levels report: the mean over a NaN value", "fit/experiment.py",
       "mean = float(ok.mean()) if ok.size else math.nan", "mean = float(np.mean(v))",
       "tests/fit/test_levels_generic.py"),
    # --- blind set 4's survivors (benchmarks/blind_mutants4.py), tests written after it was
    # measured: these no longer measure anything; a fresh blind set must
    _m("interface: uniform load as the mean spring force", "ensemble/interface.py",
       "load[j] = float(np.sum(kp * (lp - x)))", "load[j] = float(np.mean(kp * (lp - x)))",
       "tests/ensemble/test_interface_generic.py", "-k", "uniform_load"),
    _m("interface: spreads drawn one-sided on [1, 1 + s]", "ensemble/interface.py",
       "xi = rng.uniform(-1.0, 1.0, size=(2, n))", "xi = rng.uniform(0.0, 1.0, size=(2, n))",
       "tests/ensemble/test_interface_generic.py", "-k", "straddle"),
    _m("interface outputs: default edge_gap 0", "app/interface_outputs.py",
       "transient: float = 0.0, edge_gap: int = 1,", "transient: float = 0.0, edge_gap: int = 0,",
       "tests/app/test_interface_outputs_generic.py", "-k", "default_edge_gap"),
    _m("data: a waiting time of zero refused", "records/data.py",
       'if c == "t_w" and x < 0.0:', 'if c == "t_w" and x <= 0.0:',
       "tests/io/test_data.py", "-k", "waiting_time_of_zero"),
    _m("fronts figure: the density's slope on the cumulative count", "plots/fronts.py",
       "(m / mf.m_min) ** (1.0 - mf.alpha)", "(m / mf.m_min) ** (-mf.alpha)",
       "tests/plots/test_fronts_figures.py", "-k", "cumulative_count"),
    # --- interface sweeps (analysis/interface_sweep.py, app/sweeps.py; interface4)
    _m("interface sweep: spanning counted as the arrested events", "analysis/interface_sweep.py",
       "spanning = [e for e in events if e.spanning]",
       "spanning = [e for e in events if not e.spanning]", _ISW, "-k", "test_sweep_values"),
    _m("interface sweep: mean slip as the mean moment", "analysis/interface_sweep.py",
       '"mean_slip": mean([e.mean_slip for e in events]),',
       '"mean_slip": mean([e.moment for e in events]),', _ISW, "-k", "test_sweep_values"),
    _m("interface sweep: friction averaged without the trapezoid weights",
       "analysis/interface_sweep.py",
       "float(np.trapezoid(friction, tk) / (tk[-1] - tk[0]))", "float(np.mean(friction))",
       _ISW, "-k", "test_sweep_values"),
    _m("interface sweep: precursors with edge_gap 0, not simulate's 1",
       "analysis/interface_sweep.py", "after: float = 0.0, edge_gap: int = 1)",
       "after: float = 0.0, edge_gap: int = 0)", _ISW, "-k", "test_sweep_values"),
    _m("interface sweep: catalogue.after ignored", "analysis/interface_sweep.py",
       "              if e.t_start >= after]", "              if True]", _ISW, "-k",
       "catalogue_after"),
    _m("interface sweep: catalogue.after on the events' end", "analysis/interface_sweep.py",
       "              if e.t_start >= after]", "              if e.t_end >= after]", _ISW,
       "-k", "catalogue_after"),
    _m("interface sweep: points checked as spring protocols", "app/sweeps.py",
       "        if interface:  # its refusals", "        if False:  # its refusals", _ISW,
       "-k", "bad_point"),
    _m("interface sweep: only the base protocol checked", "app/sweeps.py",
       "            interface_point(point, where)", "            interface_point(spec.base, where)",
       _ISW, "-k", "bad_point"),
    _m("interface sweep: [catalogue] not checked before the workers",
       "analysis/interface_sweep.py",
       '    opts = catalogue_options(doc.pop("catalogue", None), source)',
       '    opts = dict(doc.pop("catalogue", None) or {})', _ISW, "-k", "bad_point"),
    _m("interface sweep: --linear ignored", "app/sweeps.py", "    if interface and linear:",
       "    if False:", _ISW, "-k", "linear_and_phase"),
    _m("interface sweep: min_elements 1.5 read as 1", "analysis/interface_sweep.py",
       "not math.isfinite(value) or value != int(value) or value < low",
       "not math.isfinite(value) or value < low", _ISW, "-k", "options_and_point"),
    _m("interface sweep: edge_gap 0 refused", "analysis/interface_sweep.py",
       'low = 1 if key == "min_elements" else 0', "low = 1", _ISW, "-k", "options_and_point"),
    _m("interface sweep: after equal to the duration accepted", "analysis/interface_sweep.py",
       'if opts.get("after", 0.0) >= total:', 'if opts.get("after", 0.0) > total:', _ISW, "-k",
       "options_and_point"),
)


# ----------------------------------------------------------------------------- the runner
def _apply(text: str, m: Mutant) -> str | None:
    """The mutated text, or ``None`` when the original is not found exactly once (stale)."""
    if text.count(m.original) != 1:
        return None
    return text.replace(m.original, m.replacement)


def _pytest(src: Path, tests: tuple[str, ...], timeout: float) -> tuple[str, float, str]:
    """Run a selection against the tree ``src``: ``("pass" | "fail" | "timeout", s, tail)``."""
    env = {**os.environ, "PYTHONPATH": str(src)}
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", *tests]
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timeout", time.monotonic() - t0, ""
    lines = (p.stdout + p.stderr).strip().splitlines()
    # the failing test's name when pytest names one, else the last line (a collection error)
    named = [ln for ln in lines if ln.startswith(("FAILED", "ERROR"))]
    tail = (named or lines[-1:] or [""])[0]
    return ("pass" if p.returncode == 0 else "fail"), time.monotonic() - t0, tail


def _stale(mutants: tuple[Mutant, ...]) -> list[str]:
    out = []
    for m in mutants:
        n = (ROOT / m.file).read_text().count(m.original)
        if n != 1:
            out.append(f"STALE {m.name}: original text found {n} times in {m.file}")
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m tests.mutants", description=__doc__.split("\n")[0])
    ap.add_argument("--list", action="store_true", help="list the mutants and exit")
    ap.add_argument("--only", nargs="+", metavar="TEXT",
                    help="run only the mutants whose name contains one of these")
    ap.add_argument("--timeout", type=float, default=300.0, help="seconds per pytest run")
    ap.add_argument("--no-baseline", action="store_true",
                    help="skip the unmutated run of each selection (faster, less safe)")
    args = ap.parse_args(argv)
    if args.timeout <= 0:
        ap.error(f"--timeout = {args.timeout:g} is not allowed: > 0")
    mutants = MUTANTS
    if args.only:
        mutants = tuple(m for m in MUTANTS if any(s in m.name for s in args.only))
        if not mutants:
            ap.error(f"--only {' '.join(args.only)}: no mutant's name contains that")
    if args.list:
        for m in mutants:
            print(f"{m.name}  [{m.file}]  pytest {' '.join(m.tests)}")
        return 0
    stale = _stale(mutants)
    for line in stale:
        print(line, flush=True)
    with tempfile.TemporaryDirectory(prefix="dryfriction-mutants-") as tmp:
        base = Path(tmp) / "base" / "src"
        # copy2 keeps the mtimes, so Numba's cache filled by the baseline stays valid for every
        # file a mutant leaves alone
        shutil.copytree(ROOT / "src", base, ignore=shutil.ignore_patterns("__pycache__",
                                                                          "*.egg-info"))
        broken: list[str] = []
        if not args.no_baseline:
            for sel in dict.fromkeys(m.tests for m in mutants):
                res, dt, tail = _pytest(base, sel, args.timeout)
                print(f"baseline {res:7s} {dt:6.1f}s  pytest {' '.join(sel)}", flush=True)
                if res != "pass":
                    broken.append(f"BASELINE FAILS: pytest {' '.join(sel)}: {tail}")
                    print(broken[-1], flush=True)
        killed = survived = 0
        t_all = time.monotonic()
        for m in mutants:
            src = base.parent.parent / "mutant" / "src"
            shutil.rmtree(src.parent, ignore_errors=True)
            shutil.copytree(base, src)
            target = src.parent / m.file
            new = _apply(target.read_text(), m)
            if new is None:
                continue  # reported as stale above
            target.write_text(new)
            res, dt, tail = _pytest(src, m.tests, args.timeout)
            ok = res != "pass"
            killed += ok
            survived += not ok
            print(f"{'killed ' if ok else 'SURVIVED'} ({res:7s} {dt:6.1f}s) {m.name}"
                  + (f"  <- {tail}" if ok and tail else ""), flush=True)
        n = killed + survived
        rate = killed / n if n else 0.0
        print(f"\n{killed}/{n} mutants killed ({100 * rate:.1f} %, required "
              f"{100 * REQUIRED_RATE:.0f} %); {len(stale)} stale; "
              f"{time.monotonic() - t_all:.0f} s")
        for line in stale + broken:
            print(line)
    return 0 if (rate >= REQUIRED_RATE and not stale and not broken) else 1


if __name__ == "__main__":
    sys.exit(main())
