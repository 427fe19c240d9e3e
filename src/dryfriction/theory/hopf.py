"""The first Lyapunov coefficient of a Hopf point of a smooth ODE ``x' = f(x)`` (pure: no model).

At an equilibrium ``x0`` whose Jacobian ``A = Df(x0)`` has a simple pair ``+-i omega`` (and no
other eigenvalue on the imaginary axis), the flow on the centre manifold is, to third order,
the Poincaré normal form (Kuznetsov 2004, *Elements of Applied Bifurcation Theory*, 3rd ed.,
§3.5 and §5.4)::

    z' = (beta + i omega) z + c1 z |z|^2,        x ~ x0 + 2 Re(z q)

with ``A q = i omega q``, ``A^T p = -i omega p``, ``<p, q> = 1`` (``<u, v> = conj(u) . v``) and
``beta`` the real part of the critical eigenvalue as a parameter moves. Kuznetsov's invariant
formula (his eq. (3.20), written for ``R^n`` in §5.4)::

    l1 = Re c1 / omega,
    c1 = 1/2 [ <p, C(q, q, qbar)> - 2 <p, B(q, A^-1 B(q, qbar))>
               + <p, B(qbar, (2 i omega I - A)^-1 B(q, q))> ]

with ``B`` and ``C`` the symmetric multilinear forms of the second and third derivatives of
``f`` at ``x0``. ``l1 < 0``: supercritical (a stable cycle is born on the unstable side, of
``|z|^2 = -beta / Re c1``); ``l1 > 0``: subcritical (an unstable cycle exists on the stable
side); ``l1 = 0``: degenerate (the third-order normal form decides nothing).

Normalisation (ours, stated because ``l1`` depends on it): ``|q| = 1`` in the Euclidean norm
of the coordinates ``x``. Under a linear change ``y = T x`` the sign of ``l1`` is invariant and
its size becomes ``l1 / |T q|^2`` (a rescaling of ``z``; ours, from ``z' = ...`` above). The
amplitude of component ``j`` of the cycle, half its peak-to-peak value, is
``2 |q_j| sqrt(-beta / Re c1)`` (ours, from ``x ~ x0 + 2 Re(z q)``), which is coordinate-free
and what :func:`cycle_amplitude` returns.

Derivatives (ours): ``B`` and ``C`` come from the directional derivatives
``g^(m)(0)`` of ``g(t) = f(x0 + t u)`` and polarisation. Two methods:

* ``"complex"`` (default): ``f`` accepts complex arrays and is holomorphic (written with
  ``exp``, ``log``, powers; no ``abs`` or comparisons). The Taylor coefficients of ``g`` come
  from ``N`` points on the circle ``|t| = r`` in the complex plane (the Cauchy integral by the
  trapezoidal rule, Lyness & Moler 1967, *SIAM J. Numer. Anal.* 4, 202): there is no
  subtraction of nearby values, the error is the aliasing ``(r/R)^N`` (``R`` the radius of
  convergence) plus a rounding of ``eps |f| / r^m``, so ``r = 0.25 scale`` and ``N = 32`` give
  near machine precision for an ``f`` analytic over a few ``scale``;
* ``"fd"``: real central differences of fourth order along real directions (the stencils
  ``[-1, 16, -30, 16, -1]/12 h^2`` and ``[1, -8, 13, 0, -13, 8, -1]/8 h^3``), step
  ``h = 0.01 scale``: the truncation error ``~ h^4`` and the rounding ``~ eps/h^3`` balance
  near ``h ~ eps^(1/7) ~ 0.006`` for ``f`` and its derivatives of order 1 (tested).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ..validation import Array, check_scalar

__all__ = ["HopfPoint", "first_lyapunov", "cycle_amplitude", "jacobian"]

Method = Literal["complex", "fd"]
_N_CIRCLE = 32  # points on the Cauchy circle (ours: aliasing (r/R)^32 is negligible for R >= 4 r)
_R_CIRCLE = 0.25  # circle radius, in units of ``scale``
_H_FD = 0.01  # finite-difference step, in units of ``scale`` (module docstring)


@dataclass(frozen=True)
class HopfPoint:
    """The third-order normal form of a Hopf point (module docstring).

    Attributes
    ----------
    omega : float
        Angular frequency of the critical pair, 1/(time unit of ``f``), ``> 0``.
    l1 : float
        First Lyapunov coefficient ``Re c1 / omega``, 1/(unit of x)^2 with ``|q| = 1``.
    c1 : complex
        Normal-form coefficient, 1/((unit of x)^2 time).
    q, p : ndarray of complex
        Right and left critical eigenvectors, ``|q| = 1``, ``<p, q> = 1``.
    terms : tuple of float
        ``Re`` of the three terms of ``c1/omega`` (cubic, ``A^-1`` and ``2 i omega`` parts):
        their sizes set the scale on which ``l1`` is zero (:attr:`relative_l1`).
    residual : float
        ``|Re lambda| / omega`` of the critical eigenvalue: how far ``x0`` is from an exact
        Hopf point (the formula takes ``lambda = i omega``).
    """

    omega: float
    l1: float
    c1: complex
    q: Array
    p: Array
    terms: tuple[float, float, float]
    residual: float

    @property
    def relative_l1(self) -> float:
        """``l1`` over the largest of its terms (dimensionless): near 0 is a cancellation."""
        big = max(abs(t) for t in self.terms)
        return self.l1 / big if big > 0 else 0.0


def jacobian(f: Callable[[Array], Array], x0: Array, method: Method = "complex",
             scale: float = 1.0) -> Array:
    """``Df(x0)``: by the complex step ``Im f(x0 + i h e_j)/h`` (``h = 1e-20 scale``, exact to
    rounding for a holomorphic ``f``; Squire & Trapp 1998, *SIAM Rev.* 40, 110) or by fourth-order
    central differences (``"fd"``, ``[1, -8, 8, -1]/12 h``, ``h = 0.01 scale``).

    Parameters
    ----------
    f : callable
        The vector field (units of x per unit time).
    x0 : array_like
        Where the Jacobian is taken.
    method : {"complex", "fd"}
    scale : float
        Size of ``x`` over which ``f`` is smooth (unit of x).

    Returns
    -------
    ndarray
        ``n x n``, 1/time.
    """
    x0 = np.asarray(x0, float)
    n = x0.size
    out = np.empty((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = 1.0
        if method == "complex":
            h = 1e-20 * scale
            out[:, j] = np.imag(np.asarray(f(x0 + 1j * h * e))) / h
        else:
            h = _H_FD * scale
            fp = [np.asarray(f(x0 + k * h * e), float) for k in (-2, -1, 1, 2)]
            out[:, j] = (fp[0] - 8 * fp[1] + 8 * fp[2] - fp[3]) / (12 * h)
    return out


def _directional(f: Callable[[Array], Array], x0: Array, method: Method,
                 scale: float) -> tuple[Callable[[Array], Array], Callable[[Array], Array]]:
    """``(D2, D3)``: ``u -> B(u, u)`` and ``u -> C(u, u, u)`` for a unit direction ``u``
    (complex for ``"complex"``, real for ``"fd"``)."""
    if method == "complex":
        r = _R_CIRCLE * scale
        t = r * np.exp(2j * np.pi * np.arange(_N_CIRCLE) / _N_CIRCLE)

        def taylor(u: Array, m: int) -> Array:
            g = np.array([np.asarray(f(x0 + tk * u), complex) for tk in t])
            # m-th Taylor coefficient: the trapezoidal rule on the Cauchy integral
            c = np.mean(g * np.exp(-2j * np.pi * m * np.arange(_N_CIRCLE) / _N_CIRCLE)[:, None],
                        axis=0) / r**m
            return math.factorial(m) * c

        return (lambda u: taylor(u, 2)), (lambda u: taylor(u, 3))
    h = _H_FD * scale

    def values(u: Array, ks: tuple[int, ...]) -> list[Array]:
        return [np.asarray(f(x0 + k * h * u), float) for k in ks]

    def d2(u: Array) -> Array:
        a, b, c, d, e = values(u, (-2, -1, 0, 1, 2))
        return (-a + 16 * b - 30 * c + 16 * d - e) / (12 * h * h)

    def d3(u: Array) -> Array:
        a, b, c, d, e, g = values(u, (-3, -2, -1, 1, 2, 3))
        return (a - 8 * b + 13 * c - 13 * d + 8 * e - g) / (8 * h**3)

    return d2, d3


def _forms(f: Callable[[Array], Array], x0: Array, method: Method, scale: float
           ) -> tuple[Callable[[Array, Array], Array], Callable[[Array, Array], Array]]:
    """``B(x, y)`` and ``C(x, x, y)`` for complex vectors (module docstring), by polarisation
    of the directional derivatives along unit directions."""
    d2, d3 = _directional(f, x0, method, scale)

    def unit(v: Array) -> tuple[Array, float]:
        s = float(np.linalg.norm(v))
        return (v / s, s) if s > 0 else (v, 0.0)

    if method == "complex":
        def b_form(x: Array, y: Array) -> Array:
            (xu, sx), (yu, sy) = unit(x), unit(y)
            if sx == 0 or sy == 0:
                return np.zeros(x.size, complex)
            return sx * sy * (d2(xu + yu) - d2(xu - yu)) / 4

        def c_form(x: Array, y: Array) -> Array:
            (xu, sx), (yu, sy) = unit(x), unit(y)
            # C(x, x, y) = [T(x + y) - T(x - y) - 2 T(y)] / 6, T(u) = C(u, u, u)
            return sx * sx * sy * (d3(xu + yu) - d3(xu - yu) - 2 * d3(yu)) / 6

        return b_form, c_form

    def b_real(x: Array, y: Array) -> Array:
        (xu, sx), (yu, sy) = unit(x), unit(y)
        if sx == 0 or sy == 0:
            return np.zeros(x.size)
        return sx * sy * (d2(xu + yu) - d2(xu - yu)) / 4

    def c_real(x: Array, y: Array) -> Array:  # C(x, x, y) for real x, y
        (xu, sx), (yu, sy) = unit(x), unit(y)
        if sx == 0 or sy == 0:
            return np.zeros(x.size)
        return sx * sx * sy * (d3(xu + yu) - d3(xu - yu) - 2 * d3(yu)) / 6

    def b_form(x: Array, y: Array) -> Array:
        a, b, c, d = x.real, x.imag, y.real, y.imag
        return b_real(a, c) - b_real(b, d) + 1j * (b_real(a, d) + b_real(b, c))

    def c_form(x: Array, y: Array) -> Array:
        # C(x, x, y) = C(a,a,c) - C(b,b,c) - 2 C(a,b,d) + i [C(a,a,d) - C(b,b,d) + 2 C(a,b,c)],
        # with C(a, b, w) = [C(a+b, a+b, w) - C(a-b, a-b, w)] / 4
        a, b, c, d = x.real, x.imag, y.real, y.imag

        def cab(w: Array) -> Array:
            return (c_real(a + b, w) - c_real(a - b, w)) / 4

        re = c_real(a, c) - c_real(b, c) - 2 * cab(d)
        im = c_real(a, d) - c_real(b, d) + 2 * cab(c)
        return re + 1j * im

    return b_form, c_form


def first_lyapunov(
    f: Callable[[Array], Array], x0: Array, *, jac: Array | None = None,
    method: Method = "complex", scale: float = 1.0, residual_max: float = 1e-6,
) -> HopfPoint:
    """First Lyapunov coefficient of the Hopf point ``x0`` of ``x' = f(x)`` (Kuznetsov 2004,
    eq. (3.20); module docstring for the formula, the normalisation and the derivatives).

    Parameters
    ----------
    f : callable
        The vector field, ``f(x) -> x'`` for an array ``x`` of ``n >= 2`` components (units of
        x per unit time). For ``method="complex"`` it must accept complex ``x`` and be
        holomorphic there.
    x0 : array_like
        The equilibrium, ``f(x0) = 0``.
    jac : ndarray, optional
        ``Df(x0)`` when known analytically; else computed (:func:`jacobian`).
    method : {"complex", "fd"}
        How the second and third derivatives are taken.
    scale : float
        Size of ``x`` over which ``f`` is smooth (unit of x, ``> 0``): the Cauchy circle's
        radius is ``0.25 scale``, the difference step ``0.01 scale``.
    residual_max : float
        Largest ``|Re lambda|/omega`` of the critical pair accepted (``x0`` must be a Hopf
        point to this precision).

    Returns
    -------
    HopfPoint

    Raises
    ------
    ValueError
        No complex pair, or its ``|Re lambda|/omega`` exceeds ``residual_max``; a bad method.
    """
    if method not in ("complex", "fd"):
        raise ValueError(f"method = {method!r} is not allowed: 'complex' or 'fd'")
    scale = check_scalar("scale", scale, 0.0, lo_open=True)
    x0 = np.asarray(x0, float).ravel()
    A = jacobian(f, x0, method, scale) if jac is None else np.asarray(jac, float)
    lam, vecs = np.linalg.eig(A)
    # complex relative to its own size: a stiff field's fast real eigenvalues (1e50 at a
    # vanishing mass) must not hide a pair of order 1
    pair = np.flatnonzero(lam.imag > 1e-9 * np.abs(lam))
    if pair.size == 0:
        raise ValueError("the Jacobian has no complex pair: x0 is not a Hopf point")
    i = pair[np.argmin(np.abs(lam[pair].real))]
    omega = float(lam[i].imag)
    residual = abs(float(lam[i].real)) / omega
    if residual > residual_max:
        raise ValueError(f"|Re lambda|/omega = {residual:.3g} of the critical pair exceeds "
                         f"residual_max = {residual_max:g}: x0 is not a Hopf point")
    q = vecs[:, i] / np.linalg.norm(vecs[:, i])
    lt, vt = np.linalg.eig(A.T)
    p = vt[:, np.argmin(np.abs(lt - np.conj(lam[i])))]
    p = p / np.conj(np.vdot(p, q))  # <p, q> = conj(p) . q = 1
    b_form, c_form = _forms(f, x0, method, scale)
    qb = np.conj(q)
    n = x0.size
    h11 = np.linalg.solve(A, b_form(q, qb))
    h20 = np.linalg.solve(2j * omega * np.eye(n) - A, b_form(q, q))
    t1 = np.vdot(p, c_form(q, qb))
    t2 = -2 * np.vdot(p, b_form(q, h11))
    t3 = np.vdot(p, b_form(qb, h20))
    c1 = complex(0.5 * (t1 + t2 + t3))
    terms = (0.5 * t1.real / omega, 0.5 * t2.real / omega, 0.5 * t3.real / omega)
    return HopfPoint(omega=omega, l1=c1.real / omega, c1=c1, q=q, p=p, terms=terms,
                     residual=residual)


def cycle_amplitude(point: HopfPoint, beta: float) -> Array:
    """Half peak-to-peak amplitude of each component of the cycle born at the Hopf point,
    ``2 |q_j| sqrt(-beta / Re c1)`` (module docstring), unit of x.

    Parameters
    ----------
    point : HopfPoint
    beta : float
        Real part of the critical eigenvalue at the parameter of interest (1/time): the cycle
        exists where ``beta`` and ``Re c1`` have opposite signs (else NaN).
    """
    ratio = -beta / point.c1.real if point.c1.real != 0 else math.nan
    amp = 2 * np.abs(point.q) * math.sqrt(ratio) if ratio > 0 else np.full(point.q.size, math.nan)
    return np.asarray(amp, float)
