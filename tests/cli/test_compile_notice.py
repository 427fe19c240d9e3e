"""A run that will compile the solvers says so in one line (issue 15: no silent 15 s pause)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

import dryfriction.warm as warm
from dryfriction.cli import app
from dryfriction.rsf import stepper

KERNELS = warm.KERNEL_MODULES
RSF = "rsf/stepper.py"  # the rate-and-state kernels (compiled lazily, cached all the same)


def _package(tmp_path: Path) -> Path:
    for rel in KERNELS:
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text("# kernel\n")
        os.utime(tmp_path / rel, (1000.0, 1000.0))
    return tmp_path


def test_missing_fresh_and_stale_caches(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    root = _package(tmp_path)
    assert warm.missing_kernel_caches(root) == list(KERNELS)  # nothing compiled yet
    cache = root / "ensemble" / "__pycache__" / "kernel._advance-308.py311.nbi"
    cache.parent.mkdir()
    cache.write_bytes(b"")
    os.utime(cache, (2000.0, 2000.0))
    assert warm.missing_kernel_caches(root) == [RSF]  # one cached, newer
    os.utime(root / "ensemble" / "kernel.py", (3000.0, 3000.0))
    assert warm.missing_kernel_caches(root) == list(KERNELS)  # source edited since: stale
    other = root / "rsf" / "__pycache__" / "law.x-1.py311.nbi"  # another module's cache
    other.parent.mkdir()
    other.write_bytes(b"")
    os.utime(other, (4000.0, 4000.0))
    assert RSF in warm.missing_kernel_caches(root)


def test_numba_cache_dir_is_searched(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    root = _package(tmp_path / "pkg")
    where = tmp_path / "cache" / "deep" / "rsf"
    where.mkdir(parents=True)
    for name in ("stepper._rhs-140.py311.nbi", "kernel._advance-308.py311.nbi"):
        (where / name).write_bytes(b"")
        os.utime(where / name, (2000.0, 2000.0))
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "cache"))
    assert warm.missing_kernel_caches(root) == []


@pytest.mark.parametrize("missing", [[RSF], []])
def test_command_says_it_compiles_only_when_it_will(missing: list[str], tmp_path: Path,
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    """A rate-and-state run large enough for the compiled solver, in a process that has not
    loaded it yet: the notice comes when (and only when) its cache is missing."""
    monkeypatch.setattr(warm, "missing_kernel_caches", lambda *a: missing)
    monkeypatch.setattr(stepper, "_compiled", {})  # as in a fresh process
    monkeypatch.setattr(stepper, "compile_hook", None)
    with stepper.interpreted_steps(0):
        r = CliRunner().invoke(app, ["rsf", "--case", "step", "--t1", "1", "--t2", "1"])
    assert r.exit_code == 0, r.output
    assert ("compiling the solvers once" in r.output) == bool(missing)


def test_small_rsf_run_compiles_nothing_and_says_nothing(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(warm, "missing_kernel_caches", lambda *a: [RSF])
    monkeypatch.setattr(stepper, "_compiled", {})
    monkeypatch.setattr(stepper, "compile_hook", None)
    with stepper.interpreted_steps(10**6):
        r = CliRunner().invoke(app, ["rsf", "--case", "step", "--t1", "1", "--t2", "1"])
    assert r.exit_code == 0, r.output
    assert "compiling" not in r.output
    assert stepper._compiled == {}  # interpreted throughout


def test_installed_package_is_warm() -> None:
    # make's install step runs python -m dryfriction.warm: the test environment is warm, so the
    # notice is silent for every user of `make` (fails if the warm-up misses a kernel module)
    assert warm.missing_kernel_caches() == []
