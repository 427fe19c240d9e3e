"""A folder the package writes into never costs the user a file (issue 24, items 4 to 7).

Only files a manifest lists, inside the folder (no ``..``, no absolute path, no symbolic link on
the way), unchanged since they were written, are ever replaced or removed; ``examples --copy``
hands its files to the user; a sweep's outputs and stored points are checked against their
hashes; backup names are claimed so that concurrent ``--force`` runs lose nothing; a dangling
symbolic link or an empty ``--out`` is refused before any work."""

import hashlib
import json
import multiprocessing
import os
import shutil
from pathlib import Path

import cloudpickle
import pytest
from typer.testing import CliRunner

import dryfriction.io.files as dio
import dryfriction.sweeps.sweep as sw
import sweep_runners
from dryfriction.cli import app
from dryfriction.io.examples import copy_examples, example_files, examples_path
from dryfriction.io.files import MANIFEST, check_output_dir, output_directory
from dryfriction.sweeps.sweep import load_sweep, parse_sweep, run_sweep

cloudpickle.register_pickle_by_value(sweep_runners)
runner = CliRunner()


def _sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _tree(folder: Path) -> dict[str, bytes]:
    """Every file below ``folder`` (symbolic links as their target's name) by relative path."""
    out = {}
    for p in sorted(folder.rglob("*")):
        rel = p.relative_to(folder).as_posix()
        if p.is_symlink():
            out[rel] = b"-> " + os.readlink(p).encode()
        elif p.is_file():
            out[rel] = p.read_bytes()
    return out


def _add_to_manifest(out: Path, rel: str, digest: str) -> None:
    m = json.loads((out / MANIFEST).read_text())
    m["files"][rel] = digest
    (out / MANIFEST).write_text(json.dumps(m))


def _one_line(res) -> str:
    lines = res.output.strip().splitlines()
    assert len(lines) == 1, res.output
    return lines[0]


# --- item 7: manifest paths are confined to the folder -----------------------------------------

@pytest.mark.parametrize("spelling", ["../victim.txt", "absolute", "sub/../../victim.txt"])
@pytest.mark.parametrize("force", [False, True])
def test_a_manifest_entry_outside_the_folder_is_never_removed(tmp_path, spelling, force):
    # the mistake: trusting the manifest's paths, so that a re-run deletes a file outside
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    out = tmp_path / "res"
    with output_directory(out) as d:
        (d / "a.csv").write_text("x")
        (d / "sub").mkdir()  # so that "sub/../../victim.txt" resolves
        (d / "sub" / "b.csv").write_text("x")
    rel = str(victim) if spelling == "absolute" else spelling
    _add_to_manifest(out, rel, _sha(b"precious"))
    with output_directory(out, force=force) as d:
        (d / "a.csv").write_text("y")
        (d / "sub").mkdir()
        (d / "sub" / "b.csv").write_text("y")
    assert victim.read_text() == "precious"
    assert (out / "a.csv").read_text() == "y"
    assert set(json.loads((out / MANIFEST).read_text())["files"]) == {"a.csv", "sub/b.csv"}


def test_a_symbolic_link_to_a_folder_outside_is_never_followed(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "v.txt").write_text("precious")
    out = tmp_path / "res"
    with output_directory(out) as d:
        (d / "a.csv").write_text("x")
    os.symlink(outside, out / "link")
    _add_to_manifest(out, "link/v.txt", _sha(b"precious"))
    # the link is not ours: refused without --force, named
    with pytest.raises(ValueError, match=r"\(link\)"):
        check_output_dir(out)
    with output_directory(out, force=True) as d:
        (d / "a.csv").write_text("y")
    assert (outside / "v.txt").read_text() == "precious"
    assert os.readlink(out / "link") == str(outside)
    # a result that needs a folder where the link is: refused, nothing written anywhere
    before, outside_before = _tree(out), _tree(outside)
    with pytest.raises(ValueError, match=r"link is a symbolic link or a file where the result "
                                         r"link/new\.csv needs a folder; nothing was written"):
        with output_directory(out, force=True) as d:
            (d / "link").mkdir()
            (d / "link" / "new.csv").write_text("z")
    assert _tree(out) == before and _tree(outside) == outside_before


def test_a_symbolic_link_to_a_file_outside_is_never_replaced_through(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    out = tmp_path / "res"
    with output_directory(out) as d:
        (d / "a.csv").write_text("x")
        (d / "b.csv").write_text("x")
    (out / "a.csv").unlink()
    os.symlink(victim, out / "a.csv")  # its target has the hash the manifest lists for it
    _add_to_manifest(out, "a.csv", _sha(b"precious"))
    with pytest.raises(ValueError, match=r"\(a\.csv\)"):
        check_output_dir(out)
    with output_directory(out, force=True) as d:
        (d / "b.csv").write_text("y")  # a.csv is no result of this run: kept as it is
    assert (out / "a.csv").is_symlink() and victim.read_text() == "precious"
    with output_directory(out, force=True) as d:
        (d / "a.csv").write_text("z")  # collides: the link is kept under a backup name
    assert os.readlink(out / "a.csv.~1~") == str(victim) and victim.read_text() == "precious"
    assert (out / "a.csv").read_text() == "z" and not (out / "a.csv").is_symlink()


# --- item 4: examples --copy hands its files to the user ---------------------------------------

def test_a_results_run_into_an_examples_copy_removes_nothing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = runner.invoke(app, ["examples", "--copy", "ex"])
    assert res.exit_code == 0, res.output
    copied = _tree(tmp_path / "ex")
    # the command: refused in one line, every file as it was
    res = runner.invoke(app, ["simulate", "ex/velocity_step.toml", "--out", "ex"])
    assert res.exit_code == 2
    assert "examples --copy" in _one_line(res) and "--force" in res.output
    assert _tree(tmp_path / "ex") == copied
    # with --force: the results are written beside the examples, none is removed or changed
    res = runner.invoke(app, ["simulate", "ex/velocity_step.toml", "--out", "ex", "--force"])
    assert res.exit_code == 0, res.output
    after = _tree(tmp_path / "ex")
    for rel in example_files():
        assert after[rel] == copied[rel], rel
    assert after[f"{MANIFEST}.~1~"] == copied[MANIFEST]
    assert {"summary.json", "timeseries.csv"} <= set(after)
    # and a second results run replaces only its own results
    res = runner.invoke(app, ["simulate", "ex/velocity_step.toml", "--out", "ex", "--force"])
    assert res.exit_code == 0, res.output
    assert all(_tree(tmp_path / "ex")[rel] == copied[rel] for rel in example_files())
    assert json.loads(copied[MANIFEST])["format"] == "dryfriction-examples"


def test_a_second_copy_never_replaces_an_edited_example(tmp_path):
    ex = tmp_path / "ex"
    copy_examples(ex)
    (ex / "velocity_step.toml").write_text("# my edit\n")
    (ex / "gallery" / "mine.py").write_text("print('mine')\n")
    res = runner.invoke(app, ["examples", "--copy", str(ex)])
    assert res.exit_code == 2 and _one_line(res).startswith(f"error: --copy {ex} holds")
    lines: list[str] = []
    copy_examples(ex, force=True, report=lines.append)
    assert (ex / "velocity_step.toml.~1~").read_text() == "# my edit\n"
    assert (ex / "gallery" / "mine.py").read_text() == "print('mine')\n"
    assert (ex / "velocity_step.toml").read_bytes() == \
        (examples_path() / "velocity_step.toml").read_bytes()
    assert "velocity_step.toml -> velocity_step.toml.~1~" in lines[-1]


@pytest.mark.parametrize("setup", ["foreign", "file", "dangling", "empty"])
def test_examples_copy_refusals_name_the_copy_option(tmp_path, monkeypatch, setup):
    monkeypatch.chdir(tmp_path)
    target = "dest"
    if setup == "foreign":
        Path("dest").mkdir()
        Path("dest", "notes.txt").write_text("mine")
    elif setup == "file":
        Path("dest").write_text("mine")
    elif setup == "dangling":
        os.symlink("nowhere", "dest")
    else:
        target = ""
    before = sorted(os.listdir(tmp_path))
    res = runner.invoke(app, ["examples", "--copy", target])
    assert res.exit_code == 2
    line = _one_line(res)
    assert line.startswith("error: --copy") and "--out" not in line
    assert sorted(os.listdir(tmp_path)) == before


# --- unclear: a dangling symbolic link and an empty --out --------------------------------------

def test_a_dangling_symbolic_link_out_is_refused_before_any_work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    os.symlink(tmp_path / "nowhere", "dang")
    with pytest.raises(ValueError, match=r"--out dang is a symbolic link to .*nowhere, which "
                                         r"does not exist"):
        check_output_dir("dang")
    ran = []
    with pytest.raises(ValueError, match="symbolic link"), output_directory("dang") as d:
        ran.append(d)
    assert ran == []
    proto = examples_path() / "velocity_step.toml"
    res = runner.invoke(app, ["simulate", str(proto), "--out", "dang"])
    assert res.exit_code == 2 and "dftmp" not in res.output
    assert "symbolic link" in _one_line(res)
    assert sorted(os.listdir(tmp_path)) == ["dang"]


def test_a_dangling_link_made_during_the_run_is_one_line_without_a_temporary(tmp_path,
                                                                              monkeypatch):
    out = tmp_path / "res"
    real = os.rename

    def rename(src, dst, *args, **kwargs):
        if Path(dst) == out:  # someone makes a link to nothing there meanwhile
            os.symlink(tmp_path / "nowhere", out)
        return real(src, dst, *args, **kwargs)
    monkeypatch.setattr(dio.os, "rename", rename)
    with pytest.raises(ValueError) as info, output_directory(out) as d:
        (d / "a.csv").write_text("x")
    assert str(info.value).startswith(f"--out {out} appeared during the run and is not a folder")
    assert "dftmp" not in str(info.value)
    assert sorted(os.listdir(tmp_path)) == ["res"] and out.is_symlink()


def test_an_empty_out_is_refused_not_the_working_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("mine.txt").write_text("mine")
    ex = Path(__file__).resolve().parents[2] / "examples"  # the clone's (a src copy has none)
    proto = ex / "velocity_step.toml"
    lab = ex / "data" / "lab" / "sepiolite_velstep_0.2-2um_s.txt"
    # record, fit and reproduce took --out as a path: "" became "." before any check (a new
    # user's trial wrote record.png, fit.json and the report into the working folder)
    for args in (["simulate", str(proto)], ["simulate", str(proto), "--force"],
                 ["sweep", str(ex / "phase_diagram.toml")],
                 ["record", str(lab)], ["fit", str(lab), "--model", "rsf"], ["reproduce"],
                 ["reproduce", "--force"]):
        res = runner.invoke(app, [*args, "--out", ""])
        assert res.exit_code == 2, res.output
        assert _one_line(res) == "error: --out is empty: name a folder (--out . for the " \
                                 "current one)"
    assert os.listdir(tmp_path) == ["mine.txt"]
    with pytest.raises(ValueError, match="--out is empty"), output_directory("", force=True):
        pass
    assert os.listdir(tmp_path) == ["mine.txt"]


# --- item 6: backups are claimed atomically ----------------------------------------------------

_USER_FILES = [f"u{j}.csv" for j in range(6)] + ["sub/b.csv"]


def _writer(out: str, go, i: int) -> None:
    go.wait()
    with output_directory(out, force=True) as d:
        (d / "sub").mkdir()
        for rel in _USER_FILES:
            (d / rel).write_text(f"result {i}")


@pytest.mark.slow
def test_concurrent_force_runs_never_lose_a_users_file(tmp_path):
    # the mistake: choosing the free backup name first and renaming onto it later, so that two
    # runs pick the same NAME.~1~ and the second rename clobbers the user's file (3 in 150
    # trials in the issue); here 4 writers, 7 colliding files, 40 trials
    ctx = multiprocessing.get_context("fork")
    trials, writers, lost, failed, no_result = 40, 4, [], [], []
    for k in range(trials):
        out = tmp_path / str(k)
        (out / "sub").mkdir(parents=True)
        for rel in _USER_FILES:
            (out / rel).write_text(f"USER {rel}")
        go = ctx.Event()
        procs = [ctx.Process(target=_writer, args=(str(out), go, i)) for i in range(writers)]
        for p in procs:
            p.start()
        go.set()
        for p in procs:
            p.join(60)
        failed += [p.exitcode for p in procs if p.exitcode != 0]
        contents = {f.read_text() for f in out.rglob("*") if f.is_file()}
        lost += [f"{k}: {rel}" for rel in _USER_FILES if f"USER {rel}" not in contents]
        no_result += [f"{k}: {rel}" for rel in _USER_FILES if not (out / rel).is_file()
                      or not (out / rel).read_text().startswith("result ")]
    assert lost == []
    assert failed == [] and no_result == []


@pytest.mark.parametrize("kind", ["file", "folder", "no hard links"])
def test_a_backup_name_taken_meanwhile_is_never_overwritten(tmp_path, monkeypatch, kind):
    out = tmp_path / "res"
    out.mkdir()
    if kind == "folder":
        (out / "a.csv").mkdir()
        (out / "a.csv" / "inside").write_text("USER")
    else:
        (out / "a.csv").write_text("USER")
    if kind == "no hard links":
        def no_link(*args, **kwargs):
            raise PermissionError(1, "Operation not permitted")
        monkeypatch.setattr(dio.os, "link", no_link)
    # another run claims a.csv.~1~ between this run's look and its claim
    real_lstat = os.lstat

    def lstat(path, *args, **kwargs):
        st = real_lstat(path, *args, **kwargs)
        if Path(path).name == "a.csv" and not (out / "a.csv.~1~").exists():
            (out / "a.csv.~1~").write_text("OTHER RUN'S BACKUP")
        return st
    monkeypatch.setattr(dio.os, "lstat", lstat)
    backup = dio._back_up(out / "a.csv")
    assert backup == out / "a.csv.~2~"
    assert (out / "a.csv.~1~").read_text() == "OTHER RUN'S BACKUP"
    kept = backup / "inside" if kind == "folder" else backup
    assert kept.read_text() == "USER"
    assert sorted(os.listdir(out)) == sorted({"a.csv.~1~", "a.csv.~2~"}
                                             | ({"a.csv"} if kind == "file" else set()))


# --- item 5: a sweep's outputs and stored points -----------------------------------------------

def _proto(markers: Path) -> dict:
    return {"test": {"x": 1, "y": 1.0, "markers": str(markers)},
            "sweep": {"test.x": [1, 2, 3], "test.y": [0.5, 2.0]}}


def _figure(ds) -> bytes:
    return f"figure of {float(ds['product'].sum())}".encode()


@pytest.fixture(scope="module")
def finished_sweep(tmp_path_factory):
    """A finished sweep folder (one cluster start) and its runner's marker folder (part of the
    protocol, so of every point's key: re-runs use the same one and count its files)."""
    base = tmp_path_factory.mktemp("sweep")
    (base / "m").mkdir()
    run_sweep(parse_sweep(_proto(base / "m")), sweep_runners.counting_runner, base / "out",
              n_workers=1)
    return base / "out", base / "m"


def _rerun(out: Path, markers: Path, figure: bool = False):
    extra = {"outputs": {"figure.png": _figure}} if figure else {}
    return run_sweep(parse_sweep(_proto(markers)), sweep_runners.counting_runner, out,
                     n_workers=1, **extra)


@pytest.fixture
def sweep_copy(finished_sweep, tmp_path):
    """A copy of the finished sweep and a function giving the number of points computed
    since the copy was made."""
    done, markers = finished_sweep
    out = tmp_path / "out"
    shutil.copytree(done, out, symlinks=True)
    n = len(list(markers.iterdir()))
    return out, markers, lambda: len(list(markers.iterdir())) - n


def test_a_finished_sweep_resumes_and_rewrites_its_own_outputs(sweep_copy):
    out, markers, computed = sweep_copy
    before = _tree(out)
    ds = _rerun(out, markers, figure=True)  # every point stored: nothing computed
    assert computed() == 0
    assert before["sweep.nc"] != (out / "sweep.nc").read_bytes()  # its attrs name the copy
    assert (out / "figure.png").read_bytes() == _figure(ds)
    marker = json.loads((out / "sweep.json").read_text())
    assert marker["outputs"] == {"sweep.nc": [_sha((out / "sweep.nc").read_bytes())],
                                 "figure.png": [_sha(_figure(ds))]}
    _rerun(out, markers, figure=True)  # its own figure is replaced without a word


@pytest.mark.parametrize("name", ["sweep.nc", "figure.png"])
def test_an_edited_sweep_output_is_never_overwritten(sweep_copy, name):
    # the mistake: writing sweep.nc (phase_diagram.png) over whatever is there
    out, markers, computed = sweep_copy
    figure = name == "figure.png"
    if figure:
        _rerun(out, markers, figure=True)
    (out / name).write_bytes(b"edited by hand")
    before = _tree(out)
    with pytest.raises(ValueError, match=rf"--out .*: {name} is not the file this sweep wrote "
                                         r".*move it away"):
        _rerun(out, markers, figure=figure)
    assert _tree(out) == before and computed() == 0
    # moved away: the next run writes it again (nothing computed)
    (out / name).rename(out.parent / name)
    _rerun(out, markers, figure=figure)
    assert (out / name).read_bytes() != b"edited by hand" and computed() == 0


def test_an_output_edited_during_the_run_is_kept(sweep_copy):
    # the mistake: checking the outputs only before the run (the user may edit one meanwhile)
    out, markers, _ = sweep_copy
    outputs = {"a.png": lambda ds: b"a", "b.png": lambda ds: b"b"}
    run_sweep(parse_sweep(_proto(markers)), sweep_runners.counting_runner, out, n_workers=1,
              outputs=outputs)

    def a_while_b_is_edited(ds):
        (out / "b.png").write_bytes(b"edited during the run")
        return b"a"
    with pytest.raises(ValueError, match="b.png changed during the run .* it was kept"):
        run_sweep(parse_sweep(_proto(markers)), sweep_runners.counting_runner, out,
                  n_workers=1, outputs={"a.png": a_while_b_is_edited, "b.png": outputs["b.png"]})
    assert (out / "b.png").read_bytes() == b"edited during the run"


def test_a_kill_between_the_rename_and_the_marker_leaves_the_output_ours(sweep_copy,
                                                                         monkeypatch):
    # the mistake: recording the new hash only after the rename (a kill in between would
    # leave a sweep.nc of ours that the next run refuses as the user's)
    out, markers, _ = sweep_copy
    (out / "sweep.nc").write_bytes(b"")
    (out / "sweep.nc").unlink()
    real = sw.write_json
    calls = []

    def killed_after_the_rename(path, obj):
        calls.append(Path(path).name)
        if calls.count("sweep.json") == 2:  # the marker after the rename
            raise KeyboardInterrupt
        return real(path, obj)
    monkeypatch.setattr(sw, "write_json", killed_after_the_rename)
    with pytest.raises(KeyboardInterrupt):
        _rerun(out, markers)
    monkeypatch.setattr(sw, "write_json", real)
    assert (out / "sweep.nc").exists()
    _rerun(out, markers)  # not refused: the marker accepted the new hash before the rename


@pytest.mark.parametrize("edit", ["result", "truncate", "not json", "symbolic link"])
def test_an_edited_point_is_refused_never_taken_into_sweep_nc(sweep_copy, edit, tmp_path):
    # the mistake: reading a stored point's numbers without checking them, so that an edited
    # result ends up in sweep.nc (the issue: 1234 in place of 1.0, silently)
    out, markers, computed = sweep_copy
    point = sorted((out / "points").glob("*.json"))[0]
    rec = json.loads(point.read_text())
    if edit == "result":
        rec["result"]["product"] = 1234.0
        point.write_text(json.dumps(rec, indent=2) + "\n")
    elif edit == "truncate":
        point.write_text(point.read_text()[:40])
    elif edit == "not json":
        point.write_text("my notes\n")
    else:
        (tmp_path / "elsewhere.json").write_text(point.read_text())
        point.unlink()
        os.symlink(tmp_path / "elsewhere.json", point)
    before = _tree(out)
    with pytest.raises(ValueError, match=rf"points/{point.name} is not the record this sweep "
                                         r"wrote .*move it away"):
        _rerun(out, markers)
    assert _tree(out) == before and computed() == 0
    assert 1234.0 not in load_sweep(out / "sweep.nc")["product"].values
    spec = parse_sweep(_proto(markers))
    analysis = sw.analysis_name(sweep_runners.counting_runner)
    keys = {idx: sw.point_key(spec.protocol(ov), analysis) for idx, ov in spec.points()}
    with pytest.raises(ValueError, match="is not the record this sweep wrote"):
        sw.assemble(spec, out / "points", keys)


def test_a_sweep_folder_of_an_earlier_version_is_refused_untouched(sweep_copy):
    out, markers, computed = sweep_copy
    marker = json.loads((out / "sweep.json").read_text())
    del marker["outputs"]
    (out / "sweep.json").write_text(json.dumps(marker))
    before = _tree(out)
    with pytest.raises(ValueError, match="earlier dryfriction, which recorded no hashes"):
        _rerun(out, markers)
    assert _tree(out) == before and computed() == 0


def test_a_sweep_folder_holding_a_user_file_is_not_resumed_into(sweep_copy):
    # was: exit 0, the resumed sweep writing beside notes.txt although run_sweep promises a
    # folder holding anything else is refused (a new sweep's folder is)
    out, markers, computed = sweep_copy
    (out / "notes.txt").write_text("mine")
    (out / ".sweep.nc.dftmp-99999999-0a1b2c3d.tmp").write_bytes(b"")  # a killed run's
    before = _tree(out)
    with pytest.raises(ValueError, match=r"--out .* holds files that are not this sweep's "
                                         r"\(notes.txt\): move them away"):
        _rerun(out, markers)
    assert _tree(out) == before and computed() == 0
    (out / "notes.txt").unlink()
    _rerun(out, markers)  # the temporary is not the user's: the sweep resumes


def test_a_result_of_another_command_is_refused_without_force(tmp_path, monkeypatch):
    """A folder holding one command's result (a fit that may have cost hours) is not replaced
    by another command's run unless --force; a re-run of the same command replaces its own.
    Found by a new user's trial: ``fit ... --out D`` then ``rsf --out D`` removed fit.json.
    Mistakes: the command not compared; the refusal also under --force."""
    monkeypatch.chdir(tmp_path)
    rsf = ["rsf", "--no-figure", "--t1", "3", "--t2", "3"]
    first = runner.invoke(app, [*rsf, "--out", "d"])
    assert first.exit_code == 0, first.output
    before = sorted(os.listdir("d"))
    proto = Path(__file__).resolve().parents[2] / "examples" / "velocity_step.toml"
    res = runner.invoke(app, ["simulate", str(proto), "--out", "d", "--no-figure"])
    assert res.exit_code == 2, res.output
    line = _one_line(res)
    assert line.startswith("error: --out d holds a previous rsf result (written ")
    assert line.endswith("a simulate run would replace it; choose another folder, or add "
                         "--force to replace it")
    assert sorted(os.listdir("d")) == before
    again = runner.invoke(app, [*rsf, "--out", "d"])  # the same command: its own result
    assert again.exit_code == 0, again.output
    forced = runner.invoke(app, ["simulate", str(proto), "--out", "d", "--no-figure",
                                 "--force"])
    assert forced.exit_code == 0, forced.output
    assert "replaced the previous rsf result" in forced.output
    # the writer itself checks too (a Python caller, or a result that appeared meanwhile)
    with pytest.raises(ValueError, match="holds a previous simulate result .* a fit run would "
                                         "replace it"):
        with output_directory("d", command="fit") as d:
            (d / "fit.json").write_text("{}")
    assert not Path("d/fit.json").exists()
