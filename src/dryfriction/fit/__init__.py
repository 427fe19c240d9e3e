"""Fit the trap model or rate-and-state friction to measured friction, with honest errors.

The package is split by concern (each module is imported by the ones after it):

* :mod:`.models` — what is fitted: :class:`ParamSpec`, the trap model :class:`CVModel` and
  rate-and-state :class:`RSFModel` (parameters per data kind, predictions, data-driven starts),
  the time-series models :func:`cv_series` and :func:`rsf_series`;
* :mod:`.results` — what a fit returns: :class:`ParameterEstimate`, :class:`FitResult`;
* :mod:`.problem` — the weighted least-squares problem in the fitted variables (residuals,
  bounded minimisation over any subset of the parameters, Jacobian);
* :mod:`.statistics` — covariance and Wald standard errors, Student-t quantiles, profile
  likelihood, runs test, information criteria, identifiability classification, the
  consistency test;
* :mod:`.engine` — :func:`fit` as a sequence of named steps, :func:`fit_static`,
  :func:`fit_steady`, :func:`fit_joint`, :func:`compare_models`.

Nothing here draws: the figure ``fit.png`` is :func:`dryfriction.plots.fits.plot_fit`.

Models (SI units; friction coefficients ``F/W``):

* ``"cv"`` — the Caroli–Velický trap model (:class:`CVModel`): a family of
  :class:`~dryfriction.theory.model.TrapModel` that holds one for its fixed part (``alpha``,
  0.13 by default, the creep law, and whether the direct effect is fitted) and gives the member
  at fitted values, ``cv.trap_model(values)`` (``v_ref``, m/s, made reduced there). Static
  data ``mu_s(t_w) = mu_el static_friction(TrapModel(alpha, eps), t_w/t0)`` (eq. 27) fix
  ``eps``, ``t0`` (s) and ``mu_el``; steady data
  ``mu_d(V) = mu_el steady_friction(TrapModel(alpha, eps), V/V*)`` (eq. 34) fix ``eps``,
  ``V* = a0/t0`` (m/s) and ``mu_el``; together they fix ``eps, t0, a0, mu_el`` (``a0`` in m)
  with one parameter set. Both go through :mod:`dryfriction.theory.units`.
* ``"rsf"`` — rate-and-state friction (:class:`RSFModel`), ``v0`` fixed and reported. Steady
  data give only ``a - b`` and ``mu0`` (``mu_ss = mu0 + (a - b) ln(V/V0)``, Ruina 1983); static
  (healing) data give ``mu0, b, Dc`` through
  :meth:`dryfriction.rsf.RateState.hold_peak_friction` (``mu0 + b ln(1 + t_w V0/Dc)``, ageing
  law, reload at ``V0``; Beeler, Tullis & Weeks 1994; Marone 1998) and nothing about ``a``;
  time series (velocity steps, slide-hold-slide) give ``a, b, Dc, mu0`` through
  :func:`dryfriction.rsf.driving.simulate`.

Time-series models are callables ``(values, data) -> predicted friction``
(:data:`SeriesModel`); the rate-and-state one is ``rsf_series(model, values, data)``, the trap
model's is ``cv_series(model, values, data)`` (the ensemble simulator
:func:`dryfriction.ensemble.driving.simulate` with the data's load program as a kinematic
:class:`~dryfriction.ensemble.driving.VelocityDrive` or through the machine's spring, through
:class:`~dryfriction.theory.units.PhysicalScales`). The ensemble's friction is a sum over
discrete traps, so it is a fine staircase in the parameters (a trap dies at a sample): its
Jacobian is taken with a larger difference step (:attr:`CVModel.diff_step`).

Method (ours, standard weighted least squares):

* residuals ``r_i = (y_i - f_i)/sigma_i`` with the data's uncertainties when every file gives
  them, otherwise ``sigma_i = 1`` and one common noise level estimated from the fit;
* :func:`scipy.optimize.least_squares` (trust-region reflective, bounds), positive scales fitted
  as ``ln p``; starts from linearised least-squares scans of the data (first-order eq. 28a and
  the first-order eq. 34 are linear in ``(mu_el, mu_el eps)`` at fixed ``t0`` or ``V*``; the RSF
  forms are linear in ``(mu0, b)`` at fixed ``Dc``) plus any start given;
* covariance ``C = s^2 (J^T J)^+`` of the fitted (log) parameters from a central-difference
  Jacobian, ``s^2 = 1`` with given uncertainties, ``s^2 = RSS/(n - p)`` without; intervals
  ``theta +- q sqrt(C_ii)`` mapped back (asymmetric for log parameters; ``q`` = 1.96, or
  Student t with ``n - p`` degrees of freedom when the noise level is estimated);
* a profile likelihood for every free parameter: the cost minimised over the others along a
  path in that parameter, the 95 % interval where ``2 (cost - cost_min)/s^2`` reaches 3.84
  (chi-square, one degree of freedom). A side that never reaches it inside the search bounds is
  reported open ("only bounded above by ..."), and no error bar is given for that parameter;
* goodness of fit (chi-square test with given uncertainties; per-data-set RMS residuals and a
  runs test on the residual signs), AIC/BIC for model comparison, and, for joint fits, a test
  that one parameter set explains every data set (the joint fit against separate fits: a
  chi-square difference test with given uncertainties, an F test without).
"""

from __future__ import annotations

from .engine import compare_models, fit, fit_joint, fit_static, fit_steady
from .models import CVModel, ParamSpec, RSFModel, SeriesModel, cv_series, rsf_series
from .problem import Problem
from .results import FitResult, ParameterEstimate
from .statistics import PROFILE_THRESHOLD

__all__ = [
    "ParamSpec",
    "CVModel",
    "RSFModel",
    "SeriesModel",
    "rsf_series",
    "cv_series",
    "ParameterEstimate",
    "FitResult",
    "fit",
    "fit_static",
    "fit_steady",
    "fit_joint",
    "compare_models",
    "PROFILE_THRESHOLD",
]

_Problem = Problem  # the name the solver had before the split (tests patch its ``solve``)
