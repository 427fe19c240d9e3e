"""Rupture fronts, events, the catalogue, precursors and the magnitude-frequency distribution on
synthetic fields whose answers are known (tests/fronts_synth.py). Each test names the mistake it
is for; each was seen failing with that mistake applied."""

from __future__ import annotations

import csv
import math
import re

import numpy as np
import pytest

from dryfriction.analysis.catalogue import catalogue_columns, magnitude_frequency, precursors
from dryfriction.analysis.fronts import detect_events, front_speeds, space_time
from dryfriction.io.files import write_csv
from fronts_synth import Pulse, fields, grid

THR = 0.6  # slip-rate threshold [a0/t0]; the pulses reach A = 4


def _crossing_delay(p: Pulse, v_bg: float = 0.0) -> float:
    """Time from an element's arrival to its slip rate crossing THR on the rise (over a creep
    ``v_bg``)."""
    return p.r * (THR - v_bg) / p.A


def test_front_speed_and_both_directions():
    # mistakes: speed in elements per sample (c dt/dx); the threshold on slip instead of slip
    # rate; one direction only
    t, x = grid(n_x=40, dx=0.5, t_end=9.0, dt=0.013)
    p = Pulse(i_nuc=10, lo=0, hi=39, t_nuc=1.0, c=2.7)
    v, s = fields(t, x, [p])
    (e,) = detect_events(space_time(t, x, v, s), THR)
    assert e.i_nucleation == 10 and e.x_nucleation == pytest.approx(x[10])
    assert e.t_start == pytest.approx(p.t_nuc + _crossing_delay(p), abs=1e-9)
    left, right = e.fronts
    assert (left.direction, right.direction) == (-1, 1)
    assert left.length == pytest.approx(10 * 0.5) and right.length == pytest.approx(29 * 0.5)
    for f in (left, right):
        assert f.mean_speed == pytest.approx(2.7, rel=1e-6)
        assert f.mean_speed_low <= 2.7 * (1 + 1e-9) and f.mean_speed_high >= 2.7 * (1 - 1e-9)
        assert np.allclose(f.speed[1:], 2.7, rtol=1e-6)
        tt, tip = f.tip()
        assert np.all(np.diff(tt) >= 0) and np.all(np.diff(f.direction * tip) >= 0)
    assert e.spanning and not e.cut


def test_speed_fit_is_robust_and_gives_an_interval():
    # mistake: a least-squares fit (one late element drags it) or no interval
    rng = np.random.default_rng(29)
    c, xs = 1.9, 0.7 * np.arange(30)
    T = 0.4 + xs / c + rng.normal(0.0, 0.01, xs.size)
    T[17] += 3.0  # one element reached late (a local asperity)
    speed, low, high = front_speeds(xs, T, +1, half_window=4)
    far = np.abs(np.arange(30) - 17) > 4
    assert np.mean((low[far] <= c) & (c <= high[far])) > 0.8  # 95 % intervals, 21 windows
    assert np.all(np.abs(speed[far] / c - 1) < 0.05)
    # a left-going front of the same data mirrored
    s2, _, _ = front_speeds(-xs, T, -1, half_window=4)
    assert np.allclose(s2, speed, equal_nan=True)


def test_two_events_of_known_extents():
    # mistakes: extent off by one element (x_max - x_min); slip counted from the first sample
    t, x = grid(n_x=40, dx=0.5, t_end=10.0, dt=0.011)
    a = Pulse(i_nuc=8, lo=5, hi=14, t_nuc=1.0, c=3.1)
    b = Pulse(i_nuc=30, lo=20, hi=39, t_nuc=3.5, c=1.3, A=6.0)
    v, s = fields(t, x, [a, b], v_bg=0.02)
    st = space_time(t, x, v, s)
    ea, eb = detect_events(st, THR)
    assert (ea.n_elements, eb.n_elements) == (10, 20)
    assert (ea.extent, eb.extent) == (pytest.approx(5.0), pytest.approx(10.0))
    assert (ea.x_min, ea.x_max, eb.x_min, eb.x_max) == pytest.approx(
        (x[5], x[14], x[20], x[39]))
    assert not (ea.spanning or eb.spanning or ea.cut or eb.cut)
    # min_elements keeps an event of exactly that many elements
    assert len(detect_events(st, THR, min_elements=10)) == 2
    assert [e.n_elements for e in detect_events(st, THR, min_elements=11)] == [20]
    # slip of each element: the pulse A (r + h), plus the creep v_bg over the window, which
    # starts one sample before the upward crossing and ends one after the downward one
    for e, p in ((ea, a), (eb, b)):
        assert e.mean_slip == pytest.approx(p.A * (p.r + p.h), rel=0.01)
        assert e.moment == pytest.approx(e.mean_slip * e.extent)
        far = max(abs(x[p.lo] - x[p.i_nuc]), abs(x[p.hi] - x[p.i_nuc]))
        d = _crossing_delay(p, v_bg=0.02)
        assert e.duration == pytest.approx(far / p.c + 2 * p.r + p.h - 2 * d, abs=1e-9)
        assert e.t_arrest == pytest.approx(p.t_nuc + far / p.c + d, abs=1e-9)


def test_pure_noise_has_no_event():
    # mistake: the threshold applied to the slip (which grows without bound) not the slip rate
    rng = np.random.default_rng(7)
    t, x = grid(n_x=32, t_end=5.0)
    v = rng.uniform(0.0, 0.5, (t.size, x.size))  # never reaches THR
    st = space_time(t, x, v)
    assert st.slip[-1].mean() > 1.0 > THR
    assert detect_events(st, THR) == []


def test_arrested_precursors_of_known_length():
    # mistakes: the ratio read at the event's start, not at its arrest; the length in
    # elements; an event cut by the record's end taken as arrested
    t, x = grid(n_x=40, dx=0.5, t_end=20.0, dt=0.013)
    # three precursors from the loaded edge, a global slip, and a front the record cuts
    pulses = [Pulse(0, 0, 7, 1.0, 2.0), Pulse(0, 0, 15, 4.0, 2.0), Pulse(0, 0, 39, 8.0, 2.0),
              Pulse(0, 0, 20, 19.0, 2.0)]
    v, s = fields(t, x, pulses)
    load = 0.3 + 0.05 * t
    st = space_time(t, x, v, s, load)
    events = detect_events(st, THR)
    assert [(e.spanning, e.cut) for e in events] == [(False, False), (False, False),
                                                    (True, False), (False, True)]
    pre = precursors(events, st, normal_load=2.5, edge="left")
    assert pre.length == pytest.approx([4.0, 8.0])
    arrest = [p.t_nuc + (x[p.hi] - x[0]) / p.c + _crossing_delay(p) for p in pulses[:2]]
    assert pre.ratio == pytest.approx([(0.3 + 0.05 * ta) / 2.5 for ta in arrest], rel=1e-9)
    t0 = pulses[2].t_nuc + _crossing_delay(pulses[2])
    assert pre.spanning_ratio == pytest.approx([(0.3 + 0.05 * t0) / 2.5])
    assert len(precursors(events, st, 2.5, edge="right").length) == 0
    # events that start one element in (the loaded block creeping below the threshold): kept
    # with edge_gap = 1, their length measured from the interface's edge
    inner = [Pulse(1, 1, 7, 1.0, 2.0), Pulse(1, 1, 15, 4.0, 2.0)]
    st2 = space_time(t, x, *fields(t, x, inner), load)
    ev2 = detect_events(st2, THR)
    assert len(precursors(ev2, st2, 2.5, edge="left").length) == 0
    assert precursors(ev2, st2, 2.5, edge="left", edge_gap=1).length == pytest.approx([4.0, 8.0])
    assert [e.extent for e in ev2] == pytest.approx([3.5, 7.5])
    # an initial transient left out: the first precursor starts at t = 1.0 + delay
    late = precursors(events, st, 2.5, edge="left", after=1.5)
    assert late.length == pytest.approx([8.0]) and late.spanning_ratio.size == 1


def _header(tmp_path, st, events):
    path = write_csv(tmp_path / "events.csv", *catalogue_columns(events, st, THR))
    with open(path) as fh:
        rows = list(csv.reader(fh))
    return rows[0], rows[1:]


def test_catalogue_headers_carry_units(tmp_path):
    # mistake: a header without its unit, or the moment's unit taken as the slip's
    t, x = grid(n_x=20, t_end=5.0)
    v, s = fields(t, x, [Pulse(5, 2, 12, 1.0, 2.0)])
    st = space_time(t, x, v, s, 0.1 * t)
    head, rows = _header(tmp_path, st, detect_events(st, THR))
    assert all(re.fullmatch(r"\w+\[[^\]]+\]", h) for h in head), head
    for h in ("t_start[t0]", "duration[t0]", "extent[a0]", "mean_slip[a0]", "moment[a0^2]",
              "speed_right[a0/t0]", "spanning[1]", "load_arrest[F_el]", "threshold[a0/t0]"):
        assert h in head
    assert len(rows) == 1 and float(rows[0][head.index("extent[a0]")]) == pytest.approx(5.5)
    si = space_time(t, x, v, s, units={"t": "s", "x": "m", "slip": "m", "slip_rate": "m/s"})
    head, _ = _header(tmp_path, si, detect_events(si, THR))
    assert {"t_start[s]", "moment[m^2]", "speed_left[m/s]"} <= set(head)


def test_magnitude_frequency():
    # mistakes: N(>= M) counting ties as N(> M); the exponent of the CCDF for that of p(M)
    mf = magnitude_frequency([3.0, 1.0, 2.0, 2.0])
    assert list(mf.moment) == [3.0, 2.0, 2.0, 1.0] and list(mf.count) == [1, 3, 3, 4]
    rng = np.random.default_rng(11)
    alpha = 1.7
    m = 0.5 * (1 - rng.uniform(size=4000)) ** (-1 / (alpha - 1))  # Pareto, M_min = 0.5
    mf = magnitude_frequency(m, m_min=0.5)
    assert abs(mf.alpha - alpha) < 3 * mf.alpha_err and mf.alpha_err < 0.02
    assert math.isnan(magnitude_frequency([1.0]).alpha)


@pytest.mark.parametrize("kwargs, message", [
    (dict(t=[]), "t is empty"),
    (dict(x=[]), "x is empty"),
    (dict(slip_rate=np.zeros((5, 3))), "slip_rate has shape (5, 3), but (len(t), len(x))"),
    (dict(slip=np.zeros((3, 5))), "slip has shape (3, 5)"),
    (dict(load=np.zeros(4)), "load has shape (4,)"),
    (dict(t=[0.0, 2.0, 1.0, 3.0, 4.0, 5.0]), "t must be strictly increasing"),
    (dict(x=[0.0]), "x has shape (6, 1)"),
])
def test_bad_fields_are_one_line(kwargs, message):
    t, x = np.arange(6.0), np.arange(4.0)
    args = dict(t=t, x=x, slip_rate=np.zeros((6, 4)), slip=None, load=None)
    args.update(kwargs)
    if "x" in kwargs and kwargs["x"] == [0.0]:
        message = "slip_rate has shape (6, 4), but (len(t), len(x)) = (6, 1)"
    with pytest.raises(ValueError) as err:
        space_time(**args)
    assert message in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("threshold", [-1.0, 0.0, float("nan")])
def test_bad_threshold_is_one_line(threshold):
    st = space_time(np.arange(3.0), np.arange(2.0), np.zeros((3, 2)))
    with pytest.raises(ValueError, match=r"threshold = .* must be finite and > 0 \[a0/t0\]$"):
        detect_events(st, threshold)


def test_one_element_needs_its_length():
    with pytest.raises(ValueError, match="element_length is needed"):
        space_time(np.arange(3.0), [1.0], np.zeros((3, 1)))
    st = space_time(np.arange(5.0), [1.0], [[0], [2], [2], [0], [0]], element_length=0.3)
    (e,) = detect_events(st, 1.0)
    assert e.spanning and e.extent == pytest.approx(0.3)
    # the event's slip runs from the last sample below the threshold to the first one after
    # (the trapezoidal slip of [0, 2, 2, 0] is 4; from the first sample above, 3)
    assert e.mean_slip == pytest.approx(4.0) and e.moment == pytest.approx(1.2)


def test_precursor_trend():
    # mistake: "grows" from the sign of rho alone, whatever its p-value
    from dryfriction.analysis.catalogue import Precursors, precursor_trend

    def pre(ratio, length):
        z = np.zeros(len(ratio))
        return Precursors(np.array(ratio, float), np.array(length, float), z, z.astype(int),
                          np.array([]), np.array([]))

    assert precursor_trend(pre([0.1, 0.2, 0.3, 0.4, 0.5], [2, 3, 5, 8, 13])).grows == "yes"
    down = precursor_trend(pre([0.1, 0.2, 0.3, 0.4, 0.5], [13, 8, 5, 3, 2]))
    assert down.grows == "decreasing" and down.rho == pytest.approx(-1.0)
    weak = precursor_trend(pre([0.1, 0.2, 0.3], [2, 5, 3]))  # rho = 0.5, p = 0.67
    assert weak.rho == pytest.approx(0.5) and weak.grows == "not significant"
    assert precursor_trend(pre([0.1, 0.2], [2, 5])).grows == "undetermined"


def test_front_regimes_against_the_sound_speed():
    # mistakes: the speed not divided by the sound speed; a front of under 3 elements classed
    from dryfriction.analysis.catalogue import front_regimes

    t, x = grid(n_x=30, dx=0.5, t_end=14.0, dt=0.013)
    # a slow front keeps the elements behind it slipping (h = 2 > dx/c): one connected event
    pulses = [Pulse(0, 0, 5, 1.0, 0.4, h=2.0), Pulse(15, 10, 29, 9.0, 9.0),
              Pulse(29, 28, 29, 12.0, 2.0)]
    st = space_time(t, x, *fields(t, x, pulses))
    reg = front_regimes(detect_events(st, THR), sound_speed=10.0)
    assert reg.regime == ["slow", "fast", "fast"] and reg.count("slow") == 1
    assert list(reg.event) == [0, 1, 1] and list(reg.direction) == [1, -1, 1]
    assert reg.ratio == pytest.approx([0.04, 0.9, 0.9])
    with pytest.raises(ValueError, match="sound_speed"):
        front_regimes([], sound_speed=0.0)


def test_interface_result_is_read_with_its_units():
    # the simulator's contract (ensemble/interface_result.py): positions in element spacings,
    # each element 1 long; the load's unit without its remark; side loading from block 0
    from dryfriction.analysis.fronts import (
        from_result,
        interface_loaded_edge,
        interface_normal_load,
        interface_sound_speed,
    )
    from dryfriction.ensemble.interface_result import InterfaceResult

    t, x = grid(n_x=12, dx=1.0, x0=0.5, t_end=6.0)
    v, s = fields(t, x, [Pulse(0, 0, 7, 1.0, 2.0)])
    res = InterfaceResult(t=t, x=x, slip=s, slip_rate=v, stress=np.zeros_like(v),
                          load=0.2 * t, load_point=0.01 * t,
                          params={"model": {"mu_el": 0.4}, "interface": {"coupling": 8.0,
                                  "mass": 0.5}, "drive": {"loading": "side"}})
    st = from_result(res)
    # the load is the whole chain's, in one element's F_el (as load.csv and summary.json)
    assert st.units["x"] == "element" and st.units["load"] == "F_el"
    (e,) = detect_events(st, THR)
    assert e.extent == pytest.approx(8.0) and e.fronts[1].mean_speed == pytest.approx(2.0)
    assert interface_normal_load(res) == pytest.approx(12 / 0.4)
    assert interface_loaded_edge(res) == "left" and interface_sound_speed(res) == 4.0
    _, units = catalogue_columns([e], st, THR)
    assert units["moment"] == "a0*element" and units["speed_right"] == "element/t0"
    assert units["load_arrest"] == "F_el"  # the load's unit
    # N = 1 (the single slider): its one element is one spacing long
    one = InterfaceResult(t=t, x=x[:1], slip=s[:, :1], slip_rate=v[:, :1],
                          stress=np.zeros_like(v[:, :1]), load=0.2 * t, load_point=0.01 * t,
                          params={})
    assert from_result(one).lengths == pytest.approx([1.0])


def test_simultaneous_slip_is_an_instantaneous_front():
    # mistake: a zero slowness read as "no front" (NaN) instead of an infinite speed
    t = np.linspace(0.0, 4.0, 401)
    x = np.arange(8.0)
    v = np.where((t > 1.0) & (t < 2.0), 3.0, 0.0)[:, None] * np.ones((1, 8))
    (e,) = detect_events(space_time(t, x, v), 1.0)
    assert e.spanning and e.fronts[1].mean_speed == math.inf
    assert e.fronts[0].mean_speed == math.inf and np.all(np.isinf(e.fronts[1].speed))


def test_triggered_precursors_leave_out_the_reslips_after_a_drop():
    # mistakes: the test against the last event's start load (not every earlier one's), so a
    # second re-slip is kept; the filter applied to the spanning events too; the bar raised
    # by an event away from the edge
    t, x = grid(n_x=40, dx=0.5, t_end=24.0, dt=0.013)
    # precursors at t = 1 (to 7), 6 (to 15), 10 (to 25); re-slips at t = 3.5 and 4.5 (to 2
    # and 3) while the load is below where the one at t = 1 started (the second above the
    # first's); a global slip at t = 16 after a drop of the load; an event far from the edge
    # at t = 5 during a brief rise of the load above where the second precursor starts
    pulses = [Pulse(30, 30, 30, 5.0, 4.0),
              Pulse(0, 0, 7, 1.0, 4.0), Pulse(0, 0, 2, 3.5, 4.0), Pulse(0, 0, 3, 4.5, 4.0),
              Pulse(0, 0, 15, 6.0, 4.0), Pulse(0, 0, 25, 10.0, 4.0),
              Pulse(0, 0, 39, 16.0, 4.0)]
    v, s = fields(t, x, pulses)
    load = (0.3 + 0.05 * t - 0.2 * ((t > 1.5) & (t < 5.5)) - 0.8 * (t > 15.5)
            + 1.0 * ((t > 4.8) & (t < 5.3)))
    st = space_time(t, x, v, s, load)
    events = detect_events(st, THR)
    assert [e.spanning for e in events] == [False] * 6 + [True]
    assert [e.elements[0] for e in events] == [0, 0, 0, 30, 0, 0, 0]
    every = precursors(events, st, 2.5, edge="left")
    assert every.length == pytest.approx([4.0, 1.5, 2.0, 8.0, 13.0])
    pre = precursors(events, st, 2.5, edge="left", triggered=True)
    assert pre.length == pytest.approx([4.0, 8.0, 13.0])
    assert pre.spanning_ratio.size == 1  # the global slip, at a lower load, still counted
