"""The small quantities the fronts analysis reads off an interface run (analysis/fronts.py)
against their definitions (issue 25): the normal load with mu_el != 1, the sound speed and
its NaN cases, the units of speed and moment in both branches, the default threshold from a
backward program, the threshold's refusal at 0, and the local speed at the ends of a front
(truncated windows, at least 3 elements)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from dryfriction.analysis.fronts import (
    THRESHOLD_FACTOR,
    check_threshold,
    default_threshold,
    front_speeds,
    interface_loaded_edge,
    interface_normal_load,
    interface_sound_speed,
    moment_unit,
    speed_unit,
)


def _run(**params):  # type: ignore[no-untyped-def]
    return SimpleNamespace(x=np.zeros(7), params=params)


def test_run_quantities() -> None:
    assert interface_normal_load(_run(model={"mu_el": 0.4})) == pytest.approx(7 / 0.4)
    assert interface_normal_load(_run()) == 7.0
    assert interface_sound_speed(_run(interface={"coupling": 2.6, "mass": 0.65})) == \
        pytest.approx(2.0, rel=1e-15)
    assert interface_sound_speed(_run(interface={"coupling": 0.0, "mass": 0.65})) == 0.0
    for p in ({"coupling": 2.6, "mass": 0.0}, {"coupling": 2.6}, {}):
        assert math.isnan(interface_sound_speed(_run(interface=p)))
    assert interface_loaded_edge(_run(drive={"loading": "side"})) == "left"
    assert interface_loaded_edge(_run(drive={"loading": "uniform"})) is None
    segs = [{"velocity": 0.2, "slip": 1.0}, {"velocity": 0.0, "duration": 3.0},
            {"velocity": -0.7, "slip": 0.5}]
    assert THRESHOLD_FACTOR == 10.0
    assert default_threshold(_run(drive={"segments": segs})) == pytest.approx(7.0)
    assert math.isnan(default_threshold(_run(drive={"segments": [segs[1]]})))
    assert math.isnan(default_threshold(_run()))


def test_units_and_threshold_refusal() -> None:
    assert speed_unit({"x": "m", "t": "ms"}) == "m/ms"
    assert moment_unit({"x": "a0", "slip": "a0"}) == "a0^2"
    assert moment_unit({"x": "m", "slip": "um"}) == "um*m"
    assert check_threshold(0.25) == 0.25
    for bad in (0.0, -1.0, math.inf, math.nan):
        with pytest.raises(ValueError, match=r"^threshold = .* out of range: the slip-rate "
                                             r"threshold must be finite and > 0 \[m/s\]$"):
            check_threshold(bad, "m/s")


def test_local_speeds_at_the_ends_of_a_front() -> None:
    """Arrival times linear in x (speed 2.7): every element, the first and last ones on their
    truncated windows, gets that speed; fewer than 3 elements in a window give NaN."""
    x = 0.5 * np.arange(9)
    t = 1.3 + x / 2.7
    for h in (2, 4):
        s, lo, hi = front_speeds(x, t, +1, half_window=h)
        np.testing.assert_allclose(s, 2.7, rtol=1e-12)
        assert np.all(lo <= s + 1e-12) and np.all(s <= hi + 1e-12)
    s, _, _ = front_speeds(-x, t, -1, half_window=1)  # a left-going front: speed > 0
    np.testing.assert_allclose(s[1:-1], 2.7, rtol=1e-12)
    assert np.isnan(s[0]) and np.isnan(s[-1])  # two elements in the end windows
    s, _, _ = front_speeds(x[:2], t[:2], +1, half_window=3)
    assert np.all(np.isnan(s))
    for bad in (0, 1.5):
        with pytest.raises(ValueError, match="half_window = .* a whole number >= 1"):
            front_speeds(x, t, +1, half_window=bad)  # type: ignore[arg-type]
