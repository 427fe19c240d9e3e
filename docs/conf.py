"""Sphinx configuration of the dryfriction documentation (``make docs``).

The site is built and read offline: no intersphinx, no MathJax from a CDN (math is shown as
plain text by the local ``plainmath`` extension), no web fonts.
"""

from __future__ import annotations

import os
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
html_static_path: list[str] = []
html_show_sourcelink = False
html_theme_options = {
    "description": "The Caroli–Velický model of dry friction",
    "page_width": "1100px",
    "sidebar_width": "240px",
    "font_family": "sans-serif",
    "head_font_family": "sans-serif",
}
