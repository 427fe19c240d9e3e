"""Issue 30 item 3: a record's fit driven by what its load point did (``--drive measured``,
:mod:`dryfriction.fit.loadpoint`), checked on the basalt-like record of
``tests/machine_zoo.py`` (an independent LSODA forward model whose servo lags and overshoots
the commanded 3 -> 10 um/s change at 68.65 s; 10 Hz before, 100 Hz after; red noise).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.fit.loadpoint import estimate_change, measured_series
from dryfriction.fit.steps import fit_steps
from dryfriction.records.data import SeriesData

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from machine_zoo import Machine, basalt_like, program_friction, write_record  # noqa: E402

RECORD = (Path(__file__).resolve().parents[2] / "examples/data/lab"
          / "sepiolite_velstep_0.2-2um_s.txt")


@pytest.fixture(scope="module")
def basalt(tmp_path_factory: pytest.TempPathFactory):  # type: ignore[no-untyped-def]
    from dryfriction.records import lab

    rec = basalt_like(0)
    path = write_record(tmp_path_factory.mktemp("basalt") / "basalt.txt", rec)
    return rec, lab.read_record(path)


def _fit(lab_rec, t_change: float, drive: str):  # type: ignore[no-untyped-def]
    from dryfriction.records import lab

    segs = lab.parse_segments(f"0:3e-6,{t_change}:1e-5", lab_rec)
    return fit_steps(lab_rec, lab.slice_steps(lab_rec, segs), segs, drive=drive)


def test_change_placed_between_samples():
    """A broken line with its corner at 1.234 s between samples 0.1 s apart, 0.02 um of
    noise: the corner is found to within 3 standard errors, and the error is small (a corner
    restricted to sample times would be 0.034 s off)."""
    rng = np.random.default_rng(3)
    t = np.arange(0.0, 3.0, 0.1)
    x = np.where(t < 1.234, 3e-6 * t, 3e-6 * 1.234 + 1e-5 * (t - 1.234))
    est = estimate_change(t, x + rng.normal(0, 2e-8, t.size), 1.3)
    assert abs(est.t - 1.234) < 3 * est.sigma and est.sigma < 0.01
    assert est.v_before == pytest.approx(3e-6, rel=0.02)
    assert est.v_after == pytest.approx(1e-5, rel=0.02)


@pytest.mark.slow
def test_drive_follows_the_servo(basalt):  # type: ignore[no-untyped-def]
    """The drive's displacement is the load point's to within a fraction of the transducer
    noise (0.15 um) through the servo's transient, and its change sits at the servo's
    effective corner, t_cmd + 2 zeta/w = 68.69 s (the lag of a second-order step response),
    not at the given 68.6 s. Catches a drive that ignores the measured displacement (the
    program's corner at 68.6 s is 0.6 um off) or that keeps its noise (0.15 um rms)."""
    rec, lab_rec = basalt
    from dryfriction.records import lab

    segs = lab.parse_segments("0:3e-6,68.6:1e-5", lab_rec)
    d = lab_rec
    t = np.asarray(d.time, float)
    v = np.zeros(t.size)
    for s in segs:
        v[s.i_start:s.i_end] = s.velocity
    ser = measured_series(SeriesData(t, v, np.asarray(d.friction, float)), lab_rec)
    drive = ser.drive
    assert drive is not None
    m = Machine()
    (c,) = drive.changes
    assert abs(c.t - (m.t_cmd + 2 * m.servo_zeta / m.servo_w)) < 3 * c.sigma + 0.01
    near = (t > 68.2) & (t < 69.2)  # the servo's transient, from half a second before it
    xd = drive.displacement(t[near])
    xt = rec.x_true[near]
    err = (xd - xd[0]) - (xt - xt[0])
    tn = t[near]
    xp = np.where(tn < 68.6, 3e-6 * (tn - tn[0]), 3e-6 * (68.6 - tn[0]) + 1e-5 * (tn - 68.6))
    err_prog = xp - (xt - xt[0])
    rms, rms_prog = (float(np.sqrt(np.mean(e**2))) for e in (err, err_prog))
    assert rms < 0.5 * m.x_noise and rms_prog > 2.0 * rms, (rms, rms_prog)
    assert drive.noise == pytest.approx(m.x_noise, rel=0.3)


def _independent_fit(t: np.ndarray, mu: np.ndarray, t_change: float) -> dict[str, float]:
    """SciPy least squares on machine_zoo's forward model (LSODA) driven by the program,
    with the change time a free parameter (started at ``t_change``) and the other
    parameters from a generic start: the issue's check with rsfmodel, here without it, and
    without the hidden change time (with the change held at the given 68.6 s it gives, as
    our ``--drive program`` does, b = 0.00848 for the true 0.0093)."""
    from scipy.optimize import least_squares

    m = Machine()

    def f(p: np.ndarray) -> np.ndarray:
        mu0, la, lb, ldc, lk, tr, tc = p
        return program_friction(t, tc, m, a=math.exp(la), b=math.exp(lb),
                                dc=math.exp(ldc), k=math.exp(lk), mu0=mu0, trend=tr) - mu

    p0 = np.array([float(np.mean(mu[:50])), math.log(0.01), math.log(0.01), math.log(10e-6),
                   math.log(5000.0), 0.0, t_change])
    r = least_squares(f, p0, x_scale=np.array([1e-3, 0.1, 0.1, 0.1, 0.1, 1.0, 0.01]),
                      diff_step=np.array([1e-4] * 6 + [2e-5]))
    mu0, la, lb, ldc, lk, tr, tc = r.x
    return {"a": math.exp(la), "b": math.exp(lb), "dc": math.exp(ldc), "k": math.exp(lk),
            "t_change": tc}


@pytest.mark.slow
def test_basalt_k_does_not_hang_on_the_change_time(basalt):  # type: ignore[no-untyped-def]
    """Issue 30's "done when" on the basalt-like record: with the measured drive k moves by
    less than its 95 % interval's half-width when the given change moves by one sample
    either way (68.5, 68.6, 68.7 s; measured 8887, 9083, 8932 /m, half-width ~1500). The
    program drive (``--drive program``) fails the first check (measured 3796, 5129, 8526
    /m): the test can fail."""
    _, lab_rec = basalt
    base = _fit(lab_rec, 68.6, "measured")
    row = base.rows[0]
    half = 0.5 * (row["stiffness_hi"] - row["stiffness_lo"])
    for tc in (68.5, 68.7):
        other = _fit(lab_rec, tc, "measured").rows[0]
        assert abs(other["stiffness"] - row["stiffness"]) < half, (tc, other["stiffness"])
    prog = [_fit(lab_rec, tc, "program").rows[0] for tc in (68.6, 68.7)]
    p_half = 0.5 * (prog[0]["stiffness_hi"] - prog[0]["stiffness_lo"])
    assert abs(prog[1]["stiffness"] - prog[0]["stiffness"]) > p_half


@pytest.mark.slow
def test_basalt_agrees_with_an_independent_fit(basalt):  # type: ignore[no-untyped-def]
    """a, b, Dc of the measured drive's fit hold the independent fit's values (measured:
    a 0.00811, b 0.00885, Dc 6.87 um, change at 68.732 s; ours a 0.00846 [0.00727,
    0.00983], b 0.00914 [0.00795, 0.0105], Dc 6.64 [5.35, 8.23] um, the time-lag kernel's;
    the score HAC's were [0.00780, 0.00917], [0.00859, 0.00972], [5.99, 7.35] um) and the
    truth."""
    _, lab_rec = basalt
    base = _fit(lab_rec, 68.6, "measured")
    row = base.rows[0]
    d = base.data[0]
    ind = _independent_fit(d.t, d.mu, 68.6)
    for p in ("a", "b", "dc"):
        assert row[f"{p}_lo"] <= ind[p] <= row[f"{p}_hi"], (p, ind[p], row[f"{p}_lo"],
                                                              row[f"{p}_hi"])
    # and the truth is inside them
    m = Machine()
    for p in ("a", "b", "dc"):
        assert row[f"{p}_lo"] <= getattr(m, p) <= row[f"{p}_hi"], p


def test_measured_drive_needs_a_record():
    t = np.arange(10.0)
    d = SeriesData(t, np.where(t < 5, 1e-6, 2e-6), np.full(10, 0.6))
    with pytest.raises(ValueError, match="--drive measured needs a laboratory record"):
        fit_steps(d, drive="measured")


def test_drive_option_refused_in_one_line(tmp_path: Path):
    csv_file = tmp_path / "s.csv"
    csv_file.write_text("t,v_load,mu\n0,1e-6,0.6\n1,1e-6,0.6\n2,2e-6,0.61\n")
    r = CliRunner().invoke(app, ["fit", str(csv_file), "--model", "rsf", "--out",
                                 str(tmp_path / "o"), "--drive", "sideways"])
    assert r.exit_code == 2 and "--drive 'sideways' is not allowed" in r.stderr, r.output
    assert len(r.stderr.strip().splitlines()) == 1
    r = CliRunner().invoke(app, ["fit", str(csv_file), "--model", "rsf", "--out",
                                 str(tmp_path / "o"), "--drive", "program"])
    assert r.exit_code == 2 and "--drive is for a laboratory record" in r.stderr, r.output
    assert not (tmp_path / "o").exists()


@pytest.mark.slow
@pytest.mark.skipif(not RECORD.exists(), reason="needs the shared record")
def test_shared_record_with_the_measured_drive():
    """The shipped sepiolite step with the measured drive (the record's default): a, b, Dc
    inside the intervals they had before issue 30 (as
    test_fit_identify.test_shared_record_keeps_its_values_and_raises_no_flag), no flag, and
    an rms residual no worse than the program's (measured 1.66e-3 against 1.67e-3)."""
    from dryfriction.records import lab

    rec = lab.read_record(RECORD)
    segs = lab.detect_segments(rec)
    wins = lab.slice_steps(rec, segs)
    row = fit_steps(rec, wins, segs, drive="measured").rows[0]
    assert 0.01955 <= row["a"] <= 0.02301
    assert 0.01192 <= row["b"] <= 0.01762
    assert 98.87e-6 <= row["dc"] <= 217.8e-6
    assert row["flags"] == "", row["notes"]
    assert row["rms"] <= 1.01 * fit_steps(rec, wins, segs).rows[0]["rms"]


@pytest.mark.slow
def test_fit_json_and_terminal_report_the_drive(basalt, tmp_path: Path):  # type: ignore[no-untyped-def]
    """``dryfriction fit`` on the basalt-like record (defaults: --drive measured,
    --stiffness record): fit.json carries the option, the placed change with its standard
    error, and each step's k and a under both drives (the program's k = 5129 /m, below the
    measured drive's interval); the terminal says the same. A comparison refitted on the
    measured drive again (the drive not dropped) gives the same k twice and fails here."""
    import json

    rec, _ = basalt
    path = write_record(tmp_path / "basalt.txt", rec)
    out = tmp_path / "out"
    r = CliRunner().invoke(app, ["fit", str(path), "--model", "rsf", "--segments",
                                 "0:3e-6,68.6:1e-5", "--out", str(out), "--no-figure"])
    assert r.exit_code == 0, r.output
    rep = json.loads((out / "fit.json").read_text())
    assert rep["options"]["drive"] == "measured" and rep["options"]["stiffness"] == "record"
    (ch,) = rep["drive"]["changes"]
    assert ch["t_given"] == pytest.approx(68.6) and 68.65 < ch["t_change"] < 68.75
    assert 0 < ch["sigma_t_change"] < 0.05
    (cmp,) = rep["drive"]["comparison"]
    row = rep["steps"][0]
    assert cmp["measured"]["stiffness"] == pytest.approx(row["stiffness"])
    assert cmp["program"]["stiffness"] < row["stiffness_lo"]
    assert cmp["program"]["a"] != pytest.approx(row["a"], rel=1e-3)
    text = " ".join(r.stdout.split())
    assert "measured drive: change at" in text and "program drive k =" in text


def test_a_change_the_displacement_cannot_place_keeps_the_program():
    """At 1 Hz with a wandering load point (a random walk of 0.3 um a step on 0.2 ->
    0.6 um/s) the corner's standard error exceeds the sampling interval: the program's
    change time stands (``placed`` false) and nothing is smoothed there; with a clean
    displacement the same change is placed between the samples (issue 30: records_zoo's
    slide-hold-slides at 1 Hz had corners 0.7-1.7 s uncertain and up to 3.4 s off)."""
    from dryfriction.fit.loadpoint import measured_drive

    t = np.arange(0.0, 200.0, 1.0)
    v = np.where(t < 100.0, 2e-7, 6e-7)
    x = np.where(t < 99.6, 2e-7 * t, 2e-7 * 99.6 + 6e-7 * (t - 99.6))
    walk = np.cumsum(np.random.default_rng(5).normal(0.0, 3e-7, t.size))
    (c,) = measured_drive(t, x + walk, v).changes
    assert not c.placed and c.t == 100.0 and c.sigma > 1.0
    (c,) = measured_drive(t, x + np.random.default_rng(5).normal(0.0, 2e-9, t.size),
                          v).changes
    assert c.placed and abs(c.t - 99.6) < 0.1


def test_a_velocity_column_places_a_change_no_finer_than_its_sampling() -> None:
    # the mistake (a second new user): a velocity column sampled every 0.5 s, integrated,
    # has an exact corner; its Wald error (nanoseconds) was reported as the change time's
    from dryfriction.fit.loadpoint import measured_drive

    dt = 0.47
    t = 3.1 + dt * np.arange(120)
    v_load = np.where(t < 3.1 + 41 * dt, 1.7e-6, 6.3e-6)  # the program, as detected
    v = np.where(t < 3.1 + 41 * dt - 0.2, 1.7e-6, 6.3e-6)  # the true change mid-interval
    x = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
    wald = measured_drive(t, x, v_load).changes[0]
    assert wald.sigma < 1e-6  # the integral's corner: exact to rounding
    (c,) = measured_drive(t, x, v_load, from_velocity=True).changes
    assert c.sigma == pytest.approx(dt / np.sqrt(12.0), rel=1e-12) and c.placed
    assert abs(c.t - (3.1 + 41 * dt - 0.2)) < dt  # within its interval
    # and through a record whose only load-point column is the velocity
    from dryfriction.records.data import SeriesData
    from dryfriction.records.record import LabRecord

    rec = LabRecord("v.txt", t, None, v, np.full(t.size, 0.6), None, "", {}, 2)
    drive = measured_series(SeriesData(t, v_load, np.full(t.size, 0.6)), rec).drive
    assert drive.changes[0].sigma == pytest.approx(dt / np.sqrt(12.0), rel=1e-12)
