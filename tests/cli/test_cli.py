"""CLI: ``static``, ``steady`` and ``reproduce`` (parse, call the library, print; bad input is one
line and exit code 2)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.theory.model import TrapModel
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
    assert got["mu_s"] == static_friction(TrapModel(alpha=0.13, eps=0.04),
                                          np.array(got["T"])).tolist()
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
    want = static_friction(TrapModel(alpha=0.13, eps=0.03, creep="eyring-nabarro"),
                           np.array([5.0, 50.0]), load=0.4)
    assert got["mu_s"] == want.tolist()
    assert got["load"] == 0.4 and got["creep"] == "eyring-nabarro"


def test_static_in_si_computes_the_hold_it_reports():
    # before: --t-w with --hold force printed "hold": "force" and the position hold's numbers
    got = {h: json.loads(invoke("static", "--eps", "0.04", "--t-w", "10", "1000", "--t0", "2",
                                "--load", "0.4", "--hold", h, "--json").stdout)
           for h in ("position", "force")}
    model = TrapModel(eps=0.04)
    for h, out in got.items():
        assert out["hold"] == h
        want = static_friction(model, np.array([5.0, 500.0]), load=0.4, hold=h)
        np.testing.assert_allclose(out["mu_s"], want, rtol=1e-14)
    assert got["force"]["mu_s"][1] < got["position"]["mu_s"][1] - 1e-4


def test_steady_json_matches_library():
    r = invoke("steady", "--eps", "0.05", "--u", "0.01", "0.1", "1", "100", "--json")
    assert r.exit_code == 0, r.output
    got = json.loads(r.stdout)
    assert got["mu_d"] == steady_friction(TrapModel(alpha=0.13, eps=0.05),
                                          np.array(got["u"])).tolist()
    r2 = invoke("steady", "--eps", "0.05", "--u", "1", "--creep", "eyring-nabarro", "--json")
    en = TrapModel(alpha=0.13, eps=0.05, creep="eyring-nabarro")
    assert json.loads(r2.stdout)["mu_d"] == [float(steady_friction(en, 1.0))]


def test_tables_without_json():
    r = invoke("static", "--eps", "0.04", "--T", "25")
    assert r.exit_code == 0
    assert f"{float(static_friction(TrapModel(eps=0.04), 25.0)):.10g}" in r.stdout
    r = invoke("steady", "--eps", "0.04", "--u", "0.1")
    assert r.exit_code == 0
    assert f"{float(steady_friction(TrapModel(eps=0.04), 0.1)):.10g}" in r.stdout


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
    # the closing lines list every file written, the extra figures included
    assert all(name in r.stdout for name in names - {"dryfriction.json"}), r.stdout


def test_error_lines_keep_square_brackets():
    # messages are plain text: a table name such as [drive] must not vanish as Rich markup
    import typer

    from dryfriction.cli.common import cli_errors

    @cli_errors
    def boom() -> None:
        raise ValueError("[drive] stiffness = -1 is out of range")

    app = typer.Typer()
    app.command()(boom)
    res = CliRunner().invoke(app, [])
    assert res.exit_code == 2
    assert "[drive] stiffness = -1" in res.output


# --- one line for every error, never nan/inf with exit 0 (issue 16) ---------------------------


def _main(*args: str):
    """Run the console script's entry (``dryfriction.cli:main``) in a fresh interpreter."""
    import subprocess
    import sys

    code = "import sys; from dryfriction.cli import main; sys.exit(main())"
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True,
                          timeout=120)


@pytest.mark.parametrize(("args", "word"), [
    (["--bogus"], "No such option: --bogus"),
    (["bogus"], "No such command 'bogus'"),
    (["trap", "--alpha", "x"], "'--alpha'"),
    (["trap", "--alpha"], "Option '--alpha' requires an argument"),
    (["simulate"], "Missing argument"),
    (["rsf", "--v-init", "0"], "--v-init = 0 is out of range"),
    (["rsf", "--t1", "1e308"], "--t1 = 1e+308 is out of range"),
    (["steady", "--eps", "0.05", "--creep", "eyring-nabarro", "--u", "1e-9"],
     "beyond the Eyring-Nabarro law's range"),
])
@pytest.mark.slow
def test_usage_errors_are_one_line_through_main(args, word):
    # catches Click's 5-line usage box and tracebacks (ZeroDivisionError for --v-init 0)
    r = _main(*args)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and word in lines[0], r.stderr
    assert r.stdout == ""


def test_help_still_works_through_main():
    r = _main("steady", "--help")
    assert r.returncode == 0 and "--eps" in r.stdout and r.stderr == ""


_BASE = {
    "trap": ["trap"],
    "static": ["static", "--eps", "0.04", "--T", "10"],
    "steady": ["steady", "--eps", "0.04", "--u", "0.1"],
    "stability": ["stability", "--eps", "0.04", "--u", "0.1"],
    "rsf": ["rsf", "--t1", "1", "--t2", "1", "--hold-time", "1"],
}
_NUMERIC = [("trap", "--alpha")] + [("static", o) for o in ("--eps", "--T", "--alpha", "--load")] \
    + [("steady", o) for o in ("--eps", "--u", "--alpha")] \
    + [("stability", o) for o in ("--eps", "--u", "--alpha", "--M", "--eta")] \
    + [("rsf", o) for o in ("--a", "--b", "--dc", "--mu0", "--v0", "--stiffness", "--damping",
                            "--mass", "--v1", "--v2", "--t1", "--t2", "--hold-time", "--v-init",
                            "--rtol")]


@pytest.mark.slow
@pytest.mark.parametrize(("command", "option"), _NUMERIC)
def test_every_numeric_option_gives_finite_numbers_or_one_line(command, option):
    # 0, -1, nan, inf, 1e308, 1e-308 in every numeric option: exit 0 with finite numbers or
    # exit 2 with one line (before: nan, inf, RuntimeError, ZeroDivisionError, a dropped segment)
    import math

    for value in ("0", "-1", "nan", "inf", "1e308", "1e-308"):
        args = list(_BASE[command])
        if option in args:
            args[args.index(option) + 1] = value
        else:
            args += [option, value]
        r = runner.invoke(app, [*args, "--json"])
        if r.exit_code == 0:
            numbers = json.loads(r.stdout)
            flat = [v for v in numbers.values() if isinstance(v, float)]
            flat += [x for v in numbers.values() if isinstance(v, list) for x in v
                     if isinstance(x, float)]
            # (null is the stability command's "no onset frequency": stable for every K)
            assert all(math.isfinite(x) for x in flat), (args, r.stdout)
        else:
            assert r.exit_code == 2, (args, r.output)
            assert len(r.stderr.strip().splitlines()) == 1, (args, r.stderr)
