"""Issue 30: the 95 % intervals of a step fit under red friction noise. ``k`` is fixed by
~0.2 s of data right after the change, ``a, b, Dc`` by a second or two, where red noise is
strongly correlated; their standard errors come from
:func:`dryfriction.fit.statistics.local_covariance` (the residuals' autocovariance on a time
lag, floored at the score HAC). The coverage study is ``benchmarks/bench_k_coverage.py``.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))
from benchmarks.bench_k_coverage import _old_ratio, coverage, fit_one  # noqa: E402


@pytest.mark.slow
def test_step_intervals_are_not_the_score_hac_ones():
    """Two basalt-like records with red friction noise (seeds 1, 2): the standard errors of
    k, a, b, Dc are >= 1.8x, 1.8x, 1.8x, 1.4x the score HAC's (measured k 2.5, 3.1; a 2.6,
    3.1; b 3.1, 3.2; Dc 1.6, 1.7: the score HAC's intervals held the truth in 17, 21, 15, 28
    of 40 such records), the intervals hold the truth, and the table's sigmas are the
    covariance's. Caught: k, or a, b, Dc, left on the score HAC (ratio 1)."""
    from dryfriction.fit.steps import step_covariance

    floor = {"stiffness": 1.8, "a": 1.8, "b": 1.8, "dc": 1.4}
    for seed in (1, 2):
        res, truth = fit_one("basalt_red", seed)
        row = res.rows[0]
        sc = step_covariance(res.fits[0], res.data[0])
        names = [s.name for s in sc.specs]
        for p, least in floor.items():
            (ratio,) = _old_ratio(res, p)
            assert ratio >= least, (seed, p, ratio)
            assert row[f"{p}_lo"] <= truth[p] <= row[f"{p}_hi"], (seed, p, row)
            j = names.index(p)
            assert row[f"sigma_{p}"] == pytest.approx(row[p] * float(sc.used.stderr[j]))


@pytest.mark.slow
def test_step_coverage(runslow: bool):
    """40 basalt-like records each with the generator's red friction noise and with white
    noise (``python -m benchmarks bench_k_coverage 0:40``): on red noise the intervals of
    k, a, b, Dc hold the truth in >= 36 of 40 each (measured 36, 37, 38, 39; the score HAC's
    of a, b, Dc 21, 15, 28); on white noise too (measured 37, 38, 38, 36; the score HAC's
    30, 36, 35, 35). Caught: a, b, Dc on the score HAC (red)."""
    if not runslow:
        pytest.skip("the 80-record coverage study runs with --runslow")
    red, white = (coverage(kind, range(40)) for kind in ("basalt_red", "basalt_white"))
    for p in ("stiffness", "a", "b", "dc"):
        assert red["hits"][p] >= 36, red
        assert white["hits"][p] >= 36, white


@pytest.mark.slow
@pytest.mark.ci
def test_change_time_part_against_refits():
    """The measured drive's change-time part of k's error (fit.loadpoint.change_time_effect,
    linearised) against refits of the step with the drive moved by +-sigma of its change time
    (an independent route: two nonlinear fits): within 35 % in ln k. On the basalt-like
    record with white friction noise (seed 0) the part is >= 0.8x the friction noise's
    (measured 0.058 against 0.038) and, added, k's interval holds the true 7000 /m (ln k off
    by 0.077; the noise-only interval, half-width 0.075, missed it). Caught: the part left
    out (the interval misses), the central difference not halved (2x the refits)."""
    import dataclasses

    from dryfriction.fit.engine import fit
    from dryfriction.fit.loadpoint import change_time_effect
    from dryfriction.fit.problem import Problem
    from dryfriction.fit.statistics import time_hac_covariance
    from dryfriction.fit.steps import step_covariance

    res, truth = fit_one("basalt_white", 0)
    r, d, row = res.fits[0], res.data[0], res.rows[0]
    sc = step_covariance(r, d)
    names = [s.name for s in sc.specs]
    j = names.index("stiffness")
    prob = Problem(r.fitted_model, [d], list(sc.specs), {})
    J, res0 = prob.jacobian(sc.theta), prob.residuals(sc.theta)
    part = change_time_effect(
        lambda x: Problem(r.fitted_model, [x], list(sc.specs), {}).residuals(sc.theta), d, J)
    assert part is not None
    noise = float(time_hac_covariance(J, res0, d.t)[0].stderr[j])
    (c,) = [c for c in d.drive.changes if d.t[0] < c.t < d.t[-1]]  # type: ignore[attr-defined]
    start = {p.name: p.value for p in r.parameters}
    moved = []
    for s in (1.0, -1.0):
        dd = dataclasses.replace(d, drive=dataclasses.replace(d.drive, t=d.drive.t + s * c.sigma))  # type: ignore[attr-defined]
        f = fit(dd, r.fitted_model, start=start, multistart=False, profile=False)
        moved.append(math.log({p.name: p.value for p in f.parameters}["stiffness"]))
    refit = 0.5 * abs(moved[0] - moved[1])
    assert abs(part[j] / refit - 1.0) < 0.35, (part[j], refit)
    assert part[j] >= 0.8 * noise, (part[j], noise)
    assert row["stiffness_lo"] <= truth["stiffness"] <= row["stiffness_hi"], row
