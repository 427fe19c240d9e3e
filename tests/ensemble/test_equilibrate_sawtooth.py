"""``ensemble.balance.equilibrate`` on a force of closed form (issue 25, strengthen7B).

A stand-in for the ensemble whose frozen-age force is a tilted sawtooth,
``F(X) = F0 + s (X - e_n)`` on ``(e_n, e_n+1)`` with spinodals at ``e_n = phase + n L`` where
the force drops by ``s L``: the spring's balance ``A - K X - g(X) F(X) = 0`` then has roots the
test writes down (a line per stretch, or a quadratic with a linear strength ``g``), and the
jump's extreme force, the spinodals passed and the runaway cap are known exactly. Forward and
backward jumps, with and without the direct effect's strength; generic numbers (none 0 or 1).
"""

from __future__ import annotations

import math

import pytest

from dryfriction.ensemble.balance import TINY, add_events, equilibrate
from dryfriction.ensemble.population import Observables

F0, S, L, PHASE = 0.31, 0.83, 0.47, 0.13
K = 0.05


def force(x: float, d: int) -> float:
    """The sawtooth seen from direction ``d`` (its left limit going forward)."""
    return F0 + S * (x - edge(x, d))


def edge(x: float, d: int) -> float:
    """The spinodal at the start of the stretch holding ``x`` (seen from ``d``)."""
    q = (x - PHASE) / L
    n = math.ceil(q) - 1 if d > 0 else math.floor(q)
    return PHASE + n * L


class Saw:
    """What :func:`equilibrate` asks of an ensemble: ``x``, ``t``, ``observe``, ``probe``,
    ``advance``; each spinodal passed counts 3 births, 1 spinodal and 2 exits (distinct, so
    that a permuted tuple shows)."""

    def __init__(self, x: float) -> None:
        self.x, self.t = x, 2.9
        self.path = [x]  # every position advanced to

    def probe(self, x: float, d: int, stiffness: bool = False) -> Observables:
        e = edge(x, d)
        nxt = e + L if d > 0 else e
        return Observables(force(x, d), S if stiffness else 0.0, 7, 1.3, 0, 0, 0, nxt)

    def observe(self, d: int = 1, *, stiffness: bool = False) -> Observables:
        return self.probe(self.x, d, stiffness)

    def advance(self, x1: float, t1: float) -> Observables:
        n = abs(math.floor((x1 - PHASE) / L) - math.floor((self.x - PHASE) / L))
        d = 1 if x1 >= self.x else -1
        self.x, self.t = x1, t1
        self.path.append(x1)
        o = self.probe(x1, d)
        return Observables(o.force, 0.0, 7, 1.3, 3 * n, n, 2 * n, o.next_event)


class Strength:
    """A linear strength ``g(X) = G0 + G1 (X - X0)`` with its slope (stands in for
    :class:`~dryfriction.ensemble.thermal.VelocityScale`)."""

    G0, G1, X0 = 1.17, 0.07, 0.2

    def __call__(self, x: float) -> float:
        return self.G0 + self.G1 * (x - self.X0)

    def slope(self, x: float) -> float:
        return self.G1


def test_forward_jump_root_extreme_and_spinodals() -> None:
    """A = 0.775 from x = 0.2: the balance ``A - K X - F0 - s (X - e_n)`` first vanishes in the
    stretch after the spinodals at 0.6 and 1.07, at ``X = (A - F0 + s e_2)/(K + s)``; the
    largest force met is the top of a passed stretch, ``F0 + s (L - TINY)``, above the end's.
    Mistakes: the extreme taken at the end only, min for max, the events permuted."""
    A, ens = 0.775, Saw(0.2)
    extreme, runaway, ev = equilibrate(ens, A, K, 1e3)
    root = (A - F0 + S * (PHASE + 2 * L)) / (K + S)
    assert 1.07 < root < PHASE + 3 * L
    assert ens.x == pytest.approx(root, abs=1e-12)
    assert not runaway
    assert ev == (6, 2, 4)
    top = F0 + S * (L - TINY)
    assert top > force(root, 1)
    assert extreme == pytest.approx(top, abs=1e-12)


def test_backward_jump_root_extreme_and_spinodals() -> None:
    """A = 0.328 from x = 1.3: the slider moves back over the spinodals at 1.07 and 0.6 (the
    force rises there, going backward) to ``X = (A - F0 + s e_0)/(K + s)`` in the first
    stretch; the extreme is the smallest force met, a stretch's bottom ``F0 + s TINY``.
    The slider never moves forward on the way (in the real ensemble a forward excursion would
    kill traps). Mistakes: the direction from the sign of ``A`` not of ``G``, max for min going
    back, the first spinodal looked for forwards."""
    A, ens = 0.328, Saw(1.3)
    extreme, runaway, ev = equilibrate(ens, A, K, 1e3)
    root = (A - F0 + S * PHASE) / (K + S)
    assert PHASE < root < PHASE + L
    assert ens.x == pytest.approx(root, abs=1e-12)
    assert not runaway and ev == (6, 2, 4)
    assert extreme == pytest.approx(F0 + S * TINY, abs=1e-12)
    assert extreme < force(root, -1)
    assert all(b <= a for a, b in zip(ens.path[:-1], ens.path[1:], strict=True)), ens.path


def test_a_jump_capped_by_max_slip_is_a_runaway() -> None:
    """Forward with ``max_slip`` = 0.6 short of the root (1.34 away): the slider stops at
    ``start + max_slip - TINY`` and says so; the spinodal passed on the way (0.6) counts and its
    top is the extreme. Mistakes: the cap ignored, ``runaway`` False, the cap's end not the
    slider's."""
    A, ens = 0.775, Saw(0.2)
    extreme, runaway, ev = equilibrate(ens, A, K, 0.6)
    assert runaway
    assert ens.x == pytest.approx(0.2 + 0.6 - TINY, abs=1e-13)
    assert ev == (3, 1, 2)
    assert extreme == pytest.approx(F0 + S * (L - TINY), abs=1e-12)


def test_with_a_strength_the_root_solves_the_quadratic() -> None:
    """``A - K X - g(X) F(X) = 0`` with ``g`` linear: on the stretch after 1.07 it is the
    quadratic ``G1 s X^2 + ... = 0``, solved here by its formula; the extreme is the strength
    times the top force at the last spinodal passed. Mistakes: the strength left out of the
    root or of the extreme, the strength taken at the start instead of at X."""
    g = Strength()
    A, ens = 0.93, Saw(0.2)
    extreme, runaway, ev = equilibrate(ens, A, K, 1e3, scale=g)
    # G(X) = A - K X - (g0 + g1 (X - X0)) (F0 + s (X - e)),  e the stretch's start
    e = PHASE + 2 * L
    a = -g.G1 * S
    c0, c1 = g.G0 - g.G1 * g.X0, F0 - S * e  # g = c0 + g1 X, F = c1 + s X
    b = -K - c0 * S - g.G1 * c1
    c = A - c0 * c1
    root = (-b - math.sqrt(b * b - 4 * a * c)) / (2 * a)
    assert e < root < e + L
    assert ens.x == pytest.approx(root, abs=1e-12)
    assert not runaway and ev == (6, 2, 4)
    xt = e - TINY  # the top of the stretch passed last
    assert extreme == pytest.approx(g(xt) * force(xt, 1), abs=1e-12)


def test_in_balance_already_nothing_moves() -> None:
    """``A = K x + F(x)``: the balance holds to its tolerance; the slider stays, the force is
    returned, no events."""
    x = 0.9
    ens = Saw(x)
    A = K * x + force(x, 1)
    extreme, runaway, ev = equilibrate(ens, A, K, 1e3)
    assert ens.x == x and not runaway and ev == (0, 0, 0)
    assert extreme == pytest.approx(force(x, 1), abs=1e-15)


def test_add_events_adds_componentwise() -> None:
    assert add_events((3, 5, 7), (11, 13, 17)) == (14, 18, 24)
