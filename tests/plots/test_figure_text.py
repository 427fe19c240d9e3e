"""Words on the paper's figures are readable: no label, annotation or legend is crossed by a
curve (or a reference line), none is cut by its panel's edge, and curves told apart by the
legend alone are told apart by more than a dotted line's colour."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.text import Text
from matplotlib.transforms import Bbox

from dryfriction.plots import paper
from dryfriction.plots.style import DPI, PANEL, new_figure


def _two(left, right) -> Figure:  # type: ignore[no-untyped-def]
    fig, (a, b) = new_figure((2 * PANEL[0], PANEL[1]), 1, 2)
    left(ax=a)
    right(ax=b)
    return fig


# the figures of ``dryfriction reproduce``, as it draws them
FIGURES = {
    "fig1": lambda: _two(paper.fig1_trap_hysteresis, paper.fig1b_population_at_rest),
    "fig2": lambda: _two(paper.fig2a_aged_pinning_curve, paper.fig2b_population_at_threshold),
    "fig3": lambda: paper.fig3_static_friction(n=81)[0],
    "fig4": lambda: paper.fig4_steady_pinning_curve()[0],
    "fig5": lambda: paper.fig5_steady_friction(n=81)[0],
    "fig6": lambda: paper.fig6_dieterich(n=81)[0],
    "extra_loaded": lambda: paper.extra_loaded_static(n=81)[0],
    "extra_creep": lambda: paper.extra_creep_laws(n=81)[0],
    "extra_dieterich_C": lambda: paper.extra_local_dieterich_constant(n=41)[0],
}


def _path_points(line: Line2D) -> np.ndarray:
    """The line's vertices in pixels, with points every pixel along its drawn segments (a
    marker-only line: its markers' centres)."""
    xy = line.get_transform().transform(np.column_stack([line.get_xdata(orig=False),
                                                         line.get_ydata(orig=False)]))
    if line.get_linestyle() in ("None", "", " ") or len(xy) < 2:
        return xy[np.isfinite(xy).all(axis=1)]
    pts = [xy[np.isfinite(xy).all(axis=1)]]
    for p, q in zip(xy[:-1], xy[1:], strict=True):
        if not (np.isfinite(p).all() and np.isfinite(q).all()):
            continue  # NaN breaks the line: nothing drawn between
        n = int(np.hypot(*(q - p))) + 1
        s = np.linspace(0.0, 1.0, n + 1)[1:-1, None]
        pts.append(p + s * (q - p))
    return np.concatenate(pts)


def _words(ax: Axes, renderer) -> list[tuple[str, Bbox]]:  # type: ignore[no-untyped-def]
    """Every piece of text drawn inside the panel: texts, annotations, the legend's box."""
    out = [(t.get_text(), t.get_window_extent(renderer)) for t in ax.texts
           if t.get_visible() and t.get_text().strip()]
    legend = ax.get_legend()
    if legend is not None:
        out.append(("legend", legend.get_window_extent(renderer)))
    return out


def text_collisions(fig: Figure) -> list[str]:
    """What is wrong with the words of ``fig`` (empty: nothing): a text or legend crossed by a
    line of its panel (data or reference line, 1 px inside the text's box), or reaching out of
    its panel."""
    fig.set_dpi(DPI)
    FigureCanvasAgg(fig)
    renderer = fig.canvas.get_renderer()
    fig.draw_without_rendering()
    wrong = []
    for ax in fig.axes:
        frame = ax.bbox.padded(0.5)
        lines = [(ln.get_label(), _path_points(ln)) for ln in ax.lines if ln.get_visible()]
        for text, box in _words(ax, renderer):
            if not (frame.x0 <= box.x0 and box.x1 <= frame.x1
                    and frame.y0 <= box.y0 and box.y1 <= frame.y1):
                wrong.append(f"{text!r} reaches out of its panel")
            inner = box.padded(-1.0)
            for label, pts in lines:
                hit = ((pts[:, 0] > inner.x0) & (pts[:, 0] < inner.x1)
                       & (pts[:, 1] > inner.y0) & (pts[:, 1] < inner.y1))
                if hit.any():
                    wrong.append(f"{text!r} is crossed by the line {label!r}")
    return wrong


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_no_curve_crosses_a_word_and_no_word_leaves_its_panel(name):
    assert text_collisions(FIGURES[name]()) == []


def test_the_check_sees_a_label_on_a_curve_and_one_cut_by_the_edge():
    fig, ax = new_figure()
    ax.plot([0.0, 1.0], [0.0, 1.0], label="diagonal")
    ax.set_xlim(0.0, 1.0)
    ax.text(0.5, 0.5, "on the curve", ha="center", va="center")
    ax.text(0.98, 0.1, "past the right edge")
    found = text_collisions(fig)
    assert "'on the curve' is crossed by the line 'diagonal'" in found
    assert "'past the right edge' reaches out of its panel" in found
    assert not any("past the right edge' is crossed" in w for w in found)


# ------------------------------------------------------------------------- Fig. 6's curves


def _dash_on(line: Line2D) -> float:
    """The longest drawn piece of the line's dash pattern, in points (inf: solid)."""
    _, dashes = line._unscaled_dash_pattern  # (offset, on-off sequence) or (0, None)
    return float("inf") if not dashes else max(dashes[0::2])


def test_fig6_curves_are_told_apart_by_style_and_colour():
    # every curve of the legend has its own (colour, line style), and none is a dotted line
    # (dashes shorter than 2 points: a line that thin shows too little ink for its colour to be
    # seen, the four dotted C curves were indistinguishable)
    _, ax = paper.fig6_dieterich(n=41)
    curves = [ln for ln in ax.lines if not ln.get_label().startswith("_")]
    assert len(curves) == 8
    for ln in curves:
        assert _dash_on(ln) >= 2.0, f"{ln.get_label()!r} is dotted"
    styles = {(ln.get_color(), str(ln._unscaled_dash_pattern)) for ln in curves}
    assert len(styles) == len(curves)
    assert all(isinstance(t, Text) for t in ax.get_legend().get_texts())
