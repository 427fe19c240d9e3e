"""The record fit's search and verdict (fit/cvsteps.py) by their definitions, on scripted
minimisers (no trap-model run): the search stops when a step moves every parameter by less
than ``SEARCH_STOP`` standard errors ``sqrt(diag((J^T J)^-1) RSS/(n - p))`` (RSS = 2 x scipy's
cost), on a refused step, or at the cap; each window's result says why, keeps or drops the
engine's "did not converge", and is a success only when the search converged off the bounds."""

from __future__ import annotations

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

from dryfriction.fit import cvsteps, problem
from dryfriction.fit.cvsteps import SEARCH_DOC, SEARCH_MAX_ITER, SEARCH_STOP, search_step
from dryfriction.fit.models import ParamSpec

SPECS = (ParamSpec("eps", "", True, 1e-4, 0.5), ParamSpec("trend", "1/m", False, -1e3, 1e3))


class _Model:
    def parameters(self, kinds):
        return SPECS


def _scripted(steps, n=12, cost=5.0, jac=((2.0, 0.0), (0.0, 0.5)), nfev=3):
    """A Problem whose solve takes the given internal steps (``None``: every trial refused)."""
    calls = []

    class P:
        def __init__(self, model, data, specs, extra):
            self.n, self.p = n, len(specs)

        def solve(self, theta, max_nfev=None):
            calls.append((theta.copy(), max_nfev))
            step = steps[min(len(calls), len(steps)) - 1]
            if step is None:
                return theta, cost, SimpleNamespace(nfev=nfev, jac=np.array(jac))
            return theta + np.asarray(step), cost, SimpleNamespace(nfev=nfev, jac=np.array(jac))

    return P, calls


def test_search_stops_below_a_tenth_of_the_standard_error(monkeypatch) -> None:
    # J = diag(2, 0.5), n - p = 10, RSS = 2 cost = 10: s^2 = 1, standard errors (0.5, 2),
    # thresholds (0.05, 0.2). Mistakes: RSS taken as the cost (thresholds / sqrt 2), n for
    # n - p (/ sqrt 1.2), the threshold in variances: each keeps the search going at step 2
    assert SEARCH_STOP == 0.1
    P, calls = _scripted([(0.06, 0.0), (0.049, 0.19), (0.0, 0.0)])
    monkeypatch.setattr(problem, "Problem", P)
    start = {"eps": 0.02, "trend": 3.0}
    found, it, why, nfev = search_step(None, _Model(), start)
    assert (it, why, nfev) == (2, "step", 6)
    assert calls[0][0] == pytest.approx([np.log(0.02), 3.0], rel=1e-15)
    assert calls[0][1] == 1 + cvsteps.SEARCH_TRIALS == 4
    # each batch from where the last ended; the values back in SI (eps through its log)
    np.testing.assert_allclose(calls[1][0], [np.log(0.02) + 0.06, 3.0], rtol=1e-15)
    assert found["eps"] == pytest.approx(0.02 * np.exp(0.06 + 0.049), rel=1e-13)
    assert found["trend"] == pytest.approx(3.19, rel=1e-13)
    # just above a threshold (0.201 > 0.2 on the second parameter): not converged yet
    P, _ = _scripted([(0.049, 0.201), (0.0, 0.0)])
    monkeypatch.setattr(problem, "Problem", P)
    assert search_step(None, _Model(), start)[1:3] == (2, "refused")


def test_search_refused_at_once_capped_and_start_clipped_into_the_bounds(monkeypatch) -> None:
    P, calls = _scripted([None])
    monkeypatch.setattr(problem, "Problem", P)
    found, it, why, nfev = search_step(None, _Model(), {"eps": 0.9, "trend": -5e3})
    assert (it, why, nfev) == (1, "refused", 3)
    # the start beyond the bounds enters at the bound (eps <= 0.5, trend >= -1000)
    assert calls[0][0] == pytest.approx([np.log(0.5), -1e3], rel=1e-15)
    assert found == pytest.approx({"eps": 0.5, "trend": -1e3}, rel=1e-14)
    # a step never small enough: the cap, one solve per iteration
    P, calls = _scripted([(0.3, 1.0)], nfev=2)
    monkeypatch.setattr(problem, "Problem", P)
    _, it, why, nfev = search_step(None, _Model(), {"eps": 0.02, "trend": 0.0})
    assert (it, why, nfev) == (SEARCH_MAX_ITER, "cap", 2 * SEARCH_MAX_ITER) == (30, "cap", 60)
    assert len(calls) == SEARCH_MAX_ITER


@dataclasses.dataclass(frozen=True)
class _Res:
    notes: tuple
    message: str = "evaluations exceeded"
    nfev: int = 1
    success: bool = False
    status: int = 0


@dataclasses.dataclass(frozen=True)
class _CV:
    max_nfev: int = 30


def _verdict(monkeypatch, why, notes, message="evaluations exceeded"):
    seen = {}

    def start(model, rsf, v0):
        seen.update(rsf=rsf, v0=v0)
        return {"eps": 0.03}

    monkeypatch.setattr(cvsteps, "cv_start_from_rsf", start)
    monkeypatch.setattr(cvsteps, "search_step",
                        lambda d, model, s: ({"eps": 0.031}, 7, why, 19))

    def fake_fit(d, model, **kw):
        seen.update(model=model, kw=kw)
        return _Res(tuple(notes), message)

    monkeypatch.setattr(cvsteps, "fit", fake_fit)
    fit = SimpleNamespace(parameters=[SimpleNamespace(name="a", value=0.01)],
                          options={"v0": 3.5e-6})
    (out,) = cvsteps._fit_cv_steps(["window"], [fit], _CV())
    return out, seen


def test_verdict_converged_search_drops_the_engines_no_convergence(monkeypatch) -> None:
    out, seen = _verdict(monkeypatch, "step", ["fit did not converge", "other note"])
    assert seen["rsf"] == {"a": 0.01} and seen["v0"] == 3.5e-6
    assert seen["model"].max_nfev == 1 and seen["kw"] == {
        "start": {"eps": 0.031}, "multistart": False, "profile": False, "consistency": False}
    assert out.notes == ("other note", f"trap model: search of 7 iterations ({SEARCH_DOC['step']})")
    assert (out.success, out.status, out.message, out.nfev) == (True, 1, SEARCH_DOC["step"], 20)


def test_verdict_at_the_cap_keeps_it_and_fails(monkeypatch) -> None:
    out, _ = _verdict(monkeypatch, "cap", ["fit did not converge"])
    assert out.notes[0] == "fit did not converge"
    assert "not converged: 30 iterations" in out.notes[-1]
    assert (out.success, out.status) == (False, 0)


def test_verdict_on_a_bound_or_unevaluated_is_no_success(monkeypatch) -> None:
    out, _ = _verdict(monkeypatch, "refused", ["eps on its search bound"])
    assert (out.success, out.status) == (False, 1)
    assert out.notes[-1] == "the fit is not reliable (see the parameters on their bounds)"
    out, _ = _verdict(monkeypatch, "refused", [], message="the model could not be evaluated")
    assert (out.success, out.status) == (False, 1)
    assert not any("not reliable" in n for n in out.notes)
