"""What a new user found wrong in reading and cutting records (userfixB), through the command
line: a slide-hold-slide with the normal stress stepped mid-hold (the hold whole, the change
reported with its stresses, the reslide in the window); a preamble without ``#`` and a few
missing cells (read, and said in one line each); a one-velocity record (the --segments example
built from the record, a one-velocity program answered with its reason)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from dryfriction.cli import main


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    capsys.readouterr()
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def shs_normal_step(path: Path, t_step: float = 70.0) -> Path:
    """10 um/s for 60 s, at rest 60-110 s with the normal stress 5 -> 7 MPa at ``t_step``,
    10 um/s to 170 s; 10 Hz, displacement noise 0.02 um, friction a healing peak."""
    rng = np.random.default_rng(11)
    t = 0.1 * np.arange(1700)
    v = np.where((t >= 60.0) & (t < 110.0), 0.0, 1e-5)
    x = np.concatenate([[0.0], np.cumsum(v[:-1] * 0.1)]) + rng.normal(0, 2e-8, t.size)
    mu = 0.6 + 0.01 * np.where(t >= 110.0, np.exp(-(t - 110.0) / 3.0), 0.0)
    mu += rng.normal(0, 2e-4, t.size)
    sn = np.where(t < t_step, 5.0, 7.0)
    with path.open("w") as fh:
        fh.write("Time(s),LP_disp(um),Shear(MPa),Normal(MPa)\n")
        for a, b, c, d in zip(t, x * 1e6, mu * sn, sn, strict=True):
            fh.write(f"{a:.2f},{b:.4f},{c:.5f},{d:.3f}\n")
    return path


def test_a_normal_change_mid_hold_keeps_the_hold_whole(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the user's report: hold 10 s (cut at the change), the reslide in no window
    rec = shs_normal_step(tmp_path / "shs.csv")
    code, out, err = run(capsys, "record", str(rec))
    assert code == 0, err
    assert "normal-stress changes (segment boundaries): t = 70 s: 5 -> 7 MPa" in out
    assert "step 0: the normal stress changed during its hold, t = 70 s: 5 -> 7 MPa" in out
    code, out, _ = run(capsys, "record", str(rec), "--json")
    rep = json.loads(out)
    (w,) = rep["steps"]
    assert w["kind"] == "shs" and w["hold"] == pytest.approx(50.0, abs=0.2)
    assert w["v_after"] == pytest.approx(1e-5, rel=0.02)
    assert w["i_end"] == 1700  # the reslide to the record's end
    (ch,) = w["normal_changes"]
    assert ch == {"t_normal_change": pytest.approx(70.0, abs=0.2), "normal_before": 5e6,
                  "normal_after": 7e6}
    assert rep["normal_changes"] == [ch]
    assert rep["units"]["normal_before"].startswith("Pa")


@pytest.mark.slow
def test_fit_of_a_hold_with_a_normal_change_says_so_beside_the_step(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the hold's length is what a user ages contacts by: 50 s in steps.csv and fit.json; the
    # fit has no normal-stress effect on the state: said on the step (terminal, fit.json)
    rec = shs_normal_step(tmp_path / "shs.csv")
    code, out, err = run(capsys, "fit", str(rec), "--out", str(tmp_path / "f"), "--no-figure",
                         "--no-profile", "--drive", "program", "--state-law", "ageing")
    assert code in (0, 1), err
    note = ("the normal stress changed during its hold (t = 70 s: 5 -> 7 MPa); the hold is "
            "the whole time at rest")
    assert f"- step 0: {note}" in out
    (row,) = json.loads((tmp_path / "f" / "fit.json").read_text())["steps"]
    assert row["hold"] == pytest.approx(50.0, abs=0.2) and row["kind"] == "shs"
    assert any(n.startswith(note) for n in row["notes"])


def step_with_preamble(path: Path, missing: dict[int, str] | None = None) -> Path:
    """A velocity step 0.5 -> 5 um/s at 100 s (tab separated, 2 Hz), under a three-line
    preamble without '#'; ``missing``: row -> the friction cell's text."""
    t = 0.5 * np.arange(400)
    v = np.where(t < 100.0, 0.5, 5.0)
    x = np.concatenate([[0.0], np.cumsum(v[:-1] * 0.5)])
    mu = 0.6 + 0.005 * np.exp(-np.clip(t - 100.0, 0, None) / 5.0) * (t >= 100.0)
    lines = ["Experiment p4966", "Operator: X", "Sample rate: 2 Hz",
             "Time (s)\tLP Displacement (um)\tFriction"]
    for i, (a, b, c) in enumerate(zip(t, x, mu, strict=True)):
        cell = (missing or {}).get(i, f"{c:.6f}")
        lines.append(f"{a:.1f}\t{b:.4f}\t{cell}")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_preamble_and_missing_cells_are_read_and_said(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rec = step_with_preamble(tmp_path / "p.txt", {30: "NaN", 31: ""})
    code, out, err = run(capsys, "record", str(rec))
    assert code == 0, err
    notes = [ln for ln in out.splitlines() if ln.startswith(f"note: {rec}")]
    assert notes == [
        f"note: {rec}: 3 line(s) above the header (line 4) skipped as a preamble: "
        "'Experiment p4966', 'Operator: X', 'Sample rate: 2 Hz'",
        f"note: {rec}: 2 of 400 data rows dropped for a missing value (empty, NaN) in a "
        "needed column ('Friction' (column 3) 2; lines 35, 36)"]
    assert "398 rows from line 5" in out
    code, out, _ = run(capsys, "record", str(rec), "--json")
    assert json.loads(out)["reading_notes"] == [n.removeprefix("note: ") for n in notes]


def error_line(err: str) -> str:
    """The one error line (a first run's compile notice may precede it on stderr)."""
    (line,) = [ln for ln in err.strip().splitlines() if ln.startswith("error:")]
    return line


@pytest.mark.slow
def test_fit_says_the_same_reading_notes(tmp_path: Path,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    # before the fit, as record says them, and in fit.json (mistake: read, then not a word)
    rec = step_with_preamble(tmp_path / "p.txt", {30: "NaN", 31: ""})
    code, out, err = run(capsys, "fit", str(rec), "--out", str(tmp_path / "f"), "--no-figure",
                         "--no-profile", "--drive", "program", "--state-law", "ageing")
    assert code in (0, 1), err
    # (a first run's compile notice is a note too: not the record's)
    said = [ln for ln in (out + err).splitlines() if ln.startswith(f"note: {rec}")]
    assert [n[:40] for n in said] == [f"note: {rec}: 3 line(s) above the header"[:40],
                                      f"note: {rec}: 2 of 400 data rows dropped"[:40]]
    doc = json.loads((tmp_path / "f" / "fit.json").read_text())
    assert doc["reading_notes"] == [n.removeprefix("note: ") for n in said]


def one_velocity(path: Path) -> Path:
    t = 0.05 * np.arange(1200)  # 59.95 s at 1 um/s: the user's lab_onevel.csv
    rng = np.random.default_rng(5)
    with path.open("w") as fh:
        fh.write("Time(s),Disp(um),Friction\n")
        for a in t:
            fh.write(f"{a:.2f},{a:.4f},{0.6 + rng.normal(0, 3e-4):.5f}\n")
    return path


def test_a_one_velocity_record_gets_its_own_example_and_a_reason(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rec = one_velocity(tmp_path / "one.csv")
    code, _, err = run(capsys, "record", str(rec))
    line = error_line(err)
    assert code == 2 and "it moves at 1 um/s throughout" in line
    example = line.split("e.g. ")[1].split(" ")[0]
    assert example == "0:1e-06,30:1e-05"  # inside the record (the fixed one ended at 1200 s)
    code, out, err = run(capsys, "record", str(rec), "--segments", example)
    assert code == 0 and "  0  step            30 " in out, out + err
    # a one-velocity program given by hand: read (record), refused with its reason (fit)
    code, out, err = run(capsys, "record", str(rec), "--segments", "0:1e-6")
    assert code == 0 and out.strip().splitlines()[-1].endswith(
        "a one-velocity record has no velocity step to fit")
    assert "give the program" not in out
    code, out, err = run(capsys, "fit", str(rec), "--segments", "0:1e-6", "--out",
                         str(tmp_path / "f"))
    line = error_line(err)
    assert code == 2 and line.endswith(
        "given with --segments (1 segment(s), velocities 1e-06 m/s): a one-velocity record "
        "has no velocity step to fit")
    assert not (tmp_path / "f").exists()
