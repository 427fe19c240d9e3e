"""fit.identify's helpers called directly against their docstrings' definitions, written out
in the test (issue 25): change_index (an up-step, a down-step, a hold), worse_than_noise on
both sides of its edge (the steady part's noise with two degrees of freedom taken by its
line), join_flags, and steady_before's slip and remnant transient after a velocity step and
after a hold, on both sides of the 2x-white-noise allowance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.fit.identify import (
    MISFIT_RMS,
    change_index,
    join_flags,
    split_flags,
    steady_before,
    worse_than_noise,
)
from dryfriction.records.data import SeriesData

DT = 0.25
T0 = 13.0


def _series(v: list[tuple[float, int]], mu: np.ndarray | None = None) -> SeriesData:
    vl = np.concatenate([np.full(n, x) for x, n in v])
    t = T0 + DT * np.arange(vl.size)
    return SeriesData(t, vl, np.full(vl.size, 0.6) if mu is None else mu)


def test_change_index_is_the_first_sample_of_the_new_velocity() -> None:
    assert change_index(_series([(1e-6, 7), (3e-6, 5)])) == 7
    assert change_index(_series([(3e-6, 4), (0.8e-6, 9), (2e-6, 3)])) == 4  # down, the first
    assert change_index(_series([(2e-6, 6), (0.0, 5), (2e-6, 5)])) == 6  # a hold's start
    assert change_index(_series([(2e-6, 9)])) == 0


def test_worse_than_noise_against_the_steady_parts_line_by_hand() -> None:
    n = 60
    rng = np.random.default_rng(4)
    mu = 0.61 + 2e-4 * np.arange(n) * DT + rng.normal(0.0, 3e-4, n)
    d = _series([(1e-6, 20), (3e-6, 40)], mu)
    tail = slice(n * 2 // 3, n)  # the last third, about its least-squares line in time
    p = np.polyfit(d.t[tail], mu[tail], 1)
    r = mu[tail] - np.polyval(p, d.t[tail])
    s = math.sqrt(float(r @ r) / (r.size - 2))
    assert worse_than_noise(d, MISFIT_RMS * s * (1 + 1e-9))
    assert not worse_than_noise(d, MISFIT_RMS * s * (1 - 1e-9))
    assert not worse_than_noise(_series([(1e-6, 4), (2e-6, 5)]), 1.0)  # 3 calm samples: no


def test_join_flags_keeps_the_first_of_each_word_in_order() -> None:
    words = ["bound", "misfit", "bound", "not_steady_before", "misfit"]
    cell = join_flags(words)
    assert cell == "bound;misfit;not_steady_before"
    assert split_flags(cell) == ["bound", "misfit", "not_steady_before"]
    assert join_flags([]) == "" and split_flags("") == []


B, DC = 0.011, 8e-6


def _remnant_case(hold: bool) -> tuple[SeriesData, int, float, float]:
    """The record, the window's start, the slip since the previous change and the remnant
    transient by hand: b |ln(v_after/v_before)| e^(-slip/Dc) after a step, b ln(1 + t_h v/Dc)
    e^(-slip/Dc) after a hold of t_h at v (the velocity before it)."""
    if hold:
        rec = _series([(1.1e-6, 20), (0.0, 10), (2.3e-6, 20), (0.6e-6, 40)])
        slip = 2.3e-6 * 20 * DT
        amp = B * math.log1p(10 * DT * 1.1e-6 / DC)
    else:  # 1.1 -> 3.7 um/s, then down to 0.9 um/s in the window
        rec = _series([(1.1e-6, 30), (3.7e-6, 20), (0.9e-6, 40)])
        slip = 3.7e-6 * 20 * DT
        amp = B * math.log(3.7 / 1.1)
    return rec, 44, slip, amp * math.exp(-slip / DC)


@pytest.mark.parametrize("hold", [False, True])
def test_steady_before_slip_and_remnant_by_hand(hold: bool) -> None:
    rec, i0, slip, rem = _remnant_case(hold)
    d = SeriesData(rec.t[i0:i0 + 30], rec.v_load[i0:i0 + 30], rec.mu[i0:i0 + 30])
    zero = np.zeros(len(d))
    for white, said in ((rem / 2 * (1 + 1e-6), False), (rem / 2 * (1 - 1e-6), True)):
        got, words = steady_before(d, zero, {"noise": math.nan, "white_noise": white}, rec,
                                   i0, B, DC)
        assert got == pytest.approx(slip, rel=1e-12)
        assert bool(words) is said
        if said:
            assert words == [f"{slip * 1e6:.3g} um ({slip / DC:.2g} Dc) of slip since the "
                             f"previous change leave a transient of about {rem:.2g} (> 2x the "
                             "white noise)"]
