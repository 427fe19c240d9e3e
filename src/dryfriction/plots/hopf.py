"""The figure of ``dryfriction bifurcation`` (``bifurcation.png``): the critical stiffness
against the load velocity, each point marked with the nature of the Hopf point, and the
relative first Lyapunov coefficient below it."""

from __future__ import annotations

import math
from typing import Any

from .style import (
    LEGEND_SIZE,
    RUN_WIDTH,
    STIFFNESS_K,
    TITLE_SIZE,
    VELOCITY_SI,
    VELOCITY_U,
    new_figure,
)

__all__ = ["plot_bifurcation"]

_MARK = {"supercritical": ("o", "tab:blue"), "subcritical": ("s", "tab:red"),
         "degenerate": ("D", "tab:gray"), "none": ("x", "k"),
         "undetermined": ("+", "tab:orange")}


def plot_bifurcation(report: dict[str, Any], title: str = "") -> tuple[Any, Any]:
    """Two panels sharing the velocity axis (m/s, log; ``a0/t0`` for the trap model,
    ``report["law"] == "trap"``): ``K_c`` (1/m, log; ``F_el/a0``) and ``l1 / max|term|``
    (symmetric log), marked by nature (circle supercritical, square subcritical, diamond
    degenerate). Returns ``(fig, axes)``."""
    trap = report.get("law") == "trap"  # reduced units (dryfriction.analysis.trap_hopf)
    fig, axes = new_figure((RUN_WIDTH, 5.6), nrows=2, sharex=True, suptitle=bool(title))
    rows = report["rows"]
    for nature, (marker, colour) in _MARK.items():
        pts = [r for r in rows if r["nature"] == nature]
        if not pts:
            continue
        v = [r["velocity"] for r in pts]
        kc = [r["K_c"] if math.isfinite(r["K_c"]) else float("nan") for r in pts]
        axes[0].plot(v, kc, marker, color=colour, label=nature, ms=5)
        axes[1].plot(v, [r["relative_l1"] for r in pts], marker, color=colour, ms=5)
    axes[0].set_xscale("log")
    kcs = [r["K_c"] for r in rows if math.isfinite(r["K_c"]) and r["K_c"] > 0]
    if kcs and max(kcs) > 10 * min(kcs):  # log only over a decade: else unreadable ticks
        axes[0].set_yscale("log")
    axes[0].set_ylabel(r"critical " + STIFFNESS_K.replace("$K$", "$K_c$") if trap
                       else r"critical stiffness $K_c$  [1/m]")
    axes[0].legend(fontsize=LEGEND_SIZE)
    _symlog_panel(axes[1], [r["relative_l1"] for r in rows])
    axes[1].set_ylabel(r"$\ell_1$ / largest term  [1]")
    axes[1].set_xlabel(VELOCITY_U if trap else VELOCITY_SI)
    vs = [r["velocity"] for r in rows]
    if min(vs) == max(vs):  # one velocity: a visible decade around it
        axes[1].set_xlim(min(vs) / 3, max(vs) * 3)
    if title:
        fig.suptitle(title, fontsize=TITLE_SIZE)
    return fig, axes


def _symlog_panel(ax: Any, values: list[float], linthresh: float = 1e-8) -> None:
    """A symmetric-log axis whose ticks do not collide: at most four decades a side (every
    k-th decade from ``linthresh`` to the largest ``|value|``), 0, and limits a factor 3
    beyond the largest ``|value|`` so that no point sits on a spine."""
    import numpy as np
    from matplotlib.ticker import NullLocator

    ys = np.asarray([y for y in values if math.isfinite(y)], float)
    top = 3.0 * max(float(np.max(np.abs(ys))) if ys.size else 0.0, linthresh)
    lo, hi = round(math.log10(linthresh)), math.ceil(math.log10(top))
    step = max(1, math.ceil((hi - lo) / 4))
    decades = [10.0 ** e for e in range(hi - 1, lo - 1, -step) if 10.0 ** e <= top]
    ticks = ([-d for d in decades] if ys.size and np.any(ys < 0) else []) + [0.0] + (
        decades if ys.size and np.any(ys > 0) else [])
    ax.set_yscale("symlog", linthresh=linthresh)
    ax.set_ylim(-top if ys.size and np.any(ys < 0) else -linthresh,
                top if ys.size and np.any(ys > 0) else linthresh)
    ax.set_yticks(sorted(ticks))
    ax.yaxis.set_minor_locator(NullLocator())
    ax.axhline(0.0, color="k", lw=0.6)
