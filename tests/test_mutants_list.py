"""The list of mutants stays runnable (``make mutants`` is not part of CI, so a source change
that moves a mutant's text would otherwise go unnoticed until the next mutation run: two had
gone stale that way)."""

from __future__ import annotations

import pytest

from mutants import MUTANTS, ROOT


def test_mutant_names_are_unique() -> None:
    names = [m.name for m in MUTANTS]
    assert len(names) == len(set(names))


@pytest.mark.parametrize("mutant", MUTANTS, ids=lambda m: m.name)
def test_mutant_applies_exactly_once_and_names_its_tests(mutant) -> None:  # type: ignore[no-untyped-def]
    text = (ROOT / mutant.file).read_text()
    assert text.count(mutant.original) == 1, "stale: update tests/mutants.py"
    assert mutant.replacement != mutant.original
    assert mutant.tests and (ROOT / mutant.tests[0].split("::")[0]).exists()


def test_test_selection_names_are_assigned_once() -> None:
    """Two helpers' blocks once both named a selection ``_S7LS`` (and two more): the later
    assignment silently sent the earlier block's mutants to the other block's tests. Every
    module-level name of tests/mutants.py is assigned once."""
    import ast

    tree = ast.parse((ROOT / "tests" / "mutants.py").read_text())
    names = [t.id for node in tree.body if isinstance(node, ast.Assign)
             for t in node.targets if isinstance(t, ast.Name)]
    assert len(names) == len(set(names)), sorted({n for n in names if names.count(n) > 1})
