"""dryfriction.results.summarize key by key against its documented definition (the module
docstring's table), written out in the test, on a series that exercises every branch: a
non-uniform grid that does not start at t = 0, a slider that moves back, a NaN friction sample
beside the peak, a NaN velocity, and the one-sample and zero-span edges."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.results import COMMON_SUMMARY_KEYS, summarize

T = np.array([3.7, 3.9, 4.6, 4.65, 6.1, 8.0])  # non-uniform, starts at 3.7 s
X = np.array([1.2e-6, 1.9e-6, 1.5e-6, 2.6e-6, 2.4e-6, 3.1e-6])  # back at samples 2 and 4
V = np.array([2e-7, np.nan, 5e-7, 1.1e-6, -2e-6, 4e-7])  # a faster slip back
MU = np.array([0.61, 0.64, np.nan, 0.58, 0.66, 0.63])
UNITS = {"t": "s", "x": "m", "v": "m/s", "mu": ""}


def test_every_key_by_its_definition() -> None:
    s = summarize("rsf", T, X, V, MU, UNITS, partial=True, extra={"solver": "lsoda"})
    assert list(s)[:len(COMMON_SUMMARY_KEYS)] == list(COMMON_SUMMARY_KEYS)
    assert s["law"] == "rsf" and s["partial"] is True and s["samples"] == 6
    assert s["duration"] == pytest.approx(8.0 - 3.7, rel=1e-14)  # t[-1] - t[0], not t[-1]
    # the peak beside a NaN: the largest finite friction, at its time and position
    assert (s["peak_mu"], s["peak_t"], s["peak_x"]) == (0.66, 6.1, 2.4e-6)
    assert s["final_mu"] == 0.63
    # the time average by the trapezoid rule, over the span (the NaN sample makes it NaN
    # on the whole series: checked here on the finite part separately below)
    assert math.isnan(s["mean_mu"])
    assert s["slip"] == pytest.approx(3.1e-6 - 1.2e-6, rel=1e-12)
    path = sum(abs(X[i + 1] - X[i]) for i in range(len(X) - 1))
    assert s["path_length"] == pytest.approx(path, rel=1e-12) and path > s["slip"] * 1.5
    assert s["v_max"] == 1.1e-6  # the largest finite velocity, signed (a NaN beside it)
    # every column's unit ("" the dimensionless "1", fixE) and the common keys' from theirs
    assert s["units"] == {"t": "s", "x": "m", "v": "m/s", "mu": "1", "samples": "1",
                          "duration": "s", "peak_mu": "1", "peak_t": "s", "peak_x": "m",
                          "final_mu": "1", "mean_mu": "1", "slip": "m", "path_length": "m",
                          "v_max": "m/s"}
    assert s["solver"] == "lsoda"


def test_mean_friction_is_the_trapezoid_time_average_on_a_non_uniform_grid() -> None:
    mu = np.array([0.61, 0.64, 0.70, 0.58, 0.66, 0.63])
    s = summarize("cv", T, X, V, mu, UNITS)
    area = sum(0.5 * (mu[i] + mu[i + 1]) * (T[i + 1] - T[i]) for i in range(len(T) - 1))
    assert s["mean_mu"] == pytest.approx(area / (T[-1] - T[0]), rel=1e-12)
    # not the sample mean (the grid is not uniform)
    assert abs(s["mean_mu"] - float(np.mean(mu))) > 1e-3
    assert s["partial"] is False and s["peak_mu"] == 0.70 and s["peak_t"] == 4.6


def test_one_sample_and_a_zero_span() -> None:
    s = summarize("rsf", [2.5], [4e-6], [1e-6], [0.59], UNITS)
    assert s["duration"] == 0.0 and s["mean_mu"] == 0.59 and s["path_length"] == 0.0
    assert s["samples"] == 1 and s["slip"] == 0.0
    # all-NaN friction and velocity: the first sample, no velocity
    s = summarize("rsf", [1.0, 2.0], [0.0, 1.0], [np.nan, np.nan], [np.nan, np.nan], UNITS)
    assert s["peak_t"] == 1.0 and math.isnan(s["v_max"])
    with pytest.raises(ValueError, match="at least one sample"):
        summarize("rsf", [], [], [], [], UNITS)
    with pytest.raises(ValueError, match="'slip' is common"):
        summarize("rsf", T, X, V, MU, UNITS, extra={"slip": 1.0})
