"""What a rate-and-state run produces: :class:`RSFResult` (the shared schema of
:mod:`dryfriction.results`, SI units) and its construction from the solver's step values."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from .. import simulation
from ..program import VelocityProgram
from ..results import summarize
from ..validation import Array
from .law import RateState

__all__ = ["RSFResult", "UNITS", "build_result", "force_balance_is_ill_conditioned", "hermite",
           "slip_by_quadrature"]


UNITS: dict[str, str] = {
    "t": "s", "x": "m", "v": "m/s", "mu": "", "theta": "s", "theta2": "s",
    "stress": "1 (spring force / normal force)", "x_load": "m", "v_load": "m/s",
}
"""Unit of every column of :meth:`RSFResult.columns`."""


@dataclass(frozen=True)
class RSFResult(simulation.Result):
    """A rate-and-state run (arrays read-only, one entry per output time).

    Attributes
    ----------
    t : ndarray
        Time, s. Segment boundaries appear twice (end of one segment, start of the next).
    x : ndarray
        Slider position, m (``x(0)`` = the program's ``x0``).
    v : ndarray
        Slip velocity, m/s.
    theta, theta2 : ndarray
        State variables, s (``theta2`` is ``None`` with one state variable).
    mu : ndarray
        Friction coefficient ``mu(V, theta)``.
    stress : ndarray
        Spring force per unit normal force, ``mu + eta V + m dV/dt``.
    load : ndarray
        Load-point position, m (column ``x_load``).
    load_velocity : ndarray
        Load-point velocity, m/s, right-continuous (column ``v_load``).
    n_steps, n_rejected, n_rhs : int
        Accepted and rejected steps and right-hand-side evaluations.
    """

    law: ClassVar[str] = "rsf"
    t: Array
    x: Array
    v: Array
    theta: Array
    theta2: Array | None
    mu: Array
    stress: Array
    load: Array
    load_velocity: Array
    params: RateState
    stiffness: float
    damping: float
    mass: float
    rtol: float
    n_steps: int
    n_rejected: int
    n_rhs: int
    meta: dict[str, Any] = field(default_factory=dict)

    @property
    def partial(self) -> bool:
        """Always ``False``: a failed integration raises instead of returning samples."""
        return False

    def columns(self) -> dict[str, Array]:
        """The time series as ``{column: array}``: the shared ``t, x, v, mu``, then ``theta``
        (``theta2``), ``stress``, ``x_load``, ``v_load`` (units in :data:`UNITS`)."""
        cols = {"t": self.t, "x": self.x, "v": self.v, "mu": self.mu, "theta": self.theta}
        if self.theta2 is not None:
            cols["theta2"] = self.theta2
        cols.update(stress=self.stress, x_load=self.load, v_load=self.load_velocity)
        return cols

    def critical_stiffness(self) -> float | None:
        """``k_c`` (1/m) at the final load velocity (the initial slip velocity if that is 0)
        with this damping and mass, where the closed form applies (finite spring, one state
        variable, standard law); else ``None``."""
        p = self.params
        if math.isinf(self.stiffness) or p.n_state != 1 or p.regularized:
            return None
        v = float(self.load_velocity[-1]) if self.load_velocity[-1] > 0 else float(self.v[0])
        return p.critical_stiffness(v, self.damping, self.mass) if v > 0 else None

    def summary(self) -> dict[str, Any]:
        """The shared summary (:func:`dryfriction.results.summarize`, ``law = "rsf"``, SI),
        then the solver statistics, the machine and the parameters."""
        cols = self.columns()
        extra: dict[str, Any] = {
            "steps": self.n_steps,
            "rejected_steps": self.n_rejected,
            "rhs_evaluations": self.n_rhs,
            "stiffness_per_m": self.stiffness,
            "damping_s_per_m": self.damping,
            "mass_s2_per_m": self.mass,
            "rtol": self.rtol,
        }
        k_c = self.critical_stiffness()
        if k_c is not None:
            extra["critical_stiffness_per_m"] = k_c
        if "unstable_start" in self.meta:  # set by simulate: started beside an unstable
            extra["unstable_start"] = dict(self.meta["unstable_start"])  # steady state
        extra["params"] = self.params.to_dict()
        return summarize("rsf", self.t, self.x, self.v, self.mu,
                         {k: UNITS[k] for k in cols}, extra=extra)

    def to_dict(self) -> dict[str, Any]:
        """Everything as a plain mapping (arrays as NumPy arrays; see
        :func:`dryfriction.io.files.to_jsonable`)."""
        return {
            "params": self.params.to_dict(),
            "stiffness": self.stiffness,
            "damping": self.damping,
            "mass": self.mass,
            "rtol": self.rtol,
            "n_steps": self.n_steps,
            "n_rejected": self.n_rejected,
            "n_rhs": self.n_rhs,
            **self.meta,
            **self.columns(),
        }


def hermite(T: Array, Y: Array, F: Array, te: Array) -> Array:
    """Cubic Hermite interpolation of the step values at ``te`` (right-continuous)."""
    n = len(T)
    i = np.clip(np.searchsorted(T, te, side="right") - 1, 0, n - 1)
    j = np.minimum(i + 1, n - 1)
    Ti = T[i]
    h = T[j] - Ti
    ok = h > 0
    Yi = Y[i]
    if not np.any(ok):
        return Yi
    # every row at once, the rows without a step after them (h = 0: at or past the last
    # step) then given Y[i]: the same operations, in the same order, as on the rows with one
    # (a fit's solver runs interpolate at 1000-odd times: gathering the rows once is what
    # this costs)
    hh = np.where(ok, h, 1.0)[:, None]
    # the rows past the last step may overflow (a time far past it): their values are not used
    with np.errstate(over="ignore", invalid="ignore"):
        s = ((te - Ti) / hh[:, 0])[:, None]
        h00 = (1 + 2 * s) * (1 - s) ** 2
        h10 = s * (1 - s) ** 2
        h01 = s * s * (3 - 2 * s)
        h11 = s * s * (s - 1)
        out = h00 * Yi + h10 * hh * F[i] + h01 * Y[j] + h11 * hh * F[j]
    out = np.where(ok[:, None], out, Yi) if not ok.all() else out
    return out.astype(Y.dtype, copy=False)  # Y's type, as Y[i] filled row by row was


# Gauss-Legendre nodes and weights on [0, 1], 5 points (exact for polynomials of degree 9)
_GL_X, _GL_W = (0.5 * (np.polynomial.legendre.leggauss(5)[0] + 1.0),
                0.5 * np.polynomial.legendre.leggauss(5)[1])


def slip_by_quadrature(T: Array, Y: Array, F: Array, x0: float) -> Array:
    """Slider position (m) at the solver's steps ``T`` from ``x = x0 + int V dt`` (ours).

    ``ln V`` is the cubic Hermite of the step values ``Y[:, 0]`` and slopes ``F[:, 0]`` (the
    interpolant :func:`hermite` uses), and ``exp`` of it is integrated over each step by 5-point
    Gauss-Legendre. Its error is the solver's own, a relative ``rtol`` of the slip, whatever
    the spring; the force balance ``x = x_load - (stress - stress0)/k`` divides the error of the
    stress (``rtol (a + b)``, and the rounding of ``mu0``) by ``k``: 1e-4 m at ``k = 1e-12``/m,
    -1.2e285 m at ``k = 1e-300``/m.
    """
    h = np.diff(T)
    y0, y1 = Y[:-1, 0], Y[1:, 0]
    f0, f1 = F[:-1, 0] * h, F[1:, 0] * h
    s = _GL_X[None, :]
    lnv = ((1 + 2 * s) * (1 - s) ** 2 * y0[:, None] + s * (1 - s) ** 2 * f0[:, None]
           + s * s * (3 - 2 * s) * y1[:, None] + s * s * (s - 1) * f1[:, None])
    dx = h * (np.exp(lnv) @ _GL_W)
    return x0 + np.concatenate(([0.0], np.cumsum(dx)))


def force_balance_is_ill_conditioned(params: RateState, stiffness: float, rtol: float,
                                     stress: float, travel: float) -> bool:
    """Whether ``x = x_load - (stress - stress0)/k`` loses more than the quadrature of ``V``
    (:func:`slip_by_quadrature`) over a run of load-point travel ``travel`` (m): the force
    route's error, ``(rtol (a + b + b2) + 4 eps |stress|)/k``, against ``rtol`` of the travel
    plus one ``Dc`` (ours)."""
    if math.isinf(stiffness):
        return False
    err_force = (rtol * (params.a + params.b + params.b2)
                 + 4.0 * np.finfo(float).eps * abs(stress)) / stiffness
    return bool(err_force > rtol * (abs(travel) + params.dc))


def build_result(T: Array, Y: Array, SEG: NDArray[np.int64], prog: VelocityProgram,
                 params: RateState, *, kinematic: bool, inertial: bool, stiffness: float,
                 damping: float, mass: float, rtol: float, stress0: float,
                 stats: tuple[int, int, int], x: Array | None = None) -> RSFResult:
    """:class:`RSFResult` from the solver's log variables ``Y`` at times ``T`` (segment ``SEG``).

    ``Y`` holds ``ln theta_i`` (kinematic), ``ln V, ln theta_i`` (quasi-static) or ``ln V,
    ln theta_i, tau`` (inertial); the slider's position is ``x`` when given (a soft spring:
    :func:`slip_by_quadrature`), else it follows from the force balance,
    ``x = x_load - (stress - stress0)/k``.
    """
    ns = params.n_state
    vl = prog.velocities[SEG]
    if kinematic:
        v = vl.copy()
        lnth = Y[:, :ns]
    else:
        v = np.exp(Y[:, 0])
        lnth = Y[:, 1 : 1 + ns]
    theta = np.exp(lnth[:, 0])
    theta2 = np.exp(lnth[:, 1]) if ns == 2 else None
    mu = params.friction(v, theta, theta2)
    load = prog.position(T)
    if inertial:
        stress = Y[:, ns + 1].copy()
    else:
        stress = mu + damping * v
    if kinematic:
        x = load.copy()
    elif x is None:
        x = load - (stress - stress0) / stiffness
    else:
        x = np.array(x, float)
    arrays = [T, x, v, theta, mu, stress, load, vl] + ([theta2] if theta2 is not None else [])
    for arr in arrays:
        arr.setflags(write=False)
    return RSFResult(
        t=T, x=x, v=v, theta=theta, theta2=theta2, mu=mu, stress=stress, load=load,
        load_velocity=vl, params=params, stiffness=stiffness, damping=damping, mass=mass,
        rtol=rtol, n_steps=int(stats[0]), n_rejected=int(stats[1]), n_rhs=int(stats[2]),
    )
