"""``dryfriction simulate`` of an ``[interface]`` protocol (issue 29): the fields and the summary
written, one-line refusals (exit 2) before any work."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.io.protocol import InterfaceProtocol, parse_protocol
from dryfriction.io.units import undeclared

runner = CliRunner()

PROTO = """
[model]
eps = 0.04
[ensemble]
traps_per_a0 = 30
layout = "random"
seed = 2
initial = "rest"
[interface]
n_elements = 5
coupling = 2.0
mass = 1.0
damping = 0.1
[drive]
kind = "side"
edge_stiffness = 0.4
segments = [{velocity = 0.1, slip = 1.0}]
[output]
every = 0.5
"""


def _write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "interface.toml"
    p.write_text(text)
    return p


def test_interface_protocol_is_parsed_into_the_chain() -> None:
    proto = parse_protocol(PROTO, "p.toml")
    assert isinstance(proto, InterfaceProtocol)
    assert proto.model.n_elements == 5 and proto.model.coupling == 2.0
    assert proto.drive.loading == "side" and proto.drive.edge_stiffness == 0.4
    assert proto.track.seed == 2 and proto.initial.kind == "rest"


def test_simulate_writes_the_fields_and_the_summary(tmp_path: Path) -> None:
    out = tmp_path / "out"
    r = runner.invoke(app, ["simulate", str(_write(tmp_path, PROTO)), "--out", str(out)])
    assert r.exit_code == 0, r.output
    with np.load(out / "fields.npz") as f:
        assert f["slip"].shape == (f["t"].size, 5) == f["stress"].shape == f["slip_rate"].shape
        assert f["t"][-1] == pytest.approx(10.0)
        assert np.all(np.isfinite(f["stress"]))
    summary = json.loads((out / "summary.json").read_text())
    assert summary["kind"] == "interface" and summary["n_elements"] == 5
    assert summary["units"]["stress"].startswith("F_el")
    assert summary["params"]["drive"]["loading"] == "side"
    assert (out / "load.csv").read_text().startswith("t[t0],load[F_el],load_point[a0]")
    assert undeclared(summary) == []  # every number of summary.json has its unit
    assert summary["units"]["x"] == "element" and summary["units"]["coupling"] == "F_el/a0"
    # the catalogue and the figures come with the fields (side loading: the precursors too)
    for name in ("events.csv", "fronts.csv", "precursors.csv", "spacetime.png"):
        assert (out / name).is_file(), (name, sorted(p.name for p in out.iterdir()))
    assert "events" in summary["fronts"] and "threshold" in summary["fronts"]


@pytest.mark.parametrize("edit, words", [
    (("n_elements = 5", "n_elements = 0"), "n_elements = 0 is out of range"),
    (("coupling = 2.0", "coupling = -1.0"), "coupling = -1 is out of range"),
    (("edge_stiffness = 0.4", "edge_stiffness = -0.4"), "edge_stiffness = -0.4 is out of range"),
    (('kind = "side"', 'kind = "spring"'), "drive.kind = 'spring' is not allowed with an "
                                           "[interface] table"),
    (("every = 0.5", "every = 1e-9"), "every = 1e-09 with n_elements = 5 records"),
    (("damping = 0.1", "damping = 0.1\nwidth = 3"), "unknown key(s) interface.width"),
])
def test_bad_interface_protocol_is_refused_in_one_line(tmp_path: Path, edit: tuple[str, str],
                                                       words: str) -> None:
    out = tmp_path / "out"
    r = runner.invoke(app, ["simulate", str(_write(tmp_path, PROTO.replace(*edit))), "--out",
                            str(out)])
    assert r.exit_code == 2, r.output
    assert words in r.output
    assert len(r.output.strip().splitlines()) == 1
    assert not out.exists()
