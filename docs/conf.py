"""Sphinx configuration of the dryfriction documentation (``make docs``).

The site is built and read offline: no intersphinx, no MathJax from a CDN (math is shown as
plain text by the local ``plainmath`` extension), no web fonts.
"""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(ROOT / "src"))
os.environ.setdefault("MPLBACKEND", "Agg")

import dryfriction  # noqa: E402

project = "dryfriction"
author = "the dryfriction developers"
copyright = "the dryfriction developers, MIT licence"  # noqa: A001
release = version = dryfriction.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.viewcode",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "plainmath",
]
html_math_renderer = "plainmath"

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.md5", "auto_examples/*.json"]
root_doc = "index"

autosummary_generate = True
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_member_order = "bysource"
autodoc_typehints = "description"
# a type hint imported only for type checking is a bare name that both the defining module
# and its re-export match (Output, SimulationResult, RSFResult): Sphinx links the first and
# warns, which -W would turn into a failure
suppress_warnings = ["ref.python"]
# the docstrings are NumPy style
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False

myst_heading_anchors = 3

sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples" / "gallery"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "matplotlib_animations": False,
    "within_subsection_order": "FileNameSortKey",
    "show_memory": False,
    "capture_repr": (),  # no "Out: Text(...)" under the figures
    # its page loads DataTables from a CDN: the site must work offline
    "write_computation_times": False,
    "plot_gallery": "True",
}

html_theme = "alabaster"
html_title = f"dryfriction {release}"
# custom.css (alabaster links it by that name): code wraps and wide tables scroll within
# the page, so that every page reads in an 800 px window
html_static_path = ["_static"]
html_show_sourcelink = False
html_theme_options = {
    "description": "The Caroli–Velický model of dry friction",
    "page_width": "1100px",
    "sidebar_width": "240px",
    "font_family": "sans-serif",
    "head_font_family": "sans-serif",
}


# Some docstrings name the project's tracker ("issue 26", "issue 30 item 3") for developers
# reading the source; a reader of this site has no tracker, so the API pages drop those
# references (tests/test_docs.py checks that no page shows one).
_BEFORE_ISSUE = re.compile(r"\bbefore issue\s+\d+")
_TRAILING_ISSUE = re.compile(
    r"[,;]\s*issues?\s+\d+(?:,?\s+items?\s+\d+(?:\s+and\s+\d+)?)?(?=\s*\))")
_ISSUE = re.compile(
    r"\bissues?\s+\d+(?:'s)?(?:,?\s+items?\s+\d+(?:\s+and\s+\d+)?)?(?:\s*[,;:]\s*|\s*(?=\)))")
_EMPTY_PARENS = re.compile(r"\s*\(\s*\)")


def strip_issue_numbers(text: str) -> str:
    """``text`` without references to the project's issue tracker."""
    text = _BEFORE_ISSUE.sub("in an earlier version", text)
    text = _TRAILING_ISSUE.sub("", text)
    text = _ISSUE.sub("", text)
    return _EMPTY_PARENS.sub("", text)


def _drop_issue_numbers(app, what, name, obj, options, lines: list[str]) -> None:
    cleaned = strip_issue_numbers("\n".join(lines)).split("\n")
    lines[:] = cleaned


def setup(app) -> None:
    app.connect("autodoc-process-docstring", _drop_issue_numbers)
