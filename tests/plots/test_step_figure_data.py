"""plot_step's drawn data (dryfriction.plots.steps): on a window whose time does not start at
0 and whose load velocity changes (a down-step), the left column is drawn against the load-point
displacement in µm (integral of v_load written here), the right against t - t_start in s; the
data, the fit, the residual (data - fit) and the others' curves are the arrays given."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from dryfriction.plots.steps import plot_step
from dryfriction.records.data import SeriesData


def test_plot_step_draws_displacement_time_fit_and_residuals() -> None:
    t = 417.3 + np.linspace(0.0, 6.0, 61)  # time does not start at 0
    v = np.where(t - t[0] < 2.5, 3.1e-6, 0.7e-6)  # a down-step at 2.5 s
    mu = 0.6 + 0.01 * np.sin(t)
    data = SeriesData(t=t, v_load=v, mu=mu)
    model = 0.6 + 0.009 * np.sin(t + 0.1)
    trap = 0.6 + 0.008 * np.cos(t)
    row = {"index": 2, "kind": "step", "v_before": 3.1e-6, "v_after": 0.7e-6, "a": 0.01,
           "b": 0.012, "a_minus_b": -0.002, "dc": 1.3e-5, "stiffness": 3.0e3, "rms": 1e-3,
           "flags": ""}
    res = SimpleNamespace(data=[None, None, data], rows=[None, None, row],
                          model_curve=lambda i: model)
    fig, axes = plot_step(res, 2, others={"trap model": trap})
    # the displacement: sum of v dt of the load program, from the window's start, in µm
    tt = t - t[0]
    x_ref = np.where(tt < 2.5, 3.1 * tt, 3.1 * 2.5 + 0.7 * (tt - 2.5))
    for col, xv in ((0, x_ref), (1, tt)):
        top, bot = axes[0, col], axes[1, col]
        pts = top.collections[0].get_offsets()
        np.testing.assert_allclose(pts[:, 0], xv, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(pts[:, 1], mu, rtol=1e-12)
        fit, other = top.get_lines()
        assert fit.get_label() == "fit (rsf)" and other.get_label() == "trap model"
        np.testing.assert_allclose(fit.get_xdata(), xv, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(fit.get_ydata(), model, rtol=1e-12)
        np.testing.assert_allclose(other.get_ydata(), trap, rtol=1e-12)
        r = bot.collections[0].get_offsets()
        np.testing.assert_allclose(r[:, 1], mu - model, rtol=1e-9, atol=1e-15)
        assert bot.get_lines()[0].get_ydata()[0] == 0.0
    assert "µm" in axes[1, 0].get_xlabel() and "t_{start}" in axes[1, 1].get_xlabel()
    assert "residual" == axes[1, 0].get_ylabel()
    # without others the fit is labelled plainly
    _, ax2 = plot_step(res, 2)
    assert [ln.get_label() for ln in ax2[0, 0].get_lines()] == ["fit"]
    assert fig._suptitle.get_text().startswith("step 2 (step): 3.1 -> 0.7 µm/s")


def _window(t0: float, dt: float, n: int, v: tuple[float, float], mu0: float, amp: float,
            index: int) -> tuple[SeriesData, np.ndarray, dict]:
    t = t0 + dt * np.arange(n)
    vel = np.where(t - t0 < 0.4 * dt * n, v[0], v[1])
    mu = mu0 + amp * np.tanh((t - t0 - 0.4 * dt * n) / (0.1 * dt * n)) + 1e-4 * np.sin(7.1 * t)
    model = mu0 + amp * np.tanh((t - t0 - 0.4 * dt * n) / (0.1 * dt * n))
    row = {"index": index, "kind": "step", "v_before": v[0], "v_after": v[1], "a": 0.0073,
           "b": 0.0091, "a_minus_b": -0.0018, "dc": 2.3e-5, "stiffness": 1.7e3, "rms": 1e-4,
           "flags": "b_at_bound" if index else ""}
    return SeriesData(t=t, v_load=vel, mu=mu), model, row


def test_a_figure_redrawn_for_another_step_is_the_new_figure_byte_for_byte() -> None:
    """``plot_step(..., into=fig)`` (the fit command draws a record's steps on one figure): the
    PNG of window 1 drawn into window 0's figure is the PNG of window 1 drawn afresh, though
    the two windows differ in time origin, duration, sample count, velocities and friction
    level (so stale limits, data or title would show); with other labels, a new figure."""
    import io

    from dryfriction.plots.style import save_figure

    w0 = _window(88.0, 0.05, 240, (0.31e-6, 2.9e-6), 0.613, 0.004, 0)
    w1 = _window(1735.5, 0.2, 311, (9.7e-6, 1.1e-6), 0.587, -0.0023, 1)
    res = SimpleNamespace(data=[w0[0], w1[0]], rows=[w0[2], w1[2]],
                          model_curve=lambda i: (w0, w1)[i][1])

    def png(fig: object) -> bytes:
        b = io.BytesIO()
        save_figure(fig, b, "png", 60)
        return b.getvalue()

    first, _ = plot_step(res, 0)
    png(first)  # drawn once, as the fit command saves it before the next step
    again, axes = plot_step(res, 1, into=first)
    assert again is first
    assert png(again) == png(plot_step(res, 1)[0])
    lo, hi = axes[0, 1].get_xlim()
    assert lo < 0.0 and 0.2 * 310 < hi < 0.2 * 310 * 1.1  # the new window's time, not 12 s
    # another label set: not redrawn into
    other, ax2 = plot_step(res, 1, others={"trap model": w1[1]}, into=first)
    assert other is not first
    assert [ln.get_label() for ln in ax2[0, 0].get_lines()] == ["fit (rsf)", "trap model"]


def _two_windows() -> SimpleNamespace:
    w0 = _window(88.0, 0.05, 240, (0.31e-6, 2.9e-6), 0.613, 0.004, 0)
    w1 = _window(1735.5, 0.2, 311, (9.7e-6, 1.1e-6), 0.587, -0.0023, 1)
    return SimpleNamespace(data=[w0[0], w1[0]], rows=[w0[2], w1[2]],
                           model_curve=lambda i: (w0, w1)[i][1])


def test_a_figure_let_go_of_is_collected() -> None:
    """plot_step's bookkeeping of the figures it made keeps none of them alive (a fit of many
    records, or a notebook's loop, must not keep every figure and its pixels)."""
    import gc
    import weakref

    res = _two_windows()
    fig = plot_step(res, 0)[0]
    again = plot_step(res, 1, into=fig)[0]
    ref = weakref.ref(fig)
    del fig, again
    gc.collect()
    assert ref() is None


def test_a_redrawn_figure_is_written_to_path(tmp_path) -> None:  # type: ignore[no-untyped-def]
    res = _two_windows()
    fig, _ = plot_step(res, 0, tmp_path / "a.png")
    again, _ = plot_step(res, 1, tmp_path / "b.png", into=fig)
    assert again is fig
    assert (tmp_path / "a.png").stat().st_size > 0 and (tmp_path / "b.png").stat().st_size > 0


def test_a_figure_changed_since_is_not_redrawn_into() -> None:
    """Drawn on, zoomed or cleared after plot_step made it: a new figure is made and the one
    given is left as it was."""
    res = _two_windows()
    for change in ("line", "zoom", "clear", "text"):
        fig, axes = plot_step(res, 0)
        if change == "line":
            axes[0, 1].axvline(3.0)
        elif change == "zoom":
            axes[0, 1].set_xlim(0.0, 3.0)
        elif change == "text":
            axes[1, 0].text(1.0, 0.0, "note")
        else:
            fig.clear()
        before = [ax.get_xlim() for ax in fig.axes]
        new, new_axes = plot_step(res, 1, into=fig)
        assert new is not fig, change
        assert [ax.get_xlim() for ax in fig.axes] == before, change
        assert new_axes[0, 1].get_xlim()[1] > 60.0  # the new window's 62 s


def test_residuals_all_zero_get_a_new_figure() -> None:
    """A window whose fit is its data (no finite residual but 0): a new figure, whose
    residual panel is scaled about 0 as a new figure's is (a redrawn one read a width of
    1e-21 from the axis line's stale limits)."""
    res = _two_windows()
    exact = SimpleNamespace(data=res.data, rows=res.rows,
                            model_curve=lambda i: res.data[i].mu.copy())
    fig, _ = plot_step(res, 0)
    new, axes = plot_step(exact, 1, into=fig)
    assert new is not fig
    lo, hi = axes[1, 0].get_ylim()
    assert lo < -1e-3 and hi > 1e-3
