"""Ctrl-C and SIGTERM at any moment end every command with 130 / 143 and one line (issue 24).

The mistake these tests are for: a signal handler that raises while Numba boxes a compiled
call's returned arrays (it calls Python to unpickle the array type): a segmentation fault
(exit -11/139) or ``SystemError: CPUDispatcher(...) returned a result with an exception set``
(:mod:`dryfriction.interrupts`). Before the fix: 6 of 15 Ctrl-C trials of the ``rsf`` command
below died by SIGSEGV; every interrupted ``rsf``, ``fit``, ``compare`` and ``reproduce``
printed nothing (Typer turns Ctrl-C into a silent exit 130).

Two kinds of trial, in subprocesses:

* compiled routes (rate-and-state stepper, trap-ensemble kernel, the fit engine's inner
  integrations): the signal at seeded random wall-clock times within the run, whose time is
  mostly spent in compiled code. The times count from the moment the run says it is ready
  (its compiled kernels loaded: a marker file written by a start-up hook, :mod:`ready_hook`),
  not from its start: on a loaded machine the start-up (imports, ~0.5 s of CPU) took several
  seconds of wall time, a signal at a fixed time from the start landed in it, and the test
  failed with no bug;
* every command: the signal at a seeded random call into ``dryfriction`` (counted by a
  profile hook, so that a quick command is hit mid-run whatever the machine's speed).
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from dryfriction import interrupts
from ready_hook import ENSEMBLE, STEPPER, ready_env, wait_ready

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
RECORD = EXAMPLES / "data" / "lab" / "sepiolite_velstep_0.2-2um_s.txt"
CLI = [sys.executable, "-m", "dryfriction.cli"]
RSF_LONG = ["rsf", "--case", "stick-slip", "--t1", "300000", "--stiffness", "250",
            "--damping", "0.5", "--no-figure"]
NAMES = {signal.SIGINT: "Ctrl-C", signal.SIGTERM: "SIGTERM"}


def _env() -> dict[str, str]:
    # no painter, no terminal progress bar; a fault says where it happened
    return {**os.environ, "DRYFRICTION_PAINTER": "0", "PYTHONFAULTHANDLER": "1"}


def _check(code: int, err: str, sig: int, what: str) -> None:
    """Exit 128 + sig, one line on standard error that says the run was interrupted."""
    lines = [line for line in err.splitlines() if line.strip()]
    assert "Traceback" not in err and "SystemError" not in err and "Fatal" not in err, \
        f"{what}: {err[-3000:]}"
    assert code == 128 + sig, f"{what}: exit {code}\n{err[-3000:]}"
    said = [line for line in lines if "interrupted" in line]
    assert len(said) == 1, f"{what}: {lines}"
    # a command that kept something says so in its own line; otherwise the signal is named
    assert said[0].startswith("interrupted:") or NAMES[sig] in said[0], said


def _timed_trials(args: list[str], times: list[float], sigs: list[int], cwd: Path,
                  ready_at: str) -> None:
    """Each trial: the command, and its signal ``delay`` seconds after the run is ready
    (``ready_at``, the function whose first return marks it: :mod:`ready_hook`)."""
    for i, (delay, sig) in enumerate(zip(times, sigs, strict=True)):
        out, marker = cwd / f"run{i}", cwd / f"ready{i}"
        argv = [a.replace("{out}", str(out)) for a in args]
        proc = subprocess.Popen(CLI + argv, cwd=cwd,
                                env=ready_env(_env(), cwd / "hook", ready_at, marker),
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        wait_ready(proc, marker, argv[0])
        time.sleep(delay)
        assert proc.poll() is None, f"{argv} ended before the signal at {delay:.2f} s"
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=120)
        _check(proc.returncode, err, sig,
               f"{argv[0]} {delay:.2f} s after ready ({NAMES[sig]})")


def _seeded(n: int, lo: float, hi: float, seed: int) -> tuple[list[float], list[int]]:
    rng = random.Random(seed)
    times = [rng.uniform(lo, hi) for _ in range(n)]
    sigs = [signal.SIGINT if i % 3 != 2 else signal.SIGTERM for i in range(n)]
    return times, sigs


def _long_trap_protocol(path: Path) -> Path:
    text = (EXAMPLES / "velocity_step.toml").read_text()
    text = text.replace("{velocity = 0.01, slip = 5.0}", "{velocity = 0.01, slip = 60.0}")
    assert "slip = 60.0" in text
    path.write_text(text)
    return path


# ------------------------------------------------------------------ the mechanism, in-process
def test_deferred_holds_a_signal_back_then_delivers_it_once() -> None:
    seen: list[int] = []

    class Stop(Exception):
        pass

    def handler(signum: int, frame: object) -> None:
        seen.append(signum)
        raise Stop

    before = signal.signal(signal.SIGINT, handler)
    try:
        with pytest.raises(Stop):
            with interrupts.deferred():
                signal.raise_signal(signal.SIGINT)
                signal.raise_signal(signal.SIGINT)
                time.sleep(0.01)  # bytecodes run: a handler would have raised here
                assert seen == []
        assert seen == [signal.SIGINT]
        assert signal.getsignal(signal.SIGINT) is handler  # restored
    finally:
        signal.signal(signal.SIGINT, before)


def test_deferred_keeps_the_default_action_and_does_nothing_in_a_thread() -> None:
    before = signal.getsignal(signal.SIGTERM)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    try:
        with interrupts.deferred():  # the default action runs no Python: left in place
            assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL
    finally:
        signal.signal(signal.SIGTERM, before)
    errors: list[BaseException] = []

    def worker() -> None:
        try:
            with interrupts.deferred():
                pass
        except BaseException as exc:  # noqa: BLE001 - signal.signal raises in a thread
            errors.append(exc)

    t = threading.Thread(target=worker)
    t.start()
    t.join()
    assert errors == []


_CRITICAL = """
import os, signal, sys
from dryfriction import interrupts
signal.signal(signal.SIGTERM, signal.SIG_DFL)
with interrupts.deferred(defaults={defaults}):
    os.kill(os.getpid(), signal.SIGTERM)
    print("finished the block", flush=True)
print("after the block", flush=True)
"""


@pytest.mark.parametrize("defaults", [True, False])
def test_deferred_with_defaults_holds_the_default_sigterm_to_the_blocks_end(
        defaults: bool) -> None:
    """The mistake: a results folder's final moves cut by a library user's default SIGTERM
    (``io.files`` commits inside ``deferred(defaults=True)``): the block must finish, then the
    default action end the process (status -15), never run on past the block."""
    proc = subprocess.run([sys.executable, "-c", _CRITICAL.format(defaults=defaults)],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == -signal.SIGTERM
    assert proc.stdout == ("finished the block\n" if defaults else "")


def test_chunked_compiled_stepper_gives_the_one_call_result(monkeypatch) -> None:
    """The compiled stepper runs in chunks (so that an interrupt is acted on between them):
    resumed at every chunk, it must give the single call's steps bit for bit (mistake: a
    resume that restarts the segment or forgets the rejected flag)."""
    from dryfriction.rsf import RateState, stepper
    from dryfriction.rsf.driving import RSFInitial, RSFOutput, SpringSlider, simulate

    model = RateState(a=0.005, b=0.01, dc=1e-5, mu0=0.6, v0=1e-6)
    drive = SpringSlider([{"velocity": 1e-6, "duration": 600.0},
                          {"velocity": 3e-6, "duration": 400.0}], stiffness=250.0, damping=0.5)
    runs = []
    for chunk in (10**9, 401):
        monkeypatch.setattr(stepper, "COMPILED_CHUNK", chunk)
        with stepper.interpreted_steps(0):
            runs.append(simulate(model, drive, RSFInitial(v=1.01e-6), RSFOutput()))
    one, chunked = runs
    assert (one.n_steps, one.n_rejected, one.n_rhs) == \
        (chunked.n_steps, chunked.n_rejected, chunked.n_rhs)
    assert one.n_steps > 10 * 401  # many chunks
    np.testing.assert_array_equal(one.t, chunked.t)
    np.testing.assert_array_equal(one.v, chunked.v)
    np.testing.assert_array_equal(one.theta, chunked.theta)


def test_the_trap_kernel_returns_only_scalars() -> None:
    """The ensemble kernel runs unguarded once loaded (a guard per call would cost a fifth
    of a small run): that is safe only while its result boxes without Python code, i.e. it
    returns scalars, never an array (dryfriction.interrupts)."""
    from numba.core import types

    from dryfriction.ensemble.kernel import advance_window
    from dryfriction.ensemble.population import Ensemble, Initial, Track, TrapModel

    ens = Ensemble(TrapModel(alpha=0.13, eps=0.04), Track(traps_per_a0=50),
                   Initial(kind="steady", velocity=1.0), x0=0.0, age_horizon=10.0)
    ens.advance(0.5, 0.5)
    assert advance_window.overloads
    for sig in advance_window.nopython_signatures:
        ret = sig.return_type
        items = ret.types if isinstance(ret, types.BaseTuple) else (ret,)
        assert all(isinstance(t, (types.Integer, types.Float, types.Boolean)) for t in items), \
            f"advance_window returns {ret}: call it inside interrupts.deferred()"


# ------------------------------------------------------------------ the compiled routes
_DIRECT = r"""
import os, signal, subprocess, sys
from dryfriction.rsf import RateState, stepper
from dryfriction.rsf.driving import RSFInitial, SpringSlider, simulate

def handler(signum, frame):
    raise KeyboardInterrupt

signal.signal(signal.SIGINT, handler)
model = RateState(a=0.005, b=0.01, dc=1e-5, mu0=0.6, v0=1e-6)

def drive(T):
    return SpringSlider([{"velocity": 1e-6, "duration": T}], stiffness=250.0, damping=0.5)

with stepper.interpreted_steps(0):
    simulate(model, drive(100.0), RSFInitial(v=1.01e-6))  # loads the kernels
    # another process sends the signal: a thread could not (the compiled code holds the GIL)
    killer = subprocess.Popen(["sh", "-c", f"sleep {sys.argv[1]}; kill -INT {os.getpid()}"])
    try:
        simulate(model, drive(300000.0), RSFInitial(v=1.01e-6))  # ~1 s compiled
    except KeyboardInterrupt:
        print("interrupted")
        sys.exit(130)
    finally:
        killer.wait()
print("finished")
"""


@pytest.mark.slow
@pytest.mark.parametrize("delay", [0.2, 0.45])
def test_a_signal_during_a_compiled_call_is_raised_after_it(delay: float) -> None:
    """A raising handler (Python's own kind) and a signal that surely lands inside one long
    compiled call. Before the fix: 5 of 5 trials exit 1 with ``SystemError: <function
    _numba_unpickle ...> returned a result with an exception set`` (the handler ran inside
    Numba's boxing of the returned arrays)."""
    proc = subprocess.run([sys.executable, "-c", _DIRECT, str(delay)], capture_output=True,
                          text=True, timeout=120, env=_env())
    assert "Traceback" not in proc.stderr and "SystemError" not in proc.stderr, proc.stderr
    assert proc.returncode == 130 and proc.stdout.strip() == "interrupted", proc.stdout


@pytest.mark.slow
def test_signals_into_the_compiled_rsf_stepper(tmp_path: Path) -> None:
    """Before the fix: 6 of 15 Ctrl-C trials exit -11 (segfault), the others 130 silently.
    The signals fall within the stepper: once its kernels are loaded the run has ~1.1 s of CPU
    left (its 1e6-step cap; measured with the hook, 1.62 s of CPU in all), so 0.05-0.6 s
    after it is ready, on an idle machine as on a loaded one."""
    times, sigs = _seeded(5, 0.05, 0.6, seed=24)
    _timed_trials(RSF_LONG, times, sigs, tmp_path, STEPPER)


@pytest.mark.slow
def test_signals_into_the_compiled_rsf_stepper_many(tmp_path: Path) -> None:
    times, sigs = _seeded(20, 0.05, 0.65, seed=2024)
    _timed_trials(RSF_LONG, times, sigs, tmp_path, STEPPER)


@pytest.mark.slow
def test_signals_into_the_trap_ensemble(tmp_path: Path) -> None:
    proto = _long_trap_protocol(tmp_path / "long.toml")
    # ready at the first window's return (the kernel loaded): ~1.8 s of CPU left of 2.5 s
    times, sigs = _seeded(3, 0.1, 1.2, seed=7)
    _timed_trials(["simulate", str(proto), "--no-figure", "--out", "{out}"], times, sigs,
                  tmp_path, ENSEMBLE)


@pytest.mark.slow
def test_signals_into_a_record_fit(tmp_path: Path) -> None:
    """The fit engine's inner integrations (compiled after the process's interpreted budget):
    before the fix SIGTERM here gave ~370 lines ending in SystemError, exit 1."""
    # ready once the stepper's kernels are loaded (1.6 s of CPU): ~8 s of CPU left
    times, sigs = _seeded(2, 0.1, 2.0, seed=16)
    sigs = [signal.SIGTERM, signal.SIGINT]
    _timed_trials(["fit", str(RECORD), "--model", "rsf", "--no-figure", "--out", "{out}"],
                  times, sigs, tmp_path, STEPPER)


@pytest.mark.slow
def test_signals_into_a_record_fit_many(tmp_path: Path) -> None:
    times, sigs = _seeded(8, 0.05, 2.5, seed=160)
    _timed_trials(["fit", str(RECORD), "--model", "rsf", "--no-figure", "--out", "{out}"],
                  times, sigs, tmp_path, STEPPER)


# ------------------------------------------------------------------ every command
_HOOK = r"""
import atexit, os, signal, sys
at, sig = int(sys.argv[1]), int(sys.argv[2])
count = [0]
def prof(frame, event, arg):
    if event == "call" and "dryfriction" in frame.f_code.co_filename:
        count[0] += 1
        if count[0] == at:
            sys.setprofile(None)
            os.kill(os.getpid(), sig)
atexit.register(lambda: sys.stderr.write(f"calls={count[0]}\n") if at == 0 else None)
from dryfriction.cli import main
sys.setprofile(prof)  # from main() on: it installs the command line's handlers first
raise SystemExit(main(sys.argv[3:]))
"""


def _hooked(argv: list[str], at: int, sig: int, cwd: Path) -> tuple[int, str]:
    proc = subprocess.run([sys.executable, "-c", _HOOK, str(at), str(sig), *argv], cwd=cwd,
                          env=_env(), capture_output=True, text=True, timeout=300)
    return proc.returncode, proc.stderr


COMMANDS = {
    "static": ["static", "--eps", "0.04", "--T", "1", "10", "100", "--creep", "eyring-nabarro"],
    "steady": ["steady", "--eps", "0.04", "--u", "0.01", "0.1", "1"],
    "record": ["record", str(RECORD)],
    "rsf": ["rsf", "--case", "shs", "--no-figure"],
}
"""Quick commands (a profile hook slows them several times); the long ones are hit at random
times: simulate, fit (above), compare (below), reproduce and sweep (slow)."""


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_every_command_interrupted_mid_run_says_one_line(name: str, tmp_path: Path) -> None:
    """A signal at a seeded random call into the package, for each command: before the fix
    ``rsf``, ``fit`` and ``compare`` printed nothing on Ctrl-C."""
    argv = [a.replace("{out}", str(tmp_path / "out")) for a in COMMANDS[name]]
    code, err = _hooked(argv, 0, 0, tmp_path)  # a dry run counts the calls
    assert code == 0, err
    calls = int(err.strip().splitlines()[-1].removeprefix("calls="))
    rng = random.Random(name)
    for k, sig in enumerate((signal.SIGINT, signal.SIGTERM)):
        at = rng.randint(calls // 10, 9 * calls // 10)
        out = tmp_path / f"out{k}"
        code, err = _hooked([a.replace(str(tmp_path / "out"), str(out)) for a in argv], at,
                            sig, tmp_path)
        _check(code, err, sig, f"{name} at call {at} of {calls}")


def test_compare_interrupted_says_one_line(tmp_path: Path) -> None:
    """Before the fix: exit 130 and nothing on standard error."""
    # ready at the trap model's first window (1.3 s of CPU): ~1 s of CPU left
    _timed_trials(["compare", str(EXAMPLES / "velocity_step.toml"), "--no-figure", "--out",
                   "{out}"], [0.3], [signal.SIGINT], tmp_path, ENSEMBLE)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["reproduce", "sweep"])
def test_heavy_commands_interrupted_mid_run_say_one_line(name: str, tmp_path: Path) -> None:
    argv = {"reproduce": ["reproduce", "--out", str(tmp_path / "out")],
            "sweep": ["sweep", str(EXAMPLES / "phase_diagram.toml"), "--out",
                      str(tmp_path / "out"), "--workers", "1"]}[name]
    times, sigs = _seeded(2, 2.0, 4.0, seed=len(name))
    proc_args = argv[:]
    for i, (delay, sig) in enumerate(zip(times, sigs, strict=True)):
        proc_args[proc_args.index("--out") + 1] = str(tmp_path / f"out{i}")
        proc = subprocess.Popen(CLI + proc_args, cwd=tmp_path, env=_env(),
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        time.sleep(delay)
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=300)
        _check(proc.returncode, err, sig, f"{name} after {delay:.2f} s")
