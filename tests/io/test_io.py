"""Output folders: whole or nothing, ordinary permissions, and never at the cost of a user's
files (issue 16): foreign files refuse the run, ``--force`` keeps them, ``--out .`` is safe,
inputs are never overwritten, temporaries never outlive a run (SIGTERM) or a killed one."""

import json
import os
import signal
import stat
import subprocess
import sys
import time
import weakref
from pathlib import Path

import pytest

import dryfriction.io.files as dio
from dryfriction.io.files import (
    MANIFEST,
    atomic_write_text,
    check_output_dir,
    output_directory,
    remove_stale_temporaries,
    write_csv,
)


def _names(folder: Path) -> set[str]:
    return {p.name for p in folder.iterdir()}


def _dead_pid() -> int:
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def test_permissions_follow_umask(tmp_path):
    old = os.umask(0o022)
    try:
        f = atomic_write_text(tmp_path / "a.txt", "x")
        assert stat.S_IMODE(f.stat().st_mode) == 0o644
        with output_directory(tmp_path / "res") as d:
            (d / "b.txt").write_text("y")
        assert stat.S_IMODE((tmp_path / "res").stat().st_mode) == 0o755
        assert stat.S_IMODE((tmp_path / "res" / "b.txt").stat().st_mode) == 0o644
    finally:
        os.umask(old)


def test_output_directory_whole_or_nothing(tmp_path):
    out = tmp_path / "res"
    with output_directory(out) as d:
        (d / "one").write_text("1")
    with pytest.raises(RuntimeError), output_directory(out) as d:
        (d / "two").write_text("2")
        raise RuntimeError("boom")
    assert _names(out) == {MANIFEST, "one"}
    assert (out / "one").read_text() == "1"
    assert _names(tmp_path) == {"res"}  # no temporary leftovers


def test_a_failed_first_run_leaves_no_folder(tmp_path):
    with pytest.raises(RuntimeError), output_directory(tmp_path / "res") as d:
        (d / "one").write_text("1")
        raise RuntimeError("boom")
    assert _names(tmp_path) == set()


def test_manifest_lists_every_file_with_its_hash(tmp_path):
    import hashlib

    out = tmp_path / "res"
    with output_directory(out, command="simulate") as d:
        (d / "a.csv").write_text("1,2\n")
        (d / "sub").mkdir()
        (d / "sub" / "b.txt").write_text("b")
    m = json.loads((out / MANIFEST).read_text())
    assert m["format"] == "dryfriction-results" and m["command"] == "simulate"
    assert m["files"] == {rel: hashlib.sha256((out / rel).read_bytes()).hexdigest()
                          for rel in ("a.csv", "sub/b.txt")}


def test_csv_rejects_ragged_columns(tmp_path):
    with pytest.raises(ValueError, match="different lengths"):
        write_csv(tmp_path / "x.csv", {"a": [1.0, 2.0], "b": [1.0]}, {"a": "s", "b": "m"})
    assert not (tmp_path / "x.csv").exists()


def test_atomic_write_under_a_failure_keeps_the_old_file(tmp_path, monkeypatch):
    # a writer that wrote the file in place would leave it truncated or half-written
    target = tmp_path / "f.txt"
    target.write_text("old contents")

    def failing_fsync(fd):
        raise OSError("disk full")

    monkeypatch.setattr(dio.os, "fsync", failing_fsync)
    with pytest.raises(OSError, match="disk full"):
        atomic_write_text(target, "new contents")
    assert target.read_text() == "old contents"
    assert _names(tmp_path) == {"f.txt"}


def test_foreign_files_refuse_the_run_before_any_work(tmp_path):
    out = tmp_path / "res"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    ran = []
    with pytest.raises(ValueError, match=r"--out .*res holds files this program did not "
                                         r"write \(notes.txt\).*--force"):
        with output_directory(out) as d:
            ran.append(d)
    assert ran == []
    assert _names(out) == {"notes.txt"} and (out / "notes.txt").read_text() == "mine"


def test_previous_result_is_replaced_and_reported(tmp_path):
    out = tmp_path / "res"
    with output_directory(out, command="simulate") as d:
        (d / "a.csv").write_text("old a")
        (d / "snapshot_1.csv").write_text("old snap")
    lines: list[str] = []
    with output_directory(out, command="simulate", report=lines.append) as d:
        (d / "a.csv").write_text("new a")
    assert _names(out) == {MANIFEST, "a.csv"}
    assert (out / "a.csv").read_text() == "new a"
    assert len(lines) == 1 and "1 file(s) overwritten, 1 removed" in lines[0]


def test_an_edited_result_is_no_longer_ours(tmp_path):
    out = tmp_path / "res"
    with output_directory(out) as d:
        (d / "a.csv").write_text("ours")
    (out / "a.csv").write_text("edited by hand")
    with pytest.raises(ValueError, match=r"a\.csv"):
        check_output_dir(out)
    lines: list[str] = []
    with output_directory(out, force=True, report=lines.append) as d:
        (d / "a.csv").write_text("new")
    assert (out / "a.csv").read_text() == "new"
    assert (out / "a.csv.~1~").read_text() == "edited by hand"
    assert "a.csv -> a.csv.~1~" in lines[-1]


def test_force_writes_beside_foreign_files_and_deletes_nothing(tmp_path):
    out = tmp_path / "res"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    (out / "summary.json").write_text("my own summary")
    (out / MANIFEST).write_text("not ours either")
    with output_directory(out, force=True) as d:
        (d / "summary.json").write_text("{}")
    assert (out / "notes.txt").read_text() == "mine"
    assert (out / "summary.json.~1~").read_text() == "my own summary"
    assert (out / f"{MANIFEST}.~1~").read_text() == "not ours either"
    assert (out / "summary.json").read_text() == "{}"
    assert json.loads((out / MANIFEST).read_text())["files"].keys() == {"summary.json"}


@pytest.mark.parametrize("spelling", [".", "cwd"])
def test_out_dot_and_the_working_directory_are_never_emptied(tmp_path, monkeypatch, spelling):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "protocol.toml").write_text("x")
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "d.csv").write_text("1")
    out = "." if spelling == "." else str(tmp_path)
    with pytest.raises(ValueError, match="--force"):
        check_output_dir(out)
    for _ in range(2):  # a second run replaces only its own result
        with output_directory(out, force=True, inputs=["protocol.toml"]) as d:
            (d / "result.csv").write_text("r")
    assert _names(tmp_path) == {MANIFEST, "data", "protocol.toml", "result.csv"}
    assert (tmp_path / "protocol.toml").read_text() == "x"
    assert (tmp_path / "data" / "d.csv").read_text() == "1"


def test_inputs_are_never_overwritten_or_removed(tmp_path):
    out = tmp_path / "res"
    with output_directory(out, command="simulate") as d:
        (d / "timeseries.csv").write_text("t,mu\n")
    data = out / "timeseries.csv"
    # a second command reads the first one's output and writes into the same folder (another
    # command's result is replaced only with force: it is refused otherwise, test_file_safety)
    with output_directory(out, command="fit", inputs=[data], force=True) as d:
        (d / "fit.json").write_text("{}")
    assert data.read_text() == "t,mu\n"
    assert set(json.loads((out / MANIFEST).read_text())["files"]) == {"fit.json",
                                                                       "timeseries.csv"}
    with pytest.raises(ValueError, match="would overwrite an input"):
        with output_directory(out, command="simulate", inputs=[data], force=True) as d:
            (d / "timeseries.csv").write_text("other")
    assert data.read_text() == "t,mu\n"


def test_no_folder_is_ever_replaced(tmp_path, monkeypatch):
    # the old implementation moved the whole folder aside and renamed a new one in; a folder
    # made by someone else during the run (or the working directory) must survive as it is
    out = tmp_path / "res"
    renamed = []
    real = os.rename

    def spy(a, b):
        renamed.append(Path(b))
        return real(a, b)

    monkeypatch.setattr(dio.os, "rename", spy)
    with output_directory(out) as d:
        (d / "a").write_text("1")
        out.mkdir()
        (out / "theirs").write_text("t")
    assert (out / "theirs").read_text() == "t" and (out / "a").read_text() == "1"


def test_stale_temporaries_of_a_killed_run_are_removed(tmp_path):
    dead = _dead_pid()
    stale_dir = tmp_path / f".res.dftmp-{dead}-0a1b2c3d.tmp"
    stale_dir.mkdir()
    (stale_dir / "half.csv").write_text("1")
    stale_file = tmp_path / f".x.csv.dftmp-{dead}-deadbeef.tmp"
    stale_file.write_text("half")
    alive = tmp_path / f".res.dftmp-{os.getppid()}-0a1b2c3d.tmp"  # a live writer's: kept
    alive.mkdir()
    lookalike = tmp_path / ".res.other.tmp"  # not ours by name: kept
    lookalike.mkdir()
    with output_directory(tmp_path / "res") as d:
        (d / "a").write_text("1")
    assert _names(tmp_path) == {alive.name, lookalike.name, "res"}
    assert remove_stale_temporaries(tmp_path) == []


def test_ctrl_c_during_the_commit_is_delivered_after_it(tmp_path, monkeypatch):
    out = tmp_path / "res"
    with output_directory(out) as d:
        (d / "a").write_text("old")
        (d / "b").write_text("old")
    real_replace = os.replace
    calls = []

    def replace(a, b):
        real_replace(a, b)
        calls.append(b)
        if len(calls) == 1:  # between the first and the second file of the new result
            signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(dio.os, "replace", replace)
    # Python installs its KeyboardInterrupt handler only if SIGINT was not ignored at its
    # start: a suite run in the background of a non-interactive shell (`make test &`, a CI
    # step) inherits SIGINT ignored, and raise_signal would do nothing; the handler a
    # terminal's Python has is installed here
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt), output_directory(out) as d:
            (d / "a").write_text("new")
            (d / "b").write_text("new")
    finally:
        signal.signal(signal.SIGINT, before)
    assert (out / "a").read_text() == "new" and (out / "b").read_text() == "new"
    assert set(json.loads((out / MANIFEST).read_text())["files"]) == {"a", "b"}
    assert _names(tmp_path) == {"res"} and _names(out) == {MANIFEST, "a", "b"}


def test_sigterm_removes_the_temporary_folder(tmp_path):
    # a run killed politely (SIGTERM) cleans up: exit 143, no hidden folder left
    code = (
        "import sys, time\n"
        "from dryfriction.cli import app, main\n"
        "from dryfriction.io.files import output_directory\n"
        "@app.command('slow-test-writer')\n"
        "def w(out: str) -> None:\n"
        "    with output_directory(out) as d:\n"
        "        (d / 'a').write_text('1')\n"
        "        print('staged', flush=True)\n"
        "        time.sleep(60)\n"
        "sys.exit(main())\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", code, "slow-test-writer",
                             str(tmp_path / "res")], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "staged"
    assert any(".dftmp-" in n for n in _names(tmp_path))
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 143
    assert err.strip().splitlines()[-1] == "error: interrupted (SIGTERM)"
    assert _names(tmp_path) == set()


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
def test_an_interrupt_swallowed_by_a_library_still_fails_the_run(monkeypatch):
    # KeyboardInterrupt raised inside a finaliser is printed and ignored by Python; the
    # command must not then report success
    import dryfriction.cli as cli

    class Thing:
        pass

    def app(**kwargs):
        t = Thing()
        weakref.finalize(t, signal.raise_signal, signal.SIGINT)
        del t  # the finaliser runs here; its KeyboardInterrupt is swallowed

    monkeypatch.setattr(cli, "app", app)
    old_int, old_term = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    try:
        code = cli.main([])
    finally:
        signal.signal(signal.SIGINT, old_int)
        signal.signal(signal.SIGTERM, old_term)
    assert code == 130


def test_sigkill_leaves_a_temporary_that_the_next_run_removes(tmp_path):
    code = (
        "import time\n"
        "from dryfriction.io.files import output_directory\n"
        f"with output_directory({str(tmp_path / 'res')!r}) as d:\n"
        "    (d / 'a').write_text('1')\n"
        "    print('staged', flush=True)\n"
        "    time.sleep(60)\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "staged"
    proc.kill()
    proc.wait(timeout=30)
    assert any(".dftmp-" in n for n in _names(tmp_path))
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and Path(f"/proc/{proc.pid}").exists():
        time.sleep(0.05)
    with output_directory(tmp_path / "res") as d:
        (d / "b").write_text("2")
    assert _names(tmp_path) == {"res"}


def test_a_manifest_of_another_format_does_not_make_the_folder_ours(tmp_path):
    # another program's manifest under our file name, listing its files with their true
    # hashes: only our format marks a result of ours, so the folder is refused and left alone
    import hashlib

    out = tmp_path / "res"
    out.mkdir()
    (out / "data.csv").write_text("theirs\n")
    digest = hashlib.sha256((out / "data.csv").read_bytes()).hexdigest()
    (out / MANIFEST).write_text(json.dumps({"format": "some-other-tool", "command": "x",
                                            "files": {"data.csv": digest}}))
    with pytest.raises(ValueError, match=r"did not write"):
        with output_directory(out, command="simulate") as d:
            (d / "a.csv").write_text("1\n")
    assert _names(out) == {"data.csv", MANIFEST}
    assert (out / "data.csv").read_text() == "theirs\n"


def test_a_file_appearing_during_the_run_refuses_the_whole_result(tmp_path):
    # the check comes before any file moves: the earlier results must not be half-replaced
    out = tmp_path / "res"
    with output_directory(out) as d:
        (d / "a").write_text("old a")
        (d / "b").write_text("old b")
    with pytest.raises(ValueError, match="appeared there during the run"):
        with output_directory(out) as d:
            (d / "a").write_text("new a")
            (d / "b").write_text("new b")
            (d / "c").write_text("new c")
            (out / "c").write_text("someone else's")  # after the checks, before the commit
    assert (out / "a").read_text() == "old a" and (out / "b").read_text() == "old b"
    assert (out / "c").read_text() == "someone else's"
    assert set(json.loads((out / MANIFEST).read_text())["files"]) == {"a", "b"}
    assert not [n for n in _names(tmp_path) | _names(out) if ".dftmp-" in n]
