"""The drives that move the trap ensemble (docs/model.md §6): prescribed motion
(:class:`VelocityDrive`), force control (:class:`ForceDrive`), a spring-pulled slider
(:class:`SpringDrive`). Frozen, validated when made; each a :class:`dryfriction.simulation.Drive`
of the trap model (``law = "cv"``, reduced units: ``a0``, ``t0``, forces ``F_el``, stiffness
``F_el/a0``, mass ``F_el t0^2/a0``, damping ``F_el t0/a0``).

Their own module so that both the driver (:mod:`.driving`) and the run's estimate
(:mod:`.resources`) import them, neither importing the other for them. The clock's
limit :data:`CLOCK_MAX` lives here, with the force ramp it bounds when the drive is made.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from .. import simulation
from ..program import VelocityProgram
from ..validation import U_MAX, U_MIN, check_scalar

__all__ = ["CLOCK_MAX", "MASS_MIN", "STIFFNESS_MAX", "Drive", "ForceDrive", "SpringDrive",
           "VelocityDrive"]

CLOCK_MAX = 2.0**46
"""Longest run, ``t0`` (ours). The kernel's times are floats: near ``t`` their
spacing is ``t 2^-52``, and an age (a difference of two times, under the kernel's reassociating
fast math) carries an error of a few spacings. At ``2^46 t0`` (7.0e13) that is ``1/64 t0``,
far from the ``1 t0`` at which ``ln(1 + age)`` fails. Measured: a spring drive at ``1e-15
a0/t0`` reached ``t = 9.0e15 t0 > 2^53 t0`` (spacing ``2 t0``), where the kernel's force turned
NaN and the jump then searched ``1e9 a0`` for an equilibrium, event by event, for hours
without a line."""


@dataclass(frozen=True)
class VelocityDrive(simulation.Drive):
    """Prescribed slider motion: the slider follows ``program`` (``a0/t0``, ``t0``, ``a0``)."""

    law: ClassVar[str] = "cv"
    program: VelocityProgram

    def __post_init__(self) -> None:
        if not isinstance(self.program, VelocityProgram):
            object.__setattr__(self, "program", VelocityProgram(self.program))
        self.program.check_speeds(U_MIN, U_MAX, "a0/t0")


@dataclass(frozen=True)
class ForceDrive(simulation.Drive):
    """Force control: hold the initial force for ``hold``, then ramp it up at ``rate``.

    Parameters
    ----------
    rate : float
        Loading rate of the tangential force, units ``F_el/t0``, ``> 0`` (a threshold is asked,
        so the force must grow).
    hold : float
        Wait at constant force before the ramp, units ``t0``, ``>= 0``.
    max_force : float
        Safety stop, units ``F_el``: the run ends if the force reaches it without a runaway.
    """

    law: ClassVar[str] = "cv"
    rate: float
    hold: float = 0.0
    max_force: float = 10.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "rate", check_scalar("rate", self.rate, 0.0, lo_open=True))
        object.__setattr__(self, "hold", check_scalar("hold", self.hold, 0.0))
        object.__setattr__(
            self, "max_force", check_scalar("max_force", self.max_force, 0.0, lo_open=True)
        )
        # the contacts age through the hold and the ramp: past CLOCK_MAX the clock no longer
        # resolves their ages (at rate = 1e-300 it overflowed: a threshold of 8e-17)
        if self.hold > CLOCK_MAX:
            raise ValueError(f"hold = {self.hold:g} is out of range: allowed <= "
                             f"{CLOCK_MAX:.3g} t0 (2^46, within which the clock resolves the "
                             "contacts' ages)")
        end = self.hold + self.max_force / self.rate
        if not end <= CLOCK_MAX:
            lowest = self.max_force / (CLOCK_MAX - self.hold)
            lowest = float(f"{lowest * 1.01:.3g}")  # shown rounded up: it is allowed
            raise ValueError(
                f"rate = {self.rate:g} is out of range with max_force = {self.max_force:g} "
                f"and hold = {self.hold:g}: the ramp could last until t = {end:.1e} t0, "
                f"beyond the {CLOCK_MAX:.3g} t0 (2^46) within which the clock resolves the "
                f"contacts' ages; allowed rate >= {lowest:g} F_el/t0 (or a lower max_force)")


STIFFNESS_MAX: float = 1e6
"""Stiffest spring accepted, ``F_el/a0`` (a million times a trap population's contact stiffness,
about 0.7 ``F_el/a0``): stiffer is the velocity drive (``kind = "velocity"``), without the
spring's ever smaller steps."""

MASS_MIN: float = 1e-6
"""Smallest nonzero slider mass accepted, ``F_el t0^2/a0``: below it the inertial time
``sqrt(M/K)`` makes the steps vanish while the motion is the quasi-static one (``mass = 0``)."""


@dataclass(frozen=True)
class SpringDrive(simulation.Drive):
    """A slider of mass ``mass`` pulled through a spring ``stiffness`` by a load point.

    ``M X'' = K (X_pull - X) - F - eta X'``; the load point follows ``program`` and starts where
    the spring balances the initial friction force, ``X_pull(0) = X(0) + F(0)/K``.

    Parameters
    ----------
    stiffness : float
        ``K``, units ``F_el/a0``, ``> 0``.
    mass : float
        ``M``, units ``F_el t0^2/a0``, ``>= 0``; 0 is the quasi-static limit (slips are jumps
        between equilibria with ageing frozen during the jump).
    damping : float
        ``eta``, units ``F_el t0/a0``, ``>= 0``; must be 0 when ``mass = 0`` (the quasi-static
        jumps have no time scale).
    program : VelocityProgram
        Load-point velocity program.
    """

    law: ClassVar[str] = "cv"
    stiffness: float
    mass: float
    program: VelocityProgram
    damping: float = 0.0

    def __post_init__(self) -> None:
        k = check_scalar("stiffness", self.stiffness, 0.0, STIFFNESS_MAX, lo_open=True)
        object.__setattr__(self, "stiffness", k)
        object.__setattr__(self, "mass", check_scalar("mass", self.mass, 0.0))
        if 0.0 < self.mass < MASS_MIN:
            raise ValueError(f"mass = {self.mass:g} is out of range: allowed 0 (the quasi-static "
                             f"slider) or >= {MASS_MIN:g} (the inertial time sqrt(M/K) sets the "
                             "step: a smaller mass is the quasi-static limit, only slower)")
        object.__setattr__(self, "damping", check_scalar("damping", self.damping, 0.0))
        if self.mass == 0.0 and self.damping != 0.0:
            raise ValueError(
                f"damping = {self.damping:g} is not allowed with mass = 0: the quasi-static "
                "slider jumps between equilibria; allowed damping = 0"
            )
        if not isinstance(self.program, VelocityProgram):
            object.__setattr__(self, "program", VelocityProgram(self.program))
        self.program.check_speeds(U_MIN, U_MAX, "a0/t0")


Drive = VelocityDrive | ForceDrive | SpringDrive
"""The trap model's drives (the type :func:`.driving.simulate` takes)."""
