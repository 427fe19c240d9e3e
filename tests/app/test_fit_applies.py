"""fixE item 2 (a second new user's trial, problem 14): ``fit`` on the project's CSV files
refuses, in one line naming it (exit 2, nothing written), an option that the data kinds or the
models fitted do not use (``fit steady.csv --stiffness 5 --trend --traps-per-a0 50`` ran,
exit 0); an option that does apply is taken as before."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dryfriction.app.checks import check_fit_applies
from dryfriction.app.options import OPTIONS
from dryfriction.cli import main

D = {k: o.default for k, o in OPTIONS["fit"].items()}


def _steady(path: Path) -> Path:
    v = np.geomspace(1e-7, 1e-4, 7)
    mu = 0.65 - 0.004 * np.log(v / 1e-6)
    path.write_text("V[m/s],mu_d\n" + "".join(f"{a:.6g},{b:.6f}\n" for a, b in
                                               zip(v, mu, strict=True)))
    return path


def _o(**given: object) -> dict[str, object]:
    return {**D, "model": "cv", **given}


@pytest.mark.parametrize("argv, words", [
    (["--stiffness", "5"], "--stiffness 5 applies only to a time series (t,v_load,mu) (the "
     "machine's spring: {f} hold(s) steady friction (V,mu_d), measured without it): drop "
     "--stiffness"),
    (["--stiffness", "inf"], "--stiffness inf applies only to a time series"),
    (["--trend"], "--trend applies only to a time series"),
    (["--no-trend"], "--no-trend applies only to a time series"),
    (["--traps-per-a0", "50"], "--traps-per-a0 50 applies only to a time series (t,v_load,mu) "
     "(the trap model's simulated ensemble: {f} hold(s) steady friction (V,mu_d), its "
     "integral (eqs. 27, 34), not simulated)"),
    (["--state-law", "slip"], "--state-law slip applies only to static or time-series data"),
    (["--v-ref", "2e-05"], "--v-ref 2e-05 applies only with --direct > 0"),
    (["--model", "rsf", "--no-compare", "--alpha", "0.2"], "--alpha 0.2 applies only to a "
     "trap-model fit (--model cv, or the comparison --compare; this run fits --model rsf "
     "alone): drop --alpha or --no-compare"),
    (["--model", "rsf", "--no-compare", "--creep", "eyring-nabarro"], "--creep eyring-nabarro"
     " applies only to a trap-model fit"),
    (["--model", "rsf", "--no-compare", "--direct", "0.1"], "--direct 0.1 applies only to a "
     "trap-model fit"),
    (["--model", "cv", "--no-compare", "--v0", "1e-06"], "--v0 1e-06 applies only to a "
     "rate-and-state fit"),
    (["--model", "cv", "--no-compare", "--regularized"], "--regularized applies only to a "
     "rate-and-state fit"),
])
def test_an_option_the_fit_does_not_use_is_refused_by_name_before_any_work(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], argv: list[str],
        words: str) -> None:
    """Each in one line, exit 2, the results folder never made. Mistakes: the rule left out
    (the user's run: exit 0), the option's default taken for given."""
    data = _steady(tmp_path / "steady.csv")
    capsys.readouterr()
    code = main(["fit", str(data), "--out", str(tmp_path / "o"), *argv])
    err = capsys.readouterr().err
    assert code == 2
    assert len(err.strip().splitlines()) == 1
    assert words.format(f=data) in err
    assert not (tmp_path / "o").exists()


def test_what_does_apply_is_not_refused() -> None:
    """The defaults, the options of the data kinds given (a time series' machine; static
    data's state law) and of the model the comparison fits (--alpha with --model rsf, the rsf
    options with --model cv: --compare is on by default), --v-ref with --direct. Mistakes:
    the comparison's model forgotten, a default counted as given."""
    src = ["d.csv"]
    check_fit_applies(_o(), D, {"steady"}, src)
    check_fit_applies(_o(stiffness="5", trend=True, traps_per_a0=50.0), D, {"series"}, src)
    check_fit_applies(_o(state_law="slip"), D, {"static"}, src)
    check_fit_applies(_o(state_law="slip"), D, {"steady", "series"}, src)
    check_fit_applies(_o(model="rsf", alpha=0.2, creep="eyring-nabarro"), D, {"steady"}, src)
    check_fit_applies(_o(v0=1e-6, regularized=True), D, {"steady"}, src)
    check_fit_applies(_o(direct=0.1, v_ref=2e-5), D, {"steady"}, src)


def test_the_u_ref_refusal_reads_as_before() -> None:
    # the theory's two refusals now come from the same helper, word for word as they were
    from dryfriction import app

    with pytest.raises(ValueError) as exc:
        app.steady(0.04, u=[0.1], v_ref=2.0)
    assert str(exc.value) == ("--u-ref 2 applies only with --direct > 0 (the direct effect's "
                              "reference velocity, a0/t0): give --direct or drop --u-ref")


def _record(path: Path) -> Path:
    t = 0.1 * np.arange(600)
    v = np.where(t < 30.0, 1e-6, 1e-5)
    x = np.concatenate([[0.0], np.cumsum(v[:-1] * 0.1)])
    mu = 0.6 + 0.003 * np.where(t >= 30.0, np.exp(-(t - 30.0) / 2.0), 0.0)
    path.write_text("Time(s)\tDispl(um)\tFriction\n" + "".join(
        f"{a:.2f}\t{b * 1e6:.5f}\t{c:.6f}\n" for a, b, c in zip(t, x, mu, strict=True)))
    return path


@pytest.mark.parametrize("argv, words", [
    (["--traps-per-a0", "50"], "--traps-per-a0 50 applies only to a trap-model fit (on a "
     "record: --run-cv; this run fits rate-and-state alone): drop --traps-per-a0 or add "
     "--run-cv"),
    (["--alpha", "0.2"], "--alpha 0.2 applies only to a trap-model fit"),
    (["--direct", "0.05"], "--direct 0.05 applies only to a trap-model fit"),
    (["--regularized"], "--regularized applies only to the project's CSV files (a record's "
     "steps take the regularised law across a hold"),
    (["--no-compare"], "--no-compare applies only to the project's CSV files"),
])
def test_a_record_refuses_what_its_fit_does_not_use(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], argv: list[str],
        words: str) -> None:
    """``fit RECORD --traps-per-a0 50 --alpha 0.2`` fitted rate-and-state alone, exit 0.
    Mistake: the record's fit left out of the check."""
    rec = _record(tmp_path / "r.txt")
    capsys.readouterr()
    code = main(["fit", str(rec), "--out", str(tmp_path / "o"), *argv])
    err = capsys.readouterr().err
    assert code == 2 and words in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "o").exists()
    # with --run-cv the trap model's options are its own (checked without running it)
    from dryfriction.app.checks import check_record_applies

    check_record_applies({**D, "model": "rsf", "run_cv": True, "alpha": 0.2,
                          "traps_per_a0": 50.0}, D)


def test_the_direct_effect_with_static_data_is_refused_as_typed(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``fit static.csv --direct 0.1`` was refused in the library's words (``the direct effect
    (direct)``), not the option typed; now by ``--direct``, one line, exit 2, nothing written,
    and with static data beside steady data too (the model takes no static data with the
    direct effect). Steady data with ``--direct`` stay accepted. Mistake: the rule left out."""
    t_w = np.geomspace(1.0, 1e4, 6)
    static = tmp_path / "static.csv"
    static.write_text("t_w[s],mu_s\n" + "".join(f"{a:.6g},{0.7 + 0.01 * np.log(a):.6f}\n"
                                                 for a in t_w))
    for files in ([static], [static, _steady(tmp_path / "steady.csv")]):
        capsys.readouterr()
        code = main(["fit", *map(str, files), "--direct", "0.07", "--out",
                     str(tmp_path / "o")])
        err = capsys.readouterr().err
        assert code == 2 and len(err.strip().splitlines()) == 1, err
        assert "--direct 0.07 applies only to steady or time-series data" in err
        assert not (tmp_path / "o").exists()
    check_fit_applies(_o(direct=0.07), D, {"steady"}, ["s.csv"])
