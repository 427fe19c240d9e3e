"""The paper's six figures (and a few extra panels), drawn from the library's functions.

Every function has the form ``fig_name(..., ax=None) -> (fig, ax)``: with ``ax=None`` it makes a
new :class:`matplotlib.figure.Figure` in the style of :mod:`.style` (no pyplot, no global state,
no display; PNGs are rendered by Agg); otherwise it draws into ``ax``. Figures of runs are in
:mod:`.runs`. Nothing here computes physics beyond evaluating the
library's functions on grids: forces come from :mod:`dryfriction.theory.trap`, friction from
:mod:`dryfriction.theory.static` and :mod:`dryfriction.theory.steady`, Dieterich constants from
:mod:`dryfriction.theory.dieterich`.

Units are the reduced ones of the core: lengths in ``a0``, times in ``t0``, velocities in
``V* = a0/t0``, friction in ``F_el`` (eq. 12), and every trap force, in every figure, in
``Phi00/a0`` (the force scale of a fresh trap of radius ``a0``; Fig. 1's trap is a fresh one, so
its ``Phi0/a`` is ``Phi00/a0``, and aged traps scale as ``a_r^2`` in it, eq. 23).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import ScalarFormatter

from ..theory.creep import radius
from ..theory.dieterich import (
    dieterich_constant_asymptotic,
    dieterich_constant_least_squares,
    dieterich_constant_local_over_eps,
)
from ..theory.model import TrapModel
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
from ..validation import Array
from .style import LEGEND_SIZE, PANEL, TITLE_SIZE, new_figure, save_png

if TYPE_CHECKING:
    pass

__all__ = [
    "EPS_FIGURES",
    "population_at_shift",
    "fig1_trap_hysteresis",
    "fig1b_population_at_rest",
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
]


EPS_FIGURES: tuple[float, ...] = (0.01, 0.02, 0.03, 0.04, 0.05)
"""The creep parameters of Figs. 3 and 5, labelled 1-5 in the paper."""

_COLORS = ("#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e")


def _axes(ax: Axes | None, figsize: tuple[float, float] = PANEL) -> tuple[Figure, Axes]:
    if ax is not None:
        return ax.figure, ax  # type: ignore[return-value]
    return new_figure(figsize)


def _label_curves(ax: Axes, x: Array, ys: Sequence[Array], where: float) -> None:
    """Write the paper's curve numbers 1-5 next to each curve at abscissa ``where``."""
    i = int(np.argmin(np.abs(np.log(x) - np.log(where))))
    for k, y in enumerate(ys):
        # above the curve on the side it falls away from: centred above it, a steep curve
        # ran through its own number
        rising = y[min(i + 1, len(y) - 1)] >= y[max(i - 1, 0)]
        ax.annotate(
            str(k + 1), (x[i], y[i]), textcoords="offset points",
            xytext=(-2, 3) if rising else (2, 3), ha="right" if rising else "left",
            va="bottom", fontsize=9, color=_COLORS[k % len(_COLORS)], fontweight="bold",
        )


# --------------------------------------------------------------------------------------------
# Fig. 1
# --------------------------------------------------------------------------------------------


def fig1_trap_hysteresis(alpha: float = 0.13, ax: Axes | None = None) -> tuple[Figure, Axes]:
    """Fig. 1a: pinning force ``f(y)`` of one fresh elastic trap (radius ``a0``, so ``y = p/a0``
    and the force is in ``Phi00/a0``), ``alpha = 0.13``.

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
    # the spinodals' value in the legend and only their letters beside them, outside the
    # branches: "C (y_c = ...)" written inside the loop was crossed by the (+) branch
    ax.plot([yc, -yc], [f_c, -f_c], "o", color="k", ms=5,
            label=rf"spinodals C, C′ at $\pm y_c$ = ±{yc:.4f}")
    ax.annotate("C", (yc, f_c), textcoords="offset points", xytext=(6, 0), ha="left",
                va="center", fontsize=9)
    ax.annotate("C′", (-yc, -f_c), textcoords="offset points", xytext=(-6, 0), ha="right",
                va="center", fontsize=9)
    # Maxwell plateau and its force jump
    f0p, f0m = float(force_plus(0.0, alpha)), float(force_minus(0.0, alpha))
    ax.plot([0, 0], [f0m, f0p], color="C2", lw=2.5, solid_capstyle="butt",
            label=rf"Maxwell plateau $y_M=0$, $\Delta f$ = {trap.maxwell_jump:.4f}")
    ax.axhline(0.0, color="0.6", lw=0.6, zorder=0)
    # room above the curves for the legend in two columns (in one, upper left, the (+)
    # branch and the Maxwell plateau ran through it)
    ax.set_ylim(-1.15 * f_c, 2.0 * f_c)
    ax.set_xlim(-span, span)
    ax.set_xlabel(r"configuration coordinate $p/a_0$")
    ax.set_ylabel(r"pinning force $f$  [$\Phi_{00}/a_0$]")
    ax.set_title(rf"Fig. 1a — elastic trap, $\alpha$ = {alpha:g} ({trap.regime.value})",
                 fontsize=TITLE_SIZE)
    ax.legend(fontsize=LEGEND_SIZE, loc="upper center", ncol=2)
    return fig, ax


def fig1b_population_at_rest(alpha: float = 0.13, ax: Axes | None = None
                             ) -> tuple[Figure, Axes]:
    """Fig. 1b: the asperity distribution at rest, just after contact under zero tangential
    load (docs/model.md §3, eq. 25).

    Pairs are spread uniformly in ``p`` with density ``1/(2 a0)``; those with ``-a0 < p < 0``
    sit on the (+) branch, those with ``0 < p < a0`` on the (−) branch (the edge of the
    distribution on the Maxwell plateau ``y_M = 0``). Their forces cancel: the net tangential
    force is zero. All have age zero.
    """
    trap = Trap(alpha)
    if not trap.pinned:
        raise ValueError(f"alpha = {alpha:g} is out of range: Fig. 1b needs 0 < alpha < 1")
    fig, ax = _axes(ax)
    yc = trap.y_c
    yp = np.linspace(-1.0, yc, 500)
    ax.plot(yp, force_plus(yp, alpha), color="0.55", ls="--", lw=1.0,
            label="branches of Fig. 1a (empty states)")
    ax.plot(-yp, force_minus(-yp, alpha), color="0.55", ls="--", lw=1.0)
    p_plus = np.linspace(-1.0, 0.0, 400)
    f_plus = force_plus(p_plus, alpha)
    ax.plot(p_plus, f_plus, color="C0", lw=2.2, label=r"occupied (+), $-a_0 < p < 0$")
    ax.fill_between(p_plus, 0.0, f_plus, color="C0", alpha=0.15)
    ax.plot(-p_plus, -f_plus, color="C3", lw=2.2, label=r"occupied (−), $0 < p < a_0$")
    ax.fill_between(-p_plus, 0.0, -f_plus, color="C3", alpha=0.15)
    # the density of pairs, uniform on [-a0, a0]: a band along the axis
    ax.plot([-1.0, 1.0], [0.0, 0.0], color="k", lw=4.0, solid_capstyle="butt",
            label=r"pairs in contact, density $1/(2a_0)$")
    ax.axvline(0.0, color="C2", lw=1.0, ls=":")
    # lower right, below the occupied (-) branch: lower left, the empty (-) branch crossed it
    ax.text(0.97, 0.04, "Maxwell plateau $y_M = 0$:\nforces cancel, net force 0",
            transform=ax.transAxes, fontsize=8, color="0.25", ha="right")
    _per_trap_axes(ax, rf"Fig. 1b — asperities at rest after contact, $\alpha$ = {alpha:g}")
    ax.set_xlim(-(max(yc, 1.0) + 0.6), max(yc, 1.0) + 0.6)
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
    ax.set_title(title, fontsize=TITLE_SIZE)
    ax.legend(fontsize=LEGEND_SIZE, loc="upper left")


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
    """The three groups of :func:`dryfriction.theory.static.pull_force` after a shift ``d``, on
    grids.

    Returns ``{"fresh": (p, f), "aged (+)": (p, f), "aged (-)": (p, f)}`` with ``p`` in ``a0`` and
    ``f`` the force per trap in ``Phi00/a0``: fresh traps on ``[-1, -1 + d]`` with ``f_+(p)``;
    aged (+) traps, born on ``[-1, d_w]``, now on ``[d - 1, d_w + d]`` with ``r^2 f_+(p/r)``
    (eq. 23); aged (-) traps, born on ``[d_w, 1]``, now on ``[d_w + d, 1 + d]``, alive while
    ``p/r <= 1``, with ``r^2 f_-(p/r)``. This is the same decomposition as ``pull_force``
    (a test checks that the areas add up to ``pull_force(model, d, r) H0``).
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
    d = float(threshold_shift(TrapModel(alpha), r))
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
    mu = float(pull_force(TrapModel(alpha), d, r))
    ax.axvline(-1.0 + d, color="0.5", lw=0.8, ls=":")
    ax.axvline(d, color="0.5", lw=0.8, ls=":")
    # at the foot of the lines, below the zero line where nothing is drawn, each on the side
    # of its line that stays in the panel (right of p_c, the label was cut by the edge)
    foot = ax.get_xaxis_transform()
    ax.text(-1.0 + d, 0.02, r" $-a_0+p_c$", fontsize=8, va="bottom", ha="left",
            transform=foot)
    ax.text(d, 0.02, r"$p_c(t_w)$ ", fontsize=8, va="bottom", ha="right", transform=foot)
    _per_trap_axes(ax, rf"Fig. 2b — at the static threshold: $p_c$ = {d:.4f} $a_0$, "
                   rf"$\mu_s$ = {mu:.4f}")
    return fig, ax


# --------------------------------------------------------------------------------------------
# Figs. 3 and 5
# --------------------------------------------------------------------------------------------



def _finish_log_panel(ax: Any, x: Any, xlabel: str, ylabel: str, title: str, *,
                      loc: str = "upper right", legend_size: float = LEGEND_SIZE,
                      ncol: int = 1) -> None:
    """The common finish of a panel over a logarithmic axis spanning ``x``: limits, labels,
    title, legend and a light major grid."""
    ax.set_xscale("log")
    ax.set_xlim(x[0], x[-1])
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=TITLE_SIZE)
    ax.legend(fontsize=legend_size, loc=loc, ncol=ncol)
    ax.grid(True, which="major", color="0.9")


def fig3_static_friction(
    alpha: float = 0.13, eps_values: Sequence[float] = EPS_FIGURES, T_range=(0.01, 100.0),
    n: int = 201, creep: str = "log", ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """Fig. 3: ``mu_s`` against ``T = t_w/t0`` (log scale) for ``eps`` = 0.01 ... 0.05 (1-5).

    Black dashes on top of each curve: the first-order expansion (eq. 28). It lies within
    ``6e-4`` of the full curves over the figure's range, so it is drawn over them, where it
    can be seen, and the legend says how close it is.
    """
    fig, ax = _axes(ax)
    T = np.logspace(np.log10(T_range[0]), np.log10(T_range[1]), n)
    ys = []
    gap = 0.0
    for k, e in enumerate(eps_values):
        model = TrapModel(alpha, e, creep)
        mu = static_friction(model, T)
        ys.append(mu)
        ax.plot(T, mu, color=_COLORS[k % 5], lw=1.8, label=rf"({k + 1}) $\varepsilon$ = {e:g}")
        first = static_friction_first_order(model, T)
        gap = max(gap, float(np.max(np.abs(first - mu))))
        ax.plot(T, first, color="k", lw=0.8, ls=(0, (2.5, 2.5)), zorder=3)
    ax.plot([], [], color="k", lw=0.8, ls=(0, (2.5, 2.5)),
            label=f"first order, eq. 28 (within {gap:.1g})")
    _label_curves(ax, T, ys, 30.0)
    _finish_log_panel(
        ax, T,
        r"reduced waiting time $T = t_w/t_0$",
        r"static friction $\mu_s = F_s/F_{el}$",
        rf"Fig. 3 — static friction, $\alpha$ = {alpha:g}",
        loc="upper left")
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
        model = TrapModel(alpha, e, creep)
        mu = steady_friction(model, u)
        ys.append(mu)
        ax.plot(u, mu, color=_COLORS[k % 5], lw=1.8, label=rf"({k + 1}) $\varepsilon$ = {e:g}")
        ax.plot(u[low], steady_friction_low_velocity(model, u[low]), color="0.5", lw=0.8,
                ls=":", label="low-velocity expansion, eq. 35" if k == 0 else None)
    _label_curves(ax, u, ys, 0.03)
    _finish_log_panel(
        ax, u,
        r"reduced velocity $u = V/V^*$,  $V^* = a_0/t_0$",
        r"dynamic friction $\mu_d = F_d/F_{el}$",
        rf"Fig. 5 — steady dynamic friction, $\alpha$ = {alpha:g}")
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
    model = TrapModel(alpha, eps, creep)
    p_d = float(steady_death_point(model, u))
    y = np.linspace(-1.0, p_d, 1200)
    f = steady_profile(model, y, u)
    ye = np.linspace(-1.0, trap.y_c, 600)
    ax.plot(ye, force_plus(ye, alpha), color="0.45", ls="--", lw=1.2,
            label=r"elastic curve ($\varepsilon$ = 0)")
    ax.plot(y, f, color="C0", lw=2.2, label="dynamically aged, occupied (+) states")
    ax.fill_between(y, 0.0, f, color="C0", alpha=0.12)
    ax.plot([p_d], [f[-1]], "o", color="k", ms=5)
    ax.annotate("", xy=(p_d, 0.0), xytext=(p_d, f[-1]),
                arrowprops=dict(arrowstyle="-|>", color="0.15", lw=1.2))
    # under the curves, left of the elastic spinodal's line, level with the arrow's middle
    # (beside the point, the text ran over the curve and that line)
    ax.annotate(rf"death point $p_d$ = {p_d:.4f} $a_0$ →", (trap.y_c, 0.35 * f[-1]),
                textcoords="offset points", xytext=(-4, 0), ha="right", va="center",
                fontsize=9)
    ax.axvline(trap.y_c, color="0.5", lw=0.8, ls=":")
    ax.text(trap.y_c, 0.05, r"elastic $y_c$ ", fontsize=8, color="0.3", ha="right")
    mu = float(steady_friction(TrapModel(alpha, eps, creep), u))
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
    model = TrapModel(alpha, eps, creep)
    ax.plot(u, steady_friction(model, u), color="k", lw=2.2,
            label=r"$\mu_d(u)$")
    # one legend entry per C, each its own colour and its own dashes: labels written on the
    # curves were struck through by the neighbouring ones, which lie a few points apart, and
    # dotted lines (as before) carry too little ink for their colours to be told apart
    shades = ("#b35806", "#7b3294", "#1b7837", "#c51b7d")
    dashes = ((0, (7.0, 2.0)), (0, (3.0, 1.5)), (0, (7.0, 2.0, 2.0, 2.0)),
              (0, (2.0, 1.2, 2.0, 1.2, 7.0, 1.2)))
    for k, C in enumerate(C_values):
        ax.plot(u, static_friction(model, C / u), color=shades[k % len(shades)],
                lw=1.5, ls=dashes[k % len(dashes)], label=rf"$\mu_s(C/u)$, $C$ = {C:g}")
    ax.plot(u, static_friction(model, C_paper / u), color="0.35", lw=1.4,
            ls="--", label=rf"$C$ = {C_paper:g} (paper)")
    c_inf = dieterich_constant_asymptotic(model)
    c_ls = dieterich_constant_least_squares(model, u_range[0], u_range[1])
    ax.plot(u, static_friction(model, c_inf / u), color="C3", lw=1.4,
            label=rf"$C_\infty$ = {c_inf:.4f} (ours, asymptotic)")
    ax.plot(u, static_friction(model, c_ls / u), color="C0", lw=1.4,
            label=rf"$C_{{LS}}$ = {c_ls:.4f} (ours, least squares)")
    _finish_log_panel(
        ax, u,
        r"reduced velocity $u = V/V^*$  (static curves at $T = C/u$)",
        r"$\mu_d(u)$,  $\mu_s(T = C/u)$   [$F_{el}$]",
        rf"Fig. 6 — Dieterich comparison, $\varepsilon$ = {eps:g}")
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
    model = TrapModel(alpha, eps)
    for k, f_w in enumerate(loads):
        ax.plot(T, static_friction(model, T, load=f_w), color=_COLORS[k % 5], lw=1.8,
                label=rf"$f_w$ = {f_w:g} $F_{{el}}$" + (" (at rest, paper)" if f_w == 0 else ""))
    _finish_log_panel(
        ax, T,
        r"reduced waiting time $T = t_w/t_0$",
        r"static friction $\mu_s = F_s/F_{el}$",
        rf"Extra — ageing under a tangential load, $\varepsilon$ = {eps:g}",
        loc="upper left")
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
        log, en = TrapModel(alpha, e, "log"), TrapModel(alpha, e, "eyring-nabarro")
        ax.plot(x, static_friction(log, x), color=c, lw=1.6,
                label=rf"$\mu_s(T)$, $\varepsilon$ = {e:g}")
        ax.plot(x, static_friction(en, x), color=c, lw=1.4, ls="--")
        ax.plot(x, steady_friction(log, x), color=c, lw=1.6, alpha=0.55,
                label=rf"$\mu_d(u)$, $\varepsilon$ = {e:g}")
        ax.plot(x, steady_friction(en, x), color=c, lw=1.4, ls="--",
                alpha=0.55)
    ax.plot([], [], color="k", lw=1.4, label="log law (eq. 17)")
    ax.plot([], [], color="k", lw=1.4, ls="--", label="Eyring–Nabarro (eqs. 15–16)")
    _finish_log_panel(
        ax, x,
        r"$T = t_w/t_0$  (static)   or   $u = V/V^*$  (steady)",
        r"$\mu_s$, $\mu_d$   [$F_{el}$]",
        "Extra — logarithmic vs exact Eyring–Nabarro creep",
        loc="upper center",
        legend_size=7,
        ncol=2)
    return fig, ax


def extra_local_dieterich_constant(
    eps_values: Sequence[float] = EPS_FIGURES, alpha: float = 0.13, u_range=(0.01, 100.0),
    n: int = 81, ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """``C(u)``: the Dieterich constant that makes ``mu_s(C/u) = mu_d(u)`` at each ``u``; it is
    not constant (no global fit), and tends to the asymptotic ``C_inf`` at high velocity."""
    fig, ax = _axes(ax)
    u = np.logspace(np.log10(u_range[0]), np.log10(u_range[1]), n)
    # every eps in one call: one root search for all the curves
    curves = dieterich_constant_local_over_eps(TrapModel(alpha), u,
                                               np.asarray(eps_values, float)[:, None])
    for k, (e, c) in enumerate(zip(eps_values, curves, strict=True)):
        ax.plot(u, c, color=_COLORS[k % 5], lw=1.6, label=rf"({k + 1}) $\varepsilon$ = {e:g}")
    c_inf = dieterich_constant_asymptotic(TrapModel(alpha))
    ax.axhline(c_inf, color="C3", lw=1.0, ls="--", label=rf"$C_\infty$ = {c_inf:.4f} (ours)")
    ax.axhline(2.45, color="0.4", lw=1.0, ls=":", label=r"2.45 $\approx 1 + y_c$ (paper)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.yaxis.set_major_formatter(ScalarFormatter())
    ax.yaxis.set_minor_formatter(ScalarFormatter())
    ax.set_xlim(u[0], u[-1])
    ax.set_xlabel(r"reduced velocity $u = V/V^*$")
    ax.set_ylabel(r"local Dieterich constant $C(u) = D_0/a_0$")
    ax.set_title("Extra — no single Dieterich length fits everywhere", fontsize=TITLE_SIZE)
    ax.legend(fontsize=LEGEND_SIZE, loc="upper right")
    ax.grid(True, which="both", color="0.92")
    return fig, ax
