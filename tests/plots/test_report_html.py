"""``report.html`` reads in a narrow window: every table inside a scrolling container, the
version, commit and date on the page, eq. 27 as MathML (nothing fetched from the network)."""

from __future__ import annotations

import re
from html.parser import HTMLParser

import pytest

from dryfriction import __version__
from dryfriction.plots import report

BUILD = {"version": __version__, "commit": "0123456789ab", "date": "2026-01-02 03:04 UTC"}


class _Tree(HTMLParser):
    """Records, for every <table> and <math>, the classes of the elements around it."""

    VOID = {"meta", "img", "br", "hr", "link", "input", "mspace"}

    def __init__(self) -> None:
        super().__init__()
        self.stack: list[tuple[str, str]] = []
        self.found: dict[str, list[list[tuple[str, str]]]] = {"table": [], "math": []}

    def handle_starttag(self, tag, attrs):
        if tag in self.found:
            self.found[tag].append(list(self.stack))
        if tag not in self.VOID:
            self.stack.append((tag, dict(attrs).get("class") or ""))

    def handle_endtag(self, tag):
        if tag in self.VOID:
            return
        while self.stack:
            if self.stack.pop()[0] == tag:
                break


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("figs")
    for name in (*report.FIGURE_FILES, *report.EXTRA_FILES):
        (folder / name).write_bytes(b"\x89PNG\r\n\x1a\n")  # only embedded, never decoded
    return folder, report.compute_summary()


@pytest.fixture(scope="module")
def page(inputs):
    return report.report_html(*inputs, BUILD)


def test_every_table_scrolls_inside_a_container_that_the_css_lets_overflow(page):
    tree = _Tree()
    tree.feed(page)
    assert len(tree.found["table"]) >= 2
    for ancestors in tree.found["table"]:
        assert ancestors[-1] == ("div", "table-wrap"), ancestors
    css = re.search(r"<style>(.*?)</style>", page, re.S).group(1)
    rule = re.search(r"\.table-wrap\{([^}]*)\}", css).group(1)
    assert "overflow-x:auto" in rule
    assert re.search(r"table\{[^}]*width:100%", css)  # the table takes the window's width
    assert '<meta name="viewport" content="width=device-width' in page
    assert "@media" in css


def test_the_page_says_version_commit_and_date(page, inputs):
    assert f"dryfriction {__version__}" in page
    assert "commit <code>0123456789ab</code>" in page and "2026-01-02 03:04 UTC" in page
    # installed from a wheel: no git, no commit, the rest stays
    bare = report.report_html(*inputs, {**BUILD, "commit": ""})
    assert "commit" not in bare.split("</h1>")[1].split("</p>")[0]
    assert f"dryfriction {__version__}" in bare


def test_eq27_is_mathml_and_nothing_is_fetched(page):
    tree = _Tree()
    tree.feed(page)
    assert len(tree.found["math"]) == 1
    math = re.search(r"<math display=\"block\">(.*?)</math>", page, re.S).group(1)
    for part in ("<mfrac>", "<msubsup><mo>∫</mo>", "<msup><mi>r</mi><mn>3</mn></msup>",
                 "<msub><mi>H</mi><mn>0</mn></msub>"):
        assert part in math, part
    assert "{∫" not in page  # the old LaTeX-like text
    assert not re.search(r"(src|href)=\"(https?:)?//", page)
    assert "http://" not in page and "https://" not in page


def test_build_info_reads_the_checkout():
    info = report.build_info()
    assert info["version"] == __version__
    assert re.fullmatch(r"\d{4}-\d\d-\d\d \d\d:\d\d UTC", info["date"])
    # tests run from a git checkout: the commit is found (hex, maybe "-dirty")
    assert re.fullmatch(r"[0-9a-f]{7,40}(-dirty)?", info["commit"]), info
