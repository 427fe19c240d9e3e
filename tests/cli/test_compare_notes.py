"""``dryfriction compare`` says its notes where the user reads them, in the run's units, and
refuses what it cannot run in words that fit the file. Found by a second new user's trial: the
table came alone (a twin with ``a`` on its bound and a runs test of p = 2e-60 looked fine), the
fit's first note gave ``v0 = 1e-06 m/s`` beside ``v0_a0_per_t0 = 1``, and an extended-interface
file (a cv protocol) was told that compare needs ``model.law = 'cv'``."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.fit.models import RSFModel

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

# steady sliding at its first velocity, no hold: the twin fitted to the run itself, at
# u0 = 0.37 a0/t0 (a generic reference velocity: neither 1 nor the SI scale's 1e-6 m/s)
STEPS = """
[model]
eps = 0.04
mu_el = 0.5
[ensemble]
traps_per_a0 = 300
initial = "steady"
initial_velocity = 0.37
[drive]
kind = "velocity"
segments = [{velocity = 0.37, slip = 0.5}, {velocity = 3.7, slip = 3.0},
            {velocity = 0.37, slip = 3.0}]
[output]
every_slip = 0.02
"""


def _compare(tmp_path: Path, *extra: str) -> subprocess.CompletedProcess[str]:
    f = tmp_path / "steps.toml"
    f.write_text(STEPS)
    # a pipe 80 columns wide, as a user's `| less` or `> file`
    env = {**os.environ, "COLUMNS": "80", "TERM": "dumb"}
    return subprocess.run([sys.executable, "-m", "dryfriction.cli", "compare", str(f), "--out",
                           str(tmp_path / "c"), "--no-figure", *extra],
                          capture_output=True, text=True, env=env, timeout=300)


@pytest.mark.slow
def test_compare_prints_every_note_whole_and_v0_in_reduced_units(tmp_path: Path) -> None:
    # mistakes: no notes printed (the table alone); a note wrapped at the pipe's 80 columns;
    # the twin's v0 note left in the SI of the fit's scales (0.37 a0/t0 -> "3.7e-07 m/s")
    r = _compare(tmp_path)
    assert r.returncode == 0, r.stderr
    d = json.loads((tmp_path / "c" / "compare.json").read_text())
    assert d["v0_a0_per_t0"] == 0.37
    assert d["fit"]["notes"][0] == "v0 = 0.37 a0/t0 fixed (reference velocity)"
    assert not any("m/s" in n for n in d["fit"]["notes"])
    notes = [*d["notes"], *d["fit"]["notes"]]
    lines = r.stdout.splitlines()
    # each one whole on its own line, after the table (its last border)
    last_border = max(i for i, ln in enumerate(lines) if ln.startswith("└"))
    for note in notes:
        assert f"- {note}" in lines[last_border + 1:], (note, r.stdout)
    assert any(len(f"- {n}") > 80 for n in notes)  # the run has a note wider than the pipe


@pytest.mark.slow
def test_compare_json_keeps_stdout_one_document_and_says_the_notes_on_stderr(
        tmp_path: Path) -> None:
    # mistake: the notes printed on standard output with --json (json.loads fails)
    r = _compare(tmp_path, "--json")
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    for note in doc["fit"]["notes"]:
        assert f"- {note}" in r.stderr.splitlines(), (note, r.stderr)


def test_an_si_fit_keeps_its_v0_note_in_m_per_s() -> None:
    # the reduced-units wording is compare's, not every fit's
    n = RSFModel(v0=2.5e-6).notes(frozenset({"steady"}))
    assert n[0] == "v0 = 2.5e-06 m/s fixed (reference velocity)"


def test_compare_refuses_an_interface_protocol_saying_what_it_does_not_take(
        tmp_path: Path) -> None:
    # mistake: "compare runs a trap-model protocol (model.law = 'cv')" to a file that is one
    name = "interface_side_loaded.toml"
    r = CliRunner().invoke(app, ["compare", str(EXAMPLES / name), "--out",
                                 str(tmp_path / "c")])
    assert r.exit_code == 2
    lines = [ln for ln in r.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and name in lines[0], r.output
    assert "extended-interface protocol" in lines[0]
    assert "compare runs a trap-model protocol" not in lines[0]
    assert not (tmp_path / "c").exists()
