"""Stick-slip measures against their definitions on a signal built to know them (issue 25:
an estimator never checked against its definition hides an off-by-one).

:func:`~dryfriction.analysis.stickslip.analyse` reports the time-weighted fraction of the
window the slider sticks (``v < stick_fraction u``), each sample standing for the step that
ends at it. On irregular sampling the sample that starts a step and the one that ends it
weigh differently, which is what the test uses: a sawtooth load, a velocity that is slow on
the ramps and fast in the drops, sampled at jittered times.
"""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.analysis.stickslip import analyse


def _sawtooth(seed: int) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(seed)
    dt = rng.uniform(0.013, 0.11, 4000)  # jittered, 1:8
    t = np.concatenate(([0.0], np.cumsum(dt)))
    u = 0.37
    period = 23.0
    phase = (t % period) / period
    slow = phase < 0.83  # sticking on the ramp, slipping in the last 17 %
    v = np.where(slow, 0.04 * u, 9.0 * u)
    x = np.concatenate(([0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))))
    load = np.where(slow, 0.6 + 0.05 * phase / 0.83, 0.65 - 0.05 * (phase - 0.83) / 0.17)
    return t, x, v, load, u


@pytest.mark.parametrize("seed", [3, 17])
def test_stick_fraction_is_its_definition(seed: int) -> None:
    t, x, v, load, u = _sawtooth(seed)
    got = analyse(t, x, v, load, u=u, floor=1e-3)
    slow = v < 0.5 * u
    want = float(np.sum(np.diff(t)[slow[1:]]) / (t[-1] - t[0]))  # step ending at a slow one
    assert got.stick_fraction == pytest.approx(want, rel=1e-12)
    assert got.stick_fraction == pytest.approx(0.83, abs=0.02)  # and the built-in truth
    assert got.events >= 8
