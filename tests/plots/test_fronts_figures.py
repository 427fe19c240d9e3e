"""The figures of the extended interface draw what the analysis found, where it belongs: fronts
on the space-time map at (position, arrival time), speeds at their positions, the precursor
points and the magnitude-frequency steps, with the units on the axes."""

from __future__ import annotations

import io

import numpy as np
import pytest

from dryfriction.analysis.catalogue import magnitude_frequency, precursor_trend, precursors
from dryfriction.analysis.fronts import detect_events, space_time
from dryfriction.plots.fronts import (
    front_speed_figure,
    magnitude_frequency_figure,
    precursor_figure,
    space_time_figure,
)
from dryfriction.plots.style import save_png
from fronts_synth import Pulse, fields, grid

THR = 0.6


@pytest.fixture(scope="module")
def run():
    t, x = grid(n_x=24, dx=0.5, t_end=16.0, dt=0.02)
    pulses = [Pulse(0, 0, 5, 1.0, 2.0), Pulse(0, 0, 11, 4.0, 1.5),
              Pulse(6, 0, 23, 9.0, 3.0, A=8.0)]
    v, s = fields(t, x, pulses, v_bg=0.01)
    st = space_time(t, x, v, s, 0.4 + 0.03 * t)
    return st, detect_events(st, THR)


def _png(fig) -> bytes:
    buf = io.BytesIO()
    save_png(fig, buf)
    return buf.getvalue()


def test_space_time_map_draws_each_front_at_its_arrivals(run):
    # mistake: the front drawn as (t, x) on an (x, t) map, or one direction left out
    st, events = run
    fig, ax = space_time_figure(st, events, THR)
    drawn = [(tuple(ln.get_xdata()), tuple(ln.get_ydata())) for ln in ax.get_lines()
             if ln.get_linestyle() == "-"]
    expected = [(tuple(f.x), tuple(f.t)) for e in events for f in e.fronts if f.x.size > 1]
    assert len(drawn) == len(expected) == 4  # two edge events one way, the third both ways
    for (dx, dt), (ex, et) in zip(drawn, expected, strict=True):
        assert np.allclose(dx, ex) and np.allclose(dt, et)
    assert "[a0]" in ax.get_xlabel() and "[t0]" in ax.get_ylabel()
    assert _png(fig).startswith(b"\x89PNG")


def test_speed_figure_puts_each_speed_at_its_position(run):
    st, events = run
    fig, ax = front_speed_figure(st, events, reference_speed=3.0, reference_label="c")
    points = [ln for ln in ax.get_lines() if ln.get_marker() == "."]
    xs = np.concatenate([ln.get_xdata() for ln in points])
    vs = np.concatenate([ln.get_ydata() for ln in points])
    for e, c in zip(events, (2.0, 1.5, 3.0), strict=True):
        for f in e.fronts:
            for xi, vi in zip(f.x, f.speed, strict=True):
                if np.isfinite(vi):
                    k = np.flatnonzero(np.isclose(xs, xi) & np.isclose(vs, vi))
                    assert k.size and vi == pytest.approx(c, rel=1e-6)
    assert "[a0/t0]" in ax.get_ylabel()
    _png(fig)


def test_precursor_and_magnitude_figures(run):
    st, events = run
    pre = precursors(events, st, normal_load=2.0, edge="left")
    fig, ax = precursor_figure(pre, st, precursor_trend(pre))
    (pts,) = [ln for ln in ax.get_lines() if ln.get_marker() == "o"]
    # two precursors: the trend is not judged, and the legend says so
    assert "grow with the load: undetermined (2 points)" in [
        t.get_text() for t in ax.get_legend().get_texts()]
    assert np.allclose(pts.get_xdata(), pre.ratio) and np.allclose(pts.get_ydata(), [3.0, 6.0])
    assert "[1]" in ax.get_xlabel() and "[a0]" in ax.get_ylabel()
    _png(fig)
    mf = magnitude_frequency([e.moment for e in events])
    fig, ax = magnitude_frequency_figure(mf, st)
    step = ax.get_lines()[0]
    assert np.allclose(step.get_ydata(), [1, 2, 3])
    assert np.allclose(step.get_xdata(), sorted((e.moment for e in events), reverse=True))
    assert "[a0^2]" in ax.get_xlabel() and "alpha" in ax.get_legend().get_texts()[-1].get_text()
    _png(fig)


def test_long_record_is_pooled_by_its_largest_values():
    # mistake: every k-th sample kept (a short slip between two kept samples vanishes)
    from dryfriction.plots.fronts import MAP_ROWS, space_time_figure

    t = np.arange(3 * MAP_ROWS + 7) * 0.01
    x = np.arange(3.0)
    v = np.zeros((t.size, 3))
    v[1001, 1] = 5.0  # one sample, not a multiple of the pooling factor
    v[-1, 2] = 7.0  # the last, incomplete block
    st = space_time(t, x, v)
    fig, ax = space_time_figure(st, [], 1.0)
    (mesh,) = ax.collections
    shown = np.asarray(mesh.get_array()).reshape(-1, 3)
    assert shown.shape[0] <= MAP_ROWS + 1
    assert shown[:, 1].max() == pytest.approx(np.log10(5.0))
    assert shown[-1, 2] == pytest.approx(np.log10(7.0))


def test_the_fitted_line_follows_the_cumulative_count(run):
    """The magnitude-frequency figure draws ``N(>= M)``, whose power law has the exponent
    ``1 - alpha`` when the density goes as ``M^-alpha``: the dashed line starts at ``n_fit``
    at ``M_min`` and its log-log slope matches the slope of the drawn steps (least squares on
    the steps, an independent route; 400 Pareto moments, alpha = 2.4). Mistake: the density's
    slope ``-alpha`` drawn on the cumulative count."""
    rng = np.random.default_rng(31)
    moments = 0.7 * (1.0 - rng.uniform(size=400)) ** (-1.0 / 1.4)  # density ~ M^-2.4
    mf = magnitude_frequency(moments)
    fig, ax = magnitude_frequency_figure(mf, run[0])
    step, line = ax.get_lines()[0], ax.get_lines()[1]
    lm, ln = np.log(line.get_xdata()), np.log(line.get_ydata())
    drawn = float(np.polyfit(lm, ln, 1)[0])
    assert line.get_ydata()[0] == pytest.approx(mf.n_fit, rel=1e-12)
    keep = step.get_ydata() >= 10  # the tail's last few counts are noise
    steps = float(np.polyfit(np.log(step.get_xdata()[keep]), np.log(step.get_ydata()[keep]), 1)[0])
    assert drawn == pytest.approx(1.0 - mf.alpha, rel=1e-9)
    assert abs(drawn - steps) < 0.15
    assert abs(steps - (1.0 - 2.4)) < 0.15


def test_the_map_floor_is_a_hundredth_of_the_threshold():
    # mistake (blind set 6, plot_fronts_floor_10): the colour floor at threshold/10, not the
    # documented threshold/100: slip rates between the two (the creep ahead of a front) are
    # drawn flat at the floor; at rest or slipping back, the floor; the label says which
    t = np.arange(40) * 0.25
    x = np.array([0.0, 0.7, 1.9])  # non-uniform positions
    v = np.zeros((t.size, 3))
    v[:, 1] = 0.02  # creep: above threshold/100 = 0.006, below threshold/10
    v[5, 2] = -0.3  # back-slip
    v[20:24, 0] = 2.5  # a slip
    fig, ax = space_time_figure(space_time(t, x, v), [], THR)
    (mesh,) = ax.collections[:1]
    shown = np.asarray(mesh.get_array()).reshape(t.size, 3)
    floor = THR / 100.0
    assert shown[0, 0] == pytest.approx(np.log10(floor), abs=1e-12)  # at rest
    assert shown[5, 2] == pytest.approx(np.log10(floor), abs=1e-12)  # back-slip
    assert np.allclose(shown[:, 1], np.log10(0.02), atol=1e-12)  # the creep as it is
    assert shown[21, 0] == pytest.approx(np.log10(2.5), abs=1e-12)
    assert f"floor {floor:.3g}" in fig.axes[-1].get_ylabel()
