"""dryfriction.io.files.is_ours and check_writable_dir called directly, each branch on both
sides: a file of ours is a regular file inside the folder, reached without a symbolic link,
with the recorded SHA-256 (nothing else); a folder is accepted when it is, or can be made, a
writable folder, and each refusal names the option as typed."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

import pytest

import dryfriction.io.files as dio
from dryfriction.io.files import MANIFEST, check_writable_dir, is_ours

DATA = b"t[s],mu[1]\n0.5,0.61\n"
SHA = hashlib.sha256(DATA).hexdigest()


@pytest.fixture
def out(tmp_path: Path) -> Path:
    o = tmp_path / "out"
    (o / "sub").mkdir(parents=True)
    (o / "a.csv").write_bytes(DATA)
    (o / "sub" / "b.csv").write_bytes(DATA)
    return o


def test_is_ours_true_only_for_the_unchanged_regular_file(out: Path) -> None:
    assert is_ours(out, "a.csv", SHA) and is_ours(out, "sub/b.csv", SHA)
    assert not is_ours(out, "a.csv", None)  # not in the manifest
    assert not is_ours(out, "a.csv", hashlib.sha256(DATA + b"\n").hexdigest())  # edited
    assert not is_ours(out, "missing.csv", SHA)
    (out / MANIFEST).write_bytes(DATA)  # the manifest is never a result
    assert not is_ours(out, MANIFEST, SHA)
    for rel in ("../out/a.csv", "./a.csv", "sub//b.csv", "/a.csv", "", "sub/../a.csv"):
        assert not is_ours(out, rel, SHA), rel


def test_is_ours_never_through_a_symbolic_link(out: Path, tmp_path: Path) -> None:
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "c.csv").write_bytes(DATA)
    (out / "link.csv").symlink_to(outside / "c.csv")  # a link to a file with the right hash
    (out / "dirlink").symlink_to(outside, target_is_directory=True)  # a folder on the way
    (out / "inner").symlink_to(out / "sub", target_is_directory=True)  # even inside
    assert not is_ours(out, "link.csv", SHA)
    assert not is_ours(out, "dirlink/c.csv", SHA)
    assert not is_ours(out, "inner/b.csv", SHA)
    assert is_ours(out, "sub/b.csv", SHA)  # the real path still is
    # a folder or a FIFO named like a result, and a file where a folder should be
    (out / "d").mkdir()
    os.mkfifo(out / "fifo")
    (out / "f").write_bytes(DATA)
    for rel in ("d", "fifo", "f/x"):
        assert not is_ours(out, rel, SHA), rel


def test_check_writable_dir_accepts_a_new_or_existing_folder(tmp_path: Path) -> None:
    new = tmp_path / "new"
    assert check_writable_dir(new) == new and not new.exists()  # checked, not made
    assert check_writable_dir(str(tmp_path)) == tmp_path
    (tmp_path / "real").mkdir()
    (tmp_path / "good_link").symlink_to(tmp_path / "real")
    assert check_writable_dir(tmp_path / "good_link") == tmp_path / "good_link"


@pytest.mark.parametrize("make, words", [
    (lambda p: None, "--copy is empty: name a folder (--copy . for the current one)"),
    (lambda p: (p / "x").symlink_to(p / "nowhere"), "is a symbolic link to"),
    (lambda p: (p / "x").write_text("mine"), "is an existing file, not a folder"),
    (lambda p: None, "parent folder"),
])
def test_check_writable_dir_refusals_name_the_option(tmp_path: Path, make, words: str) -> None:  # type: ignore[no-untyped-def]
    make(tmp_path)
    target = ("" if words.startswith("--copy is empty")
              else tmp_path / "no" / "x" if words == "parent folder" else tmp_path / "x")
    with pytest.raises(ValueError) as exc:
        check_writable_dir(target, option="--copy")
    msg = str(exc.value)
    assert words in msg and msg.startswith("--copy ") and "\n" not in msg
    if isinstance(target, Path) and target.is_symlink():
        assert str(tmp_path / "nowhere") in msg  # names where the link points


def test_check_writable_dir_asks_the_folder_or_its_parent(tmp_path: Path,
                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    """Write permission on the folder itself when it exists, on its parent when it must be
    made (the check runs as any user: os.access is replaced, root passes every real one)."""
    denied: set[Path] = set()
    real = os.access
    monkeypatch.setattr(dio.os, "access",
                        lambda p, mode: Path(p) not in denied and real(p, mode))
    (tmp_path / "old").mkdir()
    denied.add(tmp_path / "old")
    with pytest.raises(ValueError, match=r"^--out \S+old is not writable$"):
        check_writable_dir(tmp_path / "old")
    with pytest.raises(ValueError, match="new is not writable \\(cannot create it in"):
        check_writable_dir(tmp_path / "old" / "new")  # its parent asked
    denied.clear()
    denied.add(tmp_path)
    with pytest.raises(ValueError, match="is not writable \\(cannot create it in"):
        check_writable_dir(tmp_path / "new")
    assert check_writable_dir(tmp_path / "old") == tmp_path / "old"  # itself allowed


@pytest.mark.parametrize("force", [False, True])
def test_a_folder_made_where_a_listed_result_was_is_kept(tmp_path: Path, force: bool) -> None:
    """The previous result's a.csv replaced by a folder of the user's: the next run writes its
    result, leaves that folder (not ours) alone and does not stop with a traceback (it did:
    IsADirectoryError)."""
    from dryfriction.io.files import output_directory

    out = tmp_path / "out"
    with output_directory(out, command="t") as stage:
        (stage / "a.csv").write_bytes(DATA)
    (out / "a.csv").unlink()
    (out / "a.csv").mkdir()
    if force:  # a folder holding a file: foreign, so only --force writes beside it
        (out / "a.csv" / "notes.txt").write_text("mine")
    with output_directory(out, command="t", force=force) as stage:
        (stage / "b.csv").write_bytes(DATA)
    assert (out / "a.csv").is_dir() and (out / "b.csv").read_bytes() == DATA
    assert not force or (out / "a.csv" / "notes.txt").read_text() == "mine"
