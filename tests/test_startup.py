"""Start-up cost: a command imports only what it needs (issue 12).

Each check runs a fresh interpreter (the test process itself has imported everything by now)
and lists the heavy packages it ended up holding. The lists are what the command does not
need: SciPy's optimizers (fitting only), Numba (only when a compiled solver runs), matplotlib
(only when a figure is drawn) and Dask (sweeps only).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
HEAVY = ("matplotlib", "scipy.optimize", "scipy.signal", "scipy.linalg", "numba", "dask",
         "distributed")


def _loaded_after(code: str, cwd: Path, modules: tuple[str, ...] = HEAVY) -> dict[str, object]:
    """Run ``code`` in a fresh interpreter; return which of ``modules`` (default HEAVY) it
    imported and the exit status of the command it ran (``rc``, if the code set one)."""
    probe = (
        "import json, sys\nrc = None\n" + code + "\n"
        f"print(json.dumps({{'loaded': [m for m in {modules!r} if m in sys.modules], "
        "'rc': rc}))"
    )
    import dryfriction

    # the child imports the package under test, whatever the working directory
    src = str(Path(dryfriction.__file__).resolve().parents[1])
    path = os.pathsep.join([src, *filter(None, [os.environ.get("PYTHONPATH")])])
    env = {**os.environ, "MPLBACKEND": "Agg", "PYTHONPATH": path}
    r = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                       cwd=cwd, env=env, timeout=120)
    assert r.returncode == 0, r.stderr
    return {**json.loads(r.stdout.strip().splitlines()[-1]), "stderr": r.stderr}


def test_import_dryfriction_is_light(tmp_path: Path) -> None:
    got = _loaded_after("import dryfriction", tmp_path)
    assert got["loaded"] == []


def test_help_is_light(tmp_path: Path) -> None:
    got = _loaded_after(
        "import contextlib, io\nfrom dryfriction.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    rc = main(['--help'])\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    main(['simulate', '--help'])", tmp_path)
    assert got["rc"] == 0, got["stderr"]
    assert got["loaded"] == []


def test_rsf_protocol_without_figure_imports_nothing_heavy(tmp_path: Path) -> None:
    """A small rate-and-state run (the velocity-step example) needs nothing heavy: its solver
    runs interpreted (no Numba, and no scipy.linalg, which Numba imports), not the trap
    model's stick-slip analysis (scipy.signal), not the optimizers, not matplotlib."""
    proto = EXAMPLES / "rsf_velocity_step.toml"
    got = _loaded_after(
        "import contextlib, io\nfrom dryfriction.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    rc = main(['simulate', {str(proto)!r}, '--out', 'r', '--no-figure'])", tmp_path)
    assert got["rc"] == 0, got["stderr"]
    assert got["loaded"] == []
    assert sorted(p.name for p in (tmp_path / "r").iterdir()) == [
        "dryfriction.json", "summary.json", "timeseries.csv"]


def test_a_json_run_loads_neither_rich_nor_the_other_commands(tmp_path: Path) -> None:
    """Issue 26: ``simulate --json --no-figure`` prints JSON only, so it needs no Rich (a
    tenth of rsfmodel's whole velocity step), and only its own command module is registered
    (:data:`dryfriction.cli.COMMAND_MODULES`): not the fit's, the record's or the sweeps'."""
    proto = EXAMPLES / "rsf_velocity_step.toml"
    others = ("rich", "dryfriction.cli.fitting", "dryfriction.cli.records",
              "dryfriction.cli.record", "dryfriction.cli.sweeps", "dryfriction.cli.examples",
              "dryfriction.records.labsteps", "dryfriction.cli.runs")
    got = _loaded_after(
        "import contextlib, io\nfrom dryfriction.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    rc = main(['simulate', {str(proto)!r}, '--out', 'r', '--no-figure', '--json'])",
        tmp_path, others)
    assert got["rc"] == 0, got["stderr"]
    assert got["loaded"] == ["dryfriction.cli.runs"]


def test_every_command_is_registered_by_the_module_the_map_names() -> None:
    """:data:`dryfriction.cli.COMMAND_MODULES` names, for every command of the full app, the
    module that registers it (a command missing from the map, or mapped to another module,
    would be unknown to a command line that loads only that module)."""
    import typer.main

    from dryfriction.cli import COMMAND_MODULES, app

    commands = typer.main.get_command(app).commands  # type: ignore[attr-defined]
    assert set(commands) == set(COMMAND_MODULES)
    for name, command in commands.items():
        module = command.callback.__wrapped__.__module__
        assert module == f"dryfriction.cli.{COMMAND_MODULES[name]}", name


def test_trap_protocol_without_figure_needs_no_scipy_optimizers(tmp_path: Path) -> None:
    got = _loaded_after(
        "import contextlib, io\nfrom dryfriction.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    rc = main(['simulate', {str(EXAMPLES / 'velocity_step.toml')!r}, '--out', 'r', "
        "'--no-figure'])", tmp_path)
    assert got["rc"] == 0, got["stderr"]
    assert got["loaded"] == ["scipy.linalg", "numba"]  # the compiled trap kernel (and what
    # Numba itself imports)


@pytest.mark.parametrize("figure", [True, False])
def test_no_figure_removes_the_figure_of_a_previous_run(tmp_path: Path, figure: bool) -> None:
    """Re-running into the same folder with --no-figure must not leave the previous run's
    figure beside results it no longer describes; with --figure it is (re)written."""
    from typer.testing import CliRunner

    from dryfriction.cli import app

    runner = CliRunner()
    proto = str(EXAMPLES / "rsf_velocity_step.toml")
    out = tmp_path / "r"
    assert runner.invoke(app, ["simulate", proto, "--out", str(out)]).exit_code == 0
    assert (out / "timeseries.png").is_file()
    flag = "--figure" if figure else "--no-figure"
    r = runner.invoke(app, ["simulate", proto, "--out", str(out), flag])
    assert r.exit_code == 0, r.output
    assert (out / "timeseries.png").is_file() == figure
    assert (out / "timeseries.csv").is_file()


@pytest.mark.slow
def test_warm_compiles_every_kernel_the_examples_use(tmp_path: Path) -> None:
    """After ``python -m dryfriction.warm`` on a fresh copy of the package (no Numba cache),
    no example protocol compiles anything: the install step leaves no compile pause."""
    import shutil

    import dryfriction

    src = tmp_path / "src"
    shutil.copytree(Path(dryfriction.__file__).resolve().parent, src / "dryfriction",
                    ignore=shutil.ignore_patterns("__pycache__"))
    env = {**os.environ, "PYTHONPATH": str(src), "NUMBA_DEBUG_CACHE": "1",
           "MPLBACKEND": "Agg"}

    def run(*args: str) -> str:
        r = subprocess.run([sys.executable, *args], capture_output=True, text=True,
                           cwd=tmp_path, env=env, timeout=600)
        assert r.returncode == 0, r.stderr[-2000:]
        return r.stdout + r.stderr

    assert "data saved" in run("-m", "dryfriction.warm")  # it did compile, into the copy
    for proto in sorted(EXAMPLES.glob("*.toml")):
        if "[sweep]" in proto.read_text():
            continue
        log = run("-m", "dryfriction.cli", "simulate", str(proto), "--out",
                  f"out_{proto.stem}", "--no-figure", "--json")
        assert "data saved" not in log, f"{proto.name} compiled after the warm-up"
