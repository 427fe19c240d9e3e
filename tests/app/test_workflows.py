"""Every workflow of the command line is one call of :mod:`dryfriction.app` (issue 26): the
same files with the same contents, the same defaults (declared once, in
:mod:`dryfriction.app.options`), the same refusals.

Each test runs the command (:func:`dryfriction.cli.main`, in this process) and the same
workflow through its one Python call into another folder, and compares what was written (JSON
parsed, less the run's wall time; every other file byte for byte).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from dryfriction import app
from dryfriction.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
VOLATILE = {"wall_s"}  # the run's own wall-clock time: differs between any two runs

TRAP_STEPS = """
[model]
eps = 0.04
mu_el = 0.5
[ensemble]
traps_per_a0 = 100
initial = "steady"
initial_velocity = 0.1
[drive]
kind = "velocity"
segments = [{velocity = 0.1, slip = 0.5}, {velocity = 1.0, slip = 2.0}]
[output]
every_slip = 0.05
"""


def _json(path: Path) -> Any:
    d = json.loads(path.read_text())
    return {k: v for k, v in d.items() if k not in VOLATILE} if isinstance(d, dict) else d


def same_folders(cli_out: Path, py_out: Path, files: list[str],
                 unlike: tuple[str, ...] = ()) -> None:
    """The files a workflow says it wrote are those the command wrote, with the same
    contents (but for the files ``unlike``, which carry the time of the run)."""
    names = {p.name for p in cli_out.iterdir()} - {"dryfriction.json"}
    assert names == set(files) == {p.name for p in py_out.iterdir()} - {"dryfriction.json"}
    for name in files:
        a, b = cli_out / name, py_out / name
        if name in unlike:
            assert a.stat().st_size > 0 and b.stat().st_size > 0, name
        elif name.endswith(".json"):
            assert _json(a) == _json(b), name
        else:
            assert a.read_bytes() == b.read_bytes(), name


def run(*argv: str) -> int:
    return main([str(a) for a in argv])


def test_simulate_rsf_protocol(tmp_path: Path) -> None:
    proto = EXAMPLES / "rsf_velocity_step.toml"
    assert run("simulate", proto, "--out", tmp_path / "cli", "--no-figure") == 0
    done = app.simulate(proto, tmp_path / "py", figure=False)
    assert done.units == "SI" and done.files == ["timeseries.csv", "summary.json"]
    same_folders(tmp_path / "cli", tmp_path / "py", done.files)
    assert done.summary == {**_json(tmp_path / "py" / "summary.json"),
                            "wall_s": done.summary["wall_s"]}


def test_simulate_a_trap_protocol_with_its_figure(tmp_path: Path) -> None:
    proto = tmp_path / "steps.toml"
    proto.write_text(TRAP_STEPS)
    assert run("simulate", proto, "--out", tmp_path / "cli") == 0
    done = app.simulate(proto, tmp_path / "py")
    assert done.units == "reduced" and not done.partial and "timeseries.png" in done.files
    same_folders(tmp_path / "cli", tmp_path / "py", done.files)


@pytest.mark.slow  # the twin's calibration, twice: 47 s at a load of 13 on 2 cores
def test_compare_a_trap_protocol(tmp_path: Path) -> None:
    proto = tmp_path / "steps.toml"
    proto.write_text(TRAP_STEPS)
    assert run("compare", proto, "--out", tmp_path / "cli_c", "--state-law", "slip") == 0
    c = app.compare(proto, tmp_path / "py_c", state_law="slip")
    assert c.files == ["compare.json", "compare.png"] and c.summary["state_law"] == "slip"
    same_folders(tmp_path / "cli_c", tmp_path / "py_c", c.files)


@pytest.mark.slow
def test_fit_csv_files(tmp_path: Path) -> None:
    data = [EXAMPLES / "data" / "synthetic_static_paper.csv",
            EXAMPLES / "data" / "synthetic_steady_paper.csv"]
    assert run("fit", *data, "--out", tmp_path / "cli", "--no-profile") == 0
    done = app.fit(data, tmp_path / "py", profile=False)
    assert isinstance(done, app.FitOutcome) and done.success
    assert done.files == ["fit.json", "fit.png"] and "comparison" in done.report
    assert done.report["model"] == "cv" and done.report["options"]["alpha"] == 0.13
    same_folders(tmp_path / "cli", tmp_path / "py", done.files)


def test_fit_a_laboratory_record(tmp_path: Path) -> None:
    import records_zoo as zoo  # tests/ (the shared generators)
    path = zoo.write(zoo.make_record(0, "up", (), "tab_um"), tmp_path)
    assert run("fit", path, "--model", "rsf", "--out", tmp_path / "cli", "--no-profile") == 0
    done = app.fit(path, tmp_path / "py", model="rsf", profile=False)
    assert isinstance(done, app.RecordFitOutcome) and done.success
    assert {"fit.json", "steps.csv", "record.png", "segments.csv", "step_0.png",
            "steps_summary.png"} == set(done.files)
    same_folders(tmp_path / "cli", tmp_path / "py", done.files)
    assert done.report["options"]["stiffness"] == "record"  # a record's own default


@pytest.mark.slow  # two reproductions: 33 s at a load of 13 on 2 cores
def test_reproduce(tmp_path: Path) -> None:
    assert run("reproduce", "--out", tmp_path / "cli") == 0
    done = app.reproduce(tmp_path / "py")
    assert "fig1.png" in done.files and "report.html" in done.files
    # report.html embeds the build (the commit, the time of the run): its figures and numbers
    # are compared through the files they come from
    same_folders(tmp_path / "cli", tmp_path / "py", done.files, unlike=("report.html",))


@pytest.mark.parametrize("options, line", [
    ({"alpha": 1.5}, "--alpha = 1.5 is out of range"),
    ({"state_law": "auto"}, "--state-law auto is for a laboratory record"),
    ({"fix": ["t0"]}, "--fix 't0': expected name=value"),
    ({"stiffness": "record"}, "--stiffness record is for a laboratory record"),
])
def test_fit_refuses_as_the_command_does(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                         options: dict[str, Any], line: str) -> None:
    data = EXAMPLES / "data" / "synthetic_static_paper.csv"
    flags: list[str] = []
    for k, v in options.items():
        flag = app.OPTIONS["fit"][k].flag
        flags += [flag, *(v if isinstance(v, list) else [str(v)])]
    assert run("fit", data, "--out", tmp_path / "cli", *flags) == 2
    said = capsys.readouterr().err
    with pytest.raises(ValueError) as exc:
        app.fit(data, tmp_path / "py", **options)
    assert line in str(exc.value) and str(exc.value) in " ".join(said.split())
    assert not (tmp_path / "cli").exists() and not (tmp_path / "py").exists()


def test_the_command_line_takes_its_defaults_from_the_app_layer() -> None:
    """No option default of a command with a workflow in :mod:`dryfriction.app` is written in
    the command line: each is the one declared in :data:`dryfriction.app.options.OPTIONS`,
    and every option with a default is declared there (but ``--json``, how to print,
    ``--out`` where it is optional, and the values of the closed forms)."""
    import typer.main

    from dryfriction.cli import app as cli_app

    group = typer.main.get_command(cli_app)
    for workflow, options in app.OPTIONS.items():
        params = {p.name: p for p in group.commands[workflow].params}  # type: ignore[attr-defined]
        for name, option in options.items():
            key = {"fmt": "fmt"}.get(name, name)
            assert key in params, (workflow, name)
            assert params[key].default == option.default, (workflow, name)
            assert option.flag.split("/")[0] in params[key].opts or name == "regularized" \
                or name == "compare", (workflow, name, params[key].opts)
        # hidden: an old name kept for one release (default None: the new name's value)
        own = {n for n, p in params.items() if not p.required and p.param_type_name == "option"
               and not getattr(p, "hidden", False)}
        # --T/--t-w, --u/--V: the inputs themselves (one of the two is required)
        assert own - set(options) <= {"json_out", "out_dir", "out", "T", "t_w", "u", "V"}, \
            (workflow, own - set(options))


def _command_calls() -> dict[str, Any]:
    """Every command of ``dryfriction`` and the one library function it runs (the workflows of
    :mod:`dryfriction.app`; ``examples`` and ``model`` print or copy shipped files, through
    :mod:`dryfriction.io.examples`)."""
    from dryfriction.app import fitting, hopf, ratestate, reading, runs, sweeps, theory
    from dryfriction.io import examples

    return {"simulate": runs.simulate, "compare": runs.compare, "reproduce": runs.reproduce,
            "sweep": sweeps.sweep, "phase-diagram": sweeps.phase_diagram, "fit": fitting.fit,
            "rsf": ratestate.rsf, "record": reading.record, "bifurcation": hopf.bifurcation,
            "trap": theory.trap, "static": theory.static, "steady": theory.steady,
            "stability": theory.stability, "examples": examples.copy_examples,
            "model": examples.model_description}


def test_every_command_is_one_call_of_one_library_function() -> None:
    """Each command's body calls its library function once (read from its source: the name
    its imports bind is that very function), so a Python user runs the same workflow with one
    call; every command with options of its own is a workflow of :data:`app.OPTIONS` (whose
    defaults the test above holds to the command line's). A new command without a function
    here fails."""
    import ast
    import importlib
    import importlib.util
    import inspect
    import textwrap

    import typer.main

    from dryfriction.cli import app as cli_app

    calls = _command_calls()
    group = typer.main.get_command(cli_app)
    assert set(group.commands) == set(calls)  # type: ignore[attr-defined]
    assert set(calls) - set(app.OPTIONS) == {"examples", "model"}
    for command, fn in calls.items():
        body = inspect.unwrap(group.commands[command].callback)  # type: ignore[attr-defined]
        tree = ast.parse(textwrap.dedent(inspect.getsource(body)))
        package = importlib.import_module(body.__module__).__package__
        bound: dict[str, Any] = {}
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                where = importlib.util.resolve_name("." * node.level + (node.module or ""),
                                                    package)
                for a in node.names:
                    bound[a.asname or a.name] = getattr(importlib.import_module(where), a.name)
        n = sum(isinstance(c, ast.Call) and isinstance(c.func, ast.Name)
                and bound.get(c.func.id) is fn for c in ast.walk(tree))
        assert n == 1, (command, fn.__qualname__, n)
        if command in app.OPTIONS:
            assert getattr(app, fn.__name__) is fn, command  # the app layer's own name


# ------------------------------------------------- rsf, record, bifurcation, the closed forms

RSF_PROTOCOL = """
[model]
law = "rsf"
state_law = "ageing"
a = 0.0083
b = 0.0121
dc = 6.1e-6
mu0 = 0.6
v0 = 1.3e-6

[drive]
kind = "spring"
stiffness = 400.0
damping = 0.0
mass = 0.0
segments = [{velocity = 2e-6, duration = 10.0}]
"""


def test_rsf_slide_hold_slide(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A generic slide-hold-slide (no unit factor: a, b, Dc, k, v1 all off 1), with a t2
    short of the reload peak so that the note is said both ways."""
    opts = {"case": "shs", "a": 0.0071, "b": 0.0093, "dc": 7.3e-6, "stiffness": 2.7e3,
            "v1": 3.1e-6, "t1": 4.0, "hold": 23.0, "t2": 0.7}
    argv = [x for k, v in opts.items() for x in (app.OPTIONS["rsf"][k].flag, str(v))]
    assert run("rsf", *argv, "--out", tmp_path / "cli", "--format", "svg") == 0
    said = capsys.readouterr().err
    done = app.rsf(**opts, out=tmp_path / "py", fmt="svg")  # type: ignore[arg-type]
    assert done.units == "SI" and done.files == ["series.csv", "summary.json", "rsf.svg"]
    same_folders(tmp_path / "cli", tmp_path / "py", done.files)
    assert done.summary["case"] == "shs"
    assert done.notes and done.notes[0] in " ".join(said.split())
    # without a folder: the same numbers, nothing written
    bare = app.rsf(**opts)  # type: ignore[arg-type]
    assert bare.out is None and bare.files == []
    assert {k: v for k, v in bare.summary.items() if k != "wall_s"} == \
        _json(tmp_path / "py" / "summary.json")


@pytest.mark.parametrize("options, line", [
    ({"v1": -1e-6}, "--v1 -1e-06 is out of range"),
    ({"t1": 0.0}, "--t1 = 0 is out of range"),
    ({"v1": 0.0}, "--v-init is needed when --v1 is 0"),
])
def test_rsf_refuses_as_the_command_does(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                         options: dict[str, Any], line: str) -> None:
    flags = [x for k, v in options.items() for x in (app.OPTIONS["rsf"][k].flag, str(v))]
    assert run("rsf", *flags, "--out", tmp_path / "cli") == 2
    said = capsys.readouterr().err
    with pytest.raises(ValueError) as exc:
        app.rsf(**options, out=tmp_path / "py")
    assert line in str(exc.value) and str(exc.value) in " ".join(said.split())
    assert not (tmp_path / "cli").exists() and not (tmp_path / "py").exists()


def test_record(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import records_zoo as zoo  # tests/ (the shared generators)
    path = zoo.write(zoo.make_record(1, "shs", (), "tab_um"), tmp_path)
    assert run("record", path, "--json", "--out", tmp_path / "cli") == 0
    printed = json.loads(capsys.readouterr().out)
    done = app.record(path, out=tmp_path / "py")
    assert isinstance(done, app.RecordOutcome) and done.files == ["record.png", "segments.csv"]
    same_folders(tmp_path / "cli", tmp_path / "py", done.files)
    from dryfriction.io.files import to_jsonable

    assert printed == json.loads(json.dumps(to_jsonable(done.report)))
    assert done.report["segments_from"] == "detected" and len(done.steps) >= 2
    # the detected program given back as --segments reads the same steps
    given = app.record(path, segments=done.report["segments_option"])
    assert given.report["segments_from"] == "--segments" and given.out is None
    assert [w.t_change for w in given.steps] == pytest.approx(
        [w.t_change for w in done.steps], rel=1e-9)


def test_bifurcation(tmp_path: Path) -> None:
    proto = tmp_path / "ageing.toml"
    proto.write_text(RSF_PROTOCOL)
    assert run("bifurcation", proto, "--velocities", "2.1e-6,3.7e-5", "--out",
               tmp_path / "cli") == 0
    calls: list[tuple[int, int]] = []
    done = app.bifurcation(proto, [2.1e-6, 3.7e-5, 8.3e-6], tmp_path / "py",
                           progress=lambda i, n: calls.append((i, n)))
    assert calls == [(1, 3), (2, 3), (3, 3)]  # progress after each velocity (a check: ~5-30 s)
    done = app.bifurcation(proto, [2.1e-6, 3.7e-5], tmp_path / "py", force=True)
    assert done.files == ["bifurcation.csv", "bifurcation.json", "bifurcation.png"]
    same_folders(tmp_path / "cli", tmp_path / "py", done.files)
    assert [r["velocity"] for r in done.report["rows"]] == pytest.approx([2.1e-6, 3.7e-5])
    with pytest.raises(ValueError, match="allowed at most"):
        app.bifurcation(proto, [1e-6] * 13, tmp_path / "py2", check=True)
    assert not (tmp_path / "py2").exists()


@pytest.mark.parametrize("command, argv, call", [
    ("trap", ["--alpha", "0.21"], lambda: app.trap(0.21)),
    ("static", ["--eps", "0.037", "--T", "3.3", "170", "--load", "0.27"],
     lambda: app.static(0.037, [3.3, 170.0], load=0.27)),
    ("static", ["--eps", "0.037", "--t-w", "2.3", "70", "--t0", "0.013", "--mu-el", "0.47"],
     lambda: app.static(0.037, t_w=[2.3, 70.0], t0=0.013, mu_el=0.47)),
    ("steady", ["--eps", "0.041", "--u", "0.07", "3.1", "--direct", "0.023"],
     lambda: app.steady(0.041, [0.07, 3.1], direct=0.023)),
    ("steady", ["--eps", "0.041", "--V", "3e-6", "2e-5", "--a0", "1.7e-6", "--t0", "0.011"],
     lambda: app.steady(0.041, V=[3e-6, 2e-5], a0=1.7e-6, t0=0.011)),
    ("stability", ["--eps", "0.043", "--u", "0.3", "2.2", "--M", "0.6", "--eta",
                   "0.17"], lambda: app.stability(0.043, [0.3, 2.2], mass=0.6, damping=0.17)),
])
def test_closed_forms(capsys: pytest.CaptureFixture[str], command: str, argv: list[str],
                      call: Any) -> None:
    """The command's --json is the Python call's values, to the last digit."""
    capsys.readouterr()
    assert run(command, *argv, "--json") == 0
    printed = json.loads(capsys.readouterr().out)
    done = call()
    from dryfriction.io.files import to_jsonable

    assert printed == json.loads(json.dumps(to_jsonable(done.as_dict())))
    assert done.columns or command == "trap"
    assert set(done.columns) <= set(done.units)


@pytest.mark.parametrize("command, argv, call, line", [
    ("static", ["--eps", "0.04"], lambda: app.static(0.04), "give one of --T or --t-w"),
    ("steady", ["--eps", "0.04", "--u", "0.1", "--a0", "1e-6"],
     lambda: app.steady(0.04, [0.1], a0=1e-6), "--a0 convert(s) SI inputs"),
    ("stability", ["--eps", "0.04", "--u", "0.1", "--M", "1"],
     lambda: app.stability(0.04, [0.1], mass=1.0), "--M 1 without --eta is ill posed"),
])
def test_closed_forms_refuse_as_the_commands_do(capsys: pytest.CaptureFixture[str],
                                               command: str, argv: list[str], call: Any,
                                               line: str) -> None:
    assert run(command, *argv) == 2
    said = " ".join(capsys.readouterr().err.split())
    with pytest.raises(ValueError) as exc:
        call()
    assert line in str(exc.value) and str(exc.value) in said


def test_the_trap_model_defaults_are_the_models_own() -> None:
    """An option that sets a trap-model parameter defaults to the model's declared value
    (:data:`dryfriction.theory.model.TRAP_PARAMETERS`), not a copy; likewise the rsf law's
    (:data:`dryfriction.rsf.law.RATE_STATE_PARAMETERS`)."""
    from dryfriction.rsf.law import RATE_STATE_PARAMETERS
    from dryfriction.theory.model import TRAP_PARAMETERS

    checked = 0
    for workflow in ("fit", "trap", "static", "steady", "stability"):
        for name in ("alpha", "creep", "direct", "v_ref"):
            option = app.OPTIONS[workflow].get(name)
            if option is None or (workflow == "fit" and name == "v_ref"):  # fit's is SI, m/s
                continue
            assert option.default == TRAP_PARAMETERS[name].default, (workflow, name)
            checked += 1
    assert checked == 16
    for name in ("state_law", "regularized"):
        assert app.OPTIONS["rsf"][name].default == RATE_STATE_PARAMETERS[name].default
