"""Figures of simulation results (matplotlib; each function returns ``fig, axes``)."""

from __future__ import annotations

from typing import Any

__all__ = ["timeseries_figure"]


def timeseries_figure(result: Any) -> tuple[Any, Any]:
    """Friction against time and against slip, with the number of traps in contact.

    Parameters
    ----------
    result : dryfriction.driving.SimulationResult
        A run; times in ``t0``, slips in ``a0``, friction ``mu = mu_el F/F_el``.

    Returns
    -------
    fig, axes
        A matplotlib figure (not shown) and its three axes.
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8.0, 7.5), layout="constrained")
    axes = fig.subplots(3, 1)
    t, x, mu = result.t, result.x, result.mu
    axes[0].plot(t, mu, lw=0.8)
    axes[0].set_xlabel("t / t0")
    axes[0].set_ylabel("mu")
    axes[1].plot(x - x[0], mu, lw=0.8)
    axes[1].set_xlabel("slip (X - X0) / a0")
    axes[1].set_ylabel("mu")
    axes[2].plot(t, result.n_active, lw=0.8)
    axes[2].set_xlabel("t / t0")
    axes[2].set_ylabel("traps in contact")
    title = "partial result (interrupted)" if result.partial else "trap ensemble"
    fig.suptitle(title)
    return fig, axes
