"""The event catalogue of an extended interface, its precursor curve and its magnitude-frequency
distribution, from the events of :mod:`dryfriction.analysis.fronts`.

* **Catalogue**: one row per event, written with headers ``name[unit]`` (units from the
  fields': e.g. ``t_start[t0]``, ``extent[a0]``, ``moment[a0^2]``; ``[1]`` a pure number, an
  index or a flag 0/1). :func:`catalogue_columns` gives the columns and their units;
  ``dryfriction.io.files.write_csv`` writes them.
* **Precursors** (Rubinstein, Cohen & Fineberg, PRL 98, 226103, 2007: under side loading, fronts
  from the loaded edge arrest at lengths that grow with the applied shear before the
  system-spanning slip): each arrested event's extent against the load-to-normal ratio
  ``load(t_arrest) / normal_load`` at its arrest time (the last arrival, the tips' stop),
  the load linearly interpolated between samples. An event cut by the record's first or last
  sample is left out (it may not have arrested). Optionally (``triggered=True``) only the
  events triggered by the loading are kept: those that start at a load above the start load
  of every earlier event from the loaded edge, so that the small re-slips next to the edge
  that follow a precursor while the load is still below the level it had dropped from
  (aftershocks) are left out (ours).
* **Trend** of the precursors (do they arrest at lengths that
  grow with the applied shear?): Spearman's rank correlation ``rho`` of length against ratio and
  its two-sided p-value (``scipy.stats.spearmanr``). The answer is ``"yes"`` (they grow) when
  ``rho > 0`` and ``p < TREND_LEVEL``, ``"decreasing"`` when ``rho < 0`` and ``p <
  TREND_LEVEL``, ``"not significant"`` otherwise, and ``"undetermined"`` with fewer than 3
  precursors (or a constant length or ratio).
* **Front regimes** (part 5: slow fronts): each front's mean speed against the sound speed
  ``c_s`` of the chain, classified by its whole 95 % interval (:data:`SLOW_FRACTION`).
* **Magnitude-frequency**: the number ``N(>= M)`` of events of moment at least ``M``
  (complementary cumulative count), and the exponent of a power law ``p(M) ~ M^-alpha`` above
  ``M_min`` by maximum likelihood, ``alpha = 1 + n / sum ln(M_i / M_min)`` with standard error
  ``(alpha - 1)/sqrt(n)`` (Clauset, Shalizi & Newman, SIAM Rev. 51, 661, 2009, eqs. 3.1 and 3.2);
  ``N(>= M) ~ M^-(alpha - 1)``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..validation import Array, check_choice, check_scalar
from .fronts import Event, SpaceTime, moment_unit, speed_unit

__all__ = ["catalogue_columns", "Precursors", "precursors", "MagnitudeFrequency",
           "magnitude_frequency", "Trend", "precursor_trend", "FrontRegimes", "front_regimes",
           "SLOW_FRACTION", "TREND_LEVEL"]

SLOW_FRACTION = 0.1
"""A front is *slow* when its whole 95 % speed interval lies below this fraction of the sound
speed, *fast* when the whole interval lies above (ours: Rubinstein, Cohen & Fineberg, Nature
430, 1005, 2004, saw slow fronts an order of magnitude below the Rayleigh speed)."""

TREND_LEVEL = 0.05
"""Largest p-value of the rank correlation for which the precursor lengths are said to grow."""


def catalogue_columns(events: Sequence[Event], st: SpaceTime, threshold: float
                      ) -> tuple[dict[str, Array], dict[str, str]]:
    """The catalogue as columns (bare name -> values, one row per event) and their units
    (name -> unit, for ``dryfriction.io.files.write_csv``, which writes ``name[unit]``).

    Columns: ``event`` (index) [1], ``t_start``, ``t_arrest``, ``t_end``, ``duration`` [time],
    ``x_nucleation``, ``x_min``, ``x_max``, ``extent`` [length], ``n_elements`` [1],
    ``mean_slip`` [slip], ``moment`` [slip x length], ``spanning`` [1] (1 system-spanning, 0
    arrested), ``cut`` [1] (1: the event touches the record's first or last sample, so its
    duration, extent and slip are lower bounds), ``speed_left``/``speed_right`` with their 95 %
    bounds ``_low``/``_high`` [length/time] (mean speed of each front; NaN for a front of fewer
    than 3 elements, an upper bound ``inf`` when the fit cannot exclude an instantaneous front),
    the load at start and arrest [load unit] when the fields have a load, and ``threshold``
    [slip-rate unit], the slip-rate threshold the events were found with.
    """
    u = st.units
    T, L, V = u["t"], u["x"], speed_unit(u)
    cols: dict[str, Array] = {}
    units: dict[str, str] = {}

    def put(name: str, unit: str, values: list[float]) -> None:
        cols[name] = np.asarray(values)
        units[name] = unit

    put("event", "1 (index)", [e.index for e in events])
    for name in ("t_start", "t_arrest", "t_end"):
        put(name, T, [getattr(e, name) for e in events])
    put("duration", T, [e.duration for e in events])
    for name in ("x_nucleation", "x_min", "x_max", "extent"):
        put(name, L, [getattr(e, name) for e in events])
    put("n_elements", "1", [e.n_elements for e in events])
    put("mean_slip", u["slip"], [e.mean_slip for e in events])
    put("moment", moment_unit(u), [e.moment for e in events])
    put("spanning", "1 (1 system-spanning, 0 arrested)", [int(e.spanning) for e in events])
    put("cut", "1 (1 cut by the record's ends)", [int(e.cut) for e in events])
    for side, k in (("left", 0), ("right", 1)):
        put(f"speed_{side}", V, [e.fronts[k].mean_speed for e in events])
        put(f"speed_{side}_low", V, [e.fronts[k].mean_speed_low for e in events])
        put(f"speed_{side}_high", V, [e.fronts[k].mean_speed_high for e in events])
    if st.load is not None:
        put("load_start", u["load"], [e.load_start for e in events])
        put("load_arrest", u["load"], [e.load_arrest for e in events])
    put("threshold", u["slip_rate"], [float(threshold)] * len(events))
    return cols, units


@dataclass(frozen=True)
class Precursors:
    """The precursor curve (module doc).

    Attributes
    ----------
    ratio, length, t_arrest : ndarray
        Load-to-normal ratio [1] at each arrested event's arrest, its extent [length unit] and
        arrest time [time unit], in order of arrest.
    events : ndarray of int
        Their indices in the catalogue.
    spanning_ratio, spanning_t : ndarray
        Ratio and time at the start of each system-spanning event (the global slips).
    """

    ratio: Array
    length: Array
    t_arrest: Array
    events: np.ndarray
    spanning_ratio: Array
    spanning_t: Array


def precursors(events: Sequence[Event], st: SpaceTime, normal_load: float, *,
               edge: str | None = None, edge_gap: int = 0,
               after: float | None = None, triggered: bool = False) -> Precursors:
    """Arrested-front lengths against the load-to-normal ratio at their arrest (module doc).

    Parameters
    ----------
    events : sequence of Event
        From :func:`~dryfriction.analysis.fronts.detect_events` on ``st``.
    st : SpaceTime
        The fields; they must hold the load.
    normal_load : float
        The normal load, in the load's unit (> 0).
    edge : {"left", "right"}, optional
        The loaded edge of a side-loaded interface: keep only the events that reach within
        ``edge_gap`` elements of the first ("left") or last ("right") element, and measure
        each length from that edge of the interface to the far end of the event (the arrest
        position; the event's extent when it includes the edge element). Without ``edge``,
        every arrested event, its length its extent.
    edge_gap : int
        Elements between the edge and an event's near end that may stay below the threshold
        (>= 0): the loaded block can creep slower than the threshold while the events start
        next to it.
    after : float, optional
        Leave out the events that start before this time [time unit] (an initial transient).
    triggered : bool
        Keep only the events that start at a load above the start load of every earlier event
        that reaches the edge (those before ``after`` included; without ``edge``, every earlier
        event): each precursor needs the
        load to rise past where the last one started; a re-slip at a lower load, after the
        drop of the event before, is left out (module doc).

    Returns
    -------
    Precursors
    """
    if st.load is None:
        raise ValueError("the precursor curve needs the load: give load to space_time")
    normal = check_scalar("normal_load", normal_load, 0.0, lo_open=True)
    if edge is not None:
        check_choice("edge", edge, ("left", "right"))
    if int(edge_gap) != edge_gap or edge_gap < 0:
        raise ValueError(f"edge_gap = {edge_gap!r} is out of range: a whole number >= 0")
    n_x = st.x.size
    start = -math.inf if after is None else check_scalar("after", after)
    events = list(events)

    def touches(e: Event) -> bool:
        if edge is None:
            return True
        if edge == "left":
            return bool(e.elements[0] <= edge_gap)
        return bool(e.elements[-1] >= n_x - 1 - edge_gap)

    def length(e: Event) -> float:
        if edge is None:
            return e.extent
        # from the interface's edge to the far end of the event: the elements' lengths
        span = (slice(0, e.elements[-1] + 1) if edge == "left"
                else slice(e.elements[0], n_x))
        return float(np.sum(st.lengths[span]))

    kept = {e.index for e in events}
    if triggered:  # a new load maximum at the start among the edge's events (module doc)
        peak, kept = -math.inf, set()
        for e in sorted((e for e in events if touches(e)), key=lambda e: e.t_start):
            if e.load_start > peak:
                kept.add(e.index)
            peak = max(peak, e.load_start)
    events = [e for e in events if e.t_start >= start]
    # an event cut by the record's end may still be growing: not known to have arrested
    arrested = sorted((e for e in events
                       if not (e.spanning or e.cut) and touches(e) and e.index in kept),
                      key=lambda e: e.t_arrest)
    spanning = [e for e in events if e.spanning]
    return Precursors(
        ratio=np.array([e.load_arrest / normal for e in arrested]),
        length=np.array([length(e) for e in arrested]),
        t_arrest=np.array([e.t_arrest for e in arrested]),
        events=np.array([e.index for e in arrested], dtype=int),
        spanning_ratio=np.array([e.load_start / normal for e in spanning]),
        spanning_t=np.array([e.t_start for e in spanning]),
    )


@dataclass(frozen=True)
class MagnitudeFrequency:
    """Complementary cumulative count of the moments and a power-law fit (module doc).

    Attributes
    ----------
    moment : ndarray
        The moments in decreasing order [moment unit].
    count : ndarray
        ``N(>= moment)``: 1, 2, ... (ties share the largest count).
    m_min : float
        Smallest moment of the fit.
    alpha, alpha_err : float
        Exponent of ``p(M) ~ M^-alpha`` and its standard error; NaN with fewer than 2 moments
        above ``m_min`` or all equal.
    n_fit : int
        Number of moments in the fit.
    """

    moment: Array
    count: Array
    m_min: float
    alpha: float
    alpha_err: float
    n_fit: int


def magnitude_frequency(moments: ArrayLike, m_min: float | None = None) -> MagnitudeFrequency:
    """The magnitude-frequency distribution of event moments (module doc).

    Parameters
    ----------
    moments : array_like
        Moments of the events (> 0; events with zero or negative slip are dropped from the
        fit only).
    m_min : float, optional
        Lower end of the power-law fit (default: the smallest positive moment).

    Returns
    -------
    MagnitudeFrequency
    """
    m = np.asarray(moments, dtype=float)
    if m.ndim != 1:
        raise ValueError(f"moments must be one-dimensional, got shape {m.shape}")
    if not np.all(np.isfinite(m)):
        raise ValueError("moments must be finite: they hold NaN or infinity")
    desc = np.sort(m)[::-1]
    # N(>= M): the position of the last element equal to M in the decreasing order
    count = np.searchsorted(-desc, -desc, side="right").astype(float)
    positive = m[m > 0]
    if m_min is None:
        lo = float(positive.min()) if positive.size else math.nan
    else:
        lo = check_scalar("m_min", m_min, 0.0, lo_open=True)
    fit = positive[positive >= lo] if math.isfinite(lo) else positive[:0]
    logs = np.log(fit / lo) if fit.size else fit
    if fit.size >= 2 and logs.sum() > 0:
        alpha = 1.0 + fit.size / float(logs.sum())
        err = (alpha - 1.0) / math.sqrt(fit.size)
    else:
        alpha = err = math.nan
    return MagnitudeFrequency(moment=desc, count=count, m_min=lo, alpha=alpha, alpha_err=err,
                              n_fit=int(fit.size))


@dataclass(frozen=True)
class Trend:
    """Rank correlation of precursor length with the load ratio (module doc): ``rho``,
    ``p_value`` (NaN with fewer than 3 points or a constant series), ``n`` points, and the
    answer ``grows``: ``"yes"``, ``"decreasing"``, ``"not significant"`` or
    ``"undetermined"``."""

    rho: float
    p_value: float
    n: int
    grows: str


def precursor_trend(pre: Precursors) -> Trend:
    """Whether the arrested-front lengths grow with the load ratio (module doc)."""
    from scipy.stats import spearmanr

    n = int(pre.length.size)
    if n < 3 or np.ptp(pre.length) == 0 or np.ptp(pre.ratio) == 0:
        return Trend(math.nan, math.nan, n, "undetermined")
    res = spearmanr(pre.ratio, pre.length)
    rho, p = float(res.statistic), float(res.pvalue)
    if not p < TREND_LEVEL:
        return Trend(rho, p, n, "not significant")
    return Trend(rho, p, n, "yes" if rho > 0 else "decreasing")


@dataclass(frozen=True)
class FrontRegimes:
    """Fronts classified against the sound speed (module doc).

    Attributes
    ----------
    event, direction : ndarray of int
        The event index and direction of each front with a speed (3 elements or more).
    ratio, ratio_low, ratio_high : ndarray
        Mean speed and its 95 % interval over the sound speed [1].
    regime : list of str
        ``"slow"``, ``"fast"`` or ``"undetermined"`` (the interval straddles the fraction).
    fraction : float
        The fraction of the sound speed that separates them.
    """

    event: np.ndarray
    direction: np.ndarray
    ratio: Array
    ratio_low: Array
    ratio_high: Array
    regime: list[str]
    fraction: float

    def count(self, regime: str) -> int:
        """Number of fronts of that regime."""
        return sum(r == regime for r in self.regime)


def front_regimes(events: Sequence[Event], sound_speed: float,
                  fraction: float = SLOW_FRACTION) -> FrontRegimes:
    """Slow and fast fronts: each front's mean speed over ``sound_speed`` (same unit as the
    speeds, > 0), slow or fast by its whole 95 % interval (module doc)."""
    c = check_scalar("sound_speed", sound_speed, 0.0, lo_open=True)
    frac = check_scalar("fraction", fraction, 0.0, 1.0, lo_open=True)
    rows = [(e.index, f.direction, f.mean_speed / c, f.mean_speed_low / c,
             f.mean_speed_high / c) for e in events for f in e.fronts
            if math.isfinite(f.mean_speed)]
    ev, dr, r, lo, hi = (np.array(col) for col in zip(*rows, strict=True)) if rows else (
        np.array([], int), np.array([], int), np.array([]), np.array([]), np.array([]))
    regime = ["slow" if h < frac else "fast" if lo_ > frac else "undetermined"
              for lo_, h in zip(lo, hi, strict=True)]
    return FrontRegimes(event=ev.astype(int), direction=dr.astype(int), ratio=r, ratio_low=lo,
                        ratio_high=hi, regime=regime, fraction=frac)
