"""The README's shell lines run as written.

Every ``dryfriction ...`` line of a ```bash, ```sh or ```console block of README.md is run in a
fresh temporary folder holding a copy of ``examples/``, with the environment's ``bin`` first on
the PATH (what the README's set-up lines, ``make demo`` and ``source .venv/bin/activate``,
give), and must exit 0. Blocks fenced as ```text are synopses (``[--json]``, ``DIR``) and are
not run. Lines that take long (:data:`SLOW`) are marked ``slow``: CI runs them in its
``--runslow`` subset (Makefile ``SLOW_SUBSET``), all but the phase diagram; none is skipped.
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
SHELL_BLOCK = re.compile(r"^```(?:bash|sh|console|shell)[ \t]*\n(.*?)^```", re.M | re.S)
# the README's set-up lines: what the test environment already is
SETUP = ("make", "source", ".", "cd")

# marked slow: CI runs all but the phase diagram (a 3 x 3 stick-slip grid on Dask, ~70 s) in
# its --runslow subset (Makefile SLOW_SUBSET); `pytest --runslow` runs every one
SLOW = ("dryfriction fit", "dryfriction compare", "dryfriction simulate", "dryfriction reproduce",
        "dryfriction phase-diagram")


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


LINES = shell_lines(README.read_text())
COMMANDS = [line for line in LINES if line.startswith("dryfriction")]


def test_readme_has_runnable_lines_and_only_known_setup() -> None:
    assert len(COMMANDS) >= 8
    others = [line for line in LINES if not line.startswith("dryfriction")]
    assert all(line.split()[0] in SETUP for line in others), others


def _marks(line: str) -> list[pytest.MarkDecorator]:
    return [pytest.mark.slow] if line.startswith(SLOW) else []


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


def test_python_blocks_run() -> None:
    """Every ```python block of the README runs as written (issue 26: its examples use the
    model objects, so a signature change that breaks them fails here, not in a user's hands)."""
    blocks = PY_BLOCK.findall(README.read_text())
    assert blocks, "no python block found: the fence pattern is stale"
    for i, code in enumerate(blocks):
        exec(compile(code, f"README.md python block {i + 1}", "exec"), {})  # noqa: S102
