"""The rate-and-state run's memory estimate (rsf/resources.py) against its definition for
each machine (kinematic, spring, inertial; one and two state variables) and each output
(every step, ``every``, ``t_eval``), and the refusal naming the key that gives the most
(issue 25: a branch rarely taken, a count off by one, the limit itself)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.program import Segment
from dryfriction.rsf.law import RateState
from dryfriction.rsf.resources import BYTES_PER_OUTPUT, check_rsf_run, estimate_rsf
from dryfriction.rsf.spring import RSFOutput, SpringSlider
from dryfriction.validation import MEMORY_ENV

P1 = RateState(0.0061, 0.0097, 3.3e-6, 0.58, 1.7e-6)
P2 = RateState(0.0061, 0.0097, 3.3e-6, 0.58, 1.7e-6, b2=0.0023, dc2=2.9e-5)
SEGS = [Segment(2e-6, 3.0), Segment(7e-6, 2.5), Segment(1e-6, 1.5)]  # 7 s, 3 segments


@pytest.mark.parametrize("params, drive, ny", [
    (P1, SpringSlider(SEGS), 1),
    (P2, SpringSlider(SEGS), 2),
    (P1, SpringSlider(SEGS, stiffness=800.0), 2),
    (P2, SpringSlider(SEGS, stiffness=800.0, damping=3.0, mass=1e4), 4)])
def test_estimate_is_its_definition(params, drive, ny) -> None:  # type: ignore[no-untyped-def]
    step_bytes = 3.0 * (16.0 + 16.0 * ny)  # time, segment, state and slope; x3 at a doubling
    steps = 1000 + 3.0
    got = estimate_rsf(params, drive, RSFOutput(max_steps=1000))
    assert got == (steps, steps, steps * step_bytes + steps * BYTES_PER_OUTPUT)
    outs = 7.0 / 0.3 + 3 + 1
    got = estimate_rsf(params, drive, RSFOutput(max_steps=1000, every=0.3))
    assert got[1] == pytest.approx(outs, rel=1e-14)
    assert got[2] == pytest.approx(steps * step_bytes + outs * 128.0, rel=1e-14)
    got = estimate_rsf(params, drive, RSFOutput(max_steps=1000, t_eval=np.linspace(0, 7, 41)))
    assert got[1] == 41.0
    assert BYTES_PER_OUTPUT == 128.0


def test_refusal_names_the_key_and_accepts_the_limit(monkeypatch: pytest.MonkeyPatch) -> None:
    drive = SpringSlider(SEGS, stiffness=800.0)
    out = RSFOutput(max_steps=1000, every=1e-4)  # 7e4 samples > 1003 steps: every is the cause
    need = estimate_rsf(P1, drive, out)[2]
    monkeypatch.setenv(MEMORY_ENV, str(need))
    assert check_rsf_run(P1, drive, out) == need  # at the limit: allowed
    monkeypatch.setenv(MEMORY_ENV, str(math.floor(need) - 1))
    with pytest.raises(ValueError, match=r"^output\.every = 0\.0001 gives 7\.0e\+04 samples "
                                         r"\(.*\), more than .*: raise output\.every \(or "
                                         r"shorten the drive\)"):
        check_rsf_run(P1, drive, out, qualified=True)
    monkeypatch.setenv(MEMORY_ENV, "1000")
    with pytest.raises(ValueError, match=r"^t_eval gives 5\.0e\+03 samples .*: ask for fewer "
                                         "t_eval"):
        check_rsf_run(P1, drive, RSFOutput(max_steps=10, t_eval=np.linspace(0, 7, 5000)))
    with pytest.raises(ValueError, match=r"^max_steps = 1000 lets the solver record 1\.0e\+03 "
                                         r"steps .*: lower max_steps, give every or set"):
        check_rsf_run(P1, drive, RSFOutput(max_steps=1000))
    with pytest.raises(ValueError, match=r"^max_steps = 1000000 lets the solver record .*: "
                                         r"lower max_steps or set"):
        check_rsf_run(P1, drive, RSFOutput(every=1.0))  # fewer samples than steps
    with pytest.raises(ValueError, match=r"^max_steps = 1000 lets the solver record .*: "
                                         r"lower max_steps or set"):  # t_eval, but fewer
        check_rsf_run(P1, drive, RSFOutput(max_steps=1000, t_eval=np.linspace(0, 7, 41)))
    with pytest.raises(ValueError, match=r": give output\.every or set"):
        check_rsf_run(P1, drive, RSFOutput(max_steps=1000), qualified=True)
