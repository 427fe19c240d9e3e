"""The rate-and-state stepper's two routes (issue 12): interpreted for a small job, compiled by
Numba for a large one, and the hand-over from one to the other in the middle of a run, give the
same run: one source, the same floating-point operations in the same order, so the results
agree to rounding (1e-12 relative) and the step counts exactly."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.program import Segment
from dryfriction.rsf import stepper
from dryfriction.rsf.driving import RSFInitial, RSFOutput, SolverError, SpringSlider, simulate
from dryfriction.rsf.law import RateState

A, B, DC, MU0, V0 = 0.005, 0.01, 1e-5, 0.6, 1e-6
KC = (B - A) / DC  # critical stiffness, 1/m

CASES = {
    # quasi-static velocity step on a stiff spring (the example protocol's case)
    "velocity_step": (RateState(A, B, DC, MU0, V0),
                      SpringSlider([Segment(1e-6, 10.0), Segment(1e-5, 30.0)], stiffness=1e3),
                      RSFInitial(), RSFOutput(rtol=1e-8)),
    # kinematic machine, slip law, two state variables, slide - near-hold - slide
    "kinematic_two_state": (RateState(A, B, DC, MU0, V0, state_law="slip", b2=0.003, dc2=1e-4),
                            SpringSlider([Segment(1e-5, 5.0), Segment(1e-8, 50.0),
                                          Segment(1e-5, 5.0)]),
                            RSFInitial(), RSFOutput(rtol=1e-8)),
    # inertial slider, regularised law, sampled output (the Hermite path)
    "inertial_regularised": (RateState(A, B, DC, MU0, V0, regularized=True),
                             SpringSlider([Segment(1e-6, 5.0), Segment(1e-5, 20.0)],
                                          stiffness=1e3, damping=0.5, mass=1e-3),
                             RSFInitial(), RSFOutput(every=0.1)),
    # damped stick-slip below the critical stiffness: many events, rejected steps, the
    # growth-rate step limit at work
    "stick_slip": (RateState(A, B, DC, MU0, V0),
                   SpringSlider([Segment(1e-5, 200.0)], stiffness=0.8 * KC, damping=0.5),
                   RSFInitial(v=1.01e-5), RSFOutput(rtol=1e-7)),
}


def _run(case: str, interpreted: int):  # type: ignore[no-untyped-def]
    with stepper.interpreted_steps(interpreted):
        return simulate(*CASES[case])


def _same(r, ref) -> None:  # type: ignore[no-untyped-def]
    assert (r.n_steps, r.n_rejected, r.n_rhs) == (ref.n_steps, ref.n_rejected, ref.n_rhs)
    for name in ("t", "x", "v", "theta", "mu", "stress"):
        np.testing.assert_allclose(getattr(r, name), getattr(ref, name), rtol=1e-12, atol=0,
                                   err_msg=name)


@pytest.fixture(scope="module")
def compiled_runs() -> dict[str, object]:
    return {case: _run(case, 0) for case in CASES}


@pytest.mark.parametrize("case", list(CASES))
def test_interpreted_run_is_the_compiled_run(case: str, compiled_runs: dict) -> None:
    r = _run(case, 10**9)
    ref = compiled_runs[case]
    _same(r, ref)
    if case == "stick_slip":  # the case is what it claims: several events, rejected steps
        v = ref.v
        events = np.sum((v[:-1] < 10 * 1e-5) & (v[1:] >= 10 * 1e-5))
        assert events >= 5 and ref.n_rejected > 0


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("part", [0.0, 0.37, 1.0])
def test_hand_over_mid_run_continues_the_same_run(case: str, part: float,
                                                  compiled_runs: dict) -> None:
    """Interpreted for some steps (the first, about a third, all but the last), then compiled
    from where it stopped (mid-segment, maybe just after a rejected step): the step size, the
    segment, the counters and the recorded steps carry over."""
    ref = compiled_runs[case]
    steps = ref.n_steps + ref.n_rejected
    _same(_run(case, 1 + round(part * (steps - 2))), ref)


def test_the_budget_is_the_whole_process_s(compiled_runs: dict,
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    """The interpreted steps are counted over the process: a job that fits runs without the
    compiled kernels, the next one is handed over when the budget runs out, and every later
    one runs compiled (a fit calls the solver hundreds of times)."""
    calls = []
    real = stepper.compiled
    monkeypatch.setattr(stepper, "compiled", lambda: calls.append(1) or real())
    ref = compiled_runs["velocity_step"]
    steps = ref.n_steps + ref.n_rejected
    with stepper.interpreted_steps(steps + 5):
        _same(simulate(*CASES["velocity_step"]), ref)
        assert calls == []
        _same(simulate(*CASES["velocity_step"]), ref)  # 5 steps left
        assert calls == [1]
        _same(simulate(*CASES["velocity_step"]), ref)  # none left
        assert calls == [1, 1]


def test_failures_are_the_same_on_both_routes() -> None:
    """A quasi-static runaway (no damping, below the critical stiffness) overflows: the
    interpreter raises where the compiled kernels carry inf, so the run is redone compiled
    and fails with the same error at the same time."""
    args = (RateState(A, B, DC, MU0, V0), SpringSlider([Segment(1e-5, 100.0)],
                                                        stiffness=0.5 * KC),
            RSFInitial(v=1.01e-5))
    errors = []
    for budget in (0, 10**9):
        with stepper.interpreted_steps(budget), pytest.raises(SolverError) as e:
            simulate(*args)
        errors.append((str(e.value), e.value.t))
    assert errors[0] == errors[1]


def test_step_budget_error_on_the_interpreted_route() -> None:
    """``max_steps`` smaller than the interpreted budget: the run stops there, as compiled."""
    model, drive, init, _ = CASES["stick_slip"]
    for budget in (0, 10**9):
        with stepper.interpreted_steps(budget), pytest.raises(SolverError, match="max_steps = 40"):
            simulate(model, drive, init, RSFOutput(max_steps=40))
