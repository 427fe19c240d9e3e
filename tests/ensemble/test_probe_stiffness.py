"""The kernel's stiffness ``dF/dX`` at frozen ages (what the quasi-static jump's Newton steps
use, :mod:`dryfriction.ensemble.balance`) against a central difference of the probed force
(issue 25, strengthen7B), in both pinning regimes (the strong one with traps on the (-)
branch, ``f_-'(w) = f_+'(-w)``), at a generic position and time after a run: ``F = sum r^2
f(p/r)`` gives ``dF/dX = sum r f'(p/r)`` (eq. 23, in ``F_el/a0`` after the normalisation)."""

from __future__ import annotations

import pytest

from dryfriction.ensemble.population import Ensemble, Initial, Track, TrapModel


@pytest.mark.parametrize("alpha", [0.13, 0.61])
def test_stiffness_is_the_derivative_of_the_probed_force(alpha: float) -> None:
    """Mistakes: ``r^2 f'`` or ``f'`` alone summed, the (-) branch's slope with the wrong
    sign, the stiffness without the normalisation ``1/(lambda H0)``."""
    ens = Ensemble(TrapModel(alpha=alpha, eps=0.043), Track(130.0),
                   Initial("steady", velocity=0.023), age_horizon=100.0)
    ens.advance(0.37, 17.0)
    x, h = ens.x, 1e-6
    o = ens.observe(1, stiffness=True)
    assert o.next_event - x > 10 * h and x - ens.observe(-1).next_event > 10 * h
    fd = (ens.probe(x + h, 1).force - ens.probe(x - h, -1).force) / (2 * h)
    assert o.stiffness == pytest.approx(fd, rel=1e-5)
    assert ens.observe(1).stiffness == 0.0  # only when asked
    if alpha > 0.5:
        assert (ens.snapshot()["branch"] < 0).any()
