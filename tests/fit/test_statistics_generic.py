"""Small covariance helpers of fit/statistics.py at a generic point (issue 25): a 3 x 3
covariance with correlations of both signs, a standard error changed by a factor other than
1. Each test names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.fit.statistics import Covariance, covariance, format_value, with_stderr


def _cov() -> Covariance:
    J = np.array([[1.3, 0.2, -0.7], [0.4, 2.1, 0.3], [-0.9, 0.5, 1.7], [0.6, -1.1, 0.8],
                  [1.9, 0.3, 0.1]])
    return covariance(J, 0.037)


def test_covariance_is_s2_times_the_inverse_normal_matrix() -> None:
    # mistakes: s^2 left out (or applied as s); the pseudo-inverse of J J^T's shape
    J = np.array([[1.3, 0.2, -0.7], [0.4, 2.1, 0.3], [-0.9, 0.5, 1.7], [0.6, -1.1, 0.8],
                  [1.9, 0.3, 0.1]])
    c = _cov()
    np.testing.assert_allclose(c.matrix, 0.037 * np.linalg.inv(J.T @ J), rtol=1e-12)
    np.testing.assert_allclose(c.stderr, np.sqrt(np.diag(c.matrix)), rtol=1e-15)
    d = np.sqrt(np.diag(c.matrix))
    np.testing.assert_allclose(c.correlation, c.matrix / np.outer(d, d), rtol=1e-12)
    assert not c.singular


def test_with_stderr_scales_row_and_column_and_keeps_correlations() -> None:
    # mistakes: only the row scaled (the matrix no longer symmetric); the diagonal element
    # scaled once (se_j's square root); the other standard errors touched
    c = _cov()
    new = with_stderr(c, 1, 2.7 * c.stderr[1])
    assert new.stderr[1] == pytest.approx(2.7 * c.stderr[1], rel=1e-14)
    assert new.stderr[[0, 2]] == pytest.approx(c.stderr[[0, 2]], rel=1e-15)
    np.testing.assert_allclose(new.matrix, new.matrix.T, rtol=1e-13)
    np.testing.assert_allclose(new.correlation, c.correlation, rtol=1e-13)
    assert new.matrix[0, 1] == pytest.approx(2.7 * c.matrix[0, 1], rel=1e-14)
    assert with_stderr(c, 1, float("nan")) is c and with_stderr(c, 1, 0.0) is c


def test_format_value_three_digits_and_its_unit() -> None:
    # mistakes: a blank unit written as a trailing space; more or fewer digits than three
    assert format_value(0.0123456, "m") == "0.0123 m"
    assert format_value(1234567.0, "") == "1.23e+06"
