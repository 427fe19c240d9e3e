"""One simulator shape for both laws (issue 26, item 4): ``simulate(model, drive, initial,
output) -> Result``, the old forms warning for one release, and the two import cycles gone.

Each test is for a plausible mistake of the change (written down beside it): the old form
giving another run than the new one, a record field dropped when the track moved into the
initial population, a part of the other law (its numbers in other units) accepted, the public
entry running the wrong law, an internal code path still on an old form, a cycle put back.
"""

from __future__ import annotations

import ast
import math
import re
import warnings
from dataclasses import asdict
from pathlib import Path

import numpy as np
import pytest

import dryfriction
from dryfriction import simulation
from dryfriction.ensemble import driving
from dryfriction.ensemble.driving import ForceDrive, Output, SpringDrive, VelocityDrive
from dryfriction.ensemble.population import Initial, Track, TrapModel
from dryfriction.program import Segment, VelocityProgram
from dryfriction.rsf import driving as rsf_driving
from dryfriction.rsf.law import RateState
from dryfriction.rsf.spring import RSFInitial, RSFOutput, SpringSlider
from dryfriction.simulation import OldSimulatorFormWarning

ROOT = Path(__file__).resolve().parents[1]
MODEL = TrapModel(alpha=0.17, eps=0.037)
TRACK = Track(23.0, "random", seed=5)  # not the default lattice: a track lost would show
PROG = VelocityProgram([Segment(0.7, slip=0.6), Segment(0.0, duration=3.0),
                        Segment(1.3, slip=0.5)])
TRAP_RUNS = {
    "velocity": (VelocityDrive(PROG), Initial("steady", velocity=0.7), Output(every_slip=0.05)),
    "force": (ForceDrive(rate=0.9, hold=2.0), Initial("loaded", force=0.2),
              Output(every_slip=0.05)),
    "spring": (SpringDrive(0.3, 0.0, PROG), Initial("rest"), Output(every_slip=0.05)),
    "inertial": (SpringDrive(0.3, 0.2, PROG, 0.1), Initial("rest"), Output(every=0.25)),
}
LAB = RateState(0.0047, 0.0093, 1.3e-5, 0.61, 1.1e-6)
RSF_DRIVE = SpringSlider([Segment(1.1e-6, 7.0), Segment(1.3e-5, 3.0)], 2.1e3, 0.4)
RSF_OUTPUT = RSFOutput(t_eval=np.linspace(0.0, 10.0, 41), rtol=1e-9)


def _same(a: simulation.Result, b: simulation.Result) -> None:
    ca, cb = a.columns(), b.columns()
    assert list(ca) == list(cb)
    for k in ca:
        np.testing.assert_array_equal(ca[k], cb[k], err_msg=k)
    assert a.summary() == b.summary()


# ------------------------------------------------------------------ the old forms, one release

@pytest.mark.parametrize("kind", sorted(TRAP_RUNS))
def test_the_old_trap_form_runs_the_same_and_warns(kind: str) -> None:
    # mistake: the old form's adapter puts the track aside (a default track, the track of
    # another argument) or mixes up drive and output: another run, silently
    drive, initial, output = TRAP_RUNS[kind]
    new = driving.simulate(MODEL, drive, Initial(**{**_fields(initial), "track": TRACK}),
                           output)
    forms = [
        lambda: driving.simulate(MODEL, TRACK, initial, drive, output),
        lambda: driving.simulate(MODEL, TRACK, initial, drive, output=output),
        lambda: driving.simulate(model=MODEL, track=TRACK, initial=initial, drive=drive,
                                 output=output),
        lambda: dryfriction.simulate(MODEL, TRACK, initial, drive, output),
    ]
    for old in forms:
        with pytest.warns(DeprecationWarning, match=r"simulate\(model, drive, Initial"):
            _same(old(), new)
    # its keywords go along (mistake: the adapter drops them: no progress, a Ctrl-C raised)
    calls: list[float] = []
    with pytest.warns(OldSimulatorFormWarning):
        _same(driving.simulate(MODEL, TRACK, initial, drive, output, progress=calls.append,
                               on_interrupt="partial"), new)
    assert calls and calls[-1] == 1.0


def _fields(initial: Initial) -> dict[str, object]:
    return {k: getattr(initial, k) for k in ("kind", "force", "velocity")}


def test_the_old_trap_form_refuses_two_different_tracks() -> None:
    drive, initial, output = TRAP_RUNS["velocity"]
    with pytest.warns(OldSimulatorFormWarning), \
            pytest.raises(ValueError, match=r"track = Track\(traps_per_a0=23.0.*given twice"):
        driving.simulate(MODEL, TRACK, Initial("steady", velocity=0.7, track=Track(40.0)),
                         drive, output)


def test_the_old_rate_and_state_name_runs_the_same_and_warns() -> None:
    # mistake: simulate_rsf forwarding without its output (or initial): the default sampling
    # and start, another series
    init = RSFInitial(v=1.7e-6)
    new = rsf_driving.simulate(LAB, RSF_DRIVE, init, RSF_OUTPUT)
    with pytest.warns(DeprecationWarning, match=r"use simulate\(model, drive, initial, output"):
        _same(rsf_driving.simulate_rsf(LAB, RSF_DRIVE, init, RSF_OUTPUT), new)
    with pytest.warns(DeprecationWarning, match="SpringSlider"):  # the older keyword form
        _same(rsf_driving.simulate_rsf(LAB, RSF_DRIVE.program, stiffness=2.1e3, damping=0.4,
                                       v_init=1.7e-6, rtol=1e-9, t_eval=RSF_OUTPUT.t_eval), new)
    assert dryfriction.simulate_rsf is rsf_driving.simulate_rsf


def test_the_suite_fails_a_test_that_reaches_an_old_form() -> None:
    # pyproject.toml turns the warning into an error in every test: an internal code path on
    # an old form fails whatever test reaches it (only pytest.warns lets it through)
    with pytest.raises(OldSimulatorFormWarning):
        warnings.warn("an old form", OldSimulatorFormWarning, stacklevel=1)
    assert issubclass(OldSimulatorFormWarning, DeprecationWarning)


# ------------------------------------------------------------------ the new shape

def test_dryfriction_simulate_runs_the_law_of_its_model() -> None:
    # mistake: the public entry dispatching on something else than the model (the drive's
    # class, the first law it finds): the other solver, or the wrong units
    drive, initial, output = TRAP_RUNS["spring"]
    initial = Initial("rest", track=TRACK)
    trap = dryfriction.simulate(MODEL, drive, initial, output, on_interrupt="partial")
    _same(trap, driving.simulate(MODEL, drive, initial, output))
    rsf = dryfriction.simulate(LAB, RSF_DRIVE, output=RSF_OUTPUT)
    _same(rsf, rsf_driving.simulate(LAB, RSF_DRIVE, None, RSF_OUTPUT))
    assert (trap.law, rsf.law) == ("cv", "rsf") == (trap.summary()["law"], rsf.summary()["law"])
    assert isinstance(trap, dryfriction.Result) and isinstance(rsf, dryfriction.Result)
    with pytest.raises(ValueError, match=r"model = 0.13 is not allowed: a TrapModel .* RateState"):
        dryfriction.simulate(0.13, drive, initial, output)


@pytest.mark.parametrize("law, part, bad, units", [
    ("rsf", "drive", lambda: VelocityDrive(PROG), "reduced units"),
    ("rsf", "initial", lambda: Initial("rest", track=TRACK), "reduced units"),
    ("rsf", "output", lambda: Output(every=0.5), "reduced units"),
    ("cv", "drive", lambda: RSF_DRIVE, "SI units"),
    ("cv", "initial", lambda: RSFInitial(v=1e-6), "SI units"),
    ("cv", "output", lambda: RSFOutput(every=0.5), "SI units"),
])
def test_a_part_of_the_other_law_is_refused_naming_its_units(law: str, part: str, bad, units: str
                                                             ) -> None:
    # mistake: a drive, start or sampling of the other law accepted on the new route, its
    # numbers read in the wrong units (RSFOutput(every=0.5) s taken as 0.5 t0 by the trap
    # model, which ran into an AttributeError further on; a0/t0 read as m/s)
    parts = ({"drive": VelocityDrive(PROG), "initial": Initial("rest", track=TRACK),
              "output": Output(every=0.5)} if law == "cv" else
             {"drive": RSF_DRIVE, "initial": RSFInitial(), "output": RSF_OUTPUT})
    parts[part] = bad()
    model = MODEL if law == "cv" else LAB
    with pytest.raises(ValueError) as exc:
        dryfriction.simulate(model, **parts)
    msg = str(exc.value)
    assert msg.startswith(f"{part} = {type(parts[part]).__name__}(...) is ") and "\n" not in msg
    other = "SI units" if units == "reduced units" else "reduced units"
    assert msg.index(units) < msg.index(other)  # its own units, then those the model needs
    # and it names the law the part belongs to (a blind mutant named the model's law there)
    owner = "the trap model's" if units == "reduced units" else "rate-and-state's"
    assert f"is {owner}, in {units}" in msg, msg


def test_every_part_names_its_law_and_units() -> None:
    D, In, Out = simulation.Drive, simulation.Initial, simulation.Output
    parts = [(TRAP_RUNS[k][0], D, "cv") for k in TRAP_RUNS] + [
        (Initial("rest"), In, "cv"), (Output(every=1.0), Out, "cv"),
        (RSF_DRIVE, D, "rsf"), (RSFInitial(), In, "rsf"), (RSF_OUTPUT, Out, "rsf")]
    for part, base, law in parts:
        assert isinstance(part, base) and part.law == law
        assert part.units == simulation.LAW_UNITS[law]
        assert ("a0/t0" if law == "cv" else "m/s") in part.units


def test_the_record_keeps_the_track_on_its_own() -> None:
    # mistake: with the track inside the initial population, the run's record (summary.json's
    # parameters) loses "track" or grows initial.track: an output field moved or dropped
    drive, initial, output = TRAP_RUNS["force"]
    res = driving.simulate(MODEL, drive, Initial("loaded", force=0.2, track=TRACK), output)
    assert res.info["parameters"] == {
        "model": {"alpha": 0.17, "eps": 0.037, "creep": "log", "mu_el": 1.0},
        "track": {"traps_per_a0": 23.0, "layout": "random", "seed": 5},
        "initial": {"kind": "loaded", "force": 0.2, "velocity": None},
        "drive": {"kind": "force", "rate": 0.9, "hold": 2.0, "max_force": 10.0},
    }
    assert asdict(TRACK) == res.summary()["parameters"]["track"]


def test_a_trap_run_without_a_track_is_refused_in_one_line() -> None:
    drive, initial, output = TRAP_RUNS["velocity"]
    with pytest.raises(ValueError, match=r"^initial\.track is missing: .*Track\(traps_per_a0"):
        driving.simulate(MODEL, drive, initial, output)
    with pytest.raises(ValueError, match=r"^track = 23.0 is not allowed: a Track"):
        Initial("rest", track=23.0)  # type: ignore[arg-type]


def test_both_results_share_the_result_type() -> None:
    drive, _, output = TRAP_RUNS["velocity"]
    trap = driving.simulate(MODEL, drive, Initial("steady", velocity=0.7, track=TRACK), output)
    rsf = rsf_driving.simulate(LAB, RSF_DRIVE, None, RSF_OUTPUT)
    for res in (trap, rsf):
        assert isinstance(res, simulation.Result) and res.partial is False
        rec = res.to_records()
        assert rec.dtype.names == tuple(res.columns())
        np.testing.assert_array_equal(rec["mu"], res.mu)
        assert list(res.to_dataframe().columns) == list(res.columns())
        assert res.summary()["units"]["v"] == {"cv": "a0/t0", "rsf": "m/s"}[res.law]


# ------------------------------------------------------------------ no old form left, no cycle

_OLD_FORM_ALLOWED = {
    "src/dryfriction/rsf/driving.py",  # simulate_rsf is defined there
    "tests/test_simulator_shape.py",   # the old forms' own tests
}
_OLD_FORM_TESTS = {("tests/rsf/test_rsf.py", "test_old_keyword_form_still_works_and_warns")}


def _old_calls(tree: ast.AST, where: str, skip: set[str]) -> list[str]:
    """Calls of ``simulate_rsf`` and of ``simulate`` with five positions or ``track=``, also
    in code held in strings (a program run in a subprocess); functions in ``skip`` aside."""
    found = []
    todo = [tree]
    while todo:
        node = todo.pop()
        if isinstance(node, ast.FunctionDef) and node.name in skip:
            continue
        todo.extend(ast.iter_child_nodes(node))
        if isinstance(node, ast.Constant) and isinstance(node.value, str) \
                and "simulate" in node.value:
            try:
                found += _old_calls(ast.parse(node.value), where, skip)
            except SyntaxError:
                pass
        if not isinstance(node, ast.Call):
            continue
        f = node.func
        name = f.id if isinstance(f, ast.Name) else getattr(f, "attr", None)
        keys = {k.arg for k in node.keywords}
        if name == "simulate_rsf" or (name == "simulate" and (
                len(node.args) >= 5 or "track" in keys)):
            found.append(f"{where}:{node.lineno}: {ast.unparse(node)[:80]}")
    return sorted(set(found))


def test_no_code_or_example_uses_an_old_form() -> None:
    # the runtime error (pyproject) sees what the tests run; this sees everything written:
    # the package, benchmarks, examples, tests, and the Python in README.md and docs/ (every page)
    found = []
    for path in sorted([*ROOT.glob("src/dryfriction/**/*.py"), *ROOT.glob("benchmarks/*.py"),
                        *ROOT.glob("examples/**/*.py"), *ROOT.glob("tests/**/*.py")]):
        rel = path.relative_to(ROOT).as_posix()
        if rel in _OLD_FORM_ALLOWED:
            continue
        skip = {name for file, name in _OLD_FORM_TESTS if file == rel}
        found += _old_calls(ast.parse(path.read_text()), rel, skip)
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]:
        text = path.read_text()
        for block in re.findall(r"```python\n(.*?)```", text, flags=re.S):
            try:
                found += _old_calls(ast.parse(block), path.name, set())
            except SyntaxError:
                pass
    assert not found, "old simulator forms:\n" + "\n".join(found)


def _intra_package_imports(package: Path, name: str) -> dict[str, set[str]]:
    """``{module: modules of the same package it imports}``, imports inside functions too."""
    graph: dict[str, set[str]] = {}
    for path in package.glob("*.py"):
        mod = path.stem
        deps: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1 and node.module:
                deps.add(node.module.split(".")[0])
            elif isinstance(node, ast.ImportFrom) and node.level == 1:
                deps |= {a.name for a in node.names}
            elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith(name + "."):
                deps.add(node.module.split(".")[2])
        graph[mod] = {d for d in deps if (package / f"{d}.py").exists() and d != mod}
    return graph


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(m: str) -> list[str] | None:
        state[m] = 1
        stack.append(m)
        for d in sorted(graph.get(m, ())):
            if state.get(d) == 1:
                return stack[stack.index(d):] + [d]
            if d not in state and (c := visit(d)):
                return c
        state[m] = 2
        stack.pop()
        return None

    for m in sorted(graph):
        if m not in state and (c := visit(m)):
            return c
    return None


@pytest.mark.parametrize("package", ["ensemble", "rsf"])
def test_no_import_cycle_in_the_simulator_packages(package: str) -> None:
    # mistake: a module of the package importing one that imports it back, hidden in a
    # function ("driving imports this module": ensemble.driving <-> resources, rsf.driving
    # <-> growth before issue 26); what both sides need lives below both now
    graph = _intra_package_imports(ROOT / "src" / "dryfriction" / package,
                                   f"dryfriction.{package}")
    assert "drives" in graph["resources"] or package == "rsf"
    assert _cycle(graph) is None, " -> ".join(_cycle(graph) or [])


def test_the_cycle_check_can_fail(tmp_path: Path) -> None:
    (tmp_path / "a.py").write_text("from .b import x\n")
    (tmp_path / "b.py").write_text("def f():\n    from .a import y  # deferred\n")
    assert _cycle(_intra_package_imports(tmp_path, "p")) == ["a", "b", "a"]


def test_the_stability_of_steady_sliding_is_one_function() -> None:
    # moved beside the law (rsf.stability), still reachable where it was
    from dryfriction.rsf import stability

    assert rsf_driving.linear_stability is stability.linear_stability
    assert dryfriction.rsf_linear_stability is stability.linear_stability
    ev = stability.linear_stability(LAB, 1.1e-6, 0.5 * LAB.critical_stiffness(1.1e-6))
    assert np.max(ev.real) > 0.0 and math.isfinite(float(np.max(ev.real)))


def test_the_parts_a_run_composes_are_exported_where_the_docs_use_them() -> None:
    # the mistake (a second new user): the docs' Initial("rest", track=Track(1000)) and
    # SpringSlider(...) importable only from inner modules; lazily, as the other names
    import importlib

    import dryfriction as df

    where = {"Initial": "ensemble.population", "Track": "ensemble.population",
             "VelocityDrive": "ensemble.drives", "ForceDrive": "ensemble.drives",
             "SpringDrive": "ensemble.drives", "Output": "ensemble.result",
             "SpringSlider": "rsf.spring", "RSFInitial": "rsf.spring",
             "RSFOutput": "rsf.spring"}
    for name, mod in where.items():
        assert name in df.__all__
        assert getattr(df, name) is getattr(importlib.import_module(f"dryfriction.{mod}"), name)
