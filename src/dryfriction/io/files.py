"""Output files written whole or not at all, and never at the cost of a user's files.

Every writer goes through a temporary file in the destination folder and ``os.replace``.
:func:`output_directory` stages a whole folder of results and moves it into place only when the
run finishes. The rules for an existing ``--out`` folder (ours):

* a new or empty folder receives the results;
* a folder holding a previous result of ours (recognised by the manifest :data:`MANIFEST`, which
  lists every file the run wrote with its SHA-256) gets the new result of the same command; the
  previous run's files are replaced or removed (and this is reported), except files the new run
  reads; a previous result of another command (a fit, then an ``rsf`` run into the same
  folder) is refused before any work unless ``force`` (it may have cost hours: a user who
  re-runs ``fit`` expects its own result replaced, not a fit lost to another command);
* a folder holding anything else (a file we did not write, or one of ours changed since) is
  refused before any work, unless ``force``: then the results are written beside those files, a
  file whose name collides with a result is kept under a numbered backup name (``NAME.~1~``), and
  nothing is deleted;
* a file of ours is one the manifest lists, inside the folder (a relative path without ``..``,
  reached without a symbolic link), a regular file, with the recorded SHA-256: nothing else is
  ever replaced or removed, whatever the manifest says;
* ``examples --copy`` writes a manifest of format :data:`EXAMPLES_FORMAT`: the copied files are
  handed to the user, so that folder reads as one holding files we did not write (a run into it
  is refused, or with ``force`` writes beside them; it never replaces or removes them);
* a backup name is claimed in a way that cannot take one claimed meanwhile (a hard link, which
  fails on an existing name): two ``force`` runs at once never lose a file;
* no folder is ever removed or replaced (``--out .`` is safe), only files we wrote;
* temporary files and folders carry the writer's process id; one left by a killed run is removed
  by the next run that writes there.
"""

from __future__ import annotations

import contextlib
import csv
import datetime
import errno
import hashlib
import io
import json
import math
import os
import re
import secrets
import shutil
import stat
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..interrupts import deferred

__all__ = [
    "MANIFEST",
    "atomic_write_bytes",
    "atomic_write_text",
    "write_json",
    "write_csv",
    "output_directory",
    "check_output_dir",
    "check_writable_dir",
    "is_ours",
    "to_jsonable",
]


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> Path:
    """Write ``data`` to ``path`` through a temporary file and a rename.

    The file gets the permissions an ordinary ``open(path, "w")`` would give (``0o666`` less
    the umask), not ``mkstemp``'s private ``0o600``.
    """
    path = Path(path)
    fd, tmp = _make_temp(path.parent, path.name, directory=False)
    try:
        os.fchmod(fd, 0o666 & ~_umask())
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise
    return path


def atomic_write_text(path: str | os.PathLike[str], text: str) -> Path:
    return atomic_write_bytes(path, text.encode("utf-8"))


def to_jsonable(obj: Any) -> Any:
    """Convert NumPy scalars/arrays and non-finite floats to plain JSON values (NaN -> null)."""
    if isinstance(obj, Mapping):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return [to_jsonable(v) for v in obj.tolist()]
    if isinstance(obj, (np.floating, float)):
        x = float(obj)
        return x if math.isfinite(x) else None
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def write_json(path: str | os.PathLike[str], obj: Any) -> Path:
    return atomic_write_text(path, json.dumps(to_jsonable(obj), indent=2) + "\n")


def write_csv(
    path: str | os.PathLike[str], columns: Mapping[str, Sequence[float] | np.ndarray],
    units: Mapping[str, str | None],
) -> Path:
    """Write equal-length columns as CSV with a header row ``name[unit]``
    (:mod:`dryfriction.io.units`), full float precision.

    ``units`` gives each column's unit (``"1"``: dimensionless; ``None``: a label, written
    bare); a column without one is refused (ValueError), before anything is written.
    """
    from .units import labelled

    columns = labelled(columns, units)
    names = list(columns)
    arrays = [np.asarray(columns[n]) for n in names]
    n = {len(a) for a in arrays}
    if len(n) > 1:
        lengths = {name: len(a) for name, a in zip(names, arrays, strict=True)}
        raise ValueError(f"columns have different lengths: {lengths}")
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(names)
    for row in zip(*arrays, strict=True):
        w.writerow([repr(float(v)) if isinstance(v, (float, np.floating)) else v for v in row])
    return atomic_write_text(path, buf.getvalue())


MANIFEST = "dryfriction.json"
"""The marker of a results folder of ours: format, command, time and the SHA-256 of every file."""

MANIFEST_FORMAT = "dryfriction-results"
EXAMPLES_FORMAT = "dryfriction-examples"
"""``format`` of the manifest that ``examples --copy`` writes: a record of what was copied, whose
files are the user's (no run replaces or removes them)."""
_SHA256 = re.compile(r"^[0-9a-f]{64}$")
_TEMP = re.compile(r"^\..*\.dftmp-(\d+)-[0-9a-f]+\.tmp$")


def is_temporary(name: str) -> bool:
    """Whether a file name is one of this program's temporaries (:func:`_make_temp`)."""
    return _TEMP.match(name) is not None


def _make_temp(parent: Path, name: str, *, directory: bool) -> tuple[int, str]:
    """Create a temporary file (returns an open descriptor) or folder (descriptor -1) in
    ``parent``, named ``.NAME.dftmp-PID-RANDOM.tmp`` so that a later run can tell one left by a
    killed process (:func:`remove_stale_temporaries`)."""
    for _ in range(100):
        tmp = parent / f".{name}.dftmp-{os.getpid()}-{secrets.token_hex(4)}.tmp"
        try:
            if directory:
                os.mkdir(tmp, 0o700)
                return -1, str(tmp)
            return os.open(tmp, os.O_RDWR | os.O_CREAT | os.O_EXCL, 0o600), str(tmp)
        except FileExistsError:
            continue
    raise FileExistsError(f"could not create a temporary name in {parent}")


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # alive, someone else's
        return True
    return True


def remove_stale_temporaries(folder: str | os.PathLike[str]) -> list[Path]:
    """Remove the temporary files and folders that a killed run of ours left in ``folder``.

    Only entries named by :func:`_make_temp` whose process no longer exists are removed: they
    are ours by name and nobody is writing them. Returns what was removed.
    """
    folder = Path(folder)
    removed: list[Path] = []
    try:
        entries = list(folder.iterdir())
    except OSError:
        return removed
    for entry in entries:
        m = _TEMP.match(entry.name)
        if m is None or int(m.group(1)) == os.getpid() or _pid_alive(int(m.group(1))):
            continue
        if entry.is_dir() and not entry.is_symlink():
            shutil.rmtree(entry, ignore_errors=True)
        else:
            with contextlib.suppress(FileNotFoundError):
                entry.unlink()
        removed.append(entry)
    return removed


def _sha256(path: Path) -> str:
    with path.open("rb") as fh:
        return hashlib.file_digest(fh, "sha256").hexdigest()


def _raw_manifest(out: Path) -> Any:
    try:
        return json.loads((out / MANIFEST).read_text())
    except (OSError, ValueError):
        return None


def _confined(rel: Any) -> bool:
    """Whether a manifest entry can name a file inside the folder: a relative POSIX path with
    no empty, ``.`` or ``..`` part (``"../victim.txt"`` and ``"/etc/x"`` cannot), not the
    manifest itself."""
    if not isinstance(rel, str) or not rel or rel.startswith("/") or "\x00" in rel:
        return False
    return rel != MANIFEST and all(p not in ("", ".", "..") for p in rel.split("/"))


def _read_manifest(out: Path) -> dict[str, Any] | None:
    """The manifest of a results folder of ours, or ``None`` if there is none (or not ours).

    Its ``files`` keep only entries that can name a file inside ``out`` with a SHA-256 (an
    entry like ``"../victim.txt"`` is not ours, whatever its hash)."""
    m = _raw_manifest(out)
    if not isinstance(m, dict) or m.get("format") != MANIFEST_FORMAT:
        return None
    files = m.get("files")
    if not isinstance(files, dict):
        return None
    m["files"] = {rel: digest for rel, digest in files.items()
                  if _confined(rel) and isinstance(digest, str) and _SHA256.match(digest)}
    return m


def is_ours(out: Path, rel: str, digest: str | None) -> bool:
    """Whether ``out/rel`` is still the file we wrote: reached without a symbolic link (every
    folder on the way a real folder of ``out``), a regular file, with the SHA-256 ``digest``.

    Only such a file may be replaced or removed: a symbolic link in the folder (to a file or a
    folder outside it) is never followed to one."""
    if digest is None or not _confined(rel):
        return False
    parts = rel.split("/")
    path = out
    try:
        for part in parts[:-1]:
            path = path / part
            if not stat.S_ISDIR(os.lstat(path).st_mode):
                return False
        # O_NOFOLLOW: a symbolic link fails (ELOOP); O_NONBLOCK: a FIFO does not block
        fd = os.open(path / parts[-1], os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return False
    # checked on the descriptor, before a file object: fdopen(..., "rb") of a folder raises
    # IsADirectoryError (a folder made where a listed result was crashed the next run)
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        return False
    with os.fdopen(fd, "rb") as fh:
        return hashlib.file_digest(fh, "sha256").hexdigest() == digest


def _walk_files(folder: Path) -> Iterator[str]:
    """Every file below ``folder`` as a POSIX relative path, lazily (our temporaries left
    out)."""
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not _TEMP.match(d))
        # a symbolic link to a folder is an entry too (os.walk does not enter it): not ours
        links = [d for d in dirs if os.path.islink(os.path.join(root, d))]
        dirs[:] = [d for d in dirs if d not in links]
        for f in sorted(files + links):
            if not _TEMP.match(f):
                yield Path(root, f).relative_to(folder).as_posix()


def _relative_files(folder: Path) -> list[str]:
    return sorted(_walk_files(folder))


def _foreign_files(out: Path, manifest: dict[str, Any] | None, limit: int = 4) -> list[str]:
    """Up to ``limit`` files in ``out`` that are not an unchanged result in our manifest (the
    walk stops there: ``--out ~`` must not read the whole home folder)."""
    ours = {} if manifest is None else manifest["files"]
    foreign = []
    for rel in _walk_files(out):
        if rel == MANIFEST and manifest is not None:
            continue
        if not is_ours(out, rel, ours.get(rel)):
            foreign.append(rel)
            if len(foreign) >= limit:
                break
    return foreign


def _resolved(paths: Iterable[str | os.PathLike[str]]) -> set[Path]:
    return {Path(p).resolve() for p in paths}


def check_writable_dir(out: str | os.PathLike[str], *, option: str = "--out") -> Path:
    """Check that ``out`` is, or can be created as, a writable folder; ``ValueError`` if not.

    ``option`` is the option's name in the messages (``--copy`` for ``examples``). An empty
    name (which would be the working folder) and a symbolic link to nothing (the results could
    not be moved there at the end) are refused. What the folder may already hold is the
    caller's rule (:func:`check_output_dir` for results folders; sweeps keep their own
    marker)."""
    if os.fspath(out) == "":
        raise ValueError(f"{option} is empty: name a folder ({option} . for the current one)")
    out = Path(out)
    if out.is_symlink() and not out.exists():
        raise ValueError(f"{option} {out} is a symbolic link to {os.readlink(out)}, which does "
                         "not exist: create that folder or choose another")
    if out.exists() and not out.is_dir():
        raise ValueError(f"{option} {out} is an existing file, not a folder")
    parent = out.resolve().parent
    if not out.exists() and not parent.is_dir():
        raise ValueError(f"{option} {out}: parent folder {parent} does not exist")
    if out.exists():
        if not os.access(out, os.W_OK | os.X_OK):
            raise ValueError(f"{option} {out} is not writable")
    elif not os.access(parent, os.W_OK | os.X_OK):
        raise ValueError(f"{option} {out} is not writable (cannot create it in {parent})")
    return out


def check_output_dir(out: str | os.PathLike[str], *, force: bool = False,
                     option: str = "--out", command: str | None = None) -> Path:
    """Check, before any work, that ``out`` can receive a result; raise ``ValueError`` if not.

    Parameters
    ----------
    out : path
        The results folder: new, empty, or holding a previous result of ours.
    force : bool
        Accept a folder that holds other files too (they are kept; see the module docstring).
    option : str
        The option's name in the messages.
    command : str or None
        The command that will write the result (as :func:`output_directory` records it): a
        previous result of another command is refused unless ``force``. ``None``: any.
    """
    out = check_writable_dir(out, option=option)
    if out.is_dir() and not force:
        remove_stale_temporaries(out)
        manifest = _read_manifest(out)
        old = None if manifest is None else manifest.get("command")
        if command is not None and old is not None and old != command:
            raise ValueError(
                f"{option} {out} holds a previous {old} result (written "
                f"{manifest.get('written', '?')}): a {command} run would replace it; choose "
                "another folder, or add --force to replace it")
        foreign = _foreign_files(out, manifest)
        if foreign:
            shown = ", ".join(foreign[:3]) + (" and more" if len(foreign) > 3 else "")
            raw = _raw_manifest(out)
            if isinstance(raw, dict) and raw.get("format") == EXAMPLES_FORMAT:
                what = ("the examples that 'dryfriction examples --copy' copied there (yours: "
                        "no run replaces or removes them)")
            elif manifest is None:
                what = "files this program did not write"
            else:
                what = "files that are not an unchanged result of this program"
            raise ValueError(
                f"{option} {out} holds {what} ({shown}): choose a new or empty folder, or add "
                "--force to write beside them (nothing there is deleted or overwritten)")
    return out


def _back_up(path: Path) -> Path | None:
    """Keep what is at ``path`` under ``NAME.~N~``, the first N free (GNU
    ``--backup=numbered``), claimed so that it cannot take a name another writer claims at the
    same time; ``None`` when nothing is at ``path`` any more (another writer moved it away).

    A file or a symbolic link gets a second hard link (``link`` fails on an existing name), so
    it is never without a name: the caller then replaces ``path``. A folder, or a file on a
    file system without hard links, is renamed onto an empty placeholder claimed with
    ``mkdir`` or ``O_EXCL`` (``rename`` replaces only that placeholder)."""
    n = 1
    while True:
        backup = path.with_name(f"{path.name}.~{n}~")
        try:
            is_dir = stat.S_ISDIR(os.lstat(path).st_mode)
        except FileNotFoundError:
            return None
        placeholder = False
        try:
            if is_dir:
                os.mkdir(backup, 0o700)
                placeholder = True
            else:
                try:
                    os.link(path, backup, follow_symlinks=False)
                    return backup
                except OSError as exc:
                    if exc.errno in (errno.EEXIST, errno.ENOENT):
                        raise
                    os.close(os.open(backup, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
                    placeholder = True
            os.rename(path, backup)
            return backup
        except FileExistsError:
            n += 1
        except FileNotFoundError:
            if placeholder:  # ours, empty: nobody else could claim that name
                with contextlib.suppress(OSError):
                    (os.rmdir if is_dir else os.unlink)(backup)
            if not (os.path.lexists(path)):
                return None


def _write_manifest(folder: Path, command: str, files: Mapping[str, str],
                    hand_over: bool = False) -> None:
    manifest = {
        "format": EXAMPLES_FORMAT if hand_over else MANIFEST_FORMAT,
        "version": 1,
        "command": command,
        "written": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "files": dict(files),
    }
    if hand_over:
        manifest["note"] = ("a record of what was copied: these files are yours, no run of "
                            "dryfriction replaces or removes them")
    atomic_write_text(folder / MANIFEST, json.dumps(manifest, indent=2) + "\n")


def _not_a_folder(out: Path, rel: str) -> str | None:
    """The first folder on the way to ``out/rel`` that exists as something else than a real
    folder (a symbolic link, which could lead outside ``out``, or a file), or ``None``."""
    path = out
    for part in rel.split("/")[:-1]:
        path = path / part
        try:
            if not stat.S_ISDIR(os.lstat(path).st_mode):
                return path.relative_to(out).as_posix()
        except FileNotFoundError:
            return None
    return None


def _commit(stage: Path, out: Path, command: str, protected: set[Path], force: bool,
            report: Callable[[str], None], option: str = "--out",
            hand_over: bool = False) -> None:
    """Move the staged files into ``out`` (which exists) and write the manifest last."""
    old = _read_manifest(out)
    old_files: dict[str, str] = {} if old is None else dict(old["files"])
    new = _relative_files(stage)
    digests = {rel: _sha256(stage / rel) for rel in new}
    replaced, removed, backed_up, kept = [], [], [], {}
    collide = []
    # every refusal before the first file moves: "nothing was written" must stay true
    for rel in new:
        dest = out / rel
        if dest.resolve() in protected:
            raise ValueError(f"{option} {out}: the result {rel} would overwrite an input of "
                             "this run; choose another folder")
        blocked = _not_a_folder(out, rel)
        if blocked is not None:
            raise ValueError(f"{option} {out}: {blocked} is a symbolic link or a file where "
                             f"the result {rel} needs a folder; nothing was written (choose "
                             "another folder)")
        if os.path.lexists(dest):
            if is_ours(out, rel, old_files.get(rel)):
                replaced.append(rel)
            elif force:
                collide.append(dest)
            else:  # appeared during the run
                raise ValueError(f"{option} {out}: {rel} appeared there during the run and is "
                                 "not ours; nothing was written (use --force to keep it as a "
                                 "backup)")
    for dest in collide:
        backup = _back_up(dest)
        if backup is not None:
            backed_up.append(f"{dest.relative_to(out).as_posix()} -> {backup.name}")
    for rel in new:
        dest = out / rel
        dest.parent.mkdir(parents=True, exist_ok=True)
        os.replace(stage / rel, dest)
    for rel, digest in old_files.items():
        if rel in digests or not is_ours(out, rel, digest):
            continue  # changed since (or never inside the folder): not ours
        path = out / rel
        if path.resolve() in protected:
            kept[rel] = digest  # an input of this run: stays, and stays ours
            continue
        path.unlink()
        removed.append(rel)
    if old is None and os.path.lexists(out / MANIFEST):  # not a results manifest (force)
        backup = _back_up(out / MANIFEST)
        if backup is not None:
            backed_up.append(f"{MANIFEST} -> {backup.name}")
    _write_manifest(out, command, {**kept, **digests}, hand_over)
    if old is not None and (replaced or removed):
        report(f"replaced the previous {old.get('command', 'result')} result in {out} "
               f"(written {old.get('written', '?')}): {len(replaced)} file(s) overwritten, "
               f"{len(removed)} removed")
    if backed_up:
        report(f"kept {len(backed_up)} existing file(s) under backup names: "
               + ", ".join(backed_up))


@contextlib.contextmanager
def output_directory(out: str | os.PathLike[str], *, command: str = "results",
                     force: bool = False, inputs: Iterable[str | os.PathLike[str]] = (),
                     report: Callable[[str], None] | None = None, option: str = "--out",
                     hand_over: bool = False) -> Iterator[Path]:
    """Yield a staging folder whose files move into ``out`` only if the block finishes.

    On any exception (including Ctrl-C and SIGTERM, which the CLI turns into one) the staging
    folder is removed and ``out`` is left as it was: results appear whole or not at all. The
    rules for an existing ``out`` are in the module docstring; ``report`` receives one line for
    each thing done to files that were already there.

    Parameters
    ----------
    out : path
        The results folder.
    command : str
        What wrote the result (recorded in the manifest).
    force : bool
        Write beside files we did not write (kept, colliding ones under backup names).
    inputs : paths
        Files the run reads: never overwritten or removed.
    report : callable, optional
        ``report(line)`` for what happened to existing files (default: nothing).
    option : str
        The option's name in the messages (``--copy`` for ``examples``).
    hand_over : bool
        The files are handed to the user (``examples --copy``): the manifest, of format
        :data:`EXAMPLES_FORMAT`, records them but no later run replaces or removes them.
    """
    out = check_output_dir(out, force=force, option=option, command=command)
    protected = _resolved(inputs)
    say = report if report is not None else (lambda line: None)
    existed = out.is_dir()
    parent = out if existed else out.resolve().parent
    remove_stale_temporaries(parent)
    _, tmp = _make_temp(parent, out.name if not existed else "results", directory=True)
    stage = Path(tmp)
    try:
        yield stage
        with deferred(defaults=True):
            if existed:
                _commit(stage, out, command, protected, force, say, option, hand_over)
                shutil.rmtree(stage, ignore_errors=True)
            else:
                files = {rel: _sha256(stage / rel) for rel in _relative_files(stage)}
                _write_manifest(stage, command, files, hand_over)
                os.chmod(stage, 0o777 & ~_umask())  # as mkdir would, not 0o700
                try:
                    os.rename(stage, out)  # never replaces: a folder made meanwhile stays
                except OSError as exc:
                    if not out.is_dir():  # a file or a link to nothing made meanwhile
                        raise ValueError(f"{option} {out} appeared during the run and is not "
                                         f"a folder ({exc.strerror}); nothing was written "
                                         "there") from None
                    (stage / MANIFEST).unlink()
                    _commit(stage, out, command, protected, force, say, option, hand_over)
                    shutil.rmtree(stage, ignore_errors=True)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
