"""The summary figure of a whole experiment: ``a - b``, ``a``, ``b`` and
``Dc`` of every velocity step against the load-point velocity after the step (log axis), one
colour and marker per normal-stress level, with the 95 % intervals of ``steps.csv``.

What is drawn and what is left out is decided in :func:`dryfriction.fit.experiment.
summary_points` (values not identified or at a bound, slide-hold-slides); the figure says how
many were left out and why, and which intervals the bars are.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from .style import LEGEND_SIZE, save_png

__all__ = ["plot_experiment_summary", "MARKERS"]

MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")
"""One marker per normal-stress level (with the colour ``C<level>``)."""

_LABELS = {"a_minus_b": r"$a - b$", "a": r"$a$", "b": r"$b$", "dc": r"$D_c$  [µm]"}
_SCALE = {"a_minus_b": 1.0, "a": 1.0, "b": 1.0, "dc": 1e6}


def _left_out_text(left: Mapping[int, str]) -> str:
    if not left:
        return ""
    counts: dict[str, int] = {}
    for why in left.values():
        counts[why] = counts.get(why, 0) + 1
    return "left out: " + ", ".join(f"{n} {why}" for why, n in sorted(counts.items()))


def plot_experiment_summary(rows: Sequence[Mapping[str, Any]], path: Any = None
                            ) -> tuple[Figure, tuple[Any, ...]]:
    """The summary (module docstring) of the rows of a per-step fit (``steps.csv``'s columns,
    with :data:`dryfriction.fit.experiment.EXPERIMENT_COLUMNS`).

    Each level's points are one ``errorbar`` container labelled with the level's normal
    stress (``"20 MPa"``), so that the figure's data can be read back from its artists.
    Returns the figure and the axes in the order of :data:`~dryfriction.fit.experiment.PANELS`.
    """
    from ..fit.experiment import PANELS, interval_words, level_label, summary_points

    pts = summary_points(rows)
    labels = {int(r["normal_level"]): level_label(float(r["normal"]), str(r["normal_unit"]))
              for r in rows}
    # the label is the level's mean normal stress over its steps
    for lv in set(labels):
        v = [float(r["normal"]) for r in rows if int(r["normal_level"]) == lv]
        labels[lv] = level_label(float(np.mean(v)), str(rows[0]["normal_unit"]))
    fig = Figure(figsize=(9.0, 6.6))
    axes = fig.subplots(2, 2, sharex=True).ravel()
    for ax, (name, _) in zip(axes, PANELS, strict=True):
        panel = pts[name]
        s = _SCALE[name]
        for lv in sorted(panel["levels"]):
            p = panel["levels"][lv]
            v = np.array([q[1] for q in p]) * 1e6
            y, lo, hi = (np.array([q[k] for q in p]) * s for k in (2, 3, 4))
            # an interval end the data do not give is drawn as no bar on that side
            err = np.vstack([np.where(np.isfinite(lo), y - lo, 0.0),
                             np.where(np.isfinite(hi), hi - y, 0.0)])
            ax.errorbar(v, y, yerr=err, fmt=MARKERS[lv % len(MARKERS)], color=f"C{lv}",
                        ms=5, capsize=2.5, lw=1.0, label=labels.get(lv, str(lv)))
        text = _left_out_text(panel["left_out"])
        if text:
            ax.text(0.02, 0.02, text, transform=ax.transAxes, fontsize=7, color="C3",
                    va="bottom")
        ax.set_xscale("log")
        ax.set_ylabel(_LABELS[name])
        if name == "a_minus_b":
            ax.axhline(0.0, color="0.5", lw=0.8)
    for ax in axes[2:]:
        ax.set_xlabel(r"load-point velocity after the step $V$  [µm/s]")
    v_all = [q[1] * 1e6 for name, _ in PANELS for p in pts[name]["levels"].values() for q in p]
    if v_all:  # one velocity (or a narrow range) gave singular log limits: pad to x2 each way
        lo, hi = min(v_all), max(v_all)
        if hi < 3.0 * lo:
            axes[0].set_xlim(lo / 2.0, hi * 2.0)  # the axes share x
    found: dict[str, Any] = {}  # every level drawn in any panel, once
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            found.setdefault(lab, h)
    handles = [found[lab] for lab in sorted(found, key=lambda x: [
        k for k, v in labels.items() if v == x][:1] or [99])]
    if handles:
        fig.legend(handles=handles, loc="upper right", fontsize=LEGEND_SIZE,
                   title="normal stress", title_fontsize=LEGEND_SIZE)
    errs = sorted({str(r.get("errors", "hac")) for r in rows})
    kinds = pts["intervals"]
    head = ("95 % intervals: a, b, Dc: " + " / ".join(interval_words(k) for k in kinds)
            + "; a - b: " + " / ".join(interval_words(e) for e in errs) + " (delta method)")
    gone = sum(len(pts[name]["left_out"]) for name, _ in PANELS)
    tail = (f"{gone} value(s) not identified or at a bound left out (count and reason in each "
            "panel; steps.csv flags)" if gone else "every value of every velocity step drawn")
    if pts["holds"]:
        tail += (f"; {len(pts['holds'])} slide-hold-slide(s) not drawn (not velocity steps; "
                 "listed in steps.csv, kind shs)")
    fig.suptitle(head + "\n" + tail, fontsize=8, x=0.02, ha="left")
    fig.subplots_adjust(left=0.1, right=0.86, bottom=0.09, top=0.9, wspace=0.3, hspace=0.12)
    if path is not None:
        save_png(fig, path)
    return fig, tuple(axes)
