"""The reload estimate of a slide-hold-slide (app/ratestate.py, ours) at a generic point:
a reverse load velocity, a finite stiffness, no parameter at 1 (issue 25). Each test names the
mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import math

import pytest

from dryfriction.app.ratestate import reload_time
from dryfriction.app.theory import LOAD_MAX


def test_reload_time_by_hand_in_both_directions() -> None:
    # mistakes: the signed velocity in the healing (a reverse reslide gives NaN or a short
    # reload); the spring's take-up left out; the slip of 10 Dc at the hold's velocity
    a, b, dc, hold, k = 0.011, 0.017, 23e-6, 410.0, 1.7e4
    for v in (3.1e-6, -3.1e-6):
        heal = b * math.log1p(hold * 3.1e-6 / dc) + 2.0 * a
        want = heal / (k * 3.1e-6) + 10.0 * dc / 3.1e-6
        assert reload_time(a, b, dc, v, hold, k) == pytest.approx(want, rel=1e-12)
    # floors and caps: at least 30 s, at most LOAD_MAX; a rigid machine has no take-up
    assert reload_time(a, b, dc, 3.1e-3, hold, k) == 30.0
    assert reload_time(a, b, dc, 3.1e-6, hold, math.inf) == pytest.approx(10 * dc / 3.1e-6)
    assert reload_time(a, b, dc, 1e-17, hold, k) == LOAD_MAX
    # longer holds heal more: the reload never shortens with the hold
    times = [reload_time(a, b, dc, 3.1e-6, h, k) for h in (1.0, 37.0, 410.0, 9e3)]
    assert all(t1 < t2 for t1, t2 in zip(times, times[1:], strict=False))
