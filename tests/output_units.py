"""The check that every number a results folder holds carries its unit
(:mod:`dryfriction.io.units`), shared by the tests of the writers."""

from __future__ import annotations

import json
from pathlib import Path

from dryfriction.io import units as U

LABELS = {k for name in dir(U) if name.endswith("_UNITS")
          for k, v in getattr(U, name).items() if v is None}
"""Every column declared a label (no quantity) in any table of dryfriction.io.units."""


def check_folder(out: Path) -> list[str]:
    """What in ``out`` has no unit: ``FILE: column`` for each."""
    bad: list[str] = []
    for path in sorted(out.iterdir()):
        if path.suffix == ".csv":
            first = next(ln for ln in path.read_text().splitlines() if not ln.startswith("#"))
            for h in first.split(","):
                name, unit = U.split_header(h)
                if (unit is None and name not in LABELS) or unit == "":
                    bad.append(f"{path.name}: {h}")
        elif path.suffix == ".json" and path.name != "dryfriction.json":
            bad += [f"{path.name}: {k}" for k in U.undeclared(json.loads(path.read_text()))]
    return bad
