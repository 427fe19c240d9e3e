"""The linear stability of a protocol's spring slider, as a sweep runner (ours).

:func:`linear_summary` reads a sweep point through :func:`dryfriction.io.protocol.spring_point`
(the one parser of protocol dictionaries) and evaluates the linear theory of
:mod:`dryfriction.theory.linear_stability` there.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ..io.protocol import pulling_velocity, spring_point
from ..theory.linear_stability import DirectResponse, critical_stiffness, linear_response
from ..theory.stability import SteadyResponse, delay_chain_limit, rightmost_root

__all__ = ["linear_summary", "growth_rate", "SWEEP_VARIABLES", "GROWTH_KINDS"]

GROWTH_KINDS = {
    0: "rightmost_root",
    1: "delay_chain_limit",
    -1: "no_root_found",
    -2: "ill_posed",
}
"""What ``growth_rate`` is at a point: the real part of the rightmost root found (0); the
limit of the delay chain's real parts, above every root found (1: a supremum approached at
high frequency, :func:`~dryfriction.theory.stability.delay_chain_limit`); NaN because no
Newton start converged (-1, possible with mass or damping only: without them the chain limit
always exists) or because ``K = -Z(inf)``, where every frequency grows (-2)."""

SWEEP_VARIABLES: dict[str, dict[str, str]] = {
    "K_c": {"long_name": "critical spring stiffness of steady sliding", "units": "F_el/a0"},
    "omega_c": {"long_name": "angular frequency at the onset of instability", "units": "rad/t0"},
    "growth_rate": {"long_name": "growth rate sup Re(lambda) of the linear modes (NaN: "
                    "undefined, growth_rate_kind says why)", "units": "1/t0"},
    "growth_rate_kind": {"long_name": "what the growth rate is", "units": "1",
                         "flag_values": list(GROWTH_KINDS),
                         "flag_meanings": " ".join(GROWTH_KINDS.values())},
    "linearly_stable": {"long_name": "steady sliding linearly stable (1) or not (0)",
                        "units": "1"},
}
"""CF attributes of :func:`linear_summary`'s results in ``sweep.nc``
(:mod:`dryfriction.sweeps.cf`)."""


def linear_summary(protocol: Mapping[str, Any]) -> dict[str, float]:
    """Sweep runner: linear stability of the spring slider described by a protocol dict.

    Uses the protocol's trap model (its direct effect included), ``drive.stiffness``,
    ``drive.mass``, ``drive.damping`` and the pulling velocity of the last segment (reduced
    units).

    Returns
    -------
    dict
        ``K_c`` (``F_el/a0``), ``omega_c`` (``rad/t0``), the growth rate at the given
        stiffness (``1/t0``): the supremum of ``Re lambda`` over the roots, the larger of
        the rightmost root found and the delay chain's limit, with ``growth_rate_kind``
        (:data:`GROWTH_KINDS`), and ``linearly_stable`` (1 or 0).
    """
    proto, _ = spring_point(protocol, analysis="linear")
    m, drive = proto.model, proto.drive
    u = pulling_velocity(drive)
    res = critical_stiffness(u, m, drive.mass, drive.damping)
    rate, kind, _ = growth_rate(linear_response(u, m), drive.stiffness, drive.mass,
                                drive.damping)
    return {
        "K_c": res.critical_stiffness,
        "omega_c": res.omega,
        "growth_rate": rate,
        "growth_rate_kind": float(kind),
        "linearly_stable": float(drive.stiffness > res.critical_stiffness),
    }


def growth_rate(resp: SteadyResponse | DirectResponse, stiffness: float, mass: float = 0.0,
                damping: float = 0.0) -> tuple[float, int, complex]:
    """Supremum of ``Re lambda`` over the roots of the spring slider's characteristic
    function, what it is (a code of :data:`GROWTH_KINDS`) and the rightmost root found
    (``-inf`` when none).

    The larger of the rightmost root found
    (:func:`~dryfriction.theory.stability.rightmost_root`) and the limit of the delay chain
    (:func:`~dryfriction.theory.stability.delay_chain_limit`, ``M = eta = 0`` only); NaN
    where neither exists (no start converged) or the chain's limit is infinite.
    """
    root = rightmost_root(resp, stiffness, mass, damping)
    chain = delay_chain_limit(resp, stiffness, mass, damping)
    if chain == math.inf:
        return math.nan, -2, root
    if math.isfinite(root.real) and root.real >= chain:
        return float(root.real), 0, root
    if math.isfinite(chain):
        return chain, 1, root
    return math.nan, -1, root
