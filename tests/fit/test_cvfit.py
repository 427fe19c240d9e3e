"""The trap model on an elastic machine with a trend, fitted to a record's step (issue 11):
:func:`dryfriction.fit.cvseries.cv_series` with ``stiffness``/``trend``, the start from a
rate-and-state fit, and :func:`dryfriction.fit.cvsteps.fit_cv_steps`'s model."""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np
import pytest

from dryfriction.fit import fit
from dryfriction.fit.cvseries import cv_start_from_rsf
from dryfriction.fit.models import CVModel, cv_series
from dryfriction.records.data import SeriesData, StaticData, SteadyData
from dryfriction.theory.direct import junction_strength
from dryfriction.theory.linear_stability import effective_rsf
from dryfriction.theory.model import TrapModel
from dryfriction.theory.static import static_friction
from dryfriction.theory.steady import steady_friction

A0, T0, MU_EL = 1e-6, 1.0, 0.5  # a0 (m), t0 (s): V* = 1 um/s
V1, V2 = 0.3e-6, 3e-6
SLIP1, SLIP2 = 4.0, 4.0  # a0 before and after the step


def _step(n: int = 400, mu: np.ndarray | None = None) -> SeriesData:
    t1, t2 = SLIP1 * A0 / V1, SLIP2 * A0 / V2
    t = np.linspace(0.0, t1 + t2, n, endpoint=False)
    v = np.where(t < t1, V1, V2)
    return SeriesData(t, v, np.zeros(n) if mu is None else mu, source="step")


def _values(direct: float = 0.0) -> dict[str, float]:
    v = {"eps": 0.02, "t0": T0, "a0": A0, "mu_el": MU_EL}
    if direct:
        v.update(direct=direct)
    return v


def _series(values: dict[str, float], d: SeriesData, traps_per_a0: float,
            stiffness: float = math.inf) -> np.ndarray:
    """fit.cv_series of the family that fits the direct effect where ``values`` has one
    (v_ref 1e-6 m/s), sampled every 0.01 a0."""
    trap = TrapModel(direct=0.02 if "direct" in values else 0.0)
    return cv_series(CVModel(trap, traps_per_a0=traps_per_a0, sample_slip=0.01, v_ref=1e-6,
                             stiffness=stiffness), values, d)


@pytest.mark.slow
@pytest.mark.parametrize("direct, k_soft, tol, soft_min", [(0.0, 0.1, 2.5e-4, 7e-4),
                                                           (0.02, 0.3, 2e-5, 4e-4)])
def test_stiff_spring_reproduces_the_kinematic_series(direct: float, k_soft: float, tol: float,
                                                      soft_min: float) -> None:
    # k -> inf: the quasi-static slider on the spring follows the load point, so its friction
    # is the velocity drive's; a soft spring (below the contacts' own stiffness, about
    # 0.7 F_el/a0) must not be (else the spring would be ignored). Without the direct effect
    # the spring slider moves by jumps from trap death to trap death, which the kinematic
    # slider does not: the two agree to a fraction of one trap's force (1/200 of it) in rms
    d = _step()
    v = _values(direct)
    kin = _series(v, d, 200)
    stiff = _series(v, d, 200, stiffness=1e4 * MU_EL / A0)
    soft = _series(v, d, 200, stiffness=k_soft * MU_EL / A0)

    def rms(x: np.ndarray) -> float:
        return float(np.sqrt(np.mean(x**2)))

    assert rms(stiff - kin) < tol
    assert rms(soft - kin) > soft_min


def test_trend_adds_the_load_point_displacement() -> None:
    d = _step()
    v = _values(0.02)
    base = _series(v, d, 100, stiffness=MU_EL / A0)
    with_trend = _series({**v, "trend": -50.0}, d, 100, stiffness=MU_EL / A0)
    # x_lp by hand: the program integrated, V2 from the first sample that shows it
    t1 = float(d.t[np.argmax(d.v_load == V2)])
    x_lp = np.where(d.t < t1, V1 * d.t, V1 * t1 + V2 * (d.t - t1))
    np.testing.assert_allclose(with_trend - base, -50.0 * x_lp, atol=1e-12)
    # the cached run is only reused for the trend: another eps is another series
    other = _series({**v, "eps": 0.03, "trend": -50.0}, d, 100, stiffness=MU_EL / A0)
    assert np.max(np.abs(other - with_trend)) > 1e-3


def test_start_from_rsf_inverts_the_twin() -> None:
    # a trap model's own twin (a, b, Dc, mu0 at v0, u = v0 t0/a0 = 1) maps back to it
    eps, a0, mu_el, A, v_ref = 0.015, 50e-6, 0.6, 0.03, 1e-6
    v0 = 2e-7
    t0 = a0 / v0
    u_ref = v_ref * t0 / a0
    tw = effective_rsf(1.0, TrapModel(eps=eps, direct=A, v_ref=u_ref))
    g = float(junction_strength(1.0, A, u_ref))
    rsf = {"a": mu_el * tw["a"], "b": mu_el * tw["b"], "dc": tw["dc"] * a0,
           "mu0": mu_el * g * float(steady_friction(TrapModel(eps=eps), 1.0)), "stiffness": 2000.0,
           "trend": -3.0}
    s = cv_start_from_rsf(CVModel(TrapModel(direct=0.01), v_ref=v_ref), rsf, v0)
    assert s["eps"] == pytest.approx(eps, rel=0.02)
    assert s["a0"] == pytest.approx(a0, rel=0.02)
    assert s["t0"] == pytest.approx(t0, rel=0.02)
    assert s["mu_el"] == pytest.approx(mu_el, rel=0.01)
    assert s["direct"] == pytest.approx(A, rel=0.05)
    assert (s["stiffness"], s["trend"]) == (2000.0, -3.0)
    athermal = cv_start_from_rsf(CVModel(), rsf, v0)
    assert "direct" not in athermal


def test_cv_model_machine_options_checked() -> None:
    with pytest.raises(ValueError, match="stiffness"):
        CVModel(stiffness="slope")
    with pytest.raises(ValueError, match="stiffness"):
        CVModel(stiffness=-1.0)
    with pytest.raises(ValueError, match="trend"):
        CVModel(trend="yes")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="sample_slip"):
        CVModel(sample_slip=0.0)
    m = CVModel(stiffness="fit", trend=True)
    names = [p.name for p in m.parameters(frozenset({"series"}))]
    assert names[-2:] == ["stiffness", "trend"]
    assert "stiffness" not in [p.name for p in CVModel().parameters(frozenset({"series"}))]


@functools.cache
def _synthetic_step() -> tuple[SeriesData, dict[str, float]]:
    # a step made by the trap model itself on a spring with a trend, on a denser track than
    # the fit's (so the fit does not see its own granularity), noise 5e-4
    truth = {**_values(0.02), "stiffness": 0.5 * MU_EL / A0, "trend": -200.0}
    d0 = _step(300)
    clean = _series(truth, d0, 200, stiffness=truth["stiffness"])
    rng = np.random.default_rng(3)
    return SeriesData(d0.t, d0.v_load, clean + rng.normal(0.0, 5e-4, len(d0)),
                      source="synth"), truth


@functools.cache
def _fit_back(free: tuple[str, ...], max_nfev: int, traps: float
              ) -> tuple[dict[str, Any], dict[str, float], float, Any]:
    d, truth = _synthetic_step()
    model = CVModel(TrapModel(direct=0.02), traps_per_a0=traps, v_ref=1e-6, stiffness="fit",
                    trend=True, sample_slip=0.01, max_nfev=max_nfev)
    near = {"eps": 0.022, "t0": 1.2, "a0": 0.9e-6, "mu_el": 0.5, "direct": 0.017,
            "stiffness": 1.1 * truth["stiffness"], "trend": 0.0}
    fix = {k: truth[k] for k in near if k not in free}
    r = fit(d, model, start={k: near[k] for k in free}, fix=fix, multistart=False,
            profile=False, consistency=False)
    assert r.success
    return ({p.name: p for p in r.parameters}, truth,
            math.sqrt(2 * r.goodness["cost"] / r.goodness["n"]), r)


@pytest.mark.slow
def test_direct_effect_recovered_on_a_spring_with_a_trend() -> None:
    # the machine and A free, the trap parameters held at the truth (the CI version, about
    # 60 runs, 15-20 s CPU on a loaded machine; a shorter step (2.5 + 3 a0) was cheaper but
    # its 50-trap granularity biased A outside its interval; the slow test frees all seven):
    # A within its 95 % interval, which excludes A = 0
    est, truth, rms, _ = _fit_back(("direct", "stiffness", "trend"), 20, 50)
    lo, hi = est["direct"].interval_95
    assert lo <= truth["direct"] <= hi
    assert lo > 0.0
    # the coarse track (50 traps per a0, for speed) biases k: measured +46 %, +14 % at 100
    assert est["stiffness"].value == pytest.approx(truth["stiffness"], rel=0.6)
    assert rms < 7e-4  # the noise, 5e-4, plus the fit's granularity


@pytest.mark.slow
def test_robust_errors_of_a_cv_fit() -> None:
    """The record's cv fits get the autocorrelation-robust errors too (fit.steps
    .step_covariance on a CVModel fit): the parameters held fixed stay out, and with white
    noise the robust standard errors agree with the engine's white ones (measured within
    20 %), so a robust estimate that inflated white noise, or mixed fixed parameters in, fails."""
    from dryfriction.fit.steps import robust_estimates, step_covariance

    free = ("direct", "stiffness", "trend")
    est, truth, _, r = _fit_back(free, 20, 50)
    d, _ = _synthetic_step()
    sc = step_covariance(r, d)
    assert [s.name for s in sc.specs] == list(free)
    rob = robust_estimates(sc)
    for n in free:
        assert rob[n]["stderr"] == pytest.approx(est[n].stderr, rel=0.35), n
        assert rob[n]["value"] == pytest.approx(est[n].value, rel=1e-12)
    assert rob["direct"]["lo"] <= truth["direct"] <= rob["direct"]["hi"]


@pytest.mark.slow
def test_direct_effect_recovered_with_all_parameters_free() -> None:
    # measured: about 110 s CPU; A = 0.0198 +- 0.0002 (truth 0.02), rms 5.2e-4
    est, truth, rms, _ = _fit_back(("eps", "t0", "a0", "mu_el", "direct", "stiffness", "trend"),
                                60, 100)
    lo, hi = est["direct"].interval_95
    assert lo <= truth["direct"] <= hi
    assert lo > 0.0
    assert est["a0"].value == pytest.approx(truth["a0"], rel=0.1)
    assert rms < 6e-4


def test_the_fits_predictions_are_the_model_first_si_forms() -> None:
    # mistake caught: CVModel handing its v_ref (m/s) to the model unconverted (the model's
    # v_ref is reduced, a0/t0); the slow direct-effect fit test is the only other route
    m = CVModel(TrapModel(alpha=0.11, creep="eyring-nabarro", direct=0.02), v_ref=1e-6)
    V = np.array([3e-8, 2e-6, 5e-5])  # m/s, u = V/V* = 0.0075, 0.5, 12.5
    v = {"eps": 0.03, "vstar": 4e-6, "mu_el": 0.45, "direct": 0.025}
    got = m.predict(v, SteadyData(V, np.ones(3)))
    want = 0.45 * steady_friction(TrapModel(0.11, 0.03, "eyring-nabarro", direct=0.025,
                                            v_ref=0.25), V / 4e-6)
    np.testing.assert_allclose(got, want, rtol=1e-14)
    # the direct effect is the junction strength g(V/V_ref), a ratio of m/s (theory/direct.py)
    athermal = 0.45 * steady_friction(TrapModel(0.11, 0.03, "eyring-nabarro"), V / 4e-6)
    np.testing.assert_allclose(got / athermal, junction_strength(V / 1e-6, 0.025, 1.0),
                               rtol=1e-13)
    tw = np.array([0.5, 30.0])
    got = CVModel(TrapModel(alpha=0.11)).predict({"eps": 0.03, "t0": 0.2, "mu_el": 0.45},
                                      StaticData(tw, np.ones(2)))
    np.testing.assert_allclose(got, 0.45 * static_friction(TrapModel(0.11, 0.03), tw / 0.2),
                               rtol=1e-14)


@pytest.mark.parametrize("field, bad", [("alpha", 1.0), ("alpha", -0.2), ("creep", "power"),
                                        ("direct", 1.7), ("direct", -0.01)])
def test_fit_model_takes_the_trap_models_declared_defaults_and_ranges(field, bad) -> None:
    """CVModel's trap fields (alpha, creep, direct) are its held TrapModel's: the same
    defaults, and the old loose form refuses a bad one with TrapModel's own message."""
    from dryfriction.theory.model import OldTheoryFormWarning

    for name in ("alpha", "creep", "direct"):
        assert getattr(CVModel(), name) == getattr(TrapModel(), name)
    assert CVModel().trap == TrapModel()
    with pytest.raises(ValueError) as want:
        TrapModel(**{field: bad})
    with pytest.raises(ValueError) as got, pytest.warns(OldTheoryFormWarning):
        CVModel(**{field: bad})
    assert str(got.value) == str(want.value)


def test_old_loose_form_warns_and_builds_the_same_model() -> None:
    # mistakes caught: the old form dropping its direct (an athermal fit), or swapping alpha
    # and creep's places
    from dryfriction.theory.model import OldTheoryFormWarning

    new = CVModel(TrapModel(0.11, creep="eyring-nabarro", direct=0.02), traps_per_a0=300,
                  v_ref=2e-6, stiffness="fit")
    with pytest.warns(OldTheoryFormWarning, match=r"CVModel\(TrapModel"):
        by_keyword = CVModel(alpha=0.11, creep="eyring-nabarro", direct=0.02, traps_per_a0=300,
                             v_ref=2e-6, stiffness="fit")
    with pytest.warns(OldTheoryFormWarning):
        by_position = CVModel(0.11, "eyring-nabarro", None, 300, 0.03, 0.02, 2e-6, "fit")
    assert by_keyword == new and by_position == new
    assert (new.alpha, new.creep, new.direct) == (0.11, "eyring-nabarro", 0.02)
    with pytest.raises(TypeError, match="multiple values"):
        CVModel(0.11, alpha=0.12)
    with pytest.raises(TypeError, match="TrapModel"):
        CVModel(TrapModel(), 0.13)
    with pytest.raises(TypeError, match="direct is the trap model's"):
        CVModel(TrapModel(), direct=0.02)


@pytest.mark.parametrize("held, word", [(TrapModel(eps=0.03), "trap.eps"),
                                        (TrapModel(mu_el=0.5), "trap.mu_el"),
                                        (TrapModel(v_ref=2.0), "trap.v_ref")])
def test_held_trap_model_leaves_the_fitted_fields_alone(held: TrapModel, word: str) -> None:
    # a held eps, mu_el or reduced v_ref would be silently replaced by the fit's: refused
    with pytest.raises(ValueError, match=word):
        CVModel(held)


def test_the_member_at_fitted_values_is_the_held_trap_model_with_them() -> None:
    # mistakes caught: v_ref handed on in m/s; the member keeping the held direct (the
    # family's start) where the values say 0 (the steady start scan took g(u) in: seen on the
    # fit below, its values moved at 1e-9); the held alpha or creep ignored
    cv = CVModel(TrapModel(0.11, creep="eyring-nabarro", direct=0.02), v_ref=2.3e-6)
    got = cv.trap_model({"eps": 0.027, "a0": 1.3e-6, "t0": 0.37, "mu_el": 0.46},
                        direct=0.025)
    assert got == TrapModel(0.11, 0.027, "eyring-nabarro", 0.46, 0.025, 2.3e-6 * 0.37 / 1.3e-6)
    assert cv.trap_model(eps=0.027, direct=0.025, vstar=4e-6).v_ref == pytest.approx(
        2.3e-6 / 4e-6, rel=1e-15)
    assert cv.trap_model(eps=1.0, direct=0.0) == TrapModel(0.11, 1.0, "eyring-nabarro")
    with pytest.raises(ValueError, match="direct is not given"):
        cv.trap_model(eps=0.027, a0=1.3e-6, t0=0.37)
    with pytest.raises(ValueError, match="velocity scale"):
        cv.trap_model(eps=0.027, direct=0.01, t0=0.37)
    assert CVModel(TrapModel(0.11)).trap_model(eps=0.03) == TrapModel(0.11, 0.03)


def _steady_direct_data() -> SteadyData:
    from dryfriction.theory.units import PhysicalScales, steady_friction_si

    sc = PhysicalScales(1.3e-6, 0.37, 0.46)
    true = TrapModel(0.11, 0.027, "eyring-nabarro", direct=0.021,
                     v_ref=float(sc.reduced_velocity(2.3e-6)))
    V = np.geomspace(3e-8, 2e-4, 15)
    rng = np.random.default_rng(7)
    rng.normal(0.0, 2e-4, 14), rng.normal(0.0, 2e-4, 15)  # the draws of the fit's static data
    return SteadyData(V, steady_friction_si(true, V, sc) + rng.normal(0, 2e-4, V.size),
                      source="sdd")


def test_a_steady_fit_with_the_direct_effect_is_the_one_before_the_model_object() -> None:
    """A generic fit (alpha 0.11, Eyring-Nabarro, A and v_ref fitted and fixed) gives the
    values the fit gave before CVModel held a TrapModel (measured then, to the last digit):
    the old and the new form alike, the two to 1e-12 of each other, and both to 1e-6 of those
    values (the optimiser's own tolerance: on another machine, or NumPy 2.4 / SciPy 1.17, the
    same fit ends 1e-7 to 1e-8 away; a wrong mapping of the old form moves them by per cent)."""
    from dryfriction.theory.model import OldTheoryFormWarning

    before = {"eps": 0.02688950047407185, "vstar": 3.4998134936394638e-06,
              "mu_el": 0.46014832423812485, "direct": 0.020880726464677486}
    d = _steady_direct_data()
    new = fit(d, CVModel(TrapModel(0.11, creep="eyring-nabarro", direct=0.015), v_ref=2.3e-6),
              profile=False)
    with pytest.warns(OldTheoryFormWarning):
        old_model = CVModel(0.11, "eyring-nabarro", direct=0.015, v_ref=2.3e-6)
    old = fit(d, old_model, profile=False)
    got_new, got_old = ({p.name: p.value for p in r.parameters} for r in (new, old))
    assert got_old == pytest.approx(got_new, rel=1e-12, abs=0.0)
    assert got_new == pytest.approx(before, rel=1e-6, abs=0.0)


def test_old_forms_of_the_series_the_start_and_the_record_model_compute_the_same(
        monkeypatch: pytest.MonkeyPatch) -> None:
    # mistakes caught: an old form passing v_ref (m/s) on as the reduced one, dropping its
    # direct, or swapping alpha and creep (each shim maps its loose arguments onto CVModel)
    from dryfriction.fit import cvseries, cvsteps
    from dryfriction.theory.model import OldTheoryFormWarning

    d = _step(120)
    k = 0.4 * MU_EL / A0
    v = {**_values(0.015), "eps": 0.023, "trend": -20.0}
    cv = CVModel(TrapModel(0.12, creep="eyring-nabarro", direct=0.015), v_ref=1.7e-6,
                 traps_per_a0=60, sample_slip=0.01, stiffness=k)
    new = cv_series(cv, v, d)
    with pytest.raises(ValueError, match="v_ref is not a fitted value"):
        cv_series(cv, {**v, "v_ref": 1.7e-6}, d)
    with pytest.warns(OldTheoryFormWarning):
        old = cvseries.cv_series({**v, "v_ref": 1.7e-6}, d, 0.12, "eyring-nabarro", 60,
                                 sample_slip=0.01, stiffness=k)
    np.testing.assert_array_equal(old, new)
    with pytest.raises(TypeError, match=r"fit.cv_series\(model, values, data\)"):
        cvseries.cv_series(cv, v, d)  # type: ignore[arg-type]
    rsf = {"mu0": 0.61, "a": 0.011, "b": 0.014, "dc": 2.2e-6}
    with pytest.warns(OldTheoryFormWarning):
        old_start = cv_start_from_rsf(rsf, 1.7e-6, 0.12, "eyring-nabarro", 0.02, 1.3e-6, 0.7)
    assert old_start == cv_start_from_rsf(
        CVModel(TrapModel(0.12, creep="eyring-nabarro", direct=0.02), v_ref=1.3e-6), rsf,
        1.7e-6, 0.7)
    held = TrapModel(0.12, creep="eyring-nabarro", direct=0.02)
    with pytest.warns(OldTheoryFormWarning):
        old_record = cvsteps.record_cv_model(0.12, "eyring-nabarro", 0.02, 1.3e-6, 40.0)
    assert old_record == cvsteps.record_cv_model(held, 1.3e-6, 40.0)
    seen: list[CVModel] = []
    monkeypatch.setattr(cvsteps, "_fit_cv_steps", lambda data, fits, model: seen.append(model))
    with pytest.warns(OldTheoryFormWarning):
        cvsteps.fit_cv_steps([d], [None], 0.12, "eyring-nabarro", 0.02, 1.3e-6, 40.0)
    assert seen == [old_record]


_OLD_KEYWORDS = {"alpha", "creep", "direct", "traps_per_a0", "stiffness", "sample_slip",
                 "steady_tail", "every_slip", "max_samples", "progress"}


def _old_fit_form_calls(tree: Any) -> list[int]:
    """Lines where a fit function that takes the fit model is called in its old loose form:
    ``CVModel`` with a trap field loose; ``cv_series``, ``cv_start_from_rsf`` with a mapping
    first or loose keywords; ``record_cv_model`` with a number first; ``fit_cv_steps`` with
    more than the model."""
    import ast

    def trap_like(a: ast.expr) -> bool:
        return not isinstance(a, (ast.Constant, ast.Dict, ast.UnaryOp)) and not (
            isinstance(a, ast.Name) and a.id in ("alpha", "values", "v", "rsf", "truth"))

    bad = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        f = node.func
        name = f.id if isinstance(f, ast.Name) else getattr(f, "attr", None)
        kws = {k.arg for k in node.keywords}
        first = node.args[0] if node.args else None
        if name == "CVModel":
            old = bool(kws & {"alpha", "creep", "direct"}) or len(node.args) > 1 or (
                first is not None and not trap_like(first))
        elif name in ("cv_series", "cv_start_from_rsf", "record_cv_model"):
            old = first is not None and not trap_like(first) or bool(
                kws & _OLD_KEYWORDS - ({"progress"} if name == "record_cv_model" else set()))
        elif name == "fit_cv_steps":
            old = len(node.args) > 3 or bool(kws)
        else:
            continue
        if old:
            bad.append(node.lineno)
    return bad


def test_no_module_calls_an_old_form_of_the_fit_model() -> None:
    # the scan on both forms first (it could pass for not looking), then the package, the
    # examples and the benchmarks (the suite's error on the warning covers only the paths
    # it runs)
    import ast
    from pathlib import Path

    old = ast.parse("CVModel(0.13, 'log')\nCVModel(direct=0.02)\ncv_series(v, d, 0.13)\n"
                    "cv_start_from_rsf(rsf, v0)\nrecord_cv_model(0.13, 'log', 0.03)\n"
                    "fit_cv_steps(data, fits, 0.13, 'log')\n"
                    "cv_series(model, v, d, traps_per_a0=30)\n")
    new = ast.parse("CVModel(TrapModel(0.13), v_ref=1e-6)\ncv_series(cv, v, d)\n"
                    "cv_start_from_rsf(model, rsf, v0)\n"
                    "record_cv_model(TrapModel(direct=0.03), v_ref, tpa, progress=tick)\n"
                    "fit_cv_steps(data, fits, model)\nCVModel()\n")
    assert _old_fit_form_calls(old) == [1, 2, 3, 4, 5, 6, 7]
    assert _old_fit_form_calls(new) == []
    root = Path(__file__).resolve().parents[2]
    sources = [*sorted((root / "src").rglob("*.py")), *sorted((root / "examples").rglob("*.py")),
               *sorted((root / "benchmarks").glob("*.py"))]
    assert len(sources) > 50
    bad = [f"{p.relative_to(root)}:{ln}" for p in sources
           for ln in _old_fit_form_calls(ast.parse(p.read_text()))]
    assert bad == [], bad
