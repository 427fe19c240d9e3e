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
    """No option default of ``fit``, ``simulate``, ``compare``, ``reproduce`` is written in
    the command line: each is the one declared in :data:`dryfriction.app.options.OPTIONS`."""
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
