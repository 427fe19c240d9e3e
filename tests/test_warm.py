"""The warm-up module (dryfriction.warm), top-level like it: a cache as new as its source is
fresh (Numba's own test is the same: the source's timestamp recorded at compile time), one
older is not; the kernel modules it names exist and are cached; the warm-up protocols cover
each drive, creep law and rate-and-state variant its docstring names (issue 25: a >= moved to
>, a list that drifted from the sources)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import dryfriction
import dryfriction.warm as warm


def test_a_cache_as_new_as_its_source_is_fresh(tmp_path: Path,
                                              monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    for rel in warm.KERNEL_MODULES:
        src = tmp_path / rel
        src.parent.mkdir(parents=True, exist_ok=True)
        src.write_text("# kernel\n")
        os.utime(src, (1234.5, 1234.5))
        cache = src.parent / "__pycache__" / f"{src.stem}._f-10.py311.nbi"
        cache.parent.mkdir(exist_ok=True)
        cache.write_bytes(b"")
        os.utime(cache, (1234.5, 1234.5))  # the same second: fresh
    assert warm.missing_kernel_caches(tmp_path) == []
    first = tmp_path / warm.KERNEL_MODULES[0]
    os.utime(first.parent / "__pycache__" / f"{first.stem}._f-10.py311.nbi", (1234.0, 1234.0))
    assert warm.missing_kernel_caches(tmp_path) == [warm.KERNEL_MODULES[0]]
    # a module that is not there is not reported (nothing to compile)
    first.unlink()
    assert warm.missing_kernel_caches(tmp_path) == []


def test_the_kernel_modules_and_protocols_match_the_package() -> None:
    root = Path(dryfriction.__file__).parent
    assert warm.KERNEL_MODULES == ("ensemble/kernel.py", "rsf/stepper.py")
    for rel in warm.KERNEL_MODULES:
        assert (root / rel).is_file() and "cache=True" in (root / rel).read_text()
    kinds = {p["drive"]["kind"] for p in warm.WARM_PROTOCOLS}
    assert kinds == {"velocity", "spring", "force", "side"}
    rsf = [p["model"] for p in warm.WARM_PROTOCOLS if p["model"].get("law") == "rsf"]
    assert {m.get("state_law", "ageing") for m in rsf} >= {"ageing", "slip"}
    assert any("dc2" in m for m in rsf) and any(m.get("regularized") for m in rsf)
    creeps = {p["model"].get("creep", "log") for p in warm.WARM_PROTOCOLS
              if p["model"].get("law") != "rsf"}
    assert creeps == {"log", "eyring-nabarro"}
