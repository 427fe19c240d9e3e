"""``fit.steps.series_windows`` on a record whose time starts at 7.5 s on a non-uniform grid,
with a down-step, a hold and a hold at the very end (issue 25, strengthen6B). Expected
windows written by hand from the docstring: from halfway through the previous stretch to the
end of the stretch after the change; ``t_change`` and ``hold`` in the series' time."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.fit.steps import series_windows
from dryfriction.records.data import SeriesData


def test_windows_on_a_shifted_non_uniform_record() -> None:
    v = np.r_[np.full(6, 2e-6), np.full(6, 5e-7), np.zeros(4), np.full(6, 5e-7), np.zeros(4)]
    dt = 0.1 + 0.05 * np.arange(v.size) % 0.3
    t = 7.5 + np.r_[0.0, np.cumsum(dt[:-1])]
    w = series_windows(SeriesData(t, v, np.zeros(v.size)))
    got = [(x.index, x.kind, x.i_start, x.i_end, x.v_before, x.v_after) for x in w]
    assert got == [(0, "step", 3, 12, 2e-6, 5e-7),          # a down-step
                   (1, "shs", 9, 22, 5e-7, 5e-7)]           # hold [12, 16) and reload
    # the final hold [22, 26) gives no window: nothing slides after it (as slice_steps)
    assert [x.t_change for x in w] == pytest.approx([t[6], t[12]], rel=1e-15)
    assert [x.hold for x in w] == pytest.approx([0.0, t[16] - t[12]], abs=1e-15)
    assert w[1].hold > 0.0


def test_a_final_hold_gives_no_window_at_any_grid() -> None:
    """A series that slides at two speeds and ends in a hold has one window, the step between
    the speeds, ending where the hold starts' stretch ends; a single slide then a hold has
    none."""
    v = np.r_[np.full(6, 3e-7), np.full(8, 1.2e-6), np.zeros(3)]
    t = 40.0 + 0.25 * np.arange(v.size)
    w = series_windows(SeriesData(t, v, np.zeros(v.size)))
    assert [(x.kind, x.i_start, x.i_end, x.v_before, x.v_after) for x in w] == [
        ("step", 3, 14, 3e-7, 1.2e-6)]
    assert w[0].t_change == pytest.approx(t[6], rel=1e-15)
    assert series_windows(SeriesData(t[6:], v[6:], np.zeros(v.size - 6))) == ()


def test_noise_estimates_from_their_definitions_and_size_edges() -> None:
    """``steady_noise``: rms about the least-squares line with n - 2 dof (here by lstsq on a
    time axis far from 0); ``white_noise``: 1.4826 MAD of the first differences over sqrt 2;
    nan below 4 and 3 samples respectively."""
    from dryfriction.fit.steps import steady_noise, white_noise

    t = 1.0e3 + np.array([0.0, 0.4, 1.1, 1.3, 2.2, 3.0, 3.1])
    mu = np.array([0.61, 0.63, 0.60, 0.66, 0.62, 0.67, 0.64])
    X = np.c_[np.ones_like(t), t - t.mean()]
    r = mu - X @ np.linalg.lstsq(X, mu, rcond=None)[0]
    assert steady_noise(t, mu) == pytest.approx(np.sqrt(r @ r / (t.size - 2)), rel=1e-9)
    assert np.isnan(steady_noise(t[:3], mu[:3]))
    assert np.isfinite(steady_noise(t[:4], mu[:4]))
    d = np.diff(mu)
    want = 1.4826 * np.median(np.abs(d - np.median(d))) / np.sqrt(2.0)
    assert white_noise(mu) == pytest.approx(want, rel=1e-12)
    assert np.isnan(white_noise(mu[:2]))
    assert white_noise(mu[:3]) == pytest.approx(
        1.4826 * np.median(np.abs(d[:2] - np.median(d[:2]))) / np.sqrt(2.0), rel=1e-12)
