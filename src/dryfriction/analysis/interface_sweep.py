"""Sweeps of extended-interface protocols: one point runs
:func:`dryfriction.ensemble.interface.simulate_interface` and keeps the statistics of its event
catalogue (:mod:`.fronts`, :mod:`.catalogue`) for ``sweep.nc``.

A point is an ``[interface]`` protocol (:class:`dryfriction.io.protocol.InterfaceProtocol`) with
an optional ``[catalogue]`` table, not passed to the simulator, that sets how the catalogue is
made (defaults those of ``dryfriction simulate``):

* ``threshold`` — slip-rate threshold of the events, ``a0/t0``, ``> 0`` (default
  :func:`.fronts.default_threshold`: 10 x the largest loading velocity);
* ``min_elements`` — smallest event kept, in elements, an integer ``>= 1`` (default 1);
* ``after`` — events that start before this time (``t0``, ``>= 0`` and less than the drive's
  duration) are left out of every statistic, and the mean friction is taken from then on
  (default 0: everything, as the catalogue of ``dryfriction simulate``);
* ``edge_gap`` — elements next to the loaded edge that may creep below the threshold while a
  precursor starts beside them (:func:`.catalogue.precursors`), an integer ``>= 0`` (default 1).

The statistics (:data:`SWEEP_VARIABLES`, with units and definitions) are computed from the
same event detection as the catalogue ``events.csv`` of ``dryfriction simulate``, so that a
sweep point and the same protocol simulated alone give the same numbers.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

__all__ = ["CATALOGUE_KEYS", "SWEEP_VARIABLES", "TREND_CODES", "catalogue_options",
           "catalogue_summary", "interface_point", "interface_summary"]

CATALOGUE_KEYS: tuple[str, ...] = ("threshold", "min_elements", "after", "edge_gap")
"""Keys of a point's optional ``[catalogue]`` table (module doc)."""
_CATALOGUE_RANGES: dict[str, tuple[float, float | None, bool, bool]] = {
    # key: (lo, hi, lo_open, hi_open), as validation.check_scalar takes them; min_elements
    # (>= 1) and edge_gap (>= 0) are whole numbers
    "threshold": (0.0, None, True, False),
    "after": (0.0, None, False, False),
}

TREND_CODES: dict[int, str] = {-1: "undetermined", 0: "not_significant", 1: "yes",
                               2: "decreasing"}
"""Codes of ``precursor_trend`` (a sweep stores numbers; :func:`.catalogue.precursor_trend`'s
answers, spaces as underscores)."""
_TREND_OF = {"undetermined": -1, "not significant": 0, "yes": 1, "decreasing": 2}

_L, _T, _V, _S = "element", "t0", "a0/t0", "F_el per element"
SWEEP_VARIABLES: dict[str, dict[str, Any]] = {
    "events": {"long_name": "number of slip events (slip rate above threshold, at least "
               "min_elements elements, starting at or after catalogue.after)", "units": "1"},
    "spanning": {"long_name": "number of those events that rupture every element "
                 "(system-spanning)", "units": "1"},
    "arrested": {"long_name": "number of those events that arrest before spanning the "
                 "interface (events - spanning)", "units": "1"},
    "mean_slip": {"long_name": "mean over the events of each event's mean slip "
                  "(moment / extent); NaN without events", "units": "a0"},
    "mean_slip_spanning": {"long_name": "mean over the system-spanning events of their mean "
                           "slip; NaN without one", "units": "a0"},
    "max_extent": {"long_name": "largest extent of an event (sum of its elements' lengths); "
                   "NaN without events", "units": _L},
    "mean_extent": {"long_name": "mean extent of the events; NaN without events", "units": _L},
    "moment_alpha": {"long_name": "exponent alpha of p(M) ~ M^-alpha of the events' moments "
                     "(maximum likelihood above the smallest moment, Clauset et al. 2009 eq. "
                     "3.1); NaN with fewer than 2 events", "units": "1"},
    "moment_alpha_err": {"long_name": "standard error of moment_alpha, (alpha - 1)/sqrt(n)",
                         "units": "1"},
    "moment_n": {"long_name": "moments in the magnitude-frequency fit", "units": "1"},
    "precursors": {"long_name": "arrested events from the loaded edge (the precursor curve); "
                   "NaN under uniform loading (no loaded edge)", "units": "1"},
    "precursor_rho": {"long_name": "Spearman rank correlation of precursor length with the "
                      "load-to-normal ratio at arrest; NaN with fewer than 3 precursors or "
                      "under uniform loading", "units": "1"},
    "precursor_p": {"long_name": "two-sided p-value of precursor_rho", "units": "1"},
    "precursor_trend": {"long_name": "do precursor lengths grow with the load (p < 0.05)? "
                        "NaN under uniform loading", "units": "1",
                        "flag_values": list(TREND_CODES),
                        "flag_meanings": " ".join(TREND_CODES.values())},
    "mean_friction": {"long_name": "time average (trapezoid, from catalogue.after to the end) "
                      "of the mean over the elements of their friction force", "units": _S},
    "max_load_ratio": {"long_name": "largest applied shear as a friction coefficient: the "
                       "loading springs' total force over the chain's normal load "
                       "n_elements F_el / mu_el", "units": "1"},
    "threshold": {"long_name": "slip-rate threshold the events were found with",
                  "units": _V},
    "n_elements": {"long_name": "number of elements (blocks) of the chain", "units": "1"},
    "duration": {"long_name": "time simulated (the drive's duration)", "units": _T},
}
"""CF attributes of :func:`interface_summary`'s results in ``sweep.nc``
(:mod:`dryfriction.sweeps.cf`)."""


def catalogue_options(table: Any, source: str = "protocol") -> dict[str, Any]:
    """Check a ``[catalogue]`` table (keys, types, ranges) and return it as a dict.

    Raises
    ------
    ValueError
        One line naming ``catalogue.<key>`` and its allowed range: an unknown key, a value
        that is not a number (or not a whole number for ``min_elements``, ``edge_gap``), or
        out of range.
    """
    from ..io.protocol import option_table

    return option_table(table, "catalogue", CATALOGUE_KEYS, source, ranges=_CATALOGUE_RANGES,
                        whole={"min_elements": 1, "edge_gap": 0})


def interface_point(protocol: Mapping[str, Any], source: str = "sweep point"
                    ) -> tuple[Any, dict[str, Any]]:
    """Parse an interface sweep point completely, without running it.

    Returns the :class:`dryfriction.io.protocol.InterfaceProtocol` and the checked
    ``[catalogue]`` options; raises ``ValueError`` (one line) for anything
    :func:`interface_summary` would refuse at run time: a bad ``[catalogue]`` table, a
    protocol that is not an interface's, the interface's own refusals (:class:`~dryfriction.
    ensemble.interface.InterfaceModel`, the memory, sample and time estimate of
    :func:`~dryfriction.ensemble.interface.check_interface`), ``catalogue.after`` not before
    the end of the drive.
    """
    from ..io.protocol import InterfaceProtocol, protocol_from_dict

    doc = dict(protocol)
    opts = catalogue_options(doc.pop("catalogue", None), source)
    if "interface" not in doc:
        raise ValueError(f"{source}: no [interface] table: an interface sweep needs an "
                         "[interface] protocol")
    proto = protocol_from_dict(doc, source)
    if not isinstance(proto, InterfaceProtocol):  # law = "rsf" with an [interface] table
        raise ValueError(f"{source}: model.law must be the trap model ('cv') for an interface "
                         "sweep")
    total = float(proto.drive.program.total_time)
    if opts.get("after", 0.0) >= total:
        raise ValueError(f"{source}: catalogue.after = {opts['after']:g} t0 is out of range: "
                         f"allowed less than the drive's duration {total:g} t0")
    return proto, opts


def catalogue_summary(result: Any, threshold: float | None = None, min_elements: int = 1,
                      after: float = 0.0, edge_gap: int = 1) -> dict[str, float]:
    """The catalogue statistics of an interface run (:data:`SWEEP_VARIABLES`).

    Parameters
    ----------
    result : InterfaceResult
        The run.
    threshold, min_elements, after, edge_gap
        The ``[catalogue]`` options (module doc); ``threshold`` ``a0/t0``, ``after`` ``t0``.

    Returns
    -------
    dict
        Name -> value, every name of :data:`SWEEP_VARIABLES`.
    """
    from .catalogue import magnitude_frequency, precursor_trend, precursors
    from .fronts import (
        detect_events,
        event_threshold,
        from_result,
        interface_loaded_edge,
        interface_normal_load,
    )

    thr = event_threshold(result, threshold)
    st = from_result(result)
    events = [e for e in detect_events(st, thr, min_elements=min_elements)
              if e.t_start >= after]
    spanning = [e for e in events if e.spanning]

    def mean(values: list[float]) -> float:
        return float(np.mean(values)) if values else math.nan

    mf = magnitude_frequency([e.moment for e in events])
    n = int(result.x.size)
    t = np.asarray(result.t, float)
    keep = t >= after
    friction = np.asarray(result.stress, float)[keep].mean(axis=1)
    tk = t[keep]
    # the trapezoid mean over [after, end]; one sample is its own mean
    mean_f = (float(np.trapezoid(friction, tk) / (tk[-1] - tk[0])) if tk.size > 1
              else float(friction[0]))
    normal = interface_normal_load(result)
    out: dict[str, float] = {
        "events": float(len(events)),
        "spanning": float(len(spanning)),
        "arrested": float(len(events) - len(spanning)),
        "mean_slip": mean([e.mean_slip for e in events]),
        "mean_slip_spanning": mean([e.mean_slip for e in spanning]),
        "max_extent": max((e.extent for e in events), default=math.nan),
        "mean_extent": mean([e.extent for e in events]),
        "moment_alpha": mf.alpha,
        "moment_alpha_err": mf.alpha_err,
        "moment_n": float(mf.n_fit),
        "precursors": math.nan,
        "precursor_rho": math.nan,
        "precursor_p": math.nan,
        "precursor_trend": math.nan,
        "mean_friction": mean_f,
        "max_load_ratio": float(np.max(result.load) / normal),
        "threshold": thr,
        "n_elements": float(n),
        "duration": float(t[-1]),
    }
    edge = interface_loaded_edge(result)
    if edge is not None:
        pre = precursors(events, st, normal, edge=edge, edge_gap=edge_gap, after=after)
        trend = precursor_trend(pre)
        out.update(precursors=float(trend.n), precursor_rho=trend.rho,
                   precursor_p=trend.p_value, precursor_trend=float(_TREND_OF[trend.grows]))
    return out


def interface_summary(protocol: Mapping[str, Any]) -> dict[str, float]:
    """Sweep runner: simulate an interface protocol (dict) and summarise its catalogue.

    The protocol is an ``[interface]`` protocol of :mod:`dryfriction.io.protocol` plus an
    optional ``[catalogue]`` table (module doc). One thread per point: a sweep's parallelism
    is its points (the numbers are the same with any number of threads). Picklable (a module
    function), so :func:`dryfriction.sweeps.sweep.run_sweep` can ship it to workers.

    Returns
    -------
    dict
        :func:`catalogue_summary`'s statistics.
    """
    from ..ensemble.interface import simulate_interface

    proto, opts = interface_point(protocol)
    res = simulate_interface(proto.model, proto.drive, proto.initial, proto.output, threads=1)
    return catalogue_summary(res, **opts)
