"""Event-driven loading of the extended interface: quasi-static phases between events, dynamic
stepping within them (:mod:`dryfriction.ensemble.interface`), against the dynamic run.

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
def _stick_slip(rate: float, slip: float = 24.0) -> InterfaceResult:
    """Eight independent blocks in stick-slip under uniform loading, generic parameters
    (``k_c = 1.3``, ``K_p = 0.07``, ``m = 1.2``, ``eta = 0.03``, 80 pairs per ``a0``)."""
    return simulate_interface(
        InterfaceModel(TrapModel(eps=0.04), 8, 1.3, 1.2, 0.03, quasi_static_rate=rate),
        InterfaceDrive("uniform", 0.07, VelocityProgram([Segment(V, slip=slip)])),
        Initial("steady", velocity=V, track=Track(80.0, "random", seed=3)),
        Output(every=0.5), threads=1)


def _catalogue(r: InterfaceResult) -> tuple[int, float, float]:
    """Events above 10 V (the catalogue's default), their mean slip, the peak load."""
    events = detect_events(from_result(r), 10.0 * V)
    return len(events), float(np.mean([e.mean_slip for e in events])), float(np.max(r.load))


def test_threshold_zero_is_the_dynamic_run_bit_for_bit() -> None:
    """The switch's threshold lowered to (next to) 0: the event-driven path (the quiet test in
    the dynamic kernel every step) never switches and gives the dynamic run's numbers bit for
    bit. Mistake caught: the quiet test on ``v^2 + (a/omega)^2 <= v_qs^2`` (``<=``: a chain
    at rest is quiet at any threshold)."""
    dyn = _stick_slip(0.0, 6.0)
    tiny = _stick_slip(1e-300, 6.0)
    assert tiny.info["quasi_static_steps"] == 0
    for name in ("slip", "slip_rate", "stress", "load"):
        assert np.array_equal(getattr(dyn, name), getattr(tiny, name)), name
    assert dyn.info["steps"] == tiny.info["steps"]


@pytest.mark.slow
def test_event_catalogue_statistics_agree_with_the_dynamic_run() -> None:
    """At the default threshold the run spends time in quasi-static phases and hands over to
    the dynamics at thresholds, and its event catalogue agrees with the dynamic run's (the
    sequences differ in detail: stick-slip of a chain is chaotic): event count within 25 %,
    mean slip per event within 20 %, peak load within 2 %. Mistakes caught: contacts that do
    not age over a quasi-static step (the time left at the step's start), the spinodal check
    left out (the quasi-static step loads past the thresholds)."""
    dyn = _stick_slip(0.0)
    ed = _stick_slip(QUASI_STATIC_RATE)
    assert ed.info["quasi_static_steps"] > 100 and ed.info["handovers"] >= 3
    n_d, slip_d, peak_d = _catalogue(dyn)
    n_e, slip_e, peak_e = _catalogue(ed)
    assert n_d >= 8
    assert abs(n_e - n_d) <= 0.25 * n_d, (n_e, n_d)
    assert abs(slip_e - slip_d) <= 0.2 * slip_d, (slip_e, slip_d)
    assert abs(peak_e - peak_d) <= 0.02 * peak_d, (peak_e, peak_d)


@pytest.mark.slow
@pytest.mark.parametrize("rate", [QUASI_STATIC_RATE, 0.1])
def test_energy_balance_holds_per_event_with_quasi_static_phases(rate: float) -> None:
    """``work_load = delta(elastic + kinetic) + work_friction + work_damping +
    work_quasi_static`` over the whole run and over every event, at the default threshold
    (where what the quasi-static phases remove is small against the work) and at a ten times
    larger one (where it is not, and the balance must still close). Measured residuals ~1e-3
    of a work of ~230, the dynamic run's own. Mistakes caught: the unbalanced force's work
    not booked, the damping's work over a quasi-static step left out."""
    ed = _stick_slip(rate)
    e = ed.energy
    res = ed.energy_residual()
    work = e["work_load"][-1]
    assert work > 10.0
    assert np.max(np.abs(res)) < 2e-5 * work
    if rate == QUASI_STATIC_RATE:
        assert 0.0 < abs(e["work_quasi_static"][-1]) < 1e-4 * work
    events = detect_events(from_result(ed), 10.0 * V)
    i = np.searchsorted
    for ev in events:
        a, b = int(i(ed.t, ev.t_start)) - 1, int(i(ed.t, ev.t_end))
        b = min(b, ed.t.size - 1)
        diss = (e["work_friction"][b] - e["work_friction"][a]
                + e["work_damping"][b] - e["work_damping"][a])
        assert abs(res[b] - res[a]) < 2e-3 * max(diss, 0.1), (ev.index, res[b] - res[a], diss)


def test_event_driven_runs_are_refused_like_dynamic_ones(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """The memory and sample limits hold for the event-driven mode: refused in one line
    before any work; a negative threshold names its parameter."""
    with pytest.raises(ValueError, match="quasi_static_rate") as err:
        InterfaceModel(TrapModel(), 4, 1.0, 1.0, quasi_static_rate=-0.01)
    assert "\n" not in str(err.value)
    model = InterfaceModel(TrapModel(), 1000, 1.0, 1.0, quasi_static_rate=QUASI_STATIC_RATE)
    drive = InterfaceDrive("uniform", 0.1, VelocityProgram([Segment(1.0, duration=1e6)]))
    initial = Initial("rest", track=Track(100.0, "random", seed=1))
    with pytest.raises(ValueError, match=r"every = 0.01 with n_elements = 1000 records") as err:
        simulate_interface(model, drive, initial, Output(every=0.01))
    assert "\n" not in str(err.value)
    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", "1MB")
    small = InterfaceDrive("uniform", 0.1, VelocityProgram([Segment(1.0, duration=10.0)]))
    with pytest.raises(ValueError, match=r"traps_per_a0 = 100 places .* pairs") as err:
        simulate_interface(model, small, initial, Output(every=1.0))
    assert "\n" not in str(err.value)


def test_the_protocol_table_takes_the_threshold() -> None:
    """``quasi_static_rate`` in the ``[interface]`` table reaches the model; a negative one is
    refused in one line naming it, before any work."""
    text = (Path(__file__).parents[2] / "examples" / "interface_side_loaded.toml").read_text()
    assert "[interface]\n" in text
    good = text.replace("[interface]\n", "[interface]\nquasi_static_rate = 0.02\n")
    assert parse_protocol(good, "ed.toml").model.quasi_static_rate == 0.02
    assert parse_protocol(text, "dyn.toml").model.quasi_static_rate == 0.0
    bad = text.replace("[interface]\n", "[interface]\nquasi_static_rate = -1\n")
    with pytest.raises(ValueError, match="quasi_static_rate") as err:
        parse_protocol(bad, "bad.toml")
    assert "\n" not in str(err.value)


@pytest.mark.slow
def test_event_driven_numbers_are_the_same_with_two_threads() -> None:
    """16 blocks (the parallel loop's threshold), event-driven with quasi-static phases and
    handovers: one thread and two give the same numbers bit for bit (each block's probe
    touches only its own pairs). Mistake caught: the parallel branch of the Newton probe
    committing its trial positions."""
    runs = [simulate_interface(
        InterfaceModel(TrapModel(eps=0.04), 16, 1.3, 1.2, 0.03,
                       quasi_static_rate=QUASI_STATIC_RATE),
        InterfaceDrive("uniform", 0.07, VelocityProgram([Segment(V, slip=8.0)])),
        Initial("steady", velocity=V, track=Track(60.0, "random", seed=4)),
        Output(every=0.5), threads=th) for th in (1, 2)]
    assert runs[1].info["threads"] == 2
    assert runs[0].info["quasi_static_steps"] > 20 and runs[0].info["handovers"] > 0
    for name in ("slip", "slip_rate", "stress", "load"):
        assert np.array_equal(getattr(runs[0], name), getattr(runs[1], name)), name
