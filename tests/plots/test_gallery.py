"""The gallery (``examples/gallery``, run by ``make docs``): at least ten examples, among them
the fit of a laboratory record and the command line, and every file a script reads is shipped
inside the repository (the site builds offline in a fresh clone: no ``../shared`` record).
Running the scripts is the site build's test (tests/test_docs.py, slow)."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
GALLERY = ROOT / "examples" / "gallery"
SCRIPTS = sorted(GALLERY.glob("plot_*.py"))
DATA = re.compile(r"\.(txt|toml|csv|xlsx|mat)$")


def _literals(path: Path) -> list[str]:
    """Every string constant of the script (docstrings included)."""
    return [n.value for n in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
            if isinstance(n, ast.Constant) and isinstance(n.value, str)]


def test_at_least_ten_examples_with_the_lab_record_and_the_command_line():
    assert len(SCRIPTS) >= 10, [p.name for p in SCRIPTS]
    texts = {p.name: p.read_text(encoding="utf-8") for p in SCRIPTS}
    assert any("records import lab" in t and "fit_steps" in t for t in texts.values())
    assert any('"dryfriction.cli"' in t and "subprocess" in t for t in texts.values())


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_every_file_a_script_names_is_shipped_in_the_repository(script: Path):
    shipped = {p.name for p in (ROOT / "examples").rglob("*") if p.is_file()}
    # files the script writes itself (a protocol for the command line)
    shipped |= set(re.findall(r'/ "([^"]+)"\)\.write_text', script.read_text(encoding="utf-8")))
    for text in _literals(script):
        if "\n" in text:  # a docstring or a protocol written by the script itself
            continue
        for part in text.split():
            part = part.strip("`'\",()")
            if not DATA.search(part):
                continue
            assert "shared" not in part and not part.startswith(".."), (
                f"{script.name} reads {part!r}, outside the repository")
            assert Path(part).name in shipped, f"{script.name}: {part!r} is not shipped"


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_every_script_has_a_title_and_short_lines(script: Path):
    text = script.read_text(encoding="utf-8")
    title = text.split('"""')[1].strip().splitlines()
    assert len(title) >= 2 and set(title[1]) == {"="} and len(title[1]) >= len(title[0])
    # code blocks of the site fit 800 px without a scroll bar at about 100 characters
    long = [n for n, line in enumerate(text.splitlines(), 1) if len(line) > 100]
    assert not long, f"{script.name}: lines {long} are over 100 characters"
