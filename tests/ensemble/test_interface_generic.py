"""The interface chain's constants against an independent route (issue 25): the stiffest mode
of the free chain from a matrix eigenvalue solver, the sound speed at a generic coupling and
mass. Each test names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.ensemble.interface import InterfaceModel
from dryfriction.theory.model import TrapModel


@pytest.mark.parametrize("n", [1, 2, 3, 7, 40])
def test_stiffest_mode_of_the_free_chain_against_its_matrix(n: int) -> None:
    # mistake: the fixed-ends chain's 4 sin^2(pi N / (2 (N + 1))) for the free chain's
    # 4 sin^2(pi (N - 1) / (2 N)) (the time step's bound then too large or too small)
    lap = 2.0 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
    lap[0, 0] = lap[-1, -1] = 1.0 if n > 1 else 0.0  # free ends: one neighbour each
    want = float(np.linalg.eigvalsh(lap).max()) if n > 1 else 0.0
    m = InterfaceModel(TrapModel(eps=0.04), n_elements=n, coupling=3.7, mass=0.23)
    assert m.coupling_eigenvalue_max == pytest.approx(want, rel=1e-12, abs=1e-15)
    assert m.sound_speed() == pytest.approx(math.sqrt(3.7 / 0.23), rel=1e-15)


def test_uniform_load_is_the_sum_of_the_leaf_springs_at_the_steady_level() -> None:
    """``load`` under uniform loading is the total force of the leaf springs, ``sum_i K_p (P -
    x_i)`` (the unit ``F_el`` of the whole interface), and at steady sliding it sits at N times
    one block's steady friction (eq. 34) plus its damping force ``eta u`` (measured: 1.2623
    against 1.2613 per block at 300 traps/a0; 1.350 at 60, the track's discreteness). Mistake:
    the mean spring force for the sum (equal at N = 1 only)."""
    from dryfriction.ensemble.interface import InterfaceDrive, simulate_interface
    from dryfriction.ensemble.population import Initial, Track
    from dryfriction.ensemble.result import Output
    from dryfriction.program import Segment, VelocityProgram
    from dryfriction.theory.steady import steady_friction

    model, n, kp, u, eta = TrapModel(eps=0.04, alpha=0.11), 5, 1.5, 0.37, 0.4
    r = simulate_interface(InterfaceModel(model, n, 1.7, 0.8, eta),
                           InterfaceDrive("uniform", kp, VelocityProgram([Segment(u, slip=4.0)])),
                           Initial("steady", velocity=u, track=Track(300.0, "random", seed=11)),
                           Output(every=0.25))
    by_hand = kp * np.sum(r.load_point[:, None] - r.slip, axis=1)
    assert np.allclose(r.load, by_hand, rtol=1e-12, atol=1e-12)
    late = r.t > 0.5 * r.t[-1]
    assert float(np.mean(r.load[late])) == pytest.approx(
        n * (steady_friction(model, u) + eta * u), rel=0.01)


def test_spreads_straddle_one() -> None:
    """The per-block factors of the normal load and of the trap density are ``1 + s xi``,
    ``xi`` uniform on [-1, 1]: they straddle 1 and average to it. Mistake: ``xi`` on [0, 1]
    (every block loaded more than the nominal)."""
    from dryfriction.ensemble.interface import element_tracks
    from dryfriction.ensemble.population import Track

    m = InterfaceModel(TrapModel(eps=0.04), 400, 1.3, 0.7, normal_spread=0.2,
                       density_spread=0.3)
    tracks, normal = element_tracks(m, Track(12.0, "random", seed=7))
    dens = np.array([t.traps_per_a0 for t in tracks]) / 12.0
    for f, s in ((normal, 0.2), (dens, 0.3)):
        assert 1.0 - s <= f.min() < 1.0 - 0.8 * s and 1.0 + 0.8 * s < f.max() <= 1.0 + s
        assert abs(float(f.mean()) - 1.0) < 4.0 * s / math.sqrt(3.0 * 400)
