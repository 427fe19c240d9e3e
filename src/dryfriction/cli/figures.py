"""The figures a command hands to its painter (:mod:`.painter`), as functions, not names.

Each one imports its builder in :mod:`dryfriction.plots.runs` when called, so that a command
naming it imports no matplotlib (the painter has imported it already, :func:`preload`), while
the imports stay import statements: the layer and cycle checks of ``tests/test_layers.py`` and a
type checker see them, which they did not see in the ``"module:function"`` strings these replace
(issue 26 item 3). A reference pickles as its module and name, so the painter receives it as
cheaply as a string.
"""

from __future__ import annotations

from typing import Any

__all__ = ["preload", "rsf_figure"]


def preload() -> None:
    """Import the figure modules (the painter's first work, while the command solves)."""
    from ..plots import runs  # noqa: F401


def rsf_figure(result: Any, title: str) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.runs.rsf_figure` (the ``rsf`` command's figure)."""
    from ..plots.runs import rsf_figure as build

    return build(result, title)

