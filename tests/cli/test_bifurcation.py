"""``dryfriction bifurcation``: the known rate-and-state results come out of the command, the
files are whole, bad input is one line and exit 2 before any work."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.io.units import read_rows

runner = CliRunner()


def protocol(tmp_path: Path, law: str, damping: float = 0.0, mass: float = 0.0) -> str:
    p = tmp_path / f"{law}.toml"
    p.write_text(f"""[model]
law = "rsf"
state_law = "{law}"
a = 0.0083
b = 0.0121
dc = 6.1e-6
mu0 = 0.6
v0 = 1.3e-6

[drive]
kind = "spring"
stiffness = 400.0
damping = {damping}
mass = {mass}
segments = [{{velocity = 2e-6, duration = 10.0}}]
""")
    return str(p)


def run(*args: str):  # type: ignore[no-untyped-def]
    return runner.invoke(app, ["bifurcation", *args])


def test_ageing_quasistatic_is_degenerate_and_checked(tmp_path: Path) -> None:
    out = tmp_path / "out"
    r = run(protocol(tmp_path, "ageing"), "--velocities", "2.1e-6,3.7e-5", "--out", str(out),
            "--json", "--check")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert [row["nature"] for row in doc["rows"]] == ["degenerate", "degenerate"]
    assert all("every kick" in row["check"] for row in doc["rows"])
    rows = read_rows(out / "bifurcation.csv")
    assert list(rows[0])[:5] == ["velocity", "K_c", "frequency", "l1", "relative_l1"]
    assert float(rows[0]["K_c"]) == pytest.approx((0.0121 - 0.0083) / 6.1e-6, rel=1e-10)
    assert (out / "bifurcation.png").stat().st_size > 1000
    assert json.loads((out / "bifurcation.json").read_text())["units"]["K_c"].startswith("1/m")


def test_laws_and_inertia(tmp_path: Path) -> None:
    """Slip law quasi-static: degenerate as well (ours; not Gu et al.'s subcritical: their
    finite-kick instability is global, tests/analysis/test_rsf_hopf.py); PRZ subcritical; a mass
    (M = m V^2/Dc = 0.3 at 2 um/s) makes the ageing law supercritical."""
    def natures(law: str, mass: float = 0.0) -> list[str]:
        out = tmp_path / f"{law}{mass}"
        r = run(protocol(tmp_path, law, mass=mass), "--velocities", "2e-6", "--out", str(out),
                "--json", "--no-figure")
        assert r.exit_code == 0, r.output
        return [row["nature"] for row in json.loads(r.stdout)["rows"]]

    assert natures("slip") == ["degenerate"]
    assert natures("prz") == ["subcritical"]
    assert natures("ageing", mass=0.3 * 6.1e-6 / 2e-6**2) == ["supercritical"]


@pytest.mark.parametrize("value,word", [("1e-6,abc", "not a number"), ("0,1e-6", "(0, "),
                                        ("-1e-6", "out of range"), ("2e3", "out of range")])
def test_bad_velocities_one_line_before_any_work(tmp_path: Path, value: str, word: str) -> None:
    out = tmp_path / "out"
    r = run(protocol(tmp_path, "ageing"), "--velocities", value, "--out", str(out))
    assert r.exit_code == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "--velocities" in lines[0] and word in lines[0], r.stderr
    assert not out.exists()


def test_too_many_checks_and_trap_model_without_direct_refused(tmp_path: Path) -> None:
    out = tmp_path / "out"
    many = ",".join(str(1e-6 * (i + 1)) for i in range(13))
    r = run(protocol(tmp_path, "ageing"), "--velocities", many, "--out", str(out), "--check")
    assert r.exit_code == 2 and "at most 12" in r.stderr and not out.exists()
    cv = Path(__file__).resolve().parents[2] / "examples" / "velocity_step.toml"
    r = run(str(cv), "--velocities", "1e-6", "--out", str(out))
    # a trap protocol without the direct effect: no normal form (analysis.trap_hopf); its K_c
    # is finite (stability), the onset frequency is not: the refusal must not say otherwise
    assert r.exit_code == 2 and "model.direct = 0" in r.stderr and not out.exists()
    assert "no finite K_c" not in r.stderr and "omega_c = inf" in r.stderr


@pytest.mark.slow
def test_supercritical_check_columns(tmp_path: Path) -> None:
    out = tmp_path / "out"
    r = run(protocol(tmp_path, "ageing", mass=0.3 * 6.1e-6 / 2e-6**2), "--velocities", "2e-6",
            "--out", str(out), "--check", "--json", "--no-figure")
    assert r.exit_code == 0, r.output
    row = json.loads(r.stdout)["rows"][0]
    assert row["nature"] == "supercritical" and row["check"] == "settled cycles below K_c"
    assert abs(row["check_exponent"] - 0.5) < 0.03 and row["check_exponent_err"] < 0.02
    assert row["check_amp_ratio"] == pytest.approx(1.0, abs=0.03)
    assert "check_exponent[1]" in (out / "bifurcation.csv").read_text().splitlines()[0]


@pytest.mark.slow
def test_subcritical_check_columns(tmp_path: Path) -> None:
    """PRZ law, quasi-static: the check bisects the unstable cycle at three distances and
    reports its branch's exponent (1/2) and its size against the normal form's. The mistake
    this is for: one distance only, with no exponent (a finite threshold that does not shrink
    with d, as the slip law's, would pass for a Hopf point's unstable cycle)."""
    out = tmp_path / "out"
    r = run(protocol(tmp_path, "prz"), "--velocities", "2.3e-6", "--out", str(out), "--check",
            "--json", "--no-figure")
    assert r.exit_code == 0, r.output
    row = json.loads(r.stdout)["rows"][0]
    assert row["nature"] == "subcritical"
    assert row["check"] == "unstable cycle by bisection above K_c"
    assert abs(row["check_exponent"] - 0.5) < 0.03 and row["check_exponent_err"] < 0.01
    assert row["check_amp_ratio"] == pytest.approx(1.0, abs=0.02)


def test_extreme_velocities_are_said_not_crashed(tmp_path: Path) -> None:
    """A vanishing reduced mass (M = 1e-55 at 1e-30 m/s: a fast eigenvalue of 1e55 beside the
    pair) is still found, and degenerate to the method's precision; a huge one (M = 1e11)
    says in its row that K_c lost precision."""
    out = tmp_path / "out"
    r = run(protocol(tmp_path, "ageing", mass=0.1), "--velocities", "1e-30,1e3", "--out",
            str(out), "--json", "--no-figure")
    assert r.exit_code == 0, r.output
    rows = json.loads(r.stdout)["rows"]
    assert rows[0]["nature"] == "degenerate" and rows[0]["note"] == ""
    assert "closed form" in rows[1]["note"]


def test_frequency_is_in_the_unit_the_files_say(tmp_path: Path) -> None:
    """The mistake this is for: the files labelled the frequency Hz while the numbers were the
    angular frequency. Quasi-static ageing law at K_c: omega = (V/Dc) sqrt((b - a)/a) in rad/s
    (Rice & Ruina 1983), i.e. f = omega/(2 pi) in Hz; the number must match the unit the
    JSON gives it."""
    out = tmp_path / "out"
    r = run(protocol(tmp_path, "ageing"), "--velocities", "3.3e-6", "--out", str(out), "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads((out / "bifurcation.json").read_text())
    omega = 3.3e-6 / 6.1e-6 * math.sqrt((0.0121 - 0.0083) / 0.0083)
    unit = doc["units"]["frequency"]
    expected = {"rad/s": omega, "Hz": omega / (2 * math.pi)}[unit]
    assert doc["rows"][0]["frequency"] == pytest.approx(expected, rel=1e-8), unit


def trap_protocol(tmp_path: Path, direct: float = 0.02, mass: float = 1.7,
                  damping: float = 0.03, alpha: float = 0.13, traps: float = 200) -> str:
    """A trap-model protocol with a spring drive (its stiffness and program are not used)."""
    p = tmp_path / f"trap_{direct}_{mass}_{alpha}_{traps}.toml"
    p.write_text(f"""[model]
alpha = {alpha}
eps = 0.04
direct = {direct}

[ensemble]
traps_per_a0 = {traps}
initial = "steady"
initial_velocity = 0.03

[drive]
kind = "spring"
stiffness = 0.05
mass = {mass}
damping = {damping}
segments = [{{velocity = 0.03, slip = 12.0}}]

[output]
every = 1.0
""")
    return str(p)


@pytest.mark.slow
def test_trap_model_rows_are_trap_hopf_in_reduced_units(tmp_path: Path) -> None:
    """Each row is trap_hopf at the reduced velocity with the drive's mass and damping (the
    table's own route: app -> hopf_table; the direct call here), the headers reduced."""
    from dryfriction.analysis.trap_hopf import trap_hopf
    from dryfriction.theory.model import TrapModel

    out = tmp_path / "out"
    r = run(trap_protocol(tmp_path), "--velocities", "0.031,0.27", "--out", str(out),
            "--no-figure")
    assert r.exit_code == 0, r.output
    model = TrapModel(alpha=0.13, eps=0.04, direct=0.02)
    with open(out / "bifurcation.csv") as fh:
        assert fh.readline().strip() == ("velocity[a0/t0],K_c[F_el/a0],frequency[rad/t0],"
                                         "l1[1/a0^2],relative_l1[1],nature")
    rows = read_rows(out / "bifurcation.csv")
    for row, u in zip(rows, (0.031, 0.27), strict=True):
        h = trap_hopf(u, model, 1.7, 0.03)
        assert float(row["velocity"]) == u
        assert float(row["K_c"]) == pytest.approx(h.K_c, rel=1e-12)
        assert float(row["frequency"]) == pytest.approx(h.omega, rel=1e-12)
        assert float(row["l1"]) == pytest.approx(h.l1_x, rel=1e-9)
        assert row["nature"] == h.nature
    doc = json.loads((out / "bifurcation.json").read_text())
    assert doc["units"]["mass"] == "F_el t0^2/a0" and doc["mass"] == 1.7
    from dryfriction.plots.hopf import plot_bifurcation  # the figure's axes say reduced units

    _, axes = plot_bifurcation(doc)
    assert "a_0/t_0" in axes[1].get_xlabel() and "F_{el}/a_0" in axes[0].get_ylabel()


@pytest.mark.parametrize("kwargs,args,word", [
    ({"direct": 0.0}, (), "model.direct = 0"),
    ({"alpha": 0.2}, (), "model.alpha = 0.2"),
    ({"traps": 3000}, ("--check",), "--check: the trap ensemble's check"),
    ({}, ("--velocities", "0.03,0"), "a0/t0"),
], ids=["direct", "alpha", "check_cost", "velocity"])
def test_trap_model_refusals_one_line_before_any_work(tmp_path: Path, kwargs: dict[str, float],
                                                      args: tuple[str, ...], word: str) -> None:
    out = tmp_path / "out"
    vel = () if "--velocities" in args else ("--velocities", "0.03")
    r = run(trap_protocol(tmp_path, **kwargs), *vel, *args, "--out", str(out))
    assert r.exit_code == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and word in lines[0], r.stderr
    assert not out.exists()


def test_trap_check_runs_on_the_protocols_track_and_writes_its_columns(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """--check on a trap protocol calls the ensemble check of each row with the protocol's
    track, mass and damping, and bifurcation.csv carries its columns with their units (the
    check itself is replaced by a stub here: it takes minutes; tests/analysis/
    test_trap_hopf_check.py runs it, slow)."""
    import dryfriction.analysis.hopf_table as table

    seen: list[tuple[float, float, float, float]] = []

    def stub(u, model, hop, track, mass, damping):  # type: ignore[no-untyped-def]
        seen.append((u, track.traps_per_a0, mass, damping))
        return {"check": "stub", "check_distance": 0.03, "check_exponent": 0.5,
                "check_exponent_err": 0.01, "check_amp_ratio": 1.0,
                "check_threshold": math.nan, "check_K_c_shift": -0.01,
                "check_traps_per_a0": track.traps_per_a0}

    monkeypatch.setattr(table, "check_point", stub)
    monkeypatch.setattr(table, "check_cost", lambda hop, u, track: 1.0)
    out = tmp_path / "out"
    r = run(trap_protocol(tmp_path, traps=137), "--velocities", "0.031,0.27", "--out",
            str(out), "--check", "--no-figure")
    assert r.exit_code == 0, r.output
    assert seen == [(0.031, 137.0, 1.7, 0.03), (0.27, 137.0, 1.7, 0.03)]
    head = (out / "bifurcation.csv").read_text().splitlines()[0]
    assert "check_K_c_shift[1]" in head and "check_traps_per_a0[1/a0]" in head
    rows = read_rows(out / "bifurcation.csv")
    assert [row["check"] for row in rows] == ["stub", "stub"]
