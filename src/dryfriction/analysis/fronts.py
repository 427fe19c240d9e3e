"""Rupture fronts and slip events of an extended interface, read from its space-time fields.
Every definition here is ours unless a reference is cited.

The input is the fields of a run of N elements at positions ``x`` sampled at times ``t``:
slip rate ``v[j, i]`` and slip ``s[j, i]`` of element ``i`` at time ``t[j]`` (and optionally the
applied load against time). The analysis works in whatever units the fields are in and names
them from ``units`` (reduced units of the trap model by default: lengths ``a0``, times ``t0``).

Slipping, events and fronts
---------------------------
* **Slipping.** Element ``i`` slips at sample ``j`` when ``v[j, i] > threshold``: the threshold is
  on the *slip rate*, in the slip rate's unit (``a0/t0`` in reduced units), and must be > 0.
  A sensible choice is a few times the loading velocity (the top plate's or the loaded edge's):
  above the creep of the stuck interface, far below the slip rate of a front.
* **Event.** A connected set of slipping samples in the (time, element) plane, neighbours
  including the diagonals (8-connectivity: a front that moves one element per sample stays one
  event). The fields must therefore be sampled finer than the time a front takes to cross one
  element, or a fast front breaks into pieces. The elements an event touches form one interval
  (each connection moves at most one element), so its **extent** is the summed length of those
  elements; ``min_elements`` drops smaller events.
* **Arrival time** ``T_i`` of the event at element ``i``: the first time ``v`` crosses the
  threshold upwards, linearly interpolated between the last sample below and the first above
  (sub-sample precision; at the record's first sample, that sample's time). The **end** of the
  event at element ``i`` is the downward crossing, interpolated the same way.
* **Nucleation**: the element with the earliest arrival time (the middle one of several reached
  at the same time); ``t_start`` is that time. The
  event's ``t_end`` is its last downward crossing, ``duration = t_end - t_start``; its
  ``t_arrest`` is the last arrival time (when the tips stopped advancing).
* **Slip of the event** at element ``i``: ``s`` at the first sample after the element stopped
  minus ``s`` at the last sample before it started (the ramps included). **Moment** (ours, the
  potency per unit width of a 1D fault): ``M = sum_i ds_i l_i`` with ``l_i`` the element lengths,
  in slip unit x length unit (``a0^2``); times the shear modulus and the fault's width it is
  the seismic moment. **Mean slip** ``M / extent`` (the length-weighted mean).
* **System-spanning**: every element slipped in the event; otherwise **arrested**. An event that
  touches the first or last sample of the record is **cut**: its duration, extent and slip are
  lower bounds.
* **Fronts**: two per event, one in each direction from the nucleation element (``+1`` towards
  growing ``x``, ``-1`` towards decreasing ``x``), each the arrival times of the elements on that
  side, nucleation element included. The **tip** against time is the running extreme of the
  reached positions. The **front speed** at an element is ``1/|dT/dx|`` from a Theil-Sen fit
  (the median of the pairwise slopes, robust to a few outliers; Sen, JASA 63, 1379, 1968) of
  ``T`` against ``x`` over the ``2 h + 1`` elements around it, with the 95 % interval of the
  slope (``scipy.stats.theilslopes``) turned into an interval of the speed (an interval of the
  slowness that reaches zero gives an infinite upper speed). The **mean speed** of a front is
  the same fit over all its elements.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..validation import Array, check_memory, check_scalar

__all__ = [
    "DEFAULT_UNITS",
    "SpaceTime",
    "Front",
    "Event",
    "space_time",
    "from_result",
    "interface_normal_load",
    "interface_loaded_edge",
    "interface_sound_speed",
    "THRESHOLD_FACTOR",
    "default_threshold",
    "check_threshold",
    "event_threshold",
    "element_lengths",
    "slipping",
    "detect_events",
    "front_speeds",
    "speed_unit",
    "moment_unit",
]

DEFAULT_UNITS: dict[str, str] = {"t": "t0", "x": "a0", "slip": "a0", "slip_rate": "a0/t0",
                                 "load": "F_el"}
"""Units of the fields when none are given: the trap model's reduced units (lengths ``a0``,
times ``t0``, forces ``F_el``)."""

CONFIDENCE = 0.95
"""Confidence level of the speed intervals (Theil-Sen's slope interval)."""


@dataclass(frozen=True)
class SpaceTime:
    """Checked space-time fields of one run (build it with :func:`space_time`).

    Attributes
    ----------
    t : ndarray, shape (n_t,)
        Sample times, strictly increasing [``units['t']``].
    x : ndarray, shape (N,)
        Element positions, strictly increasing [``units['x']``].
    slip_rate, slip : ndarray, shape (n_t, N)
        Slip rate [``units['slip_rate']``] and slip [``units['slip']``] of each element.
    load : ndarray, shape (n_t,), or None
        Applied load (top-plate displacement or edge-spring force) [``units['load']``].
    lengths : ndarray, shape (N,)
        Element lengths [``units['x']``] (:func:`element_lengths`).
    units : dict
        Unit of each field by name (``t``, ``x``, ``slip``, ``slip_rate``, ``load``).
    """

    t: Array
    x: Array
    slip_rate: Array
    slip: Array
    load: Array | None
    lengths: Array
    units: dict[str, str]

    @property
    def shape(self) -> tuple[int, int]:
        """(n_t, N)."""
        return (self.t.size, self.x.size)


def _vector(name: str, value: ArrayLike, smallest: int) -> Array:
    a = np.asarray(value, dtype=float)
    if a.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {a.shape}")
    if a.size < smallest:
        raise ValueError(f"{name} is empty or too short: needs at least {smallest} values, "
                         f"got {a.size}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite: it holds NaN or infinity")
    if a.size > 1 and not np.all(np.diff(a) > 0):
        raise ValueError(f"{name} must be strictly increasing")
    return a


def _field(name: str, value: ArrayLike, shape: tuple[int, int]) -> Array:
    a = np.asarray(value, dtype=float)
    if a.shape != shape:
        raise ValueError(f"{name} has shape {a.shape}, but (len(t), len(x)) = {shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite: it holds NaN or infinity")
    return a


def element_lengths(x: ArrayLike, element_length: float | None = None) -> Array:
    """Length of each element [unit of ``x``]: the cell of the points nearer to it than to its
    neighbours (half-way to each neighbour; an end cell mirrors its one neighbour's spacing),
    or ``element_length`` for every element when given (needed for a single element).

    On a uniform grid every element gets the spacing ``dx``.
    """
    x = _vector("x", x, 1)
    if element_length is not None:
        length = check_scalar("element_length", element_length, 0.0, lo_open=True)
        return np.full(x.size, length)
    if x.size == 1:
        raise ValueError("element_length is needed for a single element (x has one position): "
                         "give it, > 0")
    gaps = np.diff(x)
    left = np.concatenate([[gaps[0]], gaps])
    right = np.concatenate([gaps, [gaps[-1]]])
    return 0.5 * (left + right)


def space_time(t: ArrayLike, x: ArrayLike, slip_rate: ArrayLike, slip: ArrayLike | None = None,
               load: ArrayLike | None = None, units: Mapping[str, str] | None = None, *,
               element_length: float | None = None) -> SpaceTime:
    """Check the fields of a run and bundle them (one ``ValueError`` line on bad input).

    Parameters
    ----------
    t : array_like, shape (n_t,)
        Sample times, strictly increasing, at least 2.
    x : array_like, shape (N,)
        Element positions, strictly increasing, at least 1.
    slip_rate : array_like, shape (n_t, N)
        Slip rate of each element at each time.
    slip : array_like, shape (n_t, N), optional
        Slip of each element; when omitted it is the trapezoidal integral of ``slip_rate``
        from zero at ``t[0]``.
    load : array_like, shape (n_t,), optional
        Applied load against time (needed for the precursor curve).
    units : mapping, optional
        Unit by field name; missing names take :data:`DEFAULT_UNITS`.
    element_length : float, optional
        Length of every element [unit of ``x``] (default: from the spacing of ``x``).

    Returns
    -------
    SpaceTime
    """
    t = _vector("t", t, 2)
    x = _vector("x", x, 1)
    shape = (t.size, x.size)
    rate = _field("slip_rate", slip_rate, shape)
    if slip is None:
        steps = 0.5 * (rate[1:] + rate[:-1]) * np.diff(t)[:, None]
        s = np.concatenate([np.zeros((1, x.size)), np.cumsum(steps, axis=0)])
    else:
        s = _field("slip", slip, shape)
    ld = None
    if load is not None:
        ld = np.asarray(load, dtype=float)
        if ld.shape != (t.size,):
            raise ValueError(f"load has shape {ld.shape}, but len(t) = {t.size}")
        if not np.all(np.isfinite(ld)):
            raise ValueError("load must be finite: it holds NaN or infinity")
    merged = dict(DEFAULT_UNITS)
    merged.update({str(k): str(v) for k, v in (units or {}).items()})
    return SpaceTime(t=t, x=x, slip_rate=rate, slip=s, load=ld,
                     lengths=element_lengths(x, element_length), units=merged)


def _short_unit(unit: str) -> str:
    """A unit without its parenthesised remark (``"F_el per element (sum over ...)"`` ->
    ``"F_el per element"``), for a header ``name[unit]``."""
    return unit.split(" (", 1)[0].strip()


def from_result(result: Any, *, element_length: float | None = None) -> SpaceTime:
    """:func:`space_time` of a result with attributes ``t``, ``x``, ``slip_rate``, ``slip`` and
    optionally ``load`` and ``units``: the interface simulator's
    :class:`~dryfriction.ensemble.interface_result.InterfaceResult` (positions in element
    spacings, ``element``: each element is 1 long unless ``element_length`` says otherwise).
    """
    units = {k: _short_unit(str(v)) for k, v in (getattr(result, "units", None) or {}).items()}
    if element_length is None and units.get("x") == "element":
        element_length = 1.0
    return space_time(result.t, result.x, result.slip_rate, getattr(result, "slip", None),
                      getattr(result, "load", None), units, element_length=element_length)


def interface_normal_load(result: Any) -> float:
    """Total normal load of an interface run in its load unit, ``N F_el / mu_el``: each element
    carries ``W = F_el / mu_el`` (``mu_el = F_el/W``, docs/model.md), so ``load / normal`` is the
    applied shear as a friction coefficient, ``mu_el load / (N F_el)``."""
    mu_el = float(result.params.get("model", {}).get("mu_el", 1.0))
    return float(np.asarray(result.x).size) / mu_el


def interface_loaded_edge(result: Any) -> str | None:
    """``"left"`` for a side-loaded run (block 0 carries the edge spring), ``None`` for uniform
    loading."""
    return "left" if result.params.get("drive", {}).get("loading") == "side" else None


def interface_sound_speed(result: Any) -> float:
    """The chain's long-wave speed ``sqrt(k_c / m)`` [element/t0] from the run's parameters
    (NaN without coupling or mass)."""
    p = result.params.get("interface", {})
    k, m = float(p.get("coupling", math.nan)), float(p.get("mass", math.nan))
    return math.sqrt(k / m) if k >= 0 and m > 0 else math.nan


def speed_unit(units: Mapping[str, str]) -> str:
    """Unit of a front speed: length unit / time unit."""
    return f"{units['x']}/{units['t']}"


def moment_unit(units: Mapping[str, str]) -> str:
    """Unit of the moment: slip unit x length unit (``a0^2`` when both are ``a0``)."""
    return f"{units['x']}^2" if units["slip"] == units["x"] else f"{units['slip']}*{units['x']}"


THRESHOLD_FACTOR = 10.0
"""Default slip-rate threshold of an interface run, in multiples of the largest loading
velocity of its program (ours: above the creep of a stuck interface, which stays below the
loading velocity on average, and far below the slip rate inside a front)."""


def default_threshold(result: Any) -> float:
    """:data:`THRESHOLD_FACTOR` times the largest velocity of the run's loading program
    (``params['drive']['segments']``) [slip-rate unit]; NaN where the program has none."""
    segments = result.params.get("drive", {}).get("segments", [])
    speeds = [abs(float(s["velocity"])) for s in segments if s.get("velocity") is not None]
    top = max(speeds, default=0.0)
    return THRESHOLD_FACTOR * top if top > 0 else math.nan


def check_threshold(threshold: float, unit: str = DEFAULT_UNITS["slip_rate"]) -> float:
    """``threshold`` as a float, or one ``ValueError`` line: a slip rate, finite and > 0."""
    return _threshold(threshold, {"slip_rate": unit})


def event_threshold(result: Any, threshold: float | None = None) -> float:
    """The slip-rate threshold events of ``result`` are found with: ``threshold`` as given, or
    :func:`default_threshold` when ``None``; checked by :func:`check_threshold` in the run's
    slip-rate unit (one ``ValueError`` line). What ``simulate`` and an interface sweep use
    alike, so that both find the same events."""
    thr = default_threshold(result) if threshold is None else threshold
    return check_threshold(thr, result.units.get("slip_rate", DEFAULT_UNITS["slip_rate"]))


def _threshold(threshold: float, units: Mapping[str, str]) -> float:
    try:
        return check_scalar("threshold", threshold, 0.0, lo_open=True)
    except ValueError:
        raise ValueError(f"threshold = {threshold!r} is out of range: the slip-rate threshold "
                         f"must be finite and > 0 [{units['slip_rate']}]") from None


def slipping(st: SpaceTime, threshold: float) -> np.ndarray:
    """Boolean (n_t, N) map of the slipping samples: ``slip_rate > threshold`` (module doc).

    ``threshold`` is a slip rate [``st.units['slip_rate']``], > 0.
    """
    return st.slip_rate > _threshold(threshold, st.units)


@dataclass(frozen=True)
class Front:
    """One rupture front: the arrival of an event at the elements on one side of its nucleation.

    Attributes
    ----------
    direction : int
        ``+1`` towards growing ``x``, ``-1`` towards decreasing ``x``.
    x : ndarray
        Positions reached, from the nucleation element outwards [length unit].
    t : ndarray
        Arrival time at each of them [time unit].
    speed, speed_low, speed_high : ndarray
        Local front speed at each position and its 95 % interval [length/time]; NaN where the
        window holds fewer than 3 elements or the arrivals run back towards the nucleation,
        ``inf`` where they are simultaneous.
    mean_speed, mean_speed_low, mean_speed_high : float
        Speed fitted over the whole front and its 95 % interval; NaN for fewer than 3 elements.
    """

    direction: int
    x: Array
    t: Array
    speed: Array
    speed_low: Array
    speed_high: Array
    mean_speed: float
    mean_speed_low: float
    mean_speed_high: float

    @property
    def length(self) -> float:
        """Distance from the nucleation element to the farthest element reached."""
        return float(np.max(np.abs(self.x - self.x[0]))) if self.x.size else 0.0

    def tip(self) -> tuple[Array, Array]:
        """Tip position against time: arrival times sorted, and the farthest position reached
        by each of them (running maximum along ``direction``)."""
        order = np.argsort(self.t, kind="stable")
        reach = np.maximum.accumulate(self.direction * self.x[order])
        return self.t[order], self.direction * reach


@dataclass(frozen=True)
class Event:
    """One slip event (module doc for each definition; units those of the fields).

    ``elements`` are the indices of the ruptured elements (one interval), ``arrival`` and
    ``slip`` the arrival time and the event's slip at each; ``fronts`` the two fronts
    (direction -1, then +1). ``load_*`` are NaN without a load record.
    """

    index: int
    t_start: float
    t_arrest: float
    t_end: float
    i_nucleation: int
    x_nucleation: float
    x_min: float
    x_max: float
    extent: float
    moment: float
    spanning: bool
    cut: bool
    elements: np.ndarray
    arrival: Array
    slip: Array
    load_start: float
    load_arrest: float
    load_end: float
    fronts: tuple[Front, Front] = field(repr=False)

    @property
    def duration(self) -> float:
        """``t_end - t_start``."""
        return self.t_end - self.t_start

    @property
    def n_elements(self) -> int:
        """Number of ruptured elements."""
        return int(self.elements.size)

    @property
    def mean_slip(self) -> float:
        """``moment / extent``: the length-weighted mean slip of the ruptured elements."""
        return self.moment / self.extent


def _crossing(t0: float, t1: float, v0: float, v1: float, level: float) -> float:
    """Time at which the straight line from (t0, v0) to (t1, v1) reaches ``level``."""
    if v1 == v0:
        return t1
    return t0 + (level - v0) / (v1 - v0) * (t1 - t0)


def _speed_from_slowness(slope: float, low: float, high: float, direction: int
                         ) -> tuple[float, float, float]:
    """Speed and interval from the slope dT/dx and its interval along ``direction``."""
    s, lo, hi = direction * slope, direction * low, direction * high
    lo, hi = min(lo, hi), max(lo, hi)
    if s == 0:  # every element reached at once: an instantaneous front
        return math.inf, (1.0 / hi if hi > 0 else math.inf), math.inf
    if not s > 0:  # the front does not move away from the nucleation there
        return math.nan, math.nan, math.nan
    return 1.0 / s, (1.0 / hi if hi > 0 else math.nan), (1.0 / lo if lo > 0 else math.inf)


def _theil_sen(x: Array, t: Array, direction: int) -> tuple[float, float, float]:
    from scipy.stats import theilslopes

    if x.size < 3:
        return math.nan, math.nan, math.nan
    slope, _, low, high = theilslopes(t, x, alpha=CONFIDENCE)
    return _speed_from_slowness(float(slope), float(low), float(high), direction)


def front_speeds(x: ArrayLike, t: ArrayLike, direction: int, half_window: int = 3
                 ) -> tuple[Array, Array, Array]:
    """Local front speed at each element and its 95 % interval (module doc).

    Parameters
    ----------
    x, t : array_like
        Positions [length] and arrival times [time], ordered from the nucleation outwards.
    direction : int
        ``+1`` or ``-1``.
    half_window : int
        ``h``: the fit at an element uses the elements up to ``h`` away on the front (>= 1).

    Returns
    -------
    speed, low, high : ndarray [length/time]
    """
    x, t = np.asarray(x, dtype=float), np.asarray(t, dtype=float)
    h = int(half_window)
    if h < 1 or h != half_window:
        raise ValueError(f"half_window = {half_window!r} is out of range: a whole number >= 1")
    out = np.full((3, x.size), math.nan)
    for k in range(x.size):
        sl = slice(max(0, k - h), min(x.size, k + h + 1))
        out[:, k] = _theil_sen(x[sl], t[sl], direction)
    return out[0], out[1], out[2]


def _front(x: Array, t: Array, direction: int, half_window: int) -> Front:
    speed, low, high = front_speeds(x, t, direction, half_window)
    mean, mean_low, mean_high = _theil_sen(x, t, direction)
    return Front(direction=direction, x=x, t=t, speed=speed, speed_low=low, speed_high=high,
                 mean_speed=mean, mean_speed_low=mean_low, mean_speed_high=mean_high)


def detect_events(st: SpaceTime, threshold: float, *, min_elements: int = 1,
                  half_window: int = 3) -> list[Event]:
    """The slip events of a run, in order of start time, each with its two fronts.

    Parameters
    ----------
    st : SpaceTime
        The fields (:func:`space_time`).
    threshold : float
        Slip-rate threshold [``st.units['slip_rate']``], > 0 (module doc).
    min_elements : int
        Smallest number of ruptured elements an event must have (>= 1).
    half_window : int
        Half-width of the local speed fit, in elements (:func:`front_speeds`).

    Returns
    -------
    list of Event
    """
    from scipy import ndimage

    thr = _threshold(threshold, st.units)
    if int(min_elements) != min_elements or min_elements < 1:
        raise ValueError(f"min_elements = {min_elements!r} is out of range: a whole number >= 1")
    if int(half_window) != half_window or half_window < 1:
        raise ValueError(f"half_window = {half_window!r} is out of range: a whole number >= 1")
    # the mask (1 byte) and the labels (4 bytes) of every sample, besides the fields themselves
    check_memory("finding the events", 5.0 * st.slip_rate.size, "record fewer samples")
    mask = st.slip_rate > thr
    labels, n = ndimage.label(mask, structure=np.ones((3, 3), dtype=bool))
    n_t, n_x = st.shape
    t, v, s = st.t, st.slip_rate, st.slip
    found = []
    for lab, box in enumerate(ndimage.find_objects(labels), start=1):
        if box is None:
            continue
        rows, cols = box
        mine = labels[box] == lab
        elements = np.arange(cols.start, cols.stop)
        if elements.size < min_elements:
            continue
        has = mine.any(axis=0)
        assert has.all()  # a connected component's columns form one interval (module doc)
        first = rows.start + np.argmax(mine, axis=0)
        last = rows.start + mine.shape[0] - 1 - np.argmax(mine[::-1], axis=0)
        arrival = np.empty(elements.size)
        leave = np.empty(elements.size)
        for k, (i, j0, j1) in enumerate(zip(elements, first, last, strict=True)):
            arrival[k] = (t[j0] if j0 == 0
                          else _crossing(t[j0 - 1], t[j0], v[j0 - 1, i], v[j0, i], thr))
            leave[k] = (t[j1] if j1 == n_t - 1
                        else _crossing(t[j1], t[j1 + 1], v[j1, i], v[j1 + 1, i], thr))
        before = np.maximum(first - 1, 0)
        after = np.minimum(last + 1, n_t - 1)
        ds = s[after, elements] - s[before, elements]
        # the earliest element; among several reached at the same time, the middle one
        tied = np.flatnonzero(arrival == arrival.min())
        k0 = int(tied[tied.size // 2])
        i0 = int(elements[k0])
        lengths = st.lengths[elements]
        fronts = tuple(
            _front(st.x[side], arrival[side - elements[0]], d, half_window)
            for d, side in ((-1, np.arange(i0, elements[0] - 1, -1)),
                            (+1, np.arange(i0, elements[-1] + 1)))
        )
        t_start, t_arrest, t_end = float(arrival[k0]), float(arrival.max()), float(leave.max())

        def at(time: float) -> float:
            return float(np.interp(time, t, st.load)) if st.load is not None else math.nan

        found.append(dict(
            t_start=t_start, t_arrest=t_arrest, t_end=t_end, i_nucleation=i0,
            x_nucleation=float(st.x[i0]), x_min=float(st.x[elements[0]]),
            x_max=float(st.x[elements[-1]]), extent=float(lengths.sum()),
            moment=float(np.sum(ds * lengths)), spanning=bool(elements.size == n_x),
            cut=bool(rows.start == 0 or rows.stop == n_t), elements=elements,
            arrival=arrival, slip=ds, load_start=at(t_start), load_arrest=at(t_arrest),
            load_end=at(t_end), fronts=fronts))
    found.sort(key=lambda e: (e["t_start"], e["x_nucleation"]))
    return [Event(index=k, **e) for k, e in enumerate(found)]
