"""Issue 30 item 3, one machine: the record's stiffness from its elastic loadings (the reload
after a hold) together with the steps' free fits (:mod:`dryfriction.fit.elastic`), and the
coverage of a, b, Dc with k taken from the record.

Synthetic records from the independent solver of ``tests/lab_synth.py`` (SciPy Radau on
``(tau, theta)``): k = 3000 /m, a = 0.006, b = 0.009, Dc = 20 um.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from dryfriction.fit.elastic import loading_segments
from dryfriction.fit.onemachine import fit_steps_one_machine
from dryfriction.fit.steps import fit_steps, step_covariance
from dryfriction.records.data import SeriesData

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from lab_synth import Truth, synth_program, synth_record  # noqa: E402

SHS = [(1e-6, 300.0), (0.0, 100.0), (1e-6, 300.0), (0.0, 300.0), (1e-6, 300.0)]


@pytest.mark.slow
def test_reload_slopes_hold_the_machine_stiffness():
    """Two reloads a record, four records with red noise (AR(1), rho = 0.9): the slope's
    95 % interval holds k in at least 7 of 8 (measured 8 of 8; the slope is low by about
    1.5 % as the slider creeps). With the noise's scale and correlation read from the
    reload's own twenty-odd residuals instead of the steady part, 4 of 8 held it: this test
    caught that.
    A slope against time instead of load-point displacement (1e6 times off) fails too."""
    tr = Truth(rho=0.9)
    hits, total = 0, 0
    for seed in range(4):
        t, v, mu, _ = synth_program(tr, SHS, 0.25, seed=seed)
        loads = loading_segments(SeriesData(t, v, mu))
        assert [ld["kind"] for ld in loads] == ["reload", "reload"]
        for ld in loads:
            total += 1
            hits += ld["stiffness_lo"] <= tr.stiffness <= ld["stiffness_hi"]
            assert abs(ld["stiffness"] / tr.stiffness - 1.0) < 0.1
    assert hits >= 7, (hits, total)


def test_a_steady_start_is_no_loading():
    """A record that starts in steady sliding has no initial loading, and a step without
    a hold no reload: no slope is read, whichever way the slip trend goes (a rising trend
    of 40 /m was taken for an initial loading by the first rule, a rise of 20x the noise
    alone, and flagged the steps of tests/fit/test_identify.py k_inconsistent)."""
    for trend in (-8.0, 40.0):
        t, v, mu, _ = synth_program(Truth(trend=trend), [(1e-6, 300.0), (3e-6, 100.0)],
                                    0.25, seed=1)
        assert loading_segments(SeriesData(t, v, mu)) == [], trend


def test_one_machine_counts_the_reload():
    """A slide-hold-slide and a step (two windows) and one reload: the record's k comes
    from the two free fits and the reload, holds the truth, and every step holds it."""
    tr = Truth(rho=0.9)
    t, v, mu, _ = synth_program(tr, [(1e-6, 300.0), (0.0, 100.0), (1e-6, 300.0),
                                     (3e-6, 100.0)], 0.25, seed=0)
    res = fit_steps_one_machine(SeriesData(t, v, mu, source="shs"))
    k = res.stiffness
    assert k is not None and k["steps"] == [0, 1]
    assert [ld["used"] for ld in k["loadings"]] == [True]
    assert k["lo"] <= tr.stiffness <= k["hi"]
    assert all(r["stiffness"] == k["value"] for r in res.rows)
    assert any("elastic loading" in n for n in res.notes)


@pytest.mark.slow
def test_coverage_with_k_from_the_record():
    """Issue 30's "done when": the coverage of a, b, Dc on red-noise records (AR(1),
    rho = 0.98; the records of fit/test_steps.py::test_coverage_with_correlated_noise) holds
    with k taken from the record (--stiffness record), its error carried into a, b, Dc:
    >= 90 % of 24 here (measured 23 of 24; on 40 records, ``python -m benchmarks
    bench_k_coverage 0:40 lab_red``: a, b, Dc 80, 72, 80 of 80, the score HAC alone with k
    taken as exact 80, 67, 80). Caught: the held k's error left out of the table (the
    one-machine fit not passing ``held``)."""
    tr = Truth(rho=0.98)
    hits = total = 0
    for seed in range(4):
        t, v, mu, _ = synth_record(tr, [1e-6, 3e-6, 1e-6], duration_slip=300e-6,
                                   dt_per_um=0.5, seed=100 + seed)
        res = fit_steps_one_machine(SeriesData(t, v, mu, source=f"red {seed}"))
        assert res.stiffness is not None
        for r, f, d in zip(res.rows, res.fits, res.data, strict=True):
            assert r["stiffness"] == res.stiffness["value"]
            if seed == 0:  # the held k's error is in the table: not the fit's own covariance
                own = step_covariance(f, d).used.stderr
                names = [s.name for s in step_covariance(f, d).specs]
                assert max(abs(r[f"sigma_{p}"] / (r[p] * own[names.index(p)]) - 1.0)
                           for p in ("a", "b", "dc")) > 1e-3, r
            for p in ("a", "b", "dc"):
                total += 1
                hits += r[f"{p}_lo"] <= getattr(tr, p) <= r[f"{p}_hi"]
    assert hits >= 0.9 * total, (hits, total)


def test_free_fits_unchanged_by_the_loadings():
    """The steps' own free fits do not see the loadings: only the record's k does."""
    t, v, mu, _ = synth_program(Truth(), SHS[:3], 0.25, seed=2)
    res = fit_steps(SeriesData(t, v, mu))
    assert res.rows[0]["stiffness"] > 0 and "k_inconsistent" not in res.rows[0]["flags"]


@pytest.mark.slow
def test_held_k_moves_a_b_dc_as_refits_do():
    """The two-step correction's ``G = d(ln a, ln b, ln Dc)/d ln k`` of a step with the
    record's k held (the linearisation :func:`dryfriction.fit.statistics.
    held_parameter_covariance` uses, from the Jacobian at the optimum) against two refits of
    that step with k held 5 % above and below (an independent route: nonlinear fits), on a
    red-noise record (seed 100): within 25 % for each of a, b, Dc whose move is more than
    1e-3 in ln p (measured: a 0.1058 against 0.1047, b 0.0716 against 0.0708; Dc moves
    less). Caught: the Jacobian's column of another parameter taken for k (the trend's: a's
    G 0.026)."""
    from dataclasses import replace

    import numpy as np

    from dryfriction.fit.problem import Problem
    from dryfriction.fit.statistics import held_parameter_covariance

    tr = Truth(rho=0.98)
    t, v, mu, _ = synth_record(tr, [1e-6, 3e-6, 1e-6], duration_slip=300e-6, dt_per_um=0.5,
                               seed=100)
    data = SeriesData(t, v, mu, source="held k")
    res = fit_steps_one_machine(data)
    assert res.stiffness is not None
    r, d, k = res.fits[0], res.data[0], float(res.stiffness["value"])
    mk = replace(r.fitted_model, stiffness="fit")
    specs = list(mk.parameters(frozenset({"series"})))
    val = {**{p.name: p.value for p in r.parameters}, "stiffness": k}
    theta = np.array([s.to_internal(val[s.name]) for s in specs])
    names = [s.name for s in specs]
    J = Problem(mk, [d], specs, {}).jacobian(theta)
    jk = names.index("stiffness")
    others = [n for n in names if n != "stiffness"]
    g = np.sqrt(np.diag(held_parameter_covariance(J, np.eye(len(names)), jk, 1.0, 0.0)))
    moved = [fit_steps(data, stiffness=k * np.exp(s)).rows[0] for s in (0.05, -0.05)]
    checked = 0
    for p in ("a", "b", "dc"):
        fd = abs(np.log(moved[0][p] / moved[1][p])) / 0.1
        if fd * 0.05 > 1e-3:
            checked += 1
            assert abs(g[others.index(p)] / fd - 1.0) < 0.25, (p, g[others.index(p)], fd)
    assert checked >= 2
