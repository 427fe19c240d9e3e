"""``analysis.interface_sweep.catalogue_summary``: the sweep columns the direct comparison with
``dryfriction simulate`` does not reach, each from its definition on the events detected here
(issue 25, strengthen7B): ``mean_slip_spanning`` (the mean over the system-spanning events
only), ``moment_alpha_err = (alpha - 1)/sqrt(n)`` and ``moment_n`` (the positive moments),
``precursor_p`` and ``precursor_trend`` (Spearman's test of the precursors from the loaded
edge, ``edge_gap`` 1 by default), ``n_elements`` and ``duration`` (the run's last time)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.analysis.catalogue import precursor_trend, precursors
from dryfriction.analysis.fronts import (
    detect_events,
    event_threshold,
    from_result,
    interface_loaded_edge,
    interface_normal_load,
)
from dryfriction.analysis.interface_sweep import TREND_CODES, catalogue_summary
from dryfriction.io.protocol import parse_protocol

PROTOCOL = """
[model]
alpha = 0.12
eps = 0.045

[ensemble]
traps_per_a0 = 40
layout = "random"
seed = 7
initial = "rest"

[interface]
n_elements = 4
coupling = 2.9
mass = 1.1
damping = 0.03
normal_spread = 0.1

[drive]
kind = "side"
edge_stiffness = 0.6
stiffness = 0.0
segments = [{velocity = 0.0, duration = 50.0}, {velocity = 0.023, duration = 1450.0}]

[output]
every = 2.1
"""


def test_the_remaining_columns_from_their_definitions() -> None:
    res = parse_protocol(PROTOCOL).run()
    got = catalogue_summary(res)
    st = from_result(res)
    events = detect_events(st, event_threshold(res, None), min_elements=1)
    spanning = [e for e in events if e.spanning]
    assert spanning and len(spanning) < len(events), "the test needs both kinds"
    assert got["mean_slip_spanning"] == pytest.approx(
        np.mean([e.mean_slip for e in spanning]), rel=1e-12)
    assert got["mean_slip_spanning"] != pytest.approx(got["mean_slip"], rel=1e-6)
    moments = np.array([e.moment for e in events])
    n = int(np.sum(moments > 0))
    assert got["moment_n"] == n >= 2
    assert got["moment_alpha_err"] == pytest.approx((got["moment_alpha"] - 1) / math.sqrt(n),
                                                    rel=1e-12)
    edge = interface_loaded_edge(res)
    assert edge == "left"
    pre = precursors(events, st, interface_normal_load(res), edge=edge, edge_gap=1)
    trend = precursor_trend(pre)
    assert got["precursors"] == trend.n
    if math.isnan(trend.p_value):
        assert math.isnan(got["precursor_p"])
    else:
        assert got["precursor_p"] == pytest.approx(trend.p_value, rel=1e-12)
    assert TREND_CODES[int(got["precursor_trend"])] == trend.grows.replace(" ", "_")
    assert got["n_elements"] == 4.0
    assert got["duration"] == pytest.approx(1500.0, rel=1e-12)
    assert got["duration"] == float(res.t[-1])
