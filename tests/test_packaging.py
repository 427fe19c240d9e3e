"""Packaging: the wheel ships every package and the examples, the examples can be found and
copied, and the sweep extra (Dask, xarray) is optional with a one-line message when missing."""

from __future__ import annotations

import os
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.io.examples import copy_examples, example_files, examples_path
from dryfriction.sweeps.sweep import SWEEP_MODULES, parse_sweep, run_sweep
from dryfriction.validation import MissingExtraError

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())


def test_every_source_package_is_listed_for_the_wheel() -> None:
    # the package list is explicit (the examples come from outside src/): a new subpackage
    # left off it would be missing from every installed copy
    listed = set(PYPROJECT["tool"]["setuptools"]["packages"])
    found = {".".join(p.parent.relative_to(SRC).parts) for p in SRC.rglob("__init__.py")}
    assert found <= listed
    # data-only packages: the examples, and the model's description (docs/model.md)
    assert listed - found == {"dryfriction.docs", "dryfriction.examples",
                              "dryfriction.examples.data",
                              "dryfriction.examples.data.lab",
                              "dryfriction.examples.gallery"}


def test_formulas_need_no_sweep_packages() -> None:
    # a user who installs without [sweep] gets the formulas and the CLI; a module that
    # imported dask or xarray at the top would break here
    code = (
        "import sys\n"
        f"for m in {SWEEP_MODULES!r}: sys.modules[m] = None\n"
        "import dryfriction as df, dryfriction.sweeps.sweep, dryfriction.cli\n"
        "print(float(df.static_friction(10.0, eps=0.04)))\n"
        "from dryfriction.cli import main\n"
        "sys.exit(main(['trap', '--alpha', '0.13', '--json']))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    assert float(r.stdout.splitlines()[0]) > 1.0  # aged contacts: mu_s > F_el


@pytest.mark.parametrize("blocked", SWEEP_MODULES)
def test_sweep_without_the_extra_is_one_line(blocked: str, tmp_path: Path,
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, blocked, None)  # as if not installed
    out = tmp_path / "sw"
    res = CliRunner().invoke(app, ["sweep", str(ROOT / "examples" / "phase_diagram.toml"),
                                   "--out", str(out)])
    assert res.exit_code == 2
    lines = res.output.strip().splitlines()
    assert len(lines) == 1 and blocked in lines[0] and "dryfriction[sweep]" in lines[0]
    assert not out.exists()
    spec = parse_sweep(tomllib.loads((ROOT / "examples" / "phase_diagram.toml").read_text()))
    with pytest.raises(MissingExtraError, match=r"pip install 'dryfriction\[sweep\]'"):
        run_sweep(spec, lambda p: {}, tmp_path / "api")
    assert not (tmp_path / "api").exists()


def test_examples_are_found_and_copied_whole(tmp_path: Path) -> None:
    files = example_files()
    assert {"velocity_step.toml", "data/synthetic_static_paper.csv",
            "gallery/plot_static_friction.py"} <= set(files)
    assert not any("__pycache__" in f for f in files)
    copied = copy_examples(tmp_path / "ex")
    assert copied == files
    for rel in files:  # byte for byte, every one
        assert (tmp_path / "ex" / rel).read_bytes() == (examples_path() / rel).read_bytes()
    res = CliRunner().invoke(app, ["examples", "--copy", str(tmp_path / "taken")])
    assert res.exit_code == 0
    # a second copy into a folder holding a file we did not write is refused, untouched
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "velocity_step.toml").write_text("mine")
    res = CliRunner().invoke(app, ["examples", "--copy", str(tmp_path / "mine")])
    assert res.exit_code == 2
    assert (tmp_path / "mine" / "velocity_step.toml").read_text() == "mine"
    assert os.listdir(tmp_path / "mine") == ["velocity_step.toml"]


@pytest.mark.slow
def test_wheel_ships_the_package_and_the_examples(tmp_path: Path) -> None:
    # pip builds in an isolated environment: needs setuptools from the package index (or a
    # cache), as any install from source does
    r = subprocess.run([sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "-q",
                        "-w", str(tmp_path)], capture_output=True, text=True, timeout=300)
    if r.returncode and not os.environ.get("CI") and "Could not" in r.stderr:
        pytest.skip(f"cannot build a wheel here (no setuptools reachable): {r.stderr[-200:]}")
    assert r.returncode == 0, r.stderr
    (wheel,) = tmp_path.glob("dryfriction-*.whl")
    names = set(zipfile.ZipFile(wheel).namelist())
    expected = {f"dryfriction/examples/{rel}" for rel in example_files()}
    assert expected <= names
    for mod in ("dryfriction/io/examples.py", "dryfriction/theory/static.py",
                "dryfriction/cli/examples.py", "dryfriction/ensemble/kernel.py"):
        assert mod in names
    assert not any(n.startswith("tests/") or n.endswith((".pyc", ".nbc", ".nbi"))
                   for n in names)
    # installed from the wheel, the examples are found as package data (not the checkout's)
    site = tmp_path / "site"
    zipfile.ZipFile(wheel).extractall(site)
    r = subprocess.run([sys.executable, "-c", "from dryfriction.io.examples import "
                        "examples_path, example_files; print(examples_path()); "
                        "print(len(example_files()))"],
                       capture_output=True, text=True, timeout=120, cwd=tmp_path,
                       env={**os.environ, "PYTHONPATH": str(site)})
    assert r.returncode == 0, r.stderr
    where, count = r.stdout.split()
    assert Path(where) == site / "dryfriction" / "examples"
    assert int(count) == len(example_files())
    # the model's description, which the help and the docstrings cite, comes with the wheel
    assert "dryfriction/docs/model.md" in names
    r = subprocess.run([sys.executable, "-c", "import sys; from dryfriction.cli import main; "
                        "sys.exit(main(['model', '--path']))"],
                       capture_output=True, text=True, timeout=120, cwd=tmp_path,
                       env={**os.environ, "PYTHONPATH": str(site)})
    assert r.returncode == 0, r.stderr
    assert Path(r.stdout.strip()) == site / "dryfriction" / "docs" / "model.md"
    assert ((site / "dryfriction" / "docs" / "model.md").read_bytes()
            == (SRC / "dryfriction" / "docs" / "model.md").read_bytes())
    meta = zipfile.ZipFile(wheel).read(
        next(n for n in names if n.endswith("METADATA"))).decode()
    requires = [line for line in meta.splitlines() if line.startswith("Requires-Dist:")]
    core = [line for line in requires if "extra ==" not in line]
    assert not any("dask" in line or "xarray" in line for line in core)
    assert any("xarray" in line and "extra == \"sweep\"" in line for line in requires)


def test_model_command_prints_the_shipped_description() -> None:
    """``dryfriction model`` prints the file the docs site includes (not a stale copy), and
    the site's page includes that one file rather than keeping a second text."""
    res = CliRunner().invoke(app, ["model"])
    assert res.exit_code == 0, res.output
    text = (SRC / "dryfriction" / "docs" / "model.md").read_text(encoding="utf-8")
    assert res.stdout == text and "Very strong pinning" in text
    page = (ROOT / "docs" / "model.md").read_text()
    assert "{include} ../src/dryfriction/docs/model.md" in page


def test_help_and_readme_cite_only_what_an_install_has() -> None:
    """Every pointer to the model's description in --help and the README names something a
    ``pip install`` has (``dryfriction model``, the package's docs/model.md), not a file of
    the source checkout: the old help's "docs/model.md" existed only in a clone."""
    runner = CliRunner()
    helps = [runner.invoke(app, [cmd, "--help"]).stdout for cmd in ("trap", "simulate")]
    assert all("dryfriction model" in h and "docs/model.md" not in h for h in helps)
    readme = (ROOT / "README.md").read_text()
    assert "dryfriction model" in readme
