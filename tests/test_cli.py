"""CLI: ``static``, ``steady`` and ``reproduce`` (parse, call the library, print; bad input is one
line and exit code 2)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.theory.static import static_friction
from dryfriction.theory.steady import steady_friction

runner = CliRunner()


def invoke(*args: str):
    return runner.invoke(app, list(args))


def test_static_json_matches_library():
    r = invoke("static", "--eps", "0.04", "--alpha", "0.13", "--T", "0", "1", "10", "100",
               "--json")
    assert r.exit_code == 0, r.output
    got = json.loads(r.stdout)
    assert got["T"] == [0.0, 1.0, 10.0, 100.0]
    assert got["eps"] == 0.04 and got["alpha"] == 0.13 and got["load"] == 0.0
    assert got["creep"] == "log"
    assert got["mu_s"] == static_friction(np.array(got["T"]), 0.04, 0.13).tolist()
    assert got["mu_s"][0] == 1.0


def test_static_repeated_flag_equals_several_values():
    a = json.loads(invoke("static", "--eps", "0.02", "--T", "1", "10", "--json").stdout)
    b = json.loads(invoke("static", "--eps", "0.02", "--T", "1", "--T", "10", "--json").stdout)
    c = json.loads(invoke("static", "--T", "1", "10", "--eps", "0.02", "--json").stdout)
    assert a == b == c
    assert len(a["mu_s"]) == 2


def test_static_load_and_creep_are_passed_through():
    r = invoke("static", "--eps", "0.03", "--T", "5", "50", "--load", "0.4",
               "--creep", "eyring-nabarro", "--json")
    assert r.exit_code == 0, r.output
    got = json.loads(r.stdout)
    want = static_friction(np.array([5.0, 50.0]), 0.03, 0.13, "eyring-nabarro", 0.4)
    assert got["mu_s"] == want.tolist()
    assert got["load"] == 0.4 and got["creep"] == "eyring-nabarro"


def test_steady_json_matches_library():
    r = invoke("steady", "--eps", "0.05", "--u", "0.01", "0.1", "1", "100", "--json")
    assert r.exit_code == 0, r.output
    got = json.loads(r.stdout)
    assert got["mu_d"] == steady_friction(np.array(got["u"]), 0.05, 0.13).tolist()
    r2 = invoke("steady", "--eps", "0.05", "--u", "1", "--creep", "eyring-nabarro", "--json")
    assert json.loads(r2.stdout)["mu_d"] == [float(steady_friction(1.0, 0.05, 0.13,
                                                                    "eyring-nabarro"))]


def test_tables_without_json():
    r = invoke("static", "--eps", "0.04", "--T", "25")
    assert r.exit_code == 0
    assert f"{float(static_friction(25.0, 0.04)):.10g}" in r.stdout
    r = invoke("steady", "--eps", "0.04", "--u", "0.1")
    assert r.exit_code == 0
    assert f"{float(steady_friction(0.1, 0.04)):.10g}" in r.stdout


@pytest.mark.parametrize(
    "args, word",
    [
        (["static", "--eps", "-0.01", "--T", "1"], "eps"),
        (["static", "--eps", "0.04", "--alpha", "1.2", "--T", "1"], "alpha"),
        (["static", "--eps", "0.04", "--T", "-1"], "T"),
        (["static", "--eps", "0.04", "--T", "1", "-1"], "T"),
        (["static", "--eps", "0.04", "--T", "1", "--load", "1"], "load"),
        (["static", "--eps", "0.04", "--T", "1", "--creep", "power"], "creep"),
        (["static", "--eps", "0.04", "--T", "nan"], "T"),
        (["static", "--eps", "0.04", "--T", "abc"], "--T"),
        (["static", "--eps", "0.04"], "--T"),
        (["steady", "--eps", "0.04", "--u", "0"], "u"),
        (["steady", "--eps", "-1", "--u", "1"], "eps"),
        (["steady", "--eps", "0.04", "--alpha", "0", "--u", "1"], "alpha"),
        (["steady", "--eps", "0.04", "--u", "1", "--bogus"], "bogus"),
    ],
)
def test_bad_input_is_one_line_exit_2(args, word):
    r = runner.invoke(app, args)
    assert r.exit_code == 2, r.output
    lines = r.output.strip().splitlines()
    assert len(lines) == 1, r.output
    assert lines[0].startswith("error:") and word in lines[0]
    assert r.stdout == ""


def test_reproduce_refuses_an_existing_file(tmp_path):
    target = tmp_path / "taken"
    target.write_text("not a folder")
    r = invoke("reproduce", "--out", str(target))
    assert r.exit_code == 2
    assert len(r.output.strip().splitlines()) == 1 and "existing file" in r.output
    assert target.read_text() == "not a folder"
    assert [p.name for p in tmp_path.iterdir()] == ["taken"]


def test_reproduce_refuses_a_missing_parent(tmp_path):
    r = invoke("reproduce", "--out", str(tmp_path / "no" / "such" / "dir"))
    assert r.exit_code == 2
    assert len(r.output.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


def test_reproduce_writes_the_folder(tmp_path):
    out = tmp_path / "results"
    r = invoke("reproduce", "--out", str(out))
    assert r.exit_code == 0, r.output
    names = {p.name for p in out.iterdir()}
    assert {f"fig{i}.png" for i in range(1, 7)} <= names
    assert {"static_friction.csv", "steady_friction.csv", "summary.json", "report.html"} <= names
    s = json.loads((out / "summary.json").read_text())
    assert f"{s['dieterich_C_asymptotic']:.4f}" in r.stdout


def test_error_lines_keep_square_brackets():
    # messages are plain text: a table name such as [drive] must not vanish as Rich markup
    import typer

    from dryfriction.cli import cli_errors

    @cli_errors
    def boom() -> None:
        raise ValueError("[drive] stiffness = -1 is out of range")

    app = typer.Typer()
    app.command()(boom)
    res = CliRunner().invoke(app, [])
    assert res.exit_code == 2
    assert "[drive] stiffness = -1" in res.output
