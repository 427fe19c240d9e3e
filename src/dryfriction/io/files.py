"""Output files written whole or not at all, and never at the cost of a user's files.

Every writer goes through a temporary file in the destination folder and ``os.replace``.
:func:`output_directory` stages a whole folder of results and moves it into place only when the
run finishes. The rules for an existing ``--out`` folder (ours):

* a new or empty folder receives the results;
* a folder holding a previous result of ours (recognised by the manifest :data:`MANIFEST`, which
  lists every file the run wrote with its SHA-256) gets the new result; the previous run's files
  are replaced or removed (and this is reported), except files the new run reads;
* a folder holding anything else (a file we did not write, or one of ours changed since) is
  refused before any work, unless ``force``: then the results are written beside those files, a
  file whose name collides with a result is kept under a numbered backup name (``NAME.~1~``), and
  nothing is deleted;
* no folder is ever removed or replaced (``--out .`` is safe), only files we wrote;
* temporary files and folders carry the writer's process id; one left by a killed run is removed
  by the next run that writes there.
"""

from __future__ import annotations

import contextlib
import csv
import datetime
import hashlib
import io
import json
import math
import os
import re
import secrets
import shutil
import signal
import threading
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "MANIFEST",
    "atomic_write_bytes",
    "atomic_write_text",
    "write_json",
    "write_csv",
    "output_directory",
    "check_output_dir",
    "check_writable_dir",
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
    path: str | os.PathLike[str], columns: Mapping[str, Sequence[float] | np.ndarray]
) -> Path:
    """Write equal-length columns as CSV with a header row, full float precision."""
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
_TEMP = re.compile(r"^\..*\.dftmp-(\d+)-[0-9a-f]+\.tmp$")


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


def _read_manifest(out: Path) -> dict[str, Any] | None:
    """The manifest of a results folder of ours, or ``None`` if there is none (or not ours)."""
    try:
        m = json.loads((out / MANIFEST).read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(m, dict) or m.get("format") != MANIFEST_FORMAT:
        return None
    files = m.get("files")
    if not isinstance(files, dict):
        return None
    return m


def _walk_files(folder: Path) -> Iterator[str]:
    """Every file below ``folder`` as a POSIX relative path, lazily (our temporaries left
    out)."""
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not _TEMP.match(d))
        for f in sorted(files):
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
        digest = ours.get(rel)
        if digest is None or digest != _sha256(out / rel):
            foreign.append(rel)
            if len(foreign) >= limit:
                break
    return foreign


def _resolved(paths: Iterable[str | os.PathLike[str]]) -> set[Path]:
    return {Path(p).resolve() for p in paths}


def check_writable_dir(out: str | os.PathLike[str]) -> Path:
    """Check that ``out`` is, or can be created as, a writable folder; ``ValueError`` if not.

    What the folder may already hold is the caller's rule (:func:`check_output_dir` for
    results folders; sweeps keep their own marker)."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise ValueError(f"--out {out} is an existing file, not a folder")
    parent = out.resolve().parent
    if not out.exists() and not parent.is_dir():
        raise ValueError(f"--out {out}: parent folder {parent} does not exist")
    if out.exists():
        if not os.access(out, os.W_OK | os.X_OK):
            raise ValueError(f"--out {out} is not writable")
    elif not os.access(parent, os.W_OK | os.X_OK):
        raise ValueError(f"--out {out} is not writable (cannot create it in {parent})")
    return out


def check_output_dir(out: str | os.PathLike[str], *, force: bool = False) -> Path:
    """Check, before any work, that ``out`` can receive a result; raise ``ValueError`` if not.

    Parameters
    ----------
    out : path
        The results folder: new, empty, or holding a previous result of ours.
    force : bool
        Accept a folder that holds other files too (they are kept; see the module docstring).
    """
    out = check_writable_dir(out)
    if out.is_dir() and not force:
        remove_stale_temporaries(out)
        manifest = _read_manifest(out)
        foreign = _foreign_files(out, manifest)
        if foreign:
            shown = ", ".join(foreign[:3]) + (" and more" if len(foreign) > 3 else "")
            what = ("files this program did not write" if manifest is None
                    else "files that are not an unchanged result of this program")
            raise ValueError(
                f"--out {out} holds {what} ({shown}): choose a new or empty folder, or add "
                "--force to write beside them (nothing there is deleted or overwritten)")
    return out


def _backup_name(path: Path) -> Path:
    """``NAME.~N~`` with the first free N (GNU ``--backup=numbered``)."""
    n = 1
    while True:
        candidate = path.with_name(f"{path.name}.~{n}~")
        if not candidate.exists() and not candidate.is_symlink():
            return candidate
        n += 1


@contextlib.contextmanager
def _signals_deferred() -> Iterator[None]:
    """Hold back Ctrl-C and SIGTERM during a short critical section, then deliver them.

    Only possible in the main thread (where Python handles signals); elsewhere a no-op.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    kinds = (signal.SIGINT, signal.SIGTERM)
    previous = {s: signal.signal(s, lambda signum, frame: caught.append(signum)) for s in kinds}
    try:
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
        for s in dict.fromkeys(caught):  # deliver each once, through the restored handler
            signal.raise_signal(s)


def _write_manifest(folder: Path, command: str, files: Mapping[str, str]) -> None:
    manifest = {
        "format": MANIFEST_FORMAT,
        "version": 1,
        "command": command,
        "written": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "files": dict(files),
    }
    atomic_write_text(folder / MANIFEST, json.dumps(manifest, indent=2) + "\n")


def _commit(stage: Path, out: Path, command: str, protected: set[Path], force: bool,
            report: Callable[[str], None]) -> None:
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
            raise ValueError(f"--out {out}: the result {rel} would overwrite an input of this "
                             "run; choose another folder")
        if dest.exists() or dest.is_symlink():
            if old_files.get(rel) is not None and dest.is_file() and \
                    old_files[rel] == _sha256(dest):
                replaced.append(rel)
            elif force:
                collide.append(dest)
            else:  # appeared during the run
                raise ValueError(f"--out {out}: {rel} appeared there during the run and is "
                                 "not ours; nothing was written (use --force to keep it as a "
                                 "backup)")
    for dest in collide:
        backup = _backup_name(dest)
        os.replace(dest, backup)
        backed_up.append(f"{dest.relative_to(out).as_posix()} -> {backup.name}")
    for rel in new:
        dest = out / rel
        dest.parent.mkdir(parents=True, exist_ok=True)
        os.replace(stage / rel, dest)
    for rel, digest in old_files.items():
        if rel in digests:
            continue
        path = out / rel
        if not path.is_file() or _sha256(path) != digest:
            continue  # changed since: no longer ours
        if path.resolve() in protected:
            kept[rel] = digest  # an input of this run: stays, and stays ours
            continue
        path.unlink()
        removed.append(rel)
    if old is None and (out / MANIFEST).exists():  # someone else's file of that name (force)
        backup = _backup_name(out / MANIFEST)
        os.replace(out / MANIFEST, backup)
        backed_up.append(f"{MANIFEST} -> {backup.name}")
    _write_manifest(out, command, {**kept, **digests})
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
                     report: Callable[[str], None] | None = None) -> Iterator[Path]:
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
    """
    out = check_output_dir(out, force=force)
    protected = _resolved(inputs)
    say = report if report is not None else (lambda line: None)
    existed = out.is_dir()
    parent = out if existed else out.resolve().parent
    remove_stale_temporaries(parent)
    _, tmp = _make_temp(parent, out.name if not existed else "results", directory=True)
    stage = Path(tmp)
    try:
        yield stage
        with _signals_deferred():
            if existed:
                _commit(stage, out, command, protected, force, say)
                shutil.rmtree(stage, ignore_errors=True)
            else:
                files = {rel: _sha256(stage / rel) for rel in _relative_files(stage)}
                _write_manifest(stage, command, files)
                os.chmod(stage, 0o777 & ~_umask())  # as mkdir would, not 0o700
                try:
                    os.rename(stage, out)  # never replaces: a folder made meanwhile stays
                except OSError:
                    if not out.is_dir():
                        raise
                    (stage / MANIFEST).unlink()
                    _commit(stage, out, command, protected, force, say)
                    shutil.rmtree(stage, ignore_errors=True)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
