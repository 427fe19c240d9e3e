"""Birth times of the pairs that enter contact during one step of the slider (issue 25,
strengthen7B): the kernel places each birth where the linear motion ``x0 -> x1`` over
``t0 -> t1`` meets it (``p = -1`` forward, ``p = +1`` backward), so after a single step at
velocity ``u`` a newborn trap at ``p`` is ``(p + 1)/u`` old (forward) or ``(1 - p)/|u|``
(backward), and the traps of the rest state are ``t1`` old. Checked on the snapshot, in a
single step at a generic time origin (``t0 = 3.1``)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.ensemble.population import Ensemble, Initial, Track, TrapModel


@pytest.mark.parametrize("direction", [1.0, -1.0])
def test_newborn_ages_follow_the_linear_motion(direction: float) -> None:
    """Mistakes: births dated at the step's start or end, the crossing fraction without the
    ``-1`` (or ``+1``) of the contact edge, measured from the step's end."""
    t0, u, slip = 3.1, 0.037, 0.9
    ens = Ensemble(TrapModel(alpha=0.13, eps=0.043), Track(170.0), Initial("rest"),
                   age_horizon=100.0)
    ens.advance(0.0, t0)  # the rest state ages: every trap t0 old
    t1 = t0 + slip / u
    o = ens.advance(direction * slip, t1)
    assert o.births > 100
    s = ens.snapshot()
    p, age = s["p"], s["age"]
    if direction > 0:
        new = p < -1.0 + slip  # entered at p = -1 during the step
        want = (p[new] + 1.0) / u
    else:
        new = p > 1.0 - slip  # entered at p = +1 going back
        want = (1.0 - p[new]) / u
    assert new.sum() == pytest.approx(o.births, abs=1)
    np.testing.assert_allclose(age[new], want, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(age[~new], t1, rtol=1e-12)
