"""The statistics of a least-squares fit: covariance and Wald standard errors, Student-t
quantiles, profile likelihood, the runs test on residual signs, information criteria,
identifiability classification and the test that one parameter set explains several data sets.

Everything works in the fitted (internal) variables of :class:`~.problem.Problem`; the methods
are described in the package docstring.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import stats

from ..validation import Array
from .models import ParamSpec
from .problem import Problem

__all__ = [
    "PROFILE_THRESHOLD",
    "Z95",
    "Covariance",
    "covariance",
    "hac_covariance",
    "hac_bandwidth",
    "time_hac_covariance",
    "local_covariance",
    "blocked_meats",
    "positive_semidefinite",
    "held_parameter_covariance",
    "with_stderr",
    "lag1_autocorrelation",
    "quantile_95",
    "runs_test",
    "information_criteria",
    "log_slope",
    "format_value",
    "profile_interval",
    "on_search_bound",
    "nearer_bound",
    "classify",
    "consistency_test",
]


PROFILE_THRESHOLD: float = float(stats.chi2.ppf(0.95, 1))
"""Rise of ``chi^2`` (3.84) that bounds a 95 % profile-likelihood interval (one parameter) with
given uncertainties; with the noise level estimated the threshold is ``t_{0.975, n-p}^2``."""

Z95: float = float(stats.norm.ppf(0.975))
"""The normal 97.5 % quantile (1.96): two-sided 95 % intervals with given uncertainties."""


@dataclass(frozen=True)
class Covariance:
    """Covariance ``C = s^2 (J^T J)^+`` of the fitted (internal) variables.

    Attributes
    ----------
    matrix : ndarray
        ``C``, ``p x p``; ``inf`` everywhere when ``J`` is singular.
    stderr : ndarray
        ``sqrt(C_ii)``.
    singular : bool
        ``J`` has a singular value below ``1e-10`` of the largest: some parameter combinations
        are not determined by the data at all.
    """

    matrix: Array
    stderr: Array
    singular: bool

    @property
    def correlation(self) -> Array:
        """``C_ij / (se_i se_j)`` (read-only; ``nan`` where a standard error is 0 or inf)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            corr = np.asarray(self.matrix / np.outer(self.stderr, self.stderr), float)
        corr.setflags(write=False)
        return corr


def covariance(J: Array, s2: float) -> Covariance:
    """The covariance from the Jacobian ``J`` of the weighted residuals (one pseudo-inverse).

    Parameters
    ----------
    J : ndarray
        ``n x p`` Jacobian in the internal variables.
    s2 : float
        Noise variance: 1 with given uncertainties, ``RSS/(n - p)`` otherwise.
    """
    p = J.shape[1]
    if p == 0:
        return Covariance(np.zeros((0, 0)), np.zeros(0), False)
    S, Vt = np.linalg.svd(J, full_matrices=False)[1:]
    keep = S > S[0] * 1e-10 if S.size and S[0] > 0 else np.zeros_like(S, bool)
    inv = np.where(keep, 1.0 / np.where(keep, S, 1.0) ** 2, np.inf)
    singular = not bool(np.all(keep))
    with np.errstate(invalid="ignore"):
        cov = np.full((p, p), np.inf) if singular else (Vt.T * inv) @ Vt * s2
    return Covariance(cov, np.sqrt(np.abs(np.diag(cov))), singular)


def lag1_autocorrelation(x: Array) -> Array:
    """Lag-1 autocorrelation of a series in time order (of each column of an ``n x p`` array),
    about its mean; 0 for a constant column."""
    x = np.asarray(x, float).reshape(len(x), -1)
    x = x - np.mean(x, axis=0)
    den = np.einsum("ij,ij->j", x, x)
    num = np.einsum("ij,ij->j", x[1:], x[:-1])
    return np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)


def hac_bandwidth(x: Array) -> int:
    """Lags of the Bartlett kernel for :func:`hac_covariance`: Andrews' (1991) AR(1) plug-in.

    ``rho`` is the lag-1 autocorrelation of ``x`` (a series in time order, or each column of
    an ``n x p`` array, the largest taken); the bandwidth is ``1.1447 (alpha n)^(1/3)`` with
    ``alpha = 4 rho^2 / ((1 - rho)^2 (1 + rho)^2)`` (Andrews, Econometrica 59, 817 (1991),
    eqs. 5.3 and 6.4), at least 1 and at most ``n/2``.
    """
    n = len(x)
    if n < 4:
        return 1
    rho = float(np.clip(np.max(np.abs(lag1_autocorrelation(x))), 0.0, 0.999))
    alpha = 4.0 * rho**2 / ((1.0 - rho) ** 2 * (1.0 + rho) ** 2)
    return int(min(max(math.ceil(1.1447 * (alpha * n) ** (1.0 / 3.0)), 1), n // 2))


PREWHITEN_CAP = 0.99
"""Largest singular value of the prewhitening VAR(1) matrix (Andrews & Monahan use 0.97; ours:
0.99, because apparatus fluctuations in friction records are correlated over hundreds of
samples, where 0.97 leaves the estimate ~2x low; measured on AR(1) noise with rho = 0.99 in
tests/fit/test_hac.py)."""


def _bartlett(u: Array, lags: int) -> Array:
    """``sum_{|l| <= L} (1 - |l|/(L + 1)) sum_t u_t u_{t-l}^T`` (Newey & West 1987, eq. 2)."""
    omega = u.T @ u
    for lag in range(1, min(lags, len(u) - 1) + 1):
        g = u[lag:].T @ u[:-lag]
        omega += (1.0 - lag / (lags + 1.0)) * (g + g.T)
    return omega


def hac_covariance(J: Array, r: Array, lags: int | None = None) -> tuple[Covariance, int]:
    """Covariance of least-squares estimates with autocorrelated residuals.

    The sandwich ``C = (J^T J)^-1 Omega (J^T J)^-1 n/(n - p)``, ``Omega`` the long-run
    covariance of the scores ``u_t = J_t r_t``, estimated with Andrews & Monahan's (Econometrica
    60, 953 (1992)) VAR(1) prewhitening: ``u_t = A u_{t-1} + e_t`` fitted by least squares
    (``A`` shrunk so that its singular values stay <= :data:`PREWHITEN_CAP`), the Newey–West
    (Bartlett) estimate ``Omega_e`` of the whitened ``e_t`` (bandwidth :func:`hac_bandwidth` of
    ``e``), recoloured: ``Omega = (I - A)^-1 Omega_e (I - A)^-T``. Without prewhitening the
    Bartlett estimate is biased low by ~``1/L`` of the correlation time; with it the bias is
    that of the (much shorter) remaining correlation. With uncorrelated residuals it reduces to
    White's heteroscedasticity-consistent form, close to :func:`covariance` with
    ``s2 = RSS/(n - p)``. Where a measured record carries slow apparatus fluctuations
    (residuals correlated over many samples) the white-noise covariance is too small by about
    ``(1 + rho)/(1 - rho)`` for AR(1) residuals; this one is not.

    Parameters
    ----------
    J : ndarray
        ``n x p`` Jacobian of the residuals, samples in time order.
    r : ndarray
        The ``n`` residuals at the optimum, in the same order.
    lags : int, optional
        Bartlett bandwidth ``L`` for the whitened scores; default :func:`hac_bandwidth`.

    Returns
    -------
    Covariance, int
        The covariance and the bandwidth ``L`` used (0 where ``J`` is singular). Singular
        also where rounding made the sandwich indefinite (:func:`positive_semidefinite`):
        a near-singular ``J`` whose bread amplifies ``Omega``'s round-off beyond the small
        directions' variance.
    """
    n, p = J.shape
    if p == 0:
        return Covariance(np.zeros((0, 0)), np.zeros(0), False), 0
    base = covariance(J, 1.0)
    if base.singular or n <= 2 * p + 2:
        return Covariance(np.full((p, p), np.inf), np.full(p, np.inf), True), 0
    omega, L = _score_meat(J, r, lags)
    bread = base.matrix  # (J^T J)^-1
    cov = bread @ omega @ bread * (n / (n - p))
    cov = 0.5 * (cov + cov.T)
    if not positive_semidefinite(cov):
        # the sandwich is a covariance in exact arithmetic; a negative variance here is
        # rounding: Omega's round-off (1e-16 of its largest eigenvalue) times the bread's
        # largest eigenvalue squared, which a near-singular Jacobian makes larger than the
        # small directions' true variance (userfixA: a noise record's shs window, Omega's
        # eigenvalues 1.6e6 down to -3e-10, the bread's up to 1.1e7: variances of -1.6e4).
        # No number is better than a wrong one: singular, as a singular Jacobian.
        return Covariance(np.full((p, p), np.inf), np.full(p, np.inf), True), 0
    return Covariance(cov, np.sqrt(np.abs(np.diag(cov))), False), L


def _score_meat(J: Array, r: Array, lags: int | None = None) -> tuple[Array, int]:
    """The long-run covariance ``Omega`` of the scores ``u_t = J_t r_t`` of
    :func:`hac_covariance` (VAR(1)-prewhitened Bartlett, recoloured) and its bandwidth."""
    n, p = J.shape
    u = J * r[:, None]
    # VAR(1) of the scores: u_t^T = u_{t-1}^T A^T + e_t^T
    At = np.linalg.lstsq(u[:-1], u[1:], rcond=None)[0]
    U, S, Vt = np.linalg.svd(At)
    At = (U * np.minimum(S, PREWHITEN_CAP)) @ Vt
    e = u[1:] - u[:-1] @ At
    L = hac_bandwidth(e) if lags is None else int(lags)
    omega_e = _bartlett(e, L) * (n / (n - 1.0))
    color = np.linalg.inv(np.eye(p) - At.T)
    return color @ omega_e @ color.T, L


def _lag_products(r: Array, t: Array, delta: float, most: int) -> tuple[Array, Array]:
    """Sums and counts of ``r_i r_j`` (``i < j``, and ``i = j`` at lag 0) binned by the time
    lag ``round((t_j - t_i)/delta)``, lags ``0..most``."""
    s = np.zeros(most + 1)
    c = np.zeros(most + 1)
    s[0], c[0] = float(r @ r), float(r.size)
    for lag in range(1, min(most, r.size - 1) + 1):  # index lag >= time lag / delta
        m = np.rint((t[lag:] - t[:-lag]) / delta).astype(np.int64)
        ok = m <= most
        if not np.any(ok):
            break
        s += np.bincount(m[ok], (r[lag:] * r[:-lag])[ok], most + 1)
        c += np.bincount(m[ok], minlength=most + 1)
    return s, c


def time_hac_covariance(J: Array, r: Array, t: Array) -> tuple[Covariance, float]:
    """Covariance of least-squares estimates with stationary autocorrelated residuals sampled
    at irregular times, the kernel on a time lag rather than a lag count.

    The sandwich for regressors fixed by the model (the Jacobian does not depend on the noise)
    and stationary noise of autocovariance ``gamma(tau)``::

        C = (J^T J)^-1 [sum_ij w(|t_i - t_j|/h) gamma(t_j - t_i) J_i J_j^T] (J^T J)^-1 n/(n-p)

    ``gamma`` estimated from the residuals (about their mean) in bins of the finest sampling
    interval ``delta``, averaged over all pairs at that lag in the window, ``w`` the Bartlett
    weights ``1 - tau/h`` (Newey & West, Econometrica 55, 703 (1987)) with ``h = (L + 1)
    delta``, ``L`` Andrews' (Econometrica 59, 817 (1991), eqs. 5.3 and 6.4) AR(1) plug-in
    ``1.1447 (alpha N)^(1/3)`` in lags of ``delta`` (``N`` the window's duration over
    ``delta``) with ``rho = gamma(2 delta)/gamma(delta)``, the AR(1) coefficient of the
    correlated part of white + AR(1) noise (the white part drops out; ours).

    Why (ours): :func:`hac_covariance` sums products of *scores* ``J_t r_t`` over a lag
    count. A parameter fixed by a short stretch of the window (the machine stiffness ``k``,
    by ~0.2 s right after a velocity change) gets its scores from a few dozen samples there,
    which hold one or two correlation times of red noise: their products estimate the long-run
    variance with about one degree of freedom, and the bandwidth chosen over the whole window
    (a lag count, while the sampling rate can change tenfold at the change) is too short for
    them. Here ``gamma`` is estimated from every pair of the window and only the Jacobian's
    weights are local. Measured on 20 basalt-like records of ``tests/machine_zoo.py`` (red
    friction noise, 10 Hz then 100 Hz; ``benchmarks/bench_k_coverage``): the 95 % interval of
    ``k`` held the true value in 6 of 20 with :func:`hac_covariance` and 18 of 20 with this
    one (standard errors 2.5x wider, median).

    Parameters
    ----------
    J : ndarray
        ``n x p`` Jacobian of the residuals, samples in time order.
    r : ndarray
        The ``n`` residuals at the optimum.
    t : ndarray
        The ``n`` sample times (s), increasing.

    Returns
    -------
    Covariance, float
        The covariance and the Bartlett bandwidth ``h`` (s); ``inf`` everywhere and 0 where
        ``J`` is singular or there are too few samples.
    """
    n, p = J.shape
    t = np.asarray(t, float)
    base = covariance(J, 1.0)
    if p == 0 or base.singular or n <= 2 * p + 2 or not np.any(np.diff(t) > 0):
        return Covariance(np.full((p, p), np.inf), np.full(p, np.inf), True), 0.0
    omega, h = _time_meat(J, r, t)
    cov = base.matrix @ omega @ base.matrix * (n / (n - p))
    cov = 0.5 * (cov + cov.T)
    return Covariance(cov, np.sqrt(np.abs(np.diag(cov))), False), h


def _time_meat(J: Array, r: Array, t: Array) -> tuple[Array, float]:
    """The middle of :func:`time_hac_covariance`'s sandwich, ``sum_ij w gamma J_i J_j^T``,
    and its bandwidth ``h`` (s); ``t`` increasing with at least one positive step."""
    n = len(r)
    dt = np.diff(t)
    delta = float(np.min(dt[dt > 0]))
    e = np.asarray(r, float) - float(np.mean(r))
    s, c = _lag_products(e, t, delta, 2)
    g = np.where(c > 0, s / np.maximum(c, 1.0), 0.0)
    rho = float(np.clip(g[2] / g[1], 0.0, 0.999)) if g[1] > 0 else 0.0
    alpha = 4.0 * rho**2 / ((1.0 - rho) ** 2 * (1.0 + rho) ** 2)
    big_n = (t[-1] - t[0]) / delta
    lags = int(min(max(math.ceil(1.1447 * (alpha * big_n) ** (1.0 / 3.0)), 1),
                   max(big_n // 2, 1)))
    s, c = _lag_products(e, t, delta, lags)
    gw = np.where(c > 0, s / np.maximum(c, 1.0), 0.0) * (1.0 - np.arange(lags + 1) / (lags + 1.0))
    omega = gw[0] * (J.T @ J)
    for lag in range(1, min(lags, n - 1) + 1):
        m = np.rint((t[lag:] - t[:-lag]) / delta).astype(np.int64)
        w = np.where(m <= lags, gw[np.minimum(m, lags)], 0.0)
        if not np.any(w):
            continue
        half = (J[:-lag] * w[:, None]).T @ J[lag:]
        omega += half + half.T
    return omega, (lags + 1) * delta


def positive_semidefinite(mat: Array, tol: float = 1e-10) -> bool:
    """Whether the symmetric ``mat`` is a covariance at all: finite, no eigenvalue below
    ``-tol`` times the largest in magnitude (round-off allowed).

    Why (ours): the time-lag sandwich (:func:`time_hac_covariance`) averages each lag's
    products over the pairs at that lag, which, unlike the Bartlett estimate of
    :func:`hac_covariance`, need not give a positive semidefinite matrix. On a record of pure
    noise with a hold (a new user's trial) it gave negative variances for ``ln a``, ``ln b``,
    ``ln Dc``, ``ln k`` and the trend; the standard errors ``sqrt|C_ii|`` hid the sign, and the
    step's stiffness was printed as ``150.1 [150.1, 150.1]`` (a variance clipped to 0).
    """
    mat = np.asarray(mat, float)
    if mat.size == 0:
        return True
    if not np.all(np.isfinite(mat)):
        return False
    eig = np.linalg.eigvalsh(0.5 * (mat + mat.T))
    return bool(eig[0] >= -tol * max(float(np.max(np.abs(eig))), 1e-300))


def local_covariance(J: Array, r: Array, t: Array, blocks: Sequence[slice] | None = None
                     ) -> tuple[Covariance, int]:
    """The covariance of a rate-and-state step fit (ours): the time-lag sandwich
    :func:`time_hac_covariance`, each standard error floored at the score HAC's
    (:func:`hac_covariance`; the time-lag one's correlations kept, ``D C D`` with ``D``
    diagonal: positive semidefinite). The score HAC where the time-lag one is singular.

    Why: in a step window ``a``, ``b``, ``Dc`` and ``k`` are fixed by the transient, a second
    or two after the change, as :func:`time_hac_covariance` explains for ``k``: their scores
    ``J_t r_t`` are non-zero over a few correlation times of red friction noise only, and
    their own products estimate the long-run variance with a few degrees of freedom, biased
    low. On 40 basalt-like records of ``tests/machine_zoo.py`` (white plus red noise, 10 then
    100 Hz; ``benchmarks/bench_k_coverage``) the score HAC's standard errors of ``ln a``,
    ``ln b``, ``ln Dc`` were 3.0, 3.5 and 1.9 times too small (spread of the errors over them)
    and its 95 % intervals held the truth in 21, 15, 28 of 40; not a bandwidth matter (at the
    time-lag one's bandwidth: 14, 12, 25 of 40); this one: 1.04, 1.04, 0.94 and 37, 38, 39 of
    40. The floor keeps the score HAC's where the residuals are not stationary (a misfit).
    Where the time-lag sandwich is not a covariance (:func:`positive_semidefinite`: a
    negative variance), the score HAC's, which is.

    Parameters
    ----------
    J : ndarray
        ``n x p`` Jacobian of the residuals, samples in time order.
    r : ndarray
        The ``n`` residuals at the optimum.
    t : ndarray
        The ``n`` sample times (s), increasing (within each block).
    blocks : sequence of slice, optional
        Rows of independent windows (:func:`blocked_meats`): each sandwich's middle is the
        sum of the windows' own; ``None``: one window.

    Returns
    -------
    Covariance, int
        The covariance and the score HAC's Bartlett bandwidth (lags; the largest window's).
    """
    if blocks is None:
        score, lags = hac_covariance(J, r)
        local = time_hac_covariance(J, r, t)[0]
    else:
        score, lags, local = blocked_meats(J, r, t, blocks)
    if score.singular or local.singular or not positive_semidefinite(local.matrix):
        return score, lags
    scale = np.ones(len(local.stderr))
    ok = local.stderr > 0
    scale[ok] = np.maximum(local.stderr[ok], score.stderr[ok]) / local.stderr[ok]
    mat = local.matrix * np.outer(scale, scale)
    return Covariance(mat, np.sqrt(np.abs(np.diag(mat))), False), lags


def blocked_meats(J: Array, r: Array, t: Array, blocks: Sequence[slice]
                  ) -> tuple[Covariance, int, Covariance]:
    """The score HAC (:func:`hac_covariance`) and the time-lag sandwich
    (:func:`time_hac_covariance`) of a fit to several independent windows, each window its
    own block::

        C = (J^T J)^-1 [sum_w Omega_w] (J^T J)^-1 n/(n - p)

    ``Omega_w`` the long-run covariance of window ``w``'s scores alone (its own residual mean,
    correlation and bandwidth; the columns that are zero in the window left out). The
    cluster sandwich (Liang & Zeger, Biometrika 73, 13 (1986); Arellano, Oxford Bull. Econ.
    Stat. 49, 431 (1987)) with each cluster's middle the HAC one (ours: its use here).

    Why (ours): the windows of a record's steps (a joint fit, :func:`.steps.fit_steps`) are
    apart in time and each has its own level, noise and correlation; one HAC over their rows
    placed end to end would sum products across the seams between windows (their ends are
    not neighbours) and estimate one correlation for all.

    Parameters
    ----------
    J : ndarray
        ``n x p`` Jacobian of the residuals, the windows' rows in ``blocks``.
    r : ndarray
        The ``n`` residuals at the optimum.
    t : ndarray
        The ``n`` sample times (s), increasing within each block.
    blocks : sequence of slice
        The rows of each window; together every row once.

    Returns
    -------
    Covariance, int, Covariance
        The score HAC, its largest bandwidth (lags), and the time-lag sandwich; both singular
        (``inf``) where ``J`` is or a window has too few samples for its columns.
    """
    n, p = J.shape
    bad = Covariance(np.full((p, p), np.inf), np.full(p, np.inf), True)
    base = covariance(J, 1.0)
    if p == 0 or base.singular or n <= 2 * p + 2:
        return bad, 0, bad
    t = np.asarray(t, float)
    score_m, time_m, most = np.zeros((p, p)), np.zeros((p, p)), 0
    for b in blocks:
        cols = np.flatnonzero(np.any(J[b] != 0.0, axis=0))
        Jb, rb, tb = J[b][:, cols], np.asarray(r[b], float), t[b]
        if len(rb) <= 2 * cols.size + 2 or not np.any(np.diff(tb) > 0):
            return bad, 0, bad
        om, lags = _score_meat(Jb, rb)
        score_m[np.ix_(cols, cols)] += om
        most = max(most, lags)
        time_m[np.ix_(cols, cols)] += _time_meat(Jb, rb, tb)[0]
    out = []
    for omega in (score_m, time_m):
        cov = base.matrix @ omega @ base.matrix * (n / (n - p))
        cov = 0.5 * (cov + cov.T)
        out.append(Covariance(cov, np.sqrt(np.abs(np.diag(cov))), False)
                   if positive_semidefinite(cov) else bad)
    return out[0], most, out[1]


def held_parameter_covariance(J: Array, cov: Array, j: int, var: float, share: float
                              ) -> Array:
    """What holding parameter ``j`` at an estimate of its own adds to the covariance of the
    others: the correction of a two-step estimator (Murphy & Topel, J. Bus. Econ. Stat. 3,
    370 (1985)), in the form it takes for least squares (ours)::

        Delta = var G G^T + share (x G^T + G x^T),   G = -(J_o^T J_o)^-1 J_o^T J_j,
        x = C_oj - G C_jj

    ``G`` is how the others move with the held value (``d theta_o / d theta_j`` of the
    constrained fit; ``J_o`` the Jacobian's other columns), ``var`` the variance of the held
    value (its first stage), ``C`` the covariance of the fit with ``j`` free on the same
    data, and ``x`` the covariance of the others' error at the true ``theta_j`` with this
    fit's own free estimate of ``theta_j`` (ours, from ``C = B J^T Sigma J B``, ``B =
    (J^T J)^-1``: ``x = (J_o^T J_o)^-1 J_o^T Sigma J B e_j = C_oj - G C_jj``; 0 for white
    noise). ``share`` is the weight of this fit's own estimate in the held value (its
    inverse-variance share; 0 when the held value comes from other data): the cross term of
    Murphy & Topel's ``R``. In the fitted (internal) variables.

    Parameters
    ----------
    J : ndarray
        ``n x p`` Jacobian of the residuals with ``j`` free, at the constrained optimum.
    cov : ndarray
        ``p x p`` covariance of that fit (the same noise model as the constrained one's).
    j : int
        The held parameter's column.
    var : float
        Variance of the held value, in its internal variable (``ln k``).
    share : float
        This fit's weight in the held value, in ``[0, 1]``.

    Returns
    -------
    ndarray
        ``(p - 1) x (p - 1)``, for the other parameters in their order.
    """
    o = [i for i in range(J.shape[1]) if i != j]
    G = -np.linalg.pinv(J[:, o]) @ J[:, j]
    x = cov[o, j] - G * cov[j, j]
    delta = var * np.outer(G, G) + share * (np.outer(x, G) + np.outer(G, x))
    return 0.5 * (delta + delta.T)


def with_stderr(cov: Covariance, j: int, se: float) -> Covariance:
    """``cov`` with parameter ``j``'s standard error set to ``se``, its correlations kept
    (row and column ``j`` scaled by ``se/se_j``: ``D C D`` stays positive semidefinite);
    ``cov`` unchanged where either is not finite and positive."""
    old = float(cov.stderr[j])
    if cov.singular or not (math.isfinite(se) and se > 0 and math.isfinite(old) and old > 0):
        return cov
    scale = np.ones(len(cov.stderr))
    scale[j] = se / old
    mat = cov.matrix * np.outer(scale, scale)
    return Covariance(mat, np.sqrt(np.abs(np.diag(mat))), False)


def quantile_95(sigma_given: bool, dof: int) -> float:
    """Two-sided 95 % quantile: normal with given uncertainties, Student t with ``dof``
    degrees of freedom when the noise level is estimated from the residuals."""
    return Z95 if sigma_given or dof <= 0 else float(stats.t.ppf(0.975, dof))


def runs_test(r: Array) -> float | None:
    """Two-sided p-value of the Wald–Wolfowitz runs test on the signs of ``r`` (in order)."""
    s = np.sign(r[r != 0])
    n1, n2 = int(np.sum(s > 0)), int(np.sum(s < 0))
    if n1 == 0 or n2 == 0 or n1 + n2 < 6:
        return None
    runs = 1 + int(np.sum(s[1:] != s[:-1]))
    n = n1 + n2
    mean = 2.0 * n1 * n2 / n + 1.0
    var = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n - 1.0))
    if var <= 0:
        return None
    return float(2.0 * stats.norm.sf(abs(runs - mean) / math.sqrt(var)))


def log_slope(x: Array, y: Array, sigma: Array | None = None) -> dict[str, Any]:
    """The measured trend of ``y`` against ``ln x``: the weighted least-squares line
    ``y = c + s ln x`` over ``x > 0`` (ours; model-free, so that a fit can say when the data's
    own trend has the wrong sign for the model).

    Parameters
    ----------
    x, y : ndarray
        Abscissa (any unit: the slope per e-fold does not depend on it) and ordinate.
    sigma : ndarray, optional
        Uncertainties of ``y``: weights ``1/sigma^2`` and a normal 95 % quantile; without
        them the noise is estimated from the line's residuals (Student t, ``n - 2``).

    Returns
    -------
    dict
        ``slope`` (``dy/d ln x``; ``ln 10`` times it per decade of ``x``), ``stderr`` and
        ``interval_95`` (``None`` with two points and no uncertainties: no noise estimate),
        ``n``; ``slope`` ``None`` where fewer than two distinct ``x > 0``.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    keep = (x > 0) & np.isfinite(y)
    lx, yy = np.log(x[keep]), y[keep]
    w = np.ones(lx.size) if sigma is None else 1.0 / np.asarray(sigma, float)[keep] ** 2
    n = int(lx.size)
    out: dict[str, Any] = {"slope": None, "stderr": None, "interval_95": None, "n": n}
    if n < 2 or np.ptp(lx) == 0:
        return out
    xm = float(np.sum(w * lx) / np.sum(w))
    sxx = float(np.sum(w * (lx - xm) ** 2))
    slope = float(np.sum(w * (lx - xm) * yy) / sxx)
    out["slope"] = slope
    resid = yy - (float(np.sum(w * yy) / np.sum(w)) + slope * (lx - xm))
    if sigma is None and n <= 2:
        return out  # no noise estimate from two points
    se = math.sqrt((1.0 if sigma is not None else float(np.sum(w * resid**2)) / (n - 2)) / sxx)
    q = quantile_95(sigma is not None, n - 2)
    out["stderr"] = se
    out["interval_95"] = (slope - q * se, slope + q * se)
    return out


def information_criteria(cost: float, n: int, p: int, sigma_given: bool) -> dict[str, float]:
    """AIC, AICc and BIC from the Gaussian likelihood (constants dropped consistently)."""
    if sigma_given:
        m2ll, k = 2.0 * cost, p
    else:  # noise level estimated: -2 ln L = n ln(RSS/n) + const, one more parameter
        m2ll, k = n * math.log(max(2.0 * cost, 1e-300) / n), p + 1
    aicc = m2ll + 2 * k + (2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else math.inf)
    return {"n": n, "k": k, "minus_2_log_likelihood": m2ll, "aic": m2ll + 2 * k,
            "aicc": aicc, "bic": m2ll + k * math.log(n)}


def format_value(x: float, unit: str) -> str:
    """``x`` to three digits, with its unit if it has one (for the notes)."""
    return f"{x:.3g}" + (f" {unit}" if unit else "")


def on_search_bound(spec: ParamSpec, th: float) -> bool:
    """Whether the internal value ``th`` sits on ``spec``'s search bound (within ``1e-6``
    relative, as the optimiser leaves it there)."""
    lo_b, hi_b = spec.bounds
    return bool(min(th - lo_b, hi_b - th) < 1e-6 * max(1.0, abs(th)))


def nearer_bound(spec: ParamSpec, th: float) -> int:
    """Which of ``spec``'s search bounds the internal value ``th`` is nearer: 0 the lower,
    1 the upper (the side :func:`on_search_bound` means)."""
    lo_b, hi_b = spec.bounds
    return 0 if th - lo_b < hi_b - th else 1


def _on_reach(spec: ParamSpec, th: float) -> bool:
    """On a search bound that is only the search's reach, not a physical limit
    (:attr:`.models.ParamSpec.physical`)."""
    return on_search_bound(spec, th) and not spec.physical[nearer_bound(spec, th)]


def profile_interval(prob: Problem, theta: Array, cost: float, s2: float, j: int, se: float,
                     thr: float = PROFILE_THRESHOLD,
                     pinned: list[tuple[int, ...]] | None = None) -> tuple[
                         float | None, float | None, float, float, tuple[Array, float] | None]:
    """95 % profile interval of parameter ``j`` (internal variable); ``None`` for open sides.

    Walks away from the optimum in each direction with steps starting near the Jacobian
    standard error and doubling while the profile stays flat, re-minimising over the other
    parameters from the previous point, until ``2 (cost - cost_min)/s^2`` exceeds the
    threshold (then bisects the crossing) or the search bound is reached.

    ``pinned``, if given, gets one tuple per side (lower, then upper): the other parameters
    that sit on their search bounds (:func:`on_search_bound`; not a bound that stands for a
    physical limit, :attr:`.models.ParamSpec.physical`) where the profile crosses the
    threshold (empty where none, or where it does not cross). Such a limit is set by that
    bound, not by the data: with the other parameter free beyond it the profile would rise
    more slowly (userfixA: ``t0`` on its 1e-12 s bound made ``eps`` and ``mu_el`` look
    identified).
    """
    spec = prob.specs[j]
    lo_b, hi_b = spec.bounds
    free = np.ones(prob.p, bool)
    free[j] = False
    better: tuple[Array, float] | None = None
    ends: list[float | None] = []
    reached: list[float] = []
    max_step = 2.3 if spec.log else 50.0 * (se if math.isfinite(se) and se > 0 else 1.0)
    for direction in (-1.0, 1.0):
        bound = lo_b if direction < 0 else hi_b
        step = se if math.isfinite(se) and se > 0 else 0.1
        step = min(max(step, 1e-3 if spec.log else 1e-9), max_step)
        prev_t, prev_d = theta.copy(), 0.0
        crossing: float | None = None
        pins: tuple[int, ...] = ()
        for _ in range(60):
            x = prev_t[j] + direction * step
            at_bound = (x - bound) * direction >= 0
            t_try = prev_t.copy()
            t_try[j] = bound if at_bound else x
            t_new, c_new, _ = prob.solve(t_try, free)
            d = 2.0 * (c_new - cost) / s2
            if d < -0.05 and (better is None or c_new < better[1]):
                better = (t_new, c_new)
            if d >= thr:
                a_t, b_t = prev_t, t_new  # bisect the crossing
                a_d = prev_d
                for _ in range(6):
                    m = a_t.copy()
                    m[j] = 0.5 * (a_t[j] + b_t[j])
                    m, c_m, _ = prob.solve(m, free)
                    d_m = 2.0 * (c_m - cost) / s2
                    if d_m >= thr:
                        b_t = m
                    else:
                        a_t, a_d = m, d_m
                crossing = 0.5 * (a_t[j] + b_t[j])
                del a_d
                if pinned is not None:
                    pins = tuple(k for k in range(prob.p) if k != j and (
                        _on_reach(prob.specs[k], float(a_t[k]))
                        or _on_reach(prob.specs[k], float(b_t[k]))))
                break
            if at_bound:
                break
            if d < thr / 8:
                step = min(2.0 * step, max_step)
            prev_t, prev_d = t_new, d
        if pinned is not None:
            pinned.append(pins if crossing is not None else ())
        ends.append(crossing)
        reached.append(float(t_try[j]))
    return ends[0], ends[1], reached[0], reached[1], better


_FAR = math.log(1e3)
"""A profile limit more than this far (in ln p) outside the data window counts as open."""


def classify(s: ParamSpec, th: float, se: float, lo_c: float | None, hi_c: float | None,
              r_lo: float, r_hi: float, window: tuple[float, float] | None = None,
              z: float = Z95) -> tuple[str, str]:
    """Identifiability label and sentence from a parameter's profile (internal variables).

    ``window`` is the range of the parameter the data probe directly (for ``t0`` the waiting
    times, for ``V*`` the velocities, for ``Dc`` the slips ``V0 t_w``). A profile limit more
    than three decades outside it rests only on the model's higher-order curvature (e.g.
    ``t0`` far below the shortest waiting time, where eq. 27 is log-linear in ``t_w``): that
    side is reported as practically open, with the far limit quoted (ours). A parameter
    fitted in ``ln p`` whose two-sided interval spans more than three decades is not
    identified either (ours: an order of magnitude at best).
    """
    u = f" {s.unit}" if s.unit else ""
    f = s.from_internal
    far_lo = lo_c is not None and window is not None and math.log(window[0]) - lo_c > _FAR
    far_hi = hi_c is not None and window is not None and hi_c - math.log(window[1]) > _FAR
    open_lo, open_hi = lo_c is None or far_lo, hi_c is None or far_hi
    if not open_lo and not open_hi:
        assert lo_c is not None and hi_c is not None
        if s.log and hi_c - lo_c > _FAR:
            # bounded, but over more than three decades: an order of magnitude at best, not
            # a measurement (userfixA: a +- of 50 times the value was printed "identified")
            return ("not identified",
                    f"{s.name}: its 95 % profile interval [{format_value(f(lo_c), s.unit)}, "
                    f"{format_value(f(hi_c), s.unit)}] spans {(hi_c - lo_c) / math.log(10):.2g}"
                    " decades (more than three): the data do not fix it")
        if math.isfinite(se) and se > 0:
            off = max(abs(th - z * se - lo_c), abs(th + z * se - hi_c))
            if off > 0.2 * z * se:
                return ("identified (nonlinear: use profile_95)",
                        f"{s.name}: the 95 % profile interval [{format_value(f(lo_c), s.unit)}, "
                        f"{format_value(f(hi_c), s.unit)}] differs from the Jacobian one: use it")
        return "identified", ""

    def far_side(c: float | None, reached: float) -> str:
        if c is None:
            return f"searched to {f(reached):.3g}{u} without reaching the 95 % limit"
        return (f"the 95 % profile limit {f(c):.3g}{u} is more than three decades outside "
                "the range the data probe and "
                "rests only on the model's higher-order curvature")

    if open_lo and not open_hi:
        assert hi_c is not None
        return ("bounded above only",
                f"{s.name} is only bounded above by {format_value(f(hi_c), s.unit)} (95 % profile "
                f"likelihood); the data do not bound it from below ({far_side(lo_c, r_lo)})")
    if open_hi and not open_lo:
        assert lo_c is not None
        return ("bounded below only",
                f"{s.name} is only bounded below by {format_value(f(lo_c), s.unit)} (95 % profile "
                f"likelihood); the data do not bound it from above ({far_side(hi_c, r_hi)})")
    return ("not identified",
            f"{s.name} is not determined by the data: below, {far_side(lo_c, r_lo)}; above, "
            f"{far_side(hi_c, r_hi)}")


def consistency_test(cost: float, p: int, n: int, sep_cost: float, sep_p: int,
                     sigma_given: bool) -> dict[str, Any]:
    """Joint fit against separate fits of each data set (a Chow-type test, ours).

    Parameters
    ----------
    cost, p : float, int
        Cost (``RSS/2`` in weighted residuals) and free parameters of the joint fit.
    n : int
        Number of points.
    sep_cost, sep_p : float, int
        Summed costs and free parameters of the separate fits.
    sigma_given : bool
        Chi-square difference test with given uncertainties, F test without.
    """
    df1 = sep_p - p
    if df1 <= 0:
        return {"test": "not run", "reason": "the joint fit has as many parameters as the "
                                             "separate fits"}
    delta = 2.0 * (cost - sep_cost)
    if sigma_given:
        pv = float(stats.chi2.sf(max(delta, 0.0), df1))
        return {"test": "chi-square difference", "delta_chi2": delta, "df": df1, "p_value": pv,
                "separate_chi2": 2.0 * sep_cost}
    df2 = n - sep_p
    if df2 <= 0:
        return {"test": "not run", "reason": "too few points for the F test"}
    F = (max(delta, 0.0) / df1) / (2.0 * sep_cost / df2)
    return {"test": "F", "F": F, "df": [df1, df2], "p_value": float(stats.f.sf(F, df1, df2)),
            "separate_rss": 2.0 * sep_cost, "joint_rss": 2.0 * cost}
