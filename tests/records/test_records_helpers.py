"""records helpers called directly (issue 25): lab.apparatus_note on each branch and at its
edges; segmentation.line_fit / rss / prune / refine against least squares written in the test
(numpy.polyfit), a prune on both sides of its threshold; placement.place_changes on a record
with two changes (up, then down: N > 1), the moved and the held boundary, and on a stop with
the servo's relaxation; detection.no_change_message's number by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.records.lab import APPARATUS_V_MAX, APPARATUS_X_MAX, apparatus_note
from dryfriction.records.placement import place_changes
from dryfriction.records.record import LabRecord
from dryfriction.records.segmentation import line_fit, prune, refine, rss, step_gains

# --- lab.apparatus_note -----------------------------------------------------------------------


def _rec(span: float | None, unit: str = "", role: str = "disp", time_unit: str = "s"
         ) -> LabRecord:
    t = np.linspace(3.0, 40.0, 20)
    x = None if span is None else 0.2 + span * (t - t[0]) / (t[-1] - t[0])
    units = {k: u for k, u in (("time", time_unit), (role, unit)) if u}
    return LabRecord("r.txt", t, x, None if x is not None else np.full(20, 1e-6),
                     np.full(20, 0.6), None, "", {"time": "Time", role: "Displ" if
                                                   role == "disp" else "Vel"}, 2, units)


def test_apparatus_note_edges_are_strict() -> None:
    # units written (m): at each limit no note; just above either: one (a velocity down
    # counts by its size)
    assert apparatus_note(_rec(APPARATUS_X_MAX, "m"), [APPARATUS_V_MAX, -APPARATUS_V_MAX]) \
        is None
    assert apparatus_note(_rec(0.3, "m"), [2e-7, -3e-6]) is None
    assert apparatus_note(_rec(0.3, "m"), [1e-6, -APPARATUS_V_MAX * 1.001]) is not None
    assert apparatus_note(_rec(APPARATUS_X_MAX * 1.001, "m"), [1e-6]) is not None
    note = apparatus_note(_rec(1.5, "m"), [2e-6, -0.02, 0.005])
    assert note == ("note: r.txt: load velocities up to 0.02 m/s and 1.5 m of displacement are "
                    "odd for a friction apparatus; column 'Displ' has the unit 'm': is it "
                    "right?")


def test_apparatus_note_names_the_column_and_what_to_give() -> None:
    # no displacement column: the velocity column is named, with um/s
    note = apparatus_note(_rec(None, role="velocity"), [0.5])
    assert note is not None and note.startswith("warning: ")
    assert "--columns velocity=Vel:um/s gives up to 500 nm/s" in note
    assert note.endswith("give the unit with --columns velocity=Vel:UNIT (SI written out, "
                         "e.g. :m, keeps this reading and silences this line)")
    assert "up to 500 mm/s over 0 nm" in note
    # a unit written: asked whether it is right, or (a given program, a plausible span)
    # reminded that --segments is in m/s
    assert apparatus_note(_rec(2.0, "mm"), [1e-6]).endswith(  # type: ignore[union-attr]
        "column 'Displ' has the unit 'mm': is it right?")
    assert apparatus_note(_rec(2.0, "mm"), [1e-6], given=True).endswith(  # type: ignore[union-attr]
        "has the unit 'mm': is it right?")  # the span is odd whatever the program
    assert apparatus_note(_rec(0.3, "mm"), [0.2], given=True).endswith(  # type: ignore[union-attr]
        "--segments takes velocities in m/s (2e-7 for 0.2 um/s)")
    assert apparatus_note(_rec(0.3, "mm"), [0.2]).endswith(  # type: ignore[union-attr]
        "has the unit 'mm': is it right?")  # the default: the program was detected


# --- segmentation ---------------------------------------------------------------------------

RNG = np.random.default_rng(2511)
N = 120
T = np.cumsum(RNG.uniform(0.05, 0.15, N)) + 7.0  # non-uniform, not from 0
K = 71  # the one kink: slope 2.3 before, -0.8 after (a turn down)
XS = np.where(np.arange(N) < K, 2.3 * (T - T[K]), -0.8 * (T - T[K])) + 4.0
XS = XS + RNG.normal(0.0, 0.05, N)


def _rss_by_hand(bounds: list[int]) -> float:
    total = 0.0
    for a, b in zip(bounds[:-1], bounds[1:], strict=True):
        p = np.polyfit(T[a:b], XS[a:b], 1)
        total += float(np.sum((XS[a:b] - np.polyval(p, T[a:b])) ** 2))
    return total


def test_line_fit_and_rss_are_least_squares() -> None:
    a, b = 10, 57
    slope, mean, sxx = line_fit(T[a:b], XS[a:b])
    p = np.polyfit(T[a:b], XS[a:b], 1)
    assert slope == pytest.approx(p[0], rel=1e-10)
    # the intercept at t = mean(t), not at t = 0
    assert mean == pytest.approx(np.polyval(p, T[a:b].mean()), rel=1e-12)
    assert sxx == pytest.approx(float(np.sum((T[a:b] - T[a:b].mean()) ** 2)), rel=1e-12)
    for bounds in ([0, N], [0, 40, K, N], [0, 30, 65, 90, N]):
        assert rss(T, XS, bounds) == pytest.approx(_rss_by_hand(bounds), rel=1e-9)


def test_prune_on_both_sides_of_its_threshold() -> None:
    """A boundary on the straight part (at 35) is dropped when merging its two stretches costs
    less than the threshold, kept when more: the edge is that cost, written by hand."""
    # the cost of a merge is measured on the two stretches beside it only
    cost = _rss_by_hand([0, K]) - _rss_by_hand([0, 35, K])
    assert cost > 0
    assert prune(T, XS, [0, 35, K, N], cost * 1.001, 3, 0.0) == [0, K, N]
    assert prune(T, XS, [0, 35, K, N], cost * 0.999, 3, 0.0)[:3] == [0, 35, K]


def test_prune_replaces_a_short_stretch_across_the_kink_by_one_hinge() -> None:
    # two splits where one would do (at 68 and 75 around the kink at 71): one hinge near it
    out = prune(T, XS, [0, 68, 75, N], 50.0, 3, 0.0)
    assert len(out) == 3 and out[0] == 0 and out[-1] == N and abs(out[1] - K) <= 2
    # the kink itself earns its place whatever the stretches' lengths: kept
    assert prune(T, XS, [0, K, N], 50.0, 3, 0.0) == [0, K, N]
    # with a window, only stretches shorter than twice it are tried
    assert prune(T, XS, [0, 35, K, N], 1e9, 3, 0.0, window=17) == [0, 35, K, N]
    assert len(prune(T, XS, [0, 35, K, N], 1e9, 3, 0.0, window=18)) < 4


def test_refine_moves_a_boundary_to_the_kink_only_when_asked() -> None:
    out = refine(T, XS, [0, 52, N], 3, 0.0)
    assert abs(out[1] - K) <= 2
    assert refine(T, XS, [0, 52, N], 3, 0.0, only={40}) == [0, 52, N]
    assert refine(T, XS, [0, 52, N], 3, 0.0, only={52})[1] == out[1]


# --- placement.place_changes ----------------------------------------------------------------


def _two_changes() -> tuple[np.ndarray, np.ndarray, list[int], np.ndarray]:
    """1.3 -> 2.9 -> 0.7 um/s at 40.3 s and 97.1 s, 8 Hz from 11 s, 0.05 um white noise."""
    rng = np.random.default_rng(77)
    t = 11.0 + np.arange(0, 140.0, 0.125)
    c1, c2 = 40.3, 97.1
    v = np.array([1.3e-6, 2.9e-6, 0.7e-6])
    x = (v[0] * (np.minimum(t, c1) - t[0]) + v[1] * np.clip(t - c1, 0.0, c2 - c1)
         + v[2] * np.maximum(t - c2, 0.0))
    x = x + rng.normal(0.0, 0.05e-6, t.size)
    # guesses 1.6 s late and 1.1 s early
    bounds = [0, int(np.searchsorted(t, c1 + 1.6)), int(np.searchsorted(t, c2 - 1.1)), t.size]
    return t, x, bounds, v


def test_place_changes_moves_each_boundary_to_its_change() -> None:
    t, x, bounds, v = _two_changes()
    scales = np.array([1.0, 4.0, 16.0])
    none = np.zeros(3)  # no wander: the white-noise hinge
    out, places = place_changes(t, x, bounds, v, 0.05e-6, scales, none, none)
    assert out[0] == 0 and out[-1] == t.size and len(out) == 4 and len(places) == 2
    for pl, k, c in zip(places, out[1:3], (40.3, 97.1), strict=True):
        assert pl.index == k
        assert abs(t[k] - c) <= 0.25, (t[k], c)  # the first sample of the new velocity
        assert pl.lo <= c <= pl.hi and pl.hi - pl.lo < 2.0 and not pl.edge
    # the second held where it was guessed; its interval still computed about it
    held, hplaces = place_changes(t, x, bounds, v, 0.05e-6, scales, none, none,
                                  weak=np.array([True, False]))
    assert held[1] == out[1] and held[2] == bounds[2]
    assert hplaces[1].index == bounds[2] and np.isfinite(hplaces[1].lo)


def test_place_changes_a_stop_with_the_servos_relaxation() -> None:
    """2.1 um/s, then a stop at 60.3 s after which the load point creeps on by the servo's
    position error, v tau_r (1 - e^(-(t - t_c)/tau_r)), tau_r = 2 s; a relative wander of 5 %
    (1 s) whose position error stands above the 0.02 um white noise: the stop is placed with
    its relaxation, on the first sample after it (the plain hinge puts it 0.75 s late)."""
    rng = np.random.default_rng(5)
    t = 7.0 + np.arange(0, 120.0, 0.125)
    tc, v1, tr = 60.3, 2.1e-6, 2.0
    x = np.where(t < tc, v1 * (t - t[0]),
                 v1 * (tc - t[0]) + v1 * tr * -np.expm1(-(t - tc) / tr))
    x = x + rng.normal(0.0, 0.02e-6, t.size)
    guess = int(np.searchsorted(t, tc + 3.0))
    out, places = place_changes(t, x, [0, guess, t.size], np.array([v1, 0.0]), 0.02e-6,
                                np.array([1.0, 4.0, 16.0]), np.array([0.05, 0.0, 0.0]),
                                np.zeros(3))
    assert out[1] == int(np.searchsorted(t, tc))
    assert places[0].lo <= tc <= places[0].hi


# --- detection.no_change_message ------------------------------------------------------------


def test_no_change_message_states_the_smallest_change_of_the_two_halves() -> None:
    """One constant velocity (1.3 um/s, 0.05 um white noise, from 3 s): the line's number is
    Z_MIN times the two halves' velocity scatters added in quadrature (the fluctuation model
    at each half's duration, velocity and Sxx, the halves' lines fitted here)."""
    from dryfriction.records.detection import Z_MIN, detect_program, displacement, no_change_message

    rng = np.random.default_rng(31)
    t = 3.0 + 0.2 * np.arange(600)
    x = 1.3e-6 * (t - t[0]) + rng.normal(0.0, 0.05e-6, t.size)
    rec = LabRecord("flat.txt", t, x, None, np.full(t.size, 0.6), None, "",
                    {"time": "t", "disp": "x"}, 2, {"disp": "m"})
    det = detect_program(rec)
    assert len(det.segments) == 1
    xd = displacement(rec)
    h = t.size // 2
    v, d, sxx = [], [], []
    for a, b in ((0, h), (h, t.size)):
        v.append(np.polyfit(t[a:b], xd[a:b], 1)[0])
        d.append(t[b - 1] - t[a])
        sxx.append(float(np.sum((t[a:b] - t[a:b].mean()) ** 2)))
    e = det.fluctuations.scatter(np.array(d), np.array(v), np.array(sxx))
    lim = Z_MIN * math.hypot(e[0], e[1])
    msg = no_change_message(rec, det)
    assert msg.startswith(
        f"flat.txt: no velocity change found above the apparatus' fluctuations of "
        f"{lim * 1e6:.3g} um/s ({Z_MIN:g} times the scatter of the velocities of the record's "
        "two halves): it moves at 1.3 um/s throughout, and a one-velocity record has no "
        "velocity step to fit; if its speed did change, give the program with --segments, "
        "e.g. "), msg
    # userfixB (15): the example is this record's own (it was 0:2e-7,1200:2e-6, outside a
    # 120-s record): a program --segments accepts, inside the record, at its speed
    from dryfriction.records.lab import parse_segments, slice_steps

    example = msg.split("e.g. ")[1].split(" ")[0]
    segs = parse_segments(example, rec)
    assert [s.velocity for s in segs] == pytest.approx([1.3e-6, 1.3e-5], rel=0.01)
    assert 0.3 * 119.8 < segs[1].t_start - t[0] < 0.7 * 119.8
    assert len(slice_steps(rec, segs)) == 1


def test_step_gains_against_least_squares() -> None:
    """``step_gains`` on irregular times from 412.6 s and a y of mixed sign (a line, a step
    of -3.7 at sample 61 and noise): for every candidate step, ``rs**2 / den`` is what the
    step saves of the line's residual sum of squares, by ``np.linalg.lstsq`` on the three
    columns (two routes); the residuals are the line's; the largest gain is at the true
    step. Mistakes: the step not projected off the slope (``den`` without its ``Sxx`` term);
    the sums taken from the sample before ``k``."""
    rng = np.random.default_rng(17)
    t = 412.6 + np.cumsum(rng.uniform(0.03, 0.21, 140))
    y = -2.9 + 0.83 * (t - 412.6) - 3.7 * (np.arange(140) >= 61) + rng.normal(0.0, 0.4, 140)
    ks = np.arange(5, 135, 7)
    ks = np.unique(np.r_[ks, 61])
    r, rs, den = step_gains(t, y, ks)
    line = np.column_stack([np.ones(140), t - t.mean()])
    res0 = y - line @ np.linalg.lstsq(line, y, rcond=None)[0]
    np.testing.assert_allclose(r, res0, atol=1e-10)
    for k, g in zip(ks, rs**2 / den, strict=True):
        a = np.column_stack([line, (np.arange(140) >= k).astype(float)])
        res1 = y - a @ np.linalg.lstsq(a, y, rcond=None)[0]
        assert g == pytest.approx(res0 @ res0 - res1 @ res1, rel=1e-9)
    assert ks[np.argmax(rs**2 / den)] == 61
