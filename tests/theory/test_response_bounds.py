"""Secondary quantities of the linear responses, from their definitions written here
(issue 25, strengthen6B): ``SteadyResponse.delay_amplitude``, ``DirectResponse.im_bound``,
``HopfPoint.relative_l1``. Responses built by hand (fixed nodes) at generic, signed values."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.theory.hopf import HopfPoint
from dryfriction.theory.linear_stability import DirectResponse
from dryfriction.theory.stability import SteadyResponse

# weights of both signs, a negative edge: the absolute values matter
_T = np.array([0.3, 1.1, 2.6])
_B = np.array([0.8, -1.9, 0.45])
H0, A, EDGE, DELAY, TAU = 1.7, 0.6, -0.9, 0.55, 3.2


def _resp() -> SteadyResponse:
    return SteadyResponse(u=0.37, eps=0.1, alpha=0.4, H0=H0, A=A, T=_T, b=_B, tau_d=TAU,
                          edge=EDGE, edge_delay=DELAY)


def test_hand_built_z_is_its_definition() -> None:
    """``H0 Z = A + sum b e^{-lambda T} + edge (1 - delay e^{-lambda tau_d})``."""
    lam = np.array([0.2 + 1.3j, 0.0 + 7.1j])
    want = (A + np.exp(-lam[:, None] * _T) @ _B + EDGE * (1 - DELAY * np.exp(-lam * TAU))) / H0
    assert np.allclose(_resp().Z(lam), want, rtol=1e-13)


def test_delay_amplitude_is_the_radius_of_the_high_frequency_circle() -> None:
    r = _resp()
    assert r.delay_amplitude == pytest.approx(abs(EDGE * DELAY) / H0, rel=1e-13)
    # the delay term alone, on one period of e^{-i omega tau_d}: its radius about -edge/H0
    om = np.linspace(0.0, 2 * np.pi / TAU, 401)
    delay_part = -EDGE * DELAY * np.exp(-1j * om * TAU) / H0
    assert np.max(np.abs(delay_part)) == pytest.approx(r.delay_amplitude, rel=1e-12)


def test_im_bound_is_g_times_the_weights_sum_and_bounds_im_z() -> None:
    g = 0.73
    d = DirectResponse(base=_resp(), g=g, a_direct=0.12)
    want = g * (np.sum(np.abs(_B)) + abs(EDGE * DELAY)) / H0
    assert d.im_bound() == pytest.approx(want, rel=1e-13)
    om = np.linspace(1e-3, 40.0, 20001)
    im = np.abs(g * _resp().Z(1j * om).imag)
    assert np.max(im) <= d.im_bound() * (1 + 1e-12)
    # and it is not loose by a factor: the bound is approached where the phases line up
    assert np.max(im) > 0.6 * d.im_bound()


def test_direct_response_z_and_derivatives() -> None:
    """``Z_A = g Z + (a_d/u) lambda``; ``Z_A'(0) = g Z'(0) + a_d/u``, higher ones ``g Z^(n)``."""
    g, ad = 0.73, 0.12
    base = _resp()
    d = DirectResponse(base=base, g=g, a_direct=ad)
    lam = np.array([0.4 + 2.2j])
    assert np.allclose(d.Z(lam), g * base.Z(lam) + ad / base.u * lam, rtol=1e-13)
    h = 1e-4
    fd1 = ((d.Z(h) - d.Z(-h)).real / (2 * h))
    assert d.derivative_at_zero(1) == pytest.approx(float(fd1), rel=1e-6)
    fd2 = ((d.Z(h) - 2 * d.Z(0.0) + d.Z(-h)).real / h**2)
    assert d.derivative_at_zero(2) == pytest.approx(float(fd2), rel=1e-5)


def _hopf(terms: tuple[float, float, float], l1: float) -> HopfPoint:
    q = np.array([1.0 + 0j, 0j])
    return HopfPoint(omega=2.3, l1=l1, c1=complex(l1 * 2.3, 0.4), q=q, p=q, terms=terms,
                     residual=0.0)


def test_relative_l1_divides_by_the_largest_term_in_size() -> None:
    # the largest term is negative: a signed max would pick 0.2
    h = _hopf((0.2, -3.1, 0.5), l1=-0.62)
    assert h.relative_l1 == pytest.approx(-0.62 / 3.1, rel=1e-13)
    assert _hopf((0.0, 0.0, 0.0), l1=0.0).relative_l1 == 0.0
