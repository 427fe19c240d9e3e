"""``dryfriction simulate``: files written whole, one-line errors, Ctrl-C handling."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.io.units import read_rows

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
    rows = read_rows(out / "timeseries.csv")
    assert {"t", "x", "v", "mu", "n_active", "mean_age"} <= set(rows[0])
    # t=0, hold split by the snapshot, 2 a0 every 0.01: 200 steps of exactly one lattice
    # spacing (1/100) would alias the lattice, so the slide gets one more (issue 14)
    assert len(rows) == 1 + 1 + 1 + 201
    s = json.loads((out / "summary.json").read_text())
    assert s["partial"] is False and s["peak_mu"] > 1.0
    assert s["slip"] == pytest.approx(2.0)
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".res")]


def test_a_protocol_kept_in_its_own_results_folder_survives(tmp_path: Path) -> None:
    # the run used to delete the folder's contents, its own protocol file included
    out = tmp_path / "res"
    out.mkdir()
    proto = _write(out, PROTO)
    r = runner.invoke(app, ["simulate", str(proto), "--out", str(out)])
    assert r.exit_code == 2 and "--force" in r.output and len(r.output.strip().splitlines()) == 1
    assert [p.name for p in out.iterdir()] == ["p.toml"]
    for _ in range(2):  # again with --force: the protocol stays, the result is replaced
        r = runner.invoke(app, ["simulate", str(proto), "--out", str(out), "--force"])
        assert r.exit_code == 0, r.output
        assert proto.read_text() == PROTO
    assert {"p.toml", "summary.json", "timeseries.csv", "dryfriction.json"} <= {
        p.name for p in out.iterdir()}


@pytest.mark.parametrize("spelling", [".", "cwd"])
def test_out_dot_or_the_working_directory_deletes_nothing(tmp_path: Path, monkeypatch,
                                                          spelling: str) -> None:
    monkeypatch.chdir(tmp_path)
    proto = _write(tmp_path, PROTO)
    (tmp_path / "thesis.tex").write_text("years of work")
    out = "." if spelling == "." else str(tmp_path)
    r = runner.invoke(app, ["simulate", str(proto), "--out", out])
    assert r.exit_code == 2 and "thesis.tex" in r.output
    assert {p.name for p in tmp_path.iterdir()} == {"p.toml", "thesis.tex"}
    r = runner.invoke(app, ["simulate", str(proto), "--out", out, "--force"])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "thesis.tex").read_text() == "years of work"
    assert proto.read_text() == PROTO
    assert not [p for p in tmp_path.iterdir() if ".dftmp-" in p.name]


def test_rerun_into_its_own_folder_replaces_and_says_so(tmp_path: Path) -> None:
    proto = _write(tmp_path, PROTO)
    out = tmp_path / "res"
    assert runner.invoke(app, ["simulate", str(proto), "--out", str(out)]).exit_code == 0
    r = runner.invoke(app, ["simulate", str(proto), "--out", str(out)])
    assert r.exit_code == 0 and "replaced the previous simulate result" in r.output


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


# The child reports "running" from inside the simulation loop (through the progress callback),
# so the signal lands at a known point of the run: after start-up and compilation, before the
# end. Each test then has one outcome to check, not two.
_CHILD = """
import sys
import dryfriction.io.protocol as P
from dryfriction.cli import main

original = P.Protocol.run

def run(self, progress=None, on_interrupt="raise"):
    said = []

    def tick(fraction):
        if not said and fraction > 0.001:
            said.append(1)
            print("running", flush=True)
        if progress is not None:
            progress(fraction)

    return original(self, progress=tick, on_interrupt=on_interrupt)

P.Protocol.run = run
sys.exit(main())
"""


def _start_long_run(tmp_path: Path) -> tuple[subprocess.Popen[str], Path]:
    long = PROTO.replace("slip = 2.0", "slip = 5000.0").replace("snapshots = [5.0]\n", "")
    proto = _write(tmp_path, long)
    out = tmp_path / "res"
    proc = subprocess.Popen([sys.executable, "-c", _CHILD, "simulate", str(proto), "--out",
                             str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    line = proc.stdout.readline().strip()
    assert line == "running", proc.communicate()[1]
    return proc, out


@pytest.mark.slow
def test_ctrl_c_writes_a_complete_partial_result(tmp_path: Path) -> None:
    proc, out = _start_long_run(tmp_path)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert "partial result written" in err
    s = json.loads((out / "summary.json").read_text())
    assert s["partial"] is True
    rows = read_rows(out / "timeseries.csv")
    assert len(rows) == s["samples"] >= 2
    assert float(rows[-1]["x"]) < 5000.0  # stopped early
    assert (out / "timeseries.png").stat().st_size > 0
    assert {p.name for p in tmp_path.iterdir()} == {"p.toml", "res"}


def test_sigterm_writes_nothing_and_leaves_no_temporary(tmp_path: Path) -> None:
    proc, out = _start_long_run(tmp_path)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 143, err
    assert err.strip().splitlines()[-1] == "error: interrupted (SIGTERM)"
    assert {p.name for p in tmp_path.iterdir()} == {"p.toml"}


def test_one_summary_schema_for_rsf_and_both_laws_of_simulate(tmp_path: Path) -> None:
    """summary.json of ``rsf --out``, ``simulate`` (rsf) and ``simulate`` (cv) come from one
    writer: the common keys are in all three, with the units of each law."""
    from dryfriction.results import COMMON_SUMMARY_KEYS

    examples = Path(__file__).resolve().parents[2] / "examples"
    runs = {
        "cv": ["simulate", str(_write(tmp_path, PROTO)), "--out", str(tmp_path / "cv")],
        "rsf-protocol": ["simulate", str(examples / "rsf_velocity_step.toml"), "--out",
                         str(tmp_path / "rsf-protocol")],
        "rsf": ["rsf", "--t1", "1", "--t2", "1", "--out", str(tmp_path / "rsf")],
    }
    summaries = {}
    for name, args in runs.items():
        r = runner.invoke(app, args)
        assert r.exit_code == 0, r.output
        summaries[name] = json.loads((tmp_path / name / "summary.json").read_text())
    for name, s in summaries.items():
        assert set(COMMON_SUMMARY_KEYS) <= set(s), (name, set(COMMON_SUMMARY_KEYS) - set(s))
    assert summaries["cv"]["law"] == "cv" and summaries["cv"]["units"]["x"] == "a0"
    for name in ("rsf", "rsf-protocol"):
        assert summaries[name]["law"] == "rsf" and summaries[name]["units"]["x"] == "m"
    assert summaries["rsf"]["duration"] == pytest.approx(2.0)  # --t1 1 --t2 1
    assert summaries["rsf"]["case"] == "step"
    assert summaries["cv"]["protocol"].endswith("p.toml")


# ---------------------------------------------------------------- resource checks (issue 13)

RSF_PROTO = """
[model]
law = "rsf"
a = 0.005
b = 0.01
dc = 1e-5
mu0 = 0.6
v0 = 1e-6
[drive]
kind = "velocity"
segments = [{velocity = 1e-6, duration = 10.0}, {velocity = 1e-5, slip = 3e-4}]
[output]
every = 0.01
"""

# (law, (old, new), the key the message must name): each input used to end in a MemoryError,
# an OverflowError or a run that could not finish
HUGE = [
    ("cv", ("traps_per_a0 = 200", "traps_per_a0 = 1e10"), "ensemble.traps_per_a0"),
    ("cv", ("traps_per_a0 = 200", "traps_per_a0 = 1e308"), "ensemble.traps_per_a0"),
    ("cv", ("traps_per_a0 = 200", "traps_per_a0 = inf"), "ensemble.traps_per_a0"),
    ("cv", ("traps_per_a0 = 200", "traps_per_a0 = nan"), "ensemble.traps_per_a0"),
    ("cv", ("every_slip = 0.01", "every = 1e-300"), "output.every"),
    ("cv", ("every_slip = 0.01", "every = 1e-9"), "output.every"),
    ("cv", ("duration = 10.0", "duration = 1e300"), "segment"),
    ("cv", ("slip = 2.0", "slip = 1e300"), "output.every_slip"),
    # the control: runs (a shorter hold, so that the snapshot at 5 t0 is within the run)
    ("cv", ("{velocity = 0.0, duration = 10.0}, ", "{velocity = 0.0, duration = 3.5}, "), None),
    ("cv", ("snapshots = [5.0]", "snapshots = [" + ", ".join(str(0.001 * i) for i in
                                                           range(1, 5001)) + "]"),
     "output.snapshots"),
    ("rsf", ("every = 0.01", "every = 1e-300"), "output.every"),
    ("rsf", ("every = 0.01", "every = 1e-9"), "output.every"),
    ("rsf", ("duration = 10.0", "duration = 1e300"), "segment 2"),
    ("rsf", ("slip = 3e-4", "duration = 1e11"), "output.every"),
    ("rsf", ("slip = 3e-4", "slip = 1e6"), "output.every"),
    # beyond rsf.spring.T_MAX (1e12 s in all) the program itself is refused
    ("rsf", ("slip = 3e-4", "duration = 1e300"), "in drive: segments last 1e+300 s"),
    ("rsf", ("slip = 3e-4", "slip = 1e300"), "in drive: segments last 1e+305 s"),
]


@pytest.mark.parametrize("law, edit, key", HUGE)
def test_inputs_too_big_for_the_machine_are_one_line_before_any_work(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, law: str, edit: tuple[str, str],
        key: str | None) -> None:
    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", "8GiB")  # the same answer on any machine
    base = PROTO if law == "cv" else RSF_PROTO
    if "snapshots" in edit[1]:  # 5000 snapshots of a dense track: ~ 65 GiB
        base = base.replace("traps_per_a0 = 200", "traps_per_a0 = 1e5")
    assert edit[0] in base
    proto = _write(tmp_path, base.replace(*edit))
    out = tmp_path / "res"
    r = runner.invoke(app, ["simulate", str(proto), "--out", str(out)])
    if key is None:
        assert r.exit_code == 0, r.output
        return
    lines = [ln for ln in r.output.splitlines() if ln.strip()]
    assert r.exit_code == 2 and len(lines) == 1, r.output
    assert "p.toml" in lines[0] and key in lines[0], lines[0]
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.toml"]


def test_the_memory_limit_is_the_environment_variable(tmp_path: Path,
                                                      monkeypatch: pytest.MonkeyPatch) -> None:
    # the small default protocol holds ~ 1 MiB: refused under 100 KiB, run under 1 GiB
    proto = _write(tmp_path, PROTO)
    out = tmp_path / "res"
    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", "100KiB")
    r = runner.invoke(app, ["simulate", str(proto), "--out", str(out)])
    assert r.exit_code == 2 and "more than the limit 100.0 KiB" in r.output, r.output
    assert "DRYFRICTION_MEMORY_LIMIT" in r.output and not out.exists()
    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", "lots")
    r = runner.invoke(app, ["simulate", str(proto), "--out", str(out)])
    assert r.exit_code == 2 and "DRYFRICTION_MEMORY_LIMIT = 'lots'" in r.output, r.output
    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", "1GiB")
    r = runner.invoke(app, ["simulate", str(proto), "--out", str(out)])
    assert r.exit_code == 0, r.output
