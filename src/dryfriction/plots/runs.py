"""Figures of runs: time series of both simulators, the ``rsf`` command's figure, the ``compare``
figure and the stick-slip phase diagram.

Every function takes a result (or arrays) and returns ``(fig, axes)``: a new
:class:`matplotlib.figure.Figure` in the style of :mod:`.style` (no pyplot, nothing shown);
save it with :func:`.style.save_png`. The trap model is drawn in reduced units (``t0``, ``a0``,
``F_el``), rate-and-state in SI (s, m, m/s), and every axis label says which.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from .style import (
    FRICTION_SI,
    LEGEND_SIZE,
    LINE,
    PANEL,
    ROW_HEIGHT,
    RUN_WIDTH,
    SLIP_A0,
    SLIP_M,
    STIFFNESS_K,
    THIN,
    TIME_S,
    TIME_T0,
    TITLE_SIZE,
    VELOCITY_SI,
    VELOCITY_U,
    new_figure,
)

__all__ = [
    "timeseries_figure",
    "rsf_timeseries_figure",
    "rsf_figure",
    "comparison_figure",
    "phase_diagram_figure",
]


def _stack(n: int, title: str, sharex: bool = False) -> tuple[Figure, Any]:
    fig, axes = new_figure((RUN_WIDTH, 1.0 + n * ROW_HEIGHT), n, 1, sharex=sharex,
                           suptitle=True)
    fig.suptitle(title, fontsize=TITLE_SIZE)
    return fig, axes


def _positive(y: Any) -> Any:
    """``y`` with zeros and negatives as NaN, for a log axis (holds have zero velocity)."""
    y = np.asarray(y, float)
    return np.where(y > 0, y, np.nan)


def _holds(t: Any, x: Any) -> list[tuple[float, float]]:
    """The time intervals over which the slider does not move (holds), merged."""
    still = (np.diff(x) == 0) & (np.diff(t) > 0)
    out: list[tuple[float, float]] = []
    for i in np.flatnonzero(still):
        if out and out[-1][1] == t[i]:
            out[-1] = (out[-1][0], float(t[i + 1]))
        else:
            out.append((float(t[i]), float(t[i + 1])))
    return out


def _unsampled(t: Any, x: Any, y: Any) -> Any:
    """Indices ``i`` of the steps ``i -> i+1`` that a straight line would misdraw: no slip, far
    longer than the sliding steps and a change of ``y`` in between (a hold sampled once, whose
    friction relaxed along a path nobody recorded). A constant ``y`` is drawn: that line is
    exact."""
    dt, dx = np.diff(t), np.diff(x)
    moving = dt[(dx != 0) & (dt > 0)]
    if not moving.size:
        return np.array([], int)
    return np.flatnonzero((dx == 0) & (dt > 3.0 * np.median(moving)) & (np.diff(y) != 0))


def _broken(u: Any, y: Any, breaks: Any) -> tuple[Any, Any]:
    """``u, y`` with a NaN after each step in ``breaks``: the line stops there."""
    u, y = np.asarray(u, float), np.asarray(y, float)
    return np.insert(u, breaks + 1, np.nan), np.insert(y, breaks + 1, np.nan)


HOLD_BAND = 0.08
"""A long hold is drawn this fraction of the sliding time wide (less when there are many)."""


class _HoldClock:
    """Real time -> position on a time axis that draws long holds as bands of one width.

    Used when the holds outlast the sliding (a slide-hold-slide with a hold of 1000 ``t0``
    against seconds of sliding would squeeze the sliding into slivers): every hold longer
    than the band width ``w = min(HOLD_BAND, 0.3 / n_holds) * sliding time`` is drawn ``w``
    wide, the time inside it compressed linearly; everything else keeps its true length.
    The data stay in real time (the map is the axis's scale), so the ticks are real times.
    """

    def __init__(self, t: Any, holds: list[tuple[float, float]]) -> None:
        t = np.asarray(t, float)
        span = float(t[-1] - t[0]) if t.size else 0.0
        held = sum(b - a for a, b in holds)
        self.bands: list[tuple[float, float]] = []  # the compressed holds (real time)
        kt, ks = [float(t[0]) if t.size else 0.0], [float(t[0]) if t.size else 0.0]
        if holds and 0.0 < span - held < held:
            w = min(HOLD_BAND, 0.3 / len(holds)) * (span - held)
            for a, b in holds:
                if b - a > w:
                    ks += [ks[-1] + a - kt[-1], ks[-1] + a - kt[-1] + w]
                    kt += [a, b]
                    self.bands.append((a, b))
        self.kt, self.ks = np.array(kt), np.array(ks)

    def forward(self, t: Any) -> Any:
        return self._map(t, self.kt, self.ks)

    def inverse(self, s: Any) -> Any:
        return self._map(s, self.ks, self.kt)

    @staticmethod
    def _map(x: Any, xk: Any, yk: Any) -> Any:
        x = np.asarray(x, float)
        y = np.interp(x, xk, yk)
        # beyond the knots the slope is 1 (sliding): the axis margins stay true
        return np.where(x > xk[-1], yk[-1] + x - xk[-1], np.where(x < xk[0], yk[0] + x - xk[0],
                                                                   y))

    def apply(self, ax: Any, t: Any) -> None:
        """Give ``ax`` this scale, real-time ticks on each stretch of sliding and the
        duration written in each compressed hold."""
        if not self.bands:
            return
        from matplotlib.ticker import FixedLocator, MaxNLocator

        ax.set_xscale("function", functions=(self.forward, self.inverse))
        edges = [float(t[0])] + [e for band in self.bands for e in band] + [float(t[-1])]
        s0, s1 = float(self.forward(edges[0])), float(self.forward(edges[-1]))
        total = s1 - s0
        cuts = [float(self.forward(e)) for band in self.bands for e in band]
        ticks: list[float] = []
        for a, b in zip(edges[::2], edges[1::2], strict=True):
            share = float(self.forward(b) - self.forward(a)) / total
            for v in MaxNLocator(nbins=max(1, round(7 * share))).tick_values(a, b):
                # on its stretch, and clear of the bands' edges: two labels either side of
                # a narrow band would run into each other
                pos = float(self.forward(v))
                if (a - 1e-9 * (b - a) <= v <= b + 1e-9 * (b - a)
                        and all(abs(pos - c) >= 0.04 * total for c in cuts)):
                    ticks.append(float(v))
        ax.xaxis.set_major_locator(FixedLocator(ticks))
        ax.xaxis.set_minor_locator(FixedLocator([]))
        ax.set_xlim(float(self.inverse(s0 - 0.03 * total)),
                    float(self.inverse(s1 + 0.03 * total)))
        for a, b in self.bands:
            ax.annotate(f"hold {b - a:g} $t_0$", (float(self.inverse(
                0.5 * (self.forward(a) + self.forward(b)))), 0.97), xycoords=("data",
                "axes fraction"), fontsize=LEGEND_SIZE, rotation=90, ha="center", va="top",
                color="0.35")


def _shade(ax: Any, holds: list[tuple[float, float]]) -> None:
    for i, (a, b) in enumerate(holds):
        ax.axvspan(a, b, color="0.88", lw=0, zorder=0, label="hold" if i == 0 else None)


def _friction_label(mu_el: float) -> str:
    if mu_el == 1.0:
        return r"friction $F/F_{el}$"
    return rf"friction $\mu = \mu_{{el}} F/F_{{el}}$  ($\mu_{{el}}$ = {mu_el:g})"


def _describe_drive(d: Mapping[str, Any], initial: Mapping[str, Any]) -> str:
    kind = d.get("kind", "")
    start = {"rest": "from rest", "steady": f"from steady sliding at u = "
             f"{initial.get('velocity')}", "loaded": f"from rest under {initial.get('force')} "
             "$F_{el}$"}.get(initial.get("kind", ""), "")
    if kind == "force":
        return (f"force control {start}: hold {d.get('hold', 0.0):g} $t_0$, then a ramp of "
                f"{d.get('rate', 0.0):g} " r"$F_{el}/t_0$")
    segs = d.get("segments", [])
    n_hold = sum(1 for s in segs if s.get("velocity") == 0)
    prog = f"{len(segs)} segment{'s' * (len(segs) != 1)}" + (
        f", {n_hold} hold{'s' * (n_hold != 1)}" if n_hold else "")
    if kind == "spring":
        return (rf"spring $K$ = {d.get('stiffness', 0.0):g} $F_{{el}}/a_0$, $M$ = "
                rf"{d.get('mass', 0.0):g}, $\eta$ = {d.get('damping', 0.0):g}; {prog} {start}")
    return f"velocity program: {prog} {start}"


def _trap_title(result: Any) -> str:
    info = getattr(result, "info", {}) or {}
    p = info.get("parameters", {})
    m, tr = p.get("model", {}), p.get("track", {})
    head = "trap model"
    if m:
        head += (rf": $\varepsilon$ = {m.get('eps', 0.0):g}, $\alpha$ = {m.get('alpha', 0.0):g}, "
                 f"{m.get('creep', 'log')} creep, {tr.get('traps_per_a0', 0.0):g} traps/$a_0$")
    if p.get("drive"):
        head += "\n" + _describe_drive(p["drive"], p.get("initial", {}))
    if result.partial:
        head = "partial result (interrupted) - " + head
    return head


def timeseries_figure(result: Any) -> tuple[Figure, Any]:
    """``timeseries.png`` of a trap-ensemble run: friction against time and against slip,
    slider velocity and slip against time; holds shaded, a static threshold marked.

    A hold sampled once (``every_slip``) is not drawn as a straight line across the time
    nobody sampled: the line stops and the hold is shaded. The title gives the model and the
    drive (``result.info["parameters"]``).

    Parameters
    ----------
    result : dryfriction.ensemble.driving.SimulationResult
        A run of the trap ensemble; times in ``t0``, slips in ``a0``, ``mu = mu_el F/F_el``.

    Returns
    -------
    fig, axes
        A new figure and its four axes: friction(t), friction(slip), velocity(t), slip(t).
    """
    info = getattr(result, "info", {}) or {}
    drive = info.get("parameters", {}).get("drive", {})
    mu_el = float(info.get("parameters", {}).get("model", {}).get("mu_el", 1.0))
    fig, grid = new_figure((RUN_WIDTH + 3.5, 1.0 + 2 * ROW_HEIGHT + 0.3), 2, 2, suptitle=True)
    fig.suptitle(_trap_title(result), fontsize=TITLE_SIZE)
    ax_ft, ax_fx, ax_v, ax_x = grid.ravel()
    t, x, mu = (np.asarray(a, float) for a in (result.t, result.x, result.mu))
    v = np.asarray(getattr(result, "v", np.zeros_like(t)), float)
    x_pull = np.asarray(getattr(result, "x_pull", np.full_like(t, np.nan)), float)
    slip = x - x[0]
    time_label = TIME_T0
    t0_ramp = float(drive.get("hold", 0.0)) if drive.get("kind") == "force" else 0.0
    if t0_ramp > 0:
        # a force ramp lasts a tiny fraction of the wait before it: draw the ramp on its own
        # clock (the wait, at a constant force and no slip, is in the title)
        keep = t >= t0_ramp - 1e-12 * t0_ramp
        t, x, mu, v, x_pull, slip = (a[keep] for a in (t, x, mu, v, x_pull, slip))
        t = t - t0_ramp
        time_label = r"time since the ramp began $t - t_w$  [$t_0$]"
    holds = _holds(t, x) if t0_ramp == 0 else []
    cut = _unsampled(t, x, mu)
    clock = _HoldClock(t, holds)
    if clock.bands:
        time_label = time_label.replace("[", "(long holds compressed)  [", 1)
    for ax in (ax_ft, ax_v, ax_x):
        _shade(ax, holds)
    ax_ft.plot(*_broken(t, mu, cut), lw=THIN)
    if cut.size:  # the two ends of each unsampled hold, which the line no longer joins
        ends = np.unique(np.concatenate([cut, cut + 1]))
        ax_ft.plot(t[ends], mu[ends], ".", ms=3, color="C0")
    ax_ft.set_xlabel(time_label)
    ax_ft.set_ylabel(_friction_label(mu_el))
    ax_fx.plot(*_broken(slip, mu, cut), lw=THIN)
    for a, b in holds:  # a hold has no slip: say where it was and how long
        i = int(np.searchsorted(t, a))
        ax_fx.axvline(slip[i], color="0.6", lw=0.6, ls=":", zorder=0)
        ax_fx.annotate(f"hold {b - a:g} $t_0$", (slip[i], 0.02), xycoords=("data", "axes "
                       "fraction"), fontsize=LEGEND_SIZE, rotation=90, ha="right", va="bottom",
                       color="0.35")
    ax_fx.set_xlabel(SLIP_A0)
    ax_fx.set_ylabel(_friction_label(mu_el))
    # a sample's velocity is that of the step ending at it: draw it as steps
    tv, vv = _broken(t, v, _unsampled(t, x, v))
    pos = _positive(np.abs(vv))
    finite = pos[np.isfinite(pos)]
    if finite.size and finite.max() > 30.0 * finite.min():
        ax_v.semilogy(tv, pos, lw=THIN, drawstyle="steps-pre")
    else:
        ax_v.plot(tv, vv, lw=THIN, drawstyle="steps-pre")
        if (v >= 0).all():  # from zero: a constant velocity is no jitter around an offset
            ax_v.set_ylim(0.0, 1.1 * max(float(np.nanmax(v)), 1e-300))
    ax_v.set_xlabel(time_label)
    ax_v.set_ylabel(r"slider velocity $|v|$  [$a_0/t_0$]" if (v < 0).any()
                    else r"slider velocity $v$  [$a_0/t_0$]")
    pulled = np.isfinite(x_pull).any()
    ax_x.plot(t, slip, lw=LINE, label="slider" if pulled else None)
    if pulled:
        ax_x.plot(t, x_pull - x_pull[np.isfinite(x_pull)][0], lw=THIN, ls="--",
                  label="load point")
    ax_x.set_xlabel(time_label)
    ax_x.set_ylabel(SLIP_A0)
    thr = info.get("threshold_mu")
    if thr is not None and np.isfinite(thr):
        t_thr = float(info.get("threshold_t", result.t[np.nanargmax(result.mu)])) - t0_ramp
        x_thr = float(np.interp(t_thr, t, slip))
        text = f"static threshold {thr:.4g}" + (f"\nafter a wait of {t0_ramp:g} $t_0$"
                                                if t0_ramp else "")
        for ax, at in ((ax_ft, t_thr), (ax_fx, x_thr)):
            ax.plot([at], [thr], "*", ms=9, color="C3", zorder=4)
            ax.annotate(text, (at, thr), xytext=(0.05, 0.8), textcoords="axes fraction",
                        fontsize=LEGEND_SIZE, arrowprops={"arrowstyle": "->", "lw": 0.6})
    for ax in (ax_ft, ax_x):
        if ax.get_legend_handles_labels()[1]:
            ax.legend(fontsize=LEGEND_SIZE, loc="lower right")
    for ax in (ax_ft, ax_v, ax_x):
        clock.apply(ax, t)
    return fig, grid.ravel()


def _friction_against_velocity(ax: Any, result: Any) -> None:
    """Friction against the slip velocity on a log axis (the plot rate-and-state users read),
    with the law's steady state ``mu_ss(V)`` for reference: a velocity step is a loop around
    it, a slide-hold-slide a detour to low velocity and back over the peak."""
    v = _positive(np.abs(np.asarray(result.v, float)))
    ax.semilogx(v, result.mu, lw=LINE, label="run")
    ok = v[np.isfinite(v)]
    if ok.size:
        grid = np.geomspace(ok.min(), ok.max(), 200) if ok.max() > ok.min() else ok[:1]
        try:
            ss = result.params.steady_state_friction(grid)
        except (AttributeError, ValueError):  # a stand-in without the law, or no steady state
            ss = None
        if ss is not None:
            ax.semilogx(grid, ss, lw=THIN, ls="--", color="0.35",
                        label=r"steady state $\mu_{ss}(V)$")
        ax.plot(ok[:1], np.asarray(result.mu, float)[np.isfinite(v)][:1], "o", ms=4,
                color="C0")  # where the run starts
    ax.set_xlabel(r"slip velocity $V$  [m/s]  (log scale: $\ln V$)")
    ax.set_ylabel(FRICTION_SI)
    ax.legend(fontsize=LEGEND_SIZE)


def _rsf_title(result: Any, head: str = "") -> str:
    """``head`` (default: the law) with the law's parameters, then ``mu0`` and the machine on
    a second line (SI units)."""
    p = result.params
    head = head or f"rate-and-state, {p.state_law} law"
    second = []
    if hasattr(p, "a"):
        head += f": a = {p.a:g}, b = {p.b:g}, " r"$D_c$" f" = {p.dc:g} m"
        second.append(r"$\mu_0$" f" = {p.mu0:g} at " r"$V_0$" f" = {p.v0:g} m/s")
    k = getattr(result, "stiffness", None)
    if k is not None:
        second.append("kinematic machine" if not np.isfinite(k) else f"spring k = {k:g} 1/m")
        second += [f"{n} = {v:g} {u}" for n, v, u in (("damping", result.damping, "s/m"),
                                                      ("mass", result.mass, "s²/m")) if v]
    return head + ("\n" + ", ".join(second) if second else "")


def rsf_timeseries_figure(result: Any) -> tuple[Figure, Any]:
    """Rate-and-state run (``simulate`` with ``law = "rsf"``): friction against time and slip,
    slip and load velocity against time, friction against ``ln V``.

    Parameters
    ----------
    result : dryfriction.rsf.driving.RSFResult
        A rate-and-state run (SI units: s, m, m/s).

    Returns
    -------
    fig, axes
        A new figure and its four axes.
    """
    fig, axes = _stack(4, _rsf_title(result))
    t, x, mu = result.t, result.x, result.mu
    axes[0].plot(t, mu, lw=THIN, label="friction")
    if result.damping or result.mass:
        # with inertia or damping the spring no longer reads the friction
        axes[0].plot(t, result.stress, lw=THIN, ls="--", label="spring force / normal force")
        axes[0].legend(fontsize=LEGEND_SIZE)
    axes[0].set_xlabel(TIME_S)
    axes[0].set_ylabel(FRICTION_SI)
    axes[1].plot(x - x[0], mu, lw=THIN)
    axes[1].set_xlabel(SLIP_M)
    axes[1].set_ylabel(FRICTION_SI)
    axes[2].semilogy(t, _positive(np.abs(result.v)), lw=THIN, label="slip velocity")
    axes[2].semilogy(t, _positive(result.load_velocity), lw=THIN, ls="--",
                     label="load velocity")
    axes[2].set_xlabel(TIME_S)
    axes[2].set_ylabel(VELOCITY_SI)
    axes[2].legend(fontsize=LEGEND_SIZE)
    _friction_against_velocity(axes[3], result)
    return fig, axes


def rsf_figure(result: Any, title: str) -> tuple[Figure, Any]:
    """``rsf.png`` of the ``rsf`` command: friction and spring force, slip and load velocity,
    against time, and friction against ``ln V`` with the steady state (SI units).

    Parameters
    ----------
    result : dryfriction.rsf.driving.RSFResult
        The run.
    title : str
        The case and state law, e.g. ``"step, ageing law"``.

    Returns
    -------
    fig, axes
        A new figure and its three axes (the first two share time).
    """
    fig, (ax1, ax2, ax3) = _stack(3, _rsf_title(result, title))
    ax2.sharex(ax1)
    ax1.plot(result.t, result.mu, lw=LINE, label="friction")
    ax1.plot(result.t, result.stress, lw=THIN, ls="--", label="spring force / normal force")
    ax1.set_ylabel(FRICTION_SI)
    ax1.legend(fontsize=LEGEND_SIZE)
    ax2.semilogy(result.t, _positive(result.v), lw=LINE, label="slip velocity")
    ax2.semilogy(result.t, _positive(result.load_velocity), lw=THIN, ls="--",
                 label="load velocity")
    ax1.set_xlabel(TIME_S)
    ax2.set_xlabel(TIME_S)
    ax2.set_ylabel(VELOCITY_SI)
    ax2.legend(fontsize=LEGEND_SIZE)
    _friction_against_velocity(ax3, result)
    return fig, (ax1, ax2, ax3)


def comparison_figure(c: Any, title: str = "") -> tuple[Figure, Any]:
    """``compare.png``: friction of the trap model and of its rate-and-state twin against time
    and slip, and their difference (reduced units).

    Parameters
    ----------
    c : dryfriction.analysis.rsf_view.Comparison
        The two runs and the twin's parameters.
    title : str
        Usually the protocol's file name.

    Returns
    -------
    fig, axes
        A new figure and its three axes.
    """
    m = c.misfit
    tw = c.twin
    fig, ax = _stack(3, f"{title}: trap model and its rate-and-state twin\n"
                     f"({tw.state_law} law, {c.calibration} calibration: a = "
                     f"{c.mu_el * tw.a:.3g}, b = {c.mu_el * tw.b:.3g}, " r"$D_c$"
                     f" = {tw.dc:.3g} " r"$a_0$" f"; rms misfit {m['rms']:.3g})")
    t, x = np.asarray(c.t, float), np.asarray(c.x, float)
    slip = x - x[0]
    holds = _holds(t, x)
    cut = _unsampled(t, x, c.mu_trap)
    label = _friction_label(c.mu_el)
    _shade(ax[0], holds)
    ax[0].plot(*_broken(t, c.mu_trap, cut), lw=LINE, label="trap model")
    ax[0].plot(*_broken(t, c.mu_rsf, cut), lw=THIN, ls="--", label="RSF twin")
    ax[0].set_xlabel(TIME_T0)
    ax[0].set_ylabel(label)
    ax[0].legend(fontsize=LEGEND_SIZE)
    ax[1].plot(*_broken(slip, c.mu_trap, cut), lw=LINE, label="trap model")
    ax[1].plot(*_broken(slip, c.mu_rsf, cut), lw=THIN, ls="--", label="RSF twin")
    ax[1].set_xlabel(SLIP_A0)
    ax[1].set_ylabel(label)
    ax[2].plot(slip, c.mu_rsf - c.mu_trap, lw=THIN)
    ax[2].axhline(0.0, color="k", lw=0.6)
    ax[2].set_xlabel(SLIP_A0)
    unit = "F_{el}" if c.mu_el == 1.0 else r"\mu_{el} F/F_{el}"
    ax[2].set_ylabel(rf"$\mu_{{RSF}} - \mu_{{trap}}$  [${unit}$]")
    return fig, ax


# class code -> marker, colour
_MARKERS = {0: ("o", "tab:blue"), 1: ("s", "tab:red"), 2: ("^", "tab:purple"),
            3: ("D", "tab:orange"), 4: ("v", "tab:green"), -1: ("x", "0.4")}


def phase_diagram_figure(ds: Any, base: Mapping[str, Any], k_key: str, v_key: str
                         ) -> tuple[Figure, Any]:
    """``phase_diagram.png``: simulated stick-slip classes as markers in the (u, K) plane over
    the linear ``K_c(u)`` line (:func:`dryfriction.analysis.stickslip.critical_line`).

    Parameters
    ----------
    ds : xarray.Dataset
        The sweep, with the coordinates ``k_key`` and ``v_key`` and (unless every point failed)
        the variable ``class`` (codes of :data:`~dryfriction.analysis.stickslip.CLASSES`; NaN
        for a failed point).
    base : mapping
        The sweep's base protocol (its ``model`` and ``drive`` tables give ``K_c``).
    k_key, v_key : str
        The swept stiffness and velocity keys
        (:func:`dryfriction.analysis.stickslip.phase_axes`).

    Returns
    -------
    fig, ax
    """
    # here, not at the top: the stick-slip analysis imports the trap model's compiled kernel,
    # which a rate-and-state run's figure does not need
    from ..analysis.stickslip import CLASSES, critical_line

    K = np.asarray(ds[k_key].values, float)
    V = np.asarray(ds[v_key].values, float)
    code = ds["class"].transpose(k_key, v_key).values if "class" in ds else \
        np.full((K.size, V.size), np.nan)
    fig, ax = new_figure((PANEL[0] + 0.2, PANEL[1] + 0.2))
    vv, kk = np.meshgrid(V, K)
    for c, (mk, col) in _MARKERS.items():
        sel = code == c
        if sel.any():
            ax.scatter(vv[sel], kk[sel], marker=mk, color=col, label=CLASSES[c], zorder=3)
    failed = ~np.isfinite(code)
    if failed.any():
        ax.scatter(vv[failed], kk[failed], marker="+", color="k", label="failed", zorder=3)
    if V.size > 1 and V.min() > 0:
        u = np.geomspace(V.min(), V.max(), 40)
        ax.set_xscale("log")
    else:
        u = np.linspace(V.min(), V.max(), 40) if V.size > 1 else V
    ax.plot(u, critical_line(base, u), "k-", lw=LINE, label="linear $K_c(u)$")
    if K.min() > 0 and K.max() / K.min() > 5:
        ax.set_yscale("log")
    d = base.get("drive", {})
    ax.set_xlabel(VELOCITY_U)
    ax.set_ylabel(STIFFNESS_K)
    ax.set_title(rf"stick-slip phase diagram, $\varepsilon$ = {base['model']['eps']:g}, "
                 rf"$M$ = {float(d.get('mass', 0.0)):g}, $\eta$ = "
                 f"{float(d.get('damping', 0.0)):g}", fontsize=TITLE_SIZE)
    ax.legend(fontsize=LEGEND_SIZE)
    return fig, ax
