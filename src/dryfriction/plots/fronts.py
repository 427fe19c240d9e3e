"""Figures of an extended interface's slip: the space-time map of the slip
rate with the rupture fronts drawn on it, front speed against position, the precursor curve and
the magnitude-frequency distribution. Each takes what :mod:`dryfriction.analysis.fronts` and
:mod:`dryfriction.analysis.catalogue` compute and returns ``(fig, axes)``."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..analysis.catalogue import MagnitudeFrequency, Precursors, Trend
from ..analysis.fronts import Event, SpaceTime, moment_unit, speed_unit
from .style import LEGEND_SIZE, LINE, PANEL, RUN_WIDTH, THIN, TITLE_SIZE, new_figure

__all__ = ["space_time_figure", "front_speed_figure", "precursor_figure",
           "magnitude_frequency_figure"]

_SIDE = {-1: ("tab:cyan", "towards $-x$"), +1: ("tab:red", "towards $+x$")}


def _title(fig: Any, ax: Any, title: str) -> None:
    if title:
        ax.set_title(title, fontsize=TITLE_SIZE)


MAP_ROWS = 1500
"""Most time rows the space-time map draws (about the figure's pixel height at 300 dpi)."""


def _pooled(t: np.ndarray, rate: np.ndarray, rows: int = MAP_ROWS) -> tuple[np.ndarray,
                                                                              np.ndarray]:
    """The slip rate over at most ``rows`` time rows: the largest value of each block of
    consecutive samples (so no front or event vanishes from the map), at the block's first
    time."""
    k = -(-t.size // rows)  # samples per row, rounded up
    if k <= 1:
        return t, rate
    n = t.size // k * k
    pooled = rate[:n].reshape(-1, k, rate.shape[1]).max(axis=1)
    times = t[:n:k]
    if n < t.size:
        pooled = np.vstack([pooled, rate[n:].max(axis=0)])
        times = np.append(times, t[n])
    return times, pooled


def space_time_figure(st: SpaceTime, events: Sequence[Event], threshold: float,
                      title: str = "") -> tuple[Any, Any]:
    """The slip rate over (position, time), log colour scale, with every front's arrival times
    drawn over it (one line per front, coloured by direction; a circle at the nucleation of each
    event of more than one element).

    Slip rates at or below ``threshold / 100`` (and any negative back-slip) are drawn at that
    floor; the colour bar's label says so and gives the threshold. A record of more than
    :data:`MAP_ROWS` samples is drawn as the largest slip rate of each block of samples; the
    fronts are drawn at their exact arrival times.
    """
    fig, ax = new_figure((RUN_WIDTH, 5.0))
    u = st.units
    floor = threshold / 100.0
    t, rate = _pooled(st.t, st.slip_rate)
    rate = np.log10(np.maximum(rate, floor))
    mesh = ax.pcolormesh(st.x, t, rate, shading="nearest", cmap="magma", rasterized=True)
    bar = fig.colorbar(mesh, ax=ax, pad=0.02)
    bar.set_label(rf"$\log_{{10}}$ slip rate [{u['slip_rate']}] (floor {floor:.3g}; "
                  f"threshold {threshold:.3g})", fontsize=LEGEND_SIZE)
    seen: set[int] = set()
    for e in events:
        for f in e.fronts:
            if f.x.size < 2:
                continue
            colour, label = _SIDE[f.direction]
            ax.plot(f.x, f.t, "-", color=colour, lw=LINE,
                    label=None if f.direction in seen else f"front {label}")
            seen.add(f.direction)
        if e.n_elements > 1:  # a one-element slip has no front to start
            ax.plot([e.x_nucleation], [e.t_start], "o", mfc="none", color="w", ms=5)
    ax.set_xlabel(f"position $x$  [{u['x']}]")
    ax.set_ylabel(f"time $t$  [{u['t']}]")
    ax.set_xlim(st.x[0] - st.lengths[0] / 2, st.x[-1] + st.lengths[-1] / 2)  # cell edges
    ax.set_ylim(st.t[0], st.t[-1])
    if seen:
        ax.legend(fontsize=LEGEND_SIZE, loc="upper right")
    _title(fig, ax, title or f"{len(events)} events; fronts by slip rate > {threshold:.3g} "
                             f"{u['slip_rate']}")
    return fig, ax


def front_speed_figure(st: SpaceTime, events: Sequence[Event], *,
                       reference_speed: float | None = None, reference_label: str = "",
                       title: str = "") -> tuple[Any, Any]:
    """Local front speed against position with its 95 % interval, every front of every event
    (coloured by direction); an interval without an upper end (the fit cannot exclude an
    instantaneous front) is drawn up to the panel's top with an arrow. ``reference_speed``
    (e.g. the chain's sound speed) is drawn as a dashed line."""
    fig, ax = new_figure(PANEL)
    u = st.units
    seen: set[int] = set()
    finite_top = []
    for e in events:
        for f in e.fronts:
            ok = np.isfinite(f.speed)
            if not ok.any():
                continue
            finite_top.append(np.nanmax(np.where(np.isfinite(f.speed_high), f.speed_high,
                                                 f.speed)[ok]))
    top = 2.0 * max(finite_top) if finite_top else 1.0
    for e in events:
        for f in e.fronts:
            ok = np.isfinite(f.speed)
            if not ok.any():
                continue
            colour, label = _SIDE[f.direction]
            low = np.where(np.isfinite(f.speed_low), f.speed_low, f.speed)[ok]
            high = np.minimum(f.speed_high[ok], top)
            ax.errorbar(f.x[ok], f.speed[ok], yerr=[f.speed[ok] - low, high - f.speed[ok]],
                        fmt=".", color=colour, ms=4, lw=THIN,
                        label=None if f.direction in seen else f"front {label}")
            open_top = ~np.isfinite(f.speed_high[ok])
            if open_top.any():
                ax.plot(f.x[ok][open_top], np.full(open_top.sum(), top), "^", color=colour,
                        ms=4)
            seen.add(f.direction)
    if reference_speed is not None:
        ax.axhline(reference_speed, color="k", ls="--", lw=THIN,
                   label=reference_label or f"reference {reference_speed:.3g}")
    speeds = [f.speed[np.isfinite(f.speed)] for e in events for f in e.fronts]
    allv = np.concatenate(speeds) if speeds else np.array([])
    if allv.size and allv.min() > 0 and allv.max() > 10 * allv.min():
        ax.set_yscale("log")
    ax.set_xlabel(f"position $x$  [{u['x']}]")
    ax.set_ylabel(f"front speed  [{speed_unit(u)}]")
    if seen or reference_speed is not None:
        ax.legend(fontsize=LEGEND_SIZE)
    _title(fig, ax, title or "front speed (Theil-Sen, 95 % interval)")
    return fig, ax


def precursor_figure(pre: Precursors, st: SpaceTime, trend: Trend | None = None, *,
                     title: str = "") -> tuple[Any, Any]:
    """Arrested-front length against the load-to-normal ratio at arrest (points), the ratios of
    the system-spanning events (dashed vertical lines) and the interface's length (dotted);
    with ``trend`` (:func:`~dryfriction.analysis.catalogue.precursor_trend`), the legend says
    whether the lengths grow, with Spearman's rho and its p-value."""
    fig, ax = new_figure(PANEL)
    u = st.units
    ax.plot(pre.ratio, pre.length, "o", color="tab:blue", ms=5,
            label=f"arrested fronts ({pre.length.size})")
    if trend is not None:
        stats = (f"rho = {trend.rho:.2f}, p = {trend.p_value:.2g}"
                 if math.isfinite(trend.rho) else f"{trend.n} points")
        ax.plot([], [], " ", label=f"grow with the load: {trend.grows} ({stats})")
    for k, r in enumerate(pre.spanning_ratio):
        ax.axvline(r, color="tab:red", ls="--", lw=THIN,
                   label="system-spanning events" if k == 0 else None)
    total = float(np.sum(st.lengths))
    ax.axhline(total, color="k", ls=":", lw=THIN, label=f"interface length {total:.3g}")
    ax.set_ylim(0.0, 1.08 * total)
    ax.set_xlabel("load / normal load at arrest  [1]")
    ax.set_ylabel(f"precursor length  [{u['x']}]")
    ax.legend(fontsize=LEGEND_SIZE, loc="upper left")
    _title(fig, ax, title or "precursors: arrested fronts against the applied shear")
    return fig, ax


def magnitude_frequency_figure(mf: MagnitudeFrequency, st: SpaceTime, *,
                               title: str = "") -> tuple[Any, Any]:
    """``N(>= M)`` against the moment ``M`` (log-log steps) and the fitted power law
    ``N ~ M^-(alpha - 1)`` above ``M_min`` when it was identified (the legend gives alpha and
    its standard error, or says that it was not)."""
    fig, ax = new_figure(PANEL)
    u = st.units
    positive = mf.moment > 0
    ax.step(mf.moment[positive], mf.count[positive], where="post", color="tab:blue", lw=LINE,
            label=f"events ({int(positive.sum())})")
    if math.isfinite(mf.alpha):
        m = np.geomspace(mf.m_min, float(mf.moment.max()), 50)
        ax.plot(m, mf.n_fit * (m / mf.m_min) ** (1.0 - mf.alpha), "k--", lw=THIN,
                label=rf"$p(M) \sim M^{{-\alpha}}$, $\alpha$ = {mf.alpha:.2f} "
                      rf"$\pm$ {mf.alpha_err:.2f} ({mf.n_fit} events)")
    else:
        ax.plot([], [], " ", label=f"no power law fitted ({mf.n_fit} events)")
    if positive.any():
        from matplotlib.ticker import NullFormatter, ScalarFormatter

        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(ScalarFormatter())  # counts read as 1, 10, 100
        ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel(f"moment $M$  [{moment_unit(u)}]")
    ax.set_ylabel(r"events with moment $\geq M$  [count]")
    ax.legend(fontsize=LEGEND_SIZE)
    _title(fig, ax, title or "magnitude-frequency distribution")
    return fig, ax
