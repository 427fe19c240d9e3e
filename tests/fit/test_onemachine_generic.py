"""The one machine's held-stiffness weights (fit/onemachine.py) against a hand computation at
generic intervals (issue 25). Each test names the mistake it is for; each was seen failing
with it applied."""

from __future__ import annotations

import math

import pytest

from dryfriction.fit.onemachine import held_stiffness


def test_held_stiffness_variance_and_shares() -> None:
    # mistakes: the standard error from the 95 % interval's half-width over z, not its full
    # width over 2z; the share as own/var (the steps with narrow intervals weighted least);
    # a step outside the record's stiffness given a share
    rec = {"lo": 2.9e3, "hi": 3.6e3, "steps": [0, 2]}
    rows = [{"stiffness_lo": 2.1e3, "stiffness_hi": 4.4e3},
            {"stiffness_lo": 2.5e3, "stiffness_hi": 3.9e3},
            {"stiffness_lo": 2.95e3, "stiffness_hi": 3.5e3}]
    var = (math.log(3.6 / 2.9) / (2 * 1.96)) ** 2
    out = held_stiffness(rec, rows)
    assert [v for v, _ in out] == pytest.approx([var] * 3, rel=1e-12)
    own0 = (math.log(4.4 / 2.1) / (2 * 1.96)) ** 2
    assert out[0][1] == pytest.approx(var / own0, rel=1e-12) and out[0][1] < 0.2
    assert out[1][1] == 0.0
    assert out[2][1] == 1.0  # narrower than the record's own: capped
