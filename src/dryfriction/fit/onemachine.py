"""One machine for a whole record (``--stiffness record``; ours): the steps of
one record share one apparatus, so its stiffness is estimated once, from the steps whose free
fit identifies it (:func:`.identify.record_stiffness`: the inverse-variance weighted mean of
``ln k``, steps that disagree flagged ``k_inconsistent`` and left out), and every step is then
refitted with ``k`` held at that value.

The per-step intervals of ``a``, ``b``, ``Dc`` carry the record's ``k``'s own error (its
interval in ``fit.json``'s ``record_stiffness``): a two-step estimator, whose second step's
covariance gains ``G var(ln k) G^T`` and the cross term of the step's own share in ``k``
(Murphy & Topel 1985; :func:`.statistics.held_parameter_covariance`), ``G`` how ``a, b, Dc``
move with the held ``k``. The elastic loadings are taken as independent of the windows.
"""

from __future__ import annotations

import math
from typing import Any

from .identify import join_flags, split_flags
from .steps import StepsResult, fit_steps

__all__ = ["fit_steps_one_machine", "held_stiffness"]

Z = 1.96
"""The quantile :func:`.identify.record_stiffness` reads standard errors of ``ln k`` with."""


def held_stiffness(rec: dict[str, Any], rows: list[dict[str, Any]]) -> list[tuple[float, float]]:
    """Per step, ``(var ln k, share)`` of the record's stiffness ``rec``
    (:func:`.identify.record_stiffness`; standard errors from the 95 % intervals as it reads
    them): the variance of its ``ln k``, and the step's inverse-variance weight in it (its
    free fit's, from ``rows``; 0 for a step left out of it).

    Parameters
    ----------
    rec : dict
        The record's stiffness (``lo``, ``hi``: its 95 % interval, 1/m; ``steps``).
    rows : list of dict
        The free fits' rows (``stiffness_lo``, ``stiffness_hi``, 1/m).

    Returns
    -------
    list of (float, float)
        Per row, ``(var ln k, share)`` for :func:`.steps.fit_steps`'s ``held``.
    """
    var = (math.log(rec["hi"] / rec["lo"]) / (2.0 * Z)) ** 2
    out = []
    for i, r in enumerate(rows):
        own = (math.log(r["stiffness_hi"] / r["stiffness_lo"]) / (2.0 * Z)) ** 2 \
            if i in rec["steps"] else math.inf
        out.append((var, min(var / own, 1.0) if own > 0 else 0.0))
    return out


def fit_steps_one_machine(record: Any, windows: Any = None, segments: Any = None,
                          **kwargs: Any) -> StepsResult:
    """:func:`.steps.fit_steps` twice: with a free stiffness per step, then with the record's
    one stiffness fixed (module docstring). Keyword arguments as :func:`.steps.fit_steps`
    (``stiffness`` is not one of them). Where fewer than two steps identify ``k`` the free
    fits are returned, with a note. The record's stiffness also counts the slopes of its
    elastic loadings (:func:`.elastic.machine_stiffness_record`)."""
    free = fit_steps(record, windows, segments, stiffness="fit", **kwargs)
    rec = free.stiffness
    if rec is None:
        several = free.levels is not None and len(free.levels["levels"]) > 1
        free.notes.append("--stiffness record: " + (
            "the steps are at several normal stresses, and k (1/m) = K/sigma_n differs "
            "between them (each level's in fit.json grouping)" if several else
            "fewer than two estimates of k (steps that identify it, elastic loadings)") +
            ", so each step keeps its own fitted stiffness")
        return free
    fixed = fit_steps(record, windows, segments, stiffness=float(rec["value"]),
                      held=held_stiffness(rec, free.rows), **kwargs)
    for row, own, f in zip(fixed.rows, free.rows, free.fits, strict=True):
        words = split_flags(row["flags"])
        carried = [n for n in own["notes"][len(f.notes):] if n.startswith("k_inconsistent")]
        if "k_inconsistent" in split_flags(own["flags"]):
            words.append("k_inconsistent")
        row["flags"] = join_flags(words)
        row["stiffness_lo"], row["stiffness_hi"] = rec["lo"], rec["hi"]
        row["sigma_stiffness"] = math.nan  # not fitted in this step: the record's interval
        row["notes"] += carried + [
            f"k = {rec['value']:.4g} /m [{rec['lo']:.4g}, {rec['hi']:.4g}] held: the record's "
            f"one machine (steps {', '.join(map(str, rec['steps']))}); this step's own free "
            f"fit gave k = {own['stiffness']:.4g} /m; the intervals of a, b, Dc carry the "
            "record's k's error"]
    fixed.stiffness = rec
    used = [ld for ld in rec.get("loadings", []) if ld["used"]]
    at = ", ".join(f"{ld['t_start']:.6g}" for ld in used)
    fixed.notes.append(f"one machine: k = {rec['value']:.4g} /m [{rec['lo']:.4g}, "
                       f"{rec['hi']:.4g}] from the free fits of steps "
                       f"{', '.join(map(str, rec['steps'])) or 'none'}"
                       + (f" and {len(used)} elastic loading(s) (at "
                          f"{at} s)"
                          if used else "") + ", held in every step")
    for ld in rec.get("loadings", []):
        if ld["k_inconsistent"]:
            fixed.notes.append(f"the elastic {ld['kind']} at {ld['t_start']:.6g} s gives k = "
                               f"{ld['stiffness']:.4g} /m [{ld['stiffness_lo']:.4g}, "
                               f"{ld['stiffness_hi']:.4g}], which disagrees with the other "
                               "estimates: left out")
    return fixed
