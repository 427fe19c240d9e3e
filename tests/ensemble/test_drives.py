"""The trap model's drives (dryfriction.ensemble.drives): defaults and both sides of every
documented range (issue 25: a refusal boundary moved from >= to >, a default changed), and the
force ramp's clock bound with the lowest rate it suggests accepted."""

from __future__ import annotations

import pytest

from dryfriction.ensemble.drives import (
    CLOCK_MAX,
    MASS_MIN,
    STIFFNESS_MAX,
    ForceDrive,
    SpringDrive,
    VelocityDrive,
)
from dryfriction.program import Segment, VelocityProgram
from dryfriction.validation import U_MAX, U_MIN

PROG = VelocityProgram([Segment(0.37, slip=2.0)])


def test_force_drive_defaults_and_ranges() -> None:
    d = ForceDrive(rate=0.3)
    assert (d.hold, d.max_force) == (0.0, 10.0)
    for kw, name in (({"rate": 0.0}, "rate"), ({"rate": 1.0, "hold": -1e-9}, "hold"),
                     ({"rate": 1.0, "max_force": 0.0}, "max_force")):
        with pytest.raises(ValueError, match=f"^{name} = "):
            ForceDrive(**kw)
    assert CLOCK_MAX == 2.0**46
    # the ramp ends at hold + max_force / rate: at CLOCK_MAX itself allowed, beyond refused
    ForceDrive(rate=4.0, hold=CLOCK_MAX - 2.0, max_force=8.0)
    with pytest.raises(ValueError, match=r"^rate = 2 is out of range with max_force = 8 and "
                                         r"hold = 7\.03687e\+13: the ramp could last until"):
        ForceDrive(rate=2.0, hold=CLOCK_MAX - 2.0, max_force=8.0)
    ForceDrive(rate=1.0, hold=CLOCK_MAX, max_force=1e-300)
    with pytest.raises(ValueError, match=r"^hold = 7\.03687e\+13 is out of range: allowed <= "):
        ForceDrive(rate=1.0, hold=CLOCK_MAX * (1 + 1e-15), max_force=1e-300)


def test_the_lowest_rate_a_refusal_suggests_is_accepted() -> None:
    hold, fmax = 3.1e13, 7.3
    with pytest.raises(ValueError) as info:
        ForceDrive(rate=1e-13, hold=hold, max_force=fmax)
    lowest = float(str(info.value).split("allowed rate >= ")[1].split()[0])
    want = fmax / (CLOCK_MAX - hold)  # the ramp ending at CLOCK_MAX
    assert want <= lowest <= 1.02 * want
    ForceDrive(rate=lowest, hold=hold, max_force=fmax)


def test_spring_drive_defaults_and_ranges() -> None:
    d = SpringDrive(stiffness=0.7, mass=0.0, program=PROG)
    assert d.damping == 0.0
    SpringDrive(stiffness=STIFFNESS_MAX, mass=MASS_MIN, program=PROG, damping=0.3)
    with pytest.raises(ValueError, match="^stiffness = "):
        SpringDrive(stiffness=STIFFNESS_MAX * 1.001, mass=0.0, program=PROG)
    with pytest.raises(ValueError, match="^stiffness = 0 "):
        SpringDrive(stiffness=0.0, mass=0.0, program=PROG)
    with pytest.raises(ValueError, match=r"^mass = 9\.9e-07 is out of range: allowed 0 \(the "
                                         r"quasi-static slider\) or >= 1e-06"):
        SpringDrive(stiffness=0.7, mass=0.99 * MASS_MIN, program=PROG)
    with pytest.raises(ValueError, match="^damping = 0.3 is not allowed with mass = 0"):
        SpringDrive(stiffness=0.7, mass=0.0, program=PROG, damping=0.3)
    # a list of segments is made a program, checked in a0/t0
    s = SpringDrive(stiffness=0.7, mass=2.0, program=[Segment(-U_MAX, 1.0)])  # type: ignore[arg-type]
    assert isinstance(s.program, VelocityProgram)
    with pytest.raises(ValueError, match=r"segments\[0\]\.velocity = .* a0/t0 is out of range"):
        SpringDrive(stiffness=0.7, mass=2.0, program=[Segment(0.5 * U_MIN, 1.0)])  # type: ignore[arg-type]


def test_velocity_drive_speeds() -> None:
    VelocityDrive([Segment(U_MIN, 1.0), Segment(0.0, 1.0), Segment(-U_MAX, 1.0)])  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"segments\[1\]\.velocity = 1\.01e\+30 a0/t0"):
        VelocityDrive([Segment(1.0, 1.0), Segment(1.01 * U_MAX, 1.0)])  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"segments\[0\]\.velocity = -9\.9e-31 a0/t0"):
        VelocityDrive([Segment(-0.99 * U_MIN, 1.0)])  # type: ignore[arg-type]


def test_initial_population_defaults_and_ranges() -> None:
    """What a run starts from: rest by default; a loaded start's force in (-1, 1) open at both
    ends (a down-load allowed), a steady start's velocity in [U_MIN, U_MAX]; each value only
    with its kind."""
    from dryfriction.ensemble.population import Initial, Track

    d = Initial()
    assert (d.kind, d.force, d.velocity, d.track) == ("rest", None, None, None)
    assert Initial("loaded", force=-0.999).force == -0.999
    assert Initial("loaded", force=0.999).force == 0.999
    for f in (-1.0, 1.0):
        with pytest.raises(ValueError, match="^initial_force = "):
            Initial("loaded", force=f)
    assert Initial("steady", velocity=U_MIN).velocity == U_MIN
    assert Initial("steady", velocity=U_MAX).velocity == U_MAX
    with pytest.raises(ValueError, match="^initial_velocity = "):
        Initial("steady", velocity=0.5 * U_MIN)
    with pytest.raises(ValueError, match="initial_force applies only to initial = 'loaded', "
                                         "not 'steady'"):
        Initial("steady", force=0.2, velocity=1.0)
    with pytest.raises(ValueError, match="initial_velocity applies only to initial = 'steady'"):
        Initial("rest", velocity=1.0)
    with pytest.raises(ValueError, match="initial_force is required"):
        Initial("loaded")
    with pytest.raises(ValueError, match="initial_velocity is required"):
        Initial("steady")
    with pytest.raises(ValueError, match="track = 100.0 is not allowed: a Track"):
        Initial(track=100.0)  # type: ignore[arg-type]
    assert Initial(track=Track(50.0)).track == Track(50.0)
