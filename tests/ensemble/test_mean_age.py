"""The ``mean_age`` column (``t0``) and ``n_active`` against two independent routes (issue 25,
strengthen7B):

* the steady population at ``u`` (eq. 29, very strong pinning): the pairs in contact sit
  uniformly in ``p`` on ``[-1, p_d]`` (``p_d`` the death point of eq. 32,
  :func:`~dryfriction.theory.steady.steady_death_point`) with age ``(p + 1)/u``, so
  ``n_active = lambda (p_d + 1)`` and ``mean_age = (p_d + 1)/(2 u)``, both to the lattice's
  granularity;
* after a run with a velocity step (both pinning regimes, the strong one with traps on the
  (-) branch), the compiled kernel's age sum over the traps in contact against the Python
  snapshot's ages (``t - birth``) at the same instant.
Generic ``u``, ``eps``, ``alpha`` and density; a ``t`` far from 0.
"""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.ensemble.driving import Output, VelocityDrive, simulate
from dryfriction.ensemble.population import Ensemble, Initial, Track, TrapModel
from dryfriction.program import Segment, VelocityProgram
from dryfriction.theory.steady import steady_death_point


def test_steady_population_count_and_mean_age() -> None:
    """Mistakes: the age sum divided by the pairs of the buffer, ages from the start of the
    step instead of the birth, the count of one branch only."""
    u, lam = 0.037, 300.0
    model = TrapModel(alpha=0.13, eps=0.043)
    o = Ensemble(model, Track(lam), Initial("steady", velocity=u)).observe()
    pd = float(steady_death_point(model, u))
    assert o.n_active == pytest.approx(lam * (pd + 1.0), abs=2.0)
    assert o.mean_age == pytest.approx((pd + 1.0) / (2.0 * u), rel=2.0 / (lam * (pd + 1.0)))


@pytest.mark.parametrize("alpha", [0.13, 0.61])
def test_mean_age_is_the_snapshots_mean_after_a_step(alpha: float) -> None:
    model = TrapModel(alpha=alpha, eps=0.043)
    drive = VelocityDrive(VelocityProgram([Segment(0.037, slip=1.1), Segment(0.41, slip=0.7)]))
    prog = drive.program
    end = float(prog.total_time)
    res = simulate(model, drive, Initial("steady", velocity=0.037, track=Track(170.0)),
                   Output(every_slip=0.05, snapshots=(end,)))
    snap = res.snapshots[-1]
    assert snap["t"] == pytest.approx(res.t[-1], rel=1e-12) and res.t[-1] > 20.0
    assert res.n_active[-1] == snap["age"].size
    assert res.mean_age[-1] == pytest.approx(float(np.mean(snap["age"])), rel=1e-12)
    if alpha > 0.5:  # strong pinning: the (-) branch is populated and counted
        assert np.any(snap["branch"] < 0)
