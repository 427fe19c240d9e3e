"""Sweeps on dask.distributed: grids, resumability, failures, bad input."""

import json
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import cloudpickle
import numpy as np
import pytest

import sweep_runners
from dryfriction.io.sweep import MAX_POINTS, load_sweep, parse_sweep, run_sweep
from dryfriction.theory.stability import critical_stiffness, linear_summary

cloudpickle.register_pickle_by_value(sweep_runners)


def _proto(markers, **extra):
    return {"test": {"x": 1, "y": 1.0, "markers": str(markers), **extra},
            "sweep": {"test.x": [1, 2, 3, 4], "test.y": {"lin": [0.0, 1.0, 3]}}}


def test_grid_runs_on_two_workers_and_round_trips(tmp_path):
    markers = tmp_path / "m"
    markers.mkdir()
    spec = parse_sweep(_proto(markers))
    assert spec.shape == (4, 3) and spec.size == 12
    seen = []
    ds = run_sweep(spec, sweep_runners.counting_runner, tmp_path / "out", n_workers=2,
                   progress=lambda d, n: seen.append((d, n)))
    x, y = np.meshgrid([1, 2, 3, 4], [0.0, 0.5, 1.0], indexing="ij")
    np.testing.assert_allclose(ds["product"].values, x * y)
    assert ds.attrs["n_failed"] == 0 and seen[-1] == (12, 12)
    assert len(list(markers.iterdir())) == 12
    back = load_sweep(tmp_path / "out" / "sweep.nc")
    np.testing.assert_allclose(back["sum"].values, x + y)
    assert list(back.dims) == ["test.x", "test.y"]


def test_failed_point_is_recorded_and_sweep_goes_on(tmp_path):
    markers = tmp_path / "m"
    markers.mkdir()
    spec = parse_sweep(_proto(markers, fail_at_3=True))
    ds = run_sweep(spec, sweep_runners.counting_runner, tmp_path / "out", n_workers=2)
    assert ds.attrs["n_failed"] == 3
    assert np.all(np.isnan(ds["product"].sel({"test.x": 3}).values))
    assert "boom at x = 3" in str(ds["error"].sel({"test.x": 3, "test.y": 0.0}).values)
    assert np.isfinite(ds["product"].sel({"test.x": 4}).values).all()


def test_killed_sweep_resumes_without_recomputing(tmp_path):
    # an uninterrupted reference
    ref_markers = tmp_path / "ref_m"
    ref_markers.mkdir()
    ref = run_sweep(parse_sweep(_proto(ref_markers)), sweep_runners.counting_runner,
                    tmp_path / "ref", n_workers=2)
    # a sweep in another process, killed once some points are stored
    markers = tmp_path / "m"
    markers.mkdir()
    out = tmp_path / "out"
    script = textwrap.dedent(f"""
        import sys, cloudpickle
        sys.path.insert(0, {str(Path(__file__).parent)!r})
        import sweep_runners
        cloudpickle.register_pickle_by_value(sweep_runners)
        from dryfriction.io.sweep import parse_sweep, run_sweep
        proto = {json.dumps(_proto(markers, sleep=0.4))}
        if __name__ == "__main__":
            run_sweep(parse_sweep(proto), sweep_runners.counting_runner, {str(out)!r},
                      n_workers=2)
    """)
    proc = subprocess.Popen([sys.executable, "-c", script])
    t0 = time.monotonic()
    while time.monotonic() - t0 < 60:
        done = list((out / "points").glob("*.json")) if (out / "points").exists() else []
        if len(done) >= 3:
            break
        time.sleep(0.05)
    proc.kill()
    proc.wait()
    finished = {p.name for p in (out / "points").glob("*.json")}
    assert 3 <= len(finished) < 12
    assert not (out / "sweep.nc").exists()
    # resume in this process: only the missing points are computed
    new_markers = tmp_path / "m2"
    new_markers.mkdir()
    proto = _proto(new_markers)
    ds = run_sweep(parse_sweep(proto), sweep_runners.counting_runner, out, n_workers=2)
    assert len(list(new_markers.iterdir())) == 12 - len(finished)
    for name in ("product", "sum"):
        np.testing.assert_array_equal(ds[name].values, ref[name].values)


def test_linear_stability_runner_on_a_grid(tmp_path):
    proto = {"model": {"alpha": 0.13, "eps": 0.04},
             "drive": {"kind": "spring", "stiffness": 0.05, "mass": 0.0, "damping": 0.05,
                       "segments": [{"velocity": 0.1, "duration": 100.0}]},
             "sweep": {"drive.segments.0.velocity": [0.01, 0.1]}}
    ds = run_sweep(parse_sweep(proto), linear_summary, tmp_path / "out", n_workers=1)
    for u in (0.01, 0.1):
        ref = critical_stiffness(u, 0.04, damping=0.05).critical_stiffness
        assert float(ds["K_c"].sel({"drive.segments.0.velocity": u})) == pytest.approx(ref)


@pytest.mark.parametrize(
    "sweep, msg",
    [({"drive.stifness": [1.0]}, "not in the protocol"),
     ({"drive.stiffness": []}, "empty list"),
     ({"drive.stiffness": {"log": [0.0, 1.0, 3]}}, "start, stop > 0"),
     ({"drive.stiffness": {"geom": [1.0, 2.0, 3]}}, "must be a list"),
     ({"drive.segments.5.velocity": [1.0]}, "not in the protocol"),
     ({}, "names no keys")],
)
def test_bad_sweep_tables(sweep, msg):
    proto = {"drive": {"stiffness": 1.0, "segments": [{"velocity": 1.0}]}, "sweep": sweep}
    with pytest.raises(ValueError, match=msg):
        parse_sweep(proto)


def test_large_grid_needs_confirmation_and_bad_scheduler(tmp_path):
    proto = {"a": {"x": 1.0, "y": 1.0},
             "sweep": {"a.x": {"lin": [0, 1, 100]}, "a.y": {"lin": [0, 1, MAX_POINTS // 50]}}}
    with pytest.raises(ValueError, match="--yes"):
        run_sweep(parse_sweep(proto), sweep_runners.counting_runner, tmp_path / "o")
    assert not (tmp_path / "o").exists()
    small = {"a": {"x": 1.0}, "sweep": {"a.x": [1.0]}}
    with pytest.raises(ValueError, match="cannot reach"):
        run_sweep(parse_sweep(small), sweep_runners.counting_runner, tmp_path / "o2",
                  scheduler="tcp://127.0.0.1:9")
