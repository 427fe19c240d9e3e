"""The trap model object (issue 26, item 1): one object at the bottom, its defaults and ranges
declared once, as data, and every route reading them from there."""

from __future__ import annotations

import ast
import dataclasses
from pathlib import Path

import pytest

from dryfriction.ensemble import population
from dryfriction.theory.model import (
    TRAP_PARAMETERS,
    TRAPS_PER_A0,
    TRAPS_PER_A0_COARSE,
    TrapModel,
)

SRC = Path(__file__).resolve().parents[2] / "src" / "dryfriction"


def test_the_object_lives_in_theory_and_the_simulator_uses_the_same_one():
    assert population.TrapModel is TrapModel
    assert TrapModel.__module__ == "dryfriction.theory.model"


def test_fields_and_defaults_are_the_declared_table():
    # mistake caught: a default edited in the class and not in the table (or the reverse)
    fields = dataclasses.fields(TrapModel)
    assert [f.name for f in fields] == list(TRAP_PARAMETERS)
    assert {f.name: f.default for f in fields} == {k: p.default
                                                     for k, p in TRAP_PARAMETERS.items()}
    m = TrapModel()
    assert (m.alpha, m.eps, m.creep, m.mu_el, m.direct, m.v_ref) == (0.13, 0.0, "log", 1.0,
                                                                      0.0, 1.0)


@pytest.mark.parametrize("name", [k for k, p in TRAP_PARAMETERS.items() if not p.choices])
def test_every_bound_is_enforced_at_construction_naming_the_parameter(name):
    p = TRAP_PARAMETERS[name]
    for bound, is_open, step in ((p.lo, p.lo_open, -1), (p.hi, p.hi_open, +1)):
        if bound is None:
            continue
        outside = bound + step * max(abs(bound), 1e-300) * 1e-3 if bound else step * 1e-3
        with pytest.raises(ValueError, match=rf"^{name} = .* out of range"):
            TrapModel(**{name: outside})
        if is_open:
            with pytest.raises(ValueError, match=rf"^{name} = "):
                TrapModel(**{name: bound})
        else:
            assert getattr(TrapModel(**{name: bound}), name) == bound
    with pytest.raises(ValueError, match=rf"^{name} = nan"):
        TrapModel(**{name: float("nan")})


def test_a_choice_is_checked_and_a_model_is_frozen():
    with pytest.raises(ValueError, match="^creep = 'power' is not allowed"):
        TrapModel(creep="power")
    m = TrapModel(0.2, 0.03, "eyring-nabarro", direct=0.02, v_ref=3.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.eps = 0.1  # type: ignore[misc]
    assert m.athermal == TrapModel(0.2, 0.03, "eyring-nabarro", v_ref=3.0)
    assert m.replace(eps=0.05).eps == 0.05
    with pytest.raises(ValueError, match="^direct = 2"):
        m.replace(direct=2.0)  # a copy is checked like a new model


def test_the_track_density_has_one_default_and_one_minimum():
    # mistake caught: a literal default (1000, 100, 20) left in one signature, or a second
    # minimum (bifurcation's 1.0) beside the track's
    literal = []
    sources = sorted(SRC.rglob("*.py"))
    assert len(sources) > 50, SRC  # the scan reads the package (it once read no file at all)
    for path in sources:
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                positional = node.args.posonlyargs + node.args.args
                args = positional + node.args.kwonlyargs
                defaults = ([None] * (len(positional) - len(node.args.defaults))
                            + list(node.args.defaults) + list(node.args.kw_defaults))
                pairs = zip(args, defaults, strict=True)
            elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
                pairs = [(node.target, node.value)]  # type: ignore[list-item]
            else:
                continue
            for a, d in pairs:
                name = getattr(a, "arg", getattr(a, "id", None))
                if (name == "traps_per_a0" and isinstance(d, ast.Constant)
                        and d.value is not None):  # None: "the default", resolved below
                    literal.append(f"{path.name}:{node.lineno}")
    assert literal == [], literal
    assert population.TRAPS_PER_A0_MIN == TRAPS_PER_A0.lo == 1e-6
    assert TRAPS_PER_A0.default == 1000.0 and TRAPS_PER_A0_COARSE == 100.0
    with pytest.raises(ValueError, match="^traps_per_a0 = 5e-07 is out of range"):
        population.Track(5e-7)
    from dryfriction.analysis.bifurcation import _checked
    _checked(0.1, TrapModel(eps=0.04, direct=0.02), 0.5, 0.03)  # one minimum: 0.5 pairs a0
    from dryfriction.fit import CVModel
    assert CVModel().traps_per_a0 == TRAPS_PER_A0.default


# ---------------------------------------------------------------- rate-and-state


def test_rate_state_model_is_the_one_object_and_reads_its_table():
    from dryfriction import RateStateModel
    from dryfriction.rsf.law import RATE_STATE_PARAMETERS, RateState
    from dryfriction.validation import REQUIRED

    assert RateStateModel is RateState
    fields = dataclasses.fields(RateState)
    assert [f.name for f in fields] == list(RATE_STATE_PARAMETERS)
    for f in fields:  # mistake caught: a default edited in one place only
        want = RATE_STATE_PARAMETERS[f.name].default
        assert (f.default is dataclasses.MISSING) if want is REQUIRED else f.default == want
    m = RateState(0.011, 0.016, 2e-5, 0.6, 3e-6)
    assert (m.state_law, m.b2, m.dc2, m.regularized, m.c) == ("ageing", 0.0, None, False, 0.0)
    # from_mapping's allowed and required keys are the table's
    with pytest.raises(ValueError, match="missing rate-and-state key.s.: dc, mu0, v0$"):
        RateState.from_mapping({"a": 0.011, "b": 0.016})
    with pytest.raises(ValueError, match="allowed a, b, b2, c, dc, dc2, law, mu0"):
        RateState.from_mapping({"a": 0.011, "q": 1})


@pytest.mark.parametrize("bad, message", [
    ({"a": 0.0}, r"^a = 0 is out of range: allowed finite and > 0 and <= 1000"),
    ({"b": -1e-3}, r"^b = -0.001 is out of range"),
    ({"dc": 0.0}, r"^dc = 0 is out of range"),
    ({"mu0": 11.0}, r"^mu0 = 11 is out of range: allowed finite and >= -10 and <= 10"),
    ({"v0": 2e3}, r"^v0 = 2000 is out of range"),
    ({"state_law": "rate"}, r"^state_law = 'rate' is not allowed"),
    ({"b2": 0.01}, r"^b2 = 0.01 needs dc2"),
    ({"b2": 0.01, "dc2": -1.0}, r"^dc2 = -1 is out of range"),
    ({"regularized": 1}, r"^regularized = 1 is not allowed: true or false"),
    ({"c": 1.0}, r"^c = 1 is Nagata's stress-rate coefficient"),
])
def test_rate_state_ranges_are_enforced_naming_the_parameter(bad, message):
    from dryfriction.rsf.law import RateState

    kw = {"a": 0.011, "b": 0.016, "dc": 2e-5, "mu0": 0.6, "v0": 3e-6, **bad}
    with pytest.raises(ValueError, match=message):
        RateState(**kw)


# ---------------------------------------------------------------- no route drops the direct effect


def test_linear_routes_of_a_protocol_keep_its_direct_effect():
    # mistake caught: a route that rebuilds the model from eps, alpha, creep only (the
    # --linear sweep runner and critical_line did, before issue 26: athermal K_c for a protocol
    # with [model] direct)
    from dryfriction.analysis.linear import linear_summary
    from dryfriction.analysis.stickslip import critical_line
    from dryfriction.theory.linear_stability import critical_stiffness

    u, eps, A, v_ref, mass, eta = 0.3, 0.04, 0.02, 0.7, 1.5, 0.05
    proto = {"model": {"alpha": 0.2, "eps": eps, "direct": A, "v_ref": v_ref},
             "ensemble": {"traps_per_a0": 100, "initial": "steady", "initial_velocity": u},
             "drive": {"kind": "spring", "stiffness": 0.05, "mass": mass, "damping": eta,
                       "segments": [{"velocity": u, "duration": 100.0}]},
             "output": {"every_slip": 0.1}}
    model = TrapModel(0.2, eps, direct=A, v_ref=v_ref)
    want = critical_stiffness(u, model, mass, eta).critical_stiffness
    athermal = critical_stiffness(u, model.athermal, mass, eta).critical_stiffness
    assert abs(want / athermal - 1) > 0.05  # the direct effect matters at this point
    assert linear_summary(proto)["K_c"] == pytest.approx(want, rel=1e-12)
    assert critical_line(proto, [u])[0] == pytest.approx(want, rel=1e-12)


def test_the_direct_effect_enters_every_linear_quantity_of_the_model():
    # one function per quantity: with direct = 0 it is the athermal analysis bit for bit, with
    # direct > 0 each quantity carries g(u) (mistake caught: g left out of one of them)
    from dryfriction.theory.direct import junction_log_slope, junction_strength
    from dryfriction.theory.linear_stability import critical_stiffness, effective_rsf
    from dryfriction.theory.stability import (
        nyquist_stiffness,
        rsf_from_response,
        shift_stiffness,
        steady_response,
    )
    from dryfriction.theory.steady import steady_friction

    u, A, v_ref = 0.2, 0.03, 0.5
    base = TrapModel(0.16, 0.05)
    m = base.replace(direct=A, v_ref=v_ref)
    resp = steady_response(u, base)
    assert critical_stiffness(u, base) == nyquist_stiffness(resp)
    assert effective_rsf(u, base) == {**rsf_from_response(resp), "a_direct": 0.0}
    g = float(junction_strength(u, A, v_ref))
    a_d = float(junction_log_slope(u, A,
                                   v_ref)) * float(steady_friction(TrapModel(alpha=0.16, eps=0.05),
                                                                   u))
    tw0, tw = effective_rsf(u, base), effective_rsf(u, m)
    assert tw["b"] == pytest.approx(g * tw0["b"], rel=1e-10)
    assert tw["a"] == pytest.approx(g * tw0["a"] + a_d, rel=1e-10)
    assert tw["dc"] == pytest.approx(tw0["dc"], rel=1e-10)
    assert tw["a_direct"] == pytest.approx(a_d, rel=1e-12)
    fwd0, bwd0 = shift_stiffness(u, base)
    fwd, bwd = shift_stiffness(u, m)
    assert (fwd, bwd) == pytest.approx((g * fwd0, g * bwd0), rel=1e-12)
    res = critical_stiffness(u, m)
    assert (res.forward_stiffness, res.backward_stiffness) == pytest.approx((fwd, bwd), rel=1e-12)


def test_alpha_one_is_refused():
    """alpha = 1 is no pinning at all (no hysteresis, no friction): the model's range is open
    there. The mistake this is for: the bound closed, so TrapModel(alpha=1.0) was accepted."""
    with pytest.raises(ValueError, match=r"^alpha = 1"):
        TrapModel(alpha=1.0)
    assert TrapModel(alpha=0.97).alpha == 0.97
