"""The paper's six figures (and a few extra panels), drawn from the library's functions.

Every function has the form ``fig_name(..., ax=None) -> (fig, ax)``: with ``ax=None`` it makes a
new :class:`matplotlib.figure.Figure` (no pyplot, no global state, no display; PNGs are rendered
by Agg); otherwise it draws into ``ax``. Nothing here computes physics beyond evaluating the
library's functions on grids: forces come from :mod:`dryfriction.trap`, friction from
:mod:`dryfriction.static` and :mod:`dryfriction.steady`, Dieterich constants from
:mod:`dryfriction.dieterich`.

Units are the reduced ones of the core: lengths in ``a0`` (``a`` for a single trap), times in
``t0``, velocities in ``V* = a0/t0``, trap forces in ``Phi0/a`` (``Phi00/a0`` for aged traps),
friction in ``F_el`` (eq. 12).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import ScalarFormatter
from numpy.typing import NDArray

from ..theory.creep import radius
from ..theory.dieterich import (
    dieterich_constant_asymptotic,
    dieterich_constant_least_squares,
    dieterich_constant_local,
)
from ..theory.static import (
    pull_force,
    static_friction,
    static_friction_first_order,
    threshold_shift,
)
from ..theory.steady import (
    steady_death_point,
    steady_friction,
    steady_friction_low_velocity,
    steady_profile,
)
from ..theory.trap import Trap, force_minus, force_plus, z_unstable

if TYPE_CHECKING:
    from ..fit import FitResult
    from ..io.data import Dataset

__all__ = [
    "EPS_FIGURES",
    "population_at_shift",
    "fig1_trap_hysteresis",
    "fig2a_aged_pinning_curve",
    "fig2b_population_at_threshold",
    "fig3_static_friction",
    "fig4_steady_pinning_curve",
    "fig5_steady_friction",
    "fig6_dieterich",
    "extra_loaded_static",
    "extra_creep_laws",
    "extra_local_dieterich_constant",
    "save_png",
    "timeseries_figure",
    "plot_fit",
    "MAX_POINTS_DRAWN",
]

Array = NDArray[np.float64]

EPS_FIGURES: tuple[float, ...] = (0.01, 0.02, 0.03, 0.04, 0.05)
"""The creep parameters of Figs. 3 and 5, labelled 1-5 in the paper."""

_COLORS = ("#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e")


def _axes(ax: Axes | None, figsize: tuple[float, float] = (5.6, 4.2)) -> tuple[Figure, Axes]:
    if ax is not None:
        return ax.figure, ax  # type: ignore[return-value]
    fig = Figure(figsize=figsize, layout="constrained")
    return fig, fig.add_subplot()


def save_png(fig: Figure, path: Any, dpi: int = 110) -> None:
    """Render ``fig`` to a PNG file with the Agg canvas."""
    fig.savefig(path, format="png", dpi=dpi)


def _label_curves(ax: Axes, x: Array, ys: Sequence[Array], where: float) -> None:
    """Write the paper's curve numbers 1-5 next to each curve at abscissa ``where``."""
    i = int(np.argmin(np.abs(np.log(x) - np.log(where))))
    for k, y in enumerate(ys):
        ax.annotate(
            str(k + 1), (x[i], y[i]), textcoords="offset points", xytext=(0, 4),
            ha="center", fontsize=9, color=_COLORS[k % len(_COLORS)], fontweight="bold",
        )


# --------------------------------------------------------------------------------------------
# Fig. 1
# --------------------------------------------------------------------------------------------


def fig1_trap_hysteresis(alpha: float = 0.13, ax: Axes | None = None) -> tuple[Figure, Axes]:
    """Fig. 1a: pinning force ``f(y)`` of one elastic trap, ``alpha = 0.13``.

    Stable branches (+) and (-), the unstable middle branch (dashed), the free states
    (``f = 0`` for ``|y| > 1``), the spinodals ``C, C' = +-y_c``, the Maxwell plateau ``y_M = 0``
    with the force jump ``12 alpha (1 - alpha)``, the jumps at the spinodals (arrows) and the
    hysteresis area ``H0`` (shaded).
    """
    trap = Trap(alpha)
    if not trap.pinned:
        raise ValueError(f"alpha = {alpha:g} is out of range: Fig. 1 needs 0 < alpha < 1")
    fig, ax = _axes(ax)
    yc = trap.y_c
    span = max(yc, 1.0) + 0.6
    yp = np.linspace(-1.0, yc, 600)
    ym = -yp[::-1]
    yu = np.linspace(-yc, yc, 600)
    fu = 6.0 * alpha * (yu - z_unstable(yu, alpha))
    fp = force_plus(yp, alpha)
    # hysteresis area: forward path along (+) (and along (-) after the jump in strong pinning)
    ax.fill_between(yp, 0.0, fp, color="0.88", zorder=0, label=r"hysteresis area $H_0$")
    ax.plot(yp, fp, color="C0", lw=2.0, label="(+) branch")
    ax.plot(ym, force_minus(ym, alpha), color="C3", lw=2.0, label="(−) branch")
    ax.plot(yu, fu, color="0.3", lw=1.2, ls="--", label="unstable branch")
    ax.plot([-span, -1.0], [0, 0], color="k", lw=1.5, label="free (no contact)")
    ax.plot([1.0, span], [0, 0], color="k", lw=1.5)
    # spinodals and the jumps leaving them
    f_c = trap.f_c
    land = float(force_minus(yc, alpha)) if yc < 1.0 else 0.0
    arrow = dict(arrowstyle="-|>", color="0.15", lw=1.2, shrinkA=0, shrinkB=0)
    ax.annotate("", xy=(yc, land), xytext=(yc, f_c), arrowprops=arrow)
    ax.annotate("", xy=(-yc, -land), xytext=(-yc, -f_c), arrowprops=arrow)
    ax.plot([yc, -yc], [f_c, -f_c], "o", color="k", ms=5)
    ax.annotate(f"C  ($y_c$ = {yc:.4f})", (yc, f_c), textcoords="offset points",
                xytext=(-10, -2), ha="right", va="top", fontsize=9)
    ax.annotate(f"C′  ($-y_c$ = {-yc:.4f})", (-yc, -f_c), textcoords="offset points",
                xytext=(12, -4), va="top", fontsize=9)
    # Maxwell plateau and its force jump
    f0p, f0m = float(force_plus(0.0, alpha)), float(force_minus(0.0, alpha))
    ax.plot([0, 0], [f0m, f0p], color="C2", lw=2.5, solid_capstyle="butt",
            label=rf"Maxwell plateau $y_M=0$, $\Delta f$ = {trap.maxwell_jump:.4f}")
    ax.axhline(0.0, color="0.6", lw=0.6, zorder=0)
    ax.margins(y=0.1)
    ax.set_xlim(-span, span)
    ax.set_xlabel(r"configuration coordinate $y = p/a$")
    ax.set_ylabel(r"pinning force $f$  [$\Phi_0/a$]")
    ax.set_title(rf"Fig. 1 — elastic trap, $\alpha$ = {alpha:g} ({trap.regime.value})",
                 fontsize=10)
    ax.legend(fontsize=7.5, loc="upper left")
    return fig, ax


# --------------------------------------------------------------------------------------------
# Fig. 2
# --------------------------------------------------------------------------------------------


def _per_trap_axes(ax: Axes, title: str) -> None:
    """Axes, zero line, title and legend shared by the force-per-trap figures (2a, 2b, 4)."""
    ax.axhline(0.0, color="0.6", lw=0.6, zorder=0)
    ax.set_xlabel(r"configuration coordinate $p/a_0$")
    ax.set_ylabel(r"pinning force per trap  [$\Phi_{00}/a_0$]")
    ax.margins(y=0.1)
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=7.5, loc="upper left")


def fig2a_aged_pinning_curve(
    T: float = 25.0, eps: float = 0.04, alpha: float = 0.13, creep: str = "log",
    ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """Fig. 2a: pinning curve of the system aged at rest under zero load for ``t_w = T t0``.

    Dashed: the elastic (fresh) curve of Fig. 1. Aged curve ``r^2 f_+-(p/r)`` (eq. 23),
    ``r = a_r(t_w)``: full where occupied (``-a0 < p < 0`` on (+), ``0 < p < a0`` on (-),
    eq. 25), dotted where empty.
    """
    trap = Trap(alpha)
    fig, ax = _axes(ax)
    r = float(radius(T, eps, creep))
    yc = trap.y_c
    yp = np.linspace(-1.0, yc, 500)
    ax.plot(yp, force_plus(yp, alpha), color="0.45", ls="--", lw=1.2,
            label="elastic (fresh) curve, Fig. 1")
    ax.plot(-yp, force_minus(-yp, alpha), color="0.45", ls="--", lw=1.2)
    # aged branches in p/a0: (+) on [-r, r y_c], (-) on [-r y_c, r]
    pa = np.linspace(-r, r * yc, 800)
    fa = r**2 * force_plus(pa / r, alpha)
    occ = (pa >= -1.0) & (pa <= 0.0)
    ax.plot(pa, np.where(occ, fa, np.nan), color="C0", lw=2.2,
            label=rf"aged, occupied ($r$ = {r:.4f})")
    ax.plot(pa, np.where(occ, np.nan, fa), color="C0", lw=1.2, ls=":", label="aged, empty")
    ax.plot(-pa, np.where(occ, -fa, np.nan), color="C3", lw=2.2)
    ax.plot(-pa, np.where(occ, np.nan, -fa), color="C3", lw=1.2, ls=":")
    ax.plot([r * yc], [r**2 * trap.f_c], "o", color="k", ms=4)
    ax.annotate(r"aged spinodal $r\,y_c$", (r * yc, r**2 * trap.f_c), textcoords="offset points",
                xytext=(-6, 6), ha="right", fontsize=8)
    ax.axvline(0.0, color="0.6", lw=0.6, zorder=0)
    _per_trap_axes(ax, rf"Fig. 2a — aged at rest, $t_w$ = {T:g} $t_0$, $\varepsilon$ = {eps:g}")
    return fig, ax


def population_at_shift(
    d: float, r: float, alpha: float = 0.13, d_w: float = 0.0, n: int = 400
) -> dict[str, tuple[Array, Array]]:
    """The three groups of :func:`dryfriction.static.pull_force` after a shift ``d``, on grids.

    Returns ``{"fresh": (p, f), "aged (+)": (p, f), "aged (-)": (p, f)}`` with ``p`` in ``a0`` and
    ``f`` the force per trap in ``Phi00/a0``: fresh traps on ``[-1, -1 + d]`` with ``f_+(p)``;
    aged (+) traps, born on ``[-1, d_w]``, now on ``[d - 1, d_w + d]`` with ``r^2 f_+(p/r)``
    (eq. 23); aged (-) traps, born on ``[d_w, 1]``, now on ``[d_w + d, 1 + d]``, alive while
    ``p/r <= 1``, with ``r^2 f_-(p/r)``. This is the same decomposition as ``pull_force``
    (a test checks that the areas add up to ``pull_force(d, r) H0``).
    """
    trap = Trap(alpha)
    yc = trap.y_c
    p_f = np.linspace(-1.0, -1.0 + d, n)
    f_f = force_plus(np.minimum(p_f, yc), alpha)
    p_p = np.linspace(d - 1.0, d_w + d, n)
    f_p = r**2 * force_plus(np.minimum(p_p / r, yc), alpha)
    lo, hi = d_w + d, min(1.0 + d, r)
    p_m = np.linspace(lo, hi, n) if hi > lo else np.empty(0)
    f_m = r**2 * force_minus(p_m / r, alpha)
    return {"fresh": (p_f, f_f), "aged (+)": (p_p, f_p), "aged (-)": (p_m, f_m)}


def fig2b_population_at_threshold(
    T: float = 25.0, eps: float = 0.04, alpha: float = 0.13, creep: str = "log",
    ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """Fig. 2b: the population just after the system of Fig. 2a is pulled to its threshold.

    The shift is ``d* = p_c(t_w)/a0 = r y_c`` (eq. 26): fresh traps entered on
    ``[-a0, -a0 + p_c]``, the aged (+) traps sit on ``[p_c - a0, p_c]`` with their edge at the
    aged spinodal, the aged (-) traps are out of contact (very strong pinning).
    """
    trap = Trap(alpha)
    fig, ax = _axes(ax)
    r = float(radius(T, eps, creep))
    d = float(threshold_shift(r, alpha))
    groups = population_at_shift(d, r, alpha)
    yp = np.linspace(-1.0, trap.y_c, 500)
    ax.plot(yp, force_plus(yp, alpha), color="0.45", ls="--", lw=1.2,
            label="elastic curve (reference)")
    styles = {"fresh": ("C1", "fresh traps (radius $a_0$)"),
              "aged (+)": ("C0", "aged (+) traps, $r^2 f_+(p/r)$"),
              "aged (-)": ("C3", "aged (−) traps, still in contact")}
    for key, (p, f) in groups.items():
        if p.size == 0:
            continue
        color, label = styles[key]
        ax.plot(p, f, color=color, lw=2.2, label=label)
        ax.fill_between(p, 0.0, f, color=color, alpha=0.15)
    mu = float(pull_force(d, r, alpha))
    ax.axvline(-1.0 + d, color="0.5", lw=0.8, ls=":")
    ax.axvline(d, color="0.5", lw=0.8, ls=":")
    top = ax.get_ylim()[1]
    ax.text(-1.0 + d, top, r" $-a_0+p_c$", fontsize=8, va="top")
    ax.text(d, top, r" $p_c(t_w)$", fontsize=8, va="top")
    _per_trap_axes(ax, rf"Fig. 2b — at the static threshold: $p_c$ = {d:.4f} $a_0$, "
                   rf"$\mu_s$ = {mu:.4f}")
    return fig, ax


# --------------------------------------------------------------------------------------------
# Figs. 3 and 5
# --------------------------------------------------------------------------------------------


def fig3_static_friction(
    alpha: float = 0.13, eps_values: Sequence[float] = EPS_FIGURES, T_range=(0.01, 100.0),
    n: int = 201, creep: str = "log", ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """Fig. 3: ``mu_s`` against ``T = t_w/t0`` (log scale) for ``eps`` = 0.01 ... 0.05 (1-5).

    Thin grey dotted lines: the first-order expansion (eq. 28).
    """
    fig, ax = _axes(ax)
    T = np.logspace(np.log10(T_range[0]), np.log10(T_range[1]), n)
    ys = []
    for k, e in enumerate(eps_values):
        mu = static_friction(T, e, alpha, creep)
        ys.append(mu)
        ax.plot(T, mu, color=_COLORS[k % 5], lw=1.8, label=rf"({k + 1}) $\varepsilon$ = {e:g}")
        ax.plot(T, static_friction_first_order(T, e, alpha), color="0.5", lw=0.8, ls=":",
                label="first order, eq. 28" if k == 0 else None)
    _label_curves(ax, T, ys, 30.0)
    ax.set_xscale("log")
    ax.set_xlim(T[0], T[-1])
    ax.set_xlabel(r"reduced waiting time $T = t_w/t_0$")
    ax.set_ylabel(r"static friction $\mu_s = F_s/F_{el}$")
    ax.set_title(rf"Fig. 3 — static friction, $\alpha$ = {alpha:g}", fontsize=10)
    ax.legend(fontsize=7.5, loc="upper left")
    ax.grid(True, which="major", color="0.9")
    return fig, ax


def fig5_steady_friction(
    alpha: float = 0.13, eps_values: Sequence[float] = EPS_FIGURES, u_range=(0.01, 100.0),
    n: int = 201, creep: str = "log", ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """Fig. 5: ``mu_d`` against ``u = V/V*`` (log scale) for ``eps`` = 0.01 ... 0.05 (1-5).

    Thin grey dotted lines: the low-velocity expansion (eq. 35 with its constant), ``u <= 1``.
    """
    fig, ax = _axes(ax)
    u = np.logspace(np.log10(u_range[0]), np.log10(u_range[1]), n)
    low = u <= 1.0
    ys = []
    for k, e in enumerate(eps_values):
        mu = steady_friction(u, e, alpha, creep)
        ys.append(mu)
        ax.plot(u, mu, color=_COLORS[k % 5], lw=1.8, label=rf"({k + 1}) $\varepsilon$ = {e:g}")
        ax.plot(u[low], steady_friction_low_velocity(u[low], e, alpha), color="0.5", lw=0.8,
                ls=":", label="low-velocity expansion, eq. 35" if k == 0 else None)
    _label_curves(ax, u, ys, 0.03)
    ax.set_xscale("log")
    ax.set_xlim(u[0], u[-1])
    ax.set_xlabel(r"reduced velocity $u = V/V^*$,  $V^* = a_0/t_0$")
    ax.set_ylabel(r"dynamic friction $\mu_d = F_d/F_{el}$")
    ax.set_title(rf"Fig. 5 — steady dynamic friction, $\alpha$ = {alpha:g}", fontsize=10)
    ax.legend(fontsize=7.5, loc="upper right")
    ax.grid(True, which="major", color="0.9")
    return fig, ax


# --------------------------------------------------------------------------------------------
# Fig. 4
# --------------------------------------------------------------------------------------------


def fig4_steady_pinning_curve(
    u: float = 0.1, eps: float = 0.04, alpha: float = 0.13, creep: str = "log",
    ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """Fig. 4: pinning curve in steady motion at ``u = 0.1`` (eq. 31) with the death point
    ``p_d`` (eq. 32); dashed, the elastic curve for comparison."""
    trap = Trap(alpha)
    fig, ax = _axes(ax)
    p_d = float(steady_death_point(u, eps, alpha, creep))
    y = np.linspace(-1.0, p_d, 1200)
    f = steady_profile(y, u, eps, alpha, creep)
    ye = np.linspace(-1.0, trap.y_c, 600)
    ax.plot(ye, force_plus(ye, alpha), color="0.45", ls="--", lw=1.2,
            label=r"elastic curve ($\varepsilon$ = 0)")
    ax.plot(y, f, color="C0", lw=2.2, label="dynamically aged, occupied (+) states")
    ax.fill_between(y, 0.0, f, color="C0", alpha=0.12)
    ax.plot([p_d], [f[-1]], "o", color="k", ms=5)
    ax.annotate("", xy=(p_d, 0.0), xytext=(p_d, f[-1]),
                arrowprops=dict(arrowstyle="-|>", color="0.15", lw=1.2))
    ax.annotate(rf"death point $p_d$ = {p_d:.4f} $a_0$", (p_d, f[-1]),
                textcoords="offset points", xytext=(-10, -4), ha="right", va="top", fontsize=9)
    ax.axvline(trap.y_c, color="0.5", lw=0.8, ls=":")
    ax.text(trap.y_c, 0.05, r"elastic $y_c$ ", fontsize=8, color="0.3", ha="right")
    mu = float(steady_friction(u, eps, alpha, creep))
    _per_trap_axes(ax, rf"Fig. 4 — steady motion, $u$ = {u:g}, $\varepsilon$ = {eps:g}: "
                   rf"$\mu_d$ = {mu:.4f}")
    return fig, ax


# --------------------------------------------------------------------------------------------
# Fig. 6
# --------------------------------------------------------------------------------------------


def fig6_dieterich(
    eps: float = 0.04, alpha: float = 0.13, C_values: Sequence[float] = (1.0, 2.0, 3.0, 4.0),
    C_paper: float = 2.45, u_range=(0.01, 100.0), n: int = 201, creep: str = "log",
    ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """Fig. 6: ``mu_d(u)`` (full line) against ``mu_s(T = C/u)`` for ``C`` = 1, 2, 3, 4, the
    paper's 2.45, and the model's asymptotic and least-squares constants (Dieterich, eq. 36)."""
    fig, ax = _axes(ax, figsize=(6.0, 4.4))
    u = np.logspace(np.log10(u_range[0]), np.log10(u_range[1]), n)
    ax.plot(u, steady_friction(u, eps, alpha, creep), color="k", lw=2.2,
            label=r"$\mu_d(u)$")
    dotted = [C for C in C_values if C != 1.0]
    for C in C_values:
        if C == 1.0:
            ls, label = "-.", r"$\mu_s(C/u)$, $C$ = 1"
        else:
            ls = ":"
            label = (r"$\mu_s(C/u)$, $C$ = " + ", ".join(f"{c:g}" for c in dotted)
                     if C == dotted[0] else None)
        line, = ax.plot(u, static_friction(C / u, eps, alpha, creep), color="0.35", lw=1.2,
                        ls=ls, label=label)
        ax.annotate(f"C={C:g}", (u[0], line.get_ydata()[0]), textcoords="offset points",
                    xytext=(3, 2), fontsize=7, color="0.3")
    ax.plot(u, static_friction(C_paper / u, eps, alpha, creep), color="0.35", lw=1.4,
            ls="--", label=rf"$C$ = {C_paper:g} (paper)")
    c_inf = dieterich_constant_asymptotic(alpha)
    c_ls = dieterich_constant_least_squares(eps, alpha, u_range[0], u_range[1], creep=creep)
    ax.plot(u, static_friction(c_inf / u, eps, alpha, creep), color="C3", lw=1.4,
            label=rf"$C_\infty$ = {c_inf:.4f} (ours, asymptotic)")
    ax.plot(u, static_friction(c_ls / u, eps, alpha, creep), color="C0", lw=1.4,
            label=rf"$C_{{LS}}$ = {c_ls:.4f} (ours, least squares)")
    ax.set_xscale("log")
    ax.set_xlim(u[0], u[-1])
    ax.set_xlabel(r"reduced velocity $u = V/V^*$  (static curves at $T = C/u$)")
    ax.set_ylabel(r"$\mu_d(u)$,  $\mu_s(T = C/u)$   [$F_{el}$]")
    ax.set_title(rf"Fig. 6 — Dieterich comparison, $\varepsilon$ = {eps:g}", fontsize=10)
    ax.legend(fontsize=7.5, loc="upper right")
    ax.grid(True, which="major", color="0.9")
    return fig, ax


# --------------------------------------------------------------------------------------------
# Extra panels (ours)
# --------------------------------------------------------------------------------------------


def extra_loaded_static(
    eps: float = 0.04, alpha: float = 0.13, loads: Sequence[float] = (0.0, 0.25, 0.5, 0.75),
    T_range=(0.01, 100.0), n: int = 201, ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """``mu_s(T)`` for ageing under a tangential load ``f_w`` (the protocol the paper describes
    but does not compute; ours) against ageing at rest (``f_w = 0``)."""
    fig, ax = _axes(ax)
    T = np.logspace(np.log10(T_range[0]), np.log10(T_range[1]), n)
    for k, f_w in enumerate(loads):
        ax.plot(T, static_friction(T, eps, alpha, load=f_w), color=_COLORS[k % 5], lw=1.8,
                label=rf"$f_w$ = {f_w:g} $F_{{el}}$" + (" (at rest, paper)" if f_w == 0 else ""))
    ax.set_xscale("log")
    ax.set_xlim(T[0], T[-1])
    ax.set_xlabel(r"reduced waiting time $T = t_w/t_0$")
    ax.set_ylabel(r"static friction $\mu_s = F_s/F_{el}$")
    ax.set_title(rf"Extra — ageing under a tangential load, $\varepsilon$ = {eps:g}",
                 fontsize=10)
    ax.legend(fontsize=7.5, loc="upper left")
    ax.grid(True, which="major", color="0.9")
    return fig, ax


def extra_creep_laws(
    alpha: float = 0.13, eps_values: Sequence[float] = (0.01, 0.03, 0.05),
    x_range=(0.01, 100.0), n: int = 201, ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """``mu_s(T)`` and ``mu_d(u)`` with the logarithmic creep law (eq. 17, full) and the exact
    Eyring-Nabarro law (eqs. 15-16, dashed)."""
    fig, ax = _axes(ax)
    x = np.logspace(np.log10(x_range[0]), np.log10(x_range[1]), n)
    for k, e in enumerate(eps_values):
        c = _COLORS[(2 * k) % 5]
        ax.plot(x, static_friction(x, e, alpha, "log"), color=c, lw=1.6,
                label=rf"$\mu_s(T)$, $\varepsilon$ = {e:g}")
        ax.plot(x, static_friction(x, e, alpha, "eyring-nabarro"), color=c, lw=1.4, ls="--")
        ax.plot(x, steady_friction(x, e, alpha, "log"), color=c, lw=1.6, alpha=0.55,
                label=rf"$\mu_d(u)$, $\varepsilon$ = {e:g}")
        ax.plot(x, steady_friction(x, e, alpha, "eyring-nabarro"), color=c, lw=1.4, ls="--",
                alpha=0.55)
    ax.plot([], [], color="k", lw=1.4, label="log law (eq. 17)")
    ax.plot([], [], color="k", lw=1.4, ls="--", label="Eyring–Nabarro (eqs. 15–16)")
    ax.set_xscale("log")
    ax.set_xlim(x[0], x[-1])
    ax.set_xlabel(r"$T = t_w/t_0$  (static)   or   $u = V/V^*$  (steady)")
    ax.set_ylabel(r"$\mu_s$, $\mu_d$   [$F_{el}$]")
    ax.set_title("Extra — logarithmic vs exact Eyring–Nabarro creep", fontsize=10)
    ax.legend(fontsize=7, loc="upper center", ncol=2)
    ax.grid(True, which="major", color="0.9")
    return fig, ax


def extra_local_dieterich_constant(
    eps_values: Sequence[float] = EPS_FIGURES, alpha: float = 0.13, u_range=(0.01, 100.0),
    n: int = 81, ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """``C(u)``: the Dieterich constant that makes ``mu_s(C/u) = mu_d(u)`` at each ``u``; it is
    not constant (no global fit), and tends to the asymptotic ``C_inf`` at high velocity."""
    fig, ax = _axes(ax)
    u = np.logspace(np.log10(u_range[0]), np.log10(u_range[1]), n)
    for k, e in enumerate(eps_values):
        ax.plot(u, dieterich_constant_local(u, e, alpha), color=_COLORS[k % 5], lw=1.6,
                label=rf"({k + 1}) $\varepsilon$ = {e:g}")
    c_inf = dieterich_constant_asymptotic(alpha)
    ax.axhline(c_inf, color="C3", lw=1.0, ls="--", label=rf"$C_\infty$ = {c_inf:.4f} (ours)")
    ax.axhline(2.45, color="0.4", lw=1.0, ls=":", label=r"2.45 $\approx 1 + y_c$ (paper)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.yaxis.set_major_formatter(ScalarFormatter())
    ax.yaxis.set_minor_formatter(ScalarFormatter())
    ax.set_xlim(u[0], u[-1])
    ax.set_xlabel(r"reduced velocity $u = V/V^*$")
    ax.set_ylabel(r"local Dieterich constant $C(u) = D_0/a_0$")
    ax.set_title("Extra — no single Dieterich length fits everywhere", fontsize=10)
    ax.legend(fontsize=7.5, loc="upper right")
    ax.grid(True, which="both", color="0.92")
    return fig, ax


def timeseries_figure(result: Any) -> tuple[Figure, Any]:
    """Friction against time and against slip, and the number of traps in contact.

    Parameters
    ----------
    result : dryfriction.driving.SimulationResult
        A run of the trap ensemble; times in ``t0``, slips in ``a0``, ``mu = mu_el F/F_el``.

    Returns
    -------
    fig, axes
        A new figure (Agg-renderable, not shown) and its three axes.
    """
    fig = Figure(figsize=(8.0, 7.5), layout="constrained")
    axes = fig.subplots(3, 1)
    t, x, mu = result.t, result.x, result.mu
    axes[0].plot(t, mu, lw=0.8)
    axes[0].set_xlabel("t / t0")
    axes[0].set_ylabel("mu")
    axes[1].plot(x - x[0], mu, lw=0.8)
    axes[1].set_xlabel("slip (X - X0) / a0")
    axes[1].set_ylabel("mu")
    axes[2].plot(t, result.n_active, lw=0.8)
    axes[2].set_xlabel("t / t0")
    axes[2].set_ylabel("traps in contact")
    fig.suptitle("partial result (interrupted)" if result.partial else "trap ensemble")
    return fig, axes


def rsf_timeseries_figure(result: Any) -> tuple[Figure, Any]:
    """Rate-and-state run: friction against time and slip, slip velocity against time.

    Parameters
    ----------
    result : dryfriction.rsf_driving.RSFResult
        A rate-and-state run (SI units: s, m, m/s).

    Returns
    -------
    fig, axes
        A new figure (Agg-renderable, not shown) and its three axes.
    """
    fig = Figure(figsize=(8.0, 7.5), layout="constrained")
    axes = fig.subplots(3, 1)
    t, x, mu = result.t, result.x, result.mu
    axes[0].plot(t, mu, lw=0.8, label="friction mu")
    if result.damping or result.mass:
        axes[0].plot(t, result.stress, lw=0.8, ls="--", label="spring force / normal force")
        axes[0].legend(fontsize=8)
    axes[0].set_xlabel("t (s)")
    axes[0].set_ylabel("mu")
    axes[1].plot(x - x[0], mu, lw=0.8)
    axes[1].set_xlabel("slip (m)")
    axes[1].set_ylabel("mu")
    v = np.abs(result.v)
    axes[2].semilogy(t, np.where(v > 0, v, np.nan), lw=0.8, label="slip velocity")
    vl = result.load_velocity
    axes[2].semilogy(t, np.where(vl > 0, vl, np.nan), lw=0.8, ls="--", label="load velocity")
    axes[2].set_xlabel("t (s)")
    axes[2].set_ylabel("V (m/s)")
    axes[2].legend(fontsize=8)
    fig.suptitle(f"rate-and-state, {result.params.state_law} law")
    return fig, axes


# ----------------------------------------------------------------------------- fit.png
MAX_POINTS_DRAWN: int = 5000
"""Most points :func:`plot_fit` draws per artist: beyond it the data are binned (drawing a
million points took most of a large fit's time and shows no more than their envelope)."""


def _bin_edges(n: int, n_bins: int) -> NDArray[np.intp]:
    """Edges of ``n_bins`` runs of consecutive samples out of ``n`` (empty runs dropped)."""
    return np.unique(np.linspace(0, n, n_bins + 1).astype(np.intp))


def _envelope(y: Array, n_bins: int) -> NDArray[np.intp]:
    """Indices of the smallest and largest ``y`` in each of ``n_bins`` runs of consecutive
    samples, in order: a decimated line that keeps every step and spike (plain striding would
    drop them)."""
    edges = _bin_edges(y.size, n_bins)
    bin_of = np.repeat(np.arange(edges.size - 1), np.diff(edges))
    by_bin = np.lexsort((y, bin_of))  # bins stay in place, sorted by y within each
    return np.unique(np.concatenate([by_bin[edges[:-1]], by_bin[edges[1:] - 1]]))


def _draw_data(ax: Axes, x: Array, y: Array, err: Array | None, n_bins: int | None,
               label: str | None) -> None:
    """Data as small light points under everything else; with ``n_bins`` (big data) their
    range in each run of consecutive samples as a band and the run means as points."""
    light = {"color": "0.55", "alpha": 0.6, "zorder": 1}
    if n_bins is None:
        ax.errorbar(x, y, yerr=err, fmt="o", ms=2.5, lw=0.6, label=label, **light)
        return
    edges = _bin_edges(y.size, n_bins)
    start, count = edges[:-1], np.diff(edges)
    xc = np.add.reduceat(x, start) / count
    per = f"{y.size / count.size:.3g} samples"
    ax.fill_between(xc, np.minimum.reduceat(y, start), np.maximum.reduceat(y, start), lw=0,
                    color="0.85", zorder=0, label=label and f"{label}: range per {per}")
    ax.plot(xc, np.add.reduceat(y, start) / count, "o", ms=1.5, mew=0,
            label=label and f"{label}: mean per {per}", **light)


def plot_fit(result: FitResult, datasets: Sequence[Dataset], path: Any = None,
             max_points: int = MAX_POINTS_DRAWN) -> tuple[Figure, Any]:
    """``fit.png``: each data set with the fitted curve (top) and the residuals (bottom).

    The data are small light points under the fitted line. A data set with more than
    ``max_points`` samples is drawn binned: sorted by abscissa (time for a series) and cut into
    about ``max_points/2`` runs of consecutive samples, each drawn as its range (a light band)
    and its mean (a point), for the data and the residuals, without error bars; the fitted line
    is evaluated on the data and drawn through the smallest and largest value of each run.

    Parameters
    ----------
    result : dryfriction.fit.FitResult
        The fit (its ``predict`` evaluates the fitted model).
    datasets : sequence of Dataset
        The data sets fitted, in order.
    path : path-like or file, optional
        Where to write the PNG; ``None``: not written.
    max_points : int
        Most points (vertices) drawn per artist (at least 8).

    Returns
    -------
    fig, axes
        A new figure (Agg-renderable, not shown) and its ``2 x len(datasets)`` axes.
    """
    from ..io.data import SeriesData

    if max_points < 8:
        raise ValueError(f"max_points = {max_points}: must be at least 8")
    k = len(datasets)
    fig = Figure(figsize=(4.6 * k, 5.6), layout="constrained")
    axes = fig.subplots(2, k, sharex="col", squeeze=False, height_ratios=[3, 1.3])
    for i, d in enumerate(datasets):
        top, bot = axes[0, i], axes[1, i]
        order = np.argsort(d.x, kind="stable")
        x, y, f = d.x[order], d.y[order], result.predict(d)[order]
        r = y - f
        thin = x.size > max_points
        # a million error bars show nothing but cost minutes
        err = None if d.sigma is None or thin else d.sigma[order]
        if isinstance(d, SeriesData):  # the fitted line evaluated on the data, decimated
            keep_f = _envelope(f, max_points // 2) if thin else slice(None)
            xs, fs = x[keep_f], f[keep_f]
        else:
            pos = d.x[d.x > 0]
            lo = pos.min() if pos.size else 1e-3
            xs = np.geomspace(lo / 1.5, d.x.max() * 1.5, 200)
            fs = result.predict(d, xs)
        n_bins = (max_points - 4) // 2 if thin else None  # a band has 2 n_bins + 3 vertices
        _draw_data(top, x, y, err, n_bins, "data")
        top.plot(xs, fs, "-", lw=1.4, color="C3", zorder=3, label=f"{result.model} fit")
        _draw_data(bot, x, r, err, n_bins, None)
        bot.axhline(0.0, color="k", lw=0.6, zorder=2)
        if not isinstance(d, SeriesData):
            top.set_xscale("log")
        top.set_ylabel(d.y_name)
        top.set_title(str(d.source).split("/")[-1], fontsize=9)
        top.legend(fontsize=8)
        bot.set_ylabel("residual")
        bot.set_xlabel(f"{d.x_name} ({d.x_unit})")
    status = "" if result.success else "  [NOT CONVERGED]"
    fig.suptitle(", ".join(f"{p.name} = {p.value:.4g}" for p in result.parameters) + status,
                 fontsize=8)
    if path is not None:
        save_png(fig, path)
    return fig, axes
