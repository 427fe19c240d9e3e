"""fixE item 5 (a second new user's trial, problem 19): steady-friction data that rise with
velocity contradict the athermal trap model, whose steady friction (eq. 34) falls with
velocity at every eps and u for alpha <= 0.3 (faster sliding, younger traps; eq. 35:
``-(3/2) eps`` at low u). They now get the static data's flag: ``against_model:<source>``,
the trend with its interval, the first note, the CLI's last line and the figure's title.
Where the model can rise (the direct effect fitted, alpha = 0.5) nothing is flagged."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.fit import CVModel, fit
from dryfriction.records.data import SteadyData
from dryfriction.theory.model import TrapModel
from dryfriction.theory.steady import athermal_steady_weakens, steady_friction
from dryfriction.theory.units import PhysicalScales, steady_friction_si

V = np.geomspace(2e-7, 3e-4, 9)  # m/s


def _rising(seed: int) -> SteadyData:
    # velocity strengthening, 0.0041 per e-fold: what a gouge often shows
    y = 0.59 + 0.0041 * np.log(V / 1e-6) + np.random.default_rng(seed).normal(0, 3e-4, V.size)
    return SteadyData(V, y, None, f"rising-{seed}")


def test_which_alphas_weaken_two_routes() -> None:
    """The grid check against mu_d itself (differences of eq. 34's quadrature, not its slope
    routine): at alpha = 0.13 mu_d falls on a fine u grid for several eps, both creep laws;
    at alpha = 0.5 it rises somewhere (so rising data are no contradiction there). Mistakes:
    any positive slope counted (the central difference's 1e-12 rounding), the alpha ignored."""
    assert athermal_steady_weakens(0.13, "log") and athermal_steady_weakens(0.13,
                                                                            "eyring-nabarro")
    assert athermal_steady_weakens(0.27, "log")
    assert not athermal_steady_weakens(0.5, "log")
    u = np.geomspace(1e-6, 1e6, 121)
    for eps in (0.003, 0.04, 0.2):
        mu = steady_friction(TrapModel(0.13, eps), u)
        assert np.all(np.diff(mu) < 1e-12), eps
    mu = steady_friction(TrapModel(0.5, 0.01), u)
    assert np.any(np.diff(mu) > 1e-6)


@pytest.mark.parametrize("seed", [0, 1])
def test_rising_steady_data_are_flagged_against_the_athermal_model(seed: int) -> None:
    d = _rising(seed)
    r = fit(d, "cv", profile=False)
    assert f"against_model:{d.source}" in r.flags
    tr = r.per_dataset[0]["trend"]
    assert tr["against_model"] is True and tr["model_allows"] == "decrease"
    lo, hi = tr["interval_95"]
    assert 0 < lo <= 0.0041 <= hi
    first = r.notes[0]
    assert first.startswith(f"{d.source}: the data contradict the model: mu_d grows with V")
    assert "falls with velocity at every eps and V" in first and "eq. 34" in first
    from dryfriction.plots.fits import plot_fit

    fig, _ = plot_fit(r, [d])
    assert any("AGAINST THE MODEL" in ax.get_title() for ax in fig.axes)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1])
def test_what_the_model_can_make_is_not_flagged(seed: int) -> None:
    """Its own falling curve with noise, flat noise, rising data with the direct effect
    fitted, and rising data at alpha = 0.5. Mistakes: the sign turned (falling data
    flagged), the direct effect or alpha ignored."""
    rng = np.random.default_rng(seed)
    down = steady_friction_si(TrapModel(eps=0.03), V, PhysicalScales(1e-6, 0.2, 0.4)) \
        + rng.normal(0, 3e-4, V.size)
    r = fit(SteadyData(V, down, None, "down"), "cv", profile=False)
    assert r.per_dataset[0]["trend"]["model_allows"] == "decrease"
    assert not any(f.startswith("against_model") for f in r.flags)
    d = _rising(seed)
    r = fit(d, CVModel(TrapModel(direct=0.05)), profile=False)
    assert not any(f.startswith("against_model") for f in r.flags)
    assert "trend" not in r.per_dataset[0]
    r = fit(d, "cv", alpha=0.5, profile=False)
    assert not any(f.startswith("against_model") for f in r.flags)
