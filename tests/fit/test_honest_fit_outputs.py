"""What a fit of the project's CSV files tells the user where the data do not fit the model or
do not fix a parameter (userfixA: a new user's trial). Each test names the mistake it is
for; tests/mutants.py's userfixA block applies them.

* Static friction that falls with hold time contradicts both models (eq. 27's ageing; the
  rate-and-state healing ``b ln(1 + t_w V0/Dc)``, ``b > 0``): the fit says so, with the data's
  own trend ``d mu_s/d ln t_w`` and its interval, in the notes, ``per_dataset[...]["trend"]``,
  ``flags`` and the table's last line.
* A parameter on its search bound is labelled with that bound, in its unit; a profile limit
  reached while another parameter sat on its bound is that bound's, not the data's, and is
  reported open; the table prints a ``+-`` only beside an interval it agrees with.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from dryfriction.cli import main
from dryfriction.fit import fit, fit_static
from dryfriction.fit.statistics import log_slope
from dryfriction.records.data import StaticData
from dryfriction.theory.model import TrapModel
from dryfriction.theory.units import PhysicalScales, static_friction_si

TW = 3.0 * np.geomspace(1.0, 1e4, 6)  # s: 3 s to 8.3 h
SLOPE = -0.0047  # d mu_s / d ln t_w of the falling data (-0.0108 per decade)


def _falling(seed: int, sigma: bool) -> StaticData:
    rng = np.random.default_rng(seed)
    noise = 4e-4
    y = 0.655 + SLOPE * np.log(TW / 3.0) + rng.normal(0.0, noise, TW.size)
    return StaticData(TW, y, np.full(TW.size, noise) if sigma else None, f"falling-{seed}")


def test_log_slope_is_the_weighted_line_numpy_fits() -> None:
    """The measured trend by an independent route: ``np.polyfit`` on ``ln x`` with weights
    ``1/sigma`` and its unscaled covariance (given uncertainties), and its scaled one with
    ``n - 2`` degrees of freedom (estimated noise). Mistakes: ``x`` not logged, weights
    ``1/sigma`` instead of ``1/sigma^2``, ``n - 1`` degrees of freedom."""
    rng = np.random.default_rng(3)
    x = np.geomspace(0.7, 5e3, 9)
    s = rng.uniform(2e-4, 9e-4, x.size)
    y = 0.41 + 0.0061 * np.log(x) + rng.normal(0.0, 1.0, x.size) * s
    got = log_slope(x, y, s)
    coef, cov = np.polyfit(np.log(x), y, 1, w=1.0 / s, cov="unscaled")
    assert got["slope"] == pytest.approx(coef[0], rel=1e-10)
    assert got["stderr"] == pytest.approx(math.sqrt(cov[0, 0]), rel=1e-10)
    lo, hi = got["interval_95"]
    assert (hi - lo) / 2 == pytest.approx(1.959964 * got["stderr"], rel=1e-5)
    got = log_slope(x, y)
    coef, cov = np.polyfit(np.log(x), y, 1, cov=True)  # scaled by RSS/(n - 2)
    assert got["slope"] == pytest.approx(coef[0], rel=1e-10)
    assert got["stderr"] == pytest.approx(math.sqrt(cov[0, 0]), rel=1e-10)
    lo, hi = got["interval_95"]
    assert (hi - lo) / 2 == pytest.approx(2.364624 * got["stderr"], rel=1e-5)  # t(0.975, 7)
    # two points and no uncertainties: a slope, no error
    two = log_slope(np.array([1.0, 10.0]), np.array([0.6, 0.59]))
    assert two["slope"] == pytest.approx(-0.01 / math.log(10.0)) and two["stderr"] is None


@pytest.mark.parametrize("model,kwargs,sigma", [("cv", {}, True), ("cv", {}, False),
                                                ("rsf", {"v0": 3e-6}, False)])
def test_static_friction_falling_with_hold_time_is_said_to_contradict_the_model(
        model: str, kwargs: dict, sigma: bool) -> None:
    """Both models, with and without uncertainties: the flag, the trend with its interval
    holding the true slope, the per-decade figure, and the first note. Mistakes: no check at
    all (the user's report: success, no word), the per-decade factor 10 instead of ln 10."""
    d = _falling(11, sigma)
    r = fit(d, model, profile=False, **kwargs)
    assert f"against_model:{d.source}" in r.flags
    tr = r.per_dataset[0]["trend"]
    assert tr["against_model"] is True and tr["model_allows"] == "growth"
    lo, hi = tr["interval_95"]
    assert lo <= SLOPE <= hi < 0
    assert tr["per_decade"] == pytest.approx(tr["value"] * math.log(10.0), rel=1e-12)
    first = r.notes[0]
    assert first.startswith(f"{d.source}: the data contradict the model: mu_s falls with t_w")
    assert f"{tr['value']:.3g}" in first and f"{tr['per_decade']:.3g} per decade" in first
    assert "grows with hold time" in first


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_rising_or_flat_static_friction_is_not_flagged(seed: int) -> None:
    """Ageing data from the model itself, and flat noise (no trend: its interval holds 0),
    are not flagged. Mistake: the test on the interval's lower end (any slope that might be
    negative flagged) or on the slope alone (noise flagged half the time)."""
    rng = np.random.default_rng(seed)
    up = static_friction_si(TrapModel(eps=0.03), TW, PhysicalScales(1e-6, 1.0, 0.4)) \
        + rng.normal(0.0, 2e-3, TW.size)
    r = fit_static(StaticData(TW, up, None, "up"), "cv", profile=False)
    assert not any(f.startswith("against_model") for f in r.flags)
    assert r.per_dataset[0]["trend"]["against_model"] is False
    flat = 0.6 + rng.normal(0.0, 2e-3, TW.size)
    r = fit_static(StaticData(TW, flat, None, "flat"), "cv", profile=False)
    tr = r.per_dataset[0]["trend"]
    lo, hi = tr["interval_95"]
    if lo < 0 < hi:  # the case this test is for (a slope of either sign, not significant)
        assert tr["against_model"] is False
        assert not any(f.startswith("against_model") for f in r.flags)


def _log_linear(seed: int) -> StaticData:
    # mu_s straight in ln t_w, slightly concave: eq. 27 fits it only with t0 -> 0
    L = np.log(TW / 3.0)
    y = 0.612 + 0.0052 * L - 3e-4 * (L - L.mean()) ** 2 \
        + np.random.default_rng(seed).normal(0.0, 5e-4, TW.size)
    return StaticData(TW, y, None, f"loglin-{seed}")


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1])
def test_a_value_on_its_bound_and_the_limits_it_sets(seed: int) -> None:
    """t0 ends on its 1e-12 s lower bound: labelled ``at lower bound (1e-12 s)``, no error
    bar, the note says which bound in s. eps and mu_el were 'identified' there, their
    profiles walked with t0 pinned to that bound: the limits t0's bound sets are open, so
    neither is identified and neither has a +- (the user's 50x-the-value +-). Mistakes: the
    pinned limits kept (eps 'identified (nonlinear ...)'), the bound's side swapped."""
    d = _log_linear(seed)
    r = fit_static(d, "cv")
    t0 = r["t0"]
    assert t0.value == pytest.approx(1e-12)
    assert t0.identifiability == "at lower bound (1e-12 s)"
    assert t0.stderr is None and t0.interval_95 is None
    assert any("t0 = 1e-12 s sits on its lower search bound 1e-12 s" in n for n in r.notes)
    for name in ("eps", "mu_el"):
        p = r[name]
        assert not p.identifiability.startswith("identified"), (name, p.identifiability)
        assert p.stderr is None and p.interval_95 is None
        assert None in p.profile_95
        assert any(n.startswith(f"{name}") and "set by t0's lower search bound (1e-12 s)" in n
                   for n in r.notes), name
    assert {"at_bound:t0", "not_identified:eps", "not_identified:mu_el"} <= set(r.flags)
    # what the data do fix is there: the slope at the data's centre, near the truth's 0.0052
    slope = next(v["value"] for k, v in r.derived.items() if k.startswith("d mu_s/d ln t_w"))
    assert slope == pytest.approx(0.0052, rel=0.15)


def _csv(path: Path, d: StaticData) -> Path:
    rows = (f"{float(x)!r},{float(y)!r}\n" for x, y in zip(d.x, d.y, strict=True))
    path.write_text("t_w[s],mu_s\n" + "".join(rows))
    return path


def _rows(table: str) -> dict[str, list[str]]:
    rows = {}
    for line in table.splitlines():
        cells = [c.strip() for c in line.split("│")[1:-1]]
        if len(cells) == 5 and "[" in cells[0]:
            rows[cells[0].split("[")[0]] = cells
    return rows


def test_the_table_prints_a_plus_minus_only_beside_an_interval_it_agrees_with(
        tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    """A parameter 'identified (nonlinear: use profile_95)' shows its profile interval and no
    +- (its Wald error disagrees with that interval by definition); an 'identified' one shows
    both. Mistake: the +- printed whenever the Jacobian gives one (the user's table: +- 22
    beside [0.4532, 0.6042] for mu_el = 0.46)."""
    tw = np.geomspace(0.1, 1e3, 6)
    y = static_friction_si(TrapModel(eps=0.03), tw, PhysicalScales(1e-6, 1.0, 0.4)) \
        + np.random.default_rng(0).normal(0.0, 0.004, tw.size)
    src = tmp_path / "nl.csv"
    src.write_text("t_w[s],mu_s,sigma_mu_s\n"
                   + "".join(f"{float(a)!r},{float(b)!r},0.004\n"
                             for a, b in zip(tw, y, strict=True)))
    assert main(["fit", str(src), "--model", "cv", "--out", str(tmp_path / "o"),
                 "--no-figure", "--no-compare"]) == 0
    rows = _rows(capsys.readouterr().out)
    pars = json.loads((tmp_path / "o" / "fit.json").read_text())["parameters"]
    kinds = {n: p["identifiability"] for n, p in pars.items()}
    assert kinds["mu_el"] == "identified (nonlinear: use profile_95)"  # the case
    assert kinds["eps"] == "identified"
    for name, cells in rows.items():
        nonlinear = kinds[name] != "identified"
        assert (cells[2] == "") is nonlinear, (name, cells)
        assert pars[name]["stderr"] is not None  # fit.json keeps it, with the label


def test_cli_says_the_data_contradict_the_model_in_its_last_line(
        tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    """Where a user reads: the table's last line, and fit.json's flags and trend."""
    src = _csv(tmp_path / "down.csv", _falling(4, False))
    assert main(["fit", str(src), "--model", "cv", "--out", str(tmp_path / "o"),
                 "--no-figure", "--no-profile", "--no-compare"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert lines[-1].startswith("the data contradict the model (")
    assert str(src) in lines[-1]
    doc = json.loads((tmp_path / "o" / "fit.json").read_text())
    assert f"against_model:{src}" in doc["flags"]
    assert doc["per_dataset"][0]["trend"]["against_model"] is True
    assert "unit" in doc["per_dataset"][0]["trend"]


def test_the_figure_says_so_too() -> None:
    """fit.png: the panel of a file against the model says so in its title, and the values
    in the figure's title carry what they are worth ('at bound', 'not identified'). Mistake:
    the figure left as it was (a flat line through falling points, titled as a fit)."""
    from dryfriction.plots.fits import plot_fit

    d = _falling(4, False)
    r = fit(d, "cv", profile=False)
    fig, axes = plot_fit(r, [d])
    titles = [ax.get_title() for ax in fig.axes]
    assert any("AGAINST THE MODEL" in t for t in titles), titles
    d = _log_linear(0)
    r = fit_static(d, "cv")
    fig, _ = plot_fit(r, [d])
    head = " ".join(fig.get_suptitle().split())
    assert "t0 = 1e-12 s (at bound)" in head and "eps = " in head
    assert "(not identified)" in head
    assert not any("AGAINST" in ax.get_title() for ax in fig.axes)


@pytest.mark.slow
def test_a_record_of_pure_noise_reports_no_degenerate_interval(tmp_path: Path,
                                                               runslow: bool) -> None:
    """The user's case end to end (about 2 min): a record of white noise (friction 0.6 +-
    3e-3, load point +- 0.05 um about 1 um/s, 10 um/s, a 50 s hold, 1 um/s; the program
    given by --segments). No step's value is reported with an interval of zero width or a
    standard error of 0, and with no transient beyond the noise neither a, b, Dc nor k is
    reported (the user's run printed k = 150.1 [150.1, 150.1])."""
    if not runslow:
        pytest.skip("a whole record's fit: runs with --runslow")
    rng = np.random.default_rng(2026)
    t = np.arange(0.0, 200.0, 0.05)
    v = np.select([t < 60, t < 90, t < 140], [1.0, 10.0, 0.0], 1.0)  # um/s
    x = np.concatenate([[0.0], np.cumsum(v[:-1] * 0.05)]) + rng.normal(0.0, 0.05, t.size)
    mu = 0.6 + rng.normal(0.0, 3e-3, t.size)
    src = tmp_path / "noise.csv"
    src.write_text("Time(s),Disp(um),Friction\n" + "".join(
        f"{a:.2f},{b:.4f},{c:.5f}\n" for a, b, c in zip(t, x, mu, strict=True)))
    out = tmp_path / "o"
    assert main(["fit", str(src), "--model", "rsf", "--segments",
                 "0:1e-6,60:1e-5,90:0,140:1e-6", "--out", str(out), "--no-figure",
                 "--no-profile"]) == 0
    rows = json.loads((out / "fit.json").read_text())["steps"]
    assert rows
    for row in rows:
        for name in ("a", "b", "dc", "stiffness", "a_minus_b"):
            lo, hi = row.get(f"{name}_lo"), row.get(f"{name}_hi")
            if lo is not None and hi is not None:
                assert hi > lo, (row["index"], name, lo, hi)
            sig = row.get(f"sigma_{name}")
            assert sig is None or sig > 0, (row["index"], name, sig)
        if "no transient" in " ".join(row["notes"]):
            assert row["stiffness"] is None and "not_identified:stiffness" in row["flags"]


@pytest.mark.parametrize("decades,identified", [(2.5, True), (3.2, False)])
def test_an_interval_over_more_than_three_decades_is_not_identified(decades: float,
                                                                    identified: bool) -> None:
    """userfixA: a parameter whose 95 % interval is huge is 'not identified', even bounded
    on both sides. For a parameter fitted in ln p: more than three decades. At 2.5 decades
    (a factor 316) it stays identified. Mistakes: the width compared in ln units with 3
    (a factor 20), no width test at all."""
    from dryfriction.fit.models import ParamSpec
    from dryfriction.fit.statistics import classify

    s = ParamSpec("t0", "s", True, 1e-12, 1e9)
    th = math.log(0.37)
    half = 0.5 * decades * math.log(10.0)
    label, note = classify(s, th, half / 1.96, th - half, th + half, th - 30, th + 30)
    assert label.startswith("identified") is identified, (label, note)
    if not identified:
        assert label == "not identified" and f"spans {decades:.2g} decades" in note


def test_a_limit_at_a_physical_bound_is_the_models_own() -> None:
    """eps's lower bound 1e-6 stands for eps = 0 (no ageing), a limit of the model, not of
    the search: a profile limit reached with eps there is the data's, and mu_el (the level,
    with t0 held) stays identified. Only bounds that are the search's reach (t0's 1e-12 s,
    Dc's 1 m) open a side. Mistake: every bound taken as the search's (mu_el 'not
    identified' on data that fix its level to 4 %)."""
    d = _falling(11, False)
    r = fit(d, "cv", fix={"t0": 1.0})
    assert r["eps"].identifiability == "at lower bound (1e-06)"
    assert r["mu_el"].identifiability.startswith("identified"), r["mu_el"]
    lo, hi = r["mu_el"].profile_95
    assert lo is not None and hi is not None and hi / lo < 1.1
