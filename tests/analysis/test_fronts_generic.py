"""Fronts, events and the catalogue at generic points (issue 25): a non-uniform grid (a uniform
one hides a plain mean for a length-weighted one), fronts of different speeds on either side
(equal speeds hide a swapped column), units other than the reduced ones, the mirror image of a
run (left and right exchange), a load read between samples, and estimators against a hand
computation. Each test names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from dryfriction.analysis.catalogue import (
    catalogue_columns,
    front_regimes,
    magnitude_frequency,
    precursors,
)
from dryfriction.analysis.fronts import (
    Front,
    default_threshold,
    detect_events,
    element_lengths,
    space_time,
)
from dryfriction.io.files import write_csv
from dryfriction.io.units import read_rows
from fronts_synth import Pulse, fields

THR = 0.6  # slip-rate threshold; the pulses reach A = 4
# a non-uniform grid: gaps between 0.25 and 0.71, no two neighbours alike
X = 1.3 + np.concatenate([[0.0], np.cumsum(0.25 + 0.46 * np.abs(np.sin(1.7 * np.arange(35))))])


def _delay(p: Pulse) -> float:
    """Time from an element's arrival to its slip rate crossing THR on the rise."""
    return p.r * THR / p.A


def test_element_lengths_on_a_non_uniform_grid() -> None:
    # mistakes: an end cell of half its neighbour's gap (a cell clipped at the end); the end
    # cells mirroring the far end's spacing; the cell as the gap to the right only
    x = [0.3, 0.8, 2.0, 2.3, 3.9]
    assert element_lengths(x) == pytest.approx([0.5, 0.85, 0.75, 0.95, 1.6], rel=1e-14)
    assert element_lengths(x, element_length=0.37) == pytest.approx([0.37] * 5)


def test_slip_from_the_rate_is_the_trapezoidal_integral() -> None:
    # mistake: the slip as a rectangle sum of the rate (rate[1:] dt), or not from zero at t[0]
    t = np.sqrt(np.linspace(0.0, 9.0, 57)) + 0.4  # non-uniform sampling, from t = 0.4
    alpha = np.array([0.3, 1.7, 2.9])
    v = (t[:, None] - 0.4) * alpha[None, :] + 0.11  # linear in t: the trapezoid is exact
    st = space_time(t, [0.0, 1.0, 2.0], v)
    want = 0.5 * (t[:, None] - 0.4) ** 2 * alpha[None, :] + 0.11 * (t[:, None] - 0.4)
    np.testing.assert_allclose(st.slip, want, rtol=1e-12, atol=1e-14)


def test_moment_is_length_weighted_on_a_non_uniform_grid() -> None:
    # mistakes: the moment as the mean slip times the extent, or as the summed slip times the
    # mean spacing (both right on a uniform grid only)
    x = np.array([0.3, 0.8, 2.0, 2.3, 3.9, 4.4])
    t = np.linspace(0.0, 4.0, 401)
    v = np.zeros((t.size, x.size))
    v[101:200, 1:5] = 3.0  # elements 1..4 slip together, samples 101..199
    S = np.array([0.0, 0.7, 2.3, 0.4, 1.9, 0.0])
    s = S[None, :] * (t[:, None] > 1.5) + 0.05 * t[:, None]  # the event's slip jumps by S
    (e,) = detect_events(space_time(t, x, v, s), 1.0)
    lengths = np.array([0.85, 0.75, 0.95, 1.05])  # of elements 1..4, by hand
    ds = S[1:5] + 0.05 * (t[200] - t[100])  # and the creep from the sample before to after
    assert e.extent == pytest.approx(lengths.sum(), rel=1e-14)
    assert e.moment == pytest.approx(float(np.sum(ds * lengths)), rel=1e-12)
    assert e.mean_slip == pytest.approx(float(np.sum(ds * lengths) / lengths.sum()), rel=1e-12)
    assert e.slip == pytest.approx(ds, rel=1e-12)


def _asymmetric(x: np.ndarray, t_nuc: float = 1.1, c_left: float = 1.3, c_right: float = 3.7,
                i_nuc: int = 13, lo: int = 3, hi: int = 31) -> list[Pulse]:
    """One event nucleating at ``i_nuc``, its left front at ``c_left``, its right at
    ``c_right`` (two pulses on disjoint elements, connected at the nucleation)."""
    return [Pulse(i_nuc, i_nuc, hi, t_nuc, c_right), Pulse(i_nuc, lo, i_nuc - 1, t_nuc, c_left)]


def test_fronts_of_different_speeds_and_the_catalogue_in_other_units(tmp_path) -> None:
    # mistakes: speed_left read from the right front (equal speeds hide it); t_arrest the
    # arrival at the last element of the row, not the latest; the speed's unit as x*t
    t = np.arange(0.0, 14.0, 0.0093)
    pulses = _asymmetric(X)
    v, s = fields(t, X, pulses)
    units = {"t": "ms", "x": "mm", "slip": "um", "slip_rate": "um/ms", "load": "kN"}
    st = space_time(t, X, v, s, 0.4 + 0.02 * t, units)
    (e,) = detect_events(st, THR)
    left, right = e.fronts
    assert left.mean_speed == pytest.approx(1.3, rel=1e-6)
    assert right.mean_speed == pytest.approx(3.7, rel=1e-6)
    arrive = {i: 1.1 + abs(X[i] - X[13]) / (3.7 if i >= 13 else 1.3) for i in range(3, 32)}
    d = _delay(pulses[0])
    assert e.t_start == pytest.approx(1.1 + d, abs=1e-9)
    assert e.t_arrest == pytest.approx(max(arrive.values()) + d, abs=1e-9)
    assert max(arrive, key=arrive.get) == 3  # the slow left front arrives last
    path = write_csv(tmp_path / "events.csv", *catalogue_columns([e], st, THR))
    head = open(path).readline().strip().split(",")
    for h in ("t_start[ms]", "extent[mm]", "mean_slip[um]", "moment[um*mm]",
              "speed_left[mm/ms]", "speed_right_high[mm/ms]", "load_arrest[kN]",
              "threshold[um/ms]"):
        assert h in head
    (row,) = read_rows(path)
    assert float(row["speed_left"]) == pytest.approx(1.3, rel=1e-6)
    assert float(row["speed_right"]) == pytest.approx(3.7, rel=1e-6)
    assert float(row["speed_left_low"]) <= 1.3 * (1 + 1e-6)
    assert float(row["speed_left_high"]) >= 1.3 * (1 - 1e-6)
    assert float(row["extent"]) == pytest.approx(float(np.sum(element_lengths(X)[3:32])))
    assert float(row["x_min"]) == X[3] and float(row["x_max"]) == X[31]
    assert float(row["n_elements"]) == 29 and float(row["threshold"]) == THR
    assert float(row["duration"]) == pytest.approx(e.t_end - e.t_start)
    assert float(row["load_arrest"]) == pytest.approx(0.4 + 0.02 * e.t_arrest, rel=1e-12)


def test_the_mirror_image_exchanges_the_fronts_and_the_loaded_edge() -> None:
    # mistakes: the right edge's precursor length from the event's far end minus one element,
    # or the right edge's test one element short (an event reaching the last element missed)
    t = np.arange(0.0, 20.0, 0.011)
    pulses = [Pulse(0, 0, 7, 1.0, 2.3), Pulse(0, 0, 15, 4.0, 2.3), *_asymmetric(X, 9.0),
              Pulse(0, 0, 35, 14.5, 4.5)]
    v, s = fields(t, X, pulses)
    load = 0.3 + 0.05 * t
    st = space_time(t, X, v, s, load)
    xm = -X[::-1]  # the mirror image: element i is element N - 1 - i
    sm = space_time(t, xm, v[:, ::-1], s[:, ::-1], load)
    ev, em = detect_events(st, THR), detect_events(sm, THR)
    assert len(ev) == len(em) == 4
    n = X.size
    for a, b in zip(ev, em, strict=True):
        assert b.i_nucleation == n - 1 - a.i_nucleation
        assert b.extent == pytest.approx(a.extent, rel=1e-12)
        assert b.moment == pytest.approx(a.moment, rel=1e-12)
        assert b.t_arrest == pytest.approx(a.t_arrest, abs=1e-12)
        assert b.fronts[0].mean_speed == pytest.approx(a.fronts[1].mean_speed, rel=1e-9,
                                                       nan_ok=True)
        assert b.fronts[1].mean_speed == pytest.approx(a.fronts[0].mean_speed, rel=1e-9,
                                                       nan_ok=True)
    assert ev[2].fronts[1].mean_speed == pytest.approx(3.7, rel=1e-6)
    pl = precursors(ev, st, 2.5, edge="left")
    pr = precursors(em, sm, 2.5, edge="right")
    lengths = element_lengths(X)
    assert pl.length == pytest.approx([lengths[:8].sum(), lengths[:16].sum()], rel=1e-12)
    assert pr.length == pytest.approx(pl.length, rel=1e-12)
    assert pr.ratio == pytest.approx(pl.ratio, rel=1e-12)
    assert pr.spanning_ratio == pytest.approx(pl.spanning_ratio, rel=1e-12)
    assert len(precursors(em, sm, 2.5, edge="left").length) == 0


def test_load_at_start_arrest_and_end_is_interpolated_between_samples() -> None:
    # mistakes: the load of the nearest sample (or of the sample after) for the interpolated
    # one; the arrest's load read at the start or at the end
    t = np.arange(0.0, 9.0, 0.037)
    load = 0.21 + 0.033 * t + 0.013 * np.sin(1.3 * t)
    v, s = fields(t, X, [Pulse(4, 0, 30, 1.05, 2.9)])
    (e,) = detect_events(space_time(t, X, v, s, load), THR)

    def by_hand(time: float) -> float:
        j = int(np.searchsorted(t, time))  # t[j - 1] < time <= t[j]
        w = (time - t[j - 1]) / (t[j] - t[j - 1])
        return float(load[j - 1] + w * (load[j] - load[j - 1]))

    for time, got in ((e.t_start, e.load_start), (e.t_arrest, e.load_arrest),
                      (e.t_end, e.load_end)):
        assert min(abs(time - t)) > 1e-3  # between samples
        assert got == pytest.approx(by_hand(time), rel=1e-13)
    assert e.t_start < e.t_arrest < e.t_end


def test_power_law_exponent_by_hand_and_scale_free() -> None:
    # mistakes: m_min itself left out of the fit (> for >=); the logarithms taken from the
    # smallest fitted moment, not from m_min; the error over sqrt(n - 1); the moments below
    # m_min kept
    for scale in (0.37, 13.0):
        m = scale * np.array([0.2, 1.0, 2.0, 4.0, 8.0, 2.0, 0.6])
        mf = magnitude_frequency(m, m_min=scale * 1.0)
        a = 1.0 + 5.0 / (7.0 * math.log(2.0))  # five moments >= 1: logs 0, 1, 2, 3, 1 (x ln 2)
        assert mf.n_fit == 5
        assert mf.alpha == pytest.approx(a, rel=1e-12)
        assert mf.alpha_err == pytest.approx((a - 1.0) / math.sqrt(5.0), rel=1e-12)
        assert list(mf.count) == [1, 2, 4, 4, 5, 6, 7]
        low = magnitude_frequency(m, m_min=scale * 0.9)  # between two moments
        b = 1.0 + 5.0 / (7.0 * math.log(2.0) + 5.0 * math.log(1.0 / 0.9))
        assert low.n_fit == 5 and low.alpha == pytest.approx(b, rel=1e-12)


def _front(direction: int, mean: float, low: float, high: float) -> Front:
    e = np.array([])
    return Front(direction, e, e, e, e, e, mean, low, high)


def test_front_regimes_by_the_whole_interval_at_a_given_fraction() -> None:
    # mistakes: the class from the mean speed alone (an interval across the fraction called
    # slow or fast); the fraction argument ignored (the default 0.1 used)
    c, frac = 7.0, 0.3
    events = [SimpleNamespace(index=0, fronts=(_front(-1, 1.4, 1.2, 1.9),
                                               _front(1, 2.2, 1.9, 2.6))),
              SimpleNamespace(index=1, fronts=(_front(-1, math.nan, math.nan, math.nan),
                                               _front(1, 2.2, 2.15, 2.5)))]
    reg = front_regimes(events, sound_speed=c, fraction=frac)  # type: ignore[arg-type]
    assert reg.regime == ["slow", "undetermined", "fast"]
    assert list(reg.event) == [0, 0, 1] and list(reg.direction) == [-1, 1, 1]
    assert reg.ratio == pytest.approx([0.2, 2.2 / 7, 2.2 / 7])
    assert reg.ratio_low == pytest.approx([1.2 / 7, 1.9 / 7, 2.15 / 7])
    assert reg.fraction == 0.3 and reg.count("undetermined") == 1


def test_default_threshold_from_the_fastest_loading_of_either_sign() -> None:
    # mistakes: the largest signed velocity (a fast reverse segment missed); the first
    # segment's velocity
    res = SimpleNamespace(params={"drive": {"segments": [
        {"velocity": 0.02}, {"velocity": -0.057}, {"velocity": None}, {"velocity": 0.031}]}})
    assert default_threshold(res) == pytest.approx(0.57, rel=1e-14)
    assert math.isnan(default_threshold(SimpleNamespace(params={})))
