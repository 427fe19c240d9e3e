"""Issue 30: the machine stiffness's 95 % interval under red friction noise. ``k`` is fixed
by ~0.2 s of data right after the change, where red noise is strongly correlated; its
standard error comes from :func:`dryfriction.fit.statistics.time_hac_covariance` (the
residuals' autocovariance on a time lag), the others' from the score HAC as before.
The coverage study is ``benchmarks/bench_k_coverage.py``.
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


def test_stiffness_interval_is_not_the_score_hac_one():
    """Two basalt-like records with red friction noise (seeds 1, 2): k's standard error is
    >= 1.8x the score HAC's (measured 2.7x and 3.3x; the score HAC's 95 % interval missed
    the truth in 14 of 20 such records), the interval holds the true 7000 /m (ln k off by
    0.14 and 0.06, standard errors 0.14 and 0.14), and a, b, Dc keep the score HAC's
    standard errors. Caught: k left on the score HAC (ratio 1)."""
    from dryfriction.fit.steps import step_covariance

    for seed in (1, 2):
        res, truth = fit_one("basalt_red", seed)
        (ratio,) = _old_ratio(res)
        row = res.rows[0]
        assert ratio >= 1.8, (seed, ratio)
        assert row["stiffness_lo"] <= truth["stiffness"] <= row["stiffness_hi"], (seed, row)
        sc = step_covariance(res.fits[0], res.data[0])
        names = [s.name for s in sc.specs]
        for p in ("a", "b", "dc"):
            j = names.index(p)
            assert sc.used.matrix[j, j] == pytest.approx(sc.robust.matrix[j, j])  # type: ignore[union-attr]
            assert row[f"sigma_{p}"] == pytest.approx(row[p] * math.sqrt(sc.used.matrix[j, j]))


@pytest.mark.slow
def test_stiffness_coverage(runslow: bool):
    """20 basalt-like records each with the generator's red friction noise and with white
    noise: k's interval holds the truth in >= 18 and >= 17 of 20 (measured 19 and 17; the
    score HAC 6 and 13). The white-noise records fall short of 18 (90 %): see the README."""
    if not runslow:
        pytest.skip("the 40-record coverage study runs with --runslow")
    red, white = (coverage(kind, range(20)) for kind in ("basalt_red", "basalt_white"))
    assert red["hits"]["stiffness"] >= 18, red
    assert white["hits"]["stiffness"] >= 17, white


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
