"""The numbers a step fit reports, against their definitions (issue 25: a reported number
checked by a second route).

steps.csv gives, for each parameter, its standard error ``sigma_<p>`` and its 95 % interval
``[<p>_lo, <p>_hi]``. With the default Wald intervals (``profile=False``) both come from one
covariance, so they must agree by definition: for a parameter fitted in its logarithm (``a``,
``b``, ``Dc``, the stiffness: all positive) the interval is ``p exp(+-z s)`` with ``s`` the
standard error of ``ln p``, and the standard error in the parameter's own units is ``p s``
(the delta method). The mistake this file is for: the standard error of ``ln p`` reported as
that of ``p`` (off by the factor ``p``: 1e-5 for a Dc of 10 um).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import t as student_t

from dryfriction.fit.steps import fit_steps, robust_estimates, step_covariance
from dryfriction.records.data import SeriesData
from lab_synth import Truth, synth_record


@pytest.fixture(scope="module")
def result():  # type: ignore[no-untyped-def]
    t, v, mu, _ = synth_record(Truth(), [1.3e-6, 4.1e-6], duration_slip=500e-6,
                               dt_per_um=0.3, seed=5)
    return fit_steps(SeriesData(t, v, mu, source="synthetic"), profile=False)


@pytest.fixture(scope="module")
def rows(result) -> list[dict]:  # type: ignore[no-untyped-def]
    return result.rows


@pytest.mark.parametrize("name, log", [("a", True), ("b", True), ("dc", True)])
def test_standard_error_and_wald_interval_agree(rows: list[dict], name: str, log: bool):
    r = rows[0]
    p, s, lo, hi = (float(r[k]) for k in (name, f"sigma_{name}", f"{name}_lo", f"{name}_hi"))
    assert all(math.isfinite(x) for x in (p, s, lo, hi)) and lo < p < hi
    z = float(student_t.ppf(0.975, 200))  # the dof are in the thousands: z to 0.5 %
    if log:
        assert hi / p == pytest.approx(p / lo, rel=1e-9)  # symmetric in ln p
        assert s / p == pytest.approx(math.log(hi / lo) / (2.0 * z), rel=0.01)
    else:
        assert hi - p == pytest.approx(p - lo, rel=1e-9)
        assert s == pytest.approx((hi - lo) / (2.0 * z), rel=0.01)


def test_standard_errors_are_in_the_parameters_units(rows: list[dict]):
    # a standard error of ln Dc (order 0.1) read as metres would be 1e4 times Dc
    r = rows[0]
    assert 0.0 < float(r["sigma_dc"]) < float(r["dc"])
    assert np.isfinite(float(r["sigma_a"])) and float(r["sigma_a"]) < 0.5 * float(r["a"])


def test_robust_estimates_are_the_rows_numbers(result) -> None:  # type: ignore[no-untyped-def]
    """:func:`robust_estimates` (what fit.json's ``robust`` block of a trap-model step
    reports) is a second route to the same standard errors and intervals as a step's row."""
    sc = step_covariance(result.fits[0], result.data[0], "hac")
    est = robust_estimates(sc)
    r = result.rows[0]
    for name in ("a", "b", "dc"):
        assert est[name]["value"] == pytest.approx(float(r[name]), rel=1e-12)
        assert est[name]["stderr"] == pytest.approx(float(r[f"sigma_{name}"]), rel=1e-6)
        assert est[name]["lo"] == pytest.approx(float(r[f"{name}_lo"]), rel=1e-6)
        assert est[name]["hi"] == pytest.approx(float(r[f"{name}_hi"]), rel=1e-6)


def test_a_one_step_summary_shows_its_point(rows: list[dict]) -> None:
    """One velocity after the step gave the log axis identical limits: matplotlib's own
    expansion put the point on the panel's edge, hidden under the spine in two panels (seen on
    the shared record). Every point drawn must lie strictly inside its panel's x range."""
    from dryfriction.plots.summary import plot_experiment_summary

    fig, axes = plot_experiment_summary(rows[:1])
    for ax in axes:
        lo, hi = ax.get_xlim()
        for cont in ax.containers:
            x = np.asarray(cont.lines[0].get_xdata(), float)
            assert x.size == 1 and lo < x[0] < hi and math.log(hi / x[0]) > 0.2, ax.get_ylabel()
