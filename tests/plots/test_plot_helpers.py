"""The numbers the figures compute before drawing (issue 25: a figure's secondary quantity
with no check): the record figure's windowed velocity (least-squares slope per window) against
the slopes put in and against np.polyfit; the fit figure's binning of big data (edges, the
min/max envelope, the band and the run means) against loops written here."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.figure import Figure

from dryfriction.plots.fits import _bin_edges, _draw_data, _envelope
from dryfriction.plots.record import smoothed_velocity


def test_smoothed_velocity_is_the_least_squares_slope_per_window() -> None:
    rng = np.random.default_rng(11)
    width = 2.5
    slopes = np.array([3.1e-6, -0.7e-6, 0.0, 12.4e-6, 5.5e-6])
    t = np.sort(rng.uniform(0.0, width * slopes.size, 400))
    t = np.sort(np.r_[0.0, t[(t < 7.5) | (t >= 10.0)], 8.1, 9.3])  # window 3: two samples
    knots = np.r_[0.0, np.cumsum(slopes * width)]  # x continuous, linear in each window
    k = np.minimum((t // width).astype(int), slopes.size - 1)
    x = 4.2e-3 + knots[k] + slopes[k] * (t - width * k)
    tc, v = smoothed_velocity(t, x, width)
    kept = [j for j in range(slopes.size) if np.sum(k == j) >= 3]
    assert 3 not in kept and len(kept) == 4
    np.testing.assert_allclose(v, slopes[kept], rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(tc, [t[k == j].mean() for j in kept], rtol=1e-12)
    # with noise, shifted by 101.3 s (not a whole number of windows: they start at the first
    # sample): np.polyfit's slope in each window
    y = x + 1e-7 * rng.standard_normal(t.size)
    tc2, v2 = smoothed_velocity(t + 101.3, y, width)
    want = [np.polyfit(t[k == j], y[k == j], 1)[0] for j in kept]
    np.testing.assert_allclose(v2, want, rtol=1e-7)
    np.testing.assert_allclose(tc2, np.asarray(tc) + 101.3, rtol=1e-12)


def test_binning_edges_envelope_band_and_means() -> None:
    np.testing.assert_array_equal(_bin_edges(10, 4), [0, 2, 5, 7, 10])
    rng = np.random.default_rng(5)
    n, bins = 103, 7
    y = rng.standard_normal(n)
    x = np.cumsum(rng.uniform(0.5, 1.5, n))
    edges = _bin_edges(n, bins)
    runs = [np.arange(a, b) for a, b in zip(edges[:-1], edges[1:], strict=True)]
    want = sorted({int(r[np.argmin(y[r])]) for r in runs} | {int(r[np.argmax(y[r])]) for r in runs})
    np.testing.assert_array_equal(_envelope(y, bins), want)
    ax = Figure().subplots()
    _draw_data(ax, x, y, None, bins, "data")
    band = ax.collections[0]
    (line,) = ax.lines
    np.testing.assert_allclose(line.get_xdata(), [x[r].mean() for r in runs], rtol=1e-14)
    np.testing.assert_allclose(line.get_ydata(), [y[r].mean() for r in runs], rtol=1e-12)
    verts = band.get_paths()[0].vertices
    lo = np.array([y[r].min() for r in runs])
    hi = np.array([y[r].max() for r in runs])
    for v in lo:
        assert np.any(np.isclose(verts[:, 1], v, rtol=0, atol=1e-14))
    assert verts[:, 1].max() == pytest.approx(hi.max()) and verts[:, 1].min() == pytest.approx(
        lo.min())
    assert set(np.round(verts[:, 1], 12)) <= set(np.round(np.r_[lo, hi], 12))
    assert line.get_label() == f"data: mean per {n / bins:.3g} samples"


def test_step_title_values_and_units() -> None:
    """The step figure's title: velocities in um/s, Dc in um, k per metre, 4 digits; the
    parameters not identified named on the second line (mistakes: Dc in mm, V in mm/s)."""
    from dryfriction.plots.steps import step_title

    row = {"index": 4, "kind": "step", "v_before": 3.3e-6, "v_after": 1.1e-5, "a": 0.0061237,
           "b": float("nan"), "a_minus_b": float("nan"), "dc": 2.34567e-5, "stiffness": 4.4e3,
           "rms": 0.00123, "flags": "not_identified:b;not_identified:a_minus_b"}
    head, tail = step_title(row).split("\n")
    assert head == ("step 4 (step): 3.3 -> 11 µm/s;  a = 0.006124, b = not identified, a-b = "
                    "not identified, Dc = 23.46 µm, k = 4400 /m, rms = 0.0012")
    assert tail == ("b, a_minus_b not identified; flags: not_identified:b; "
                    "not_identified:a_minus_b")
    assert "\n" not in step_title(dict(row, flags=""))


def test_bifurcation_upper_panel_axes_and_marks() -> None:
    """bifurcation.png's K_c panel: each nature's points with its marker (a K_c not finite
    drawn as a gap), a log axis only beyond a decade, units by law, one velocity padded x3."""
    import math

    from dryfriction.plots.hopf import plot_bifurcation

    rows = [{"velocity": 2.3e-6, "K_c": 410.0, "relative_l1": -0.2, "nature": "supercritical"},
            {"velocity": 7.9e-6, "K_c": 4700.0, "relative_l1": 0.03, "nature": "subcritical"},
            {"velocity": 3.1e-5, "K_c": math.inf, "relative_l1": 0.0, "nature": "none"},
            {"velocity": 9.0e-5, "K_c": 870.0, "relative_l1": 1e-9, "nature": "degenerate"}]
    fig, axes = plot_bifurcation({"rows": rows})
    marks = {ln.get_label(): (ln.get_marker(), list(ln.get_xdata()), list(ln.get_ydata()))
             for ln in axes[0].get_lines()}
    assert marks["supercritical"] == ("o", [2.3e-6], [410.0])
    assert marks["subcritical"] == ("s", [7.9e-6], [4700.0])
    assert marks["degenerate"] == ("D", [9.0e-5], [870.0])
    assert marks["none"][0] == "x" and math.isnan(marks["none"][2][0])
    assert axes[0].get_yscale() == "log"  # 410 .. 4700: beyond a decade
    assert "[1/m]" in axes[0].get_ylabel() and "m/s" in axes[1].get_xlabel()
    lin = [dict(r, K_c=r["K_c"] / 2.0 if r["K_c"] > 3000 else r["K_c"]) for r in rows]
    assert plot_bifurcation({"rows": lin})[1][0].get_yscale() == "linear"  # 410 .. 2350
    one = [dict(rows[0])]
    _, ax1 = plot_bifurcation({"rows": one, "law": "trap"})
    assert ax1[1].get_xlim() == pytest.approx((2.3e-6 / 3, 2.3e-6 * 3), rel=1e-12)
    assert "a_0/t_0" in ax1[1].get_xlabel() or "a0/t0" in ax1[1].get_xlabel()


def test_run_figure_helpers_holds_gaps_and_the_hold_clock() -> None:
    """The time-series figure's helpers: holds merged, the unsampled steps (no slip, longer
    than 3 sliding steps, a change of y) broken, and the axis that draws long holds as bands
    ``min(0.08, 0.3/n) x`` the sliding time wide, real time kept outside them."""
    from dryfriction.plots.runs import (
        HOLD_BAND,
        _broken,
        _friction_label,
        _HoldClock,
        _holds,
        _unsampled,
    )

    t = np.array([0.0, 1.0, 2.0, 3.0, 50.0, 51.0, 52.0, 130.0, 131.0])
    x = np.array([0.0, 0.5, 1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 2.5])
    y = np.array([1.0, 1.1, 1.2, 1.2, 0.9, 1.0, 1.1, 1.1, 1.2])
    assert _holds(t, x) == [(2.0, 50.0), (52.0, 130.0)]  # the first two steps merged
    np.testing.assert_array_equal(_unsampled(t, x, y), [3])  # 3 -> 50: y changes; 6 -> 7: not
    assert _unsampled(t, x, np.where(t < 10, y, 1.2)).size == 0
    # the bound: a still step longer than 3 median sliding steps (2.5 is not, 3.5 is)
    tb = np.array([0.0, 1.0, 2.0, 4.5, 5.5, 9.0, 10.0])
    xb = np.array([0.0, 0.5, 1.0, 1.0, 1.5, 1.5, 2.0])
    np.testing.assert_array_equal(_unsampled(tb, xb, np.arange(7.0)), [4])
    u, yy = _broken(t, y, np.array([3]))
    assert np.isnan(u[4]) and np.isnan(yy[4]) and u.size == t.size + 1
    np.testing.assert_array_equal(u[5:], t[4:])
    clock = _HoldClock(t, _holds(t, x))
    sliding = 131.0 - (48.0 + 78.0)  # 5 of sliding, 126 held
    w = min(HOLD_BAND, 0.3 / 2) * sliding
    assert HOLD_BAND == 0.08 and clock.bands == [(2.0, 50.0), (52.0, 130.0)]
    s = clock.forward(np.array([0.0, 2.0, 50.0, 51.0, 52.0, 130.0, 131.0, 140.0, -1.0]))
    np.testing.assert_allclose(s, [0.0, 2.0, 2.0 + w, 3.0 + w, 4.0 + w, 4.0 + 2 * w,
                                   5.0 + 2 * w, 14.0 + 2 * w, -1.0], rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(clock.inverse(s), [0.0, 2.0, 50.0, 51.0, 52.0, 130.0, 131.0,
                                                  140.0, -1.0], rtol=1e-14, atol=1e-13)
    # four holds: each band 0.3/4 = 0.075 (< 0.08) of the sliding time wide
    t4 = np.array([0.0, 1.0, 30.0, 31.0, 60.0, 61.0, 90.0, 91.0, 120.0, 121.0])
    x4 = np.array([0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 5.0])
    c4 = _HoldClock(t4, _holds(t4, x4))
    assert len(c4.bands) == 4
    assert float(c4.forward(121.0)) == pytest.approx(5.0 + 4 * 0.075 * 5.0, rel=1e-14)
    # holds shorter than the sliding: real time throughout
    assert _HoldClock(t[:4], _holds(t[:4], x[:4])).bands == []
    assert _friction_label(1.0) == r"friction $F/F_{el}$"
    assert "= 0.45" in _friction_label(0.45)


def test_paper_figures_3_and_5_draw_their_functions() -> None:
    """Fig. 3 and 5: each eps's curve is mu_s(T) (mu_d(u)) of that model, the dashes the
    first-order expansion with the legend's "within" its largest gap, the dotted lines the
    low-velocity expansion over u <= 1 only (mistakes: the expansion drawn over the whole
    range, the gap of the last curve only)."""
    from dryfriction.plots import paper
    from dryfriction.theory.model import TrapModel
    from dryfriction.theory.static import static_friction, static_friction_first_order
    from dryfriction.theory.steady import steady_friction, steady_friction_low_velocity

    eps = (0.047, 0.013)  # the larger gap first
    _, ax = paper.fig3_static_friction(alpha=0.11, eps_values=eps, T_range=(0.03, 70.0), n=13)
    T = np.logspace(np.log10(0.03), np.log10(70.0), 13)
    lines = [ln for ln in ax.get_lines() if len(ln.get_xdata()) == 13]
    assert len(lines) == 4
    gap = 0.0
    for k, e in enumerate(eps):
        m = TrapModel(0.11, e)
        np.testing.assert_allclose(lines[2 * k].get_ydata(), static_friction(m, T), rtol=1e-14)
        first = static_friction_first_order(m, T)
        np.testing.assert_allclose(lines[2 * k + 1].get_ydata(), first, rtol=1e-14)
        gap = max(gap, float(np.max(np.abs(first - static_friction(m, T)))))
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert f"first order, eq. 28 (within {gap:.1g})" in labels
    _, ax = paper.fig5_steady_friction(alpha=0.11, eps_values=eps, u_range=(0.02, 30.0), n=11)
    u = np.logspace(np.log10(0.02), np.log10(30.0), 11)
    dotted = [ln for ln in ax.get_lines() if ln.get_linestyle() == ":"]
    assert len(dotted) == 2
    for ln, e in zip(dotted, eps, strict=True):
        m = TrapModel(0.11, e)
        np.testing.assert_array_equal(ln.get_xdata(), u[u <= 1.0])
        np.testing.assert_allclose(ln.get_ydata(), steady_friction_low_velocity(m, u[u <= 1.0]),
                                   rtol=1e-14)
    solid = [ln for ln in ax.get_lines() if ln.get_linestyle() == "-" and len(ln.get_xdata()) == 11]
    np.testing.assert_allclose(solid[1].get_ydata(), steady_friction(TrapModel(0.11, 0.013), u),
                               rtol=1e-14)
