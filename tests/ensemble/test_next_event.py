"""The kernel's ``next_event`` (the frozen-age slider position of the next spinodal, where the
force jumps: :mod:`dryfriction.ensemble.balance` brackets its roots between them) against the
snapshot (issue 25, strengthen7B): a (+) trap at ``p = X - c`` of radius ``r`` reaches
``w = y_c`` at ``X + (y_c r - p)``; a (-) trap (strong pinning) reaches ``w = -y_c`` going
back at ``X - (y_c r + p)``; a pair not yet in contact (``c > X + 1``) is fresh, ``r = 1``,
so the first of them bounds the forward event by ``c + y_c``. Aged populations (radii well
above 1) at a generic position, both regimes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.ensemble.population import Ensemble, Initial, Track, TrapModel


@pytest.mark.parametrize("alpha", [0.13, 0.61])
def test_next_event_both_ways_from_the_snapshot(alpha: float) -> None:
    """Mistakes: the spinodal at ``c + y_c`` (the radius left out), the (-) branch's event
    on the far side."""
    lam = 130.0
    ens = Ensemble(TrapModel(alpha=alpha, eps=0.043), Track(lam),
                   Initial("steady", velocity=0.023), age_horizon=100.0)
    ens.advance(0.37, 17.0)
    x, yc = ens.x, ens.y_c
    s = ens.snapshot()
    plus, minus = s["branch"] > 0, s["branch"] < 0
    assert np.max(s["radius"]) > 1.05  # aged: the radius matters (y_c (r - 1) >> 1e-12)
    c_next = (math.ceil((x + 1.0) * lam - 0.5) + 0.5) / lam  # first pair not yet in contact
    forward = min(float(np.min(x + yc * s["radius"][plus] - s["p"][plus])), c_next + yc)
    assert ens.observe(1).next_event == pytest.approx(forward, abs=1e-12)
    if alpha > 0.5:
        assert minus.any()
        back = float(np.max(x - yc * s["radius"][minus] - s["p"][minus]))
        assert ens.observe(-1).next_event == pytest.approx(back, abs=1e-12)
