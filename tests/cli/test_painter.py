"""The painter: a process forked at a figure command's start that draws the figure (issue 12).

Every check that forks runs in a fresh interpreter: the test process has threads and modules
of its own, and a fork must start from a single-threaded process (``painter.start`` refuses
otherwise). What could go wrong: the figure silently drawn here instead (no speed-up; caught
by the pid checks), a different figure (caught by comparing bytes with the in-process one), an
error lost or changed on the way back, a painter left running after the command, a dead
painter hanging the command.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from dryfriction.cli import painter

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _environ(**extra: str) -> dict[str, str]:
    """This process's environment with the checkout's package first on the path, the painter
    not turned off, and ``extra``."""
    import dryfriction

    src = str(Path(dryfriction.__file__).resolve().parents[1])
    path = os.pathsep.join([src, *filter(None, [os.environ.get("PYTHONPATH")])])
    env = {k: v for k, v in os.environ.items() if k != painter.ENV}
    return {**env, "MPLBACKEND": "Agg", "PYTHONPATH": path, **extra}


def _python(code: str, cwd: Path) -> dict:  # type: ignore[type-arg]
    """Run ``code`` in a fresh interpreter; return the JSON object it prints last."""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=cwd,
                       env=_environ(), timeout=120)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout.strip().splitlines()[-1])  # type: ignore[no-any-return]


@pytest.mark.parametrize(("argv", "expected"), [
    (["simulate", "p.toml", "--out", "r"], True),
    (["rsf", "step", "--out", "r"], True),
    (["compare", "p.toml", "--out", "r", "--format", "svg"], True),
    (["simulate", "p.toml", "--out", "r", "--no-figure"], False),
    (["simulate", "--help"], False),
    (["reproduce", "--out", "r"], False),  # draws in its own pool
    (["sweep", "p.toml", "--out", "r"], False),
    (["fit", "d.csv", "--model", "rsf"], False),
    ([], False),
])
def test_only_figure_commands_want_a_painter(argv: list[str], expected: bool,
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(painter.ENV, raising=False)
    assert painter.wanted(argv) is expected
    monkeypatch.setenv(painter.ENV, "0")
    assert painter.wanted(argv) is False


def test_jobs_run_in_the_painter_errors_come_back_and_a_dead_one_is_replaced(
        tmp_path: Path) -> None:
    got = _python(
        "import json, math, os, signal, sys\n"
        "from dryfriction.cli import painter\n"
        "def whoami(payload):\n"
        "    return os.getpid()\n"
        "p = painter.start(preload=())\n"
        "out = {'started': p is not None, 'me': os.getpid()}\n"
        "out['pid'] = p.pid\n"
        "out['ran_in'] = painter.paint(os.getpid)\n"
        "out['sum'] = painter.paint(sum, [1.5, 2.5], start=1)\n"
        "try:\n"
        "    painter.paint(math.sqrt, -1.0)\n"
        "except ValueError as exc:\n"
        "    out['error'] = [type(exc).__name__, str(exc)]\n"
        "out['small_ran_in'] = painter.paint(whoami, b'x' * 10)\n"
        "painter.MAX_PAYLOAD = 100\n"  # a larger job is run here, not sent
        "out['big_ran_in'] = painter.paint(whoami, b'x' * 1000)\n"
        "painter.MAX_PAYLOAD = 64 * 2**20\n"
        "out['unpicklable_ran_in'] = painter.paint(whoami, lambda: None)\n"
        "out['still'] = painter.active() is not None\n"
        "os.kill(p.pid, signal.SIGKILL)\n"
        "out['after_death'] = painter.paint(os.getpid)\n"
        "out['active_after'] = painter.active() is not None\n"
        "try:\n"
        "    os.waitpid(p.pid, os.WNOHANG)\n"
        "    out['reaped'] = False\n"
        "except ChildProcessError:\n"
        "    out['reaped'] = True\n"
        "print(json.dumps(out))\n", tmp_path)
    assert got["started"]
    assert got["ran_in"] == got["pid"] != got["me"]
    assert got["sum"] == 5.0
    assert got["error"] == ["ValueError", "math domain error"]
    assert got["small_ran_in"] == got["pid"]
    assert got["big_ran_in"] == got["me"] and got["still"]
    assert got["unpicklable_ran_in"] == got["me"]
    assert got["after_death"] == got["me"]  # drawn here once the painter died
    assert not got["active_after"] and got["reaped"]


def test_the_painter_is_stopped_when_the_command_fails(tmp_path: Path) -> None:
    got = _python(
        "import json, os\n"
        "from dryfriction.cli import painter\n"
        "pid = None\n"
        "try:\n"
        "    with painter.painting(['simulate', 'p.toml', '--out', 'r']) as p:\n"
        "        pid = p.pid\n"
        "        raise KeyboardInterrupt\n"
        "except KeyboardInterrupt:\n"
        "    pass\n"
        "try:\n"
        "    os.kill(pid, 0)\n"
        "    alive = True\n"
        "except ProcessLookupError:\n"
        "    alive = False\n"
        "print(json.dumps({'pid': pid, 'alive': alive, 'active': painter.active() is not None}))\n",
        tmp_path)
    assert got["pid"] is not None
    assert not got["alive"] and not got["active"]


def test_not_started_in_a_process_with_threads(tmp_path: Path) -> None:
    got = _python(
        "import json, threading\n"
        "from dryfriction.cli import painter\n"
        "e = threading.Event()\n"
        "t = threading.Thread(target=e.wait)\n"
        "t.start()\n"
        "p = painter.start(preload=())\n"
        "e.set()\n"
        "t.join()\n"
        "print(json.dumps({'started': p is not None}))\n", tmp_path)
    assert got == {"started": False}


@pytest.mark.slow
@pytest.mark.parametrize("protocol", ["rsf_velocity_step.toml", "velocity_step.toml"])
def test_the_console_command_draws_in_its_painter_the_same_figure(tmp_path: Path,
                                                                  protocol: str) -> None:
    """``main()`` as the console script runs it (no arguments): a painter is forked, draws
    ``timeseries.png`` byte for byte as this process would, and is gone when main returns;
    the command's own process never imports matplotlib."""
    proto = str(EXAMPLES / protocol)
    code = (
        "import contextlib, io, json, os, sys\n"
        "from dryfriction.cli import main, painter\n"
        "started, ran = [], []\n"
        "start, paint = painter.start, painter.paint\n"
        "def recording_start(*a, **k):\n"
        "    p = start(*a, **k)\n"
        "    started.append(p.pid if p else None)\n"
        "    return p\n"
        "def recording_paint(target, *a, **k):\n"
        "    ran.append(paint(os.getpid))\n"
        "    return paint(target, *a, **k)\n"
        "painter.start, painter.paint = recording_start, recording_paint\n"
        f"sys.argv = ['dryfriction', 'simulate', {proto!r}, '--out', 'painted']\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    rc = main()\n"
        "import psutil\n"
        "print(json.dumps({'rc': rc, 'started': started, 'ran': ran, 'me': os.getpid(),\n"
        "                  'children': len(psutil.Process().children()),\n"
        "                  'matplotlib': 'matplotlib' in sys.modules}))\n")
    got = _python(code, tmp_path)
    assert got["rc"] == 0
    assert got["started"] and got["started"][0] is not None
    assert got["ran"] == got["started"] and got["ran"][0] != got["me"]
    assert got["children"] == 0
    assert got["matplotlib"] is False

    # the same command drawn in-process (no painter): the same bytes
    r = subprocess.run([sys.executable, "-m", "dryfriction.cli", "simulate", proto, "--out",
                        "here"], cwd=tmp_path, capture_output=True, text=True, timeout=120,
                       env=_environ(**{painter.ENV: "0"}))
    assert r.returncode == 0, r.stderr
    painted = (tmp_path / "painted" / "timeseries.png").read_bytes()
    assert painted == (tmp_path / "here" / "timeseries.png").read_bytes()
    assert painted.startswith(b"\x89PNG")
