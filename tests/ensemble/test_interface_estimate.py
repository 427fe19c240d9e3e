"""The extended interface's estimate before a run (ensemble/interface.py), against its
definitions written here for both loadings, a hold, a backward segment and each initial
state (issue 25: a branch rarely taken, N > 1, a count off by one); and the refusal of too
many recorded values on both sides of its bound."""

from __future__ import annotations

import math

import pytest

from dryfriction.ensemble import interface as itf
from dryfriction.ensemble.interface import (
    InterfaceDrive,
    InterfaceModel,
    check_interface,
    estimate_interface,
)
from dryfriction.ensemble.population import Initial, Track
from dryfriction.ensemble.result import Output
from dryfriction.program import Segment, VelocityProgram
from dryfriction.theory.model import TrapModel

PROG = VelocityProgram([Segment(0.3, slip=1.2), Segment(0.0, duration=2.0),
                        Segment(0.5, slip=3.0), Segment(-0.2, slip=0.5)])
TRAP = TrapModel(alpha=0.21, eps=0.04)  # strong pinning: y_c < 1
N, TPA = 4, 37.0


def _est(loading: str, initial: Initial, output: Output) -> itf.InterfaceEstimate:
    model = InterfaceModel(TRAP, N, 1.3, 0.9, 0.2, normal_spread=0.3)
    drive = (InterfaceDrive("uniform", 0.6, PROG) if loading == "uniform"
             else InterfaceDrive("side", 0.0, PROG, edge_stiffness=2.5))
    return estimate_interface(model, drive, initial, output)


def test_samples_pairs_and_cover_are_their_definitions() -> None:
    track = Track(TPA, "random", seed=3)
    # every_slip 0.35: ceil(1.2/0.35) = 4, the hold 1, ceil(3/0.35) = 9, ceil(0.5/0.35) = 2
    e = _est("uniform", Initial("loaded", force=-0.3, track=track), Output(every_slip=0.35))
    assert e.samples == 1 + 4 + 1 + 9 + 2
    travel = 1.2 + 3.0  # the farthest the load point gets from where it started (not its end)
    lo, hi = -10.0, 2.0 * (0.3 / 0.6 + travel) + 20.0  # |force| over the loading spring
    assert e.cover == pytest.approx((lo, hi), rel=1e-14)
    reach = 2.0 * 1.0 + 12.0  # y_c < 1 in strong pinning
    assert e.pairs == pytest.approx(N * TPA * (hi - lo + 2 * reach), rel=1e-14)
    assert e.window == pytest.approx(2.0 * N * TPA, rel=1e-14)
    assert e.field_values == 3.0 * e.samples * N
    assert e.total_bytes == pytest.approx(e.pairs * itf.BYTES_PER_PAIR
                                          + 8.0 * (3 * e.samples * N + 8 * e.samples), rel=1e-14)
    # side loading: the edge spring holds the whole chain's initial friction
    s = _est("side", Initial("steady", velocity=0.3, track=track), Output(every=0.8))
    total = 1.2 / 0.3 + 2.0 + 0.5 / 0.2 + 3.0 / 0.5
    assert s.samples == 1 + math.ceil(4.0 / 0.8) + math.ceil(2.0 / 0.8) + math.ceil(
        6.0 / 0.8) + math.ceil(2.5 / 0.8)
    assert s.cover[1] == pytest.approx(2.0 * (N * 1.5 / 2.5 + travel) + 20.0, rel=1e-14)
    r = _est("side", Initial("rest", track=track), Output(every=0.8))
    assert r.cover[1] == pytest.approx(2.0 * (N * 0.05 / 2.5 + travel) + 20.0, rel=1e-14)
    # the time step at the largest normal load of the spread blocks, 1 + normal_spread
    dt = itf._step(InterfaceModel(TRAP, N, 1.3, 0.9, 0.2), InterfaceDrive("side", 0.0, PROG, 2.5),
                   1.3)
    assert s.steps == pytest.approx(total / dt, rel=1e-14)


def test_very_strong_pinning_reach_uses_y_c() -> None:
    trap = TrapModel(alpha=0.08, eps=0.04)  # y_c = 2.645 > 1
    yc = (1 - 0.08) ** 2 / (4 * 0.08)
    e = estimate_interface(InterfaceModel(trap, N, 1.3, 0.9), InterfaceDrive("uniform", 0.6, PROG),
                           Initial("rest", track=Track(TPA)), Output(every=1.0))
    lo, hi = e.cover
    assert e.pairs == pytest.approx(N * TPA * (hi - lo + 2 * (2 * yc + 12.0)), rel=1e-14)
    assert e.window == pytest.approx(2.0 * yc * N * TPA, rel=1e-14)


def test_recorded_values_refused_above_the_bound_only(monkeypatch: pytest.MonkeyPatch) -> None:
    model = InterfaceModel(TRAP, N, 1.3, 0.9, 0.2)
    drive = InterfaceDrive("uniform", 0.6, PROG)
    init = Initial("rest", track=Track(TPA))
    out = Output(every=0.8)
    e = estimate_interface(model, drive, init, out)
    monkeypatch.setattr(itf, "MAX_FIELD_VALUES", e.field_values)
    check_interface(model, drive, init, out)  # at the bound: allowed
    monkeypatch.setattr(itf, "MAX_FIELD_VALUES", e.field_values - 1)
    with pytest.raises(ValueError, match=r"^every = 0\.8 with n_elements = 4 records "
                                         r"2\.5e\+02 field values"):
        check_interface(model, drive, init, out)
