"""dryfriction.results.check_physical's bounds each on both sides of its tolerance (issue 25:
the existing test names each bound once, far from its edge): a slide back or a slip over the
allowed travel within ``tol`` passes, just beyond it does not; NaN allowed in velocity and
friction (an undefined sample), never in time or position; time that stands still passes,
time that runs back is refused at the sample where it does."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.results import ImpossibleResultError, check_physical

T = np.array([0.3, 0.9, 0.9, 2.6])  # a repeated time: allowed (non-decreasing)
V = np.array([1e-6, np.nan, 2e-6, 1.5e-6])
MU = np.array([0.61, np.nan, 0.58, 0.6])


def test_a_slide_back_within_the_tolerance_passes() -> None:
    x = np.array([1.0, 1.7, 1.7 - 0.25, 2.1])  # back by 0.25 after the maximum 1.7
    check_physical("r", T, x, V, MU, unit="a0", forward=True, tol=0.25 * (1 + 1e-9))
    with pytest.raises(ImpossibleResultError, match=r"moved backwards by 0.25 a0 \(at t = 0.9\)"):
        check_physical("r", T, x, V, MU, unit="a0", forward=True, tol=0.25 * (1 - 1e-9))
    check_physical("r", T, x, V, MU, unit="a0")  # not forward: no bound on it


def test_the_slip_bound_and_the_integral_within_the_tolerance() -> None:
    x = np.array([1.0, 1.7, 1.9, 2.1])  # slip 1.1
    check_physical("r", T, x, V, MU, unit="m", slip_max=1.0, tol=0.1 * (1 + 1e-6))
    with pytest.raises(ImpossibleResultError, match="slip 1.1 m is more than"):
        check_physical("r", T, x, V, MU, unit="m", slip_max=1.0, tol=0.1 * (1 - 1e-6))
    check_physical("r", T, x, V, MU, unit="m", slip_integral=1.1 - 0.02, tol=0.02 * (1 + 1e-6))
    with pytest.raises(ImpossibleResultError, match="not the integral of the velocity"):
        check_physical("r", T, x, V, MU, unit="m", slip_integral=1.1 + 0.02,
                       tol=0.02 * (1 - 1e-6))


def test_nan_and_time_order() -> None:
    x = np.array([1.0, 1.7, 1.9, 2.1])
    check_physical("r", T, x, V, MU, unit="m", mu_min=0.58)  # NaN friction is not below
    with pytest.raises(ImpossibleResultError, match="below the model's bound 0.59"):
        check_physical("r", T, x, V, MU, unit="m", mu_min=0.59)
    with pytest.raises(ImpossibleResultError, match="t = nan at sample 2"):
        check_physical("r", np.array([0.3, 0.9, np.nan, 2.6]), x, V, MU, unit="m")
    with pytest.raises(ImpossibleResultError, match=r"time runs backwards at sample 3 "
                                                    r"\(t = 0.8\)"):
        check_physical("r", np.array([0.3, 0.9, 0.95, 0.8]), x, V, MU, unit="m")
    with pytest.raises(ImpossibleResultError, match="v = -inf at sample 1"):
        check_physical("r", T, x, np.array([1e-6, -np.inf, 0.0, 0.0]), MU, unit="m")
