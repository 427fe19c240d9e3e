"""The fit's law names and initial state mapped to the rate-and-state law and the slider's start
(fit/laws.py), at generic values (issue 25): each fitted value lands where the law reads it,
and the free start is ``theta0 = (Dc/V) exp(state0)``, checked through the friction it gives.
Each test names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import math

import pytest

from dryfriction.fit.laws import initial_state, law_guess, rate_state

VALUES = {"a": 0.0113, "b": 0.0157, "dc": 13e-6, "mu0": 0.617, "b2": 0.0041, "dc2": 170e-6,
          "c": 2.3, "state0": 0.41}


def test_each_value_lands_in_its_place() -> None:
    # mistakes: ageing2's second state given dc (or b) instead of its own; Nagata's c dropped;
    # the regularised flag not passed on
    two = rate_state("ageing2", VALUES, 1.7e-6, regularized=True)
    assert (two.a, two.b, two.dc, two.mu0, two.v0) == (0.0113, 0.0157, 13e-6, 0.617, 1.7e-6)
    assert (two.state_law, two.b2, two.dc2, two.regularized, two.c) == (
        "ageing", 0.0041, 170e-6, True, 0.0)
    nag = rate_state("nagata", VALUES, 1.7e-6, regularized=False)
    assert (nag.state_law, nag.c, nag.b2, nag.dc2, nag.regularized) == (
        "nagata", 2.3, 0.0, None, False)
    assert rate_state("prz", VALUES, 1.7e-6, False).state_law == "prz"


def test_free_start_is_state0_above_steady_sliding() -> None:
    # mistakes: theta0 = Dc/V (state0 ignored) or (Dc/V) exp(-state0); V the reference
    # velocity; a free start without a sliding first velocity
    v = 2.2e-6
    init = initial_state("free", VALUES, v)
    assert init is not None and init.v == v
    assert init.theta == pytest.approx(13e-6 / v * math.exp(0.41), rel=1e-14)
    # through the law: at V the friction sits b state0 above the steady level (ageing law)
    law = rate_state("ageing", VALUES, 1.7e-6, regularized=False)
    excess = law.b * math.log(v * init.theta / law.dc)
    assert excess == pytest.approx(0.0157 * 0.41, rel=1e-12)
    assert initial_state("steady", VALUES, v) is None
    assert initial_state("free", VALUES, 0.0) is None


def test_starting_values_of_the_extra_parameters() -> None:
    # mistakes: the second state's Dc at a tenth of Dc (not ten times); b2 at b; c's start 0
    # (the ageing law, where the search for c has no slope to follow)
    g = law_guess("ageing2", "free", {"b": 0.0157, "dc": 13e-6})
    assert g == pytest.approx({"b2": 0.0157 / 3, "dc2": 130e-6, "state0": 0.0}, rel=1e-14)
    assert law_guess("nagata", "steady", {}) == {"c": 1.0}
    assert law_guess("ageing2", "steady", {"b": 1e-6})["b2"] == 1e-5
