"""The old module paths import for one release, with a warning naming the new path.

The mistake this is for: a module moved (``io/lab.py`` -> ``records/lab.py``, issue 26) and
left out of :data:`dryfriction._compat.MOVED`, so that a user's ``import dryfriction.io.lab``
fails at once instead of warning for a release.
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

import pytest

import dryfriction
from dryfriction._compat import MOVED

SRC = Path(dryfriction.__file__).resolve().parent
# an old flat module that is a package's name now (dryfriction.ensemble) is that package
STILL_MOVED = sorted(old for old in MOVED if not (SRC / old).is_dir())

# the modules of io/ that moved in issue 26 item 3 (by concern: records, sweeps)
IO_MOVED = {"lab", "labsteps", "labforms", "data", "detection", "segmentation", "placement",
            "artifacts", "hinge_kernel", "sweep", "cluster", "cf"}


def test_every_moved_io_module_is_listed() -> None:
    assert {f"io.{m}" for m in IO_MOVED} <= set(MOVED)


@pytest.mark.parametrize("old", STILL_MOVED)
def test_the_old_path_warns_and_gives_the_new_names(old: str) -> None:
    new = importlib.import_module(f"dryfriction.{MOVED[old]}")
    name = f"dryfriction.{old}"
    parent_name, _, leaf = name.rpartition(".")
    parent = sys.modules[parent_name]
    before = (sys.modules.pop(name, None), vars(parent).get(leaf))
    try:
        with pytest.warns(DeprecationWarning, match=f"dryfriction.{MOVED[old]}"):
            module = importlib.import_module(name)
        public = getattr(new, "__all__", None) or [n for n in vars(new) if not n.startswith("_")]
        assert public
        assert all(getattr(module, n) is getattr(new, n) for n in public)
    finally:
        # leave no old path behind: the import set it as the parent package's attribute, which
        # tests/test_doc_paths.py would then find
        sys.modules.pop(name, None)
        if before[0] is not None:
            sys.modules[name] = before[0]
        if before[1] is None:
            vars(parent).pop(leaf, None)
        else:
            setattr(parent, leaf, before[1])


def test_the_lazy_public_names_use_current_paths() -> None:
    # ``dryfriction.read_csv`` is loaded from a module named in a string: an old path there
    # would still work (through the finder above) while warning every user of the name
    where = {name: (module, name) for name, module in dryfriction._PUBLIC.items()}
    where.update(dryfriction._RENAMED)
    assert "read_csv" in where
    stale = [f"{name}: {module}" for name, (module, _) in where.items() if module in MOVED]
    assert not stale, stale
    for name, (module, attr) in where.items():
        real = importlib.import_module(f"dryfriction.{module}")
        assert name == "fit" or hasattr(real, attr), f"{name}: dryfriction.{module}.{attr}"
