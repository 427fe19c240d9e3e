"""What a rate-and-state run is asked to do: the drive, the initial state and the output.

Frozen, validated at construction, so that :func:`~dryfriction.rsf.driving.simulate`, the
protocol files and the fits share one set of checks (this module is the only place the
spring, damping, mass and load-velocity checks live):

* :class:`SpringSlider` - the load point follows a :class:`~dryfriction.program.VelocityProgram`
  (m/s, s) and pulls the slider through a spring ``stiffness`` (1/m per unit normal force; ``inf``
  is the kinematic machine, the slider moves with the load point), with radiation damping
  ``damping`` (``eta/sigma``, s/m) and mass ``mass`` (s^2/m per unit normal force);
* :class:`RSFInitial` - the initial slip velocity and state (default: steady sliding at the
  first load velocity);
* :class:`RSFOutput` - output times (``every`` or ``t_eval``; default every solver step), the
  solver tolerance and step budget.

Each is the rate-and-state (``law = "rsf"``, SI) :class:`~dryfriction.simulation.Drive`,
:class:`~dryfriction.simulation.Initial` or :class:`~dryfriction.simulation.Output`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .. import simulation
from ..program import Segment, VelocityProgram
from ..validation import Array, check_range, check_scalar
from .law import V_MAX, V_MIN, RateState

K_MAX: float = 1e15
"""Stiffest finite machine accepted, 1/m per unit normal force: a spring so stiff that its
elastic slip ``mu/k`` is below a femtometre is the kinematic machine (``inf``), which is
integrated without the stiff spring's tiny time scale."""

__all__ = ["RSFInitial", "RSFOutput", "SpringSlider", "T_MAX", "check_spring"]

RTOL_RANGE = (1e-13, 1e-2)
"""Accepted local error tolerances of the solver."""

T_MAX = 1e12
"""Longest load-point program a rate-and-state run takes, s (about 32 000 years; ours). The
``rsf`` command's ``--t1``, ``--t2`` and ``--hold-time`` take the same bound. Far beyond it
the spring solver's steps grow so long that the slip's quadrature
(:func:`dryfriction.rsf.result.slip_by_quadrature`) overflows: a 1e308-s run at 1 um/s
ended in an "impossible result" instead of a refusal."""


def check_spring(stiffness: Any, damping: Any = 0.0, mass: Any = 0.0) -> tuple[float, float, float]:
    """Validated ``(stiffness, damping, mass)`` of a rate-and-state machine.

    Parameters
    ----------
    stiffness : float
        1/m per unit normal force, ``> 0``; ``inf`` is the kinematic machine.
    damping : float
        Radiation damping ``eta/sigma``, s/m, ``>= 0``; needs a finite stiffness if ``> 0``.
    mass : float
        Mass per unit normal force, s^2/m, ``>= 0``; needs a finite stiffness if ``> 0``.

    Raises
    ------
    ValueError
        Naming the parameter, its value and the allowed range.
    """
    if isinstance(stiffness, (int, float, np.floating)) and not isinstance(stiffness, bool) \
            and math.isinf(stiffness) and stiffness > 0:
        k = math.inf
    else:
        try:
            k = check_scalar("stiffness", stiffness, 0.0, K_MAX, lo_open=True)
        except ValueError as exc:
            raise ValueError(f"{exc} (1/m), or inf for the kinematic machine") from None
    eta = check_scalar("damping", damping, 0.0)
    m = check_scalar("mass", mass, 0.0)
    if math.isinf(k):
        for name, value in (("damping", eta), ("mass", m)):
            if value != 0.0:
                raise ValueError(
                    f"{name} = {value:g} is not allowed on the kinematic machine (stiffness = "
                    "inf, no spring force): allowed 0, or give a finite stiffness"
                )
    return k, eta, m


@dataclass(frozen=True)
class SpringSlider(simulation.Drive):
    """A rate-and-state slider pulled through a spring by a load point following ``program``.

    ``k (x_load(t) - x) = mu(V, theta) + eta V + m dV/dt``; see :func:`check_spring` for the
    ranges. ``stiffness = inf`` (default) is the kinematic machine, ``V = V_load(t)``.

    Parameters
    ----------
    program : VelocityProgram or iterable of segments
        Load-point velocity, m/s, with durations (s) or slips (m).
    stiffness, damping, mass : float
        Spring (1/m), radiation damping (s/m) and mass (s^2/m), per unit normal force.
    """

    law: ClassVar[str] = "rsf"
    program: VelocityProgram
    stiffness: float = math.inf
    damping: float = 0.0
    mass: float = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.program, VelocityProgram):
            prog: Iterable[Segment | Mapping[str, float]] = self.program
            object.__setattr__(self, "program", VelocityProgram(prog))
        k, eta, m = check_spring(self.stiffness, self.damping, self.mass)
        object.__setattr__(self, "stiffness", k)
        object.__setattr__(self, "damping", eta)
        object.__setattr__(self, "mass", m)
        vel = self.program.velocities
        self.program.check_speeds(V_MIN, V_MAX, "m/s")
        total = self.program.total_time
        if total > T_MAX:
            raise ValueError(f"segments last {total:g} s in all (durations, and slips over "
                             f"|velocity|): allowed up to {T_MAX:g} s")
        if not self.kinematic:
            for i, vl in enumerate(vel):
                if vl < 0.0:
                    raise ValueError(
                        f"segments[{i}].velocity = {vl:g} m/s is out of range: the spring "
                        "driver needs >= 0 (it integrates ln V of the slider)"
                    )

    @property
    def kinematic(self) -> bool:
        """The infinitely stiff machine: the slider moves with the load point."""
        return math.isinf(self.stiffness)

    def check_model(self, model: RateState) -> None:
        """The load velocities this machine can run with ``model`` (before any work)."""
        if self.kinematic and model.state_law == "nagata":
            raise ValueError("stiffness = inf is out of range for state_law = 'nagata': its "
                             "stress-rate term needs the spring's stress, allowed a finite "
                             "stiffness > 0 (1/m)")
        if self.kinematic and not model.regularized:
            for i, vl in enumerate(self.program.velocities):
                if vl <= 0.0:
                    raise ValueError(
                        f"segments[{i}].velocity = {vl:g} m/s is out of range: the kinematic "
                        "machine with the standard law needs > 0 (ln V); use the regularized "
                        "law for holds (--regularized; regularized = true in a protocol's [model])"
                    )

    def critical_stiffness(self, model: RateState, v: float) -> float | None:
        """``k_c`` (1/m) of steady sliding at ``v`` with this damping and mass, where the
        closed form applies (finite spring, one state variable, standard law); else ``None``."""
        if (self.kinematic or model.n_state != 1 or model.regularized or not v > 0
                or model.state_law == "nagata"):
            return None
        return model.critical_stiffness(v, self.damping, self.mass)


@dataclass(frozen=True)
class RSFInitial(simulation.Initial):
    """Initial slip velocity (m/s) and state (s); ``None``: the defaults below.

    Parameters
    ----------
    v : float, optional
        Initial slip velocity, ``> 0``; default the first load velocity. On the kinematic
        machine it only sets the default state.
    theta, theta2 : float, optional
        Initial state, ``> 0``; default steady state ``Dc/v`` (``Dc2/v``).
    """

    law: ClassVar[str] = "rsf"
    v: float | None = None
    theta: float | None = None
    theta2: float | None = None

    def __post_init__(self) -> None:
        for name in ("v", "theta", "theta2"):
            value = getattr(self, name)
            if value is not None:
                label = "v_init" if name == "v" else f"{name}_init"
                hi = V_MAX if name == "v" else None
                object.__setattr__(self, name, check_scalar(label, value, 0.0, hi, lo_open=True))

    def resolve(self, model: RateState, drive: SpringSlider) -> tuple[float, float, float | None]:
        """``(v, theta, theta2)`` for this model and drive, defaults filled in.

        Raises
        ------
        ValueError
            The program starts with a hold and no ``v`` is given; ``theta2`` is given for one
            state variable.
        """
        v = self.v
        if v is None:
            first = float(drive.program.velocities[0])
            if first <= 0.0:
                raise ValueError(
                    f"the program starts with load velocity {first:g} m/s: give v_init (> 0, "
                    "m/s) to set the initial slip velocity and steady state"
                )
            v = first
        theta = model.dc / v if self.theta is None else self.theta
        theta2: float | None = None
        if model.dc2 is not None:
            theta2 = model.dc2 / v if self.theta2 is None else self.theta2
        elif self.theta2 is not None:
            raise ValueError("theta2_init is given but the parameters have one state variable")
        return v, theta, theta2


@dataclass(frozen=True, eq=False)
class RSFOutput(simulation.Output):
    """Output times and solver settings of a rate-and-state run.

    Parameters
    ----------
    every : float, optional
        Sampling interval, s, ``> 0`` (plus every segment boundary).
    t_eval : array_like, optional
        Output times, s, within the program. Give at most one of ``every`` and ``t_eval``;
        neither: every accepted solver step.
    rtol : float
        Local error tolerance per step, in ``[1e-13, 1e-2]``: absolute in ``ln V`` and
        ``ln theta`` (relative in ``V`` and ``theta``), ``rtol * a`` in the spring force.
    max_steps : int
        Step budget, ``>= 1``.
    """

    law: ClassVar[str] = "rsf"
    every: float | None = None
    t_eval: Array | None = None
    rtol: float = 1e-7
    max_steps: int = 1_000_000

    def __post_init__(self) -> None:
        if self.every is not None and self.t_eval is not None:
            raise ValueError("give at most one of every (s) and t_eval (s)")
        if self.every is not None:
            object.__setattr__(self, "every",
                               check_scalar("every", self.every, 0.0, lo_open=True))
        if self.t_eval is not None:
            te = check_range("t_eval", self.t_eval, 0.0).ravel().copy()
            te.setflags(write=False)
            object.__setattr__(self, "t_eval", te)
        object.__setattr__(self, "rtol", check_scalar("rtol", self.rtol, *RTOL_RANGE))
        n = self.max_steps
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ValueError(f"max_steps = {n!r} is out of range: allowed an integer >= 1")
        object.__setattr__(self, "max_steps", int(n))

    def times(self, program: VelocityProgram) -> Array | None:
        """Output times for ``program`` (``None``: every solver step)."""
        total = program.total_time
        if self.t_eval is not None:
            return check_range("t_eval", self.t_eval, 0.0, total)
        if self.every is not None:
            n = max(1, math.ceil(total / self.every * (1.0 - 1e-12)))
            # np.union1d, without the 0.1 s import of numpy.ma that np.unique makes
            t = np.sort(np.concatenate([np.linspace(0.0, total, n + 1), program.times]))
            return t[np.concatenate(([True], t[1:] != t[:-1]))]
        return None

