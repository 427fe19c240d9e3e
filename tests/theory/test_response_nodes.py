"""``theory.stability.SteadyResponse.nodes``: the refined quadrature of the steady
population's memory term (issue 25, strengthen7B).

At every level the nodes must still integrate the population: ``Z(0) = 0`` (a constant shift
is a relabelling) and ``Z'(0) = d mu_d/du`` (the slope of
:func:`~dryfriction.theory.steady.steady_friction`, by central difference), with the static
part and the edge terms of the coarse level; ``16 x 6 x 2^level`` Gauss nodes per branch, one
branch in very strong pinning and two in strong pinning (the (-) branch up to ``w = 1``), all
ages inside ``[0, tau_end]``. Generic ``u``, ``eps`` and ``alpha`` in both regimes.
"""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.theory.model import TrapModel
from dryfriction.theory.stability import steady_response
from dryfriction.theory.steady import steady_friction

CASES = [(0.13, 0.043, 0.0071, 1), (0.61, 0.057, 0.023, 2)]  # alpha, eps, u, branches


@pytest.mark.parametrize("alpha, eps, u, n_branches", CASES, ids=["very-strong", "strong"])
def test_every_level_integrates_the_population(alpha: float, eps: float, u: float,
                                               n_branches: int) -> None:
    model = TrapModel(alpha=alpha, eps=eps)
    resp = steady_response(u, model)
    assert len(resp.branches) == n_branches
    du = 1e-4 * u
    slope = float((steady_friction(model, u + du) - steady_friction(model, u - du)) / (2 * du))
    tau_end = max(float(br_end) for br_end in resp.law.age(np.array(
        [br.c1 for br in resp.branches])))
    for level in (0, 1, 3):
        T, b = resp.nodes(level)
        assert T.size == b.size == 16 * 6 * 2**level * n_branches
        assert np.all((T >= 0.0) & (T <= tau_end * (1 + 1e-12)))
        assert np.unique(T).size == T.size
        z0 = (resp.A + float(np.sum(b)) + resp.edge * (1.0 - resp.edge_delay)) / resp.H0
        assert abs(z0) < 1e-10, (level, z0)
        z1 = (float(np.sum(-T * b)) + resp.edge * resp.edge_delay * resp.tau_d) / resp.H0
        assert z1 == pytest.approx(slope, rel=2e-6), level
    assert resp.nodes(0)[0] is resp.T  # the coarse level is the response's own nodes
    assert resp.nodes(3) is resp.nodes(3)  # cached


def test_memory_at_a_high_frequency_agrees_with_finer_nodes() -> None:
    """At ``lambda = 0.83 + 170 i`` (under the endpoint expansion's ``|lambda| = 200``)
    ``memory`` equals the sum over converged nodes (level 10) to 1e-9: the level is chosen from
    ``|lambda|`` by the phase rule, not left coarse (level 6, 16 times fewer panels per phase
    than the rule, is 1.7e-7 off; level 0 is off by more than the value)."""
    resp = steady_response(0.0071, TrapModel(alpha=0.61, eps=0.057))
    lam = 0.83 + 170.0j
    T, b = resp.nodes(10)
    fine = complex(np.exp(-lam * T) @ b)
    T0, b0 = resp.nodes(0)
    coarse = complex(np.exp(-lam * T0) @ b0)
    got = complex(resp.memory(np.array([lam]))[0])
    assert abs(got - fine) <= 1e-9 * abs(fine)
    assert abs(coarse - fine) > 1e-4 * abs(fine)  # the coarse nodes would not do
