"""The experiment summary figure (plots/summary.py) read back from its artists at generic
values: x in um/s, Dc in um, each bar from the row's own interval (none on a side the row does
not give), one container per level labelled with the level's mean normal stress (in kN for a
force), the legend in level order, and the x range padded to a factor 2 each way only when
the velocities span less than 3."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.plots.summary import MARKERS, plot_experiment_summary


def _row(index, level, normal, v_after, a, b, dc, unit="Pa", **kw):
    r = {"index": index, "kind": "step", "normal_level": level, "normal": normal,
         "normal_unit": unit, "v_after": v_after, "intervals": "hac", "errors": "hac",
         "flags": "", "a": a, "b": b, "a_minus_b": a - b, "dc": dc}
    for n, w in (("a", 0.001), ("b", 0.0015), ("a_minus_b", 0.002), ("dc", 3e-6)):
        r[f"{n}_lo"], r[f"{n}_hi"] = r[n] - w, r[n] + 2 * w  # asymmetric intervals
    r.update(kw)
    return r


ROWS = [_row(0, 0, 10.1e6, 2.3e-6, 0.0112, 0.0131, 21e-6),
        _row(1, 1, 20.2e6, 7.1e-6, 0.0093, 0.0074, 17e-6, dc_lo=math.nan),
        _row(2, 1, 20.6e6, 23e-6, 0.0101, 0.0097, 33e-6)]


def _bars(cont):
    """(x, y, lower end, upper end) of an errorbar container's points."""
    line, _, (bars, *_) = cont
    segs = np.array(bars.get_segments())
    return (np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float),
            segs[:, 0, 1], segs[:, 1, 1])


def test_points_bars_units_and_levels_read_back() -> None:
    # mistakes: v in m/s (or mm/s), Dc in m, the bar from the value's other side, a bar drawn
    # to NaN or to 0 where the interval is not given, the label of a level's first step
    fig, axes = plot_experiment_summary(ROWS)
    dc = axes[3]
    assert "[µm]" in dc.get_ylabel() and "[µm/s]" in axes[2].get_xlabel()
    (c0, c1) = dc.containers
    assert (c0.get_label(), c1.get_label()) == ("10.1 MPa", "20.4 MPa")  # the mean, 20.4
    x, y, lo, hi = _bars(c1)
    np.testing.assert_allclose(x, [7.1, 23.0], rtol=1e-12)
    np.testing.assert_allclose(y, [17.0, 33.0], rtol=1e-12)
    np.testing.assert_allclose(lo, [17.0, 30.0], rtol=1e-12)  # NaN lower end: no bar below
    np.testing.assert_allclose(hi, [23.0, 39.0], rtol=1e-12)
    x, y, lo, hi = _bars(axes[0].containers[0])  # a - b of level 0
    assert (x[0], y[0]) == pytest.approx((2.3, 0.0112 - 0.0131), rel=1e-12)
    assert (lo[0], hi[0]) == pytest.approx((0.0112 - 0.0131 - 0.002, 0.0112 - 0.0131 + 0.004),
                                           rel=1e-12)
    assert c0[0].get_marker() == MARKERS[0] and c1[0].get_marker() == MARKERS[1]
    assert [t.get_text() for t in fig.legends[0].get_texts()] == ["10.1 MPa", "20.4 MPa"]
    # a - b's zero line; the velocities span 10: not padded to a factor 2
    assert any(list(ln.get_ydata()) == [0.0, 0.0] for ln in axes[0].lines)
    assert axes[0].get_xlim() != pytest.approx((2.3 / 2.0, 23.0 * 2.0), rel=1e-6)


def test_narrow_velocity_range_padded_by_two_each_way_and_forces_in_kn() -> None:
    # velocities 4.0 and 11.0 um/s span 2.75 < 3: limits 2.0 and 22.0 (mistakes: a factor 10,
    # the test on the span reversed); a normal force in N is labelled in kN
    rows = [_row(0, 0, 5200.0, 4.0e-6, 0.011, 0.013, 2e-5, unit="N"),
            _row(1, 0, 5400.0, 11.0e-6, 0.011, 0.012, 3e-5, unit="N")]
    _, axes = plot_experiment_summary(rows)
    assert axes[0].get_xlim() == pytest.approx((2.0, 22.0), rel=1e-12)
    assert axes[1].containers[0].get_label() == "5.3 kN"
    # a span of 3 exactly is left to matplotlib (the rule is "less than 3")
    rows[1] = _row(1, 0, 5400.0, 12.0e-6, 0.011, 0.012, 3e-5, unit="N")
    _, axes = plot_experiment_summary(rows)
    assert axes[0].get_xlim() != pytest.approx((2.0, 24.0), rel=1e-6)
