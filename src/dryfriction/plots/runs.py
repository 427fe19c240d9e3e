"""Figures of runs: time series of both simulators, the ``rsf`` command's figure, the ``compare``
figure and the stick-slip phase diagram.

Every function takes a result (or arrays) and returns ``(fig, axes)``: a new
:class:`matplotlib.figure.Figure` in the style of :mod:`.style` (no pyplot, nothing shown);
save it with :func:`.style.save_png`. The trap model is drawn in reduced units (``t0``, ``a0``,
``F_el``), rate-and-state in SI (s, m, m/s), and every axis label says which.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from .style import (
    CONTACTS,
    FRICTION_EL,
    FRICTION_SI,
    LEGEND_SIZE,
    LINE,
    PANEL,
    ROW_HEIGHT,
    RUN_WIDTH,
    SLIP_A0,
    SLIP_M,
    STIFFNESS_K,
    THIN,
    TIME_S,
    TIME_T0,
    TITLE_SIZE,
    VELOCITY_SI,
    VELOCITY_U,
    new_figure,
)

__all__ = [
    "timeseries_figure",
    "rsf_timeseries_figure",
    "rsf_figure",
    "comparison_figure",
    "phase_diagram_figure",
]


def _stack(n: int, title: str, sharex: bool = False) -> tuple[Figure, Any]:
    fig, axes = new_figure((RUN_WIDTH, 1.0 + n * ROW_HEIGHT), n, 1, sharex=sharex,
                           suptitle=True)
    fig.suptitle(title, fontsize=TITLE_SIZE)
    return fig, axes


def _positive(y: Any) -> Any:
    """``y`` with zeros and negatives as NaN, for a log axis (holds have zero velocity)."""
    y = np.asarray(y, float)
    return np.where(y > 0, y, np.nan)


def timeseries_figure(result: Any) -> tuple[Figure, Any]:
    """Trap-ensemble run: friction against time and against slip, and the traps in contact.

    Parameters
    ----------
    result : dryfriction.ensemble.driving.SimulationResult
        A run of the trap ensemble; times in ``t0``, slips in ``a0``, ``mu = mu_el F/F_el``.

    Returns
    -------
    fig, axes
        A new figure and its three axes.
    """
    fig, axes = _stack(3, "partial result (interrupted)" if result.partial else "trap ensemble")
    t, x, mu = result.t, result.x, result.mu
    axes[0].plot(t, mu, lw=THIN)
    axes[0].set_xlabel(TIME_T0)
    axes[0].set_ylabel(FRICTION_EL)
    axes[1].plot(x - x[0], mu, lw=THIN)
    axes[1].set_xlabel(SLIP_A0)
    axes[1].set_ylabel(FRICTION_EL)
    axes[2].plot(t, result.n_active, lw=THIN)
    axes[2].set_xlabel(TIME_T0)
    axes[2].set_ylabel(CONTACTS)
    return fig, axes


def rsf_timeseries_figure(result: Any) -> tuple[Figure, Any]:
    """Rate-and-state run (``simulate`` with ``law = "rsf"``): friction against time and slip,
    slip and load velocity against time.

    Parameters
    ----------
    result : dryfriction.rsf.driving.RSFResult
        A rate-and-state run (SI units: s, m, m/s).

    Returns
    -------
    fig, axes
        A new figure and its three axes.
    """
    fig, axes = _stack(3, f"rate-and-state, {result.params.state_law} law")
    t, x, mu = result.t, result.x, result.mu
    axes[0].plot(t, mu, lw=THIN, label="friction")
    if result.damping or result.mass:
        # with inertia or damping the spring no longer reads the friction
        axes[0].plot(t, result.stress, lw=THIN, ls="--", label="spring force / normal force")
        axes[0].legend(fontsize=LEGEND_SIZE)
    axes[0].set_xlabel(TIME_S)
    axes[0].set_ylabel(FRICTION_SI)
    axes[1].plot(x - x[0], mu, lw=THIN)
    axes[1].set_xlabel(SLIP_M)
    axes[1].set_ylabel(FRICTION_SI)
    axes[2].semilogy(t, _positive(np.abs(result.v)), lw=THIN, label="slip velocity")
    axes[2].semilogy(t, _positive(result.load_velocity), lw=THIN, ls="--",
                     label="load velocity")
    axes[2].set_xlabel(TIME_S)
    axes[2].set_ylabel(VELOCITY_SI)
    axes[2].legend(fontsize=LEGEND_SIZE)
    return fig, axes


def rsf_figure(result: Any, title: str) -> tuple[Figure, Any]:
    """``rsf.png`` of the ``rsf`` command: friction and spring force, slip and load velocity,
    against time (SI units).

    Parameters
    ----------
    result : dryfriction.rsf.driving.RSFResult
        The run.
    title : str
        The case and state law, e.g. ``"step, ageing law"``.

    Returns
    -------
    fig, axes
        A new figure and its two axes (time shared).
    """
    fig, (ax1, ax2) = _stack(2, title, sharex=True)
    ax1.plot(result.t, result.mu, lw=LINE, label="friction")
    ax1.plot(result.t, result.stress, lw=THIN, ls="--", label="spring force / normal force")
    ax1.set_ylabel(FRICTION_SI)
    ax1.legend(fontsize=LEGEND_SIZE)
    ax2.semilogy(result.t, _positive(result.v), lw=LINE, label="slip velocity")
    ax2.semilogy(result.t, _positive(result.load_velocity), lw=THIN, ls="--",
                 label="load velocity")
    ax2.set_xlabel(TIME_S)
    ax2.set_ylabel(VELOCITY_SI)
    ax2.legend(fontsize=LEGEND_SIZE)
    return fig, (ax1, ax2)


def comparison_figure(c: Any, title: str = "") -> tuple[Figure, Any]:
    """``compare.png``: friction of the trap model and of its rate-and-state twin against time
    and slip, and their difference (reduced units).

    Parameters
    ----------
    c : dryfriction.analysis.rsf_view.Comparison
        The two runs and the twin's parameters.
    title : str
        Usually the protocol's file name.

    Returns
    -------
    fig, axes
        A new figure and its three axes.
    """
    m = c.misfit
    fig, ax = _stack(3, f"{title}  ({c.calibration} calibration, rms misfit {m['rms']:.3g})")
    tw = c.twin
    label = (f"RSF twin ({tw.state_law}; a = {c.mu_el * tw.a:.3g}, b = {c.mu_el * tw.b:.3g}, "
             f"Dc = {tw.dc:.3g} a0)")
    ax[0].plot(c.t, c.mu_trap, lw=LINE, label="trap model")
    ax[0].plot(c.t, c.mu_rsf, lw=THIN, ls="--", label=label)
    ax[0].set_xlabel(TIME_T0)
    ax[0].set_ylabel(FRICTION_EL)
    ax[0].legend(fontsize=LEGEND_SIZE)
    slip = c.x - c.x[0]
    ax[1].plot(slip, c.mu_trap, lw=LINE, label="trap model")
    ax[1].plot(slip, c.mu_rsf, lw=THIN, ls="--", label="RSF twin")
    ax[1].set_xlabel(SLIP_A0)
    ax[1].set_ylabel(FRICTION_EL)
    ax[2].plot(slip, c.mu_rsf - c.mu_trap, lw=THIN)
    ax[2].axhline(0.0, color="k", lw=0.6)
    ax[2].set_xlabel(SLIP_A0)
    ax[2].set_ylabel(r"$\mu_{RSF} - \mu_{trap}$  [$\mu_{el}\,F/F_{el}$]")
    return fig, ax


# class code -> marker, colour
_MARKERS = {0: ("o", "tab:blue"), 1: ("s", "tab:red"), 2: ("^", "tab:purple"),
            3: ("D", "tab:orange"), 4: ("v", "tab:green"), -1: ("x", "0.4")}


def phase_diagram_figure(ds: Any, base: Mapping[str, Any], k_key: str, v_key: str
                         ) -> tuple[Figure, Any]:
    """``phase_diagram.png``: simulated stick-slip classes as markers in the (u, K) plane over
    the linear ``K_c(u)`` line (:func:`dryfriction.analysis.stickslip.critical_line`).

    Parameters
    ----------
    ds : xarray.Dataset
        The sweep, with the coordinates ``k_key`` and ``v_key`` and (unless every point failed)
        the variable ``class`` (codes of :data:`~dryfriction.analysis.stickslip.CLASSES`; NaN
        for a failed point).
    base : mapping
        The sweep's base protocol (its ``model`` and ``drive`` tables give ``K_c``).
    k_key, v_key : str
        The swept stiffness and velocity keys
        (:func:`dryfriction.analysis.stickslip.phase_axes`).

    Returns
    -------
    fig, ax
    """
    # here, not at the top: the stick-slip analysis imports the trap model's compiled kernel,
    # which a rate-and-state run's figure does not need
    from ..analysis.stickslip import CLASSES, critical_line

    K = np.asarray(ds[k_key].values, float)
    V = np.asarray(ds[v_key].values, float)
    code = ds["class"].transpose(k_key, v_key).values if "class" in ds else \
        np.full((K.size, V.size), np.nan)
    fig, ax = new_figure((PANEL[0] + 0.2, PANEL[1] + 0.2))
    vv, kk = np.meshgrid(V, K)
    for c, (mk, col) in _MARKERS.items():
        sel = code == c
        if sel.any():
            ax.scatter(vv[sel], kk[sel], marker=mk, color=col, label=CLASSES[c], zorder=3)
    failed = ~np.isfinite(code)
    if failed.any():
        ax.scatter(vv[failed], kk[failed], marker="+", color="k", label="failed", zorder=3)
    if V.size > 1 and V.min() > 0:
        u = np.geomspace(V.min(), V.max(), 40)
        ax.set_xscale("log")
    else:
        u = np.linspace(V.min(), V.max(), 40) if V.size > 1 else V
    ax.plot(u, critical_line(base, u), "k-", lw=LINE, label="linear $K_c(u)$")
    if K.min() > 0 and K.max() / K.min() > 5:
        ax.set_yscale("log")
    d = base.get("drive", {})
    ax.set_xlabel(VELOCITY_U)
    ax.set_ylabel(STIFFNESS_K)
    ax.set_title(rf"stick-slip phase diagram, $\varepsilon$ = {base['model']['eps']:g}, "
                 rf"$M$ = {float(d.get('mass', 0.0)):g}, $\eta$ = "
                 f"{float(d.get('damping', 0.0)):g}", fontsize=TITLE_SIZE)
    ax.legend(fontsize=LEGEND_SIZE)
    return fig, ax
