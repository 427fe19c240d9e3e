"""One result schema for both simulators (the trap ensemble and rate-and-state).

Both :class:`dryfriction.ensemble.driving.SimulationResult` and
:class:`dryfriction.rsf.driving.RSFResult` offer

``columns()``
    The time series as ``{name: array}``, one entry per sample, always starting with the
    common columns :data:`COMMON_COLUMNS` (same names for the same quantities)::

        t    time                 x    slider position
        v    slider velocity      mu   friction coefficient

    followed by the simulator's own: ``theta`` (``theta2``), ``stress``, ``x_load``,
    ``v_load`` for rate-and-state; ``n_active``, ``mean_age``, ``x_pull``, ``f_applied``,
    ``births``, ``spinodal``, ``exits`` for the trap ensemble.

``summary()``
    A flat mapping made by :func:`summarize`, with the keys :data:`COMMON_SUMMARY_KEYS`:

    ==============  ==============================================================
    law             ``"cv"`` (trap model) or ``"rsf"`` (rate-and-state)
    partial         the run was interrupted (the samples stop early)
    samples         number of samples
    duration        ``t[-1] - t[0]``
    peak_mu         largest sampled friction; ``peak_t``, ``peak_x`` where it is
    final_mu        friction at the last sample
    mean_mu         time average of the friction (trapezoid rule)
    slip            ``x[-1] - x[0]``; ``path_length`` the sum of ``|dx|``
    v_max           largest sampled slider velocity
    units           ``{column: unit}`` for every column (``""``: dimensionless)
    ==============  ==============================================================

    and then the simulator's extras (solver statistics and the spring for rate-and-state;
    event counts, drive scalars and parameters for the trap ensemble). Times, lengths and
    velocities are in the simulator's units, named by ``units``: reduced (``t0``, ``a0``,
    ``a0/t0``) for the trap model, SI (s, m, m/s) for rate-and-state.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["COMMON_COLUMNS", "COMMON_SUMMARY_KEYS", "summarize"]

COMMON_COLUMNS: tuple[str, ...] = ("t", "x", "v", "mu")

COMMON_SUMMARY_KEYS: tuple[str, ...] = (
    "law", "partial", "samples", "duration", "peak_mu", "peak_t", "peak_x", "final_mu",
    "mean_mu", "slip", "path_length", "v_max", "units",
)


def summarize(
    law: str,
    t: ArrayLike,
    x: ArrayLike,
    v: ArrayLike,
    mu: ArrayLike,
    units: Mapping[str, str],
    *,
    partial: bool = False,
    extra: Mapping[str, Any] | None = None,
) -> dict[str, Any]:
    """The common summary of a time series (the keys :data:`COMMON_SUMMARY_KEYS`), then ``extra``.

    Parameters
    ----------
    law : str
        ``"cv"`` or ``"rsf"``.
    t, x, v, mu : array_like
        The common columns (same length, at least one sample).
    units : mapping
        Unit of every column.
    partial : bool
        Whether the run stopped early.
    extra : mapping, optional
        Simulator-specific entries; they may not redefine a common key.

    Returns
    -------
    dict
    """
    t, x, v, mu = (np.asarray(a, float) for a in (t, x, v, mu))
    if not len(t):
        raise ValueError("a result needs at least one sample")
    # NaN friction (e.g. an undefined sample) must not hide the peak of the others
    k = int(np.nanargmax(mu)) if np.any(np.isfinite(mu)) else 0
    span = float(t[-1] - t[0])
    mean = float(np.trapezoid(mu, t) / span) if span > 0 else float(np.mean(mu))
    out: dict[str, Any] = {
        "law": law,
        "partial": bool(partial),
        "samples": int(len(t)),
        "duration": span,
        "peak_mu": float(mu[k]),
        "peak_t": float(t[k]),
        "peak_x": float(x[k]),
        "final_mu": float(mu[-1]),
        "mean_mu": mean,
        "slip": float(x[-1] - x[0]),
        "path_length": float(np.sum(np.abs(np.diff(x)))),
        "v_max": float(np.nanmax(v)) if np.any(np.isfinite(v)) else float("nan"),
        "units": dict(units),
    }
    for key, value in (extra or {}).items():
        if key in out:
            raise ValueError(f"summary key {key!r} is common to every result: rename the extra")
        out[key] = value
    return out
