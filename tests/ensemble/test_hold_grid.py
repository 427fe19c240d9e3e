"""A force hold's sampling grid (ensemble/result.py ``force_hold_grid``) against its definition
at a generic hold and step (issue 25: a hold that is a whole number of steps hides a count
rounded down). Each test names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.ensemble.result import force_hold_grid


def test_uniform_grid_within_every_and_ending_at_the_hold() -> None:
    # mistakes: the count rounded down (steps longer than every); a sample at the hold's
    # start (t = 0, where the state is the initial one, not a sample of the hold)
    g = force_hold_grid(37.3, 4.1)
    assert g.size == 10 and g[-1] == 37.3 and g[0] > 0.0
    assert np.allclose(np.diff(g), 3.73, rtol=1e-12) and g[0] == pytest.approx(3.73)
    assert force_hold_grid(41.0, 4.1).size == 10  # a whole number of steps: no extra sample
    assert force_hold_grid(0.0, 4.1).size == 0


def test_geometric_grid_uniform_in_the_log_of_the_age() -> None:
    # mistakes: exp for expm1 (every sample one t0 late); more than log_step per step
    g = force_hold_grid(913.0, log_step=0.17)
    steps = np.diff(np.log1p(np.concatenate([[0.0], g])))
    assert np.allclose(steps, steps[0], rtol=1e-9) and steps[0] <= 0.17
    assert g.size == int(np.ceil(np.log1p(913.0) / 0.17)) and g[-1] == 913.0


@pytest.mark.parametrize("hold", [0.63, 2.7])
def test_short_holds_are_resolved_in_the_log_of_one_plus_the_age(hold: float) -> None:
    # mistake (blind set 5, hold_grid_log_not_log1p): the count from ln(hold) instead of
    # ln(1 + hold); at a long hold the two agree, at holds of a few t0 the grid is coarser than
    # log_step in ln(1 + t), and under 1 t0 it is a single sample
    step = 0.05
    g = force_hold_grid(hold, log_step=step)
    assert g.size == int(np.ceil(np.log1p(hold) / step))  # 10 at 0.63, 27 at 2.7
    assert np.diff(np.log1p(np.concatenate([[0.0], g]))).max() <= step * (1 + 1e-12)
