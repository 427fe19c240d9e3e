"""``dryfriction compare``: a trap-model protocol next to its fitted rate-and-state twin."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.theory.model import TrapModel
from dryfriction.theory.steady import steady_friction

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

STEPS = """
[model]
eps = 0.04
mu_el = 0.5
[ensemble]
traps_per_a0 = 500
initial = "steady"
initial_velocity = 0.1
[drive]
kind = "velocity"
segments = [{velocity = 0.1, slip = 0.5}, {velocity = 1.0, slip = 4.0},
            {velocity = 0.1, slip = 4.0}]
[output]
every_slip = 0.02
"""


def test_compare_own_program(tmp_path: Path) -> None:
    f = tmp_path / "steps.toml"
    f.write_text(STEPS)
    out = tmp_path / "cmp"
    r = runner.invoke(app, ["compare", str(f), "--out", str(out), "--json"])
    assert r.exit_code == 0, r.output
    assert {p.name for p in out.iterdir()} == {"compare.json", "compare.png", "dryfriction.json"}
    d = json.loads((out / "compare.json").read_text())
    assert d["calibration"] == "own program" and d["state_law"] == "ageing"
    # twin in friction-coefficient units (mu_el = 0.5): mu0 is the steady level at u0 (eq. 34)
    assert d["mu0"] == pytest.approx(0.5 * float(steady_friction(TrapModel(eps=0.04), 0.1)),
                                     abs=0.01)
    assert d["b"] > 10 * d["a"] > 0 and 0.25 < d["dc_a0"] < 1.5
    change = 0.5 * float(steady_friction(TrapModel(eps=0.04),
                                         0.1) - steady_friction(TrapModel(eps=0.04), 1.0))
    assert 0.0 < d["misfit"]["rms"] < 0.15 * change


@pytest.mark.parametrize("name, needle", [("spring_stick_slip.toml", "drive.kind"),
                                          ("rsf_velocity_step.toml", "trap-model protocol")])
def test_compare_refuses_what_it_cannot_do(tmp_path: Path, name: str, needle: str) -> None:
    out = tmp_path / "cmp"
    r = runner.invoke(app, ["compare", str(EXAMPLES / name), "--out", str(out)])
    assert r.exit_code == 2
    lines = [ln for ln in r.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and needle in lines[0] and name in lines[0], r.output
    assert not out.exists()
