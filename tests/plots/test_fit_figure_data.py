"""fit.png (plots/fits.py ``plot_fit``) read back from its artists, on a scripted result (the
drawing is tested, not the fit): for a steady or static data set the model on 200 geometric
points from 1/1.5 of the smallest positive abscissa to 1.5 times the largest, a log axis, the
error bars the data's sigma; for a series the model on the data's own times, sorted; every value
of the title with its unit."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from dryfriction.plots.fits import plot_fit
from dryfriction.records.data import SeriesData, SteadyData


def _result(fn, success=True):
    def predict(d, x=None):
        return fn(d.x if x is None else np.asarray(x, float))

    params = [SimpleNamespace(name="a_minus_b", value=-0.0031, unit=""),
              SimpleNamespace(name="dc", value=2.5e-5, unit="m")]
    return SimpleNamespace(predict=predict, model="rsf", success=success, parameters=params)


def test_steady_model_curve_error_bars_and_title() -> None:
    # mistakes: the curve over the data's range only (or a margin of 2), a linear grid, the
    # error bars of the sorted data matched to the unsorted sigma, the unit left off
    V = np.array([3e-6, 2e-7, 4e-5, 9e-7])  # not sorted
    sigma = np.array([1e-3, 2e-3, 3e-3, 4e-3])
    d = SteadyData(V, 0.6 - 0.003 * np.log(V / 1e-6), sigma, "steady.csv")
    fig, axes = plot_fit(_result(lambda v: 0.61 - 0.0031 * np.log(v / 1e-6)), [d])
    top = axes[0, 0]
    model = next(ln for ln in top.get_lines() if ln.get_label() == "rsf fit")
    xs = np.geomspace(2e-7 / 1.5, 4e-5 * 1.5, 200)
    np.testing.assert_allclose(model.get_xdata(), xs, rtol=1e-12)
    np.testing.assert_allclose(model.get_ydata(), 0.61 - 0.0031 * np.log(xs / 1e-6), rtol=1e-12)
    assert top.get_xscale() == "log"
    bars = top.containers[0]  # the data's errorbar container
    segs = np.array(bars[2][0].get_segments())
    order = np.argsort(V)
    np.testing.assert_allclose(segs[:, 1, 1] - segs[:, 0, 1], 2 * sigma[order], rtol=1e-12)
    assert fig.get_suptitle() == "a_minus_b = -0.0031, dc = 2.5e-05 m"
    assert axes[1, 0].get_xlabel() == "V (m/s)" and top.get_title() == "steady.csv"


def test_series_model_on_the_data_times_and_the_residuals() -> None:
    t = 7.0 + np.linspace(0.0, 10.0, 51)
    d = SeriesData(t, np.where(t < 12.0, 1e-6, 5e-6), 0.6 + 0.002 * np.sin(t), source="s.csv")
    fig, axes = plot_fit(_result(lambda x: 0.6 + 0.001 * np.cos(x), success=False), [d])
    model = next(ln for ln in axes[0, 0].get_lines() if ln.get_label() == "rsf fit")
    np.testing.assert_array_equal(model.get_xdata(), t)
    np.testing.assert_allclose(model.get_ydata(), 0.6 + 0.001 * np.cos(t), rtol=1e-14)
    assert axes[0, 0].get_xscale() == "linear"
    assert axes[1, 0].get_xlabel() == "t (s)"
    assert fig.get_suptitle().endswith("  [NOT CONVERGED]")
    with pytest.raises(ValueError, match="max_points = 7: must be at least 8"):
        plot_fit(_result(np.cos), [d], max_points=7)
    assert plot_fit(_result(np.cos), [d], max_points=8)
