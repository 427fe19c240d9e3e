"""``fit RECORD --json`` as a user pipes it: standard output is one JSON document (the
detected load program goes to standard error), and the program's table is printed whole on a
pipe (80 columns) without it. Found by a new user's trial: the program's table came first on
standard output, so ``| python -m json.tool`` failed, and it was wrapped at 80 columns."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

SHARED = (Path(__file__).resolve().parents[2] / "examples" / "data" / "lab"
          / "sepiolite_velstep_0.2-2um_s.txt")


def _fit(tmp_path: Path, *extra: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "COLUMNS": "80", "TERM": "dumb"}
    return subprocess.run([sys.executable, "-m", "dryfriction.cli", "fit", str(SHARED), "--model",
                           "rsf", "--out", str(tmp_path / "o"), "--no-figure", *extra],
                          capture_output=True, text=True, env=env, timeout=120)


@pytest.mark.slow
@pytest.mark.ci
def test_json_on_stdout_is_one_document_and_the_program_table_is_whole(tmp_path: Path) -> None:
    # mistakes: the program table on stdout with --json; the table wrapped at the pipe's width
    r = _fit(tmp_path, "--json")
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    assert doc["model"] == "rsf" and len(doc["segments"]) == 2
    head = [ln for ln in r.stderr.splitlines() if "t_start (s)" in ln]
    assert len(head) == 1 and "velocity (m/s)" in head[0] and "normal" in head[0]
