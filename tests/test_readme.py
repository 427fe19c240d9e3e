"""The shell lines and Python of the README and of the documentation's pages run as written.

Every ``dryfriction ...`` line of a ```bash, ```sh or ```console block of README.md and of every
Markdown page under docs/ is run (once, however many pages show it) in a fresh temporary folder
holding a copy of ``examples/``, with the environment's ``bin`` first on the PATH (what the
set-up lines, ``pip install .``, ``make demo`` and ``source .venv/bin/activate``, give), and
must exit 0. Blocks fenced as ```text are synopses (``[--json]``, ``DIR``) and are not run.
Lines that take long (:data:`SLOW`) are marked ``slow``; all but the phase diagram and the
precursor study (:data:`NOT_IN_CI`) are marked ``ci`` too, and ``make test`` (CI) runs them;
none is skipped. Every ```python
block of the same files runs too.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
# the documentation's own pages (docs/changelog.md and docs/model.md only include other files)
PAGES = [README, *sorted(p for p in (ROOT / "docs").rglob("*.md")
                         if not {"_build", "generated", "auto_examples"} & set(p.parts))]
SHELL_BLOCK = re.compile(r"^```(?:bash|sh|console|shell)[ \t]*\n(.*?)^```", re.M | re.S)
# the set-up lines: what the test environment already is
SETUP = ("make", "source", ".", "cd", "pip")

# marked slow: CI runs all but NOT_IN_CI (marked ci: make test's --with-ci); `pytest --runslow`
# runs every one
SLOW = ("dryfriction fit", "dryfriction compare", "dryfriction simulate", "dryfriction reproduce",
        "dryfriction phase-diagram", "dryfriction sweep",
        "python examples/interface_precursors.py")
# the phase diagram (a 3 x 3 stick-slip grid on Dask, ~70 s) and the interface's precursor study
# (three chain runs, ~7 min)
NOT_IN_CI = ("dryfriction phase-diagram", "python examples/interface_precursors.py")


def shell_lines(text: str) -> list[str]:
    """Commands of the shell blocks: continuations joined, ``$`` prompts and comments gone."""
    lines: list[str] = []
    for block in SHELL_BLOCK.findall(text):
        pending = ""
        for raw in block.splitlines():
            line = raw.rstrip()
            if line.startswith("$ "):
                line = line[2:]
            if line.endswith("\\"):
                pending += line[:-1] + " "
                continue
            line = pending + line
            pending = ""
            words = shlex.split(line, comments=True)
            if words:
                lines.append(shlex.join(words))
    return lines


def test_shell_lines_parser() -> None:
    text = ("```bash\nmake demo   # set-up\ndryfriction fit a.csv \\\n    --out f/   # or --x\n"
            "```\n```text\ndryfriction trap [--json]\n```\n```console\n$ dryfriction -h\n```\n")
    assert shell_lines(text) == ["make demo", "dryfriction fit a.csv --out f/", "dryfriction -h"]


LINES = [line for page in PAGES for line in shell_lines(page.read_text())]
# each command once, in the order first shown
# the package's commands, and the example scripts a page tells the reader to run
RUNNABLE = ("dryfriction", "python examples/")
COMMANDS = list(dict.fromkeys(line for line in LINES if line.startswith(RUNNABLE)))


def test_readme_has_runnable_lines_and_only_known_setup() -> None:
    readme = [line for line in shell_lines(README.read_text()) if line.startswith("dryfriction")]
    # the README's command-line example: simulate, record, fit
    assert [line.split()[1] for line in readme] == ["simulate", "record", "fit"]
    assert len(COMMANDS) >= 30
    others = [line for line in LINES if not line.startswith(RUNNABLE)]
    assert all(line.split()[0] in SETUP for line in others), others


def test_pages_name_only_files_a_clone_has() -> None:
    """A path in a runnable line exists in a clone (a line that read ``../shared/...`` failed
    there), and no page points outside the repository."""
    for page in PAGES:
        text = page.read_text()
        assert "../shared" not in text, page.name
        for line in shell_lines(text):
            for word in line.split():
                if word.startswith("examples/") and "." in word.rsplit("/", 1)[-1]:
                    assert (ROOT / word).exists(), f"{page.name}: {word} is not in the clone"
        # a Markdown link to a file of the repository leads to one (GitHub shows the README
        # and the pages with these links; the site's build checks its own)
        for target in re.findall(r"\]\(([^)#:\s]+)(?:#[^)]*)?\)", text):
            path = (page.parent / target).resolve()
            if target.endswith((".rst", ".md", ".png")) and "auto_examples" not in target:
                assert path.exists(), f"{page.relative_to(ROOT)} links to {target}: not there"


def test_readme_fits_a_screen_and_pages_carry_no_tracker_numbers() -> None:
    assert len(README.read_text().splitlines()) <= 150
    issue = re.compile(r"\b(?:issue|issues)\s+\d+", re.IGNORECASE)
    for page in [*PAGES, ROOT / "CHANGELOG.md", ROOT / "src" / "dryfriction" / "docs" / "model.md"]:
        hit = issue.search(page.read_text())
        assert hit is None, f"{page.relative_to(ROOT)}: {hit.group(0)!r}"


def _marks(line: str) -> list[pytest.MarkDecorator]:
    if not line.startswith(SLOW):
        return []
    return [pytest.mark.slow] + ([] if line.startswith(NOT_IN_CI) else [pytest.mark.ci])


@pytest.mark.parametrize("line", [pytest.param(c, marks=_marks(c), id=c[:60]) for c in COMMANDS])
def test_readme_line_exits_0(line: str, tmp_path: Path) -> None:
    shutil.copytree(ROOT / "examples", tmp_path / "examples",
                    ignore=shutil.ignore_patterns("__pycache__"))
    bindir = Path(sys.executable).parent
    if not (bindir / "dryfriction").exists():
        pytest.skip(f"no dryfriction script beside {sys.executable} (pip install -e .)")
    env = {**os.environ, "PATH": f"{bindir}{os.pathsep}{os.environ.get('PATH', '')}",
           "MPLBACKEND": "Agg"}
    r = subprocess.run(["bash", "-c", line], cwd=tmp_path, env=env, capture_output=True,
                       text=True, timeout=300, stdin=subprocess.DEVNULL)
    assert r.returncode == 0, f"{line!r} exited {r.returncode}:\n{r.stderr[-2000:]}"


PY_BLOCK = re.compile(r"^```python[ \t]*\n(.*?)^```", re.M | re.S)


PY_PAGES = [p for p in PAGES if p == README or PY_BLOCK.search(p.read_text())]


@pytest.mark.parametrize("page", PY_PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_python_blocks_run(page: Path) -> None:
    """Every ```python block of the README and of the pages runs as written (its examples use
    the model objects, so a signature change that breaks them fails here, not in a user's
    hands)."""
    blocks = PY_BLOCK.findall(page.read_text())
    if page == README:
        assert blocks, "no python block found: the fence pattern is stale"
    for i, code in enumerate(blocks):
        name = f"{page.relative_to(ROOT)} python block {i + 1}"
        exec(compile(code, name, "exec"), {})  # noqa: S102


def test_how_to_cite_names_this_version() -> None:
    """The README's citation and CITATION.cff name the version pyproject.toml builds (a release
    that forgets them would have users cite the wrong one)."""
    version = re.search(r'^version = "([^"]+)"', (ROOT / "pyproject.toml").read_text(), re.M)
    assert version, "no version in pyproject.toml"
    readme = README.read_text()
    assert f"version {version.group(1)}" in readme
    assert f"version = {{{version.group(1)}}}" in readme
    cff = (ROOT / "CITATION.cff").read_text()
    assert re.search(rf"^version: {re.escape(version.group(1))}$", cff, re.M)
    assert "doi: 10.1051/jp1:1997137" in cff and "doi:10.1051/jp1:1997137" in readme
