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
