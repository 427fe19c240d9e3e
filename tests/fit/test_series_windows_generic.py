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
                   (1, "shs", 9, 22, 5e-7, 5e-7),           # hold [12, 16) and reload
                   (2, "step", 19, 26, 5e-7, 0.0)]          # a final hold: no reload to fit
    assert [x.t_change for x in w] == pytest.approx([t[6], t[12], t[22]], rel=1e-15)
    assert [x.hold for x in w] == pytest.approx([0.0, t[16] - t[12], 0.0], abs=1e-15)
    assert w[1].hold > 0.0
