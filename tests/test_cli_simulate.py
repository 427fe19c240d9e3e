"""``dryfriction simulate``: files written whole, one-line errors, Ctrl-C handling."""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from dryfriction.cli import app

runner = CliRunner()

PROTO = """
[model]
eps = 0.04
[ensemble]
traps_per_a0 = 200
initial = "rest"
[drive]
kind = "velocity"
segments = [{velocity = 0.0, duration = 10.0}, {velocity = 1.0, slip = 2.0}]
[output]
every_slip = 0.01
snapshots = [5.0]
"""


def _write(tmp_path: Path, text: str, name: str = "p.toml") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def test_simulate_writes_the_results(tmp_path: Path) -> None:
    proto = _write(tmp_path, PROTO)
    out = tmp_path / "res"
    r = runner.invoke(app, ["simulate", str(proto), "--out", str(out), "--json"])
    assert r.exit_code == 0, r.output
    names = {p.name for p in out.iterdir()}
    assert {"timeseries.csv", "summary.json", "timeseries.png"} <= names
    assert any(n.startswith("snapshot_000") for n in names)
    rows = list(csv.DictReader((out / "timeseries.csv").open()))
    assert {"t", "x", "v", "mu", "n_active", "mean_age"} <= set(rows[0])
    assert len(rows) == 1 + 1 + 1 + 200  # t=0, hold split by the snapshot, 2 a0 every 0.01
    s = json.loads((out / "summary.json").read_text())
    assert s["partial"] is False and s["peak_mu"] > 1.0
    assert s["slip"] == pytest.approx(2.0)
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".res")]


@pytest.mark.parametrize(
    "edit, key",
    [
        (("eps = 0.04", "eps = -1"), "in model: eps"),
        (("traps_per_a0 = 200", "traps_per_a0 = 0"), "in ensemble: traps_per_a0"),
        (("[output]", "[output]\nunknown = 1"), "output.unknown"),
        (("duration = 10.0", "duration = -10.0"), "in drive.segments[0]: duration"),
        (("kind = \"velocity\"", "kind = 3"), "drive.kind"),
        (("[model]", "[model"), "malformed TOML"),
    ],
)
def test_bad_protocol_is_one_line_exit_2_no_output(tmp_path: Path, edit: tuple[str, str],
                                                   key: str) -> None:
    proto = _write(tmp_path, PROTO.replace(*edit), "bad.toml")
    out = tmp_path / "res"
    r = runner.invoke(app, ["simulate", str(proto), "--out", str(out)])
    assert r.exit_code == 2
    lines = [ln for ln in r.output.splitlines() if ln.strip()]
    assert len(lines) == 1, r.output
    assert "bad.toml" in lines[0] and key in lines[0]
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_spring_with_no_stiffness(tmp_path: Path) -> None:
    text = PROTO.replace('kind = "velocity"', 'kind = "spring"\nstiffness = 0\nmass = 0')
    proto = _write(tmp_path, text, "s.toml")
    r = runner.invoke(app, ["simulate", str(proto), "--out", str(tmp_path / "o")])
    assert r.exit_code == 2 and "s.toml: in drive: stiffness = 0 is out of range" in r.output
    assert not (tmp_path / "o").exists()


def test_missing_file(tmp_path: Path) -> None:
    r = runner.invoke(app, ["simulate", str(tmp_path / "none.toml"), "--out",
                            str(tmp_path / "o")])
    assert r.exit_code == 2 and "none.toml" in r.output
    assert not (tmp_path / "o").exists()


def test_ctrl_c_leaves_nothing_or_a_complete_partial_result(tmp_path: Path) -> None:
    long = PROTO.replace("slip = 2.0", "slip = 2000.0").replace("snapshots = [5.0]\n", "")
    proto = _write(tmp_path, long)
    out = tmp_path / "res"
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    code = "from dryfriction.cli import main; main()"
    proc = subprocess.Popen([sys.executable, "-c", code, "simulate", str(proto), "--out",
                             str(out)], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    # wait until the run is under way (imports and compilation done), then interrupt
    # (a second SIGINT is sent only if the first went unnoticed, e.g. during start-up; the
    # generous wait keeps it from landing while a loaded machine writes the partial result)
    deadline = time.monotonic() + 240
    time.sleep(3.0)
    while time.monotonic() < deadline and proc.poll() is None:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(timeout=60)
        except subprocess.TimeoutExpired:
            continue
    assert proc.poll() is not None
    leftovers = [p.name for p in tmp_path.iterdir() if p.name not in ("p.toml", "res")]
    assert leftovers == []
    if out.exists():
        s = json.loads((out / "summary.json").read_text())
        assert s["partial"] is True
        rows = list(csv.DictReader((out / "timeseries.csv").open()))
        assert len(rows) == s["samples"] >= 1
        assert (out / "timeseries.png").stat().st_size > 0
        assert proc.returncode == 130
    else:
        assert proc.returncode != 0
