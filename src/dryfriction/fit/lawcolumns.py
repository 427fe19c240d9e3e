"""The per-step table's columns for the state law and the initial state:
the law used, the values and 95 % intervals of the parameters that the law or the free
initial state add (:mod:`.laws`), whether each is identified, and the information criteria
that :mod:`.lawchoice` compares.

Identified (ours, as :mod:`.identify` for ``a, b, Dc``): a finite 95 % interval (the row's,
Wald in the fitted variable), not on a search bound, spanning at most ``MAX_SPAN`` for a
positive scale (``b2``, ``dc2``) and at most ``ln MAX_SPAN`` for ``state0`` (a factor 10 in
``theta0``); ``c`` needs a finite interval only (``c = 0`` is the ageing law, an answer). Not
identified: value NaN, the word ``not_identified:<name>`` in ``flags`` and a note.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ..validation import Array
from .identify import MAX_SPAN, join_flags, split_flags
from .models import ParamSpec

__all__ = ["LAW_COLUMNS", "LAW_PARAMETERS", "add_law_columns"]

LAW_PARAMETERS: tuple[str, ...] = ("state0", "c", "b2", "dc2")
"""Parameters a law (``c``: nagata; ``b2``, ``dc2``: ageing2) or the free initial state
(``state0``) adds."""

LAW_COLUMNS: tuple[str, ...] = ("state_law", "initial", *(f"{p}{s}" for p in LAW_PARAMETERS
                                                          for s in ("", "_lo", "_hi")),
                                "aic", "bic")
"""``state_law`` the law of the row's fit, ``initial`` its initial state (``steady`` or
``free``); ``state0`` (dimensionless, ``ln(theta0 V/Dc)``), ``c`` (dimensionless), ``b2``
(dimensionless), ``dc2`` (m) with their 95 % intervals, NaN where the law has no such
parameter or it is not identified; ``aic``, ``bic`` of the fit (Gaussian likelihood of
independent residuals: compare them between laws of one step only)."""

_BOUND_REL = 1e-3


def add_law_columns(row: dict[str, Any], law: str, information: Mapping[str, Any],
                    specs: Sequence[ParamSpec], theta: Array, cov: Array, singular: bool,
                    z: float) -> None:
    """Fill :data:`LAW_COLUMNS` of one row in place (module docstring), adding flag words and
    notes for what is not identified."""
    names = [s.name for s in specs]
    row["state_law"] = law
    row["initial"] = "free" if "state0" in names else "steady"
    row["aic"] = float(information.get("aic", math.nan))
    row["bic"] = float(information.get("bic", math.nan))
    words = split_flags(row.get("flags", ""))
    notes: list[str] = row.setdefault("notes", [])
    for name in LAW_PARAMETERS:
        row[name] = row[f"{name}_lo"] = row[f"{name}_hi"] = math.nan
        if name not in names:
            continue
        j = names.index(name)
        sp = specs[j]
        # a variance of 0 is a degenerate covariance: no interval, not a zero-width one
        se = math.sqrt(cov[j, j]) if not singular and np.isfinite(cov[j, j]) \
            and cov[j, j] > 0 else math.nan
        val = sp.from_internal(float(theta[j]))
        lo, hi = ((sp.from_internal(float(theta[j]) - z * se),
                   sp.from_internal(float(theta[j]) + z * se)) if math.isfinite(se)
                  else (math.nan, math.nan))
        lo_b, hi_b = sp.bounds
        width = float(hi_b - lo_b)
        on_bound = min(abs(float(theta[j]) - lo_b), abs(hi_b - float(theta[j]))) \
            < _BOUND_REL * max(width, 1.0) if name != "c" else \
            abs(hi_b - float(theta[j])) < _BOUND_REL * width
        finite = math.isfinite(lo) and math.isfinite(hi)
        if name == "state0":
            narrow = finite and hi - lo <= math.log(MAX_SPAN)
        elif sp.log:
            narrow = finite and lo > 0 and hi / lo <= MAX_SPAN
        else:
            narrow = finite
        if narrow and not on_bound:
            row[name], row[f"{name}_lo"], row[f"{name}_hi"] = val, lo, hi
            continue
        why = ("it ended on its search bound" if on_bound else
               "the covariance gives no finite interval" if not finite else
               f"its 95 % interval [{lo:.3g}, {hi:.3g}] is wider than "
               + ("ln 10" if name == "state0" else "a factor 10"))
        words.append(f"not_identified:{name}")
        notes.append(f"{name} = {val:.3g}{' ' + sp.unit if sp.unit else ''} is not "
                     f"identified: {why}; not reported")
    if law == "ageing2" and math.isfinite(row.get("b2", math.nan)):
        notes.append(f"two state variables: a_minus_b is a - b; the steady-state rate "
                     f"dependence is a - b - b2 = {row['a_minus_b'] - row['b2']:.4g}")
    row["flags"] = join_flags(words)
