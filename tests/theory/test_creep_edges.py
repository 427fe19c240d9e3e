"""Creep-law helpers at their edges (issue 25): the Eyring-Nabarro range T_v against its
closed form, the refusal on both sides of it with an eps per point, per_eps's grouping and
chunking against a plain loop, eq. 18's material round trip at a generic point."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import exp1

from dryfriction.theory import creep
from dryfriction.theory.creep import CreepMaterial, check_age, max_age, per_eps


def _tv(eps: float) -> float:
    """``T_v = (e^{1/eps}/eps) [E1(1) - E1(1/eps)]`` (module docstring of theory/creep.py)."""
    return math.exp(1.0 / eps) / eps * (exp1(1.0) - exp1(1.0 / eps))


def test_max_age_is_its_closed_form() -> None:
    for eps in (0.043, 0.1, 0.31):
        assert max_age(eps) == pytest.approx(_tv(eps), rel=1e-12)
    assert max_age(0.1) == pytest.approx(4.8e4, rel=0.02)  # the docstring's numbers
    assert max_age(0.05) == pytest.approx(2.1e9, rel=0.02)
    assert max_age(0.043, "log") == math.inf
    assert max_age(1e-3) == math.inf  # beyond the largest float


def test_check_age_both_sides_with_an_eps_per_point() -> None:
    e1, e2 = 0.1, 0.043
    t1, t2 = max_age(e1), max_age(e2)
    check_age(np.array([t1, t2]), np.array([e1, e2]), "eyring-nabarro")  # each at its own end
    check_age(1e300, 0.1, "log")  # the log law takes every age
    with pytest.raises(ValueError, match=r"^t_w = 1e\+06 is beyond the Eyring-Nabarro law's "
                                         r"range at eps = 0.1: by T = 4\.8.*use t_w <= 4\.8"):
        check_age(np.array([1.0, 1e6]), np.array([e2, e1]), "eyring-nabarro", name="t_w")
    with pytest.raises(ValueError, match="at eps = 0.043"):
        check_age(t2 * (1 + 1e-9), e2, "eyring-nabarro")


def test_per_eps_groups_and_chunks_like_a_loop(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(creep, "PER_EPS_CHUNK", 3)  # several chunks per eps
    eps = np.array([[0.07], [0.02], [0.07], [0.05]])  # unsorted, repeated, broadcast
    x = np.linspace(0.3, 9.1, 11)

    def fn(law, xs):  # type: ignore[no-untyped-def]
        return np.asarray(law.radius(xs)) + 100.0 * law.eps

    got = per_eps(fn, "log", eps, x)
    want = np.array([[fn(creep.creep_law("log", float(e)), np.array([v]))[0] for v in x]
                     for e in eps[:, 0]])
    assert got.shape == (4, 11)
    np.testing.assert_allclose(got, want, rtol=1e-15)
    assert np.ndim(per_eps(fn, "log", np.float64(0.05), np.float64(2.0))) == 0


def test_material_from_reduced_round_trip() -> None:
    m = CreepMaterial.from_reduced(0.043, 2.7e-3, 3.1e9)
    assert m.eps == pytest.approx(0.043, rel=1e-15)
    assert m.S == pytest.approx(0.043 * 3.1e9, rel=1e-15) and m.Y == 3.1e9
    assert m.t0 == pytest.approx(2.7e-3, rel=1e-12)
    x = 1 / 0.043  # eq. 18: t0 = 1/(edot0 (Y/S) e^{Y/S})
    assert 1.0 / (m.edot0 * x * math.exp(x)) == pytest.approx(2.7e-3, rel=1e-12)
