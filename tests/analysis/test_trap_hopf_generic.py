"""The trap-Hopf reduction's pieces a user reads, each against a route written here
(dryfriction.analysis.trap_hopf): the death age and the population's friction of an age
profile OFF steady sliding (a quadratic sigma(tau), which the Chebyshev interpolant carries
exactly) against the definition of the module docstring (spinodal by brentq, the integral by
scipy.integrate.quad), for both creep laws; the normal-form amplitudes and the nature's
branches of a hand-built TrapHopf against their formulas, on both sides of each threshold."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from dryfriction.analysis.trap_hopf import TrapField, TrapHopf
from dryfriction.theory.model import TrapModel
from dryfriction.theory.trap import Trap, force_plus


def _profile(fld: TrapField) -> tuple[float, float]:
    """A forward-sliding profile sigma = a tau + b tau^2 off steady (a != u, b != 0)."""
    return 0.83 * fld.u, 0.21 * fld.u / fld.tau_d


@pytest.mark.parametrize("creep", ["log", "eyring-nabarro"])
def test_death_age_and_mu_age_of_a_non_steady_profile_match_the_definition(creep: str) -> None:
    model = TrapModel(alpha=0.13, eps=0.037, direct=0.023, v_ref=1.3, creep=creep)
    u = 0.27
    fld = TrapField(u, model, n=12, panels=16, stretch=1.6)
    a, b = _profile(fld)
    law, alpha, yc = model.law, model.alpha, Trap(model.alpha).y_c

    def R(t: float) -> float:  # r^2 of the age t (eq. 19 / eqs. 15-16, the law's own radius)
        return float(law.radius(np.array([t]))[0]) ** 2

    def sig(t: float) -> float:
        return a * t + b * t * t

    # the spinodal: sigma(tau_end) - 1 = y_c r(tau_end) (eq. 32)
    t_end = brentq(lambda t: sig(t) - 1.0 - yc * math.sqrt(R(t)), 1e-9, fld.L, xtol=1e-14)
    vals = a * fld.tau + b * fld.tau**2
    dvals = a + 2.0 * b * fld.tau
    assert fld.death_age(vals, dvals) == pytest.approx(t_end, rel=1e-9)
    assert abs(t_end / fld.tau_d - 1.0) > 0.02  # truly off the steady death age

    def integrand(t: float) -> float:
        w = (sig(t) - 1.0) / math.sqrt(R(t))
        return (a + 2.0 * b * t) * R(t) * float(force_plus(min(w, yc), alpha))

    brk = [t for t in (0.5, 1.0, 2.0, 4.0, 8.0) if t < t_end]
    ref = quad(integrand, 0.0, t_end, points=brk, limit=200, epsabs=0.0, epsrel=1e-11)[0]
    ref /= Trap(alpha).H0
    assert fld.mu_age(vals[1:]) == pytest.approx(ref, rel=2e-6)


def _hopf(K_c: float = 0.41, omega: float = 0.73, l1_x: float = -2.9, rel: float = 0.3,
          dbeta: float = -0.57) -> TrapHopf:
    return TrapHopf(u=0.27, n=12, K_c=K_c, omega=omega, l1_x=l1_x, relative_l1=rel,
                    dbeta_dK=dbeta, K_c_nyquist=K_c, omega_nyquist=omega, mu_error=0.0,
                    point=None)


def test_normal_form_amplitudes_against_the_formula_on_both_sides() -> None:
    h = _hopf()  # supercritical, dbeta < 0: unstable below K_c, the stable cycle there
    K = 0.37
    beta = -0.57 * (K - 0.41)
    slip = 2.0 * math.sqrt(-beta / (0.73 * -2.9))
    assert h.slip_amplitude(K) == pytest.approx(slip, rel=1e-12)
    assert h.force_amplitude(K) == pytest.approx(K * slip, rel=1e-12)
    assert math.isnan(h.slip_amplitude(0.45)) and math.isnan(h.force_amplitude(0.45))
    assert math.isnan(h.slip_amplitude(0.41))  # at K_c itself: no cycle (r = 0 is not > 0)
    sub = _hopf(l1_x=2.9)  # subcritical: the (unstable) cycle sits on the stable side
    assert sub.slip_amplitude(0.45) == pytest.approx(
        2.0 * math.sqrt(0.57 * 0.04 / (0.73 * 2.9)), rel=1e-12)
    assert math.isnan(sub.slip_amplitude(0.37))


def test_nature_branches_and_the_degenerate_threshold_both_sides() -> None:
    assert _hopf().nature == "supercritical"
    assert _hopf(l1_x=2.9).nature == "subcritical"
    assert _hopf(rel=0.9e-8).nature == "degenerate"
    assert _hopf(rel=-0.9e-8, l1_x=2.9).nature == "degenerate"
    assert _hopf(rel=1.1e-8).nature == "supercritical"
    assert _hopf(rel=-1.1e-8, l1_x=2.9).nature == "subcritical"
    assert _hopf(K_c=math.nan).nature == "none"
    assert _hopf(K_c=math.inf).nature == "none"
