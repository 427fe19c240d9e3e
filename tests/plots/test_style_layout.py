"""The fixed layout of plots/style.py ``new_figure`` in inches, by its definition: margins
0.85 (left), 0.3 (right), 0.6 (bottom), 0.35 (top, plus 0.3 for a figure title), gaps 0.95
between columns and 0.75 between rows, whatever the figure's size; the refusal at the size
where a panel would have no width (both sides of the edge)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.plots.style import new_figure


@pytest.mark.parametrize("suptitle", [False, True])
def test_margins_and_gaps_in_inches(suptitle) -> None:
    # mistakes: a gap taken as a fraction of the figure (matplotlib's wspace is of the mean
    # axes width), the title's room forgotten, rows and columns' gaps swapped
    w, h = 9.3, 6.7
    fig, axes = new_figure((w, h), 2, 3, suptitle=suptitle)
    boxes = [[axes[r, c].get_position() for c in range(3)] for r in range(2)]
    top = 0.35 + (0.3 if suptitle else 0.0)
    ax_w = (w - 0.85 - 0.3 - 2 * 0.95) / 3
    ax_h = (h - 0.6 - top - 0.75) / 2
    for r in range(2):
        for c in range(3):
            b = boxes[r][c]
            x0 = 0.85 + c * (ax_w + 0.95)
            y1 = h - top - r * (ax_h + 0.75)
            np.testing.assert_allclose([b.x0 * w, b.width * w, b.y1 * h, b.height * h],
                                       [x0, ax_w, y1, ax_h], rtol=0, atol=1e-9)


def test_refused_when_a_panel_has_no_width() -> None:
    # three columns in 0.85 + 0.3 + 2 x 0.95 = 3.05 in leave nothing: refused; a hair more: not
    with pytest.raises(ValueError, match=r"size = \(3.05, 4.0\) is too small for 1 x 3 panels"):
        new_figure((3.05, 4.0), 1, 3)
    fig, axes = new_figure((3.06, 4.0), 1, 3)
    assert len(axes) == 3
