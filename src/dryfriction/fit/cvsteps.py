"""The trap model fitted to a laboratory record's steps, on the same machine as the
rate-and-state fit (ours): :func:`fit_cv_steps`.

Each window of a :class:`.steps.StepsResult` is fitted with :class:`.models.CVModel` on a
fitted spring with a linear trend (``stiffness="fit"``, ``trend=True``: the rate-and-state
fit's machine), from one start, the window's rate-and-state optimum mapped through the
trap model's rate-and-state twin (:func:`.cvseries.cv_start_from_rsf`), instead of a
multistart. The cost is held down by a coarse regular track (:data:`RECORD_TRAPS_PER_A0`), by
sampling the ensemble in slip rather than at the data's rate (:data:`RECORD_SAMPLE_SLIP`), by
not simulating the steady tail of a segment (:mod:`.cvtail`), by the memory of runs
(:mod:`.cvseries`: the trend's Jacobian column, the covariances' repeated points), and by a
search that stops when its steps are a tenth of a standard error (:func:`search_step`;
the basalt step took 445 s of CPU). The data are fitted whole (every sample), so the
misfit and AIC compare with the rate-and-state fit's directly.
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..records.data import SeriesData
from ..theory.model import TRAPS_PER_A0_COARSE, OldTheoryFormWarning, TrapModel
from .cvseries import cv_start_from_rsf
from .engine import fit
from .models import CVModel
from .results import FitResult

__all__ = ["fit_cv_steps", "record_cv_model", "search_step", "RECORD_TRAPS_PER_A0",
           "RECORD_SAMPLE_SLIP", "RECORD_MAX_NFEV", "RECORD_DIFF_STEP", "SEARCH_MAX_ITER",
           "SEARCH_STOP", "SEARCH_TRIALS"]

RECORD_TRAPS_PER_A0 = TRAPS_PER_A0_COARSE
"""Track density for a record (measured on the shared sepiolite step, at the rate-and-state
start: rms difference from a 1000-trap track 1.0e-3 with ``A = 0`` and 2.8e-4 with
``A = 0.03``, below the record's steady noise 1.5e-3; a forward run 0.3 s and 1 s CPU)."""

RECORD_SAMPLE_SLIP = 0.01
"""Ensemble sampling for a record, ``a0`` of load-point travel (the data are read from it by
linear interpolation; 0.02 changed the series by less than 1e-4 rms)."""

RECORD_MAX_NFEV = 30
"""Cap on the evaluations of a record window's minimisation, as scipy counts them (those
outside the finite-difference Jacobian: about one per iteration; each iteration also costs
one run per free parameter but the trend). The sepiolite step converged in 22."""

SEARCH_MAX_ITER = RECORD_MAX_NFEV
"""Most iterations of the search (:func:`search_step`), one accepted step each."""

SEARCH_STOP = 0.1
"""The search stops when its last step moved every parameter by less than this fraction of
its standard error (the Jacobian's, white noise; ours): a least-squares fit on the
ensemble's staircase never meets scipy's relative tolerances, and went on to its cap of
evaluations with steps of a thousandth of a standard error."""

SEARCH_TRIALS = 3
"""Trial points of one iteration of :func:`search_step` (a refused one shrinks scipy's trust
region fourfold: three refused, a 64th of its first radius, end the search)."""

SEARCH_DOC = {
    "step": f"converged: the last step moved every parameter by < {SEARCH_STOP:g} standard "
            "error",
    "refused": "converged: no step lowers the cost, down to a 64th of the trust region (the "
               "ensemble's staircase)",
    "cap": f"not converged: {SEARCH_MAX_ITER} iterations",
}
"""Why :func:`search_step` stopped, as the fit's message says it."""

RECORD_DIFF_STEP = 0.03
"""Finite-difference step of the Jacobian, relative in the internal variables."""


def record_cv_model(trap: TrapModel | float | None = None, *args: Any, **kwargs: Any) -> CVModel:
    """The trap model as a record is fitted with it (module docstring):
    ``record_cv_model(trap, v_ref=1e-6, traps_per_a0=RECORD_TRAPS_PER_A0, progress=None,
    max_nfev=RECORD_MAX_NFEV)``.

    Parameters
    ----------
    trap : TrapModel
        The held trap model (:class:`.models.CVModel`): ``alpha``, ``creep`` fixed; ``direct >
        0``: the direct effect is fitted. The old form ``record_cv_model(alpha, creep, direct,
        v_ref, traps_per_a0, progress, max_nfev)`` warns
        (:class:`~dryfriction.theory.model.OldTheoryFormWarning`) for one more release.
    v_ref : float
        Reference velocity of the direct effect, m/s.
    traps_per_a0 : float
        Track density.
    progress : callable, optional
        Called after each forward run.
    max_nfev : int
        Cap on the evaluations of the engine's minimisation.
    """
    if trap is None or isinstance(trap, TrapModel):
        return _record_cv_model(TrapModel() if trap is None else trap, *args, **kwargs)
    warnings.warn("fit.cvsteps.record_cv_model(alpha, creep, direct, v_ref, ...) is the old "
                  "form (one more release): use record_cv_model(TrapModel(alpha, creep=creep, "
                  "direct=direct), v_ref, ...), with a dryfriction.TrapModel",
                  OldTheoryFormWarning, stacklevel=2)
    return _old_record_cv_model(trap, *args, **kwargs)


def _old_record_cv_model(alpha: float, creep: str, direct: float = 0.0, v_ref: float = 1e-6,
                         traps_per_a0: float = RECORD_TRAPS_PER_A0,
                         progress: Callable[[], None] | None = None,
                         max_nfev: int = RECORD_MAX_NFEV) -> CVModel:
    return _record_cv_model(TrapModel(alpha, creep=creep, direct=direct), v_ref, traps_per_a0,
                            progress, max_nfev)


def _record_cv_model(trap: TrapModel, v_ref: float = 1e-6,
                     traps_per_a0: float = RECORD_TRAPS_PER_A0,
                     progress: Callable[[], None] | None = None,
                     max_nfev: int = RECORD_MAX_NFEV) -> CVModel:
    return CVModel(trap, traps_per_a0=traps_per_a0, v_ref=v_ref, stiffness="fit", trend=True,
                   sample_slip=RECORD_SAMPLE_SLIP, max_nfev=max_nfev,
                   diff_step=RECORD_DIFF_STEP, progress=progress, steady_tail=True)


def fit_cv_steps(data: Sequence[SeriesData], rsf_fits: Sequence[FitResult],
                 model: CVModel | float | None = None, *args: Any,
                 **kwargs: Any) -> list[FitResult]:
    """Fit the trap model to each window from its rate-and-state fit (module docstring):
    ``fit_cv_steps(data, rsf_fits, model)``.

    Parameters
    ----------
    data, rsf_fits : sequences
        The windows and their rate-and-state fits (:func:`.steps.fit_steps`).
    model : CVModel
        The trap model as a record is fitted with it (:func:`record_cv_model`; default:
        ``record_cv_model(TrapModel())``), its progress called after each forward run. With
        the direct effect (``model.trap.direct > 0``) ``A``'s start comes from the twin, not
        from the model. The old form ``fit_cv_steps(data, rsf_fits, alpha, creep, direct,
        v_ref, traps_per_a0, progress)`` warns
        (:class:`~dryfriction.theory.model.OldTheoryFormWarning`) for one more release.

    Returns
    -------
    list of FitResult
        One per window, without profiles (the covariance gives the intervals and the
        correlations).
    """
    if model is None or isinstance(model, CVModel):
        if args or kwargs:
            raise TypeError("fit_cv_steps(data, rsf_fits, model) takes no more arguments: "
                            "the model holds them (record_cv_model)")
        return _fit_cv_steps(data, rsf_fits, record_cv_model() if model is None else model)
    warnings.warn("fit.cvsteps.fit_cv_steps(data, rsf_fits, alpha, creep, direct, v_ref, "
                  "traps_per_a0, progress) is the old form (one more release): use "
                  "fit_cv_steps(data, rsf_fits, record_cv_model(TrapModel(alpha, creep=creep, "
                  "direct=direct), v_ref, traps_per_a0, progress)), with a "
                  "dryfriction.TrapModel", OldTheoryFormWarning, stacklevel=2)
    return _old_fit_cv_steps(data, rsf_fits, model, *args, **kwargs)


def _old_fit_cv_steps(data: Sequence[SeriesData], rsf_fits: Sequence[FitResult], alpha: float,
                      creep: str, direct: float = 0.0, v_ref: float = 1e-6,
                      traps_per_a0: float = RECORD_TRAPS_PER_A0,
                      progress: Callable[[], None] | None = None) -> list[FitResult]:
    return _fit_cv_steps(data, rsf_fits, _record_cv_model(
        TrapModel(alpha, creep=creep, direct=direct), v_ref, traps_per_a0, progress))


def _fit_cv_steps(data: Sequence[SeriesData], rsf_fits: Sequence[FitResult], model: CVModel
                  ) -> list[FitResult]:
    out = []
    for d, r in zip(data, rsf_fits, strict=True):
        rsf = {p.name: p.value for p in r.parameters}
        v0 = r.options["v0"]
        start = cv_start_from_rsf(model, rsf, float(v0))
        found, iterations, why, nfev = search_step(d, model, start)
        # the engine's fit from there: its first evaluation and Jacobian are the search's last
        # (remembered, :mod:`.cvseries`), and it takes no step (one evaluation), so its own
        # verdict is "evaluations exceeded"; the search's is the one that counts
        res = fit(d, dataclasses.replace(model, max_nfev=1), start=found, multistart=False,
                  profile=False, consistency=False)
        at_bound = any("search bound" in n for n in res.notes)
        done = why != "cap"
        notes = [n for n in res.notes if "did not converge" not in n or not done]
        notes.append(f"trap model: search of {iterations} iterations ({SEARCH_DOC[why]})")
        if done and at_bound:
            notes.append("the fit is not reliable (see the parameters on their bounds)")
        out.append(dataclasses.replace(
            res, nfev=nfev + res.nfev, notes=tuple(notes),
            success=done and not at_bound and "could not be evaluated" not in res.message,
            status=1 if done else 0, message=SEARCH_DOC[why]))
    return out


def search_step(d: SeriesData, model: CVModel, start: dict[str, float]
                ) -> tuple[dict[str, float], int, str, int]:
    """The least-squares search of one window (ours): scipy's trust-region
    iterations (as :meth:`.problem.Problem.solve` runs them) a few trial points at a time
    (:data:`SEARCH_TRIALS`), each batch from where the last ended (the memory of runs makes the
    restart free), until a batch moves every free parameter by less than :data:`SEARCH_STOP`
    of its standard error (``s^2 (J^T J)^-1``, ``J`` the Jacobian where it ended), refuses
    every trial, or :data:`SEARCH_MAX_ITER` batches.

    Returns
    -------
    values, iterations, why, nfev : dict, int, str, int
        The parameters found (SI), the iterations taken, why the search stopped (``"step"``,
        ``"refused"``, ``"cap"``: :data:`SEARCH_DOC`) and scipy's count of evaluations (those
        outside the finite-difference Jacobians, restarts included).
    """
    from .problem import Problem

    specs = model.parameters(frozenset({"series"}))
    prob = Problem(model, [d], specs, {})
    theta = np.array([s.to_internal(float(np.clip(start[s.name], s.lo, s.hi))) for s in specs])
    it, why, nfev = 0, "cap", 0
    while it < SEARCH_MAX_ITER:
        it += 1
        # up to SEARCH_TRIALS trial points: a refused step shrinks the trust region, which
        # each restart resets
        new, cost, sol = prob.solve(theta, max_nfev=1 + SEARCH_TRIALS)
        nfev += 0 if sol is None else int(sol.nfev)
        if sol is None or np.array_equal(new, theta):  # every trial refused: the floor
            why = "refused"
            break
        step, theta = new - theta, new
        J = np.asarray(sol.jac)
        with np.errstate(all="ignore"):
            var = np.diag(np.linalg.pinv(J.T @ J)) * 2.0 * cost / max(prob.n - prob.p, 1)
        if np.all(np.abs(step) < SEARCH_STOP * np.sqrt(np.abs(var))):
            why = "step"
            break
    return ({s.name: s.from_internal(t) for s, t in zip(specs, theta, strict=True)}, it, why,
            nfev)

