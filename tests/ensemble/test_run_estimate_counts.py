"""``ensemble.resources.estimate_run`` and ``check_run`` against what a run does and what its
refusals say (issue 25, strengthen7B).

* the samples of a force drive (its hold on the geometric or uniform grid, then its ramp)
  bound those the run records, a few above: both output spacings;
* the pairs estimated bound the largest buffer the run holds, and the traps in contact the
  most in contact, within a factor: regular and random layouts (whole blocks of 1024);
* the ramp whose force step is under the clock's rounding is refused, on one side of
  ``dt = 1e-12 max(1, hold)`` and not on the other, for a hold under and over 1 t0;
* a run over the time limit names the key that sets its work (the output spacing, the
  density, the mass), as the API or the protocol file spells it, with the kernel calls
  counted by hand from the drive;
* the price: per call, per trap in contact per call, per pair placed.
Generic numbers: none of the densities, rates or spacings is 1.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from dryfriction.ensemble import resources
from dryfriction.ensemble.driving import ForceDrive, SpringDrive, VelocityDrive, simulate
from dryfriction.ensemble.population import Ensemble, Initial, Track, TrapModel
from dryfriction.ensemble.resources import check_run, estimate_run, estimate_work
from dryfriction.ensemble.result import Output, force_hold_grid
from dryfriction.program import Segment, VelocityProgram
from dryfriction.validation import TIME_ENV

MODEL = TrapModel(alpha=0.13, eps=0.04)


@pytest.mark.parametrize("output", [Output(every_slip=0.01, snapshots=(5.0, 30.0)),
                                    Output(every=0.7, snapshots=(5.0,))],
                         ids=["every_slip", "every"])
def test_force_drive_samples_bound_the_recorded_ones(output: Output) -> None:
    """A hold of 23 t0 then a ramp at 0.07 F_el/t0 to 0.9 F_el (below depinning, so the ramp
    runs to its end): the estimate is 1-5 samples above the recorded count, and its hold
    part covers the hold's own grid. Mistakes: the hold left out of the ``every`` count, the
    log grid's step or ``log1p`` changed, the snapshots not counted."""
    drive = ForceDrive(rate=0.07, hold=23.0, max_force=0.9)
    track = Track(37.0)
    est = estimate_run(MODEL, track, Initial("rest"), drive, output)
    res = simulate(MODEL, drive, Initial("rest", track=track), output)
    assert float(np.max(res.mu)) == pytest.approx(0.9, abs=0.01)  # the ramp's end reached
    assert 1.0 <= est.samples - len(res.t) <= 5.0, (est.samples, len(res.t))
    k_c = MODEL.trap.contact_stiffness
    ramp = (0.9 / (output.every_slip * k_c) if output.every is None
            else (0.9 / 0.07) / output.every)
    hold = est.samples - ramp - 2.0 - len(output.snapshots)
    assert abs(hold - len(force_hold_grid(23.0, output.every))) <= 2.0, hold


@pytest.mark.parametrize("track, initial", [
    (Track(37.0), Initial("rest")),
    (Track(91.0, layout="random", seed=3), Initial("rest")),
    (Track(23.0), Initial("steady", velocity=3e-3)),
], ids=["regular", "random", "steady"])
def test_pairs_and_contacts_bound_the_run(track: Track, initial: Initial,
                                          monkeypatch: pytest.MonkeyPatch) -> None:
    """The largest buffer the run makes (``Ensemble._set_buffer``) is at most the estimate's
    pairs, and those at most 1.4 x it beyond the 2 random blocks; the most traps in contact at
    most ``active``, which is at most 1.5 x it. At 91 pairs per a0 the random buffer spans 4
    blocks (4096 pairs). Mistakes: one side of the slider counted, one block for the random
    layout's whole blocks, the contact reach without its ``+ 1``... any that drops the bound."""
    sizes: list[int] = []
    original = Ensemble._set_buffer

    def record(self, k0: int, k1: int) -> None:  # type: ignore[no-untyped-def]
        sizes.append(k1 - k0)
        original(self, k0, k1)

    monkeypatch.setattr(Ensemble, "_set_buffer", record)
    drive = VelocityDrive(VelocityProgram([Segment(0.3, slip=5.0)]))
    output = Output(every_slip=0.1)
    est = estimate_run(MODEL, track, initial, drive, output)
    res = simulate(MODEL, drive, Initial(initial.kind, velocity=initial.velocity, track=track),
                   output)
    blocks = 2048.0 if track.layout == "random" else 0.0
    assert max(sizes) <= est.traps <= 1.4 * max(sizes) + blocks, (est.traps, max(sizes))
    if track.layout == "random":
        assert max(sizes) == 4096
    most = float(np.max(res.n_active))
    assert most <= est.active <= 1.5 * most, (est.active, most)


@pytest.mark.parametrize("hold", [0.37, 3.1e3])
@pytest.mark.parametrize("qualified", [False, True])
def test_a_ramp_step_under_the_clock_rounding_is_refused(hold: float, qualified: bool) -> None:
    """The ramp's time step ``every_slip k_c / rate`` must exceed ``1e-12 max(1, hold)``: 3 %
    above it runs, 3 % below is refused in one line naming the rate (``drive.rate`` in a
    protocol). Mistakes: the hold's floor 1 dropped (a short hold), the contact stiffness left
    out, the step taken per unit force."""
    every_slip, k_c = 0.013, MODEL.trap.contact_stiffness
    floor = 1e-12 * max(1.0, hold)
    fast = every_slip * k_c / (0.97 * floor)
    ok = every_slip * k_c / (1.03 * floor)
    out = Output(every_slip=every_slip)
    key = "drive.rate" if qualified else "rate"
    with pytest.raises(ValueError, match="^" + re.escape(
            f"{key} = {fast:g} is out of range with every_slip = 0.013: the force step of one "
            "sample")) as info:
        check_run(MODEL, Track(37.0), Initial("rest"),
                  ForceDrive(rate=fast, hold=hold, max_force=0.9), out, qualified=qualified)
    assert "\n" not in str(info.value)
    check_run(MODEL, Track(37.0), Initial("rest"), ForceDrive(rate=ok, hold=hold, max_force=0.9),
              out, qualified=qualified)


K_C = MODEL.trap.contact_stiffness
CASES = {
    # velocity: (2.7 + 0.4)/0.05 samples, less one part step per segment
    "samples": (Track(37.0), VelocityDrive(VelocityProgram([Segment(0.3, slip=2.7),
                                                            Segment(0.03, slip=0.4)])),
                Output(every_slip=0.05), 54.0 + 8.0 - 2.0,
                "{o}every_slip = 0.05 gives 6.0e+01 kernel calls:", "raise {o}every_slip"),
    # force: two calls a step, (23 + 0.9/0.07)/0.7 steps
    "force": (Track(37.0), ForceDrive(rate=0.07, hold=23.0, max_force=0.9), Output(every=0.7),
              2.0 * (23.0 + 0.9 / 0.07) / 0.7,
              "{o}every = 0.7 gives 1.0e+02 kernel calls:", "raise {o}every"),
    # quasi-static spring: 2 lambda events per a0 of travel, 2 calls a sample step
    "events": (Track(370.0), SpringDrive(0.3, 0.0, [Segment(0.05, slip=2.0)]),
               Output(every_slip=0.5), 2.0 * 370.0 * 2.0 + 2.0 * (2.0 / 0.5 - 1.0),
               "{e}traps_per_a0 = 370 gives 1.5e+03 kernel calls over 1319 traps in contact:",
               "lower {e}traps_per_a0"),
    # inertial spring: the travel over a quarter spacing
    "steps": (Track(37.0), SpringDrive(0.3, 0.7, [Segment(0.05, slip=2.0)]),
              Output(every_slip=0.05), 2.0 * 37.0 / 0.25,
              "{d}mass = 0.7 over 40 t0 of drive needs 3.0e+02 time steps of 134 traps in contact:",
              "raise {d}mass"),
    # velocity at 2e4 pairs per a0: the traps in contact outweigh the call
    "pairs": (Track(2e4), VelocityDrive(VelocityProgram([Segment(0.3, slip=2.7)])),
              Output(every=0.7), 2.7 / 0.3 / 0.7 - 1.0,
              "{e}traps_per_a0 = 20000 gives 1.2e+01 kernel calls over 70425 traps in contact:",
              "lower {e}traps_per_a0"),
}


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("qualified", [False, True])
def test_a_run_over_the_time_limit_names_what_sets_its_work(
        case: str, qualified: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    """Each kind of work, under a limit of 1 ms: the key, the calls counted by hand and the
    hint, in one line; the same run passes under the default hour. Mistakes: the calls of a
    force drive one a step, the events per a0 not twice the density, the inertial steps from
    the oscillation period when the slip bound is larger, the kinds' messages crossed."""
    track, drive, output, calls, what, hint = CASES[case]
    est = estimate_run(MODEL, track, Initial("rest"), drive, output)
    assert estimate_work(MODEL, track, drive, est)[0] == pytest.approx(calls, rel=1e-12)
    names = dict(o="output." if qualified else "", e="ensemble." if qualified else "",
                 d="drive." if qualified else "")
    monkeypatch.setenv(TIME_ENV, "1e-3")
    with pytest.raises(ValueError) as info:
        check_run(MODEL, track, Initial("rest"), drive, output, qualified=qualified)
    msg = str(info.value)
    assert msg.startswith(what.format(**names)), msg
    assert hint.format(**names) in msg and "\n" not in msg and "limit 0.001 s" in msg
    monkeypatch.delenv(TIME_ENV)
    assert check_run(MODEL, track, Initial("rest"), drive, output) == est


def test_the_price_per_call_pair_and_placement() -> None:
    """``seconds = calls (15 us + 10 ns x traps in contact) + 40 ns x pairs placed``
    (:func:`estimate_work`'s docstring) on an estimate of generic counts. Mistakes: the pairs
    in contact priced once rather than per call, the placement per trap in contact."""
    est = resources.RunEstimate(samples=3.7e4, traps=2.9e5, active=2.3e4, snapshots=3)
    drive = VelocityDrive(VelocityProgram([Segment(0.3, slip=2.7)]))
    calls, seconds, kind = estimate_work(MODEL, Track(37.0), drive, est)
    assert kind == "samples" and calls == pytest.approx(3.7e4 - 2.0 - 3.0 - 1.0, rel=1e-15)
    assert seconds == pytest.approx(calls * (15e-6 + 10e-9 * 2.3e4) + 4e-8 * 2.9e5, rel=1e-12)
    assert math.isfinite(seconds)
