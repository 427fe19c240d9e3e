"""Linear stability of steady sliding under rate-and-state friction (Rice & Ruina 1983),
from the solver's own exact Jacobian: the eigenvalues of the spring slider linearised about
steady sliding, for any number of state variables, either law, standard or regularised.

Beside the law (:mod:`.law`, whose :meth:`~.law.RateState.critical_stiffness` is the closed
form for one state variable), and below both the driver (:mod:`.driving`) and the check of
an unstable start (:mod:`.growth`), which both use it (it was in the driver, which
the start check is part of).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..validation import check_scalar
from .law import RateState
from .spring import check_spring
from .stepper import INERTIAL, QUASISTATIC, param_vector, rhs_at

__all__ = ["linear_stability"]


def linear_stability(params: RateState, v: float, stiffness: float, damping: float = 0.0,
                     mass: float = 0.0) -> NDArray[np.complex128]:
    """Eigenvalues (1/s) of the spring slider linearised about steady sliding at ``v``.

    Computed from the exact Jacobian of the log-variable system (:mod:`.driving`) at steady
    state (the method of Rice & Ruina 1983; any number of state variables, either law,
    standard or regularised friction). Steady sliding is linearly stable iff every real part is < 0.
    With inertia the eigenvalues of ``(ln V, ln theta_i, tau)`` are returned.

    Parameters
    ----------
    params : RateState
    v : float
        Steady sliding (= load) velocity, m/s, ``> 0``.
    stiffness : float
        Spring stiffness per unit normal force, 1/m, ``> 0`` (finite).
    damping : float
        Radiation damping ``eta/sigma``, s/m, ``>= 0``.
    mass : float
        Mass per unit normal force, s^2/m, ``>= 0``.
    """
    v = check_scalar("v", v, 0.0, lo_open=True)
    stiffness, damping, mass = check_spring(stiffness, damping, mass)
    if math.isinf(stiffness):
        raise ValueError("stiffness = inf is out of range: the linearisation needs a finite "
                         "spring, allowed > 0 (1/m)")
    mode = INERTIAL if mass > 0.0 else QUASISTATIC
    p = param_vector(params, stiffness, damping, mass, mode, load_velocity=v)
    ns = params.n_state
    lnth = [math.log(params.dc / v)] + ([math.log(params.dc2 / v)] if ns == 2 else [])
    y = [math.log(v), *lnth]
    if mode == INERTIAL:
        th2 = None if ns == 1 else params.dc2 / v
        y.append(float(params.friction(v, params.dc / v, th2)) + damping * v)
    _, jac = rhs_at(np.array(y), p)
    return np.linalg.eigvals(jac).astype(np.complex128)
