"""The theory functions take a TrapModel first (issue 26, item 1); their old loose forms work
for one release with an OldTheoryFormWarning, and no module of the package uses one."""

from __future__ import annotations

import ast
import warnings
from pathlib import Path

import numpy as np
import pytest

from dryfriction.analysis import rsf_view
from dryfriction.theory import dieterich, static, steady, units
from dryfriction.theory.model import OldTheoryFormWarning, TrapModel
from dryfriction.theory.units import PhysicalScales

SRC = Path(__file__).resolve().parents[2] / "src" / "dryfriction"

# a generic model: no parameter at its default, the direct effect on, v_ref away from 1
M = TrapModel(alpha=0.1, eps=0.04, creep="eyring-nabarro", direct=0.03, v_ref=0.5)
LOG = M.replace(creep="log")
U = np.array([0.07, 0.8, 13.0])
T = np.array([0.3, 7.0, 200.0])
SCALES = PhysicalScales(a0=2e-6, t0=0.5)

# (function, old call's arguments, new call's arguments, old call's keywords, new's keywords)
CASES = [
    (steady.steady_friction, (U, 0.04, 0.1, "eyring-nabarro", 0.03, 0.5), (M, U), {}, {}),
    (steady.steady_friction, (U, 0.04), (TrapModel(eps=0.04), U), {"creep": "log"}, {}),
    (steady.steady_friction_low_velocity, (U, 0.04, 0.1, 0.03, 0.5), (LOG, U), {}, {}),
    (steady.steady_friction_first_order, (U, 0.04, 0.1), (LOG.athermal, U), {}, {}),
    (static.static_friction, (T, 0.04, 0.1, "eyring-nabarro", 0.3, 0.03, 0.5, 2.0, "force"),
     (M, T), {}, {"load": 0.3, "pull_velocity": 2.0, "hold": "force"}),
    (static.static_friction, (T, 0.04), (LOG.athermal, T), {"alpha": 0.1, "load": -0.2},
     {"load": -0.2}),
    (static.static_friction_first_order, (T, 0.04, 0.1), (LOG.athermal, T), {}, {}),
    (static.static_friction_at_radius, (np.array([1.0, 1.2, 3.0]), 0.1, 0.05),
     (M.athermal, np.array([1.0, 1.2, 3.0]), 0.05), {}, {}),
    (units.steady_friction_si, (U * 4e-6, 0.04, SCALES, 0.1, "eyring-nabarro", 0.03, 2e-6),
     (M, U * 4e-6, SCALES), {}, {}),
    (units.static_friction_si, (T * 0.5, 0.04, SCALES, 0.1, "eyring-nabarro", 0.3, 0.03, 2e-6,
                                8e-6), (M, T * 0.5, SCALES), {}, {"load": 0.3,
                                                                   "pull_velocity": 8e-6}),
    (dieterich.dieterich_constant_asymptotic, (0.1,), (M.athermal,), {}, {}),
    (steady.steady_log_slope, (U, 0.04, 0.1, "eyring-nabarro", 0.03, 0.5), (M, U), {}, {}),
    (steady.steady_log_slope, (U, 0.04), (TrapModel(eps=0.04), U), {"creep": "log"}, {}),
    (steady.steady_log_slope_low_velocity, (U, 0.04, 0.1, 0.03, 0.5), (LOG, U), {}, {}),
    (steady.steady_death_point, (U, 0.04, 0.1, "eyring-nabarro"), (M, U), {}, {}),
    (steady.steady_death_point, (U, 0.04), (LOG.replace(alpha=0.4), U), {"alpha": 0.4}, {}),
    (steady.steady_profile, (np.linspace(-1.2, 1.5, 7), 0.8, 0.04, 0.1, "eyring-nabarro"),
     (M, np.linspace(-1.2, 1.5, 7), 0.8), {}, {}),
    (steady.min_velocity, (0.04, 0.1, "eyring-nabarro"), (M,), {}, {}),
    (steady.min_velocity, (0.3,), (TrapModel(eps=0.3, creep="eyring-nabarro"),), {}, {}),
    (steady.low_velocity_constant, (0.1,), (M,), {}, {}),
    (static.force_hold_shift, (30.0, 0.04, 0.1, "eyring-nabarro", 0.3), (M, 30.0), {},
     {"load": 0.3}),
    (static.force_hold_shift, (30.0, 0.04), (LOG.replace(alpha=0.4), 30.0),
     {"alpha": 0.4, "load": -0.2}, {"load": -0.2}),
    (static.fresh_force, (np.array([0.0, 0.05, 0.2]), 0.1), (M, np.array([0.0, 0.05, 0.2])),
     {}, {}),
    (static.loaded_edge, (0.3, 0.1), (M, 0.3), {}, {}),
    (static.loaded_edge, (-0.3,), (LOG.replace(alpha=0.13), -0.3), {}, {}),
    (static.pull_force, (np.array([0.05, 0.3, 1.4]), 1.2, 0.1, 0.04),
     (M, np.array([0.05, 0.3, 1.4]), 1.2, 0.04), {}, {}),
    (static.pull_force, (0.3, np.array([1.0, 1.3])), (LOG.replace(alpha=0.4), 0.3,
                                                     np.array([1.0, 1.3])), {"alpha": 0.4}, {}),
    (static.threshold_shift, (np.array([1.0, 1.3]), 0.1, 0.04), (M, np.array([1.0, 1.3]), 0.04),
     {}, {}),
    (static.threshold_shift, (1.3,), (LOG.replace(alpha=0.13), 1.3), {"d_w": 0.1},
     {"d_w": 0.1}),
    (static.static_slope_per_eps, (0.1,), (M,), {}, {}),
    (static.static_slope_per_eps, (), (TrapModel(eps=0.3),), {"alpha": 0.13}, {}),
    (dieterich.forward_moment, (1, 0.1), (M, 1), {}, {}),
    (dieterich.forward_moment, (0, 0.6), (LOG.replace(alpha=0.6), 0), {}, {}),
    (dieterich.dieterich_constant_least_squares, (0.04, 0.1, 0.05, 20.0, 9, "eyring-nabarro"),
     (M.athermal, 0.05, 20.0, 9), {}, {}),
    (dieterich.dieterich_constant_local, (U, 0.04, 0.1), (LOG.athermal, U), {}, {}),
]


@pytest.mark.slow
@pytest.mark.parametrize(("fn", "old", "new", "old_kw", "new_kw"), CASES,
                         ids=[f"{c[0].__name__}-{i}" for i, c in enumerate(CASES)])
def test_the_old_form_warns_and_gives_the_new_forms_numbers(fn, old, new, old_kw, new_kw):
    # mistakes caught: an old form that maps its arguments onto the model wrongly (eps and
    # alpha swapped, direct or v_ref dropped, v_ref left in m/s in SI), or no longer warns
    with pytest.warns(OldTheoryFormWarning, match=rf"^{fn.__name__}\(.* is the old form .*"
                                                  rf"use {fn.__name__}\(model"):
        got = fn(*old, **old_kw)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the new form warns of nothing
        want = fn(*new, **new_kw)
    np.testing.assert_allclose(got, want, rtol=1e-13, atol=0)
    assert np.all(np.isfinite(want))


def test_the_new_forms_use_the_whole_model():
    # mistake caught: a new form that drops a field of the model (each changes the result)
    every = ("alpha", "eps", "creep", "direct", "v_ref")
    for fn, x, kw, fields in (
            (steady.steady_friction, U, {}, every),
            (static.static_friction, T, {"pull_velocity": 2.0}, every),
            (steady.steady_friction_low_velocity, U, {}, every[:2] + every[3:]),
            (steady.steady_friction_first_order, U, {}, every[:2] + every[3:]),
            (steady.steady_log_slope, U, {}, every),
            (steady.steady_log_slope_low_velocity, U, {}, every[:2] + every[3:]),
            (steady.steady_death_point, U, {}, every[:3]),
            (steady.steady_profile, np.linspace(-0.9, 0.5, 5), {"u": 0.8}, every[:3]),
            (static.static_friction_first_order, T, {"pull_velocity": 2.0},
             every[:2] + every[3:]),
            (units.steady_friction_si, U * 4e-6, {"scales": SCALES}, every),
            (units.static_friction_si, T * 0.5, {"scales": SCALES, "pull_velocity": 8e-6},
             every)):
        base = fn(M, x, **kw)
        for field in fields:
            other = {"alpha": 0.3, "eps": 0.05, "creep": "log", "direct": 0.05, "v_ref": 3.0}
            assert not np.allclose(fn(M.replace(**{field: other[field]}), x, **kw), base,
                                   rtol=1e-9), (fn.__name__, field)


@pytest.mark.slow
def test_the_new_scalar_forms_use_their_fields():
    # mistake caught: min_velocity, force_hold_shift, low_velocity_constant, fresh_force,
    # loaded_edge, pull_force, threshold_shift, static_slope_per_eps or forward_moment reading
    # a field of the model wrongly
    # (eps and alpha swapped, creep or alpha dropped); each field below changes the result
    base = steady.min_velocity(M)
    assert base > 0
    for field, value in (("alpha", 0.3), ("eps", 0.05), ("creep", "log")):
        assert steady.min_velocity(M.replace(**{field: value})) != base, field
    shift = static.force_hold_shift(M, 30.0, load=0.3)
    assert shift < 0
    for field, value in (("alpha", 0.3), ("eps", 0.05), ("creep", "log")):
        assert static.force_hold_shift(M.replace(**{field: value}), 30.0, load=0.3) != shift
    for fn, x in ((static.fresh_force, 0.05), (static.loaded_edge, 0.3),
                  (lambda m, d: static.pull_force(m, d, 1.2), 0.3),
                  (lambda m, r: static.threshold_shift(m, r), 1.2),
                  (lambda m, k: static.static_slope_per_eps(m) * k, 1),
                  (dieterich.forward_moment, 1)):
        assert fn(M.replace(alpha=0.3), x) != fn(M, x)
    k1 = steady.low_velocity_constant(M)
    assert steady.low_velocity_constant(M.replace(alpha=0.3)) != k1
    assert steady.low_velocity_constant(M.replace(eps=0.3, creep="log", direct=0.0)) == k1


def test_sweeps_over_eps_equal_one_model_per_eps():
    eps = np.array([[0.0], [0.02], [0.05]])
    grid = steady.steady_friction_over_eps(M, U, eps)
    thr = static.static_friction_over_eps(M, T, eps, load=0.3, pull_velocity=2.0)
    loc = dieterich.dieterich_constant_local_over_eps(LOG.athermal, U, eps[1:])
    for k, e in enumerate(eps[:, 0]):
        one = M.replace(eps=float(e))
        np.testing.assert_array_equal(grid[k], steady.steady_friction(one, U))
        np.testing.assert_array_equal(thr[k], static.static_friction(one, T, load=0.3,
                                                                     pull_velocity=2.0))
        if k:
            np.testing.assert_array_equal(
                loc[k - 1], dieterich.dieterich_constant_local(LOG.athermal.replace(eps=e), U))
    with pytest.raises(ValueError, match=r"^eps = -0.01 is out of range"):
        steady.steady_friction_over_eps(M, U, -0.01)


def test_functions_of_the_athermal_population_refuse_a_direct_effect():
    with pytest.raises(ValueError, match="^static_friction_at_radius .* model.athermal"):
        static.static_friction_at_radius(M, 1.5)
    with pytest.raises(ValueError, match="^dieterich_constant_local compares .* model.athermal"):
        dieterich.dieterich_constant_local(M, U)
    with pytest.raises(ValueError, match="^pull_velocity is required"):
        static.static_friction_first_order(M, T)


def test_trap_model_as_rsf_old_form_runs_the_same_model(monkeypatch):
    # mistake caught: the old form building its model with eps and alpha swapped (or its
    # creep dropped); the first run is stopped, so nothing is simulated
    seen = []

    def stop(model, track, *args, **kwargs):
        seen.append((model, track.traps_per_a0))
        raise RuntimeError("stop")

    monkeypatch.setattr(rsf_view, "trap_series", stop)
    with pytest.warns(OldTheoryFormWarning, match=r"use trap_model_as_rsf\(model"), \
            pytest.raises(RuntimeError, match="stop"):
        rsf_view.trap_model_as_rsf(0.04, 0.1, 0.1, traps_per_a0=50.0, creep="eyring-nabarro")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(RuntimeError, match="stop"):
            rsf_view.trap_model_as_rsf(M, 0.1, traps_per_a0=50.0)
    assert seen == [(M.athermal.replace(v_ref=1.0), 50.0), (M, 50.0)]
    with pytest.raises(ValueError, match="^eps = 0 is out of range"):
        rsf_view.trap_model_as_rsf(TrapModel())


def test_the_warning_is_a_future_warning_and_an_error_in_the_suite():
    assert issubclass(OldTheoryFormWarning, FutureWarning)  # shown to users, not only to devs
    with pytest.raises(OldTheoryFormWarning):
        steady.steady_friction(1.0, 0.04)


# ---------------------------------------------------------------- no module uses an old form

MODEL_FIRST = {"steady_friction", "steady_friction_first_order", "steady_friction_low_velocity",
               "static_friction", "static_friction_first_order", "static_friction_at_radius",
               "static_friction_si", "steady_friction_si", "dieterich_constant_asymptotic",
               "dieterich_constant_least_squares", "dieterich_constant_local",
               "trap_model_as_rsf", "steady_log_slope", "steady_log_slope_low_velocity",
               "steady_death_point", "steady_profile", "min_velocity",
               "low_velocity_constant", "force_hold_shift", "fresh_force", "loaded_edge",
               "pull_force", "threshold_shift", "static_slope_per_eps", "forward_moment"}


def _is_model(node: ast.expr, names: set[str]) -> bool:
    """A TrapModel by construction: ``TrapModel(...)``, ``x.replace(...)``, a fit model's
    member ``cv.trap_model(...)``, ``x.athermal``, ``x.model``, or a name bound to one of
    these or annotated ``TrapModel``."""
    if isinstance(node, ast.Call):
        f = node.func
        return (isinstance(f, ast.Name) and f.id == "TrapModel") or (
            isinstance(f, ast.Attribute) and f.attr in ("TrapModel", "replace", "trap_model"))
    if isinstance(node, ast.Attribute):
        return node.attr in ("athermal", "model")
    return isinstance(node, ast.Name) and node.id in names


def _model_names(fn: ast.AST) -> set[str]:
    names: set[str] = set()
    if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
        args = fn.args.posonlyargs + fn.args.args + fn.args.kwonlyargs
        names |= {a.arg for a in args if a.annotation is not None
                  and "TrapModel" in ast.unparse(a.annotation)}
    for _ in range(2):  # a name bound from another model name
        for node in ast.walk(fn):
            if isinstance(node, ast.Assign):
                for t in node.targets:
                    pairs = (zip(t.elts, node.value.elts, strict=False)
                             if isinstance(t, ast.Tuple) and isinstance(node.value, ast.Tuple)
                             else [(t, node.value)])
                    names |= {a.id for a, v in pairs
                              if isinstance(a, ast.Name) and _is_model(v, names)}
    return names


def old_form_calls(tree: ast.Module) -> list[int]:
    """Lines where a model-first function is called without a model first."""
    bad = []
    module = _model_names(tree)  # a module's names are seen from its functions
    scopes = [tree, *(n for n in ast.walk(tree)
                      if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)))]
    for scope in scopes:
        names = module | _model_names(scope)
        for node in ast.walk(scope):
            if not isinstance(node, ast.Call):
                continue
            f = node.func
            name = f.id if isinstance(f, ast.Name) else getattr(f, "attr", None)
            if name in MODEL_FIRST and not (
                    (node.args and _is_model(node.args[0], names))
                    or any(k.arg == "model" for k in node.keywords)):
                bad.append(node.lineno)
    return sorted(set(bad))


def test_the_guard_sees_an_old_form():
    # the scan itself, on both forms (it once could pass for not looking)
    old = ast.parse("def f(u):\n    return steady_friction(u, 0.04, 0.13)\n")
    new = ast.parse("def f(model: TrapModel, u):\n    m = model.replace(eps=0.1)\n"
                    "    a, b = TrapModel(), m\n    return steady_friction(b, u) + "
                    "static_friction(m, u) + steady_friction(TrapModel(eps=0.1), u)\n")
    assert old_form_calls(old) == [2]
    assert old_form_calls(new) == []


@pytest.mark.slow
def test_no_module_of_the_package_calls_an_old_form():
    # the suite turns the warning into an error on the paths it runs; this scan covers the
    # paths it does not run (a branch, a figure, a rarely used option), and the examples and
    # benchmarks, which the suite runs in part or not at all
    sources = sorted(SRC.rglob("*.py"))
    assert len(sources) > 50, SRC
    root = SRC.parents[1]
    sources += [*sorted((root / "examples").rglob("*.py")),
                *sorted((root / "benchmarks").glob("*.py"))]
    bad = []
    for path in sources:
        tree = ast.parse(path.read_text())
        defined = {n.name for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
        # the loose implementations the old forms dispatch to call each other loosely
        bad += [f"{path.relative_to(root)}:{ln}" for ln in old_form_calls(tree)
                if not (defined & MODEL_FIRST and _inside_loose(tree, ln))]
    assert bad == [], bad


def _inside_loose(tree: ast.Module, line: int) -> bool:
    return any(isinstance(n, ast.FunctionDef) and n.name.endswith("_loose")
               and n.lineno <= line <= (n.end_lineno or n.lineno) for n in ast.walk(tree))
