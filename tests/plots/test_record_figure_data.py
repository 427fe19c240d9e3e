"""record.png's drawn data (dryfriction.plots.record.plot_record) on a synthetic record whose
time starts at 1234.5 s, with a down-step, a hold and a boundary set by the normal force alone
(in N): every panel drawn from the first sample, the velocity in µm/s, the program's segments
at their velocity, the shading and marks where the segments and the detector put them, the
normal force in kN; the velocity axis linear or symmetric-log on either side of its x 30 rule."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from dryfriction.plots.record import plot_record
from dryfriction.records.record import LabRecord

T0 = 1234.5


def _record(v_fast: float, v_slow: float) -> tuple[LabRecord, list[SimpleNamespace]]:
    t = T0 + np.arange(6001) * 0.1  # 600 s
    tt = t - T0
    edges = [0.0, 200.0, 300.0, 450.0, 600.0]
    vel = [v_fast, 0.0, v_slow, v_slow]
    k = np.minimum(np.searchsorted(edges, tt, side="right") - 1, 3)
    x_edges = np.r_[0.0, np.cumsum(np.diff(edges) * vel)]
    x = 7.3e-3 + x_edges[k] + np.asarray(vel)[k] * (tt - np.asarray(edges)[k])
    normal = np.where(tt < 450.0, 2.7e3, 3.1e3)  # N
    rec = LabRecord(source="synthetic.txt", time=t, load_point=x, load_velocity=None,
                    friction=0.6 + 0.01 * np.sin(tt), normal_stress=normal, normal_unit="N",
                    columns={}, first_line=0)
    segs = [SimpleNamespace(t_start=T0 + a, t_end=T0 + b, velocity=v, start_placed=True)
            for a, b, v in zip(edges[:-1], edges[1:], vel, strict=True)]
    return rec, segs


def test_record_figure_draws_the_program_shading_marks_and_normal_force() -> None:
    rec, segs = _record(2.3e-6, 0.41e-6)
    det = SimpleNamespace(rate_changes=[T0 + 200.0, T0 + 300.0], gaps=[T0 + 77.7], resets=[],
                          normal_changes=[T0 + 450.0])
    fig, info = plot_record(rec, segs, det)
    ax_v, ax_f, ax_n = (fig.axes[info.panels.index(p)] for p in ("velocity", "friction",
                                                                 "normal"))
    # the smoothed velocity: windows of max(600/400, 3 x 0.1) = 1.5 s, from the first sample
    lines = [ln for ln in ax_v.get_lines() if np.asarray(ln.get_xdata()).size > 50]
    assert len(lines) == 1 and "slope over 1.5 s" in lines[0].get_label()
    xv, yv = (np.asarray(a, float) for a in lines[0].get_data())
    assert 0.0 <= xv.min() < 1.5 and 598.5 < xv.max() <= 600.0
    inside = (xv > 2.0) & (xv < 198.0)
    np.testing.assert_allclose(yv[inside], 2.3, rtol=1e-6)
    np.testing.assert_allclose(yv[(xv > 302.0) & (xv < 598.0)], 0.41, rtol=1e-6)
    # the program's segments at their velocity (µm/s), from the first sample
    prog = sorted((tuple(ln.get_xdata()), tuple(ln.get_ydata())) for ln in ax_v.get_lines()
                  if len(ln.get_xdata()) == 2 and ln.get_color() == "C3")
    assert prog == sorted(((a - T0, b - T0), (v * 1e6, v * 1e6)) for a, b, v in
                          ((s.t_start, s.t_end, s.velocity) for s in segs))
    assert ax_v.get_yscale() == "linear"
    assert ax_v.get_ylim() == pytest.approx((-0.15 * 2.3, 1.5 * 2.3), rel=1e-12)
    # shaded: the hold and the down-step; not segment 0, not the normal-force boundary
    assert info.shaded == [1, 2]
    for name in info.panels:
        spans = [(p.get_x(), p.get_x() + p.get_width()) for p in info.artists[name]]
        np.testing.assert_allclose(spans, [(200.0, 300.0), (300.0, 450.0)], atol=1e-9)
    assert "1 velocity change(s), 1 hold(s)" in fig._suptitle.get_text()
    # marks at record time - t0 on every panel, reported in record time
    for a in (ax_v, ax_f, ax_n):
        marked = sorted(float(ln.get_xdata()[0]) for ln in a.get_lines()
                        if ln.get_linestyle() in (":", "--", "-."))
        assert marked == pytest.approx([77.7, 200.0, 300.0, 450.0], abs=1e-9)
    assert info.marks == {"rate change": [T0 + 200.0, T0 + 300.0], "gap": [T0 + 77.7],
                          "normal change": [T0 + 450.0]}
    # friction and normal force against t - t0; the force in kN under a kN label
    np.testing.assert_allclose(ax_f.collections[0].get_offsets()[:, 0], rec.time - T0,
                               atol=1e-9)
    normal = [ln for ln in ax_n.get_lines() if np.asarray(ln.get_xdata()).size == rec.time.size]
    np.testing.assert_allclose(normal[0].get_ydata(), rec.normal_stress * 1e-3, rtol=1e-12)
    assert ax_n.get_ylabel() == "normal force  [kN]"
    assert f"t0 = {T0:g} s" in fig.axes[-1].get_xlabel()


@pytest.mark.parametrize("slow, log", [(2.3e-6 / 25.0, False), (2.3e-6 / 40.0, True)])
def test_record_velocity_axis_symlog_beyond_a_ratio_of_30(slow: float, log: bool) -> None:
    rec, segs = _record(2.3e-6, slow)
    fig, info = plot_record(rec, segs, None)
    ax = fig.axes[info.panels.index("velocity")]
    assert ax.get_yscale() == ("symlog" if log else "linear")
    if log:
        # the decade at or below the slowest speed (0.0575 um/s)
        assert ax.yaxis.get_transform().linthresh == pytest.approx(0.01, rel=1e-12)
    assert info.marks == {}


@pytest.mark.parametrize("unplaced", [False, True])
def test_record_legend_hides_no_segment_number_nor_the_title(unplaced: bool) -> None:
    # the mistake: the legend inside the top panel's upper left, over the number of a step
    # starting early in the record (a new user's segment 1 at 60 s of 200 s); and, moved
    # above the panel, over the title's second line (a change not placed)
    rec, segs = _record(2.3e-6, 0.41e-6)
    segs[1].start_placed = not unplaced
    det = SimpleNamespace(rate_changes=[T0 + 200.0], gaps=[T0 + 77.7], resets=[T0 + 33.0],
                          normal_changes=[T0 + 450.0])
    fig, info = plot_record(rec, segs, det)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    r = FigureCanvasAgg(fig).get_renderer()
    fig.draw(r)
    ax_v = fig.axes[info.panels.index("velocity")]
    leg = ax_v.get_legend().get_window_extent(r)
    box = ax_v.get_window_extent(r)
    assert leg.y0 >= box.y1 - 1.0  # above the panel, not in it
    assert not leg.overlaps(fig._suptitle.get_window_extent(r))
    labels = [t for t in ax_v.texts if t.get_text().startswith(("1", "2"))]
    assert len(labels) == 2 and not any(leg.overlaps(t.get_window_extent(r)) for t in labels)
    assert len(ax_v.get_legend().get_texts()) == 6  # velocity, program, four kinds of mark


def test_a_hold_split_by_a_normal_change_is_shaded_whole() -> None:
    # userfixB: the hold 200-300 s with the normal force changed at 250 s (two segments at
    # rest) is one hold, shaded to its end as slice_steps cuts it (mistake: shaded to 250 s)
    rec, segs = _record(2.3e-6, 0.41e-6)
    segs = [segs[0], SimpleNamespace(t_start=T0 + 200.0, t_end=T0 + 250.0, velocity=0.0,
                                     start_placed=True),
            SimpleNamespace(t_start=T0 + 250.0, t_end=T0 + 300.0, velocity=0.0,
                            start_placed=True), *segs[2:]]
    fig, info = plot_record(rec, segs, None)
    assert info.shaded == [1, 3]
    for name in info.panels:
        spans = [(p.get_x(), p.get_x() + p.get_width()) for p in info.artists[name]]
        np.testing.assert_allclose(spans, [(200.0, 300.0), (300.0, 450.0)], atol=1e-9)
    assert "1 velocity change(s), 1 hold(s)" in fig._suptitle.get_text()


def test_a_reset_draws_no_velocity_spike() -> None:
    """The record above (2.3 um/s, then a hold and 0.41 um/s) with its transducer re-zeroed
    by -317 um at 123.45 s (within the first slide): the drawn velocity stays at the slide's
    2.3 um/s through the reset (within 1e-6, as elsewhere). Mistake, seen failing: the
    displacement drawn as read (a spike of -317 um over a 1.5-s window, about -210 um/s)."""
    rec, segs = _record(2.3e-6, 0.41e-6)
    x = np.asarray(rec.load_point, float).copy()
    k = int(np.searchsorted(np.asarray(rec.time) - T0, 123.45))
    x[k:] -= 317e-6
    rec = LabRecord(source=rec.source, time=rec.time, load_point=x, load_velocity=None,
                    friction=rec.friction, normal_stress=rec.normal_stress,
                    normal_unit=rec.normal_unit, columns={}, first_line=0)
    fig, info = plot_record(rec, segs, None)
    ax_v = fig.axes[info.panels.index("velocity")]
    (line,) = [ln for ln in ax_v.get_lines() if np.asarray(ln.get_xdata()).size > 50]
    xv, yv = (np.asarray(a, float) for a in line.get_data())
    np.testing.assert_allclose(yv[(xv > 2.0) & (xv < 198.0)], 2.3, rtol=1e-6)


def test_record_velocity_breaks_at_a_gap() -> None:
    """A 23.6-s gap in the logging (no sample from 137.2 to 160.8 s of the synthetic record):
    the drawn velocity has one break there (a NaN between the last window before the gap and
    the first after it) and none elsewhere, and reads 2.3 um/s on both sides. Mistake: the
    windows joined by a straight line across the gap (``breaks`` off: no NaN)."""
    rec, segs = _record(2.3e-6, 0.41e-6)
    tt = np.asarray(rec.time) - T0
    keep = (tt < 137.2) | (tt > 160.8)
    rec = LabRecord(source="synthetic.txt", time=np.asarray(rec.time)[keep],
                    load_point=np.asarray(rec.load_point)[keep], load_velocity=None,
                    friction=np.asarray(rec.friction)[keep],
                    normal_stress=np.asarray(rec.normal_stress)[keep], normal_unit="N",
                    columns={}, first_line=0)
    fig, info = plot_record(rec, segs, None)
    ax_v = fig.axes[info.panels.index("velocity")]
    line = next(ln for ln in ax_v.get_lines() if np.asarray(ln.get_xdata()).size > 50)
    xv, yv = (np.asarray(a, float) for a in line.get_data())
    gap = np.flatnonzero(np.isnan(yv))
    assert gap.size == 1 and np.isnan(xv[gap[0]])
    assert xv[gap[0] - 1] < 137.2 < 160.8 < xv[gap[0] + 1]
    near = np.r_[yv[gap[0] - 5:gap[0] - 1], yv[gap[0] + 2:gap[0] + 6]]
    np.testing.assert_allclose(near, 2.3, rtol=1e-6)


@pytest.mark.parametrize("source", ["/data/" + "WWmm_Run-07/" * 25 + "velstep.txt",
                                    "/lab/" + "a" * 300 + ".csv"])
def test_record_title_is_wrapped_within_the_figure(source: str) -> None:
    """A path of 300 characters (wide ones, or one word with no space or /) and a long note:
    the drawn title lies within the figure's width and above the legend, and holds the whole
    path (no character lost at a cut). Mistake: the title left on one line (cut at the
    figure's edges: the path's start and end unreadable); the panels not lowered for the
    lines the title takes (the title over the legend)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    rec, segs = _record(2.3e-6, 0.41e-6)
    rec = LabRecord(source=source, time=rec.time, load_point=rec.load_point,
                    load_velocity=None, friction=rec.friction, normal_stress=rec.normal_stress,
                    normal_unit="N", columns={}, first_line=0)
    fig, info = plot_record(rec, segs, None, note="unit assumed: " + "um (no unit row) " * 12)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    title = fig._suptitle
    box = title.get_window_extent(renderer)
    legend = fig.axes[info.panels.index("velocity")].get_legend().get_window_extent(renderer)
    assert 0.0 <= box.x0 and box.x1 <= fig.bbox.width
    assert box.y0 >= legend.y1 and box.y1 <= fig.bbox.height
    assert title.get_text().count("\n") >= 3
    assert "".join(source.split()) in "".join(title.get_text().split())


def test_record_velocity_unbroken_where_sampling_is_only_jittered() -> None:
    """800 samples at 10 Hz jittered +-45 % (windows of 3 median intervals, some with fewer
    than 3 samples and so left out) and no gap: the drawn velocity has no break. Mistake:
    a break wherever a window was left out (a review measured 24-48 breaks: a dashed line)."""
    rng = np.random.default_rng(8)
    t = T0 + np.concatenate([[0.0], np.cumsum(rng.uniform(0.055, 0.145, 799))])
    x = 4.1e-3 + 2.3e-6 * (t - T0)
    rec = LabRecord(source="jitter.txt", time=t, load_point=x, load_velocity=None,
                    friction=0.6 + 0.0 * t, normal_stress=None, normal_unit="Pa", columns={},
                    first_line=0)
    segs = [SimpleNamespace(t_start=t[0], t_end=t[-1], velocity=2.3e-6, start_placed=True)]
    fig, info = plot_record(rec, segs, None)
    ax_v = fig.axes[info.panels.index("velocity")]
    line = next(ln for ln in ax_v.get_lines() if np.asarray(ln.get_xdata()).size > 50)
    assert not np.isnan(np.asarray(line.get_ydata(), float)).any()


@pytest.mark.slow
def test_record_title_keeps_the_panels_room() -> None:
    """800 segments, every one unplaced (a title listing them all): the figure is drawn,
    its title at most TITLE_LINES lines, the last saying it is cut, and the panels keep
    their height. Mistake: no cap (the panels' top below their bottom: matplotlib raised)."""
    from dryfriction.plots.record import TITLE_LINES

    rec, _ = _record(2.3e-6, 0.41e-6)
    edges = np.linspace(T0, T0 + 600.0, 801)
    segs = [SimpleNamespace(t_start=a, t_end=b, velocity=(2.3e-6 if k % 2 else 0.41e-6),
                            start_placed=False, start_lo=a - 1.0, start_hi=a + 1.0)
            for k, (a, b) in enumerate(zip(edges[:-1], edges[1:], strict=True))]
    fig, info = plot_record(rec, segs, None)
    text = fig._suptitle.get_text()
    assert text.count("\n") + 1 <= TITLE_LINES and "title cut" in text
    assert all(ax.get_position().height > 0.15 for ax in fig.axes)


def test_the_velocity_is_drawn_on_both_sides_of_a_sampling_rate_change() -> None:
    """A slide at 6.3 um/s sampled at 4.1 Hz with intervals jittered by +-30 % for 70 s, then
    at 41 Hz for 50 s (the zoo's tenfold rate change): the smoothed velocity is drawn on
    every 5 s of the slow side too, at 6.3 um/s (a line, no noise), its window three of the
    slow intervals at least. Mistake: the window from the median interval (three of the fast
    ones, 0.073 s: every slow window had under 3 samples and was left out, nothing drawn
    before the change; seen on zoo 44052's record.png)."""
    rng = np.random.default_rng(41)
    slow = np.cumsum(rng.uniform(0.7, 1.3, 287) / 4.1)
    slow = slow[slow < 70.0]
    t = T0 + np.concatenate([[0.0], slow, 70.0 + np.arange(1, 2051) / 41.0])
    x = 7.3e-3 + 6.3e-6 * (t - T0)
    rec = LabRecord(source="rate.txt", time=t, load_point=x, load_velocity=None,
                    friction=0.6 + 0.0 * t, normal_stress=None, normal_unit="Pa", columns={},
                    first_line=0)
    seg = [SimpleNamespace(t_start=t[0], t_end=t[-1], velocity=6.3e-6, start_placed=True)]
    fig, info = plot_record(rec, seg, SimpleNamespace(rate_changes=[T0 + 70.0], gaps=[],
                                                      resets=[], normal_changes=[]))
    ax_v = fig.axes[info.panels.index("velocity")]
    (line,) = [ln for ln in ax_v.get_lines() if "slope over" in str(ln.get_label())]
    xv, yv = (np.asarray(a, float) for a in line.get_data())
    drawn = np.isfinite(yv)
    assert all(((xv >= a) & (xv < a + 5.0) & drawn).any() for a in np.arange(0.0, 120.0, 5.0))
    np.testing.assert_allclose(yv[drawn], 6.3, rtol=1e-6)


def test_record_velocity_symlog_tick_labels_do_not_overlap() -> None:
    """The symmetric-log velocity axis puts its linear range at the decade at or below the
    slowest speed, so that its ticks are 0 and whole decades either side, one decade's height
    apart. Seen in an independent review's record.png (a slide-hold-slide at 30 um/s whose
    hold read 0.008 um/s, the smoothed velocity dipping to -0.1 um/s): with the linear range
    at 0.008 um/s itself, the labels 10^-3, 0 and -10^-3 were drawn over each other. Mistake,
    seen failing: the linear range at the slowest speed (the labels' boxes overlap)."""
    rng = np.random.default_rng(7)
    t = T0 + np.arange(20001) * 0.01  # 200 s at 100 Hz
    tt = t - T0
    v = np.where((tt > 60.0) & (tt < 65.0), 0.0083e-6, 29.8e-6)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(tt))])
    x += rng.normal(0.0, 0.03e-6, t.size)
    rec = LabRecord(source="synthetic.txt", time=t, load_point=x, load_velocity=None,
                    friction=0.6 + 0.01 * np.sin(tt), normal_stress=None, normal_unit="Pa",
                    columns={}, first_line=0)
    segs = [SimpleNamespace(t_start=T0 + a, t_end=T0 + b, velocity=w, start_placed=True)
            for a, b, w in ((0.0, 60.0, 29.8e-6), (60.0, 65.0, 0.0083e-6),
                            (65.0, 200.0, 29.8e-6))]
    fig, info = plot_record(rec, segs, None)
    ax = fig.axes[info.panels.index("velocity")]
    assert ax.get_yscale() == "symlog"
    assert ax.yaxis.get_transform().linthresh == pytest.approx(1e-3, rel=1e-12)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)
    lo, hi = ax.get_ylim()
    boxes = sorted((lab.get_window_extent(renderer) for lab in ax.yaxis.get_ticklabels()
                    if lab.get_visible() and lab.get_text()
                    and lo <= lab.get_position()[1] <= hi), key=lambda b: b.y0)
    assert len(boxes) >= 4
    for a, b in zip(boxes[:-1], boxes[1:], strict=True):
        assert a.y1 <= b.y0, (a, b)
