"""fit.statistics' small estimators at their edges (issue 25): the 95 % quantile (normal with
given uncertainties or no degree of freedom, Student t otherwise, at dof 1 and 7 against
tabulated values) and the runs test's refusals (fewer than six signs, one sign only) and its
zeros, which are no signs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.fit.statistics import Z95, quantile_95, runs_test


def test_quantile_95_normal_or_student() -> None:
    assert Z95 == pytest.approx(1.959963985, rel=1e-9)
    assert quantile_95(True, 7) == Z95 and quantile_95(False, 0) == Z95
    assert quantile_95(False, 1) == pytest.approx(12.7062047, rel=1e-7)  # t tables
    assert quantile_95(False, 7) == pytest.approx(2.36462425, rel=1e-7)


def test_runs_test_edges_and_zeros() -> None:
    assert runs_test(np.array([1.0, -1.0, 2.0, -0.5, 0.3])) is None  # five signs
    assert runs_test(np.array([1.0, 2.0, 0.0, 3.0, 4.0, 5.0, 6.0])) is None  # one sign
    six = np.array([0.4, 0.7, -0.2, -0.9, 0.3, -0.6])
    p = runs_test(six)
    # by hand: n1 = n2 = 3, 4 runs; mean 2 n1 n2/n + 1 = 4: z = 0, p = 1
    assert p == pytest.approx(1.0, abs=1e-12)
    with_zeros = np.array([0.4, 0.0, 0.7, -0.2, 0.0, -0.9, 0.3, -0.6, 0.0])
    assert runs_test(with_zeros) == p
    alt = np.array([1.0, -1.0] * 5)  # 10 runs of 10 signs: n1 = n2 = 5
    mean, var = 6.0, 2.0 * 25 * (50 - 10) / (100 * 9)
    want = math.erfc(abs(10 - mean) / math.sqrt(var) / math.sqrt(2.0))
    assert runs_test(alt) == pytest.approx(want, rel=1e-12)
