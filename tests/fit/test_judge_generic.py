"""``judge_step`` (fit/identify.py) at a generic point, each number by its definition: a
down-step on a non-uniform clock starting at 1000 s; ``a - b``'s interval by the delta method
(``var = a^2 s_a^2 + b^2 s_b^2 - 2 a b c_ab`` in ln a, ln b), ``b/Dc``'s in ``ln(b/Dc)``
(``exp(+-z s)``, ``s^2 = s_b^2 + s_dc^2 - 2 c_b,dc``), the stiffness's interval in ``ln k``; and
the edges: a span of exactly 10 is identified, the lower end of Dc's range is one sample's
slip at the velocity after the change, a window of exactly 3 Dc of slip is not short."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction.fit.identify import MAX_SPAN, SHORT_DC, judge_step
from dryfriction.fit.models import ParamSpec
from dryfriction.records.data import SeriesData

SPECS = [ParamSpec("a", "", True, 1e-6, 1.0), ParamSpec("b", "", True, 1e-6, 1.0),
         ParamSpec("dc", "m", True, 1e-12, 1.0), ParamSpec("stiffness", "1/m", True, 1.0, 1e10)]
Z = 1.96


def _data() -> SeriesData:
    # 4 um/s, then 1.5 um/s from t = 1100 s; after the change samples 0.5 s and 2 s apart
    t = np.concatenate([1000.0 + np.arange(0.0, 100.0, 1.0),
                        1100.0 + np.cumsum(np.tile([0.5, 2.0], 60)) - 0.5])
    return SeriesData(t, np.where(t < 1100.0, 4e-6, 1.5e-6), np.zeros(t.size))


def _row(val, lohi=None):
    row = {}
    for s in SPECS:
        row[s.name] = val[s.name]
        row[f"sigma_{s.name}"] = 0.1 * val[s.name]
        lo, hi = (lohi or {}).get(s.name, (val[s.name] / 1.5, val[s.name] * 1.5))
        row[f"{s.name}_lo"], row[f"{s.name}_hi"] = lo, hi
    row["a_minus_b"], row["sigma_a_minus_b"] = val["a"] - val["b"], 0.0
    return row


VAL = {"a": 0.0071, "b": 0.0093, "dc": 1.3e-5, "stiffness": 4200.0}


def test_combinations_by_the_delta_method() -> None:
    # mistakes: the covariance term's sign, the gradient without the values (ln p fitted),
    # the ratio's interval linear instead of in ln(b/Dc), the stiffness's on the linear scale
    se = np.array([0.04, 0.06, 0.09, 0.05])
    corr = np.eye(4)
    corr[0, 1] = corr[1, 0] = 0.7
    corr[1, 2] = corr[2, 1] = 0.8
    cov = corr * np.outer(se, se)
    theta = np.log([VAL[s.name] for s in SPECS])
    row = _row(VAL)
    words = judge_step(row, SPECS, theta, cov, False, Z, _data())
    assert words == []
    a, b = VAL["a"], VAL["b"]
    s_amb = math.sqrt(a * a * se[0] ** 2 + b * b * se[1] ** 2 - 2 * a * b * cov[0, 1])
    assert (row["a_minus_b_lo"], row["a_minus_b_hi"]) == pytest.approx(
        (a - b - Z * s_amb, a - b + Z * s_amb), rel=1e-12)
    s_r = math.sqrt(se[1] ** 2 + se[2] ** 2 - 2 * cov[1, 2])
    r = b / VAL["dc"]
    assert (row["b_over_dc"], row["b_over_dc_lo"], row["b_over_dc_hi"]) == pytest.approx(
        (r, r * math.exp(-Z * s_r), r * math.exp(Z * s_r)), rel=1e-12)
    assert (row["stiffness_lo"], row["stiffness_hi"]) == pytest.approx(
        (4200.0 * math.exp(-Z * 0.05), 4200.0 * math.exp(Z * 0.05)), rel=1e-12)
    # slip after the change: 1.5 um/s over the samples after it (from t = 1100 s)
    d = _data()
    i = int(np.searchsorted(d.t, 1100.0))
    assert row["slip_after"] == pytest.approx(1.5e-6 * (d.t[-1] - d.t[i]), rel=1e-12)


def test_edges_span_ten_dc_range_and_short_window() -> None:
    assert (MAX_SPAN, SHORT_DC) == (10.0, 3.0)
    d = _data()
    theta = np.log([VAL[s.name] for s in SPECS])
    cov = np.diag([0.04, 0.06, 0.09, 0.05]) ** 2
    # dc's interval spanning exactly 10: identified; a hair more: not
    row = _row(VAL, {"dc": (4e-6, 4e-6 * 10.0)})  # hi/lo == 10.0 exactly in floating point
    assert judge_step(row, SPECS, theta, cov, False, Z, d) == []
    row = _row(VAL, {"dc": (4e-6, 4e-6 * 10.0001)})
    assert "not_identified:dc" in judge_step(row, SPECS, theta, cov, False, Z, d)
    # the lower end of Dc's range: the shortest interval after the change (0.5 s) times the
    # velocity after it (1.5 um/s) = 0.75 um (mistakes: the velocity before, 4 um/s: 2 um; the
    # interval before the change, 1 s)
    rlo = 0.5 * 1.5e-6
    row = _row(VAL, {"dc": (rlo * 1.001, rlo * 9.0)})
    assert judge_step(row, SPECS, theta, cov, False, Z, d) == []
    row = _row(VAL, {"dc": (rlo * 0.999, rlo * 9.0)})
    words = judge_step(row, SPECS, theta, cov, False, Z, d)
    assert "not_identified:dc" in words
    assert f"leaves the range [{rlo:.3g}," in " ".join(row["notes"])
    # short window: slip after the change under 3 Dc; exactly 3 Dc is not short
    probe = _row(VAL)
    judge_step(probe, SPECS, theta, cov, False, Z, d)
    slip = probe["slip_after"]  # as judge_step computes it (checked against 1.5 um/s above)
    # a Dc with 3 Dc == slip exactly in floating point (slip/3 may be one unit off)
    exact = next(c for c in (slip / 3.0, np.nextafter(slip / 3.0, 0.0),
                             np.nextafter(slip / 3.0, 1.0)) if 3.0 * c == slip)
    for dc, short in ((float(exact), False), (slip / 2.99, True)):
        val = dict(VAL, dc=dc)
        row = _row(val, {"dc": (dc / 2.0, dc * 2.0)})
        th = np.log([val[s.name] for s in SPECS])
        assert ("short_window" in judge_step(row, SPECS, th, cov, False, Z, d)) is short, dc


def test_an_interval_reaching_zero_is_not_identified_in_one_note() -> None:
    """A fit to noise can give an interval whose lower end is 0 (a parameter fitted on a linear
    scale, or a robust interval clipped at 0): the note says the interval reaches 0 instead of
    dividing by it (a new user's record of pure noise stopped on a ZeroDivisionError here)."""
    d = _data()
    theta = np.log([VAL[s.name] for s in SPECS])
    cov = np.diag([0.04, 0.06, 0.09, 0.05]) ** 2
    row = _row(VAL, {"b": (0.0, 0.02)})
    words = judge_step(row, SPECS, theta, cov, False, Z, d)
    assert "not_identified:b" in words
    note = [n for n in row["notes"] if n.startswith("b = ")]
    assert len(note) == 1 and "[0, 0.02] reaches 0 or below" in note[0]
    assert math.isnan(row["b"])


@pytest.mark.parametrize("var_k", [0.0, -4.0e-3])
def test_a_degenerate_variance_is_no_interval(var_k: float) -> None:
    """userfixA: a covariance that gives the stiffness a variance of 0 or below (a robust
    sandwich that is not positive semidefinite) is no measurement. The stiffness gets no
    interval and ``not_identified:stiffness``, and 'what the data fix' leaves it out. The
    mistake it is for: the variance clipped to 0, which printed a new user's noise record's
    k as ``150.1 [150.1, 150.1]`` (a zero-width interval inside the physical range and
    within a decade, so 'identified')."""
    d = _data()
    theta = np.log([VAL[s.name] for s in SPECS])
    cov = np.diag([0.04, 0.06, 0.09, 0.05]) ** 2
    cov[3, 3] = var_k
    row = _row(VAL)
    words = judge_step(row, SPECS, theta, cov, False, Z, d)
    assert "not_identified:stiffness" in words
    assert math.isnan(row["stiffness_lo"]) and math.isnan(row["stiffness_hi"])
    assert math.isnan(row["stiffness"])
    fixed = [n for n in row["notes"] if n.startswith("what the data fix")]
    assert fixed and "stiffness" not in fixed[0]
    # the same for a - b: a zero variance of the combination is no interval either
    cov0 = np.diag([0.04, 0.06, 0.09, 0.05]) ** 2
    cov0[0, 0] = cov0[1, 1] = cov0[0, 1] = cov0[1, 0] = 0.0
    row = _row(VAL)
    judge_step(row, SPECS, theta, cov0, False, Z, d)
    assert math.isnan(row["a_minus_b_lo"]) and math.isnan(row["a_minus_b"])


def test_a_zero_width_interval_is_not_identified() -> None:
    """userfixA: an interval with ``lo == hi`` (a profile or covariance that collapsed) is
    not a measurement: ``not_identified`` with a note that says so (mistake: the span test
    ``hi/lo <= 10`` alone, which a zero width passes)."""
    d = _data()
    theta = np.log([VAL[s.name] for s in SPECS])
    cov = np.diag([0.04, 0.06, 0.09, 0.05]) ** 2
    row = _row(VAL, {"b": (VAL["b"], VAL["b"])})
    words = judge_step(row, SPECS, theta, cov, False, Z, d)
    assert "not_identified:b" in words
    note = [n for n in row["notes"] if n.startswith("b = ")]
    assert len(note) == 1 and "zero width" in note[0]


def test_no_transient_leaves_the_stiffness_unidentified_too() -> None:
    """userfixA: a noise record's step (white noise displacement and friction, one change
    given by --segments) printed "what the data fix (95 %): ... stiffness = 13.76 [5.227,
    36.2]" from a fit no better than a straight line. k enters only through the transient,
    so without one it is no more identified than a, b, Dc, whatever its interval (here a
    clean one, within a decade and the physical range). Mistake: the transient test applied
    to a, b, Dc only."""
    d = _data()
    theta = np.log([VAL[s.name] for s in SPECS])
    cov = np.diag([0.04, 0.06, 0.09, 0.05]) ** 2
    row = _row(VAL)
    words = judge_step(row, SPECS, theta, cov, False, Z, d,
                       "the fit is no better than a straight line (F test, p = 0.28)")
    assert {f"not_identified:{n}" for n in ("a", "b", "dc", "stiffness")} <= set(words)
    assert math.isnan(row["stiffness"])
    fixed = [n for n in row["notes"] if n.startswith("what the data fix")]
    assert fixed and "stiffness" not in fixed[0]
    # with a transient the same interval identifies it
    row = _row(VAL)
    assert judge_step(row, SPECS, theta, cov, False, Z, d) == []
