"""``analysis.rsf_view.trap_series`` and ``hold_peaks``: the columns handed to the fit, from
their definitions, and the healing peaks' invariants (issue 25, strengthen7B).

* ``trap_series``: the SI series through ``SCALES`` (a0 = 1 um, t0 = 1 s): ``t`` in s,
  ``v_load`` the program's right-continuous velocity in m/s (the change on the sample at the
  boundary), ``mu = F/F_el`` (the run's ``mu`` over ``mu_el``), and the run's absolute level
  at the start the steady friction ``mu_el mu_d(u_init)`` (eq. 34);
* ``hold_peaks``: ``F/F_el``, so the same numbers for any ``mu_el``; non-decreasing in the hold
  time (the static friction grows with the waiting time), above the steady friction.
Generic ``mu_el`` (0.43), velocities and holds.
"""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.analysis.rsf_view import SCALES, hold_peaks, trap_series
from dryfriction.ensemble.driving import Output, VelocityDrive, simulate
from dryfriction.ensemble.population import Initial, Track
from dryfriction.program import Segment, VelocityProgram
from dryfriction.theory.model import TrapModel
from dryfriction.theory.steady import steady_friction

MU_EL, U0 = 0.43, 0.037


def test_trap_series_columns_from_their_definitions() -> None:
    """Mistakes: ``mu`` not divided by ``mu_el``, the velocity in a0/t0 (not m/s), taken
    left-continuous at the step, the time scaled by ``a0``, the population steady at the
    program's first velocity instead of ``u_init``."""
    model = TrapModel(alpha=0.13, eps=0.04, mu_el=MU_EL)
    prog = VelocityProgram([Segment(U0, slip=0.6), Segment(8.3 * U0, slip=1.1)])
    u_init = 0.11  # the population's velocity, not the program's first
    res, data = trap_series(model, Track(300.0), u_init, prog, every_slip=0.05)
    assert SCALES.a0 == 1e-6 and SCALES.t0 == 1.0
    np.testing.assert_allclose(data.t, res.t, rtol=1e-15)
    t_step = 0.6 / U0
    want_v = np.where(res.t >= t_step * (1 - 1e-12), 8.3 * U0, U0) * 1e-6
    np.testing.assert_allclose(data.v_load, want_v, rtol=1e-12)
    assert np.any(np.isclose(res.t, t_step, rtol=1e-12))  # a sample on the step itself
    np.testing.assert_allclose(data.mu, res.mu / MU_EL, rtol=1e-15)
    mu_d = float(steady_friction(model, u_init))
    assert abs(mu_d - float(steady_friction(model, U0))) > 0.02 * mu_d
    assert res.mu[0] == pytest.approx(MU_EL * mu_d, rel=0.02)
    assert data.mu[0] == pytest.approx(mu_d, rel=0.02)


def test_hold_peaks_in_units_of_F_el_grow_with_the_hold() -> None:
    """Mistakes: the peak divided by ``mu_el`` twice or not at all (the numbers then depend on
    ``mu_el``), the hold and the reload swapped (no healing), the reload too short to reach the
    peak (the peak then equals the steady friction)."""
    holds = [3.7, 370.0, 3.7e4]
    track = Track(300.0)
    a = hold_peaks(TrapModel(alpha=0.13, eps=0.04, mu_el=MU_EL), track, U0, holds,
                   every_slip=0.01)
    b = hold_peaks(TrapModel(alpha=0.13, eps=0.04), track, U0, holds, every_slip=0.01)
    np.testing.assert_allclose(a, b, rtol=1e-12)
    mu_d = float(steady_friction(TrapModel(alpha=0.13, eps=0.04), U0))
    assert np.all(np.diff(a) > 0.0), a
    assert a[0] > mu_d and a[-1] - mu_d > 0.05 * mu_d, (a, mu_d)
    # the longest hold run here: alone (its force at the end), and with a longer reload
    # (3 (1 + y_c) a0): the peak is on the reload (0.17 a0 in), above the hold's end
    model = TrapModel(alpha=0.13, eps=0.04, mu_el=MU_EL)
    ini = Initial("steady", velocity=U0, track=track)
    out = Output(every_slip=0.01)
    reload = 3.0 * (1.0 + model.trap.y_c)
    longer = simulate(model, VelocityDrive([Segment(0.0, 3.7e4), Segment(U0, slip=reload)]),
                      ini, out)
    held = simulate(model, VelocityDrive([Segment(0.0, 3.7e4)]), ini, out)
    assert a[-1] == pytest.approx(float(np.max(longer.mu)) / MU_EL, rel=1e-3)
    assert a[-1] > 1.05 * float(held.mu[-1]) / MU_EL
