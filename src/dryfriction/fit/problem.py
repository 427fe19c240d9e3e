"""The weighted least-squares problem of a model on data sets, in the fitted variables.

:class:`Problem` turns parameter vectors ``theta`` (``ln p`` for positive scales, see
:class:`~.models.ParamSpec`) into weighted residuals, minimises them over any subset of the
parameters (:meth:`Problem.solve`, used by the fit and by the profiles) and gives their
Jacobian (:meth:`Problem.jacobian`, for the covariance).
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares

from ..records.data import Dataset, SeriesData
from ..rsf.driving import SolverError
from ..validation import Array
from .models import Model, ParamSpec

__all__ = ["Problem"]


class Problem:
    """Residuals of a model on data sets, in the fitted (internal) variables."""

    def __init__(self, model: Model, datasets: Sequence[Dataset], specs: Sequence[ParamSpec],
                 fixed: Mapping[str, float]) -> None:
        self.model, self.datasets, self.specs = model, list(datasets), list(specs)
        self.fixed = dict(fixed)
        self.sigma_given = all(d.sigma is not None for d in datasets)
        self.w = [1.0 / d.sigma if self.sigma_given else np.ones(len(d))  # type: ignore[operator]
                  for d in datasets]
        self.n = sum(len(d) for d in datasets)
        self.p = len(specs)
        self.failures = 0
        self.last_failure = ""  # why the model could not be evaluated, the last time
        self.evaluations = 0
        # called after every evaluation of the model (the fit's progress report)
        self.on_evaluation: Callable[[], None] | None = None

    def values(self, theta: Array) -> dict[str, float]:
        v = dict(self.fixed)
        v.update({s.name: s.from_internal(t) for s, t in zip(self.specs, theta, strict=True)})
        return v

    def split(self, theta: Array) -> list[Array]:
        v = self.values(theta)
        out = []
        for d, w in zip(self.datasets, self.w, strict=True):
            try:
                f = self.model.predict(v, d)
            except (SolverError, ValueError) as exc:
                # the simulator or a range check failed for these trial parameters (ours):
                # a large penalty makes the trust region step back
                self.failures += 1
                self.last_failure = str(exc)
                f = d.y + 10.0 / w
            out.append((d.y - f) * w)
        self.evaluations += 1
        if self.on_evaluation is not None:
            self.on_evaluation()
        return out

    def residuals(self, theta: Array) -> Array:
        r = np.concatenate(self.split(theta))
        return np.where(np.isfinite(r), r, 1e6)

    @property
    def bounds(self) -> tuple[Array, Array]:
        lo, hi = zip(*(s.bounds for s in self.specs), strict=True)
        return np.array(lo), np.array(hi)

    def diff_step(self) -> float | None:
        if not any(isinstance(d, SeriesData) for d in self.datasets):
            return None
        return float(getattr(self.model, "diff_step", 1e-5))

    def solve(self, theta0: Array, free: NDArray[np.bool_] | None = None,
              max_nfev: int | None = None) -> tuple[Array, float, Any]:
        """Minimise over the ``free`` entries of theta (all by default) from ``theta0``."""
        lo, hi = self.bounds
        free = np.ones(self.p, bool) if free is None else free
        theta0 = np.clip(theta0, lo, hi)
        if not np.any(free):
            r = self.residuals(theta0)
            return theta0, 0.5 * float(r @ r), None
        full = theta0.copy()

        def res(x: Array) -> Array:
            full[free] = x
            return self.residuals(full)

        x0 = np.clip(theta0[free], lo[free] + 1e-12, hi[free] - 1e-12)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            tol = 1e-12 if self.diff_step() in (None, 1e-5) else 1e-6  # staircase: see CVModel
            sol = least_squares(res, x0, bounds=(lo[free], hi[free]), method="trf",
                                x_scale="jac", ftol=tol, xtol=tol, gtol=1e-10,
                                diff_step=self.diff_step(),
                                max_nfev=max_nfev or getattr(self.model, "max_nfev", None)
                                or 200 * (int(free.sum()) + 1))
        out = theta0.copy()
        out[free] = sol.x
        return out, float(sol.cost), sol

    def jacobian(self, theta: Array) -> Array:
        """Central-difference Jacobian of the residuals in the internal variables."""
        ds = self.diff_step()
        h0 = (ds if ds > 1e-5 else 1e-4) if ds else 1e-6
        lo, hi = self.bounds
        J = np.empty((self.n, self.p))
        for j in range(self.p):
            h = h0 * max(1.0, abs(theta[j]))
            tp, tm = theta.copy(), theta.copy()
            tp[j] = min(theta[j] + h, hi[j])
            tm[j] = max(theta[j] - h, lo[j])
            J[:, j] = (self.residuals(tp) - self.residuals(tm)) / (tp[j] - tm[j])
        return J

