"""The figure layer: run figures label their axes with the right units, nothing draws through
pyplot, and the fixed layout clips and overlaps nothing."""

from __future__ import annotations

import io
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.text import Text

from dryfriction.analysis.rsf_view import Comparison
from dryfriction.plots import paper, runs
from dryfriction.plots.style import DPI, new_figure, save_png

K_KEY, V_KEY = "drive.stiffness", "drive.segments.0.velocity"


# --------------------------------------------------------------------- results to draw
# Stand-ins with the attributes the figures read: drawing is what is tested, not the models.


PARAMS = {"model": {"alpha": 0.13, "eps": 0.04, "creep": "log", "mu_el": 1.0},
          "track": {"traps_per_a0": 400.0}, "initial": {"kind": "steady", "velocity": 0.1},
          "drive": {"kind": "velocity", "segments": [{"velocity": 0.1, "slip": 0.5},
                                                     {"velocity": 0.0, "duration": 100.0},
                                                     {"velocity": 0.1, "slip": 0.5}]}}


def trap_run(partial: bool = False) -> SimpleNamespace:
    # slide 5 t0 at u = 0.1, a hold of 100 t0 sampled once (its two ends), slide 5 t0 again
    t = np.concatenate([np.linspace(0.0, 5.0, 100), 105.0 + np.linspace(0.0, 5.0, 100)])
    v = np.full(t.size, 0.1)
    v[100] = 0.0  # the velocity of the step ending at the first sample after the hold
    x = 0.5 + np.concatenate([0.1 * t[:100], 0.5 + 0.1 * (t[100:] - 105.0)])
    mu = 1 + 0.05 * np.sin(t)
    return SimpleNamespace(t=t, x=x, v=v, mu=mu, n_active=100 + 5 * np.cos(t),
                           x_pull=np.full(t.size, np.nan), partial=partial,
                           info={"parameters": PARAMS})


def threshold_run() -> SimpleNamespace:
    # force control: a wait of 100 t0 at zero force, then a ramp to the threshold 1.2
    t = np.concatenate([[0.0], 100.0 + np.linspace(0.0, 1e-4, 50)])
    mu = np.concatenate([[0.0], np.linspace(0.0, 1.2, 50)])
    x = np.concatenate([[0.0], np.linspace(0.0, 1.5, 50)])
    params = {**PARAMS, "initial": {"kind": "rest"},
              "drive": {"kind": "force", "rate": 1e4, "hold": 100.0}}
    return SimpleNamespace(t=t, x=x, v=np.gradient(x, t), mu=mu, n_active=0 * t,
                           x_pull=np.full(t.size, np.nan), partial=False,
                           info={"parameters": params, "threshold_mu": 1.2,
                                 "threshold_t": 100.0 + 1e-4})


def rsf_run(damping: float = 0.0) -> SimpleNamespace:
    t = np.linspace(0.0, 40.0, 400)
    v = np.where(t < 10, 1e-6, 1e-5)
    v[200:250] = 0.0  # a hold: zero velocity has no place on a log axis
    x = np.concatenate([[0.0], np.cumsum(v[1:] * np.diff(t))]) + 3e-3
    mu = 0.6 + 0.005 * np.log(np.maximum(v, 1e-9) / 1e-6)
    return SimpleNamespace(t=t, x=x, v=v, mu=mu, stress=mu - 1e-3, load_velocity=v,
                           damping=damping, mass=0.0, params=SimpleNamespace(state_law="ageing"))


def comparison() -> Comparison:
    t = np.linspace(0.0, 20.0, 100)
    mu_trap = 1 + 0.02 * np.tanh(t - 5)
    mu_rsf = mu_trap + 0.003 * np.cos(t)
    mu_rsf[40:50] = np.nan  # a kinematic hold, where the twin is undefined
    twin = SimpleNamespace(state_law="ageing", a=0.001, b=0.02, dc=1.5)
    return Comparison(t, 0.1 * t + 2.0, mu_trap, mu_rsf, twin, "standard", 1.0)


def sweep() -> xr.Dataset:
    # one velocity keeps the K_c line to one point (each costs ~0.06 s)
    codes = np.array([[0.0], [1.0], [np.nan]])
    return xr.Dataset({"class": ((K_KEY, V_KEY), codes)},
                      coords={K_KEY: [0.025, 0.05, 0.1], V_KEY: [0.1]})


BASE = {"model": {"eps": 0.04}, "drive": {"mass": 0.0, "damping": 0.0}}


def run_figures() -> dict[str, tuple[Figure, object]]:
    return {
        "timeseries": runs.timeseries_figure(trap_run()),
        "rsf_timeseries": runs.rsf_timeseries_figure(rsf_run(damping=0.1)),
        "rsf": runs.rsf_figure(rsf_run(), "step, ageing law"),
        "compare": runs.comparison_figure(comparison(), "velocity_step.toml"),
        "phase_diagram": runs.phase_diagram_figure(sweep(), BASE, K_KEY, V_KEY),
    }


# --------------------------------------------------------------------- labels and units

# (x unit, y unit) of each panel, top to bottom: reduced units for the trap model (t0, a0,
# F_el), SI for rate-and-state; None where a shared axis carries no label
UNITS = {
    "timeseries": [("[$t_0$]", "F_{el}"), ("[$a_0$]", "F_{el}"), ("[$t_0$]", "[$a_0/t_0$]"),
                   ("[$t_0$]", "[$a_0$]")],
    "rsf_timeseries": [("[s]", r"\mu"), ("[m]", r"\mu"), ("[s]", "[m/s]"),
                       ("[m/s]", r"\mu")],
    "rsf": [("[s]", r"\mu"), ("[s]", "[m/s]"), ("[m/s]", r"\mu")],
    "compare": [("[$t_0$]", "F_{el}"), ("[$a_0$]", "F_{el}"), ("[$a_0$]", "F_{el}")],
    "phase_diagram": [("[$a_0/t_0$]", "[$F_{el}/a_0$]")],
}


@pytest.fixture(scope="module")
def figures():
    return run_figures()


@pytest.mark.parametrize("name", sorted(UNITS))
def test_run_figures_label_their_axes_with_units(figures, name):
    fig, axes = figures[name]
    assert isinstance(fig, Figure)
    axes = list(np.atleast_1d(axes))
    assert list(fig.axes) == axes  # every panel returned, top to bottom
    assert len(axes) == len(UNITS[name])
    for ax, (x_unit, y_unit) in zip(axes, UNITS[name], strict=True):
        if x_unit is not None:
            assert x_unit in ax.get_xlabel(), (name, ax.get_xlabel())
        assert y_unit in ax.get_ylabel(), (name, ax.get_ylabel())
        assert ax.lines or ax.collections


def test_slip_axes_start_at_zero_and_velocities_on_a_log_scale(figures):
    _, axes = figures["timeseries"]
    assert axes[1].lines[0].get_xdata()[0] == 0.0  # slip, not the slider position
    assert axes[3].lines[0].get_ydata()[0] == 0.0
    _, axes = figures["rsf_timeseries"]
    assert axes[1].lines[0].get_xdata()[0] == 0.0
    for ax in (axes[2], figures["rsf"][1][1]):
        assert ax.get_yscale() == "log"
        v = ax.lines[0].get_ydata()
        assert np.isnan(v[200:250]).all() and (v[np.isfinite(v)] > 0).all()


def test_compare_draws_the_difference_of_the_twin_and_the_trap_model(figures):
    c = comparison()
    _, axes = figures["compare"]
    np.testing.assert_array_equal(axes[2].lines[0].get_ydata(), c.mu_rsf - c.mu_trap)
    assert "rms misfit" in figures["compare"][0].get_suptitle()


def test_phase_diagram_marks_each_class_and_the_failed_points(figures):
    fig, ax = figures["phase_diagram"]
    labels = {t.get_text() for t in ax.get_legend().get_texts()}
    assert labels == {"steady", "periodic", "failed", "linear $K_c(u)$"}


def test_timeseries_does_not_draw_a_line_across_an_unsampled_hold_and_shades_it(figures):
    # the hold of 100 t0 is sampled at its two ends only: a straight line between them would
    # invent the friction's path; the slides are drawn whole
    fig, axes = figures["timeseries"]
    t, mu = (np.asarray(a, float) for a in (axes[0].lines[0].get_xdata(),
                                          axes[0].lines[0].get_ydata()))
    gap = np.flatnonzero(np.isnan(mu))
    assert gap.size == 1 and t[gap[0] - 1] == 5.0 and t[gap[0] + 1] == 105.0
    assert np.isfinite(mu[:gap[0]]).all() and np.isfinite(mu[gap[0] + 1:]).all()
    spans = [p for p in axes[0].patches if p.get_label() == "hold"]
    assert len(spans) == 1
    box = spans[0].get_bbox()  # x in data units
    assert (box.x0, box.x1) == (5.0, 105.0)
    assert "hold 100 $t_0$" in [tx.get_text() for tx in axes[1].texts]
    title = fig.get_suptitle()
    assert "0.04" in title and "0.13" in title and "400 traps" in title and "1 hold" in title


def hold_run(hold: float) -> SimpleNamespace:
    # slide 5 t0 at u = 1, a hold sampled once (its two ends), slide 5 t0 again
    t = np.concatenate([np.linspace(0.0, 5.0, 101), 5.0 + hold + np.linspace(0.0, 5.0, 101)])
    x = np.concatenate([np.linspace(0.0, 5.0, 101), np.linspace(5.0, 10.0, 101)])
    v = np.ones(t.size)
    v[101] = 0.0
    mu = 1 + 0.05 * np.sin(x)
    mu[101:] += 0.1  # aged over the hold: the friction changed along an unrecorded path
    params = {**PARAMS, "drive": {"kind": "velocity", "segments": [
        {"velocity": 1.0, "slip": 5.0}, {"velocity": 0.0, "duration": hold},
        {"velocity": 1.0, "slip": 5.0}]}}
    return SimpleNamespace(t=t, x=x, v=v, mu=mu, n_active=100 + 0 * t,
                           x_pull=np.full(t.size, np.nan), partial=False,
                           info={"parameters": params})


def _sliding_share(ax) -> float:
    """The fraction of the axis's width not taken by the shaded holds (display units)."""
    to_px = ax.transData.transform
    x0, x1 = ax.get_xlim()
    width = to_px((x1, 0))[0] - to_px((x0, 0))[0]
    held = sum(to_px((p.get_bbox().x1, 0))[0] - to_px((p.get_bbox().x0, 0))[0]
               for p in ax.patches if p.get_label() in ("hold", "_nolegend_", ""))
    return 1.0 - held / width


def test_timeseries_compresses_a_long_hold_so_the_sliding_is_readable():
    # 10 t0 of sliding around a hold of 1000 t0: on a true time axis the sliding would get 1 %
    # of the width; the hold becomes a band of fixed width, still shaded, still not bridged,
    # its duration written in it
    fig, axes = runs.timeseries_figure(hold_run(1000.0))
    for ax in (axes[0], axes[2], axes[3]):
        assert _sliding_share(ax) >= 0.75, ax.get_xlabel()
        spans = [p for p in ax.patches if p.get_label() == "hold"]
        assert len(spans) == 1
        assert (spans[0].get_bbox().x0, spans[0].get_bbox().x1) == (5.0, 1005.0)  # real time
        assert "hold 1000 $t_0$" in [tx.get_text() for tx in ax.texts]
        assert "compressed" in ax.get_xlabel() and "[$t_0$]" in ax.get_xlabel()
        ticks = ax.get_xticks()  # real times, on the sliding only
        assert ticks.size >= 3 and not ((ticks > 5.0) & (ticks < 1005.0)).any()
    t, mu = (np.asarray(a, float) for a in (axes[0].lines[0].get_xdata(),
                                          axes[0].lines[0].get_ydata()))
    gap = np.flatnonzero(np.isnan(mu))
    assert gap.size == 1 and t[gap[0] - 1] == 5.0 and t[gap[0] + 1] == 1005.0
    # both slides are drawn at the same scale: equal durations, equal widths
    px = axes[0].transData.transform
    first = px((5.0, 0))[0] - px((0.0, 0))[0]
    second = px((1010.0, 0))[0] - px((1005.0, 0))[0]
    assert first == pytest.approx(second, rel=1e-6)
    _assert_laid_out(fig, "long hold")


def test_timeseries_keeps_true_time_when_the_holds_are_short():
    # a hold of 2 t0 beside 10 t0 of sliding squeezes nothing: the axis stays linear time
    _, axes = runs.timeseries_figure(hold_run(2.0))
    assert axes[0].get_xscale() == "linear"
    assert "compressed" not in axes[0].get_xlabel()


def test_timeseries_marks_a_static_threshold_with_its_value():
    fig, axes = runs.timeseries_figure(threshold_run())
    for ax in axes[:2]:
        stars = [ln for ln in ax.lines if ln.get_marker() == "*"]
        assert len(stars) == 1 and stars[0].get_ydata()[0] == 1.2
        assert any("static threshold 1.2" in tx.get_text() for tx in ax.texts)
    # the ramp on its own clock: the wait of 100 t0 would squeeze it into a spike
    t = axes[0].lines[0].get_xdata()
    assert t[0] == 0.0 and t[-1] == pytest.approx(1e-4)
    _assert_laid_out(fig, "threshold")


def test_interrupted_run_says_so():
    fig, _ = runs.timeseries_figure(trap_run(partial=True))
    assert "interrupted" in fig.get_suptitle()


# --------------------------------------------------------------------- no pyplot


@pytest.mark.slow
def test_figures_are_drawn_and_saved_without_pyplot():
    # in a fresh interpreter: importing pyplot would select a backend and keep every figure
    # alive in its global registry
    code = (
        "import sys, io\n"
        f"sys.path.insert(0, {str(Path(__file__).resolve().parent)!r})\n"
        "import test_plots\n"
        "from dryfriction.plots import report\n"
        "from dryfriction.plots.style import save_png\n"
        "for fig, _ in test_plots.run_figures().values():\n"
        "    save_png(fig, io.BytesIO())\n"
        "fig, _ = report.plotting.fig1_trap_hysteresis()\n"
        "save_png(fig, io.BytesIO())\n"
        "print('matplotlib.pyplot' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "False"


def test_save_png_writes_a_png_at_the_common_resolution():
    fig, _ = new_figure((4.0, 3.0))
    buf = io.BytesIO()
    save_png(fig, buf)
    data = buf.getvalue()
    assert data.startswith(b"\x89PNG\r\n\x1a\n")
    width, height = (int.from_bytes(data[i:i + 4], "big") for i in (16, 20))
    assert (width, height) == (round(4.0 * DPI), round(3.0 * DPI))


# --------------------------------------------------------------------- fixed layout


def _fig2() -> Figure:
    fig, (a, b) = new_figure((11.2, 4.2), 1, 2)
    paper.fig2a_aged_pinning_curve(ax=a)
    paper.fig2b_population_at_threshold(ax=b)
    return fig


PAPER = {
    "fig1": lambda: paper.fig1_trap_hysteresis()[0],
    "fig1b": lambda: paper.fig1b_population_at_rest()[0],
    "fig2": _fig2,
    "fig3": lambda: paper.fig3_static_friction(n=41)[0],
    "fig4": lambda: paper.fig4_steady_pinning_curve()[0],
    "fig5": lambda: paper.fig5_steady_friction(n=41)[0],
    "fig6": lambda: paper.fig6_dieterich(n=41)[0],
    "extra_loaded": lambda: paper.extra_loaded_static(n=41)[0],
    "extra_creep": lambda: paper.extra_creep_laws(n=41)[0],
    "extra_dieterich_C": lambda: paper.extra_local_dieterich_constant(n=21)[0],
}


def _assert_laid_out(fig: Figure, name: str) -> None:
    """Every axes with its labels, ticks, title and legend lies inside the figure, no two
    panels overlap, and the figure title clears the panels."""
    fig.set_dpi(DPI)
    FigureCanvasAgg(fig)
    renderer = fig.canvas.get_renderer()
    fig.draw_without_rendering()
    page = fig.bbox.padded(1.0)
    boxes = [ax.get_tightbbox(renderer) for ax in fig.axes]
    for ax, box in zip(fig.axes, boxes, strict=True):
        inside = page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0 <= box.y1 <= page.y1
        assert inside, f"{name}: panel {ax.get_title() or ax.get_ylabel()!r} leaves the figure"
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            assert not a.overlaps(b), f"{name}: two panels overlap"
    title = fig.get_suptitle()
    if title:
        text = next(t for t in fig.findobj(Text) if t.get_text() == title and t.figure is fig
                    and t not in [ax.title for ax in fig.axes])
        box = text.get_window_extent(renderer)
        assert box.y1 <= page.y1 and not any(box.overlaps(b) for b in boxes), name


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(PAPER))
def test_paper_figures_fit_their_fixed_layout(name):
    _assert_laid_out(PAPER[name](), name)


@pytest.mark.parametrize("name", sorted(UNITS))
def test_run_figures_fit_their_fixed_layout(figures, name):
    _assert_laid_out(figures[name][0], name)


def test_fig1b_population_at_rest_cancels_and_spans_one_a0_each_side():
    # eq. 25: (+) on -a0 < p < 0, (-) on 0 < p < a0, forces cancel (the Maxwell plateau)
    _, ax = paper.fig1b_population_at_rest()
    occ = {ln.get_label(): ln for ln in ax.lines if ln.get_label().startswith("occupied")}
    assert len(occ) == 2
    (plus,) = [ln for k, ln in occ.items() if "(+)" in k]
    (minus,) = [ln for k, ln in occ.items() if "(−)" in k]
    pp, fp = plus.get_xdata(), plus.get_ydata()
    pm, fm = minus.get_xdata(), minus.get_ydata()
    assert (pp.min(), pp.max()) == (-1.0, 0.0) and (pm.min(), pm.max()) == (0.0, 1.0)
    assert (fp >= 0).all() and (fm <= 0).all()
    om = np.argsort(pm)  # the (-) branch is drawn right to left
    total = np.trapezoid(fp, pp) + np.trapezoid(fm[om], pm[om])
    assert abs(total) < 1e-9 * np.trapezoid(fp, pp)


def test_fig3_shows_the_first_order_lines_over_the_curves():
    # they lie within 6e-4 of the full curves: under them they were invisible, yet in the legend
    _, ax = paper.fig3_static_friction(n=41)
    curves = [ln for ln in ax.lines if ln.get_label().startswith("(")]
    first = [ln for ln in ax.lines if ln.get_color() == "k" and len(ln.get_xdata())]
    assert len(curves) == len(first) == 5
    assert all(f.get_zorder() > c.get_zorder() for f in first for c in curves)
    assert all(f.get_linestyle() != "-" for f in first)
    assert any("eq. 28" in t.get_text() for t in ax.get_legend().get_texts())


def test_fig6_names_every_c_in_the_legend_and_writes_nothing_on_the_curves():
    _, ax = paper.fig6_dieterich(n=41)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    for C in (1, 2, 3, 4):
        assert any(lb.endswith(f"$C$ = {C}") for lb in labels), labels
    assert not ax.texts  # a label on a curve is struck through by its neighbours


def test_trap_forces_share_one_unit_across_figures():
    units = set()
    for fn in (paper.fig1_trap_hysteresis, paper.fig1b_population_at_rest,
               paper.fig2a_aged_pinning_curve, paper.fig2b_population_at_threshold,
               paper.fig4_steady_pinning_curve):
        label = fn()[1].get_ylabel()
        units.add(label[label.index("["):])
    assert units == {r"[$\Phi_{00}/a_0$]"}


def test_layout_check_catches_a_clipped_label():
    fig, ax = new_figure((3.0, 2.0))
    ax.set_ylabel("a label long enough to leave a figure two inches high " * 2)
    with pytest.raises(AssertionError, match="leaves the figure"):
        _assert_laid_out(fig, "clipped")


def test_too_small_a_figure_is_refused():
    with pytest.raises(ValueError, match="too small"):
        new_figure((1.0, 1.0), 3, 1)
