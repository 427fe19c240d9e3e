"""A run that says when it is ready for a signal: tests that interrupt a command at a chosen
point of its run (the Ctrl-C tests of tests/cli/test_signals.py and tests/sweeps/test_sweep.py).

A signal sent a fixed time after a subprocess starts lands wherever that process happens to be:
on a loaded machine its start-up (imports, ~0.5 s of CPU) took seconds, and the signal landed
there instead of in the work it was meant for. Here the command runs as users run it
(``python -m dryfriction.cli``) with one function wrapped by a ``sitecustomize`` module (Python
imports it at start-up from the ``PYTHONPATH``): when that function first returns, a marker
file appears, and the test counts its delay from then.
"""

from __future__ import annotations

import os
import subprocess
import time
from pathlib import Path

HOOK = r"""
# written by tests/ready_hook.py: the process says when its run is ready for a signal
import importlib.abc, importlib.util, os, sys

_target, _marker = os.environ["DRYFRICTION_TEST_READY"].split("=", 1)
_module, _attr = _target.split(":")
_on_call = os.environ.get("DRYFRICTION_TEST_READY_WHEN") == "call"


def _wrap(mod):
    *path, name = _attr.split(".")
    owner = mod
    for part in path:
        owner = getattr(owner, part)
    func = getattr(owner, name)

    def mark():
        if not os.path.exists(_marker):
            open(_marker, "w").close()

    def ready(*args, **kwargs):
        if _on_call:
            mark()
        try:
            return func(*args, **kwargs)
        finally:
            mark()

    setattr(owner, name, ready)


class _Finder(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path, target=None):
        if name != _module:
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec(name)
        run = spec.loader.exec_module

        def exec_module(mod):
            run(mod)
            _wrap(mod)

        spec.loader.exec_module = exec_module
        return spec


sys.meta_path.insert(0, _Finder())
"""
"""The ``sitecustomize`` module: ``DRYFRICTION_TEST_READY=MODULE:ATTR=FILE`` writes ``FILE`` when
``MODULE.ATTR`` (a function, or a method as ``Class.name``) first returns (first is called, with
``DRYFRICTION_TEST_READY_WHEN=call``), in whichever process of the run calls it."""

STEPPER = "dryfriction.rsf.stepper:compiled"
"""The rate-and-state stepper's kernels are loaded: the long compiled work comes next."""
ENSEMBLE = "dryfriction.ensemble.population:Ensemble.advance"
"""The trap ensemble's first window is done (its kernel loaded)."""
FORK_SERVER = "multiprocessing.forkserver:main"
"""Called (``when="call"``) in a sweep's fork server as it begins to import Dask and the
runner's modules (a second or more of CPU)."""


def ready_env(env: dict[str, str], folder: Path, at: str, marker: Path,
              when: str = "return") -> dict[str, str]:
    """``env`` with the hook (written into ``folder``) on the path, set to write ``marker``
    when ``at`` (``MODULE:ATTR``) first returns (``when="call"``: is first called)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "sitecustomize.py").write_text(HOOK)
    path = os.pathsep.join([str(folder), *filter(None, [env.get("PYTHONPATH")])])
    return {**env, "PYTHONPATH": path, "DRYFRICTION_TEST_READY": f"{at}={marker}",
            "DRYFRICTION_TEST_READY_WHEN": when}


def wait_ready(proc: subprocess.Popen[str], marker: Path, what: str,
               timeout: float = 300.0) -> None:
    """Wait for ``marker``; fail (with the process's standard error, the process killed) if
    the process ends first or ``timeout`` seconds pass."""
    t0 = time.monotonic()
    while not marker.exists():
        if proc.poll() is not None or time.monotonic() - t0 > timeout:
            if proc.poll() is None:
                proc.kill()
            err = proc.communicate()[1] or ""
            raise AssertionError(f"{what} never got ready (exit {proc.returncode}): "
                                 f"{err[-3000:]}")
        time.sleep(0.01)
