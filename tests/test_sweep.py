"""Sweeps on dask.distributed: grids, resumability, failures, bad input."""

import copy
import json
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import cloudpickle
import numpy as np
import pytest

import dryfriction.sweep as sweep_mod
import sweep_runners
from dryfriction.stability import critical_stiffness, linear_summary
from dryfriction.sweep import MAX_POINTS, load_sweep, parse_sweep, point_key, run_sweep

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
        from dryfriction.sweep import parse_sweep, run_sweep
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
    # resume in this process, the same protocol: only the missing points are computed
    before = len(list(markers.iterdir()))
    ds = run_sweep(parse_sweep(_proto(markers, sleep=0.4)), sweep_runners.counting_runner, out,
                   n_workers=2)
    assert len(list(markers.iterdir())) - before == 12 - len(finished)
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
                  scheduler="tcp://127.0.0.1:9", connect_timeout=1.0)
    assert not (tmp_path / "o2").exists()


# ------------------------------------------------------------------ issue 16: whose numbers


def _run(markers, out, **extra):
    return run_sweep(parse_sweep(_proto(markers, **extra)), sweep_runners.counting_runner, out,
                     n_workers=1)


def test_point_key_covers_every_table_the_analysis_and_the_version(monkeypatch):
    proto = {"model": {"eps": 0.04}, "drive": {"stiffness": 0.05},
             "stickslip": {"transient": 10.0}}
    key = point_key(proto, "a")
    assert point_key(copy.deepcopy(proto), "a") == key
    assert point_key({**proto, "model": {"eps": 0.05}}, "a") != key  # an unswept key
    assert point_key({**proto, "stickslip": {"transient": 11.0}}, "a") != key
    assert point_key(proto, "b") != key
    monkeypatch.setattr(sweep_mod, "RESULT_VERSION", sweep_mod.RESULT_VERSION + 1)
    assert point_key(proto, "a") != key


def test_changed_base_protocol_is_refused_identical_one_resumes(tmp_path):
    markers = tmp_path / "m"
    markers.mkdir()
    out = tmp_path / "out"
    _run(markers, out)
    n = len(list(markers.iterdir()))
    # the same sweep again: everything is stored, nothing computed
    ds = _run(markers, out)
    assert len(list(markers.iterdir())) == n
    # an unswept key changed (what model.eps is to a real sweep): refused, nothing touched
    before = {p.name: p.read_bytes() for p in out.rglob("*") if p.is_file()}
    with pytest.raises(ValueError, match="holds a different sweep.*another --out or remove"):
        _run(markers, out, extra_param=2.0)
    # another analysis of the same protocol (what --linear is to stick-slip): refused
    with pytest.raises(ValueError, match="different sweep .analysis"):
        run_sweep(parse_sweep(_proto(markers)), sweep_runners.other_runner, out, n_workers=1)
    assert {p.name: p.read_bytes() for p in out.rglob("*") if p.is_file()} == before
    assert len(list(markers.iterdir())) == n
    np.testing.assert_allclose(load_sweep(out / "sweep.nc")["product"], ds["product"])
    marker = json.loads((out / "sweep.json").read_text())
    assert marker["format"] == "dryfriction-sweep" and len(marker["protocol_hash"]) == 64


@pytest.mark.parametrize("content", ["notes.txt", "points", "sweep.json"])
def test_folder_that_is_not_our_sweep_is_refused_and_left_alone(tmp_path, content):
    out = tmp_path / "out"
    out.mkdir()
    if content == "points":  # a folder of the old format: points keyed by overrides only
        (out / "points").mkdir()
        (out / "points" / "0123456789abcdef.json").write_text('{"result": {"product": 1}}')
    else:
        (out / content).write_text("mine\n")
    before = sorted(str(p.relative_to(out)) for p in out.rglob("*"))
    markers = tmp_path / "m"
    markers.mkdir()
    with pytest.raises(ValueError, match="not a dryfriction sweep"):
        _run(markers, out)
    assert sorted(str(p.relative_to(out)) for p in out.rglob("*")) == before
    assert not list(markers.iterdir())


def test_failed_points_are_computed_again_on_the_next_run(tmp_path):
    markers = tmp_path / "m"
    markers.mkdir()
    out = tmp_path / "out"
    ds = _run(markers, out, fail_at_3=True)
    assert ds.attrs["n_failed"] == 3
    n = len(list(markers.iterdir()))
    ds = _run(markers, out, fail_at_3=True)
    assert len(list(markers.iterdir())) - n == 3  # only the three failed points ran again
    rec = [json.loads(p.read_text()) for p in (out / "points").glob("*.json")]
    assert sum("error" in r for r in rec) == 3 and all("boom" in r["traceback"]
                                                       for r in rec if "error" in r)


def test_no_http_server_and_no_process_left(tmp_path):
    import psutil

    from dryfriction.sweep import _client

    me = psutil.Process()
    client = _client(None, 1)
    try:
        info = client.scheduler_info()
        assert "dashboard" not in info["services"]
        tree = [me, *me.children(recursive=True)]
        listening = {c.laddr.port for p in tree for c in p.net_connections(kind="inet")
                     if c.status == psutil.CONN_LISTEN}
        dask_ports = {int(client.scheduler.address.rsplit(":", 1)[1])}
        for addr, w in info["workers"].items():
            dask_ports |= {int(addr.rsplit(":", 1)[1]), int(w["nanny"].rsplit(":", 1)[1])}
        assert listening == dask_ports  # no HTTP (dashboard, health, metrics) anywhere
        workers = [p for p in me.children(recursive=True)
                   if "resource_tracker" not in " ".join(p.cmdline())]
        assert workers
    finally:
        client.close()
        client.cluster.close()
    gone, alive = psutil.wait_procs(workers, timeout=10)
    assert not alive


def _http_server():
    import http.server
    import threading

    srv = http.server.HTTPServer(("127.0.0.1", 0), http.server.SimpleHTTPRequestHandler)
    threading.Thread(target=srv.serve_forever, daemon=True).start()
    return srv


def test_scheduler_that_is_not_dask_fails_fast_and_a_real_one_works(tmp_path):
    from dask.distributed import LocalCluster

    srv = _http_server()
    try:
        small = {"test": {"x": 1, "y": 2.0, "markers": str(tmp_path)}, "sweep": {"test.x": [1]}}
        t0 = time.monotonic()
        with pytest.raises(ValueError, match="cannot reach a Dask scheduler.*1.5 s"):
            run_sweep(parse_sweep(small), sweep_runners.counting_runner, tmp_path / "o",
                      scheduler=f"tcp://127.0.0.1:{srv.server_port}", connect_timeout=1.5)
        assert time.monotonic() - t0 < 6
        assert not (tmp_path / "o").exists()
    finally:
        srv.shutdown()
    with pytest.raises(ValueError, match="--workers"):
        run_sweep(parse_sweep(small), sweep_runners.counting_runner, tmp_path / "o",
                  scheduler="tcp://127.0.0.1:9", n_workers=2)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster:
        ds = run_sweep(parse_sweep(small), sweep_runners.counting_runner, tmp_path / "o",
                       scheduler=cluster.scheduler_address)
    assert ds["product"].item() == 2.0
