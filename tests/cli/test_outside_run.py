"""Classes found by the second outside run of issue 24 (outside24: 1,166 cases kept outside the
repository, in /tmp/outside24/run.py): one fast test per class, each written against the
mistake named in its comment."""

from __future__ import annotations

import pytest

from dryfriction.cli import main
from dryfriction.theory.model import TrapModel


def _one_error_line(capsys: pytest.CaptureFixture[str], argv: list[str]) -> str:
    capsys.readouterr()
    code = main(argv)
    lines = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and lines[0].startswith("error:"), lines
    return lines[0]


@pytest.mark.parametrize(("argv", "option"), [
    (["static", "--eps", "0.04", "--T", "10", "--u-ref", "-1"], "--u-ref = -1"),
    (["stability", "--eps", "0.04", "--u", "0.3", "--u-ref", "nan"], "--u-ref = nan"),
    (["static", "--eps", "0.04", "--T", "3", "--direct", "0.1"], "--pull-velocity is required"),
    (["rsf", "--mu0", "inf"], "--mu0 = inf"),
])
def test_a_refused_value_is_named_by_the_option_typed(
        capsys: pytest.CaptureFixture[str], argv: list[str], option: str) -> None:
    # mistake: the command line passes on the library's Python name (v_ref, pull_velocity),
    # which is no option the user can type (--v-ref): the one line must name the option
    assert option in _one_error_line(capsys, argv)


def test_a_message_whose_first_word_is_no_option_is_left_alone(
        capsys: pytest.CaptureFixture[str], tmp_path) -> None:
    # mistake: every leading word turned into an option, a protocol's own key included
    proto = tmp_path / "p.toml"
    proto.write_text('[model]\nlaw = "rsf"\na = 0.005\nb = 0.01\ndc = 1e-5\nmu0 = 0.6\n'
                     'v0 = 1e-6\n[drive]\nkind = "spring"\nstiffness = -3.0\n'
                     'segments = [{velocity = 1e-6, duration = 1.0}]\n')
    line = _one_error_line(capsys, ["simulate", str(proto), "--out", str(tmp_path / "o")])
    assert "stiffness" in line and "--stiffness" not in line


def test_a_gap_of_years_in_a_record_asks_for_a_bounded_number_of_windows(monkeypatch) -> None:
    # mistake: the fluctuation windows sized from the median sample interval alone, so that
    # one gap of 1e9 s between samples asked bincount for ~1e9 windows (record and fit hung
    # silently, exhausting the memory); the guard counts the windows asked for, not the time
    import numpy as np

    from dryfriction.records import detection

    rng = np.random.default_rng(24)
    n = 3000
    t = 0.136 * np.arange(n)
    x = 2e-7 * t + 1e-8 * rng.standard_normal(n)
    t[n // 3:] += 1e9  # the clock jumps by 31 years; the displacement goes on
    asked: list[float] = []
    pairs = detection._window_pairs

    def counted(tt, xx, uu, width, offset, half_s2):
        asked.append((tt[-1] - tt[0]) / width)
        if asked[-1] > 100 * len(tt):
            raise AssertionError(f"{asked[-1]:.3g} windows for {len(tt)} samples")
        return pairs(tt, xx, uu, width, offset, half_s2)

    monkeypatch.setattr(detection, "_window_pairs", counted)
    monkeypatch.setattr(detection, "COMPILED_SCALES", False)  # the NumPy loop, window by window
    detection.measure_fluctuations(t, x, 1e-8, [0, n], np.array([2e-7]))
    assert asked and max(asked) <= 10 * n + 1
    # the compiled loop is given its durations: the same bound on the windows of each
    from dryfriction.records import hinge_kernel

    kernel = hinge_kernel.fluctuation_scales
    widths: list[float] = []

    def given(tt, rr, uu, ws, *rest):
        widths.extend(ws.tolist())
        if ws.size and (tt[-1] - tt[0]) / ws.min() > 100 * len(tt):
            raise AssertionError(f"{(tt[-1] - tt[0]) / ws.min():.3g} windows")
        return kernel(tt, rr, uu, ws, *rest)

    monkeypatch.setattr(hinge_kernel, "fluctuation_scales", given)
    monkeypatch.setattr(detection, "COMPILED_SCALES", True)
    detection.measure_fluctuations(t, x, 1e-8, [0, n], np.array([2e-7]))
    assert widths and (t[-1] - t[0]) / min(widths) <= 10 * n + 1


def test_a_false_mat_file_is_one_line(capsys: pytest.CaptureFixture[str], tmp_path) -> None:
    # mistake: only ValueError, OSError... caught around scipy's loadmat, whose MatReadError
    # (a truncated or false .mat) is none of them: a 40-line traceback, exit 1
    bad = tmp_path / "run.mat"
    bad.write_text("not a mat file\n")
    for argv in (["record", str(bad)],
                 ["fit", str(bad), "--model", "rsf", "--out", str(tmp_path / "o")]):
        assert "run.mat: not a readable MATLAB .mat file" in _one_error_line(capsys, argv)


def test_fit_reads_a_mat_record_as_record_does(capsys: pytest.CaptureFixture[str],
                                               tmp_path) -> None:
    # mistake: fit sniffs a .xlsx/.mat as text (a project CSV or not) before reading it as a
    # record, and refuses it ("holds NUL bytes", "a zip archive") where record reads it
    import numpy as np
    from scipy.io import savemat

    t = 8000.0 + 0.25 * np.arange(400)
    rec = tmp_path / "run.mat"
    savemat(rec, {"Time_s": t, "LP_disp_um": 0.2 * (t - t[0]), "Mu": 0.6 + 0 * t})
    for argv in (["record", str(rec)],
                 ["fit", str(rec), "--model", "rsf", "--out", str(tmp_path / "o")]):
        line = _one_error_line(capsys, argv)  # one velocity only: no change to fit
        assert "no velocity change found" in line, line


@pytest.mark.parametrize(("argv", "said"), [
    (["static", "--eps", "0.04", "--t-w", "10", "--t0", "0.01", "--mu-el", "1e300"],
     "--mu-el = 1e+300 is out of range"),
    (["steady", "--eps", "0.04", "--V", "1e-6", "--a0", "1e-6", "--t0", "0.01", "--mu-el",
      "12"], "<= 10"),
    (["rsf", "--mu0", "50", "--t1", "1", "--t2", "1", "--no-figure"], "--mu0 = 50"),
])
def test_a_friction_coefficient_no_apparatus_shows_is_refused(
        capsys: pytest.CaptureFixture[str], argv: list[str], said: str) -> None:
    # mistake: mu_el (F_el/W) and mu0 checked only for > 0 (or |mu0| <= 1e3): a friction
    # coefficient of 1.3e300 (or 50) was printed with exit 0
    assert said in _one_error_line(capsys, argv)


def test_a_protocol_mu_el_past_the_bound_is_refused(capsys: pytest.CaptureFixture[str],
                                                    tmp_path) -> None:
    proto = tmp_path / "p.toml"
    proto.write_text('[model]\nalpha = 0.13\neps = 0.04\nmu_el = 1e300\n[ensemble]\n'
                     'traps_per_a0 = 100\ninitial = "steady"\ninitial_velocity = 1.0\n[drive]\n'
                     'kind = "velocity"\nsegments = [{velocity = 1.0, slip = 0.3}]\n'
                     '[output]\nevery_slip = 0.01\n')
    line = _one_error_line(capsys, ["simulate", str(proto), "--out", str(tmp_path / "o")])
    assert "mu_el = 1e+300" in line and "<= 10" in line
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("bad", [["--mu0", "-1"], ["--v0", "1e-300"]])
def test_a_negative_rate_and_state_friction_is_no_result(
        capsys: pytest.CaptureFixture[str], tmp_path, bad: list[str]) -> None:
    # mistake: the friction's lower bound 0 checked for the regularised law only; the classic
    # law's ln(V/V0) went to mu = -2.8 (v0 = 1e-300) with exit 0 and a results folder
    out = tmp_path / "o"
    argv = ["rsf", "--t1", "2", "--t2", "2", "--v1", "1e-7", "--v2", "1e-6", "--no-figure",
            "--out", str(out), *bad]
    line = _one_error_line(capsys, argv)
    assert "below 0" in line and "regularised" in line
    assert not out.exists()
    # the same run at the default mu0 and v0 is a result: the bound refuses no good run
    capsys.readouterr()
    assert main(argv[:-2]) == 0 and out.is_dir()


def test_more_sweep_workers_than_the_machine_holds_are_refused_before_any_start(
        capsys: pytest.CaptureFixture[str], tmp_path) -> None:
    # mistake: --workers bounded below only: --workers 100000 started a local cluster of
    # 100000 processes and printed nothing for as long as it took to run out
    proto = tmp_path / "p.toml"
    proto.write_text('[model]\nalpha = 0.13\neps = 0.04\n[ensemble]\ntraps_per_a0 = 50\n'
                     'initial = "steady"\ninitial_velocity = 0.1\n[drive]\nkind = "spring"\n'
                     'stiffness = 0.05\nsegments = [{velocity = 0.1, slip = 4.0}]\n[output]\n'
                     'every_slip = 0.05\n[sweep]\n"drive.stiffness" = [0.05, 0.1]\n')
    out = tmp_path / "o"
    line = _one_error_line(capsys, ["sweep", str(proto), "--out", str(out), "--workers",
                                    "100000"])
    assert "--workers 100000 is out of range" in line and "per core" in line
    assert not out.exists()


@pytest.mark.parametrize("option", [["--fix", "a=nan"], ["--fix", "zz=1"], ["--v0", "1e-6"]])
def test_fit_of_a_record_refuses_the_csv_options_it_would_ignore(
        capsys: pytest.CaptureFixture[str], tmp_path, option: list[str]) -> None:
    # mistake: --fix (and --v0) read only on the project's CSV route: on a record they were
    # dropped silently and the steps fitted free, exit 0, as if --fix a=nan had been obeyed
    from pathlib import Path

    lab = Path(__file__).parents[2] / "examples/data/lab/sepiolite_velstep_0.2-2um_s.txt"
    out = tmp_path / "o"
    line = _one_error_line(capsys, ["fit", str(lab), "--model", "rsf", *option, "--out",
                                    str(out), "--no-figure"])
    assert f"{option[0]} is for the project's CSV files" in line
    assert not out.exists()


def test_the_athermal_model_with_mass_and_damping_is_stable_not_refused(
        capsys: pytest.CaptureFixture[str]) -> None:
    # mistake: with damping, the scan's top frequency is 1.05 reach/eta, 0 at eps = 0 (Z real,
    # no Im Z for eta omega to meet): refused as "omega_max = 0", an input nobody gave;
    # eps = 0 is allowed (--eps >= 0), and no crossing means K_c = 0 (stable at any K)
    import json

    from dryfriction.theory.linear_stability import critical_stiffness

    res = critical_stiffness(0.1, TrapModel(eps=0.0), mass=1.0, damping=0.1)
    assert res.critical_stiffness == 0.0
    capsys.readouterr()
    assert main(["stability", "--eps", "0", "--u", "0.1", "--M", "1", "--eta", "0.1",
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["K_c"] == [0.0]


def test_a_shear_column_without_a_unit_is_said_so(capsys: pytest.CaptureFixture[str],
                                                  tmp_path) -> None:
    # mistake: the kind of a unitless column printed as it is, '', so the one line read
    # "shear column 'Friction' is a  and normal column ... a stress"
    rec = tmp_path / "r.txt"
    rows = [f"{8000 + 0.5 * i:.3f}\t{0.1 * i:.4f}\t0.6\t30" for i in range(40)]
    rec.write_text("Time(s)\tDispl(microns)\tFriction\tNormal(MPa)\n" + "\n".join(rows) + "\n")
    line = _one_error_line(capsys, ["record", str(rec), "--columns",
                                    "shear=Friction,normal=Normal(MPa)"])
    assert "'Friction' is without a unit" in line and "a  and" not in line


@pytest.mark.parametrize("alpha", ["5", "1e300"])
def test_a_trap_without_pinning_shows_no_nan_or_inf(
        capsys: pytest.CaptureFixture[str], alpha: str) -> None:
    # mistake: the undefined constants of a trap that does not pin (alpha >= 1: no spinodal,
    # no friction) printed as nan and inf with exit 0, as if the computation had failed
    capsys.readouterr()
    assert main(["trap", "--alpha", alpha]) == 0
    table = capsys.readouterr().out
    assert "no pinning" in table and " nan " not in table and " inf " not in table
    assert table.count("none (no pinning: alpha >= 1)") == 6


@pytest.mark.parametrize("text", ["", " , "])
@pytest.mark.parametrize("command", ["record", "fit"])
def test_an_empty_segments_option_is_refused_not_taken_as_absent(
        capsys: pytest.CaptureFixture[str], command: str, text: str, tmp_path) -> None:
    # mistake: `--segments ""` read as "not given", so the program was detected (and, in fit,
    # fitted) instead of the user hearing that the program they meant to give is empty
    from pathlib import Path

    record = (Path(__file__).resolve().parents[2] / "examples" / "data" / "lab"
              / "sepiolite_velstep_0.2-2um_s.txt")
    argv = [command, str(record), "--segments", text]
    if command == "fit":
        argv += ["--model", "rsf", "--out", str(tmp_path / "o")]
    assert "--segments is empty" in _one_error_line(capsys, argv)
    assert not (tmp_path / "o").exists()
