"""Rate-and-state protocol files (``model.law = "rsf"``) and ``dryfriction simulate`` on them."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.io.protocol import Protocol, RSFProtocol, load_protocol, parse_protocol
from dryfriction.io.units import read_rows

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

STEP = """
[model]
law = "rsf"
state_law = "ageing"
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


def test_rsf_protocol_parses_to_the_parameters() -> None:
    p = parse_protocol(STEP, "step.toml")
    assert isinstance(p, RSFProtocol)
    assert (p.params.a, p.params.b, p.params.dc, p.params.mu0, p.params.v0) == \
        (0.005, 0.01, 1e-5, 0.6, 1e-6)
    assert math.isinf(p.stiffness) and p.params.state_law == "ageing"
    assert p.program.total_time == pytest.approx(10.0 + 30.0)


def test_default_law_is_still_the_trap_model() -> None:
    p = load_protocol(EXAMPLES / "velocity_step.toml")
    assert isinstance(p, Protocol)
    text = (EXAMPLES / "velocity_step.toml").read_text().replace("[model]",
                                                                 '[model]\nlaw = "cv"')
    assert isinstance(parse_protocol(text), Protocol)


def test_kinematic_step_against_closed_forms(tmp_path: Path) -> None:
    """Kinematic velocity step: the jump is a ln(V2/V1) (direct effect, state unchanged) and the
    end is the steady state mu0 + (a - b) ln(V2/V0) (Ruina 1983) - not from the code."""
    f = tmp_path / "step.toml"
    f.write_text(STEP)
    out = tmp_path / "res"
    r = runner.invoke(app, ["simulate", str(f), "--out", str(out), "--json"])
    assert r.exit_code == 0, r.output
    assert {p.name for p in out.iterdir()} == {"timeseries.csv", "summary.json",
                                               "timeseries.png", "dryfriction.json"}
    rows = read_rows(out / "timeseries.csv")
    assert {"t", "x", "v", "mu", "theta"} <= set(rows[0])
    t = np.array([float(r_["t"]) for r_ in rows])
    mu = np.array([float(r_["mu"]) for r_ in rows])
    a, b = 0.005, 0.01
    before = mu[t < 10.0 - 1e-9]
    assert np.allclose(before, 0.6, atol=1e-9)  # steady state at V0
    after = mu[t > 10.0 + 1e-9]
    assert after[0] - 0.6 == pytest.approx(a * math.log(10.0), abs=2e-4)  # one 0.01 s sample
    assert mu[-1] == pytest.approx(0.6 + (a - b) * math.log(10.0), abs=1e-6)  # 30 Dc of slip
    s = json.loads((out / "summary.json").read_text())
    assert s["law"] == "rsf" and s["slip"] == pytest.approx(1e-5 + 3e-4, rel=1e-9)


def test_stick_slip_example_is_finite_and_periodic(tmp_path: Path) -> None:
    p = load_protocol(EXAMPLES / "rsf_stick_slip.toml")
    assert isinstance(p, RSFProtocol)
    assert p.stiffness < p.params.critical_stiffness()  # below k_c: unstable steady sliding
    res = p.run()
    assert np.all(np.isfinite(res.v)) and res.v.max() < 1.0
    fast = res.v > 100 * 1e-6
    events = int(np.sum(fast[1:] & ~fast[:-1]))
    assert events >= 3  # repeated slip events, each with V > 100 V_load


@pytest.mark.parametrize(
    "edit, needle",
    [
        (("mu0 = 0.6", "mu0 = 0.6\nfriction = 1"), "model.friction"),
        (("a = 0.005\n", ""), "model.a is missing"),
        (("dc = 1e-5", "dc = -1e-5"), "in model: dc"),
        (('state_law = "ageing"', 'state_law = "aging"'), "state_law"),
        (('kind = "velocity"', 'kind = "spring"\nstiffness = -3.0'), "in drive: stiffness = -3"),
        (('kind = "velocity"', 'kind = "spring"'), "drive.stiffness is missing"),
        (('kind = "velocity"\n', ""), "drive.kind is missing"),
        (('kind = "velocity"', 'kind = "force"'), "not allowed with model.law = 'rsf'"),
        (('kind = "velocity"', 'kind = "ramp"'), "'velocity', 'force', 'spring'"),
        (("[drive]", "[drive]\ndamping = 0.1"), "drive key(s) damping not allowed"),
        (("velocity = 1e-6, duration", "velocity = 0.0, duration"),
         "segments[0].velocity = 0"),
        (("[output]", "[ensemble]\ntraps_per_a0 = 3\n[output]"), "ensemble"),
        (("every = 0.01", "every = 0.01\nevery_slip = 1.0"), "output.every_slip"),
        (('law = "rsf"', 'law = "rs"'), "model.law"),
    ],
)
def test_bad_rsf_protocol_is_one_line_naming_file_and_key(tmp_path: Path, edit: tuple[str, str],
                                                          needle: str) -> None:
    assert edit[0] in STEP
    f = tmp_path / "bad.toml"
    f.write_text(STEP.replace(*edit))
    with pytest.raises(ValueError, match="bad.toml") as exc:
        load_protocol(f)
    assert needle in str(exc.value)
    out = tmp_path / "res"
    r = runner.invoke(app, ["simulate", str(f), "--out", str(out)])
    assert r.exit_code == 2
    lines = [ln for ln in r.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and "bad.toml" in lines[0] and needle in lines[0], r.output
    assert not out.exists()


def test_runaway_without_damping_is_an_error_not_nan(tmp_path: Path) -> None:
    text = (EXAMPLES / "rsf_stick_slip.toml").read_text().replace("damping = 0.5\n", "")
    f = tmp_path / "runaway.toml"
    f.write_text(text)
    out = tmp_path / "res"
    r = runner.invoke(app, ["simulate", str(f), "--out", str(out)])
    assert r.exit_code == 2
    assert "runaway.toml" in r.output and "damping" in r.output
    assert not out.exists()


def test_old_rsf_file_without_kind_is_one_line_that_tells_the_fix(tmp_path: Path) -> None:
    """Before issue 9 a rate-and-state [drive] had no kind (stiffness absent = kinematic)."""
    f = tmp_path / "old.toml"
    f.write_text(STEP.replace('kind = "velocity"\n', "stiffness = 1e3\n"))
    out = tmp_path / "res"
    r = runner.invoke(app, ["simulate", str(f), "--out", str(out)])
    assert r.exit_code == 2 and not out.exists()
    lines = [ln for ln in r.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and "drive.kind is missing" in lines[0]
    assert "kind = 'spring'" in lines[0] and "'velocity'" in lines[0]


def test_kind_means_the_same_for_both_laws() -> None:
    """kind = "velocity" is the kinematic program, "spring" the spring slider, for both laws."""
    cv_spring = load_protocol(EXAMPLES / "spring_stick_slip.toml")
    assert type(cv_spring.drive).__name__ == "SpringDrive"
    rsf_spring = load_protocol(EXAMPLES / "rsf_velocity_step.toml")
    assert isinstance(rsf_spring, RSFProtocol) and rsf_spring.stiffness == 1e3
    rsf_kin = parse_protocol(STEP)
    assert isinstance(rsf_kin, RSFProtocol) and math.isinf(rsf_kin.stiffness)
    with pytest.raises(ValueError, match="inf"):
        parse_protocol(STEP.replace('kind = "velocity"', 'kind = "spring"\nstiffness = 0.0'))


@pytest.mark.parametrize(
    "output, limit, key",
    [
        ({"every": 1e-300}, "8GiB", "every = 1e-300"),
        ({"every": 1e-9}, "8GiB", "every = 1e-09"),
        ({"t_eval": np.linspace(0.0, 10.0, 10**7)}, "1GiB", "t_eval"),
        # every solver step kept: max_steps bounds the buffers (~ 100 MiB at the default)
        ({}, "10MiB", "max_steps = 1000000"),
    ],
)
def test_simulate_rsf_refuses_what_the_machine_cannot_hold(monkeypatch: pytest.MonkeyPatch,
                                                           output: dict, limit: str,
                                                           key: str) -> None:
    from dryfriction.rsf import RSFOutput, SpringSlider, simulate

    proto = parse_protocol(STEP)
    assert isinstance(proto, RSFProtocol)
    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", limit)
    with pytest.raises(ValueError, match="more than the limit") as exc:
        simulate(proto.params, SpringSlider(proto.program), output=RSFOutput(**output))
    assert key in str(exc.value) and "DRYFRICTION_MEMORY_LIMIT" in str(exc.value)
    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", "4GiB")  # the control: the same run fits
    if not output:
        res = simulate(proto.params, SpringSlider(proto.program), output=RSFOutput())
        assert np.all(np.isfinite(res.mu))
