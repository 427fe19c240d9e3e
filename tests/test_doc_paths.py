"""Docstrings, comments and help name the package's current paths (issue 26 item 6).

After the re-layout into layer folders, 36 docstrings still named module paths of release 0.1
(``dryfriction.driving.simulate``, ``dryfriction.stability.effective_rsf``): a reader who
follows one gets an ImportError (or, through the compatibility finder, a deprecation warning).
Every absolute ``dryfriction.a.b`` in the package's source must import and resolve to an
attribute, and every relative Sphinx reference ``:func:`.a.b``` must end a real path, except
in :mod:`dryfriction._compat`, whose subject is the old paths. The command line's help, as a
user reads it (every command's and option's text, composed however the source composes it), is
held to the same rule.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
from functools import cache
from pathlib import Path

import dryfriction

SRC = Path(dryfriction.__file__).resolve().parent
ABSOLUTE = re.compile(r"\bdryfriction(?:\.[A-Za-z_]\w*)+")
RELATIVE = re.compile(r":(?:mod|func|class|meth|attr|data|obj|exc):`~?(\.[A-Za-z_][\w.]*)`")
IMPORT_LINE = re.compile(r"\s*(from|import)\s")
OLD_PATHS_ON_PURPOSE = {"_compat.py"}


@cache
def modules() -> dict[str, object]:
    out: dict[str, object] = {"dryfriction": dryfriction}
    for info in pkgutil.walk_packages(dryfriction.__path__, "dryfriction."):
        if info.name.endswith("__main__"):  # running it would run the command line
            continue
        out[info.name] = importlib.import_module(info.name)
    return out


def resolves(path: str) -> bool:
    """``path`` is a module, or a module's attribute chain (lazy names included)."""
    parts = path.split(".")
    for i in range(len(parts), 0, -1):
        module = modules().get(".".join(parts[:i]))
        if module is None:
            continue
        obj = module
        for name in parts[i:]:
            try:
                obj = getattr(obj, name)
            except AttributeError:
                return False
        return True
    return False


@cache
def every_name() -> frozenset[str]:
    """Every module, module attribute and class attribute, as full dotted paths."""
    names = set()
    for mod_name, module in modules().items():
        names.add(mod_name)
        for attr, obj in vars(module).items():
            names.add(f"{mod_name}.{attr}")
            if inspect.isclass(obj):
                names.update(f"{mod_name}.{attr}.{member}" for member in vars(obj))
    return frozenset(names)


def references() -> list[tuple[str, int, str, bool]]:
    """(file, line, path, absolute) for each path named outside import statements."""
    found = []
    for file in sorted(SRC.rglob("*.py")):
        if file.name in OLD_PATHS_ON_PURPOSE:
            continue
        for number, line in enumerate(file.read_text().splitlines(), 1):
            if IMPORT_LINE.match(line):
                continue
            rel = str(file.relative_to(SRC))
            found += [(rel, number, m.group(0).rstrip("."), True) for m in ABSOLUTE.finditer(line)
                      if m.group(0) != "dryfriction.json"]  # the manifest's file name
            found += [(rel, number, m.group(1), False) for m in RELATIVE.finditer(line)]
    return found


def test_every_named_path_exists() -> None:
    refs = references()
    assert len(refs) > 200  # the scan sees the docstrings
    names = every_name()
    stale = [f"{f}:{n}: {p}" for f, n, p, absolute in refs
             if not (resolves(p) if absolute else any(x.endswith(p) for x in names))]
    assert not stale, "stale paths:\n" + "\n".join(stale)


def help_texts() -> list[tuple[str, str]]:
    """(command, text) for the help of every command and group of the command line and of each
    of their arguments and options."""
    import typer

    from dryfriction.cli.commands import app

    def walk(command: object, path: str) -> list[tuple[str, str]]:
        texts = [getattr(command, "help", None), getattr(command, "epilog", None)]
        texts += [getattr(p, "help", None) for p in getattr(command, "params", [])]
        out = [(path, t) for t in texts if t]
        for name, sub in getattr(command, "commands", {}).items():
            out += walk(sub, f"{path} {name}")
        return out

    return walk(typer.main.get_command(app), "dryfriction")


def test_every_path_in_help_exists() -> None:
    texts = help_texts()
    assert len(texts) > 100  # the walk reaches the commands' options
    named = [(c, m.group(0).rstrip(".")) for c, t in texts for m in ABSOLUTE.finditer(t)]
    assert named  # at least one help text names a module (simulate's protocol)
    stale = [f"{c}: {p}" for c, p in named if not resolves(p)]
    assert not stale, "stale paths in help:\n" + "\n".join(stale)


def test_the_check_sees_an_old_path() -> None:
    # the mistake this file is for: a path of release 0.1, or a relative one that ends nowhere
    assert not resolves("dryfriction.stability.effective_rsf")
    assert not resolves("dryfriction.io.lab.read_record")  # moved to records/ (issue 26)
    assert resolves("dryfriction.records.lab.read_record")
    assert not resolves("dryfriction.theory.stability.effective_rsf_twin")
    assert resolves("dryfriction.theory.linear_stability.effective_rsf")
    assert not resolves("dryfriction.theory.stability.effective_rsf")  # moved (issue 26)
    assert resolves("dryfriction.rsf.RateState")  # a lazy public name
    assert not any(x.endswith(".steady.steady_frictions") for x in every_name())


def test_no_docstring_names_the_tracker() -> None:
    """What ``help()`` and the API pages show carries no issue number of the project's
    tracker (a user cannot look it up); developer comments may."""
    import ast

    tracker = re.compile(r"\b[Ii]ssues? \d+")
    found = []
    for path in SRC.rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            body = getattr(node, "body", None)
            if not isinstance(body, list):
                continue
            for prev, stmt in zip([None, *body], body, strict=False):
                doc = (isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant)
                       and isinstance(stmt.value.value, str))
                first = prev is None and isinstance(node, (ast.Module, ast.ClassDef,
                                                            ast.FunctionDef,
                                                            ast.AsyncFunctionDef))
                attr = isinstance(prev, (ast.Assign, ast.AnnAssign))
                if doc and (first or attr) and tracker.search(stmt.value.value):
                    found.append(f"{path.relative_to(SRC)}:{stmt.lineno}")
    assert not found, found
