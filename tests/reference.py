"""Independent high-precision references (mpmath, 30 digits) for the analytic results.

They share no code with the package: the (+) branch is solved here from its quadratic, the
integrals are taken with mpmath's tanh-sinh quadrature in the configuration coordinate ``y``
(not in the package's clock or branch variables), and roots with mpmath's solvers.
"""

from __future__ import annotations

import mpmath as mp

mp.mp.dps = 30


class RefTrap:
    def __init__(self, alpha: float):
        a = mp.mpf(alpha)
        self.a = a
        self.D = (1 - a) ** 2
        self.yc = self.D / (4 * a)
        self.strong = self.yc < 1

    def fp(self, w):
        """f_+(w) = 6 a (w - z_+(w)), z_+ the root <= -(1-a)/2 of z^2 + (1-a) z + a w = 0."""
        disc = self.D - 4 * self.a * w
        return 6 * self.a * (w + ((1 - self.a) + mp.sqrt(max(disc, 0))) / 2)

    def fm(self, w):
        return -self.fp(-w)

    def forward(self, w):
        if w < -1:
            return mp.mpf(0)
        if w <= self.yc:
            return self.fp(w)
        if self.strong and w <= 1:
            return self.fm(w)
        return mp.mpf(0)

    def H0(self):
        if self.strong:
            return mp.quad(self.fp, [-1, self.yc]) + mp.quad(self.fm, [self.yc, 1])
        return mp.quad(self.fp, [-1, self.yc])


def _log_radius(eps, T):
    return mp.sqrt(1 + mp.mpf(eps) * mp.log(1 + mp.mpf(T)))


def ref_static_eq27(T: float, eps: float, alpha: float) -> float:
    """The eq. 27 reading, literally, in very strong pinning (paper's regime)."""
    tr = RefTrap(alpha)
    r = _log_radius(eps, T)
    yc = tr.yc
    first = mp.quad(tr.fp, [-1, -1 + r * yc])
    second = r**3 * mp.quad(tr.fp, [yc - 1 / r, yc])
    return float((first + second) / tr.H0())


def ref_pull_force(d: float, r: float, alpha: float, d_w: float = 0.0) -> float:
    """Force after a shift d by summing the three populations trap by trap, in p (Fig. 2b)."""
    tr = RefTrap(alpha)
    d, r, d_w = mp.mpf(d), mp.mpf(r), mp.mpf(d_w)
    fresh_pts = sorted({mp.mpf(-1), -1 + d, *[x for x in (tr.yc, mp.mpf(1)) if -1 < x < -1 + d]})
    fresh = mp.quad(tr.forward, fresh_pts) if d > 0 else 0

    def aged_plus(p):
        return r**2 * tr.forward(p / r)

    def aged_minus(p):
        w = p / r
        return r**2 * tr.fm(w) if w <= 1 else mp.mpf(0)

    brk = [x for x in (r * tr.yc, r) if -1 + d < x < 1 + d]
    plus_pts = sorted({-1 + d, d_w + d, *[x for x in brk if -1 + d < x < d_w + d]})
    minus_pts = sorted({d_w + d, 1 + d, *[x for x in brk if d_w + d < x < 1 + d]})
    return float(
        (fresh + mp.quad(aged_plus, plus_pts) + mp.quad(aged_minus, minus_pts)) / tr.H0()
    )


def ref_steady(u: float, eps: float, alpha: float) -> float:
    """eq. 34 with the log creep law, integrated in y."""
    tr = RefTrap(alpha)
    u, eps = mp.mpf(u), mp.mpf(eps)

    def r(y):
        return mp.sqrt(1 + eps * mp.log(1 + (y + 1) / u))

    yd = mp.findroot(lambda y: y / r(y) - tr.yc, (tr.yc, tr.yc * r(tr.yc) * 1.01 + 1e-3),
                     solver="anderson")
    knots = [-1, -1 + u] if u < 1 else [-1]
    integral = mp.quad(lambda y: r(y) ** 2 * tr.fp(y / r(y)), [*knots, yd])
    if tr.strong:
        ye = mp.findroot(lambda y: y / r(y) - 1, (mp.mpf(1), r(1) * 1.01 + 1e-3),
                         solver="anderson")
        integral += mp.quad(lambda y: r(y) ** 2 * tr.fm(y / r(y)), [yd, ye])
    return float(integral / tr.H0())
