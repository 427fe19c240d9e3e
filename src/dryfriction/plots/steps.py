"""Figures of a per-step fit (:func:`dryfriction.fit.steps.fit_steps`): one figure per step
(against load-point displacement and against time, residuals below) and the summary of
``a - b``, ``a``, ``b``, ``Dc`` against velocity (:mod:`.summary`)."""

from __future__ import annotations

import weakref
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from .style import FRICTION_SI, TIME_S, save_png

if TYPE_CHECKING:
    from ..fit.steps import StepsResult

__all__ = ["plot_step", "plot_steps_summary", "step_title"]

_DATA = {"s": 2.0, "color": "0.6", "alpha": 0.5, "linewidths": 0, "rasterized": True,
         "zorder": 1}
_MODEL = {"color": "C3", "lw": 1.4, "zorder": 3}


def _g(x: float, scale: float = 1.0, unit: str = "") -> str:
    """4 significant digits and the unit, as the terminal table; "not identified" for a
    value not reported (NaN)."""
    return "not identified" if x != x else f"{x * scale:.4g}{unit}"


def step_title(row: Mapping[str, Any]) -> str:
    """The step figure's title: velocities, the values as in ``steps.csv`` (4 digits; "not
    identified" where the value is not reported) and, on a second line, the flags."""
    from ..fit.identify import split_flags

    head = (f"step {row['index']} ({row['kind']}): {row['v_before'] * 1e6:.3g} -> "
            f"{row['v_after'] * 1e6:.3g} µm/s;  a = {_g(row['a'])}, b = {_g(row['b'])}, "
            f"a-b = {_g(row['a_minus_b'])}, Dc = {_g(row['dc'], 1e6, ' µm')}, "
            f"k = {_g(row['stiffness'], 1.0, ' /m')}, rms = {row['rms']:.2g}")
    words = split_flags(row.get("flags", ""))
    if not words:
        return head
    lost = [w.split(":", 1)[1] for w in words if w.startswith("not_identified:")]
    tail = (f"{', '.join(lost)} not identified" if lost else "") + (
        ("; " if lost else "") + "flags: " + "; ".join(words))
    return head + "\n" + tail


def plot_step(result: StepsResult, i: int, path: Any = None, *,
              others: Mapping[str, np.ndarray] | None = None,
              into: Figure | None = None) -> tuple[Figure, Any]:
    """Window ``i``: data (small light points) and the fitted model (line, drawn on top)
    against load-point displacement (left) and time (right), residuals below; ``others``
    (label: friction at the window's samples, e.g. the trap model fitted to the same window)
    are drawn as dashed lines beside the fit; the residuals are the fit's. ``path``: also
    written there as a PNG.

    ``into``: a figure this function returned before, with the same ``others`` labels and as
    it left it (its axes, their artists, autoscaling on): its artists take window ``i``'s
    data, its axes are autoscaled again, and it is returned (the same picture as a new
    figure's; a record's steps drawn one after another then create their axes and ticks once,
    not once a step). Any other figure (drawn with other labels, drawn on, zoomed or cleared
    since), or residuals with no finite value other than 0, and a new figure is made; the
    figure given is left alone."""
    from ..fit.models import load_point_displacement

    d = result.data[i]
    row = result.rows[i]
    model = result.model_curve(i)
    x_um = load_point_displacement(d) * 1e6
    t = d.t - d.t[0]
    names = tuple(others or {})
    resid = d.mu - model
    axes = _reusable(into, names) if into is not None else None
    if axes is not None and np.any(np.isfinite(resid) & (resid != 0.0)):
        fig = into
        _redraw(fig, axes, (x_um, t), d.mu, resid, model, others or {}, step_title(row))
    else:
        fig, axes = _new_step_figure(x_um, t, d.mu, resid, model, others or {},
                                     step_title(row))
    if path is not None:
        save_png(fig, path)
    return fig, axes


def _new_step_figure(x_um: np.ndarray, t: np.ndarray, mu: np.ndarray, resid: np.ndarray,
                     model: np.ndarray, others: Mapping[str, np.ndarray], title: str
                     ) -> tuple[Figure, Any]:
    """plot_step's figure, made new."""
    fig = Figure(figsize=(10.0, 5.6))
    # an Agg canvas of its own: savefig then draws on it, not on a canvas made for the one
    # call, so a figure saved again (``into``) keeps its renderer and the renderer's parsed
    # mathtext labels (three parses a step otherwise)
    FigureCanvasAgg(fig)
    axes = fig.subplots(2, 2, sharex="col", gridspec_kw={"height_ratios": [3, 1]})
    for col, (xv, label) in enumerate(((x_um, r"load-point displacement $x_{lp}$  [µm]"),
                                       (t, TIME_S.replace("$t$", "$t - t_{start}$")))):
        top, bot = axes[0, col], axes[1, col]
        top.scatter(xv, mu, label="data", **_DATA)
        top.plot(xv, model, label="fit" if not others else "fit (rsf)", **_MODEL)
        bot.scatter(xv, resid, **_DATA)
        bot.axhline(0.0, **_MODEL)
        for k, (name, curve) in enumerate(others.items()):
            style = {"color": f"C{k}", "lw": 1.2, "ls": "--", "zorder": 4}
            top.plot(xv, curve, label=name, **style)
        bot.set_xlabel(label)
        top.set_ylabel(FRICTION_SI)
        bot.set_ylabel("residual")
    axes[0, 0].legend(loc="best", fontsize=8, markerscale=4)
    fig.suptitle(title, fontsize=9)
    fig.subplots_adjust(left=0.09, right=0.98, bottom=0.1, top=0.9, hspace=0.08, wspace=0.25)
    _DRAWN[fig] = tuple(others)
    return fig, axes


# the others' labels of each figure plot_step made (weak keys, and values that do not refer
# to the figure: a figure let go of is collected and forgotten)
_DRAWN: weakref.WeakKeyDictionary[Figure, tuple[str, ...]] = weakref.WeakKeyDictionary()


def _reusable(fig: Figure, names: tuple[str, ...]) -> Any:
    """``fig``'s 2 x 2 axes where plot_step made it with these labels and it holds what
    plot_step put there, autoscaling on; else ``None``."""
    if _DRAWN.get(fig) != names or len(fig.axes) != 4:
        return None
    axes = np.array(fig.axes, dtype=object).reshape(2, 2)
    for col in range(2):
        top, bot = axes[0, col], axes[1, col]
        if not (len(top.collections) == len(bot.collections) == 1
                and len(top.get_lines()) == 1 + len(names) and len(bot.get_lines()) == 1
                and len(top.patches) == len(bot.patches) == 0
                and len(top.texts) == len(bot.texts) == 0):
            return None
        if not all(ax.get_autoscalex_on() and ax.get_autoscaley_on() for ax in (top, bot)):
            return None
    return axes


def _redraw(fig: Figure, axes: Any, xs: tuple[np.ndarray, np.ndarray], mu: np.ndarray,
            resid: np.ndarray, model: np.ndarray, others: Mapping[str, np.ndarray],
            title: str) -> None:
    """plot_step's artists on ``fig`` given another window's data (in the order plot_step
    added them), its data limits recomputed as the axes' own methods compute them (``relim``
    for the lines; a collection's limits as ``add_collection`` adds them, which ``relim``
    leaves out before matplotlib 3.11) and the views autoscaled."""
    for col, xv in enumerate(xs):
        top, bot = axes[0, col], axes[1, col]
        top.collections[0].set_offsets(np.column_stack([xv, mu]))
        bot.collections[0].set_offsets(np.column_stack([xv, resid]))
        for line, y in zip(top.get_lines(), (model, *others.values()), strict=True):
            line.set_data(xv, y)
    for ax in axes.flat:
        ax.relim()  # takes in collections too from matplotlib 3.11; added here for earlier ones
        lim = ax.collections[0].get_datalim(ax.transData)
        pts = lim.get_points()
        ax.update_datalim(pts if np.isinf(lim.minpos).all() else np.vstack([pts, [lim.minpos]]))
    for ax in axes.flat:
        ax.autoscale_view()
    fig.suptitle(title, fontsize=9)


def plot_steps_summary(result: StepsResult, path: Any = None) -> tuple[Figure, Any]:
    """``a - b``, ``a``, ``b`` and ``Dc`` of every velocity step against the velocity after the
    change, grouped by normal stress, with their 95 % intervals (``steps.csv``'s ``*_lo``,
    ``*_hi``): :func:`.summary.plot_experiment_summary` of the result's rows."""
    from .summary import plot_experiment_summary

    return plot_experiment_summary(result.rows, path)
