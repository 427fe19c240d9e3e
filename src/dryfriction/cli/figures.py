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

__all__ = ["comparison_figure", "preload", "rsf_figure", "rsf_timeseries_figure",
           "timeseries_figure"]


def preload() -> None:
    """Import the figure modules (the painter's first work, while the command solves)."""
    from ..plots import runs  # noqa: F401


def timeseries_figure(result: Any) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.runs.timeseries_figure` (the trap model's run)."""
    from ..plots.runs import timeseries_figure as build

    return build(result)


def rsf_timeseries_figure(result: Any) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.runs.rsf_timeseries_figure` (a rate-and-state protocol run)."""
    from ..plots.runs import rsf_timeseries_figure as build

    return build(result)


def rsf_figure(result: Any, title: str) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.runs.rsf_figure` (the ``rsf`` command's figure)."""
    from ..plots.runs import rsf_figure as build

    return build(result, title)


def comparison_figure(c: Any, title: str = "") -> tuple[Any, Any]:
    """:func:`dryfriction.plots.runs.comparison_figure` (the ``compare`` command's figure)."""
    from ..plots.runs import comparison_figure as build

    return build(c, title)
