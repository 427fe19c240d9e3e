"""The trap model fitted to a laboratory record's steps, on the same machine as the
rate-and-state fit (issue 11, ours): :func:`fit_cv_steps`.

Each window of a :class:`.steps.StepsResult` is fitted with :class:`.models.CVModel` on a
fitted spring with a linear trend (``stiffness="fit"``, ``trend=True``: the rate-and-state
fit's machine), from one start, the window's rate-and-state optimum mapped through the
trap model's rate-and-state twin (:func:`.cvseries.cv_start_from_rsf`), instead of a
multistart. The cost is held down by a coarse regular track (:data:`RECORD_TRAPS_PER_A0`), by
sampling the ensemble in slip rather than at the data's rate (:data:`RECORD_SAMPLE_SLIP`), by
the trend's cached run (:mod:`.cvseries`) and by a cap on evaluations
(:data:`RECORD_MAX_NFEV`). The data are fitted whole (every sample), so the misfit and AIC
compare with the rate-and-state fit's directly.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from ..io.data import SeriesData
from .cvseries import cv_start_from_rsf
from .engine import fit
from .models import CVModel
from .results import FitResult

__all__ = ["fit_cv_steps", "record_cv_model", "RECORD_TRAPS_PER_A0", "RECORD_SAMPLE_SLIP",
           "RECORD_MAX_NFEV", "RECORD_DIFF_STEP"]

RECORD_TRAPS_PER_A0 = 100.0
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

SEARCH_COARSENING = 2.0
"""The search runs on a track this many times sparser (ours, issue 30): a run costs about the
square of the density (the creep steps per ``a0`` and the traps in contact both grow with it:
0.30 s against 0.75 s on the basalt-like step), and its optimum is polished on the final
track."""

SEARCH_MAX_NFEV = 15
"""Cap on the search's evaluations (as :data:`RECORD_MAX_NFEV` counts them)."""

POLISH_MAX_NFEV = 3
"""Cap on the polish's evaluations on the final track, from the search's optimum."""

RECORD_DIFF_STEP = 0.03
"""Finite-difference step of the Jacobian, relative in the internal variables."""


def record_cv_model(alpha: float, creep: str, direct: float = 0.0, v_ref: float = 1e-6,
                    traps_per_a0: float = RECORD_TRAPS_PER_A0,
                    progress: Callable[[], None] | None = None,
                    max_nfev: int = RECORD_MAX_NFEV) -> CVModel:
    """The trap model as a record is fitted with it (module docstring)."""
    return CVModel(alpha, creep, traps_per_a0=traps_per_a0, direct=direct, v_ref=v_ref,
                   stiffness="fit", trend=True, sample_slip=RECORD_SAMPLE_SLIP,
                   max_nfev=max_nfev, diff_step=RECORD_DIFF_STEP, progress=progress,
                   steady_tail=True)


def fit_cv_steps(data: Sequence[SeriesData], rsf_fits: Sequence[FitResult], alpha: float,
                 creep: str, direct: float = 0.0, v_ref: float = 1e-6,
                 traps_per_a0: float = RECORD_TRAPS_PER_A0,
                 progress: Callable[[], None] | None = None) -> list[FitResult]:
    """Fit the trap model to each window from its rate-and-state fit (module docstring).

    Parameters
    ----------
    data, rsf_fits : sequences
        The windows and their rate-and-state fits (:func:`.steps.fit_steps`).
    alpha, creep : float, str
        Trap model (fixed).
    direct : float
        ``0``: the athermal model; ``> 0``: the direct effect ``A`` is fitted (its start comes
        from the twin, not from this value).
    v_ref : float
        Reference velocity of the direct effect, m/s.
    traps_per_a0 : float
        Track density.
    progress : callable, optional
        Called after each forward run.

    Returns
    -------
    list of FitResult
        One per window, without profiles (the covariance gives the intervals and the
        correlations).
    """
    search = record_cv_model(alpha, creep, direct, v_ref, traps_per_a0 / SEARCH_COARSENING,
                             progress, max_nfev=SEARCH_MAX_NFEV)
    model = record_cv_model(alpha, creep, direct, v_ref, traps_per_a0, progress,
                            max_nfev=POLISH_MAX_NFEV)
    out = []
    for d, r in zip(data, rsf_fits, strict=True):
        rsf = {p.name: p.value for p in r.parameters}
        v0 = r.options["v0"]
        start = cv_start_from_rsf(rsf, float(v0), alpha, creep, direct, v_ref)
        coarse = fit(d, search, start=start, multistart=False, profile=False,
                     consistency=False)
        found = {p.name: p.value for p in coarse.parameters}
        out.append(fit(d, model, start=found, multistart=False, profile=False,
                       consistency=False))
    return out
