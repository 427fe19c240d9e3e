"""The fit figure, ``fit.png``: data, the fitted model and the residuals, for data sets of any
size (big data are drawn binned, so a million samples draw in about a second)."""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from numpy.typing import NDArray

from ..validation import Array
from .style import save_png

if TYPE_CHECKING:
    from ..fit import FitResult
    from ..records.data import Dataset

__all__ = ["plot_fit", "MAX_POINTS_DRAWN"]


MAX_POINTS_DRAWN: int = 5000
"""Most points :func:`plot_fit` draws per artist: beyond it the data are binned (drawing a
million points took most of a large fit's time and shows no more than their envelope)."""


def _bin_edges(n: int, n_bins: int) -> NDArray[np.intp]:
    """Edges of ``n_bins`` runs of consecutive samples out of ``n`` (empty runs dropped)."""
    return np.unique(np.linspace(0, n, n_bins + 1).astype(np.intp))


def _envelope(y: Array, n_bins: int) -> NDArray[np.intp]:
    """Indices of the smallest and largest ``y`` in each of ``n_bins`` runs of consecutive
    samples, in order: a decimated line that keeps every step and spike (plain striding would
    drop them)."""
    edges = _bin_edges(y.size, n_bins)
    bin_of = np.repeat(np.arange(edges.size - 1), np.diff(edges))
    by_bin = np.lexsort((y, bin_of))  # bins stay in place, sorted by y within each
    return np.unique(np.concatenate([by_bin[edges[:-1]], by_bin[edges[1:] - 1]]))


def _draw_data(ax: Axes, x: Array, y: Array, err: Array | None, n_bins: int | None,
               label: str | None) -> None:
    """Data as small light points under everything else; with ``n_bins`` (big data) their
    range in each run of consecutive samples as a band and the run means as points."""
    light = {"color": "0.55", "alpha": 0.6, "zorder": 1}
    if n_bins is None:
        ax.errorbar(x, y, yerr=err, fmt="o", ms=2.5, lw=0.6, label=label, **light)
        return
    edges = _bin_edges(y.size, n_bins)
    start, count = edges[:-1], np.diff(edges)
    xc = np.add.reduceat(x, start) / count
    per = f"{y.size / count.size:.3g} samples"
    ax.fill_between(xc, np.minimum.reduceat(y, start), np.maximum.reduceat(y, start), lw=0,
                    color="0.85", zorder=0, label=label and f"{label}: range per {per}")
    ax.plot(xc, np.add.reduceat(y, start) / count, "o", ms=1.5, mew=0,
            label=label and f"{label}: mean per {per}", **light)


def plot_fit(result: FitResult, datasets: Sequence[Dataset], path: Any = None,
             max_points: int = MAX_POINTS_DRAWN) -> tuple[Figure, Any]:
    """``fit.png``: each data set with the fitted curve (top) and the residuals (bottom).

    The data are small light points under the fitted line. A data set with more than
    ``max_points`` samples is drawn binned: sorted by abscissa (time for a series) and cut into
    about ``max_points/2`` runs of consecutive samples, each drawn as its range (a light band)
    and its mean (a point), for the data and the residuals, without error bars; the fitted line
    is evaluated on the data and drawn through the smallest and largest value of each run.

    Parameters
    ----------
    result : dryfriction.fit.FitResult
        The fit (its ``predict`` evaluates the fitted model).
    datasets : sequence of Dataset
        The data sets fitted, in order.
    path : path-like or file, optional
        Where to write the PNG; ``None``: not written.
    max_points : int
        Most points (vertices) drawn per artist (at least 8).

    Returns
    -------
    fig, axes
        A new figure (Agg-renderable, not shown) and its ``2 x len(datasets)`` axes.
    """
    from ..records.data import SeriesData

    if max_points < 8:
        raise ValueError(f"max_points = {max_points}: must be at least 8")
    k = len(datasets)
    fig = Figure(figsize=(4.6 * k, 5.6), layout="constrained")
    axes = fig.subplots(2, k, sharex="col", squeeze=False, height_ratios=[3, 1.3])
    for i, d in enumerate(datasets):
        top, bot = axes[0, i], axes[1, i]
        order = np.argsort(d.x, kind="stable")
        x, y, f = d.x[order], d.y[order], result.predict(d)[order]
        r = y - f
        thin = x.size > max_points
        # a million error bars show nothing but cost minutes
        err = None if d.sigma is None or thin else d.sigma[order]
        if isinstance(d, SeriesData):  # the fitted line evaluated on the data, decimated
            keep_f = _envelope(f, max_points // 2) if thin else slice(None)
            xs, fs = x[keep_f], f[keep_f]
        else:
            pos = d.x[d.x > 0]
            lo = pos.min() if pos.size else 1e-3
            xs = np.geomspace(lo / 1.5, d.x.max() * 1.5, 200)
            fs = result.predict(d, xs)
        n_bins = (max_points - 4) // 2 if thin else None  # a band has 2 n_bins + 3 vertices
        _draw_data(top, x, y, err, n_bins, "data")
        top.plot(xs, fs, "-", lw=1.4, color="C3", zorder=3, label=f"{result.model} fit")
        _draw_data(bot, x, r, err, n_bins, None)
        bot.axhline(0.0, color="k", lw=0.6, zorder=2)
        if not isinstance(d, SeriesData):
            top.set_xscale("log")
        top.set_ylabel(d.y_name)
        against = f"against_model:{d.source}" in getattr(result, "flags", ())
        top.set_title(str(d.source).split("/")[-1]
                      + (f"\nAGAINST THE MODEL: its {d.y_name} trend has the wrong sign"
                         if against else ""), fontsize=9, color="C3" if against else "k")
        top.legend(fontsize=8)
        bot.set_ylabel("residual")
        bot.set_xlabel(f"{d.x_name} ({d.x_unit})")
    status = "" if result.success else "  [NOT CONVERGED]"
    # each value with its unit (a0 = 8.266e-07 m), as a user copies it
    # and what it is worth where it is no estimate: "t0 = 1e-12 s (at bound)"
    def worth(p: Any) -> str:
        w = getattr(p, "identifiability", "identified")
        return ("" if w.startswith("identified") or w == "fixed" else
                " (at bound)" if w.startswith("at ") else " (not identified)")

    fig.suptitle(textwrap.fill(", ".join(f"{p.name} = {p.value:.4g}"
                                         + (f" {p.unit}" if p.unit else "") + worth(p)
                                         for p in result.parameters),
                               width=70 * max(1, len(datasets))) + status, fontsize=8)
    if path is not None:
        save_png(fig, path)
    return fig, axes
