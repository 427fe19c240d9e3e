"""The example protocols, data and gallery scripts that ship with the package.

In a wheel they are the package data ``dryfriction/examples/``; in a source checkout (or an
editable install) the repository's ``examples/`` folder. :func:`copy_examples` (the command
``dryfriction examples --copy DIR``) copies them into a folder of the user's, where the
documentation's command lines run as written (``dryfriction simulate DIR/velocity_step.toml ...``).

The model's description (the specification that docstrings cite as ``docs/model.md §N``) ships
as the package data ``dryfriction/docs/model.md``: :func:`model_description`.
"""

from __future__ import annotations

import os
import shutil
from collections.abc import Callable
from pathlib import Path

__all__ = ["copy_examples", "example_files", "examples_path", "model_description"]

_SKIP = ("__pycache__", ".pyc")


def examples_path() -> Path:
    """The folder holding the examples (package data, or the checkout's ``examples/``).

    Raises
    ------
    OSError
        When neither exists (a broken install).
    """
    here = Path(__file__).resolve()
    # installed: the package data beside the package's modules; a source tree run with
    # PYTHONPATH=src (or installed editable): the repository's examples/ beside src/
    for folder in (here.parents[1] / "examples", here.parents[3] / "examples"):
        if (folder / "velocity_step.toml").is_file():
            return folder
    raise OSError("the examples are not installed with this copy of dryfriction "
                  "(expected the package data dryfriction/examples)")


def model_description() -> Path:
    """The model's description, ``dryfriction/docs/model.md`` (Markdown; the documentation
    site's page "The model" includes it).

    Raises
    ------
    OSError
        When it is missing (a broken install).
    """
    path = Path(__file__).resolve().parents[1] / "docs" / "model.md"
    if not path.is_file():
        raise OSError(f"the model's description is not installed with this copy of "
                      f"dryfriction (expected {path})")
    return path


def example_files() -> list[str]:
    """Every example file, as paths relative to :func:`examples_path` (sorted, POSIX)."""
    root = examples_path()
    return sorted(p.relative_to(root).as_posix() for p in root.rglob("*")
                  if p.is_file() and not any(s in p.as_posix() for s in _SKIP))


def copy_examples(dest: str | os.PathLike[str], *, force: bool = False,
                  report: Callable[[str], None] | None = None) -> list[str]:
    """Copy the examples into ``dest``, whole or not at all, and hand them to the user.

    The copy carries a manifest (``dryfriction.json``, format
    :data:`dryfriction.io.files.EXAMPLES_FORMAT`) that records what was copied and says the
    files are the user's: no later run (``simulate ... --out dest``, ``fit``, another copy)
    replaces or removes them; it is refused, or with ``--force`` writes beside them.

    Parameters
    ----------
    dest : path
        New or empty folder; see :func:`dryfriction.io.files.output_directory` for the rules
        (its messages name the option ``--copy``).
    force : bool
        Copy beside files already in ``dest`` (kept; a colliding one is renamed ``NAME.~1~``).
    report : callable, optional
        Receives one line per thing done to files already there.

    Returns
    -------
    list of str
        The copied files, relative to ``dest``.
    """
    from .files import output_directory

    root = examples_path()
    files = example_files()
    with output_directory(dest, command="examples", force=force, report=report,
                          option="--copy", hand_over=True) as stage:
        for rel in files:
            target = stage / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(root / rel, target)
    return files
