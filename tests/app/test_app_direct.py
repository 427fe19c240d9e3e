"""The app layer's helpers called directly, not through the command line: their returned
values against the theory functions they wrap (at generic points, SI units other than 1,
a friction level mu_el other than 1), each column's unit, every range check on both sides of
its edge, and the defaults (issue 25)."""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

import dryfriction.fit.cvsteps as cvsteps
from dryfriction.app import records as app_records
from dryfriction.app import theory as app_theory
from dryfriction.app.checks import check_fit_options
from dryfriction.app.fitting import is_project_csv
from dryfriction.app.sweeps import protocol_text
from dryfriction.theory.model import TrapModel

# --- app.theory: the closed-form tables ------------------------------------------------------


def test_steady_si_is_mu_el_times_the_reduced_friction_at_v_t0_over_a0() -> None:
    from dryfriction.theory.steady import steady_friction

    eps, alpha, a0, t0, mu_el = 0.041, 0.17, 1.7e-6, 0.011, 0.47
    V = [3e-6, 2.3e-5, 7e-4]
    out = app_theory.steady(eps, V=V, alpha=alpha, a0=a0, t0=t0, mu_el=mu_el)
    u = np.asarray(V) * t0 / a0
    want = mu_el * steady_friction(TrapModel(alpha, eps, "log"), u)
    assert out.columns["V"] == V
    np.testing.assert_allclose(out.columns["mu_d"], want, rtol=1e-12)
    assert out.units["V"] == "m/s" and out.units["mu_d"] == "F/W"
    assert out.params == {"eps": eps, "alpha": alpha, "creep": "log", "a0": a0, "t0": t0,
                          "mu_el": mu_el}
    # without mu_el: the friction in units of F_el (the model's level, 1)
    plain = app_theory.steady(eps, V=V, alpha=alpha, a0=a0, t0=t0)
    np.testing.assert_allclose(plain.columns["mu_d"], want / mu_el, rtol=1e-12)
    assert plain.units["mu_d"] == "F_el" and "mu_el" not in plain.params


def test_steady_reduced_with_the_direct_effect() -> None:
    from dryfriction.theory.steady import steady_friction

    eps, u, A, u_ref = 0.037, [0.07, 3.1], 0.023, 0.29
    out = app_theory.steady(eps, u, direct=A, v_ref=u_ref)
    want = steady_friction(TrapModel(0.13, eps, "log", direct=A, v_ref=u_ref), np.asarray(u))
    np.testing.assert_allclose(out.columns["mu_d"], want, rtol=1e-12)
    assert out.units["u"] == "a0/t0" and out.units["mu_d"] == "F_el"
    assert out.params["direct"] == A and out.params["v_ref"] == u_ref
    assert "direct" not in app_theory.steady(eps, u).params  # athermal output unchanged
    assert out.as_dict()["units"]["mu_d"] == "F_el"


def test_static_si_is_mu_el_times_the_reduced_friction_at_t_w_over_t0() -> None:
    from dryfriction.theory.static import static_friction

    # a backward load: there the force hold differs from the position hold (by 2 % here;
    # at small forward loads the two coincide)
    eps, t0, mu_el, load = 0.037, 0.013, 0.47, -0.4
    t_w = [70.0]  # one value: a force hold costs ~0.2 s a point
    out = app_theory.static(eps, t_w=t_w, t0=t0, mu_el=mu_el, load=load, hold="force")
    model = TrapModel(0.13, eps, "log")
    want = mu_el * static_friction(model, np.asarray(t_w) / t0, load=load, hold="force")
    np.testing.assert_allclose(out.columns["mu_s"], want, rtol=1e-12)
    held = static_friction(model, np.asarray(t_w) / t0, load=load, hold="position")
    assert abs(want[0] / mu_el - held[0]) > 0.01  # the hold matters at this point
    assert out.columns["t_w"] == t_w and out.units["t_w"] == "s" and out.units["mu_s"] == "F/W"
    assert out.params["t0"] == t0 and out.params["hold"] == "force"
    red = app_theory.static(eps, [3.3, 170.0], load=0.27)
    np.testing.assert_allclose(red.columns["mu_s"], static_friction(
        model, np.array([3.3, 170.0]), load=0.27), rtol=1e-12)
    assert red.units["T"] == "t0" and red.units["mu_s"] == "F_el"
    assert red.params["hold"] == "position"  # the documented default


def test_steady_velocity_range_edges_name_v() -> None:
    """u = V t0/a0 in [U_MIN, U_MAX] (both ends accepted): V* a power of two, so the edge is
    exact; just beyond it is refused in --V's name."""
    from dryfriction.validation import U_MAX

    a0, t0 = 2.0**-20, 2.0**-3  # V* = 2**-17 m/s exactly
    vstar = a0 / t0
    out = app_theory.steady(0.04, V=[U_MAX * vstar], a0=a0, t0=t0)
    assert np.isfinite(out.columns["mu_d"]).all()
    with pytest.raises(ValueError, match=r"^--V \S+ m/s is out of range: with --a0"):
        app_theory.steady(0.04, V=[2.0 * U_MAX * vstar], a0=a0, t0=t0)


def test_stability_columns_are_the_theory_functions_values() -> None:
    from dryfriction.analysis.rsf_stability import rsf_stability_prediction
    from dryfriction.theory.linear_stability import critical_stiffness

    eps, u, M, eta = 0.043, [0.3, 2.2], 0.6, 0.17
    out = app_theory.stability(eps, u, mass=M, damping=eta)
    model = TrapModel(0.13, eps, "log")
    for i, v in enumerate(u):
        r = critical_stiffness(v, model, M, eta)
        got = [out.columns[c][i] for c in ("K_c", "omega_c", "forward_stiffness",
                                           "backward_stiffness", "dmu_d_du", "K_c_rsf")]
        want = [r.critical_stiffness, r.omega, r.forward_stiffness, r.backward_stiffness,
                r.velocity_slope, max(rsf_stability_prediction(v, model, M, eta)["K_c"], 0.0)]
        np.testing.assert_equal(got, want)  # NaN where no onset (u = 2.2: K_c = 0)
    # u = 2.2: the twin is velocity strengthening (its formula's K_c < 0), shown as 0
    assert rsf_stability_prediction(2.2, model, M, eta)["K_c"] < 0 < out.columns["K_c_rsf"][0]
    assert out.units == {"u": "a0/t0", "K_c": "F_el/a0", "omega_c": "rad/t0",
                         "forward_stiffness": "F_el/a0", "backward_stiffness": "F_el/a0",
                         "dmu_d_du": "F_el t0/a0", "K_c_rsf": "F_el/a0"}
    assert out.params["mass"] == M and out.params["damping"] == eta


def test_stability_rounding_and_a_strengthening_twin_are_zero_and_said() -> None:
    # the mistakes: a negative K_c_rsf printed as a stiffness (a velocity-strengthening twin,
    # b - a < 0, is stable at every stiffness: K_c = 0 as the model's column says), and the
    # athermal model's K_c = 1.5e-14 (rounding of an exact 0) printed as a value
    from dryfriction.analysis.rsf_stability import rsf_stability_prediction

    u = [0.037, 1.7, 23.0]
    out = app_theory.stability(0.083, u, direct=0.27, v_ref=0.61)
    model = TrapModel(0.13, 0.083, "log", direct=0.27, v_ref=0.61)
    raw = [rsf_stability_prediction(v, model)["K_c"] for v in u]
    assert all(k < -0.01 for k in raw)  # the formula's value: strengthening at every u
    assert out.columns["K_c_rsf"] == [0.0, 0.0, 0.0]
    (note,) = out.notes
    assert note.startswith("K_c_rsf = 0 where the rate-and-state twin is stable at every "
                           "stiffness, b - a - eta u <= 0: u = 0.037 a0/t0: b - a - eta u = -")
    assert note.count("(velocity strengthening)") == 3 and "damping" not in note
    assert out.as_dict()["notes"] == out.notes
    # the mistake a second user found: the damping, not the law, makes a weakening twin
    # (b - a > 0) stable, b - a - eta u <= 0; the note must not call it strengthening
    damped = app_theory.stability(0.043, [0.13, 1.1], mass=10.0, damping=0.1)
    twin = rsf_stability_prediction(1.1, TrapModel(0.13, 0.043, "log"), 10.0, 0.1)
    assert twin["b"] - twin["a"] > 0 > twin["b"] - twin["a"] - 0.1 * 1.1
    assert damped.columns["K_c_rsf"][1] == 0.0 < damped.columns["K_c_rsf"][0]
    (note,) = damped.notes
    assert note.endswith(f"u = 1.1 a0/t0: b - a - eta u = "
                         f"{twin['b'] - twin['a'] - 0.11:.4g} F_el (b - a = "
                         f"{twin['b'] - twin['a']:.4g} F_el: the damping stabilises it)")
    assert "strengthening" not in note
    # a weakening twin keeps its positive K_c and no note
    weak = app_theory.stability(0.083, [1.7])
    assert weak.columns["K_c_rsf"][0] > 0.01 and weak.notes == [] and "notes" not in \
        weak.as_dict()
    # eps = 0: K_c and the forward stiffness are rounding of 0 (below 1e-13 of the backward
    # stiffness), shown as 0 with omega_c NaN, and said
    zero = app_theory.stability(0.0, [0.041, 3.3])
    assert zero.columns["K_c"] == [0.0, 0.0]
    assert zero.columns["forward_stiffness"] == [0.0, 0.0]
    assert all(np.isnan(zero.columns["omega_c"]))
    assert zero.columns["backward_stiffness"][0] > 0.5
    assert "rounding" in zero.notes[0] and "u = 0.041, 3.3 a0/t0" in zero.notes[0]
    # a small true K_c (eps = 1e-9, 7.5e-10 at u = 1) is kept
    small = app_theory.stability(1e-9, [1.3])
    assert 1e-10 < small.columns["K_c"][0] < 1e-8 and small.notes == []


def test_stability_mass_and_damping_edges() -> None:
    # zero inertia and zero damping are accepted; below zero each is refused by name
    out = app_theory.stability(0.043, [2.2], mass=0.0, damping=0.0)
    assert out.params["mass"] == 0.0 and len(out.columns["K_c"]) == 1
    # inertia without damping is accepted with the direct effect (it damps like eta)
    assert app_theory.stability(0.043, [2.2], mass=0.6, direct=0.05).params["direct"] == 0.05
    for kw, name in (({"mass": -1e-9, "damping": 0.1}, "mass"),
                     ({"mass": 0.0, "damping": -1e-9}, "damping")):
        with pytest.raises(ValueError, match=f"^{name} = "):
            app_theory.stability(0.043, [0.3], **kw)
    # inertia without damping: ill posed, unless the direct effect damps
    with pytest.raises(ValueError, match="without --eta is ill posed"):
        app_theory.stability(0.043, [0.3], mass=0.5)


def test_trap_and_the_no_pinning_display() -> None:
    from dryfriction.theory.trap import Trap

    out = app_theory.trap(0.21)
    assert out.params == Trap(0.21).summary() and out.title == "trap, alpha = 0.21"
    assert out.columns == {} and app_theory.trap().params == Trap(0.13).summary()
    s = Trap(1.3).summary()
    shown = app_theory.no_pinning_display(s)
    nonfinite = [k for k, v in s.items() if isinstance(v, float) and not math.isfinite(v)]
    assert any(s[k] == math.inf for k in nonfinite) and any(math.isnan(s[k]) for k in nonfinite)
    for k, v in s.items():
        if k in nonfinite:
            assert shown[k] == "none (no pinning: alpha >= 1)", k
        else:
            assert shown[k] == v, k


# --- app.checks: every value option of fit on both sides of its edges -----------------------

_OK = dict(alpha=0.13, creep="log", v0=None, state_law="ageing", errors="white",
           traps_per_a0=None, direct=0.0, v_ref=1e-6)


@pytest.mark.parametrize("name, good, bad", [
    ("alpha", (1e-6, 1.0 - 1e-12), (1e-6 * (1 - 1e-9), 1.0)),
    ("direct", (0.0, 1.0), (-1e-12, 1.0 + 1e-9)),
    ("v_ref", (1e-30, 1e3), (0.99e-30, 1e3 * (1 + 1e-9))),
    ("v0", (1e-30, 1e3), (0.99e-30, 1e3 * (1 + 1e-9))),
])
def test_fit_options_both_sides_of_each_edge(name: str, good: tuple[float, ...],
                                            bad: tuple[float, ...]) -> None:
    flag = "--" + name.replace("_", "-")
    for value in good:
        check_fit_options(**{**_OK, name: value})
    for value in bad:
        with pytest.raises(ValueError, match=f"^{flag} = "):
            check_fit_options(**{**_OK, name: value})


def test_fit_options_choices_and_trap_density() -> None:
    from dryfriction.ensemble.population import TRAPS_PER_A0_MIN

    for name, flag in (("creep", "--creep"), ("state_law", "--state-law"),
                       ("errors", "--errors")):
        with pytest.raises(ValueError, match=f"^{flag} = 'x' is not allowed"):
            check_fit_options(**{**_OK, name: "x"})
    check_fit_options(**{**_OK, "state_law": "auto", "errors": "hac", "creep": "eyring-nabarro"})
    check_fit_options(**{**_OK, "traps_per_a0": TRAPS_PER_A0_MIN})
    with pytest.raises(ValueError, match="^--traps-per-a0 = "):
        check_fit_options(**{**_OK, "traps_per_a0": TRAPS_PER_A0_MIN * (1 - 1e-9)})
    with pytest.raises(ValueError, match="--traps-per-a0 1e\\+30 keeps at least 2.8e\\+31 pairs"):
        check_fit_options(**{**_OK, "traps_per_a0": 1e30})


# --- app.fitting.is_project_csv -------------------------------------------------------------


@pytest.mark.parametrize("text, ours", [
    ("# made by hand\n\nt_w[s],mu_s[1]\n1,0.6\n", True),
    ("V[um/s] , MU_D\n1,0.5\n", True),  # spaces, case, a unit
    ("t[s],v_load[m/s],mu[1],normal[MPa]\n0,1e-6,0.6,5\n", True),  # an extra column
    ("t_w[s],friction\n1,0.6\n", False),  # half of a kind
    ("time,LP_disp,shear,normal\n0,1,2,3\n", False),  # a laboratory record
    ("# only a comment\n\n", False),
])
def test_is_project_csv(tmp_path: Path, text: str, ours: bool) -> None:
    p = tmp_path / "data.csv"
    p.write_text(text)
    assert is_project_csv(p) is ours
    for name in ("data.xlsx", "DATA.MAT"):  # a spreadsheet is a record whatever it holds
        q = tmp_path / name
        q.write_text(text)
        assert is_project_csv(q) is False


# --- app.sweeps.protocol_text, app.records.cv_cost ------------------------------------------


def test_protocol_text_is_the_file_or_nothing(tmp_path: Path) -> None:
    p = tmp_path / "p.toml"
    p.write_text("[sweep]\nx = 1  # \u00b5\n", encoding="utf-8")
    assert protocol_text(str(p)) == "[sweep]\nx = 1  # \u00b5\n"
    assert protocol_text(str(tmp_path / "none.toml")) == ""
    p.write_bytes(b"\xff\xfe bad")
    assert protocol_text(str(p)) == ""


def test_cv_cost_scales_one_run_by_the_windows_durations(monkeypatch: pytest.MonkeyPatch) -> None:
    """One timed forward run of the first window, times the summed durations over the first's
    (windows that do not start at t = 0), times CV_CALLS_PER_STEP; inf when that run is
    refused. The trap model and the clock are replaced: the arithmetic is what is checked."""
    calls: list[Any] = []

    class Fake:
        def guesses(self, pieces: list[Any]) -> list[dict[str, float]]:
            return [{"p": 1.0} for _ in pieces]

        def predict(self, guess: dict[str, float], piece: Any) -> None:
            calls.append(piece)
            if piece.t[0] < 0:
                raise ValueError("too long")

    made: list[tuple[Any, ...]] = []
    monkeypatch.setattr(cvsteps, "record_cv_model",
                        lambda *a, **k: made.append(a) or Fake())
    clock = iter([10.0, 10.75])
    monkeypatch.setattr(app_records.time, "process_time", lambda: next(clock))
    p1 = SimpleNamespace(t=np.array([100.0, 104.0]))  # 4 s
    p2 = SimpleNamespace(t=np.array([300.0, 310.0]))  # 10 s
    cost = app_records.cv_cost([p1, p2], 0.21, "eyring-nabarro", 0.03, 2e-6)
    assert cost == pytest.approx(0.75 * (14.0 / 4.0) * app_records.CV_CALLS_PER_STEP, rel=1e-12)
    assert calls == [p1] and app_records.CV_CALLS_PER_STEP == 91
    trap, v_ref, tpa = made[0]
    assert (trap.alpha, trap.creep, trap.direct, v_ref) == (0.21, "eyring-nabarro", 0.03, 2e-6)
    assert tpa == cvsteps.RECORD_TRAPS_PER_A0  # the default track density
    clock = iter([0.0, 1.0])
    app_records.cv_cost([p1], 0.21, "log", traps_per_a0=37.0)
    assert made[-1][2] == 37.0
    clock = iter([0.0])  # the refused run: read once, before it
    assert app_records.cv_cost([SimpleNamespace(t=np.array([-1.0, 1.0]))], 0.2, "log") == math.inf


def test_direct_effect_options_without_the_direct_effect_are_refused() -> None:
    # the mistake (a second new user): --u-ref and --pull-velocity taken and ignored without
    # --direct; each is now refused by its own name, before any work
    for run in (lambda: app_theory.steady(0.043, u=[0.37], v_ref=2.3),
                lambda: app_theory.stability(0.043, [0.37], v_ref=2.3),
                lambda: app_theory.static(0.043, T=[3.7], v_ref=2.3)):
        with pytest.raises(ValueError, match=r"^--u-ref 2\.3 applies only with --direct > 0"):
            run()
    with pytest.raises(ValueError, match=r"^--pull-velocity 0\.37 applies only with --direct"):
        app_theory.static(0.043, T=[3.7], pull_velocity=0.37)
    # with the direct effect both are taken
    out = app_theory.static(0.043, T=[3.7], direct=0.02, v_ref=2.3, pull_velocity=0.37)
    assert out.params["v_ref"] == 2.3 and out.params["pull_velocity"] == 0.37
