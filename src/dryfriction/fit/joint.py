"""All steps of a record fitted together (``fit_steps(..., joint=True)``): one ``a, b, Dc`` (and
one stiffness: the same machine), with per window its own ``mu0`` and trend, started from the
per-step fits' medians (:mod:`.steps`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..records.data import SeriesData
from ..validation import Array
from .engine import fit
from .models import ParamSpec, RSFModel, rsf_series
from .results import FitResult

__all__ = ["JointStepsModel", "fit_joint"]


@dataclass(frozen=True)
class JointStepsModel:
    """Rate-and-state on several windows at once with one ``a, b, dc`` (and one stiffness:
    the same machine), and per window its own ``mu0_<i>`` (reference velocity: the window's
    first load velocity) and ``trend_<i>``. The :func:`.engine.fit` model protocol."""

    windows: tuple[SeriesData, ...]
    base: RSFModel
    start: Mapping[str, float] = field(default_factory=dict)
    name: str = "rsf-joint"

    def _index(self, d: SeriesData) -> int:
        for i, w in enumerate(self.windows):
            if w is d:
                return i
        raise ValueError(f"{d.source} is not one of the joint fit's windows")

    def options(self) -> dict[str, Any]:
        return {**self.base.options(), "joint_windows": len(self.windows)}

    def parameters(self, kinds: frozenset[str]) -> tuple[ParamSpec, ...]:
        own = self.base.parameters(frozenset({"series"}))
        shared = tuple(s for s in own if s.name in ("a", "b", "dc", "stiffness"))
        per: list[ParamSpec] = []
        for i in range(len(self.windows)):
            for s in own:
                if s.name in ("mu0", "trend"):
                    per.append(ParamSpec(f"{s.name}_{i}", s.unit, s.log, s.lo, s.hi))
        return (*shared, *per)

    def notes(self, kinds: frozenset[str]) -> list[str]:
        return [f"joint fit of {len(self.windows)} windows: one a, b, dc and stiffness; "
                "mu0 and trend per window"]

    def predict(self, v: Mapping[str, float], d: Any, x: Array | None = None) -> Array:
        i = self._index(d)
        vals = {k: v[k] for k in ("a", "b", "dc", "stiffness") if k in v}
        vals["mu0"] = v[f"mu0_{i}"]
        if f"trend_{i}" in v:
            vals["trend"] = v[f"trend_{i}"]
        m = RSFModel(float(d.v_load[0]), self.base.state_law, self.base.stiffness,
                     self.base.damping, self.base.regularized, trend=self.base.trend)
        return rsf_series(m, vals, d)

    def data_window(self, name: str, datasets: Sequence[Any]) -> tuple[float, float] | None:
        return self.base.data_window(name, datasets)

    def derived(self, v: Mapping[str, float]) -> dict[str, tuple[float, str]]:
        return {"a_minus_b": (v["a"] - v["b"], "")}

    def guesses(self, datasets: Sequence[Any]) -> list[dict[str, float]]:
        """The start from the per-step fits (:func:`fit_steps`)."""
        return [dict(self.start)]



def fit_joint(pieces: list[SeriesData], fits: list[FitResult], law: str,
               stiffness: float | str, trend: bool) -> FitResult:
    """All windows with one ``a, b, dc`` (and stiffness), from the per-step fits' medians."""
    if isinstance(stiffness, str) and stiffness == "slope":
        # one machine: the stiffness from the first window's slope holds for all
        stiffness = float(RSFModel(1.0, law, "slope").resolve([pieces[0]]).stiffness)
    base = RSFModel(1.0, law, stiffness, trend=trend)
    vals = [{p.name: p.value for p in r.parameters} for r in fits]
    start: dict[str, float] = {}
    for name in ("a", "b", "dc", "stiffness"):
        if name in vals[0]:
            start[name] = float(np.exp(np.median(np.log([v[name] for v in vals]))))
    for i, v in enumerate(vals):
        start[f"mu0_{i}"] = v["mu0"]
        if trend:
            start[f"trend_{i}"] = v.get("trend", 0.0)
    jm = JointStepsModel(tuple(pieces), base, start)
    # Wald intervals: the engine's profile walk over 3 + 2 n parameters would cost far more
    # than all the per-step fits
    return fit(list(pieces), jm, start=start, multistart=False, profile=False,
               consistency=False)
