"""The one style of every figure: sizes, resolution, line and font sizes, a fixed layout, and the
axis labels of the run figures with their units.

Figures are :class:`matplotlib.figure.Figure` objects (no pyplot: no global state, no backend to
choose; ``fig.savefig`` renders with Agg). The layout is fixed margins in inches, not
constrained layout: every figure here is a simple grid of panels, and constrained layout drew
each figure twice on saving (more than half of ``dryfriction reproduce``'s time).
"""

from __future__ import annotations

from typing import Any

from matplotlib.figure import Figure

from ..validation import check_figure_format

__all__ = [
    "DPI", "PNG_COMPRESSION", "LINE", "THIN", "TITLE_SIZE", "LEGEND_SIZE", "PANEL", "RUN_WIDTH",
    "ROW_HEIGHT",
    "new_figure", "save_png", "save_figure",
    "TIME_T0", "SLIP_A0", "FRICTION_EL", "CONTACTS", "VELOCITY_U", "STIFFNESS_K",
    "TIME_S", "SLIP_M", "VELOCITY_SI", "FRICTION_SI",
]

DPI = 150
"""Resolution of every PNG (dots per inch): a one-panel figure (:data:`PANEL`) is 840 x 630
pixels, enough for a slide or a report read at full width (110 gave 616 x 462)."""
PNG_COMPRESSION = 3
"""zlib level of every PNG (Pillow's default is 6; lossless either way): the 20-step fit's 23
step figures, drawn and written, take 4.0-5.0 s of CPU instead of 5.6-5.7 s, their files 12 %
larger (3613 kB against 3235 kB)."""
LINE = 1.2
"""Width of a data line (points)."""
THIN = 0.8
"""Width of a reference line, or of a dense time series."""
TITLE_SIZE = 10.0
LEGEND_SIZE = 7.5

PANEL = (5.6, 4.2)
"""Size of a one-panel figure (inches)."""
RUN_WIDTH = 7.5
ROW_HEIGHT = 2.3
"""Width of a run figure and height of each of its stacked panels (inches)."""

# Margins in inches, so that they hold the tick labels and axis labels (10 pt) whatever the
# figure's size; ``top`` holds an axes title, ``suptitle`` a figure title above it.
_LEFT, _RIGHT, _BOTTOM, _TOP, _SUPTITLE = 0.85, 0.3, 0.6, 0.35, 0.3
_HGAP, _WGAP = 0.75, 0.95  # between rows (x labels above, a title below), between columns

# axis labels of the run figures; the trap model in reduced units, rate-and-state in SI
TIME_T0 = r"time $t$  [$t_0$]"
SLIP_A0 = r"slip $X - X_0$  [$a_0$]"
FRICTION_EL = r"friction $\mu = \mu_{el}\,F/F_{el}$"
CONTACTS = r"traps in contact  [count]"
VELOCITY_U = r"pulling velocity $u = V t_0/a_0$  [$a_0/t_0$]"
STIFFNESS_K = r"spring stiffness $K$  [$F_{el}/a_0$]"
TIME_S = r"time $t$  [s]"
SLIP_M = r"slip $x - x_0$  [m]"
VELOCITY_SI = r"velocity $V$  [m/s]"
FRICTION_SI = r"friction $\mu = \tau/\sigma_n$"


def new_figure(size: tuple[float, float] = PANEL, nrows: int = 1, ncols: int = 1, *,
               sharex: bool = False, suptitle: bool = False) -> tuple[Figure, Any]:
    """A figure with an ``nrows`` x ``ncols`` grid of axes in the fixed layout.

    Parameters
    ----------
    size : (float, float)
        Width and height in inches.
    nrows, ncols : int
        The grid; a single axes is returned bare, a grid as an array (``Figure.subplots``).
    sharex : bool
        Share the x axis between panels.
    suptitle : bool
        Leave room for a figure title (``fig.suptitle``) above the panels' own titles.

    Returns
    -------
    fig, axes
    """
    fig = Figure(figsize=size)
    axes = fig.subplots(nrows, ncols, sharex=sharex)
    w, h = size
    top = _TOP + (_SUPTITLE if suptitle else 0.0)
    ax_w = (w - _LEFT - _RIGHT - (ncols - 1) * _WGAP) / ncols
    ax_h = (h - _BOTTOM - top - (nrows - 1) * _HGAP) / nrows
    if ax_w <= 0 or ax_h <= 0:
        raise ValueError(f"size = {size} is too small for {nrows} x {ncols} panels")
    # matplotlib's spaces are fractions of the mean axes width and height
    fig.subplots_adjust(left=_LEFT / w, right=1 - _RIGHT / w, bottom=_BOTTOM / h,
                        top=1 - top / h, wspace=_WGAP / ax_w, hspace=_HGAP / ax_h)
    return fig, axes


def save_png(fig: Figure, path: Any, dpi: int = DPI) -> None:
    """Render ``fig`` to a PNG file (or binary file object): :func:`save_figure` as PNG."""
    save_figure(fig, path, "png", dpi)



def save_figure(fig: Figure, path: Any, fmt: str = "png", dpi: int | None = None) -> None:
    """Render ``fig`` to ``path`` (a file name or a binary file object) as ``fmt`` (one of
    :data:`dryfriction.validation.FIGURE_FORMATS`: png, pdf, svg). ``dpi`` (default
    :data:`DPI`) sets a PNG's resolution, and that of any raster part of a vector file; the
    size in inches is the figure's own."""
    fmt, dpi = check_figure_format(fmt, dpi)
    from matplotlib import rc_context

    # no date in vector files and fixed SVG ids: the same figure gives the same bytes
    metadata: dict[str, Any] = {"pdf": {"CreationDate": None}, "svg": {"Date": None}}.get(fmt, {})
    png = {"pil_kwargs": {"compress_level": PNG_COMPRESSION}} if fmt == "png" else {}
    with rc_context({"svg.hashsalt": "dryfriction"}):
        fig.savefig(path, format=fmt, dpi=DPI if dpi is None else dpi, metadata=metadata, **png)
