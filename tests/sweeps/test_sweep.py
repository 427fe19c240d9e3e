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

import dryfriction.sweeps.sweep as sweep_mod
import sweep_runners
from dryfriction.analysis.linear import linear_summary
from dryfriction.sweeps.sweep import MAX_POINTS, load_sweep, parse_sweep, point_key, run_sweep
from dryfriction.theory.linear_stability import critical_stiffness
from dryfriction.theory.model import TrapModel
from sweep_protocols import spring_sweep

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
    # the results folder reads its sweep.nc (a new user's load_sweep('out') raised
    # IsADirectoryError); a folder without one is one line naming the file
    np.testing.assert_allclose(load_sweep(tmp_path / "out")["sum"].values, x + y)
    with pytest.raises(FileNotFoundError, match=r"m/sweep\.nc: no such sweep file"):
        load_sweep(markers)


def test_failed_point_is_recorded_and_sweep_goes_on(tmp_path):
    markers = tmp_path / "m"
    markers.mkdir()
    spec = parse_sweep(_proto(markers, fail_at_3=True))
    ds = run_sweep(spec, sweep_runners.counting_runner, tmp_path / "out", n_workers=2)
    assert ds.attrs["n_failed"] == 3
    assert np.all(np.isnan(ds["product"].sel({"test.x": 3}).values))
    assert "boom at x = 3" in str(ds["error"].sel({"test.x": 3, "test.y": 0.0}).values)
    assert np.isfinite(ds["product"].sel({"test.x": 4}).values).all()


@pytest.mark.slow
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
        sys.path.insert(0, {str(Path(__file__).resolve().parents[1])!r})
        import sweep_runners
        cloudpickle.register_pickle_by_value(sweep_runners)
        from dryfriction.sweeps.sweep import parse_sweep, run_sweep
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
    # a whole protocol: the runner reads it through the protocol parser, like every point
    proto = {"model": {"alpha": 0.13, "eps": 0.04},
             "ensemble": {"traps_per_a0": 100, "initial": "steady", "initial_velocity": 0.1},
             "drive": {"kind": "spring", "stiffness": 0.05, "mass": 1.0, "damping": 0.05,
                       "segments": [{"velocity": 0.1, "duration": 100.0}]},
             "output": {"every_slip": 0.1},
             "sweep": {"drive.segments.0.velocity": [0.01, 0.1]}}
    ds = run_sweep(parse_sweep(proto), linear_summary, tmp_path / "out", n_workers=1)
    for u in (0.01, 0.1):
        ref = critical_stiffness(u, TrapModel(eps=0.04), mass=1.0, damping=0.05).critical_stiffness
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

    from dryfriction.sweeps.cluster import close_client, start_client

    me = psutil.Process()
    client = start_client(None, 1)
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
        close_client(client, None, [])
    gone, alive = psutil.wait_procs(workers, timeout=10)
    assert not alive


def _http_server():
    import http.server
    import threading

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):  # the server's own log is not the command's output
            pass

    srv = http.server.HTTPServer(("127.0.0.1", 0), Quiet)
    threading.Thread(target=srv.serve_forever, daemon=True).start()
    return srv


def _warm_probe():
    """Import what a probe of a scheduler imports (Dask's comms, the sweep command), so that the
    fail-fast tests time the wait for the answer, not the imports: alone in a process on a
    loaded machine (load 13 on 2 cores) importing them took several seconds of wall time."""
    import distributed.comm  # noqa: F401

    import dryfriction.cli.sweeps  # noqa: F401
    import dryfriction.sweeps.cluster  # noqa: F401


def test_scheduler_that_is_not_dask_fails_fast_and_a_real_one_works(tmp_path):
    from dask.distributed import LocalCluster

    srv = _http_server()
    _warm_probe()
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


# ------------------------------------------------------------------ the commands

CLI_PROTO = spring_sweep(slip="SLIP")


def _cli_proto(tmp_path, sweep, slip=30.0, name="p.toml", **replace):
    text = CLI_PROTO.replace("SLIP", repr(slip)) + sweep
    for old, new in replace.items():
        text = text.replace(old, new)
    path = tmp_path / name
    path.write_text(text)
    return path


def _cli(*args, **kw):
    return subprocess.Popen([sys.executable, "-m", "dryfriction.cli", *map(str, args)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


@pytest.mark.parametrize("table, message", [
    ("transient = -5.0", "stickslip.transient = -5 is out of range"),
    ("transient = 30.0", "less than the load-point travel 30"),
    ("rel_threshold = 1.5", "stickslip.rel_threshold = 1.5 is out of range"),
    ("stick_fraction = 0.0", "stickslip.stick_fraction = 0 is out of range"),
    ("floor = -1.0", "stickslip.floor = -1 is out of range"),
    ("transient = \"ten\"", "stickslip.transient = 'ten' is not a number"),
    ("follow_velocity = 1", "stickslip.follow_velocity = 1 is not allowed"),
])
def test_bad_stickslip_values_refused_before_any_worker(tmp_path, table, message):
    from typer.testing import CliRunner

    from dryfriction.cli import app

    p = _cli_proto(tmp_path, '"drive.stiffness" = [0.04, 0.05]\n',
                   **{"transient = 10.0": table})
    # the table is checked with --linear too; the travel only matters to stick-slip
    for extra in ([], ["--linear"])[:1 if "travel" in message else 2]:
        r = CliRunner().invoke(app, ["sweep", str(p), "--out", str(tmp_path / "o"), *extra])
        assert r.exit_code == 2, r.output
        assert message in r.output.replace("\n", " ")
        assert len(r.output.strip().splitlines()) == 1
    assert not (tmp_path / "o").exists()


def test_swept_stickslip_value_checked_per_point_rsf_and_workers_with_scheduler(tmp_path):
    from typer.testing import CliRunner

    from dryfriction.cli import app

    run = CliRunner().invoke
    p = _cli_proto(tmp_path, '"stickslip.transient" = [5.0, -5.0]\n')
    r = run(app, ["sweep", str(p), "--out", str(tmp_path / "o")])
    assert r.exit_code == 2 and "stickslip.transient = -5.0" in r.output
    rsf = tmp_path / "rsf.toml"
    rsf.write_text('[model]\nlaw = "rsf"\na = 0.005\nb = 0.01\ndc = 1e-5\nmu0 = 0.6\n'
                   'v0 = 1e-6\n[drive]\nstiffness = 1e3\nsegments = [{velocity = 1e-6, '
                   'duration = 10.0}]\n[sweep]\n"drive.stiffness" = [1e3, 2e3]\n')
    for extra in ([], ["--linear"]):
        r = run(app, ["sweep", str(rsf), "--out", str(tmp_path / "o"), *extra])
        assert r.exit_code == 2 and "not supported yet" in r.output, r.output
        assert len(r.output.strip().splitlines()) == 1
    p = _cli_proto(tmp_path, '"drive.stiffness" = [0.05]\n')
    r = run(app, ["sweep", str(p), "--out", str(tmp_path / "o"), "--workers", "2",
                  "--scheduler", "tcp://127.0.0.1:9"])
    assert r.exit_code == 2 and "--workers" in r.output and "--scheduler" in r.output
    assert not (tmp_path / "o").exists()


def test_cli_not_a_scheduler_fails_fast_with_one_line(tmp_path):
    from typer.testing import CliRunner

    from dryfriction.cli import app

    srv = _http_server()
    _warm_probe()
    try:
        p = _cli_proto(tmp_path, '"drive.stiffness" = [0.05]\n')
        t0 = time.monotonic()
        r = CliRunner().invoke(app, ["sweep", str(p), "--out", str(tmp_path / "o"),
                                     "--scheduler", f"127.0.0.1:{srv.server_port}",
                                     "--connect-timeout", "1"])
    finally:
        srv.shutdown()
    assert r.exit_code == 2 and "cannot reach a Dask scheduler" in r.output, r.output
    assert len(r.output.strip().splitlines()) == 1 and time.monotonic() - t0 < 6
    assert not (tmp_path / "o").exists()


@pytest.mark.slow
def test_some_or_all_points_failed_exit_1_with_one_line(tmp_path):
    from typer.testing import CliRunner

    from dryfriction.cli import app

    # transient 29.6 of 30 a0 leaves one sample (every 0.5 a0, which is 25 trap spacings, so
    # the grid gets one sample more: 61 steps of 0.49 a0): fails at run time
    p = _cli_proto(tmp_path, '"stickslip.transient" = [10.0, 29.6]\n')
    r = CliRunner().invoke(app, ["sweep", str(p), "--out", str(tmp_path / "o"),
                                 "--workers", "1"])
    assert r.exit_code == 1, r.output
    assert "1 of 2 points failed (first: ValueError: only 1 samples" in r.output
    ds = load_sweep(tmp_path / "o" / "sweep.nc")  # written, the failure recorded
    assert ds.attrs["n_failed"] == 1 and np.isfinite(ds["class"].values[0])
    assert "only 1 samples" in str(ds["error"].values[1])
    p = _cli_proto(tmp_path, '"stickslip.transient" = [29.6]\n', name="q.toml")
    r = CliRunner().invoke(app, ["sweep", str(p), "--out", str(tmp_path / "q"),
                                 "--workers", "1"])
    assert r.exit_code == 1 and "all 1 points failed" in r.output, r.output
    assert f"{tmp_path / 'q'}/points/*.json" in r.output.replace("\n", "")


@pytest.mark.slow
def test_concurrent_sweeps_into_one_folder_second_is_refused(tmp_path):
    import psutil

    out = tmp_path / "o"
    # several seconds a point: the first run is still busy when the others try
    grid = '"drive.stiffness" = [0.04, 0.05, 0.06, 0.07]\n'
    a = _cli_proto(tmp_path, grid, slip=3000.0)
    b = _cli_proto(tmp_path, grid, slip=3000.0, name="b.toml",
                   **{"eps = 0.04": "eps = 0.05"})
    first = _cli("sweep", a, "--out", out, "--workers", "1", start_new_session=True)
    t0 = time.monotonic()
    # the cluster is up once points/ exists (a Ctrl-C during its start can be lost)
    while not (out / "points").exists() and time.monotonic() - t0 < 60:
        time.sleep(0.05)
    same = _cli("sweep", a, "--out", out, "--workers", "1")
    other = _cli("sweep", b, "--out", out, "--workers", "1")
    (_, err_same), (_, err_other) = same.communicate(timeout=60), other.communicate(timeout=60)
    assert first.poll() is None  # still running: the lock, not the end of the run, refused
    kids = psutil.Process(first.pid).children(recursive=True)
    assert same.returncode == 2 and "another sweep is running" in err_same, err_same
    assert other.returncode == 2 and "different sweep" in err_other, err_other
    assert len(err_same.strip().splitlines()) == len(err_other.strip().splitlines()) == 1
    # a crash of the first run (SIGKILL): its workers go, and nothing of the others got in
    first.kill()
    first.communicate(timeout=60)
    _, alive = psutil.wait_procs(kids, timeout=15)
    assert not alive
    # nothing of the refused runs got in
    for rec in (out / "points").glob("*.json"):
        assert json.loads(rec.read_text())["protocol"]["model"]["eps"] == 0.04


@pytest.mark.slow
def test_ctrl_c_prints_the_resume_command_which_finishes_the_sweep(tmp_path):
    import os
    import shlex
    import signal

    out = tmp_path / "o"
    p = _cli_proto(tmp_path, '"drive.stiffness" = [0.04, 0.05, 0.06]\n', slip=60.0)
    proc = _cli("sweep", p, "--out", out, "--workers", "1", start_new_session=True)
    t0 = time.monotonic()
    while time.monotonic() - t0 < 60 and not (
            (out / "points").exists() and list((out / "points").glob("*.json"))):
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and "Traceback" not in err, err
    stored = len(list((out / "points").glob("*.json")))
    assert f"interrupted: {stored} of 3 points stored" in err and stored < 3
    cmd = shlex.split(err.split("resume with: ")[1].strip())
    assert cmd[0] == "dryfriction"
    resumed = _cli(*cmd[1:])
    so, se = resumed.communicate(timeout=120)
    assert resumed.returncode == 0, se
    assert "3 points, 0 failed" in so
    assert load_sweep(out / "sweep.nc")["class"].shape == (3,)


@pytest.mark.parametrize("moment", ["marker", "fork server"])
def test_ctrl_c_while_the_cluster_starts_is_not_lost(tmp_path, moment):
    """The interrupt is recorded during the start and acted on as soon as it is over, with no
    traceback: sent to the whole process group as a terminal's Ctrl-C is, when the folder's
    marker is written (before the cluster) and while the fork server imports Dask (the
    ``fork server`` case: before the fix that server printed its own KeyboardInterrupt
    traceback; the test sent its signal at the marker only, and caught that only when load
    delayed the signal into the server's imports). The moments are told by the run itself
    (:mod:`ready_hook`), not by a time."""
    import os
    import signal

    from ready_hook import FORK_SERVER, ready_env, wait_ready

    out = tmp_path / "o"
    p = _cli_proto(tmp_path, '"drive.stiffness" = [0.04, 0.05, 0.06]\n', slip=60.0)
    kw = {}
    if moment == "fork server":
        kw["env"] = ready_env(dict(os.environ), tmp_path / "hook", FORK_SERVER,
                              tmp_path / "ready", when="call")
    proc = _cli("sweep", p, "--out", out, "--workers", "2", start_new_session=True, **kw)
    if moment == "fork server":
        wait_ready(proc, tmp_path / "ready", "sweep")
    else:
        t0 = time.monotonic()
        while time.monotonic() - t0 < 60 and not (out / "sweep.json").exists():
            time.sleep(0.01)
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert "Traceback" not in err and "interrupted" in err, err
    assert len(list((out / "points").glob("*.json"))) < 3
