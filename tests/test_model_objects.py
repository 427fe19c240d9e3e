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

SRC = Path(__file__).resolve().parents[1] / "src" / "dryfriction"


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
    for path in SRC.rglob("*.py"):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                args = node.args.args + node.args.kwonlyargs
                defaults = ([None] * (len(node.args.args) - len(node.args.defaults))
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
    _checked(0.1, 0.04, 0.02, 1.0, 0.5, 0.03)  # one minimum: 0.5 pairs per a0 is a track
    from dryfriction.fit import CVModel
    assert CVModel().traps_per_a0 == TRAPS_PER_A0.default
