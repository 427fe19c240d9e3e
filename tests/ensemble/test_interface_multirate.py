"""Multirate stepping of the extended interface: every block's contact window on its own clock
(:func:`dryfriction.ensemble.interface_kernel.advance_chain_multirate`), against the default
run that updates every window at every step.

Each test names the plausible mistake it is for (seen failing with it applied, then reverted).
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest

from dryfriction.analysis.fronts import detect_events, from_result
from dryfriction.ensemble.interface import (
    QUASI_STATIC_RATE,
    InterfaceDrive,
    InterfaceModel,
    simulate_interface,
)
from dryfriction.ensemble.interface_result import InterfaceResult
from dryfriction.ensemble.population import Initial, Track
from dryfriction.ensemble.result import Output
from dryfriction.io.protocol import parse_protocol
from dryfriction.program import Segment, VelocityProgram
from dryfriction.theory.model import TrapModel

V = 0.013  # a0/t0: the plate's velocity (generic: not 0.01)


@functools.cache
def _stick_slip(multirate: bool, rate: float = 0.0, slip: float = 48.0) -> InterfaceResult:
    """Eight independent blocks in stick-slip under uniform loading, the generic parameters
    of tests/ensemble/test_interface_events.py (``k_c = 1.3``, ``K_p = 0.07``, ``m = 1.2``,
    ``eta = 0.03``, 80 pairs per ``a0``)."""
    return simulate_interface(
        InterfaceModel(TrapModel(eps=0.04), 8, 1.3, 1.2, 0.03, quasi_static_rate=rate,
                       multirate=multirate),
        InterfaceDrive("uniform", 0.07, VelocityProgram([Segment(V, slip=slip)])),
        Initial("steady", velocity=V, track=Track(80.0, "random", seed=3)),
        Output(every=0.5), threads=1)


def _catalogue(r: InterfaceResult) -> tuple[int, float, float, float]:
    """Events above 10 V (the catalogue's default), their mean slip, the peak load, the mean
    load after the first 100 ``t0``."""
    events = detect_events(from_result(r), 10.0 * V)
    return (len(events), float(np.mean([e.mean_slip for e in events])), float(np.max(r.load)),
            float(np.mean(r.load[r.t > 100.0])))


@pytest.mark.parametrize("loading", ["uniform", "side"])
def test_one_block_is_the_every_step_run_bit_for_bit(loading: str) -> None:
    """One block is always the fastest, whose window is updated at every step: the multirate
    run is the every-step run (and so the single slider, tests/ensemble/test_interface.py)
    bit for bit, through stick-slip with a sample every 0.5 ``t0`` (the steps cut short by a
    sample included). Mistake caught: the fastest block not always updated (a step cut short
    by a sample then skips its window: 0.78 ``a0`` apart after the first large slip)."""
    kp, ks = (0.07, 0.0) if loading == "uniform" else (0.0, 0.07)
    runs = [simulate_interface(
        InterfaceModel(TrapModel(eps=0.04), 1, 0.0, 1.3, 0.02, multirate=m),
        InterfaceDrive(loading, kp, VelocityProgram([Segment(V, slip=5.0)]), edge_stiffness=ks),
        Initial("steady", velocity=V, track=Track(80.0, "random", seed=3)),
        Output(every=0.5), threads=1) for m in (False, True)]
    assert np.max(runs[0].slip_rate) > 1.0  # a large slip, where a skipped update shows
    for name in ("slip", "slip_rate", "stress", "load"):
        assert np.array_equal(getattr(runs[0], name), getattr(runs[1], name)), name
    assert runs[0].info["steps"] == runs[1].info["steps"]


def test_blocks_at_rest_are_updated_on_time_and_age() -> None:
    """Four blocks held at rest (side loading, the edge's load point still for 40 ``t0``,
    then moving): every block is slow, the step is the oscillation bound and every window is
    due at every step, so the hold is the every-step run's to rounding, the friction of each
    block changing by up to 0.014 ``F_el`` as its fresh contacts age. Mistake caught: a block
    updated only on its slip, never on time (its friction then frozen while it rests: 5e-4
    ``F_el`` off, with 39 % of the updates)."""
    runs = [simulate_interface(
        InterfaceModel(TrapModel(eps=0.04), 4, 1.3, 1.2, 0.03, multirate=m),
        InterfaceDrive("side", 0.0, VelocityProgram([Segment(0.0, duration=40.0),
                                                     Segment(V, duration=20.0)]),
                       edge_stiffness=0.07),
        Initial("rest", track=Track(80.0, "random", seed=3)), Output(every=0.5), threads=1)
        for m in (False, True)]
    hold = runs[0].t <= 40.0
    ageing = float(np.max(np.abs(runs[0].stress[hold] - runs[0].stress[0])))
    assert ageing > 0.01
    assert np.max(np.abs(runs[1].stress[hold] - runs[0].stress[hold])) < 1e-9 * ageing
    assert np.max(np.abs(runs[1].slip - runs[0].slip)) < 1e-4


def test_trajectories_follow_the_every_step_run_through_the_first_events() -> None:
    """Over the first 150 ``t0`` (the loading from rest and the first slips), every block's
    slip stays within 0.03 ``a0`` (under three trap spacings) of the run that updates every
    window at every step, and the load within 0.2 %; with fewer window updates. Measured
    against the every-step run with a four times finer slip bound: 0.0035 ``a0`` for the
    every-step run itself, 0.012 with its bound halved, 0.020 for the multirate run; the
    load 0.06 % apart. Mistakes caught: the friction held at its last update (no
    stiffness term: the contacts' elasticity leaves the fast dynamics), the stiffness term's
    sign, a block updated only on its slip (never on time: a stuck block's contacts stop
    ageing)."""
    dyn = _stick_slip(False, slip=2.0)
    mr = _stick_slip(True, slip=2.0)
    assert mr.info["trap_updates"] < 0.9 * dyn.info["trap_updates"]
    assert np.max(dyn.slip[-1]) > 0.5  # the blocks have slipped
    dx = float(np.max(np.abs(dyn.slip - mr.slip)))
    assert dx < 0.03, dx
    dl = float(np.max(np.abs(dyn.load - mr.load) / np.abs(dyn.load)))
    assert dl < 2e-3, dl


@pytest.mark.slow
def test_event_catalogue_statistics_agree_with_the_every_step_run() -> None:
    """The catalogue of a chaotic stick-slip run (48 ``a0`` of plate travel, about 120
    events) agrees with the every-step run's to the event-driven check's tolerances
    (tests/ensemble/test_interface_events.py): event count within 25 %, mean slip per event
    within 20 %; the peak load within 4 % (it is one sample of a chaotic run: the every-step
    run's own peak spans 11.47 to 12.10 over seeds 1 to 4, and the two routes differ by -0.5,
    -0.5, +1.0, -2.9 % on them); the mean load within 1 %; with fewer window updates.
    Measured on seeds 1 to 4 (every-step / multirate): events 117/113, 118/102, 119/128,
    145/132; mean slip 0.544/0.590, 0.547/0.611, 0.523/0.479, 0.547/0.570 ``a0``; mean load
    higher by 0.6, 0.0, 0.7, 0.4 %; window updates 71 % of the every-step run's (81 % on
    seed 3 once the fastest block is always updated, as now: 130 events, mean slip 0.538
    ``a0``, peak load 2.1 % higher). Mistakes
    caught: a stuck block never updated on time, a contact's spinodal not looked for (its
    force drop seen only a quarter trap spacing later)."""
    dyn = _stick_slip(False)
    mr = _stick_slip(True)
    assert mr.info["trap_updates"] < 0.9 * dyn.info["trap_updates"]
    n_d, slip_d, peak_d, mean_d = _catalogue(dyn)
    n_m, slip_m, peak_m, mean_m = _catalogue(mr)
    assert n_d >= 50
    assert abs(n_m - n_d) <= 0.25 * n_d, (n_m, n_d)
    assert abs(slip_m - slip_d) <= 0.2 * slip_d, (slip_m, slip_d)
    assert abs(peak_m - peak_d) <= 0.04 * peak_d, (peak_m, peak_d)
    assert abs(mean_m - mean_d) <= 0.01 * mean_d, (mean_m, mean_d)


@pytest.mark.slow
@pytest.mark.parametrize("rate", [0.0, QUASI_STATIC_RATE])
def test_energy_balance_closes_with_multirate_stepping(rate: float) -> None:
    """``work_load = delta(elastic + kinetic) + work_friction + work_damping +
    work_quasi_static`` over the run and over every event, dynamic and event-driven: the work
    against the contacts is booked with the force the blocks felt (extrapolated between a
    window's updates). Mistakes caught: the work booked with the force at the last update
    only (not the extrapolated one); the windows not brought up to date when the dynamics
    hand over to a quasi-static phase."""
    r = _stick_slip(True, rate)
    e = r.energy
    res = r.energy_residual()
    work = e["work_load"][-1]
    assert work > 10.0
    assert np.max(np.abs(res)) < 2e-5 * work
    if rate > 0.0:
        assert r.info["quasi_static_steps"] > 100 and r.info["handovers"] >= 3
    events = detect_events(from_result(r), 10.0 * V)
    assert len(events) >= 8
    i = np.searchsorted
    for ev in events:
        a, b = int(i(r.t, ev.t_start)) - 1, int(i(r.t, ev.t_end))
        b = min(b, r.t.size - 1)
        diss = (e["work_friction"][b] - e["work_friction"][a]
                + e["work_damping"][b] - e["work_damping"][a])
        assert abs(res[b] - res[a]) < 2e-3 * max(diss, 0.1), (ev.index, res[b] - res[a], diss)


@pytest.mark.slow
def test_event_driven_multirate_catalogue_agrees_with_the_dynamic_run() -> None:
    """Both savings together (quasi-static loading between events, windows on their own
    clocks within them): the catalogue still agrees with the plain dynamic run's to the same
    tolerances. Mistake caught: the windows not brought up to date at the handover to a
    quasi-static phase (its Newton solve then starts from stale windows)."""
    dyn = _stick_slip(False)
    both = _stick_slip(True, QUASI_STATIC_RATE)
    n_d, slip_d, peak_d, _ = _catalogue(dyn)
    n_b, slip_b, peak_b, _ = _catalogue(both)
    assert abs(n_b - n_d) <= 0.25 * n_d, (n_b, n_d)
    assert abs(slip_b - slip_d) <= 0.2 * slip_d, (slip_b, slip_d)
    assert abs(peak_b - peak_d) <= 0.02 * peak_d, (peak_b, peak_d)


@pytest.mark.slow
def test_rupture_front_runs_at_the_sound_speed_with_windows_on_their_own_clocks() -> None:
    """The inertial front of tests/ensemble/test_interface.py (a prestressed creeping chain
    kicked at block 0, ``k_c = 30``, ``m = 2.5``): the blocks ahead of the tip are stuck, their
    windows updated on time only and their friction extrapolated in between; the tip crosses
    the middle of the chain at ``sqrt(k_c/m)`` within 5 % and reaches every block when the
    every-step run's tip does, to 1 % of the crossing time (measured: the same sample, 1.015
    c_s, with 36 % of the window updates). Mistakes caught: the stiffness term's sign, the
    extrapolation from the last update's time instead of its position."""
    N, u, kc, mass = 64, 1e-3, 30.0, 2.5
    cs = float(np.sqrt(kc / mass))
    T = 1.5 * N / cs
    v0 = np.full(N, u)
    v0[0] = 2.0 * np.sqrt(mass)
    runs = [simulate_interface(
        InterfaceModel(TrapModel(eps=0.04), N, kc, mass, 0.05, multirate=m),
        InterfaceDrive("uniform", 0.05, VelocityProgram([Segment(u, duration=T)])),
        Initial("steady", velocity=u, track=Track(50.0, "random", seed=1)),
        Output(every=T / 600), velocity=v0, threads=1) for m in (False, True)]
    fast = [r.slip_rate > 0.1 for r in runs]
    assert fast[0].any(axis=0).all() and fast[1].any(axis=0).all()
    arrival = [r.t[np.argmax(f, axis=0)] for r, f in zip(runs, fast, strict=True)]
    i = np.arange(N)
    mid = (i >= N // 8) & (i < 7 * N // 8)
    speed = np.polyfit(arrival[1][mid], i[mid], 1)[0]
    assert speed == pytest.approx(cs, rel=0.05)
    crossing = float(arrival[0][-1] - arrival[0][0])
    assert np.max(np.abs(arrival[1] - arrival[0])) <= 0.01 * crossing
    assert np.min(runs[1].slip[-1]) > 0.3  # a rupture, not a sound wave
    assert runs[1].info["trap_updates"] < 0.5 * runs[0].info["trap_updates"]


def test_multirate_is_a_boolean_switch() -> None:
    """``multirate`` is true or false, refused in one line naming it otherwise."""
    assert not InterfaceModel(TrapModel(), 2, 1.0, 1.0).multirate
    assert InterfaceModel(TrapModel(), 2, 1.0, 1.0, multirate=True).multirate
    with pytest.raises(ValueError, match="multirate") as err:
        InterfaceModel(TrapModel(), 2, 1.0, 1.0, multirate="yes")  # type: ignore[arg-type]
    assert "\n" not in str(err.value)


def test_the_protocol_table_takes_the_switch() -> None:
    """``multirate`` in the ``[interface]`` table reaches the model (default false); a value
    that is not true or false is refused in one line naming it, before any work. Mistake
    caught: the key allowed but not passed on."""
    text = (Path(__file__).parents[2] / "examples" / "interface_side_loaded.toml").read_text()
    assert "[interface]\n" in text
    good = text.replace("[interface]\n", "[interface]\nmultirate = true\n")
    assert parse_protocol(good, "mr.toml").model.multirate is True
    assert parse_protocol(text, "dyn.toml").model.multirate is False
    bad = text.replace("[interface]\n", "[interface]\nmultirate = 1\n")
    with pytest.raises(ValueError, match="multirate") as err:
        parse_protocol(bad, "bad.toml")
    assert "\n" not in str(err.value)


def test_multirate_numbers_are_the_same_with_two_threads() -> None:
    """32 blocks in multirate stepping, where 16 or more blocks due in one step are updated in
    the parallel loop (in the slow phases every block is due at every step): one thread and
    two give the same numbers bit for bit (each block's update touches only its own
    arrays). Mistake caught: the parallel branch updating the blocks in step order instead
    of the due list."""
    runs = [simulate_interface(
        InterfaceModel(TrapModel(eps=0.04), 32, 1.3, 1.2, 0.03, multirate=True),
        InterfaceDrive("uniform", 0.07, VelocityProgram([Segment(V, slip=2.0)])),
        Initial("steady", velocity=V, track=Track(60.0, "random", seed=4)),
        Output(every=0.5), threads=th) for th in (1, 2)]
    assert runs[1].info["threads"] == 2
    assert np.max(runs[0].slip_rate) > 10.0 * V  # slips, where few blocks are due
    for name in ("slip", "slip_rate", "stress", "load"):
        assert np.array_equal(getattr(runs[0], name), getattr(runs[1], name)), name
