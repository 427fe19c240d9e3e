"""Figures of a per-step fit (:func:`dryfriction.fit.steps.fit_steps`): one figure per step
(against load-point displacement and against time, residuals below) and a summary of
``a - b`` and ``Dc`` against velocity."""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.figure import Figure

from .style import FRICTION_SI, TIME_S, VELOCITY_SI, save_png

if TYPE_CHECKING:
    from ..fit.steps import StepsResult

__all__ = ["plot_step", "plot_steps_summary"]

_DATA = {"s": 2.0, "color": "0.6", "alpha": 0.5, "linewidths": 0, "rasterized": True,
         "zorder": 1}
_MODEL = {"color": "C3", "lw": 1.4, "zorder": 3}


def plot_step(result: StepsResult, i: int, path: Any = None, *,
              others: Mapping[str, np.ndarray] | None = None) -> tuple[Figure, Any]:
    """Window ``i``: data (small light points) and the fitted model (line, drawn on top)
    against load-point displacement (left) and time (right), residuals below; ``others``
    (label: friction at the window's samples, e.g. the trap model fitted to the same window)
    are drawn as dashed lines beside the fit; the residuals are the fit's."""
    from ..fit.models import load_point_displacement

    d = result.data[i]
    row = result.rows[i]
    model = result.model_curve(i)
    x_um = load_point_displacement(d) * 1e6
    t = d.t - d.t[0]
    fig = Figure(figsize=(10.0, 5.6))
    axes = fig.subplots(2, 2, sharex="col", gridspec_kw={"height_ratios": [3, 1]})
    for col, (xv, label) in enumerate(((x_um, r"load-point displacement $x_{lp}$  [µm]"),
                                       (t, TIME_S.replace("$t$", "$t - t_{start}$")))):
        top, bot = axes[0, col], axes[1, col]
        top.scatter(xv, d.mu, label="data", **_DATA)
        top.plot(xv, model, label="fit" if not others else "fit (rsf)", **_MODEL)
        bot.scatter(xv, d.mu - model, **_DATA)
        bot.axhline(0.0, **_MODEL)
        for k, (name, curve) in enumerate((others or {}).items()):
            style = {"color": f"C{k}", "lw": 1.2, "ls": "--", "zorder": 4}
            top.plot(xv, curve, label=name, **style)
        bot.set_xlabel(label)
        top.set_ylabel(FRICTION_SI)
        bot.set_ylabel("residual")
    axes[0, 0].legend(loc="best", fontsize=8, markerscale=4)
    fig.suptitle(f"step {row['index']} ({row['kind']}): {row['v_before'] * 1e6:.3g} -> "
                 f"{row['v_after'] * 1e6:.3g} µm/s;  a-b = {row['a_minus_b']:.4g}, "
                 f"Dc = {row['dc'] * 1e6:.3g} µm, k = {row['stiffness']:.4g} /m, "
                 f"rms = {row['rms']:.2g}", fontsize=9)
    fig.subplots_adjust(left=0.09, right=0.98, bottom=0.1, top=0.92, hspace=0.08, wspace=0.25)
    if path is not None:
        save_png(fig, path)
    return fig, axes


def plot_steps_summary(result: StepsResult, path: Any = None) -> tuple[Figure, Any]:
    """``a - b`` and ``Dc`` of every step against the velocity after the change (error bars:
    one standard error)."""
    rows = result.rows
    v = np.array([r["v_after"] for r in rows])
    fig = Figure(figsize=(8.0, 3.6))
    ax1, ax2 = fig.subplots(1, 2)
    ax1.errorbar(v, [r["a_minus_b"] for r in rows], yerr=[r["sigma_a_minus_b"] for r in rows],
                 fmt="o", capsize=3)
    ax1.axhline(0.0, color="0.5", lw=0.8)
    ax1.set_ylabel(r"$a - b$")
    ax2.errorbar(v, [r["dc"] * 1e6 for r in rows], yerr=[r["sigma_dc"] * 1e6 for r in rows],
                 fmt="o", capsize=3)
    ax2.set_ylabel(r"$D_c$  [µm]")
    for ax in (ax1, ax2):
        ax.set_xscale("log")
        ax.set_xlabel(VELOCITY_SI.replace("$V$", r"$V_{after}$"))
    fig.subplots_adjust(left=0.13, right=0.98, bottom=0.16, top=0.94, wspace=0.35)
    if path is not None:
        save_png(fig, path)
    return fig, (ax1, ax2)
