"""Where exactly a velocity change happens, under a red-noise load point (ours).

A change found by :mod:`.detection` is placed by the maximum-likelihood hinge of the
displacement near it, with the apparatus' fluctuations as a Gaussian process rather than as
white noise: the load point's velocity wanders as ``v(t) (1 + eps(t)) + eta(t)``, ``eps`` and
``eta`` Ornstein-Uhlenbeck processes (a relative wander of rms ``s`` and an absolute one of rms
``s_a``, one correlation time ``tau``), and the transducer adds white noise ``sigma``. The
displacement's covariance is then known in closed form (below), and the change time is the
hinge ``x = c + v1 (t - t_c) + (v2 - v1) (t - t0)+`` of least generalised residual; the
wander's parameters are those of the record's own fluctuation model
(:class:`.detection.Fluctuations`), fitted by :func:`ou_parameters`. A machine oscillation
(a periodic velocity wander, ``v(t) A sin(2 pi t / P + phi)``: the zoo's 22 and 45 s) is no OU
process: its periods are found in the record (:func:`oscillation_periods`) and, for a small
step (:data:`OSC_RATIO`), each enters the hinge as two free regressors, ``int sin(2 pi t /
P)`` and ``int cos(2 pi t / P)`` (amplitude and phase free, one amplitude for both sides;
ours). At a stop, the servo's position error relaxes after the command (:data:`RELAX_STOP`):
``(1 - exp(-(t - t_c) / tau))+`` enters as a free regressor beside the hinge. Each change's
95 % interval is its profile likelihood's (:func:`profile_interval`), widened
(:data:`WIDEN`), and the same widened profile gives the probability that it lies within a
tolerance of the time reported (:func:`placed_probability`, :data:`.labsteps.PLACED_P`).

Integrated Ornstein-Uhlenbeck covariance (standard; e.g. Gardiner, *Stochastic Methods*,
section 3.8): with ``C(u) = s**2 exp(-|u| / tau)``,
``cov(int_p^q eps, int_r^w eps) = s**2 (g(q - r) - g(p - r) - g(q - w) + g(p - w))``,
``g(y) = tau |y| + tau**2 (exp(-|y| / tau) - 1)`` (``g'' = exp(-|y|/tau)``, ``g(0) = 0``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from scipy.linalg import cho_factor, solve_triangular

from ..validation import Array
from .artifacts import gap_intervals
from .labsteps import PLACED_P
from .segmentation import median

__all__ = ["LEVEL", "Placement", "change_profile", "oscillation_periods",
           "ou_parameters", "place_change", "place_changes", "placed_at", "placed_probability",
           "profile_interval", "profile_weights"]


def _g(y: Array, tau: float) -> Array:
    """``g(y) = tau |y| + tau**2 (exp(-|y|/tau) - 1)``, the double antiderivative of the OU
    correlation (module docstring). The same operations as ``tau * a + tau * tau *
    np.expm1(-a / tau)`` (``a = |y|``), in two arrays, not six: the covariance of a window's
    256 blocks is 65 536 numbers, and a temporary each costs its allocation."""
    a = np.abs(y)
    if not isinstance(a, np.ndarray) or a.ndim == 0:
        return tau * a + tau * tau * np.expm1(-a / tau)
    b = np.divide(a, tau)
    np.negative(b, out=b)  # -(a / tau) is (-a) / tau exactly
    np.expm1(b, out=b)
    b *= tau * tau
    a *= tau
    a += b
    return a


def _cov_int(p: Array, q: Array, r: Array, w: Array, tau: float) -> Array:
    """``cov(int_p^q eps, int_r^w eps) / s**2`` for unit-rms OU ``eps`` (module docstring):
    ``g(q - r) - g(p - r) - g(q - w) + g(p - w)``, evaluated in that order, the largest term
    (``q - w``, both ends arrays) taking the others in place."""
    big = _g(q - w, tau)
    first = _g(q - r, tau) - _g(p - r, tau)
    last = _g(p - w, tau)
    if not (isinstance(big, np.ndarray) and big.shape == np.broadcast_shapes(
            np.shape(first), big.shape, np.shape(last))):
        return first - big + last
    np.subtract(first, big, out=big)
    big += last
    return big


@lru_cache(maxsize=1)
def _psi_table() -> tuple[Array, Array]:
    """``psi(T / tau)``: what :func:`.detection.measure_fluctuations` measures (the variance of
    a window's least-squares slope less its covariance with the next window's) for a unit-rms
    OU velocity wander, on a log grid of ``T / tau``, as its non-increasing envelope. The
    slope of a line fitted over ``[0, T]`` to ``int eps`` is ``int w eps`` with
    ``w(u) = 6 u (T - u) / T**3`` (ours)."""
    q = np.logspace(-2.0, 3.0, 61)
    u = (np.arange(200) + 0.5) / 200.0  # window in units of T
    w = 6.0 * u * (1.0 - u) / 200.0
    out = np.empty_like(q)
    for j, qq in enumerate(q):
        d = np.abs(u[:, None] - u[None, :])
        var = w @ np.exp(-d * qq) @ w
        cov = w @ np.exp(-(u[None, :] + 1.0 - u[:, None]) * qq) @ w
        out[j] = var - cov
    # the fluctuation model is made non-increasing in T (a short window's value is at least a
    # longer one's): so is what it is compared with
    return q, np.maximum.accumulate(out[::-1])[::-1]


def ou_parameters(scales: Array, level: Array) -> tuple[float, float]:
    """``(s, tau)`` of the OU wander whose slope scatter best matches ``level(T)`` (in log,
    over the scales where it is positive); ``(0, 1)`` where none is.

    Parameters
    ----------
    scales : Array
        Window durations ``T``, s.
    level : Array
        Measured scatter ``r(T)`` (relative, 1) or ``a(T)`` (absolute, m/s).
    """
    T, r = np.asarray(scales, float), np.asarray(level, float)
    ok = r > 0
    if ok.sum() < 2:
        return (float(r[ok][0]) if ok.any() else 0.0), 1.0
    T, y = T[ok], 2.0 * np.log(r[ok])
    q, psi = _psi_table()
    taus = np.logspace(-1.0, 2.5, 36)
    # every tau of the grid at once (one interpolation), the first best as in a loop
    lp = np.log(np.interp((T[None, :] / taus[:, None]).ravel(), q, psi)).reshape(taus.size, -1)
    ls2 = np.mean(y[None, :] - lp, axis=1)
    err = np.sum((y[None, :] - lp - ls2[:, None]) ** 2, axis=1)
    j = int(np.argmin(err))
    return float(np.exp(0.5 * ls2[j])), float(taus[j])


OSC_K = 20.0
"""A periodogram peak is an oscillation when it exceeds this many times the median power
within a factor 2 of its frequency (ours: for an exponential ordinate, a chance of 1e-6 per
frequency; a false period costs the placement only two free regressors)."""


OSC_RATIO = 1.6
"""The oscillation's regressors (one amplitude for both sides) are used for a change of at most
this velocity ratio (ours: the amplitude, a fraction of the velocity, differs by the ratio
between the sides; zoo record 290, in the test subset, not a tuning record: a ratio-9 short
step placed 2.3 s off with them, within 0.4 s without)."""


OSC_FOLLOW = True
"""A change beyond :data:`OSC_RATIO` is placed with the oscillation's amplitude following the
velocity through it (ours): the wander is relative, ``v(t) A sin(2 pi t / P + phi)``, so its
displacement is ``A int v(s) sin(2 pi s / P + phi) ds``, which for the hinge at ``t_c`` is
``v1 I(t) + (v2 - v1) (I(t) - I(t_c))+`` with ``I`` the integral of the sine from the window's
start: one amplitude and phase (two columns per period) for both sides, switched with the
candidate, not at the guess (a column switched at the guess has a kink of its own there, which
takes the hinge's place: :func:`_osc_columns`). At a hold the held side carries no
oscillation, as the model says. A period enters only where the window (not widened for it)
holds it whole on each side of the change: over less than a period a side's sine is a ramp
of velocity, told from the hinge's slope change by the few samples' noise alone. Measured on
the tuning records without it: 0-299 96.0 % right against 96.3 %, 300-449 92.7 against
93.3 %, 3000-3299 91.7 against 92.7 %, the new misses at holds (zoo 166, 388, 442, 3028,
3040, 3196, 3232: at a hold one side carries no oscillation, and the other may hold less
than a period). The window is not widened for the periods as for a small step: a first try
that widened it to two periods broke short steps of ratio 10 (4 of the 5 it broke on zoo
records 150-449)."""


OSC_WIDE = True
"""A step of ratio beyond :data:`OSC_RATIO` up to :data:`OSC_WIDE_RATIO` (a step of ratio 2) is
placed on a window of two oscillation periods each side, as a step of ratio up to
:data:`OSC_RATIO` is, where the samples between its neighbours hold two periods on each side
(:func:`osc_wide`; ours). Why: beyond :data:`OSC_RATIO` a period enters the hinge (following
the velocity, :data:`OSC_FOLLOW`) only where the window holds it whole on each side of the
change, and the window of such a step (20-60 s each side by the wander's correlation time)
seldom holds the longer period (the zoo's 45 s) whole: that period's displacement,
``A v P / (2 pi)`` (0.29 s times the speed at 4 % and 45 s), is left to the OU wander, against
a kink of ``|v2 - v1|`` times the time from it (1 s times the speed over the first second at
ratio 2). Not where a side is shorter than two periods: a short step's other side cannot tell
the oscillation from its own slope, and widening the long side alone broke short steps (zoo
194, 5018, 7238, 11234 with a bound at ratio 3.5 and no such guard; 4 of the 5 changes a first
try broke on zoo records 150-449, ``OSC_FOLLOW``'s note). Measured (``detect10``): replayed on
the zoo's up/down steps of the used ranges 0-449 and 3000-11299, ratio 2 15 of 170 off the
tolerance before, 5 after (10 fixed, none broken; the posterior oracle, which knows the
oscillation, expects 3.2), ratio 1.3 unchanged (widened already); ``python -m benchmarks
bench_detect A:B --no-stress``: docs/performance.md (detect10). Tried there: one amplitude for
both sides without the wider window (the small steps' model), 4 fixed and 4 broken; every
moving step short of a stop, with the guard (zoo ratio-3 and multi steps 397, 5196, 6231,
11173 fixed, 9182 and 10233 broken)."""
OSC_WIDE_RATIO = 2.5
"""The largest velocity ratio placed on the window of :data:`OSC_WIDE` (ours): a measured ratio
scatters about the commanded one by a few per cent (the zoo's ratio-2 steps measure 1.95-2.06,
97 of 170 above 2, so not :data:`FINE_RATIO`); beyond it, up to a stop, the wider window fixed
four zoo records and broke two (:data:`OSC_WIDE`)."""


def osc_wide(v1: float, v2: float, room: float, period: float) -> bool:
    """Whether a change from ``v1`` to ``v2`` (m/s) is placed on a window of two oscillation
    periods each side (:data:`OSC_WIDE`): a change between two speeds at most :data:`OSC_RATIO`
    apart; or, with :data:`OSC_WIDE`, at most :data:`OSC_WIDE_RATIO` apart (both moving) whose
    samples reach ``room`` (s, the nearer of the two sides) at least twice the longest
    ``period`` (s)."""
    lo, hi = sorted((abs(v1), abs(v2)))
    if hi <= OSC_RATIO * lo:
        return True
    return OSC_WIDE and hi <= OSC_WIDE_RATIO * lo and room >= 2.0 * period


OSC_WHOLE = True
"""A moving step of ratio beyond :data:`OSC_WIDE_RATIO` short of a stop (the slower above
:data:`RELAX_STOP` of the faster) is placed on a window of one oscillation period (the longest
found) each side, where the samples between its neighbours reach one period on each side
(:func:`osc_whole`; ours; branch stepfix).

Why: with the amplitude following the velocity (:data:`OSC_FOLLOW`) a period enters the
hinge only where the window holds it whole on each side of the change, and the window of a
step of ratio 3 or 10 (20-60 s each side by the wander's correlation time, 25 s for the
zoo's servo error, whose fitted correlation time is about 1 s) holds the zoo's 22-s period
but not its 45-s one. That line's displacement, ``A v P / (2 pi)`` (0.29 s times the speed at
4 % and 45 s), over a window of less than a period is a curvature of the load point's path
that the OU wander of 1 s cannot take up, and the hinge's kink takes it instead: the
ratio-3 steps of zoo 277, 397, 5196, 6231, 11173 and 12183 were 1.3-1.4 tolerances off with
``start_p`` 0.2-0.7. One period each side is the least window in which the line enters, and
the narrowest widening: two periods each side (as :data:`OSC_WIDE`) for every moving step
fixed four zoo records and broke two (``OSC_WIDE``'s note). Where the nearer neighbour is
closer than one period (a short step of 8-20 s) the window stays as it was: widened on the
long side alone the period could not enter, and the long side's wander would only pull the
hinge. Measured on the zoo's used ranges: docs/performance.md (stepfix)."""


def osc_whole(v1: float, v2: float, room: float, period: float) -> bool:
    """Whether a change from ``v1`` to ``v2`` (m/s) is placed on a window of one oscillation
    period each side (:data:`OSC_WHOLE`): both moving, more than :data:`OSC_WIDE_RATIO` apart
    and not a stop (the slower above :data:`RELAX_STOP` of the faster), its samples reaching
    ``room`` (s, the nearer of the two sides) at least the longest ``period`` (s; 0: none
    found)."""
    lo, hi = sorted((abs(v1), abs(v2)))
    return (OSC_WHOLE and period > 0.0 and OSC_WIDE_RATIO * lo < hi
            and lo > RELAX_STOP * hi and room >= period)


def oscillation_periods(t: Array, res: Array, speed: Array, max_peaks: int = 3
                        ) -> tuple[float, ...]:
    """Periods (s) of a machine oscillation in the relative wander ``res / speed`` (s).

    The wander is interpolated on a uniform grid (at most 2048 points, gaps bridged linearly)
    and its periodogram (Hann window, FFT zero-padded 2 times) searched for peaks of periods 5
    s (and 10 samples) to a third of the record that stand :data:`OSC_K` times above the
    median power within a factor 2 of their frequency, none within 4 / span of a stronger one
    (ours).

    Parameters
    ----------
    t : Array
        Times, s.
    res : Array
        Displacement about the record's broken line, m.
    speed : Array
        Speed of the stretch each sample lies in, m/s (samples slower than 5 % of the
        fastest are left out: a hold has no relative wander).
    max_peaks : int
        Most periods returned (the strongest).
    """
    speed = np.asarray(speed, float)
    ok = speed >= 0.05 * float(np.max(speed)) if speed.size else speed > 0
    if ok.sum() < 64 or not np.max(speed) > 0:
        return ()
    tt, y = np.asarray(t, float)[ok], np.asarray(res, float)[ok] / speed[ok]
    span = float(tt[-1] - tt[0])
    n = int(min(2048, tt.size))
    grid = np.linspace(float(tt[0]), float(tt[-1]), n)
    yg = np.interp(grid, tt, y)
    yg -= yg.mean()
    dt = span / (n - 1)
    # a Hann window: a strong line's sidelobes (5 % of it unwindowed) are no lines of their own
    p = np.abs(np.fft.rfft(yg * np.hanning(n), 2 * n)) ** 2
    f = np.fft.rfftfreq(2 * n, dt)
    pmin = max(5.0, 10.0 * median(np.diff(tt)))
    band = (f >= 3.0 / span) & (f <= 1.0 / pmin)
    idx = np.flatnonzero(band)
    if idx.size < 8:
        return ()
    lf = np.log(f[idx])
    pb = p[idx]
    peaks = np.flatnonzero((pb[1:-1] >= pb[:-2]) & (pb[1:-1] > pb[2:])) + 1
    peaks = peaks[np.argsort(pb[peaks])[::-1][: 4 * max_peaks]]  # the strongest only
    out: list[float] = []
    for j in peaks:  # strongest first; none within the main lobe (4 / span) of a stronger one
        if len(out) >= max_peaks:
            break  # (a later period would not be returned, nor change those that are)
        fj = float(f[idx[j]])
        # the cheap test first: a peak in a stronger one's lobe needs no median
        if all(abs(fj - 1.0 / q) > 4.0 / span for q in out):
            near = np.abs(lf - lf[j]) <= np.log(2.0)
            if p[idx[j]] >= OSC_K * median(pb[near]):
                out.append(1.0 / fj)
    return tuple(out[:max_peaks])


def _osc_columns(tb: Array, periods: tuple[float, ...]) -> list[Array]:
    """``-cos(w t) / w`` and ``sin(w t) / w`` (``int sin``, ``int cos``; ``w = 2 pi / P``) for
    each period, at the times ``tb`` (relative to ``tb[0]``): one amplitude for the whole window.
    Not ``int V sin`` with ``V`` switching at the guess: that column has a kink of its own at
    the guess, which takes the hinge's place there (measured: changes pushed to the edge of
    the search)."""
    cols = []
    u = tb - float(tb[0])
    for per in periods:
        w = 2.0 * np.pi / per
        cols += [-np.cos(w * u) / w, np.sin(w * u) / w]
    return cols


def place_change(t: Array, x: Array, guess: int, lo: int, hi: int, v1: float, v2: float,
                 sigma: float, rel: tuple[float, float], ab: tuple[float, float],
                 search: float = 5.0, periods: tuple[float, ...] = ()) -> int:
    """The sample where the velocity changes: the generalised-least-squares hinge (module
    docstring) on the samples ``lo:hi`` around ``guess`` (:func:`change_profile`'s sample;
    the parameters are its)."""
    return change_profile(t, x, guess, lo, hi, v1, v2, sigma, rel, ab, search,
                          periods).index


def _chi2_1(level: float) -> float:
    """The ``level`` quantile of chi-square with one degree of freedom, ``ndtri((1 + level)/2)^2``
    (the square of a standard normal). ``scipy.special`` is imported here, not ``scipy.stats`` at
    the top: ``dryfriction --help`` reaches this module, and scipy.stats costs ~0.4 s to import."""
    from scipy.special import ndtri

    return float(ndtri(0.5 * (1.0 + level))) ** 2


@dataclass(frozen=True)
class Placement:
    """Where a velocity change is, and how well the record places it (ours).

    Attributes
    ----------
    index : int
        The boundary (first sample of the new velocity).
    lo, hi : float
        The 95 % interval of the change time, s (record time): the central 95 % of the
        profile likelihood of the hinge's time (:func:`change_profile`); NaN where none was
        computed.
    edge : bool
        The interval reaches the end of the times searched: the record does not place the
        change within them (``lo``, ``hi`` are then those ends: a lower bound on the
        uncertainty).
    cells, weights : Array or None
        The profile likelihood behind the interval, unwidened: the edges of the times the
        candidates stand for (s, record time, one more than the candidates) and each
        candidate's probability (summing to 1); None where none was computed.
    guess : float
        The time the whole stretches put the change at before it was placed, s (NaN where
        not computed).
    far_step : bool
        A step the stretches' far samples could inform (:data:`FAR_STEPS`) and which was
        placed without them.
    """

    index: int
    lo: float = float("nan")
    hi: float = float("nan")
    edge: bool = False
    cells: Array | None = field(default=None, compare=False, repr=False)
    weights: Array | None = field(default=None, compare=False, repr=False)
    guess: float = float("nan")
    far_step: bool = False


LEVEL = 0.95
"""Probability of the change-time interval (:func:`change_profile`)."""
RELAX_STOP = 0.05
"""A change to a speed below this fraction of the one before is a *stop* (ours): after it a
servo's position error relaxes with nothing driving it (a type-1 position loop tracks a ramp
with a bounded error, which decays once the command stops: e.g. Ogata, *Modern Control
Engineering*, 5th ed., ch. 5), a slow continued motion of the load point that the hinge alone
takes for a later stop (zoo records 184, 220, 244, 274, 424, 436 of 150-449: 3.4-5.5 s late).
The stop is placed with ``(1 - exp(-(t - t_c) / tau))+`` as a further free regressor
(amplitude free, ``tau`` profiled over :data:`RELAX_TAUS`). 1/20, not 1/100 as before (ours):
the servo's error scales with the speed, so after a change to 1/20 of it the error left to
relax is 20 times what the new speed's wander carries; that remnant (5 %) is below the
servo's own relative wander (6 % on the shared record), so the change is a stop to within
the wander itself (zoo records 3013 and 3115 of 3000-3299, down-steps of ratio 30: 5.4 and
4.0 tolerances off as steps, within 0.6 as stops). The zoo's ratios, 10 and 30, leave any
value from 0.034 to 0.1 the same."""
RELAX_ABOVE = 3.0
"""The relaxation is looked for only where the position error before the stop (the relative
wander's rms times its correlation time times the speed, and the measured ``lag`` times the
speed: :func:`_relaxes`) is at least this many white-noise standard deviations (ours): a free
regressor below the noise only pulls the hinge (zoo records 250 and 322, stops from 0.4-0.5
um/s, placed 0.7 and 2.6 s early without this)."""
RELAX_TAUS = tuple(float(2.0 ** (k / 2.0)) for k in range(7))
"""The loop's time constants (s) the relaxation is profiled over: 1 to 8 s by half octaves
(ours; a generic grid, not the zoo's 3 s). An octave grid (1, 2, 4, 8 s, before stop 45) is
too coarse where the relaxation is large: a settling of 12-40 um approached over 2.7 s after a
stop from 31 um/s (``tests/records/test_count_causes.py``) drew the stop 2.2-3.8 s late with
it in 6 of 10 records, within 0.15 s with half octaves; between grid points the hinge takes up
what the exponential's wrong time constant leaves."""
RELAX_BY_LAG = True
"""Whether the relaxation also needs the record's measured position error (``lag`` times the
speed, :class:`.detection.Fluctuations`) above the noise, beside the fitted OU wander's
``s tau`` times it (:func:`_relaxes`; ours)."""


def _relaxes(v1: float, v2: float, rel: tuple[float, float], sigma: float,
             lag: float | None) -> bool:
    """Whether a change from ``v1`` to ``v2`` (m/s) is placed as a stop with the servo's
    relaxation (:data:`RELAX_STOP`): a change to below ``RELAX_STOP`` of the speed whose
    position error before it stands :data:`RELAX_ABOVE` white-noise deviations ``sigma`` (m)
    above the noise by both of the record's measures of it: the fitted OU wander's ``s tau
    |v1|`` (``rel = (s, tau)``) and, with :data:`RELAX_BY_LAG` where it is known (not None),
    the measured ``lag |v1|`` (``lag`` the position error per unit speed, s; inf where the
    white noise hides it: no relaxation).

    Why (ours): the relaxation's amplitude is the position error at the stop, whose rms is
    what ``lag`` measures; ``s tau`` is an extrapolation of the slope scatter, which the OU
    fit makes 126-200 s long where the wander is bounded or periodic (bursts, a machine
    oscillation, a servo's error over long windows): every ratio-30 down-step then got the
    relaxation's free amplitude, which takes the kink's place and puts the step early
    whether the record shows a position error or not (zoo records 3241, 7075, 3073, 7021,
    7081: 0.9-3.6 s early, ``s tau |v1|`` 6-55 white-noise deviations where ``lag |v1|`` is
    0.5-1.8 of them or not measured). ``lag`` alone is not enough either way: where the
    OU's ``s tau |v1|`` is below the noise and ``lag |v1|`` above it, the free amplitude
    still pulled a hold's start 0.5 s early (zoo 5098, with ``lag`` alone); both measures
    must see the error. Measured: docs/performance.md (detect8).
    """
    if not abs(v2) <= RELAX_STOP * abs(v1):
        return False
    above = rel[0] * rel[1] * abs(v1) >= RELAX_ABOVE * sigma
    if RELAX_BY_LAG and lag is not None:
        return bool(above and np.isfinite(lag) and lag * abs(v1) >= RELAX_ABOVE * sigma)
    return above

HOLD_HALF = 60.0
"""The window about a change at a hold reaches this far (s) each side, not 20 s (ours):
where the servo's position error at the sliding speed (``lag`` times it,
:class:`.detection.Fluctuations`) is below ``RELAX_ABOVE`` white-noise standard deviations,
the kink is placed by the white noise over the two stretches' levels, which fall as the
samples grow (and the oracle of ``bench_detect_bound`` uses 60 s). Where the position error
stands above the white noise (a fast stop: ``tests/records/test_change_interval.py``, 20 um/s
at 50 Hz, one of 12 stops 0.62 s off with 60 s) the window stays as it was. Measured with
the rule on every change at a hold or a stop (no guard): on zoo records 0-299 96.3 ->
96.7 %, on 3000-3299 92.7 -> 92.7 % (holds fixed 3, broken 3: the ratio-30 stops and
slow-sampled holds)."""
HOLD_FAR = 300.0
"""Beyond :data:`HOLD_HALF`, the window about a change at a hold (and at a step:
:data:`FAR_STEPS`), where the white noise hides the servo's position error, reaches on to this
far (s) each side, in :data:`FAR_BLOCKS` long blocks each side; the blocks within
:data:`HOLD_HALF` stay as they were (:func:`zoned_blocks`; ours; stop 48). 0 (or below
:data:`HOLD_HALF`): no far blocks.

Why: there the kink is placed by where the two stretches' lines meet, and under white noise
``sigma`` the meeting point is known to about ``sigma sqrt(4/n1 + 4/n2) / |v1 - v2|`` (each
line's value at its end, from ``n`` samples). Slow slide-hold-slides (0.1-0.3 um/s sampled at
2-5 Hz, stretches of hundreds of seconds) were held to 60 s each side: their 95 % intervals
were 2-5 s wide and many changes 0.5-1.3 s off (of the 270 changes off the tolerance in the
280 zoo records wrong since stop 46, 62 were stops or restarts at under 0.3 um/s). Far
samples inform only the lines, not where the kink lies, so they are kept as a few long block
means; the near blocks keep the resolution the change is told at (a window 300 s long cut into
128 blocks of one duration lost the candidates beside a neighbour 13 s away: zoo 9292's short
hold unplaced with 1000 s). Measured (``bench_detect`` on the zoo; docs/performance.md, "Slow
holds placed on their whole stretches"): the 4650 used records 99 -> 87 wrong, the 4500
examined 106 -> 98; with one duration over the whole window, 60/150/300/1000 s gave 99, 90,
87 and 102 wrong on the used records."""
FAR_STEPS = True
"""A step between moving speeds that its near window leaves not placed, where the white noise
hides the servo's position error and both stretches run straight (:func:`straight_sides`),
is placed again with the stretches' far samples, as a change at a hold is (:data:`HOLD_FAR`):
the far look moves it, and the near window's profile still judges whether it is placed
(:func:`far_look`); False: far samples at holds only (ours; stop 49).

Why: the same as at a hold, and more so for a small step: the kink is where the two
stretches' lines meet, known to about ``sigma sqrt(4/n1 + 4/n2) / |v1 - v2|``, and a
ratio-1.3 step at 0.2 um/s changes the slope by 0.06 um/s, a third of a stop's. Of the 284
changes off the tolerance or missed in the 280 zoo records re-run at stop 48, 146 were
ratio-1.3 steps between moving speeds (87 of them with the slower under 1 um/s), all but 7
marked not placed. Only a second look: given to every such step with its own profile (the
first form of this rule), the far samples turned a speed change of a few per cent near a
step, too small to split on, into a step placed 2 s off with probability 1 (an independent
review's records). Measured (``bench_detect`` on the zoo; docs/performance.md, "Steps placed
on their whole stretches"): this rule alone, the 4650 used records 87 -> 73 wrong, the 4500
examined 98 -> 81; with the straightness guard on a hold's far samples too (stop 49's final
form) 74 and 82, and 2700 fresh ones (60000-68299) 70 -> 60, side by side at the same CPU
(the first form: 70, 81, and 1800 fresh 52 -> 45)."""
FAR_BLOCKS = 16
"""Blocks each side beyond :data:`HOLD_HALF` (:data:`HOLD_FAR`): the Cholesky factor then
costs ``(BLOCKS + 2 FAR_BLOCKS)**3 / 3``, twice that of :data:`BLOCKS` alone, for these
windows only."""
HOLD_RATIO = 0.01
"""A change between speeds more than ``1 / HOLD_RATIO`` apart is at a hold for the window
(:data:`HOLD_HALF`), beside the detector's own hold flag, which misses a hold read before
placement as a creep (zoo records 4036, 4108 and 5116: the flag alone left 1.23, 2.22 and
1.31 tolerances off); the ratio-30 steps of the zoo are not (with 1/20, as for the stops,
zoo 3157 went from 0.05 to 1.27 tolerances off before the position-error guard; ours)."""
BLOCKS = 128
"""Most block means the hinge is fitted on (:func:`change_profile`): the Cholesky factor of
their covariance costs ``BLOCKS**3 / 3``."""
FINE_RATIO = 2.0
"""A change between speeds at most this ratio apart is a *small step* (:func:`small_step`)."""
FINE_BLOCKS = 256
"""Most block means a small step is placed on (:data:`EVEN_BLOCKS`): where blocks of one
duration would be more (a window mostly sampled slower than its median), they are made longer;
256 costs 8 times :data:`BLOCKS`' Cholesky factor, for the small steps of uneven windows only."""
EVEN_BLOCKS = True
"""A small step (:data:`FINE_RATIO`) is placed on block means of one duration, that of the
``k`` samples of a block at the window's median sampling interval, not of one sample count
(:func:`even_blocks`; at most :data:`FINE_BLOCKS`; ours).

Why: a block mean keeps one number of the samples within it, so the hinge's profile sees
where the kink lies inside a block only through that number, and a change is placed by the
profile's mass within the tolerance (0.5 s, :func:`_most_probable`): the blocks' duration is
the placement's resolution. Blocks of one count are as long as that count of samples: ten
times longer on the slow side of a 10-fold sampling-rate change (the zoo's ``rate``, often at
the change itself), longer across a gap; a small step's window is the longest (two
oscillation periods each side, :data:`OSC_RATIO`: 190 s with the zoo's 45 s), and its
profile, spread over several tolerances (its information goes as the squared velocity
change), is where that resolution decides. On evenly sampled times the blocks are those of
one count (the same placements: ``bench_detect_oracle``'s records unchanged). Measured
(``detect7``: a diagnostic that replays each placement of the detector with only the blocks
changed, on the zoo's ratio-1.3 and ratio-2 steps of records 0-449 and 3000-8299 placed by
the hinge): ratio 1.3, 40 of 139 off the tolerance before, 29 after (11 fixed, none broken);
ratio 2, 8 of 106 before, 7 after (1 fixed). Tried there: blocks of one duration cut into 128
equal spans of the window (34 and 6; it moved ``bench_detect_oracle``'s evenly sampled
records: 19 of 27 ratio-1.3 steps within the tolerance against 20, the test in
``tests/records/test_detect.py``), 512 blocks of one count (32 and 6; twice the detection's CPU on
``bench_detect_oracle``'s ratio-1.3 records, 9.1 against 4.8 s per 1e6 rows), 256 of one
count (31 and 9)."""


HOLD_EVEN = True
"""A change at a hold placed on the long window (:data:`HOLD_HALF`: the white noise hides the
servo's position error there) is placed on block means of one duration, as a small step is
(:data:`EVEN_BLOCKS`), at most :data:`BLOCKS` of them (ours; ``holdfix``).

Why: the window of a hold is 60 s each side, so its blocks of one sample count (at most
:data:`BLOCKS`) hold up to about 100 samples; where the sampling rate changes 10-fold in the
window (the zoo's ``rate``, often at the change itself) the blocks on the slow side are ten
times longer than on the fast one, several seconds against a 0.5-s tolerance, and the hinge sees
where the kink lies inside a block only through that block's mean. Blocks of one duration (the
window cut into spans of ``k`` median intervals, or into :data:`BLOCKS` equal spans where more
would be needed) keep the resolution the same on both sides, and on an evenly sampled window
they are the blocks of one count (the same placements). At most :data:`BLOCKS`, not
:data:`FINE_BLOCKS`: the same zoo records either way (measured), at the cost of one count.
Measured: docs/performance.md (holdfix), zoo records 5122, 5128, 9076, 10096 (hold changes
0.55-1.98 s off, every one with ``rate``) within the tolerance, none broken."""


RATE_EVEN = 3.0
"""A change whose window, cut into blocks of one sample count, has a block this many times
longer than their median (a sampling-rate change in the window) is placed on blocks of one
duration (:func:`even_blocks`, at most :data:`BLOCKS`), as a small step and a hold are; 0 turns
the rule off (ours; lead, stop 40).

Why: a block mean keeps one number of its samples, so a block's duration is the hinge's
resolution, and the candidate times stay three blocks inside the window. On the slow side
of a 10-fold rate change, blocks of one count are ten times longer: at the end of a short
step (8 s on that side) they were 4-5 s long and the candidates never reached the true time
(zoo 332 and 380 on main: a short step's change 2.12 and 0.66 s off). Only such
windows: every window on blocks of one duration (stepfix's form) moved a change after a 1-s
stretch of a whole experiment by 0.22 s (``tests/fit/test_experiment.py``); this rule leaves
it where it was. Measured:
docs/performance.md ("The three merged")."""


TIME_GRID = True
"""A change's coarse candidates (:func:`change_profile`: every ``step``-th sample, ``step``
the search's sample count over 100) are joined by the samples nearest 101 times evenly spread
over the search; the fine search is as before, every sample within ``step`` of the best (ours;
stop 46).

Why: where the sampling rate changes within the search (the zoo's ``rate``, often at the
change itself: 50 Hz before, 500 Hz after), a grid of one sample count is ten times coarser
in time on the slow side, a second apart against a 0.5-s tolerance, and the fine search
around the best coarse sample never reaches a change between two coarse samples there: zoo
35288, an 8 -> 81 um/s step at 60.0 s, plain to the eye, was placed at 60.58 s with the
interval 60.24-60.58 s (the blocks of one duration, :data:`RATE_EVEN`, sharpen the profile
there). On evenly sampled times the time grid falls between the other's samples (about twice
the coarse candidates; the profile's cells, and so the intervals, move a little). Measured
(docs/performance.md, "Candidates spread in time"): zoo 4650 used records 105 -> 101 wrong,
4500 examined 111 -> 107, none broken; 900 fresh (38000-40299) unchanged, 3-5 % more CPU."""


def small_step(v1: float, v2: float) -> bool:
    """Whether a change from ``v1`` to ``v2`` (m/s) is a small step: both moving, at most
    :data:`FINE_RATIO` apart."""
    lo, hi = sorted((abs(v1), abs(v2)))
    return 0.0 < lo and hi <= FINE_RATIO * lo


def even_blocks(tt: Array, width: float, most: int) -> Array:
    """The first sample of each block when the times ``tt`` (s, increasing) are cut into
    spans of ``width`` s from the first (at most ``most`` of them: longer spans where more
    would be needed); an empty span (a gap) gives no block. On evenly sampled times, spans of
    ``k`` sample intervals are the blocks of ``k`` samples."""
    span = float(tt[-1] - tt[0])
    if not (span > 0.0 and width > 0.0):
        return np.arange(1)
    width = max(width, span / max(most, 1) * (1.0 + 1e-8))
    # a sample on a span's edge (up to rounding) opens the span
    j = np.floor((tt - tt[0]) / width + 1e-9)
    return np.flatnonzero(np.diff(np.concatenate([[-1.0], j])) != 0)


def zoned_blocks(tt: Array, near_lo: float, near_hi: float, width: float, far: int) -> Array:
    """The first sample of each block (:data:`HOLD_FAR`): spans of ``width`` s from ``near_lo``
    to ``near_hi`` (s; at most :data:`BLOCKS` of them, longer spans where more would be
    needed), and ``far`` equal spans over the times before ``near_lo`` and ``far`` over those
    after ``near_hi``; an empty span (a gap) gives no block. The first block starts at sample
    0."""
    t0, t1 = float(tt[0]), float(tt[-1])
    lo, hi = max(near_lo, t0), min(near_hi, t1)
    width = max(width, (hi - lo) / BLOCKS * (1.0 + 1e-8), 1e-300)
    edges = [np.arange(lo, hi, width) if hi > lo else np.array([lo])]
    if lo > t0:
        edges.insert(0, np.linspace(t0, lo, far + 1)[:-1])
    if hi < t1:
        edges.append(np.linspace(hi, t1, far + 1)[:-1])
    # a sample on an edge (up to rounding) opens its span
    tol = 1e-9 * max(t1 - t0, 1.0)
    idx = np.unique(np.searchsorted(tt, np.concatenate(edges) - tol, side="left"))
    idx = idx[idx < tt.size]
    return np.union1d([0], idx).astype(int)


WIDEN = 2.0
"""Each side of the change-time interval is this many times the profile's (ours, empirical):
the profile is that of the model (an OU velocity wander, white noise, a machine oscillation);
where the model is the truth (``tests/records/test_placement.py``) its intervals cover 92-95 %
of the changes, but on the zoo's held-out records 150-449 (a servo's position error, bursts,
quantisation, rate changes) they covered 78 %: 2 gave 95.5 % there (1.5: 89 %, 3: 97.6 %). Over
the families (velocity ratio, program, artifacts) the widening each needed at 95 % was
1.4-2.7, so one factor serves."""


def profile_weights(times: Array, gain: Array, scale: float, left: float, right: float
                    ) -> tuple[Array, Array]:
    """The cells the candidate change times stand for (edges, s: half way to each
    neighbour, ``left``/``right`` for the first and the last) and each one's probability,
    ``exp((gain - max) / (2 scale))`` times its cell's length, normalised
    (:func:`profile_interval`); all zero where no gain is finite."""
    tt = np.asarray(times, float)
    mid = 0.5 * (tt[1:] + tt[:-1])
    edges = np.concatenate([[min(left, float(tt[0]))], mid, [max(right, float(tt[-1]))]])
    g = np.asarray(gain, float)
    ok = np.isfinite(g)
    if not ok.any():
        return edges, np.zeros(tt.size)
    w = np.where(ok, np.exp(np.where(ok, g - g[ok].max(), 0.0) / (2.0 * scale)), 0.0)
    w = w * np.diff(edges)
    return edges, w / w.sum()



def placed_probability(pl: Placement, at: float, tol: float, widen: float | None = None
                       ) -> float:
    """The probability that the change lies within ``tol`` of ``at`` (s), by its profile
    likelihood (:class:`Placement`'s ``cells``, ``weights``) widened ``widen`` times about
    ``at`` (default :data:`WIDEN`, as its interval): the profile's mass within ``tol /
    widen`` of ``at``, each cell counted by the part of it inside (ours). 1 where no profile
    was computed (nothing said against the time)."""
    if pl.cells is None or pl.weights is None:
        return 1.0
    w = WIDEN if widen is None else widen
    c = np.asarray(pl.cells, float)
    a, b = at - tol / w, at + tol / w
    part = (np.clip(np.minimum(c[1:], b) - np.maximum(c[:-1], a), 0.0, None)
            / np.maximum(np.diff(c), 1e-300))
    return float(np.clip(part @ np.asarray(pl.weights, float), 0.0, 1.0))


def profile_interval(times: Array, gain: Array, scale: float, left: float, right: float,
                     level: float = LEVEL) -> tuple[float, float, bool]:
    """The central ``level`` interval of a change time from its profile likelihood (ours).

    With the wander's covariance known up to a factor ``scale`` (the generalised residual
    variance), the hinge's log-likelihood at a candidate time is ``gain / (2 scale)`` plus a
    constant (``gain`` the generalised-least-squares sum of squares it saves; the offset, the
    slopes and the oscillation's amplitudes profiled out). With a uniform prior in time, each
    candidate weighs ``exp((gain - max) / (2 scale))`` times the time it stands for (half way
    to each neighbour; ``left``/``right`` for the first and the last): the interval runs from
    the cell where that cumulative weight passes ``(1 - level) / 2`` to the one where it
    passes ``(1 + level) / 2``, cells whole.

    Parameters
    ----------
    times : Array
        Candidate change times, s, increasing.
    gain : Array
        Generalised sum of squares each saves (-inf: not a candidate).
    scale : float
        The generalised residual variance (1 where the covariance is exact), > 0.
    left, right : float
        The ends of the times searched, s.
    level : float
        Probability, 0 < level < 1.

    Returns
    -------
    lo, hi : float
        The interval, s.
    edge : bool
        The first or the last candidate lies in the likelihood-ratio region of the same level
        (log-likelihood within ``chi2_1(level) / 2`` of the best): the profile is cut by the
        times searched.
    """
    tt = np.asarray(times, float)
    edges, w = profile_weights(tt, gain, scale, left, right)
    g = np.asarray(gain, float)
    ok = np.isfinite(g)
    if not ok.any():
        return float(edges[0]), float(edges[-1]), True
    c = np.cumsum(w)
    i = int(np.searchsorted(c, 0.5 * (1.0 - level)))
    j = min(int(np.searchsorted(c, 0.5 * (1.0 + level))), tt.size - 1)
    # at the edge: the first or the last candidate inside the likelihood-ratio region of the
    # same level (log-likelihood within chi2_1(level) / 2 of the best: 1.92 at 95 %)
    ends = g[ok][[0, -1]]
    edge = bool(np.any((ends - g[ok].max()) / (2.0 * scale) >= -0.5 * _chi2_1(level)))
    return float(edges[i]), float(edges[j + 1]), edge


def change_profile(t: Array, x: Array, guess: int, lo: int, hi: int, v1: float, v2: float,
                   sigma: float, rel: tuple[float, float], ab: tuple[float, float],
                   search: float = 5.0, periods: tuple[float, ...] = (), move: bool = True,
                   stop: bool = False, tol: float = 0.0, held: bool | None = None,
                   lag: float | None = None, far_step: bool = False) -> Placement:
    """The sample where the velocity changes: the generalised-least-squares hinge (module
    docstring) on the samples ``lo:hi`` around ``guess``, and the 95 % interval of its time
    (:func:`profile_interval`, scaled by the generalised residual variance at the best
    hinge).

    Parameters
    ----------
    t, x : Array
        Times, s, and displacement, m, of the whole record.
    guess : int
        Current boundary (first sample of the new velocity).
    lo, hi : int
        The samples the window may use (not past the neighbouring boundaries).
    v1, v2 : float
        Velocities before and after, m/s.
    sigma : float
        White noise of ``x``, m.
    rel, ab : tuple of float
        ``(s, tau)`` of the relative (1, s) and absolute (m/s, s) wander.
    search : float
        The change is looked for within this many seconds (and at least 10 samples) of
        ``guess``.
    periods : tuple of float
        Periods (s) of a machine oscillation (:func:`oscillation_periods`), each two free
        regressors.
    move : bool
        ``False``: the boundary stays at ``guess`` (placed otherwise); only the interval is
        computed.
    stop : bool
        A stop (:data:`RELAX_STOP`): the hinge is fitted with the servo's relaxation after it,
        ``(1 - exp(-(t - t_c) / tau))+``, amplitude free, the gain the best over ``tau`` in
        :data:`RELAX_TAUS`.
    tol : float
        With ``move``, a tolerance (s, > 0): the boundary is the sample most probably within
        the larger of its sample interval and ``tol`` of the change (:func:`_most_probable`),
        not the profile's mode (``0``, the default).
    held : bool, optional
        The change is to or from a hold (the detector's flag): its window reaches
        :data:`HOLD_HALF` each side where ``lag`` allows; ``None``: by the speeds alone
        (:data:`HOLD_RATIO`).
    lag : float, optional
        The servo's position error per unit speed, s (:class:`.detection.Fluctuations`; inf:
        hidden by the white noise); ``None`` (not known): no hold window.
    far_step : bool
        A step (not at a hold) placed on its stretches' far samples too where ``lag`` allows
        (:data:`FAR_STEPS`); ``False``: far samples at a hold only.

    Returns
    -------
    Placement
        The boundary (``guess`` where the window is too small to judge, the interval then
        NaN).
    """
    tau = max(rel[1] if rel[0] > 0 else ab[1], 1e-3)
    tg = float(t[guess])
    # an oscillation's regressors are told from the hinge over two of its periods each side
    # (a step of ratio up to OSC_RATIO; with OSC_WIDE, up to OSC_WIDE_RATIO where its samples
    # hold two periods each side)
    wide = osc_wide(v1, v2, min(tg - float(t[lo]), float(t[hi - 1]) - tg),
                    max(periods, default=0.0))
    # at a hold, where the white noise hides the servo's position error: a longer window
    fast, slow = max(abs(v1), abs(v2)), min(abs(v1), abs(v2))
    quiet = lag is not None and not (np.isfinite(lag) and lag * fast >= RELAX_ABOVE * sigma)
    still = quiet and (bool(held) or slow <= HOLD_RATIO * fast)
    # a larger step, not a stop, one period each side where its samples hold one (OSC_WHOLE)
    longest = max(periods, default=0.0)
    whole = not still and osc_whole(v1, v2, min(tg - float(t[lo]), float(t[hi - 1]) - tg),
                                    longest)
    near = max(min(max(HOLD_HALF if still else 20.0, 10.0 * tau), 60.0),
               2.0 * longest if wide else longest if whole else 0.0) + search
    # at a hold, and at a step's far look (FAR_STEPS), where the white noise hides the servo's
    # position error: on to the stretches' far samples, as a few long blocks (HOLD_FAR)
    farther = quiet and HOLD_FAR + search > near
    # at a hold only where both stretches run straight (a step's far look checks it before)
    zoned = farther and (far_step or (still and straight_sides(t, x, guess, lo, hi)))
    # a step the far samples could inform, placed without them
    unfarred = farther and not still and not far_step
    half = HOLD_FAR + search if zoned else near
    a = max(lo, int(np.searchsorted(t, tg - half)))
    b = min(hi, int(np.searchsorted(t, tg + half)))
    if b - a < 12 or not a < guess < b:
        return Placement(guess)
    tt = t[a:b]
    # the near window, whose samples the block count is set by
    a_n = max(a, int(np.searchsorted(t, tg - near)))
    b_n = min(b, int(np.searchsorted(t, tg + near)))
    # block means, at most 128: the wander is smooth within a block, the white noise of a
    # block falls as 1/count (256 before: 8 times the Cholesky factor's cost; its effect on
    # the placements alone was not measured apart); for a small step, blocks of one duration,
    # that of k samples at the window's median interval (EVEN_BLOCKS); so, at most BLOCKS of
    # them, for a change at a hold on the long window (HOLD_EVEN)
    small = EVEN_BLOCKS and small_step(v1, v2)
    fine = small or (HOLD_EVEN and still)
    k = max(1, int(np.ceil((b_n - a_n) / BLOCKS)))
    if RATE_EVEN and not fine and k > 1:
        # blocks of one count of which one lasts RATE_EVEN times their median (a sampling-rate
        # change in the window): of one duration instead (the last, partial block left out)
        e = tt[np.append(np.arange(0, b - a, k), b - a - 1)]
        dur = np.diff(e)
        fine = bool(dur.size > 2 and dur[:-1].max() > RATE_EVEN * median(dur[:-1]))
    if zoned:
        idx = zoned_blocks(tt, float(t[a_n]), float(t[b_n - 1]), k * median(np.diff(tt)),
                           FAR_BLOCKS)
    else:
        idx = (even_blocks(tt, k * median(np.diff(tt)), FINE_BLOCKS if small else BLOCKS)
               if fine and k > 1 else np.arange(0, b - a, k))
    cnt = np.diff(np.append(idx, b - a)).astype(float)
    tb = np.add.reduceat(tt, idx) / cnt
    xb = np.add.reduceat(x[a:b] - x[a], idx) / cnt
    n = tb.size
    if n < 12:
        return Placement(guess)
    t0 = float(tb[0])
    # D_i = v1 int_{t0}^{min(t_i, tg)} eps + v2 int_{tg}^{max(t_i, tg)} eps (relative) and
    # int_{t0}^{t_i} eta (absolute), block means taken at their mean times
    e1, s2 = np.minimum(tb, tg), np.maximum(tb, tg)
    C = np.zeros((n, n))
    if rel[0] > 0:
        tr = rel[1]
        cross = _cov_int(t0, e1[:, None], tg, s2[None, :], tr)
        C += rel[0] ** 2 * (
            v1 * v1 * _cov_int(t0, e1[:, None], t0, e1[None, :], tr)
            + v2 * v2 * _cov_int(tg, s2[:, None], tg, s2[None, :], tr)
            + v1 * v2 * (cross + cross.T))
    if ab[0] > 0:
        C += ab[0] ** 2 * _cov_int(t0, tb[:, None], t0, tb[None, :], ab[1])
    C[np.diag_indices(n)] += sigma**2 / cnt
    C[np.diag_indices(n)] += 1e-6 * float(np.max(np.diag(C)))  # conditioning
    try:
        L = np.tril(cho_factor(C, lower=True)[0])
    except np.linalg.LinAlgError:
        return Placement(guess)
    # a period much longer than the window is a curvature there, not an oscillation; one
    # amplitude for both sides holds for a small step only (OSC_RATIO)
    small = max(abs(v1), abs(v2)) <= OSC_RATIO * min(abs(v1), abs(v2))
    per = tuple(q for q in periods if (small or OSC_FOLLOW) and q <= 2.0 * float(tb[-1] - tb[0]))
    # following the velocity: a period is told from the hinge only where the window holds
    # it whole on each side of the change (a part of a sine is a ramp of velocity there)
    if OSC_FOLLOW and not small:
        per = tuple(q for q in per if q <= min(tg - float(tb[0]), float(tb[-1]) - tg))
    follow = OSC_FOLLOW and bool(per) and not small
    base = np.column_stack([np.ones(n), tb - tg, *([] if follow else _osc_columns(tb, per))])
    W = solve_triangular(L, np.column_stack([xb, base]), lower=True, check_finite=False)
    Qb, _ = np.linalg.qr(W[:, 1:])
    yp = W[:, 0] - Qb @ (Qb.T @ W[:, 0])
    cs = np.concatenate([[0.0], np.cumsum(tt)])

    def follow_gains(c: Array, Hp: Array) -> Array:
        """GLS gain of the hinge with the oscillation following the velocity through the
        change at each candidate time ``c``: per period, ``v1 I(t) + (v2 - v1) (I(t) -
        I(c))+`` for ``I = int sin`` and ``int cos`` (:data:`OSC_FOLLOW`), amplitudes free, the
        hinge and these columns together (batched normal equations)."""
        after = tb[:, None] > c[None, :]
        cols = [Hp]
        # I(t) and I(c) of each period, int sin and int cos (as _osc_columns)
        for i_t, i_c in zip(_osc_columns(tb, per),
                            _osc_columns(np.concatenate([tb[:1], c]), per), strict=True):
            col = v1 * i_t[:, None] + (v2 - v1) * np.where(after, i_t[:, None] - i_c[None, 1:],
                                                           0.0)
            cw = solve_triangular(L, col, lower=True, check_finite=False)
            cols.append(cw - Qb @ (Qb.T @ cw))
        M = np.stack(cols, axis=2)  # (n, candidates, columns)
        G = np.einsum("ick,icl->ckl", M, M)
        r = np.einsum("ick,i->ck", M, yp)
        G[:, np.arange(G.shape[1]), np.arange(G.shape[1])] *= 1.0 + 1e-10
        try:
            sol = np.linalg.solve(G, r[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:
            return np.full(c.size, -np.inf)
        gain = np.einsum("ck,ck->c", r, sol)
        return np.where(np.isfinite(gain), gain, -np.inf)

    def gains(cand: Array) -> Array:
        """GLS gain of the hinge at each candidate sample (``a``-relative index): its block
        mean ``mean (t - t_c)+`` exact, also in the block that holds the candidate."""
        c = tt[cand]
        Hb = np.maximum(tb[:, None] - c[None, :], 0.0)
        beta = np.searchsorted(idx, cand, side="right") - 1  # the block holding each
        e = np.append(idx[1:], b - a)[beta]
        Hb[beta, np.arange(cand.size)] = (cs[e] - cs[cand] - c * (e - cand)) / cnt[beta]
        Hw = solve_triangular(L, Hb, lower=True, check_finite=False)
        Hp = Hw - Qb @ (Qb.T @ Hw)
        if follow and not stop:
            return follow_gains(c, Hp)
        if not stop:
            with np.errstate(divide="ignore", invalid="ignore"):
                gain = (Hp.T @ yp) ** 2 / np.einsum("ij,ij->j", Hp, Hp)
            return np.where(np.isfinite(gain), gain, -np.inf)
        # with the servo's relaxation after the stop, (1 - exp(-(t - t_c) / tau))+, its
        # amplitude free: the gain of the two columns together (2 x 2 normal equations)
        hh = np.einsum("ij,ij->j", Hp, Hp)
        u = Hp.T @ yp
        best = np.full(cand.size, -np.inf)
        for tau_r in RELAX_TAUS:  # the loop's time constant, profiled on a grid
            Rb = -np.expm1(-np.maximum(tb[:, None] - c[None, :], 0.0) / tau_r)
            Rw = solve_triangular(L, Rb, lower=True, check_finite=False)
            Rp = Rw - Qb @ (Qb.T @ Rw)
            rr = np.einsum("ij,ij->j", Rp, Rp)
            hr = np.einsum("ij,ij->j", Hp, Rp)
            w = Rp.T @ yp
            with np.errstate(divide="ignore", invalid="ignore"):
                det = hh * rr - hr * hr
                gain = (rr * u * u - 2.0 * hr * u * w + hh * w * w) / det
            best = np.maximum(best, np.where(np.isfinite(gain) & (det > 1e-12 * hh * rr),
                                             gain, -np.inf))
        return best

    # candidates: the samples within `search` s (>= 10 samples) of the guess, coarse first
    # (three blocks clear of the window's ends)
    c_lo = max(int(idx[3]), min(int(np.searchsorted(tt, tg - search)), guess - a - 10))
    c_hi = min(int(idx[-3]) if fine else b - a - 3 * k,
               max(int(np.searchsorted(tt, tg + search)), guess - a + 10))
    if c_hi <= c_lo:
        return Placement(guess)
    step = max(1, -(-(c_hi - c_lo) // 100))
    cand = np.arange(c_lo, c_hi, step)
    if TIME_GRID and step > 1:
        # and 100 spans of one duration (TIME_GRID): across a sampling-rate change, a grid of
        # one sample count is seconds apart on the slow side
        on_time = np.searchsorted(tt, np.linspace(float(tt[c_lo]), float(tt[c_hi - 1]), 101))
        cand = np.union1d(cand, np.clip(on_time, c_lo, c_hi - 1))
    g = gains(cand)
    j = int(np.argmax(g))
    allc, allg = cand, g
    if step > 1:
        cand = np.arange(max(c_lo, cand[j] - step + 1), min(c_hi, cand[j] + step))
        g = gains(cand)
        j = int(np.argmax(g))
        allc, idx_u = np.unique(np.concatenate([allc, cand]), return_index=True)
        allg = np.concatenate([allg, g])[idx_u]
    if not np.isfinite(g[j]):
        return Placement(guess)
    best = a + int(cand[j])
    # the generalised residual variance at the best hinge (1 for the exact covariance): the
    # projected data's sum of squares less the hinge's gain, over its degrees of freedom
    dof = n - Qb.shape[1] - 2
    scale = max(float(yp @ yp) - float(g[j]), 0.0) / dof if dof > 0 else 1.0
    scale = scale if scale > 0 else 1.0
    left, right = 0.5 * float(tt[c_lo - 1] + tt[c_lo]), 0.5 * float(tt[c_hi - 1] + tt[c_hi])
    lo_t, hi_t, edge = profile_interval(tt[allc], allg, scale, left, right)
    cells, weights = profile_weights(tt[allc], allg, scale, left, right)
    if move and tol > 0.0:  # the time most probably within the tolerance, not the mode
        best = a + _most_probable(tt, cells, weights, c_lo, c_hi, tol, best - a)
    at = best if move else guess
    # the interval holds the time reported (a change left where the whole stretches put it
    # may lie outside the profile's own interval): at least its sample's cell; then each side
    # WIDEN times as far from it (the model's profile is too sharp on real wander: WIDEN)
    ta = float(t[at])
    lo_t = min(lo_t, 0.5 * float(t[at - 1] + t[at]))
    hi_t = max(hi_t, 0.5 * float(t[at] + t[min(at + 1, t.size - 1)]))
    lo_t, hi_t = ta - WIDEN * (ta - lo_t), ta + WIDEN * (hi_t - ta)
    if edge:  # not placed within the times searched: those at least
        lo_t, hi_t = min(lo_t, left), max(hi_t, right)
    return Placement(at, lo_t, hi_t, edge, cells, weights, tg, unfarred)


def sample_intervals(t: Array, k: Array) -> Array:
    """The sampling interval (s) at each sample ``k`` (``1 <= k < len(t)``) of the times ``t``
    (s): the interval before it, or where that interval is a gap (longer than 10 times the
    larger of the median interval and the one before it, as :func:`.artifacts.sampling_changes`
    reads a gap) the one after it (the one before where it is the last sample).

    Why (ours; stop 48): "one sample" of the tolerance is the sampling's resolution. The first
    sample after a 101-s gap was given the whole gap as its interval, so a stop 2 s after the
    gap's end was reported there, at the first sample after it, placed with probability 1
    (an independent review's records, a hold's window reaching across the gap)."""
    dt = np.diff(np.asarray(t, float))
    k = np.atleast_1d(np.asarray(k, int))
    if dt.size == 0:
        return np.zeros(k.size)
    gap = gap_intervals(dt, median(dt))
    after = dt[np.minimum(k, dt.size - 1)]
    return np.where(gap[k - 1], np.minimum(after, dt[k - 1]), dt[k - 1])


def _most_probable(tt: Array, cells: Array, weights: Array, c_lo: int, c_hi: int, tol: float,
                   best: int) -> int:
    """The sample (``c_lo <= k < c_hi``, an index into ``tt``, s) whose time is the most
    probably within the larger of its sample interval (:func:`sample_intervals`) and ``tol``
    (s) of the change, by the
    profile likelihood widened :data:`WIDEN` times (the probability :func:`placed_probability`
    reports); ``best`` (the profile's mode) unless another sample holds more.

    Why (ours): a change is right when it lies within that tolerance of the truth, and the
    estimate that maximises the probability of that is the centre of the window of the
    tolerance's width holding the most posterior mass (Bayes' rule under a 0-1 loss), not the
    mode of the posterior: a narrow spike of the profile beside a broad shoulder of more mass
    (a wander the model takes for a kink) is the mode and the wrong place. Measured on the zoo
    (``python -m benchmarks bench_detect``), alone: 0-299 96.3 -> 96.7 %, 3000-3299 92.7 ->
    93.3 %, 5000-5299 93.3 -> 93.0 % (two ratio-1.3 steps broken, one ratio-2 fixed); with the
    profile unwidened (the window ``tol`` each side) 96.7, 93.0 and 92.7 %.
    """
    cum = np.concatenate([[0.0], np.cumsum(weights)])
    k = np.arange(max(c_lo, 1), c_hi)
    one = sample_intervals(tt, np.arange(1, tt.size))  # once: a median of the window's
    h = np.maximum(one[k - 1], tol) / WIDEN
    mass = np.interp(tt[k] + h, cells, cum) - np.interp(tt[k] - h, cells, cum)
    j = int(np.argmax(mass))
    hb = max(float(one[best - 1]), tol) / WIDEN
    mb = float(np.interp(tt[best] + hb, cells, cum) - np.interp(tt[best] - hb, cells, cum))
    return int(k[j]) if mass[j] > mb + 1e-9 else best


def place_changes(t: Array, x: Array, bounds: list[int], velocity: Array, sigma: float,
                  scales: Array, relative: Array, absolute: Array, m: int = 3,
                  weak: Array | None = None, periods: tuple[float, ...] = (),
                  tol: float = 0.0, holds: Array | None = None, lag: float | None = None
                  ) -> tuple[list[int], list[Placement]]:
    """Each inner boundary of ``bounds`` placed by :func:`change_profile`, in order, each window
    kept ``m`` samples clear of the neighbouring boundaries, with the 95 % interval of its time.

    Parameters
    ----------
    t, x : Array
        Times, s, and displacement, m.
    bounds : list of int
        Boundaries, increasing, to ``len(t)``: the first (0 for a whole record) is where
        the first window starts (:data:`OWN_START`), the last where the last ends.
    velocity : Array
        Velocity of each stretch, m/s.
    sigma : float
        White noise of ``x``, m.
    scales, relative, absolute : Array
        The fluctuation model (:class:`.detection.Fluctuations`): ``T`` (s), ``r(T)`` (1) and
        ``a(T)`` (m/s).
    m : int
        Samples kept clear of a neighbouring boundary.
    weak : Array of bool, optional
        Which inner boundaries to move (default all); the others stay, their interval computed
        about where they are.
    periods : tuple of float
        Periods (s) of a machine oscillation (:func:`change_profile`).
    tol : float
        Tolerance, s (:func:`change_profile`; 0: each moved change at the profile's mode).
    holds : Array of bool, optional
        Which stretches are holds (:func:`change_profile`'s ``held``).
    lag : float, optional
        The servo's position error per unit speed, s (:func:`change_profile`).

    Returns
    -------
    bounds : list of int
        The boundaries placed.
    placements : list of Placement
        One per inner boundary, its interval (NaN where the window was too small to judge).
    """
    rel = ou_parameters(scales, relative)
    ab = ou_parameters(scales, absolute)

    def place(j: int, lo: int, hi: int) -> Placement:
        """Change ``j`` (an index into ``bounds``) placed on the samples ``lo:hi``."""
        v1, v2 = float(velocity[j - 1]), float(velocity[j])
        stop = _relaxes(v1, v2, rel, sigma, lag)
        move = weak is None or bool(weak[j - 1])
        held = None if holds is None else bool(holds[j - 1] != holds[j])
        pl = change_profile(t, x, bounds[j], lo, hi, v1, v2, sigma, rel, ab, periods=periods,
                            move=move, stop=stop, tol=tol, held=held, lag=lag)
        if SEARCH_AGAIN and move and _search_again(pl, t, lo, hi, v1, v2):
            pl = change_profile(t, x, pl.index, lo, hi, v1, v2, sigma, rel, ab,
                                periods=periods, move=True, stop=stop, tol=tol, held=held,
                                lag=lag)
        if (FAR_STEPS and move and pl.far_step and np.isfinite(pl.lo)
                and not placed_at(pl, t, tol)[0]
                and straight_sides(t, x, pl.index, lo, hi)):
            far = change_profile(t, x, pl.index, lo, hi, v1, v2, sigma, rel, ab,
                                 periods=periods, move=True, stop=stop, tol=tol, held=held,
                                 lag=lag, far_step=True)
            pl = far_look(pl, far)
        if not lo < pl.index < hi:
            pl = Placement(bounds[j], pl.lo, pl.hi, pl.edge, pl.cells, pl.weights, pl.guess)
        return pl

    # the first window starts after bounds[0], which need not be the record's first sample:
    # a change placed again between its neighbours passes just those (detection's P_MOVE)
    out = [bounds[0] if OWN_START else 0]
    places: list[Placement] = []
    for j in range(1, len(bounds) - 1):
        start = _left_end(bounds, out, j)
        pl = place(j, start + m, bounds[j + 1] - m)
        if start != out[-1] and not pl.index > out[-1] + m:
            # placed before the previous change as placed (a window from its guess,
            # MOVED_INTO): that one placed again clear of this one, where its samples left
            # judge it; else this one placed after it, as without the rule (the order kept)
            prev = place(j - 1, _left_end(bounds, out, j - 1) + m, pl.index - m)
            if np.isfinite(prev.lo) and out[-2] < prev.index < pl.index - m:
                out[-1], places[-1] = prev.index, prev
            else:
                pl = place(j, out[-1] + m, bounds[j + 1] - m)
        out.append(pl.index)
        places.append(pl)
    out.append(bounds[-1])
    if NEIGHBOURS_PLACED:
        # no window reaches farther from its guess than this (change_profile's half-width
        # at its largest, and its search)
        reach = max(HOLD_HALF, HOLD_FAR, 60.0, 2.0 * max(periods, default=0.0)) + 5.0
        _clear_of_neighbours(bounds, out, places, m, place, t, reach)
    return out, places


def placed_at(pl: Placement, t: Array, tol: float, one: float | None = None
              ) -> tuple[bool, float]:
    """Whether the change ``pl`` is *placed* where it is reported, ``t[pl.index]`` (s), and
    the probability of that: its profile's probability (:func:`placed_probability`) of lying
    within the larger of its sample interval and ``tol`` (s) of that time; placed when that
    is at least :data:`.labsteps.PLACED_P` and the profile does not reach the end of the
    times searched (ours; the one rule for :class:`.labsteps.Segment`'s ``start_placed`` and
    for the placement's second looks). ``one``: the sample interval (s) at ``pl.index`` if
    already computed (:func:`sample_intervals`). A placement without an interval (NaN ``lo``:
    its window too small to judge) is not placed, with probability NaN; nor is one whose
    profile reaches the end of the times searched, its probability NaN too (over those times
    alone it would overstate it: an independent review's records read "not placed" beside a
    probability of 1.000)."""
    if not np.isfinite(pl.lo) or pl.edge:
        return False, float("nan")
    if one is None:
        one = float(sample_intervals(t, max(pl.index, 1))[0])
    p = placed_probability(pl, float(t[pl.index]), max(one, tol))
    return p >= PLACED_P, p


STRAIGHT_Z = 3.0
"""A stretch is straight out to :data:`HOLD_FAR` when the slopes of its samples within
:data:`HOLD_HALF` of the change and of those beyond differ by less than this many standard
errors (:func:`straight_sides`; ours; stop 49). Both a step's far look (:data:`FAR_STEPS`)
and a hold's far samples (:data:`HOLD_FAR`) need both stretches straight."""


def straight_sides(t: Array, x: Array, at: int, lo: int, hi: int) -> bool:
    """Whether both stretches about the change at sample ``at`` run straight out to
    :data:`HOLD_FAR` s: on each side (samples ``lo:at`` and ``at:hi``), the least-squares
    slope of the samples 5 to :data:`HOLD_HALF` s from the change and that of those from
    :data:`HOLD_HALF` to :data:`HOLD_FAR` s differ by less than :data:`STRAIGHT_Z` standard
    errors, each from its own residual scatter as if independent (ours; stop 49). A side with
    fewer than 10 samples in either part is straight (nothing to test it with).

    Why: the far samples (:data:`FAR_STEPS`, :data:`HOLD_FAR`) pin each stretch's line over
    300 s, and a speed change too small for the detector to split on bends it: on steps of
    ratio 1.3 at 0.2 um/s with a 3 % change 30 s after, the far samples put 29 of 30 changes
    off the tolerance where the near window alone put 18; on stops at 1 um/s with a 4 %
    change 30 s before, 12 of 30 off and 11 of those marked placed, where without far samples
    none was off (an independent review's family: 32 of 800 stops and restarts wrong and
    placed with stop 48's far samples, 9 without). Where the wander is red the independent
    standard errors are too small and the test says bent more often than it should: the far
    samples are then left out, as before them."""
    tc = float(t[at])
    for a, b, sign in ((lo, at, -1.0), (at, hi, 1.0)):
        tt, xx = np.asarray(t[a:b], float), np.asarray(x[a:b], float)
        d = sign * (tt - tc)
        fits = []
        for inner, outer in ((5.0, HOLD_HALF), (HOLD_HALF, HOLD_FAR)):
            k = (d >= inner) & (d < outer)
            if k.sum() < 10:
                break
            u = tt[k] - tt[k].mean()
            sxx = float(u @ u)
            if sxx <= 0.0:
                break
            slope = float(u @ (xx[k] - xx[k].mean())) / sxx
            res = xx[k] - xx[k].mean() - slope * u
            fits.append((slope, float(res @ res) / (k.sum() - 2) / sxx))
        if len(fits) == 2:
            (s1, v1), (s2, v2) = fits
            if abs(s1 - s2) > STRAIGHT_Z * np.sqrt(v1 + v2):
                return False
    return True


def far_look(near: Placement, far: Placement) -> Placement:
    """A step left not placed by its near window, placed again with its stretches' far samples
    (:data:`FAR_STEPS`): the far look's sample, the union of the two 95 % intervals, and the
    near window's profile, by which the change is judged placed or not (ours; stop 49).

    Why the near profile: the far samples pin each stretch's line over 300 s, and a speed
    change too small for the detector to split on (a few per cent, a servo's drift) within a
    minute of the step bends that line: an independent review's steps with a 2 % change 30 s
    away were placed 2 s off with an interval 2 s wide and probability 1 by the far samples,
    where the near window alone gave 6 s holding the truth and left them not placed. The far
    look moves the change; it does not make it placed."""
    if not np.isfinite(far.lo):
        return near
    return Placement(far.index, min(near.lo, far.lo), max(near.hi, far.hi),
                     near.edge or far.edge, near.cells, near.weights, near.guess)


OWN_START = True
"""Whether :func:`place_changes` starts the first window after ``bounds[0]`` (ours; a fix).
Before, it started after sample 0 whatever ``bounds[0]`` was, and a change placed again
between its neighbours (:data:`.detection.P_MOVE`: ``bounds`` the three of them) was searched
on a window reaching back across the change before it, which the hinge's two velocities do
not hold: zoo 22016, a down-step 37 s after an up-step, sampled at 1 Hz, was moved from the
right sample to 4.6 s late, its profile flat over 8 s."""

SEARCH_AGAIN = True
"""Whether a change whose profile is cut by the times searched, its best time within
:data:`SEARCH_END` of their end, is placed once more with the search about that time
(:func:`_search_again`; ours; branch stepfix).

Why: the change is looked for within ``search`` (5 s) of the whole stretches' guess, and the
guess of a step under a large servo error (a measured position error of 1.5-2.8 s per unit
speed) can lie farther than that from the change: zoo 336, 11281 and 11293 (ratio 3 and 2,
guesses 8.1, 13.9 and 5.9 s off) were placed at the end of the times searched, 2.1-6.4
tolerances off, the profile giving the truth ``start_p`` 0.000. A profile cut by the search
with its best at the end says the likelihood still rises beyond it, and a search about that
best reaches the change (within the tolerance, all three). Not at a reversal between two
moving speeds: the zoo commands none, and the one the detector read (zoo 9000, a 4-s
stretch at -35 um/s between two of +4.5 and +5.6) was moved 10 s and split the record's count.
Measured on the zoo's used ranges: docs/performance.md (stepfix)."""
SEARCH_END = 1.0
"""How near the end of the times searched (s) the best time of a cut profile must lie to be
searched again (:data:`SEARCH_AGAIN`; ours: two tolerances, :data:`.detection.PLACE_TOL`)."""


def _search_again(pl: Placement, t: Array, lo: int, hi: int, v1: float, v2: float) -> bool:
    """Whether the change placed at ``pl`` (on the samples ``lo:hi`` of the times ``t``, s, from
    ``v1`` to ``v2``, m/s) is searched again about its place (:data:`SEARCH_AGAIN`): its
    profile is cut by the times searched (``pl.edge``), its best time within
    :data:`SEARCH_END` of their first or last (``pl.cells``), and it is no reversal between
    two moving speeds (the slower above :data:`HOLD_RATIO` of the faster)."""
    slow, fast = sorted((abs(v1), abs(v2)))
    if v1 * v2 < 0.0 and slow > HOLD_RATIO * fast:
        return False
    if not (pl.edge and pl.cells is not None and lo < pl.index < hi):
        return False
    ta = float(t[pl.index])
    return min(ta - float(pl.cells[0]), float(pl.cells[-1]) - ta) <= SEARCH_END


MOVED_INTO = 0.5
"""A change placed more than this share of the stretch after its guess into that stretch
(towards the next change) does not bound the next change's window, which starts after the
first one's guess instead (:func:`_left_end`; ours; ``0``: off).

Why: the changes are placed in order, each window running to the next change's *guess*. In a
slide-hold-slide sampled at 100-500 Hz, a hold's end found 0.3-0.7 s late (a servo's ringing
after the restart) puts the re-slide's first samples in the stop's window; the hinge under the
wander's model, which scales the wander after the stop by the hold's slow speed, is ruled by
those few fast samples and put the stop by the hold's end, 4-5 s late, with an interval of
hundredths of a second (placed, probability 1.00). The re-slide, its window then starting
there, could not be placed before its guess, so :func:`_clear_of_neighbours` did not place
the stop again: the hold was read as a 0.5-s slow stretch, or lost (an independent review's
records, 30 um/s, 5-s holds, 100 Hz: 22 of 30 right; 29 of 30 with this rule). Where the
re-slide's window starts after the stop's guess it finds the restart, and the stop is placed
again clear of it. Half the stretch: a change's own placement moves it within its
uncertainty, seconds at most, not across most of the stretch the search found after it.

The order is kept (a second review's stub placements): where the change is placed before
the first one as placed, the first one is placed again clear of it, and kept there only if
it still lies after its own previous neighbour; else the change is placed after it, as
without the rule; a second look of :func:`_clear_of_neighbours` is taken only after the
previous change as placed."""


def _left_end(guess: list[int], out: list[int], j: int) -> int:
    """Where change ``j``'s window may start: after its previous neighbour as placed
    (``out[j - 1]``), or after that neighbour's guess where its placement moved it more than
    :data:`MOVED_INTO` of the stretch between their guesses towards change ``j``."""
    if (MOVED_INTO and j > 1
            and out[j - 1] - guess[j - 1] > MOVED_INTO * (guess[j] - guess[j - 1])):
        return guess[j - 1]
    return out[j - 1]


NEIGHBOURS_PLACED = True
"""Whether a change whose window held samples at or past where its next neighbour was then
placed is placed again, its window ending before that neighbour (:func:`_clear_of_neighbours`;
ours)."""


def _clear_of_neighbours(guess: list[int], out: list[int], places: list[Placement], m: int,
                         place: Callable[[int, int, int], Placement], t: Array,
                         reach: float) -> None:
    """Each change (in ``out``, placed in order) whose window, which ended ``m`` samples
    before its next neighbour's *guess* (``guess``), held samples at or past where that
    neighbour was then placed, placed again by ``place(j, lo, hi)`` on the samples clear of
    its neighbours as placed (its start as :func:`_left_end` gives it; ``out`` and ``places``
    updated in place), from the last to the
    first; a neighbour placed more than ``reach`` (s) after the change's guess (times ``t``,
    s) was beyond its window.

    Why (ours): the changes are placed in order, so a change's window runs to the next one's
    guess, not to where it lies; a guess late by more than ``m`` samples puts samples of the
    next stretch in the window, at a velocity the hinge's two-velocity model does not hold.
    Where that stretch is fast and the window's other side slow (a stop before a short hold:
    a restart's slip of a few tenths of a micrometre against nanometres of noise in a
    velocity column's integral) the hinge's likelihood is ruled by those few samples (zoo
    records 4204 and 7264: hold starts placed 5.3 and 4.7 s late, at the end of the times
    searched; within the tolerance placed again). Only where the window did reach the
    neighbour as placed: placed again wherever the neighbour moved earlier at all, a short
    step's start whose window had ended before it (zoo 6254) moved from 0.33 to 0.59 s off.
    """
    for j in range(len(out) - 2, 0, -1):
        lo, hi = _left_end(guess, out, j) + m, out[j + 1] - m
        # the window held samples at or past the neighbour as placed; kept where the samples
        # left are too few to judge (no interval) or the change would leave them
        if (guess[j + 1] - m > out[j + 1] and lo < guess[j] < hi
                and t[out[j + 1]] - t[guess[j]] < reach):
            pl = place(j, lo, hi)
            # (and after the previous change as placed: a window from its guess, MOVED_INTO,
            # may reach before it)
            if np.isfinite(pl.lo) and max(lo, out[j - 1] + m) < pl.index < hi:
                out[j], places[j - 1] = pl.index, pl
