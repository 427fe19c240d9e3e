"""The benchmarks stay runnable: they are not run here (they time things), but a benchmark that
no longer imports, or whose probe no longer compiles, would print nothing but "failed" where
docs/performance.md quotes its figures (``bench_memory``'s probe once had a syntax error that
hid two real faults for a whole session)."""

from __future__ import annotations

import ast
import importlib
import pkgutil
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NAMES = sorted(m.name for m in pkgutil.iter_modules([str(ROOT / "benchmarks")])
               if m.name.startswith("bench_"))


@pytest.fixture(autouse=True)
def _root_on_path(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.syspath_prepend(str(ROOT))


def test_every_benchmark_is_found() -> None:
    assert {"bench_cli", "bench_memory", "bench_sweep", "bench_ensemble"} <= set(NAMES)


@pytest.mark.parametrize("name", NAMES)
def test_benchmark_imports_and_has_a_main(name: str) -> None:
    module = importlib.import_module(f"benchmarks.{name}")
    assert callable(module.main)


@pytest.mark.parametrize("name", NAMES)
def test_code_strings_a_benchmark_runs_in_a_child_compile(name: str) -> None:
    """Every module-level string that a benchmark hands to ``python -c`` (a name ending in
    ``_PROBE`` or ``_CODE``) is valid Python."""
    tree = ast.parse((ROOT / "benchmarks" / f"{name}.py").read_text())
    for node in tree.body:
        if (isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant)
                and isinstance(node.value.value, str)):
            for target in node.targets:
                if isinstance(target, ast.Name) and target.id.endswith(("_PROBE", "_CODE")):
                    compile(node.value.value, f"{name}.{target.id}", "exec")


def test_the_sweep_benchmarks_are_32_points_of_what_they_say() -> None:
    from benchmarks.bench_sweep import CASES

    from dryfriction.analysis.stickslip import stick_slip_summary
    from dryfriction.sweeps.sweep import parse_sweep

    for case, make in CASES.items():
        assert parse_sweep(make()[0]).size == 32, case
    protocol, runner = CASES["stick-slip"]()
    phase = parse_sweep(protocol)
    assert runner is stick_slip_summary
    assert {a.key for a in phase.axes} == {"drive.stiffness", "drive.segments.0.velocity"}
    assert sys.modules["benchmarks.bench_sweep"].ROOT == ROOT


def test_the_light_sweeps_runner_module_does_not_import_the_simulators() -> None:
    """The fork server imports the light sweep's runner module before any worker starts: it
    must stay light (importing the stick-slip modules with it added 0.2 s to every run)."""
    import subprocess

    code = ("import sys; import benchmarks.bench_sweep; "
            "print('dryfriction.analysis.stickslip' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                         text=True, check=True).stdout.strip()
    assert out == "False"


def test_the_ensemble_benchmarks_counter_wraps_the_ensemble_as_it_is() -> None:
    """``bench_ensemble`` counts kernel passes by wrapping :class:`Ensemble`'s ``advance`` and
    ``probe``: a change of their signatures must not break it (it once did, silently until
    the benchmark was next run). A tiny run of each drive, counted, with the direct effect."""
    from benchmarks.bench_ensemble import drive_rate

    for kind in ("velocity", "quasi-static", "inertial"):
        committed, every, _ = drive_rate(kind, 0.01, lam=100.0, slip=0.02)
        assert 0 < committed <= every, kind
