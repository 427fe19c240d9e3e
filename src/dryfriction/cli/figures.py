"""What the painter (:mod:`.painter`) imports first, while the command solves.

The figures a command hands to its painter are functions of :mod:`dryfriction.app` (e.g.
:func:`dryfriction.app.ratestate.rsf_figure`), each importing its builder in
:mod:`dryfriction.plots.runs` when called, so that a command naming it imports no matplotlib
(the painter has imported it already, :func:`preload`), while the imports stay import
statements that the layer and cycle checks of ``tests/test_layers.py`` see.
A reference pickles as its module and name, so the painter receives it as cheaply as a string.
"""

from __future__ import annotations

__all__ = ["preload"]


def preload() -> None:
    """Import the figure modules (the painter's first work, while the command solves)."""
    from ..plots import runs  # noqa: F401
