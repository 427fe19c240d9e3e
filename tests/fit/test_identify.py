"""Issue 30 (items 1, 2, 4) and issue 24 item 12: each step's fit says what the data identify,
and its flags travel into steps.csv, fit.json, the terminal table and the figures.

Synthetic records from the independent solver of ``tests/lab_synth.py`` (SciPy Radau on
``(tau, theta)``) through ``tests/identify_synth.py``: identifiable ones, and ones built not
to be (the window shorter than ``Dc``, ``Dc`` far beyond the window, ``a = b`` with the
transient lost in the noise).
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.fit.identify import judge_step, split_flags
from dryfriction.fit.models import ParamSpec
from dryfriction.fit.steps import fit_steps
from dryfriction.io.units import read_rows
from dryfriction.records.data import SeriesData

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from identify_synth import make_case  # noqa: E402
from lab_synth import Truth, synth_program, write_lab_file  # noqa: E402

RECORD = (Path(__file__).resolve().parents[2] / "examples/data/lab"
          / "sepiolite_velstep_0.2-2um_s.txt")
IDENTIFYING = ("not_identified", "at_bound", "short_window")


def _classified(seed: int) -> tuple[bool, str, str]:
    """(correct, kind, flags) for the synthetic record of ``seed``: an identifiable record
    carries no flag at all; one built not to be carries a flag that says so."""
    c = make_case(seed)
    row = fit_steps(SeriesData(c.t, c.v_load, c.mu, source=f"seed {seed}")).rows[0]
    words = split_flags(row["flags"])
    said = any(w.startswith(IDENTIFYING) for w in words)
    return (not words) if c.identifiable else said, c.kind, row["flags"]


@pytest.mark.slow
def test_flags_on_synthetic_records_subset():
    """17 records, four or five of each kind (CI's subset of the 100 below): at most one
    wrong (measured: none). Catches a rule that never flags (the unidentifiable ones) and one
    that flags identifiable steps: Dc's lower limit taken as one sample's slip at the fastest
    velocity instead of the velocity after the change flagged seed 16 (a step down)."""
    got = [_classified(seed) for seed in range(17)]
    assert sum(ok for ok, _, _ in got) >= 16, got


@pytest.mark.slow
def test_flags_on_synthetic_records_100(runslow: bool):
    """Issue 30's acceptance: >= 95 % of 100 seeded records classified right."""
    if not runslow:
        pytest.skip("the 100-record study runs with --runslow")
    got = [_classified(seed) for seed in range(100)]
    assert sum(ok for ok, _, _ in got) >= 95, [g for g in got if not g[0]]


def _judge(val: dict[str, float], se: dict[str, float], rho_bd: float = 0.0
           ) -> tuple[dict, list[str]]:
    """judge_step on a hand-made row: a, b, dc fitted in ln p with the given standard
    errors (of ln p), ln b and ln dc correlated by ``rho_bd``; a window of 1 -> 3 um/s, 900 um
    of slip after the change."""
    specs = [ParamSpec("a", "", True, 1e-6, 1.0), ParamSpec("b", "", True, 1e-6, 1.0),
             ParamSpec("dc", "m", True, 1e-12, 1.0)]
    theta = np.array([math.log(val[s.name]) for s in specs])
    cov = np.diag([se[s.name] ** 2 for s in specs])
    cov[1, 2] = cov[2, 1] = rho_bd * se["b"] * se["dc"]
    z = 1.96
    row = {}
    for s, th in zip(specs, theta, strict=True):
        row[s.name] = val[s.name]
        row[f"sigma_{s.name}"] = val[s.name] * se[s.name]
        row[f"{s.name}_lo"] = math.exp(th - z * se[s.name])
        row[f"{s.name}_hi"] = math.exp(th + z * se[s.name])
    row["a_minus_b"], row["sigma_a_minus_b"] = val["a"] - val["b"], 0.0
    t = np.arange(400.0)
    v = np.where(t < 100, 1e-6, 3e-6)
    d = SeriesData(t, v, np.zeros(400))
    return row, judge_step(row, specs, theta, cov, False, z, d)


def test_judge_by_hand():
    """Identified within range and a decade; a wide interval, one leaving the window, and a
    value on its search bound are not, with NaN values and the combinations that hold."""
    row, words = _judge({"a": 0.006, "b": 0.009, "dc": 20e-6},
                        {"a": 0.05, "b": 0.05, "dc": 0.1})
    assert words == [] and row["dc"] == 20e-6
    # dc's interval spans more than a decade: dc and only dc not identified; b/Dc fixed
    row, words = _judge({"a": 0.006, "b": 0.009, "dc": 20e-6},
                        {"a": 0.05, "b": 0.55, "dc": 0.7}, rho_bd=0.99)
    assert words == ["not_identified:dc"] and math.isnan(row["dc"])
    assert math.isnan(row["sigma_dc"]) and row["b"] == 0.009  # b spans 8.6
    assert row["b_over_dc_lo"] < 0.009 / 20e-6 < row["b_over_dc_hi"]
    assert any("b/Dc" in n for n in row["notes"])
    # dc beyond the slip after the change (900 um here: 300 samples at 3 um/s): open above
    row, words = _judge({"a": 0.006, "b": 0.009, "dc": 800e-6},
                        {"a": 0.05, "b": 0.05, "dc": 0.2})
    assert "not_identified:dc" in words and "short_window" in words
    assert math.isnan(row["dc_hi"]) and row["dc_lo"] == pytest.approx(800e-6 * math.exp(-0.392))
    # b on its search bound 1e-6: never reported as a fitted value (issue 24 item 12)
    row, words = _judge({"a": 0.006, "b": 1e-6, "dc": 20e-6},
                        {"a": 0.05, "b": 0.05, "dc": 0.1})
    assert "at_bound:b" in words and "not_identified:b" in words and math.isnan(row["b"])


def test_nan_sigma_never_beside_success_without_a_flag():
    """Issue 24 item 12: a fit whose covariance is singular (a = b with the transient lost
    in the noise: every sigma NaN) still succeeds, and then every missing error has its
    flag, and the flags say which values are not reported."""
    c = make_case(3)  # "flat"
    assert c.kind == "flat"
    res = fit_steps(SeriesData(c.t, c.v_load, c.mu, source="flat"))
    row = res.rows[0]
    words = split_flags(row["flags"])
    for name in ("a", "b", "dc", "stiffness", "trend"):
        if not math.isfinite(row[f"sigma_{name}"]):
            assert f"not_identified:{name}" in words, (name, words)
    for name in ("a", "b", "dc", "stiffness"):
        if f"not_identified:{name}" in words:
            assert math.isnan(row[name])
    assert words and row["notes"]


def _two_steps(tmp_path: Path, normal_mpa: float | None = None) -> Path:
    """1 -> 3 um/s (300 um after: identified), then 3 -> 1 um/s for only 25 um (Dc = 20 um:
    the window is short); with ``normal_mpa`` a normal-stress column (MPa) too."""
    tr = Truth()
    t, _, mu, x = synth_program(tr, [(1e-6, 300.0), (3e-6, 100.0), (1e-6, 25.0)], 0.25,
                                seed=11)
    if normal_mpa is None:
        return write_lab_file(tmp_path / "rec.txt", t, x, mu)
    path = tmp_path / "rec.txt"
    np.savetxt(path, np.column_stack([t, x * 1e6, mu, np.full_like(t, normal_mpa)]),
               delimiter="\t", header="Time(s)\tDispl(microns)\tFriction\t"
               "EffectiveNormalstress(MPa)", comments="", fmt="%.10g")
    return path


def _table_rows(text: str) -> list[list[str]]:
    return [[c.strip() for c in ln.split("│")[1:-1]] for ln in text.splitlines()
            if ln.startswith("│")]


def _num(cell: str) -> float:
    return math.nan if cell in ("—", "not identified") else float(cell)


@pytest.mark.slow
def test_csv_json_table_and_figures_agree(tmp_path: Path):
    """steps.csv, fit.json, the terminal table and the figures carry the same values (to the
    table's 4 digits), 95 % intervals and flags; the last line counts the flagged steps."""
    from dryfriction.plots import steps as step_plots

    titles: list[str] = []
    bars: dict[str, tuple] = {}
    plot, summary = step_plots.plot_step, step_plots.plot_steps_summary

    def spy_step(*a, **k):  # type: ignore[no-untyped-def]
        fig, axes = plot(*a, **k)
        titles.append(fig._suptitle.get_text())
        return fig, axes

    def spy_summary(*a, **k):  # type: ignore[no-untyped-def]
        fig, axes = summary(*a, **k)
        for ax, name in zip(axes, ("a_minus_b", "a", "b", "dc"), strict=True):
            if not ax.containers:  # nothing identified in this panel
                bars[name] = (np.array([]), [])
                continue
            cont = ax.containers[0]  # one normal-stress level: one container
            xy = cont.lines[0].get_data()
            segs = cont.lines[2][0].get_segments()
            bars[name] = (np.asarray(xy[1]), [(s[0][1], s[1][1]) for s in segs])
        return fig, axes

    out = tmp_path / "out"
    mp = pytest.MonkeyPatch()
    mp.setattr(step_plots, "plot_step", spy_step)
    mp.setattr(step_plots, "plot_steps_summary", spy_summary)
    try:
        r = CliRunner().invoke(app, ["fit", str(_two_steps(tmp_path, 13.7)), "--model", "rsf",
                                     "--out", str(out)])
    finally:
        mp.undo()
    assert r.exit_code == 0, r.output
    rows = read_rows(out / "steps.csv")
    rep = json.loads((out / "fit.json").read_text())["steps"]
    assert len(rows) == len(rep) == len(titles) == 2
    table = _table_rows(r.stdout)
    values, intervals = table[:2], table[2:4]
    names = ("a", "b", "a_minus_b", "dc", "stiffness")
    heads = ("index", "kind", "v_before", "v_after", "normal", "a", "b", "a_minus_b", "dc",
             "stiffness", "trend", "rms", "noise", "peak_residual", "flags")
    iv_names = ("a", "b", "a_minus_b", "dc", "b_over_dc", "stiffness")
    for i, (c, j) in enumerate(zip(rows, rep, strict=True)):
        assert c["flags"] == j["flags"] == (values[i][heads.index("flags")].replace("—", ""))
        for n in names:
            x = float(c[n])
            y = math.nan if j[n] is None else j[n]
            assert (math.isnan(x) and math.isnan(y)) or x == pytest.approx(y, rel=1e-12), n
            tab = _num(values[i][heads.index(n)])
            assert (math.isnan(x) and math.isnan(tab)) or tab == pytest.approx(x, rel=5e-4), n
        # the columns in other units than steps.csv's: the table's heads say which
        for n, scale in (("v_before", 1.0), ("v_after", 1.0), ("normal", 1e-6)):
            assert c["normal_unit"] == "Pa" and float(c["normal"]) == pytest.approx(13.7e6)
            x, tab = float(c[n]) * scale, _num(values[i][heads.index(n)])
            assert (math.isnan(x) and math.isnan(tab)) or tab == pytest.approx(x, rel=5e-4), n
        for k, n in enumerate(iv_names):
            lo, hi = (_num(s) for s in intervals[i][k + 1].strip("[]").split(", "))
            for got, key in ((lo, f"{n}_lo"), (hi, f"{n}_hi")):
                want = float(c[key])
                assert (math.isnan(got) and math.isnan(want)) \
                    or got == pytest.approx(want, rel=5e-4), key
                jv = math.nan if j[key] is None else j[key]
                assert (math.isnan(jv) and math.isnan(want)) or jv == pytest.approx(want), key
        # the figure's title: values and flags
        title = titles[i]
        for n, label, scale in (("a", "a = ", 1), ("b", "b = ", 1), ("a_minus_b", "a-b = ", 1),
                                ("dc", "Dc = ", 1e-6), ("stiffness", "k = ", 1)):
            cell = title.split(label, 1)[1].split(",")[0].split(" µm")[0].split(" /m")[0]
            got = _num(cell) * scale
            want = float(c[n])
            assert (math.isnan(got) and math.isnan(want)) or got == pytest.approx(want, 5e-4)
        assert all(w in title for w in split_flags(c["flags"]))
        if "not_identified:dc" in c["flags"]:
            assert "dc not identified" in title
    # the summary figure: identified values with their 95 % intervals, the others left out
    for name, scale in (("a_minus_b", 1.0), ("a", 1.0), ("b", 1.0), ("dc", 1e6)):
        y, segs = bars[name]
        shown = [c for c in rows if math.isfinite(float(c[name]))]
        assert len(y) == len(shown)
        for yy, (lo, hi), c in zip(y, segs, shown, strict=True):
            assert yy == pytest.approx(float(c[name]) * scale)
            assert lo == pytest.approx(float(c[f"{name}_lo"]) * scale)
            assert hi == pytest.approx(float(c[f"{name}_hi"]) * scale)
    # every note of each step is in fit.json, the flags' reasons among them
    assert rows[0]["flags"] == "" and rows[1]["flags"] != ""
    assert any("v0 =" in n for n in rep[1]["notes"]) and len(rep[1]["notes"]) > 2
    last = [ln for ln in r.stdout.splitlines() if ln.strip()][-1]
    assert last.startswith("1 of 2 steps flagged"), last


def test_every_step_flagged_exits_0_and_says_so(tmp_path: Path):
    c = make_case(2)  # "huge": Dc far beyond the window
    x = np.concatenate([[0.0], np.cumsum(np.diff(c.t) * c.v_load[:-1])])
    rec = write_lab_file(tmp_path / "huge.txt", c.t, x, c.mu)
    r = CliRunner().invoke(app, ["fit", str(rec), "--model", "rsf", "--out",
                                 str(tmp_path / "o"), "--no-figure"])
    assert r.exit_code == 0, r.output
    last = [ln for ln in r.stdout.splitlines() if ln.strip()][-1]
    assert last.startswith("every step is flagged"), last


@pytest.mark.slow
def test_not_steady_before_and_misfit():
    """1 -> 10 um/s for only 30 um (1.5 Dc), then -> 1 um/s: the second change comes inside
    the first's transient and is flagged, the first is not. A kinematic machine fitted to
    the soft one's record is a misfit; the soft fit is not."""
    tr = Truth(noise=1e-4)
    t, v, mu, _ = synth_program(tr, [(1e-6, 300.0), (1e-5, 3.0), (1e-6, 300.0)], 0.05,
                                seed=5)
    res = fit_steps(SeriesData(t, v, mu, source="unsteady"))
    assert "not_steady_before" not in res.rows[0]["flags"], res.rows[0]["notes"]
    assert "not_steady_before" in res.rows[1]["flags"], res.rows[1]["notes"]
    assert res.rows[1]["slip_before"] == pytest.approx(30e-6, rel=0.02)
    t, v, mu, _ = synth_program(Truth(), [(1e-6, 300.0), (3e-6, 100.0)], 0.25, seed=6)
    d = SeriesData(t, v, mu, source="soft")
    assert "misfit" not in fit_steps(d).rows[0]["flags"]
    assert "misfit" in fit_steps(d, stiffness=math.inf).rows[0]["flags"]


@pytest.mark.slow
@pytest.mark.ci
@pytest.mark.skipif(not RECORD.exists(), reason="needs the shared record")
def test_shared_record_keeps_its_values_and_raises_no_flag():
    """The shipped sepiolite step: a, b, Dc inside the intervals they had before issue 30
    (steps.csv of commit 83acd23: a [0.01955, 0.02301], b [0.01192, 0.01762], Dc [98.87,
    217.8] um) and no flag (measured: none; rms/noise 1.13, peak residual 2.5e-3 against an
    allowance of 4.4e-3)."""
    from dryfriction.records import lab

    rec = lab.read_record(RECORD)
    segs = lab.detect_segments(rec)
    row = fit_steps(rec, lab.slice_steps(rec, segs), segs).rows[0]
    assert 0.01955 <= row["a"] <= 0.02301
    assert 0.01192 <= row["b"] <= 0.01762
    assert 98.87e-6 <= row["dc"] <= 217.8e-6
    assert row["flags"] == "", row["notes"]


@pytest.mark.slow
def test_record_stiffness_and_k_inconsistent():
    """One machine: the steps' identified k combine into the record's (inverse-variance in
    ln k); the step that disagrees with the others gets k_inconsistent, the others do not
    (a one-pass leave-one-out comparison, this rule's first version, flagged the two good
    steps as well: the outlier pulls the mean of "the others")."""
    from dryfriction.fit.identify import record_stiffness

    def row(k: float, rel: float) -> dict:
        return {"stiffness": k, "stiffness_lo": k * math.exp(-1.96 * rel),
                "stiffness_hi": k * math.exp(1.96 * rel), "flags": ""}

    rows = [row(3000.0, 0.05), row(3100.0, 0.05), row(4500.0, 0.05), row(math.nan, 0.05)]
    rec = record_stiffness(rows)
    assert rec is not None
    assert [r["flags"] for r in rows] == ["", "", "k_inconsistent", ""]
    assert rec["lo"] < rec["value"] < rec["hi"]
    assert rec["steps"] == [0, 1]  # the outlier left out of the record's k
    assert rec["value"] == pytest.approx(math.exp(np.mean(np.log([3000, 3100]))))
    assert record_stiffness([row(3000.0, 0.05)]) is None
    # the same machine in every step of a synthetic record: no step is flagged, and with
    # --stiffness record every step holds the record's k, its a, b, Dc near the truth
    from dryfriction.fit.onemachine import fit_steps_one_machine

    tr = Truth()
    t, v, mu, _ = synth_program(tr, [(1e-6, 300.0), (3e-6, 100.0), (1e-6, 300.0)], 0.25,
                                seed=12)
    res = fit_steps_one_machine(SeriesData(t, v, mu, source="one machine"))
    k = res.stiffness
    assert k is not None and k["steps"] == [0, 1] and k["lo"] < tr.stiffness < k["hi"]
    hits = 0
    for r in res.rows:
        assert r["stiffness"] == k["value"] and r["flags"] == "", r["notes"]
        hits += sum(r[f"{p}_lo"] <= getattr(tr, p) <= r[f"{p}_hi"] for p in ("a", "b", "dc"))
    assert hits >= 5, res.rows


def test_stiffness_record_is_for_a_record(tmp_path: Path):
    csv_file = tmp_path / "s.csv"
    csv_file.write_text("t,v_load,mu\n0,1e-6,0.6\n1,1e-6,0.6\n2,2e-6,0.61\n")
    r = CliRunner().invoke(app, ["fit", str(csv_file), "--model", "rsf", "--out",
                                 str(tmp_path / "o"), "--stiffness", "record"])
    assert r.exit_code == 2 and "--stiffness record" in r.stderr, r.output
    assert not (tmp_path / "o").exists()


def test_a_fit_to_noise_is_not_identified():
    """Seed 67 ("flat": a = b = 1.7e-5, the transient 0.2x the noise): the fit finds a
    spurious transient (a = 1.0e-4, Dc = 1.9 um) whose Wald intervals span less than a factor
    3; only the test against a straight line (p = 0.26) says that there is no transient."""
    c = make_case(67)
    assert c.kind == "flat"
    row = fit_steps(SeriesData(c.t, c.v_load, c.mu, source="noise")).rows[0]
    words = split_flags(row["flags"])
    assert {"not_identified:a", "not_identified:b", "not_identified:dc"} <= set(words)
    assert any("no transient" in n for n in row["notes"])


def test_dc_range_at_the_velocity_after_the_change():
    """Seed 16: a step down 1 -> 0.1 um/s with Dc = 4.2 um, sampled every 5 s (5 um a sample
    before the change, 0.5 um after it): Dc is resolved after the change and identified (a
    lower limit at the faster velocity before it flagged it)."""
    c = make_case(16)
    assert c.identifiable and c.v2 < c.v1
    row = fit_steps(SeriesData(c.t, c.v_load, c.mu, source="down")).rows[0]
    assert row["flags"] == "", row["notes"]
    assert row["dc_lo"] <= c.truth.dc <= row["dc_hi"]


def test_red_noise_is_not_an_unsteady_start():
    """Red noise (AR(1), rho = 0.98) drifts by 2-3 noise levels over a pre-step stretch by
    chance; the drift allowance counts that (the first rule, 2x the noise alone, flagged 3 of
    20 steady steps not_steady_before; seed 108 was one)."""
    from lab_synth import synth_record

    t, v, mu, _ = synth_record(Truth(rho=0.98), [1e-6, 3e-6, 1e-6], duration_slip=300e-6,
                               dt_per_um=0.5, seed=108)
    res = fit_steps(SeriesData(t, v, mu, source="red"))
    assert all("not_steady_before" not in r["flags"] for r in res.rows), \
        [r["notes"] for r in res.rows]


@pytest.mark.slow
def test_a_step_whose_cheapest_start_leads_astray_is_refitted():
    """Seed 28 (identifiable, 1 -> 0.1 um/s): the data-driven start with the lowest cost
    (a = 0.02, Dc = 630 um) converges to a local minimum (k = 24 /m, rms 14x the noise);
    a fit worse than the noise is retried from every start and finds the truth."""
    c = make_case(28)
    assert c.identifiable
    row = fit_steps(SeriesData(c.t, c.v_load, c.mu, source="astray")).rows[0]
    assert row["flags"] == "", row["notes"]
    assert row["dc_lo"] <= c.truth.dc <= row["dc_hi"]


@pytest.mark.slow
def test_a_flat_record_starts_its_stiffness_within_the_search_bounds():
    """Seed 87 (kind ``flat``): its loading slope gives a stiffness of 0.87 1/m, below the
    fitted stiffness's lower bound (1 1/m), and the data-driven start was refused by the fit
    itself (``start['stiffness'] [1/m] = 0.86693 is out of range``: the 100-record study
    stopped there). Every data-driven start is now put within the search bounds, as the fit
    puts its own guesses (``ParamSpec.within``), and the step is fitted and flagged as the
    flat record it is (measured: a, b, Dc and the stiffness not identified, the stiffness at
    its bound). Mistake, seen failing: the start not put within them (the ValueError)."""
    c = make_case(87)
    row = fit_steps(SeriesData(c.t, c.v_load, c.mu, source="seed 87")).rows[0]
    assert c.kind == "flat" and not c.identifiable
    words = split_flags(row["flags"])
    assert "at_bound:stiffness" in words
    assert any(w.startswith(IDENTIFYING) for w in words if not w.endswith("stiffness"))
