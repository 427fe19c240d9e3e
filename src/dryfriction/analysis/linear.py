"""The linear stability of a protocol's spring slider, as a sweep runner (ours).

:func:`linear_summary` reads a sweep point through :func:`dryfriction.io.protocol.spring_point`
(the one parser of protocol dictionaries) and evaluates the linear theory of
:mod:`dryfriction.theory.stability` there.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..io.protocol import pulling_velocity, spring_point
from ..theory.stability import critical_stiffness, rightmost_root, steady_response

__all__ = ["linear_summary", "SWEEP_VARIABLES"]

SWEEP_VARIABLES: dict[str, dict[str, str]] = {
    "K_c": {"long_name": "critical spring stiffness of steady sliding", "units": "F_el/a0"},
    "omega_c": {"long_name": "angular frequency at the onset of instability", "units": "1/t0"},
    "growth_rate": {"long_name": "growth rate Re(lambda) of the rightmost linear mode "
                    "(NaN: no root found)", "units": "1/t0"},
    "linearly_stable": {"long_name": "steady sliding linearly stable (1) or not (0)",
                        "units": "1"},
}
"""CF attributes of :func:`linear_summary`'s results in ``sweep.nc`` (:mod:`dryfriction.io.cf`)."""


def linear_summary(protocol: Mapping[str, Any]) -> dict[str, float]:
    """Sweep runner: linear stability of the spring slider described by a protocol dict.

    Uses ``model.alpha``, ``model.eps``, ``model.creep``, ``drive.stiffness``, ``drive.mass``,
    ``drive.damping`` and the pulling velocity of the last segment (reduced units).

    Returns
    -------
    dict
        ``K_c`` (``F_el/a0``), ``omega_c`` (``1/t0``), the growth rate ``Re lambda`` of the
        rightmost mode at the given stiffness (``1/t0``), and ``linearly_stable`` (1 or 0).
    """
    proto, _ = spring_point(protocol, analysis="linear")
    m, drive = proto.model, proto.drive
    u = pulling_velocity(drive)
    res = critical_stiffness(u, m.eps, m.alpha, m.creep, drive.mass, drive.damping)
    root = rightmost_root(steady_response(u, m.eps, m.alpha, m.creep), drive.stiffness,
                          drive.mass, drive.damping)
    return {
        "K_c": res.critical_stiffness,
        "omega_c": res.omega,
        "growth_rate": root.real,
        "linearly_stable": float(drive.stiffness > res.critical_stiffness),
    }
