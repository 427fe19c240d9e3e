"""A window's covariance from the fit's own Jacobian (dryfriction.fit.steps.step_covariance with
``fitted_on_d``): the engine keeps the central-difference Jacobian it computed at its optimum
(``FitResult.theta``, ``FitResult.jacobian``), and the step's covariance uses it only where its
parameters and point are the same, bit for bit; elsewhere it is computed again. On a generic
down-step (3.1 -> 1.3 um/s, a stiffness fitted, white friction noise)."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

from dryfriction.fit import problem
from dryfriction.fit.steps import fit_steps, step_covariance
from dryfriction.records.data import SeriesData

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from lab_synth import Truth, synth_record  # noqa: E402


@pytest.fixture(scope="module")
def window() -> tuple[object, SeriesData]:
    t, v, mu, _ = synth_record(Truth(), [3.1e-6, 1.3e-6], duration_slip=260e-6, dt_per_um=0.7,
                               seed=23)
    res = fit_steps(SeriesData(t, v, mu, source="synthetic down-step"), stiffness="fit")
    return res.fits[0], res.data[0]


def _calls(mp: pytest.MonkeyPatch) -> list[int]:
    """Count Problem.jacobian's calls from here on."""
    n = [0]
    orig = problem.Problem.jacobian

    def counted(self, theta):  # type: ignore[no-untyped-def]
        n[0] += 1
        return orig(self, theta)

    mp.setattr(problem.Problem, "jacobian", counted)
    return n


def _same(a: object, b: object) -> bool:
    return all(np.array_equal(getattr(a, k).matrix, getattr(b, k).matrix)
               for k in ("white", "used"))


def test_the_fits_jacobian_is_used_and_gives_the_same_covariance(
        window: tuple[object, SeriesData], monkeypatch: pytest.MonkeyPatch) -> None:
    r, d = window
    assert r.jacobian is not None and r.jacobian.shape == (len(d), len(r.free))
    assert r.theta is not None and r.theta.shape == (len(r.free),)
    # kept on the result and shared by its copies (dataclasses.replace): read-only
    assert not r.jacobian.flags.writeable and not r.theta.flags.writeable
    n = _calls(monkeypatch)
    again = step_covariance(r, d, "hac")
    assert n[0] == 1  # computed: nothing says r was fitted on d
    kept = step_covariance(r, d, "hac", fitted_on_d=True)
    assert n[0] == 1  # the fit's own: no forward runs for it
    assert _same(again, kept)
    assert np.all(np.isfinite(kept.used.stderr)) and np.all(kept.used.stderr > 0)


@pytest.mark.parametrize("what", ["another point", "other parameters"])
def test_a_jacobian_of_another_point_or_parameters_is_not_used(
        window: tuple[object, SeriesData], what: str) -> None:
    """The kept Jacobian doubled (so that using it would show), with the point moved or the
    parameters' order changed: the covariance is the one computed afresh."""
    r, d = window
    changed = (dict(theta=r.theta + 1e-3) if what == "another point"
               else dict(free=tuple(reversed(r.free))))
    wrong = dataclasses.replace(r, jacobian=2.0 * r.jacobian, **changed)
    assert _same(step_covariance(wrong, d, "hac", fitted_on_d=True), step_covariance(r, d, "hac"))
    # and where point and parameters are the same, the kept one is what is used
    used = step_covariance(dataclasses.replace(r, jacobian=2.0 * r.jacobian), d, "hac",
                           fitted_on_d=True)
    np.testing.assert_allclose(used.white.matrix, step_covariance(r, d, "hac").white.matrix / 4.0,
                               rtol=1e-12)


def test_fit_steps_computes_each_windows_jacobian_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """Two windows (1.7 -> 4.4 -> 2.3 um/s), HAC intervals: one Jacobian a window (the fit's),
    not two (the fit's, then the covariance's at the same point)."""
    t, v, mu, _ = synth_record(Truth(), [1.7e-6, 4.4e-6, 2.3e-6], duration_slip=220e-6,
                               dt_per_um=0.6, seed=5)
    n = _calls(monkeypatch)
    res = fit_steps(SeriesData(t, v, mu, source="synthetic two steps"))
    assert len(res.rows) == 2 and all(f.jacobian is not None for f in res.fits)
    assert n[0] == 2
