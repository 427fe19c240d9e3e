"""app.sweeps.prepare_sweep called directly (issue 25): every refusal on both sides of its
edge (workers 0 and 1; the per-core limit and one more; a connect timeout of 0 and a small
one; a grid at the confirmation limit and one point over), every grid point checked with the
analysis asked for, before any worker starts."""

from __future__ import annotations

from pathlib import Path

import pytest

import dryfriction.sweeps.sweep as sw
from dryfriction.app import sweeps as app_sweeps
from dryfriction.app.sweeps import prepare_sweep
from sweep_protocols import spring_sweep


def _proto(tmp_path: Path, sweep: str = '"drive.stiffness" = [0.05, 0.07]\n') -> str:
    p = tmp_path / "p.toml"
    p.write_text(spring_sweep(sweep, slip=30.0, transient=10.0))
    return str(p)


def test_workers_from_one_to_four_per_core(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    proto, out = _proto(tmp_path), str(tmp_path / "out")
    monkeypatch.setattr(app_sweeps.os, "cpu_count", lambda: 3)
    assert prepare_sweep(proto, out, False, 1).size == 2
    assert prepare_sweep(proto, out, False, 12).size == 2
    with pytest.raises(ValueError, match=r"^--workers 0 is out of range: allowed >= 1$"):
        prepare_sweep(proto, out, False, 0)
    with pytest.raises(ValueError, match=r"^--workers 13 is out of range: allowed 1 to 12 "
                                         r"\(4 per core, 3 cores here"):
        prepare_sweep(proto, out, False, 13)
    with pytest.raises(ValueError, match="give one of the two"):
        prepare_sweep(proto, out, False, 1, scheduler="tcp://127.0.0.1:9")
    assert prepare_sweep(proto, out, False, None, scheduler="tcp://127.0.0.1:9").size == 2
    assert not Path(out).exists()  # checked, nothing made


def test_connect_timeout_and_grid_size_edges(tmp_path: Path,
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    proto, out = _proto(tmp_path), str(tmp_path / "out")
    with pytest.raises(ValueError, match=r"^--connect-timeout 0 is out of range: allowed > 0$"):
        prepare_sweep(proto, out, False, None, connect_timeout=0.0)
    prepare_sweep(proto, out, False, None, connect_timeout=1e-3)
    monkeypatch.setattr(sw, "MAX_POINTS", 2)
    assert prepare_sweep(proto, out, False, None).size == 2  # at the limit: no --yes needed
    three = _proto(tmp_path, '"drive.stiffness" = [0.05, 0.07, 0.09]\n')
    with pytest.raises(ValueError, match="the grid has 3 points, more than 2: confirm with --yes"):
        prepare_sweep(three, out, False, None)
    assert prepare_sweep(three, out, True, None).size == 3


def test_every_point_checked_for_the_analysis_asked(tmp_path: Path) -> None:
    # a point whose travel (5 a0) is not longer than the transient (10 a0): refused for the
    # stick-slip summary, by its name; accepted for the linear analysis (no transient)
    proto = _proto(tmp_path, '"drive.segments.0.slip" = [30.0, 5.0]\n')
    with pytest.raises(ValueError, match=r"\(point drive.segments.0.slip = 5.0\): "
                                         r"stickslip.transient = 10 a0 is out of range"):
        prepare_sweep(proto, str(tmp_path / "out"), False, None)
    assert prepare_sweep(proto, str(tmp_path / "out"), False, None, linear=True).size == 2
    (tmp_path / "file").write_text("mine")
    with pytest.raises(ValueError, match="is an existing file, not a folder"):
        prepare_sweep(_proto(tmp_path), str(tmp_path / "file"), False, None)
