"""Bad values are refused before any work, in one line naming what the user typed (issue 24).

Each case is one the outside run found: an option whose refusal was written inside fit.json
after a fit, a ``--segments`` program that ``record`` accepted and ``fit`` refused, sweep
tables that raised tracebacks, files whose bytes went into the message, a friction cell of
1e300 that overflowed the fit, a record of micrometres read as metres without a word.
"""

from __future__ import annotations

import gzip
from pathlib import Path

import numpy as np
import pytest

from dryfriction.cli import main

LAB = Path(__file__).resolve().parents[2] / "examples" / "data" / "lab" / \
    "sepiolite_velstep_0.2-2um_s.txt"


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    capsys.readouterr()
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def one_error_line(code: int, err: str, *words: str) -> str:
    lines = err.strip().splitlines()
    assert code == 2, err
    assert len(lines) == 1 and lines[0].startswith("error:"), err
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


def small_record(path: Path, header: str = "Time(s)\tDispl(microns)\tFriction",
                 friction_cell: dict[int, str] | None = None) -> Path:
    """A velocity step 0.37 -> 3.1 um/s, 300 rows, with the displacement in micrometres."""
    t = np.linspace(0.0, 240.0, 300)
    v = np.where(t < 120.0, 0.37, 3.1)
    x = np.concatenate(([0.0], np.cumsum(np.diff(t) * v[1:])))
    rng = np.random.default_rng(3)
    mu = 0.61 + 2e-4 * rng.standard_normal(t.size)
    rows = [f"{a:.4f}\t{b:.5f}\t{c:.6f}" for a, b, c in zip(t, x, mu, strict=True)]
    for i, cell in (friction_cell or {}).items():
        a, b, _ = rows[i].split("\t")
        rows[i] = f"{a}\t{b}\t{cell}"
    path.write_text(header + "\n" + "\n".join(rows) + "\n")
    return path


# ------------------------------------------------------------------------- fit options
@pytest.mark.parametrize("option, value", [
    ("--direct", "-1"), ("--direct", "nan"), ("--v-ref", "0"), ("--alpha", "2"),
    ("--traps-per-a0", "-5"), ("--creep", "bogus"), ("--v0", "-1"),
    ("--traps-per-a0", "1e12"),  # a memory refusal naming fit's own option
])
def test_fit_refuses_a_bad_option_before_any_work(option: str, value: str, tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str],
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    # was: exit 0 after 6 s of rsf fitting, the refusal only inside fit.json
    import dryfriction.records.lab

    def no_work(*args: object, **kwargs: object) -> None:
        raise AssertionError("the record was read: work started before the refusal")

    monkeypatch.setattr(dryfriction.records.lab, "read_record", no_work)
    code, _, err = run(capsys, "fit", str(LAB), "--model", "rsf", "--run-cv", option, value,
                       "--out", str(tmp_path / "out"), "--no-figure")
    one_error_line(code, err, option)
    assert not (tmp_path / "out").exists()


# ------------------------------------------------------------------------- --segments
@pytest.mark.parametrize("segments", ["0:-2e-7", "0:1e300", "0:1e300,100:2e-6",
                                      "0:2e-7,100:-1", "0:2e-7,100:1e-300"])
@pytest.mark.parametrize("command", ["record", "fit"])
def test_record_and_fit_refuse_the_same_load_programs(command: str, segments: str,
                                                      tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]
                                                      ) -> None:
    # was: record exit 0, fit a refusal (or 10 lines of NumPy warnings, then "v0")
    rec = small_record(tmp_path / "r.txt")
    extra = ["--model", "rsf", "--out", str(tmp_path / "out")] if command == "fit" else []
    code, _, err = run(capsys, command, str(rec), "--segments", segments, *extra)
    one_error_line(code, err, "--segments", "allowed 0 (a hold) or 1e-30 to 1000 m/s")


# ------------------------------------------------------------------------- files
@pytest.mark.parametrize("kind, said", [
    ("gzip", "is gzip-compressed: decompress it first"),
    ("utf-16", "is UTF-16 text: save it as UTF-8"),
    ("utf-16-le", "is UTF-16 text: save it as UTF-8"),
])
@pytest.mark.parametrize("command", ["record", "fit", "simulate"])
def test_a_file_that_is_not_utf8_text_is_named_in_one_clean_line(
        command: str, kind: str, said: str, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    # was: NUL and binary bytes of the file in the message
    src = small_record(tmp_path / "r.txt") if command != "simulate" else \
        Path(__file__).resolve().parents[2] / "examples" / "velocity_step.toml"
    text = src.read_text()
    data = gzip.compress(text.encode()) if kind == "gzip" else text.encode(kind)
    bad = tmp_path / f"bad{src.suffix}"
    bad.write_bytes(data)
    extra = ["--out", str(tmp_path / "out")] if command != "record" else []
    code, _, err = run(capsys, command, str(bad), *extra)
    line = one_error_line(code, err, f"{bad} {said}")
    assert line.isprintable()


def test_a_friction_cell_of_1e300_is_refused_naming_its_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # was: overflow warnings, exit 1 and rms = inf written
    rec = small_record(tmp_path / "r.txt", friction_cell={150: "1e300"})
    for command in ("record", "fit"):
        extra = ["--model", "rsf", "--out", str(tmp_path / "out")] if command == "fit" else []
        code, _, err = run(capsys, command, str(rec), *extra)
        one_error_line(code, err, "line 152", "column 3 (Friction)", "friction 1e+300",
                       "allowed |friction| <= 10")
    assert not (tmp_path / "out").exists()


def test_an_implausible_apparatus_gets_one_note_with_the_unit_to_give(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the displacement column without a unit: micrometres read as metres, 3.1 m/s
    rec = small_record(tmp_path / "r.txt", header="Time(s)\tDispl\tFriction")
    code, out, err = run(capsys, "record", str(rec))
    assert code == 0
    # fixE: louder (a warning) where the SI reading leaves what friction apparatus do
    notes = [ln for ln in err.splitlines() if ln.startswith(("note:", "warning:"))]
    assert len(notes) == 1, err
    assert notes[0].startswith("warning:")
    assert "load velocities up to 3.1 m/s" in notes[0]
    assert "--columns disp=Displ:um" in notes[0]
    code, out, err = run(capsys, "record", str(rec), "--columns", "disp=Displ:um")
    assert code == 0 and "note:" not in err and "warning:" not in err
    code, out, err = run(capsys, "record", str(small_record(tmp_path / "ok.txt")))
    assert code == 0 and "note:" not in err


# ------------------------------------------------------------------------- sweeps
SWEEP_BASE = """
[model]
alpha = 0.13
eps = 0.04
[ensemble]
traps_per_a0 = 20
initial = "steady"
initial_velocity = 0.1
[drive]
kind = "spring"
stiffness = 0.05
mass = 0.0
segments = [{velocity = 0.1, slip = 4.0}]
[output]
every_slip = 0.05
[stickslip]
transient = 1.0
[sweep]
"""


@pytest.mark.parametrize("line, words", [
    ('"model.eps" = {log = ["a", 1.0, 3]}', ("log start = 'a'", "a finite number")),
    ('"model.eps" = {lin = [0.01, "b", 3]}', ("lin stop = 'b'",)),
    ('"model.eps" = {lin = [0.01, 0.05, true]}', ("n = True", "an integer")),
    ('"model.eps" = {lin = [0.01, 0.05, 1000000000000]}', ("n = 1000000000000",)),
    ('"drive.segments" = [1, 2]', ("drive.segments = 1", "a non-empty list of tables")),
    ('"drive.segments.0.velocity" = [[0.1], [0.2]]', ("drive.segments[0].velocity = [0.1]",
                                                     "wrong type")),
    ('"drive.segments.0" = [1, 2]', ("drive.segments[0] must be a table",)),
    # found by the fuzz (tests/cli/test_fuzz.py): a KeyError traceback
    ('"drive.segments" = [[{velocity = 0.1, slip = 4.0}]]\n"drive.segments.0.velocity" = [0.05]',
     ("keys 'drive.segments' and 'drive.segments.0.velocity' overlap",)),
])
def test_a_sweep_value_of_the_wrong_type_is_one_line(line: str, words: tuple[str, ...],
                                                     tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]
                                                     ) -> None:
    # was: a traceback each (TypeError), or a sweep run with n = 1 for n = true
    proto = tmp_path / "s.toml"
    proto.write_text(SWEEP_BASE + line + "\n")
    code, _, err = run(capsys, "sweep", str(proto), "--out", str(tmp_path / "sw"))
    one_error_line(code, err, str(proto), *words)
    assert not (tmp_path / "sw").exists()


def test_a_ramp_that_starts_above_its_safety_stop_is_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # found by the fuzz: the run stopped at its first sample and its figure failed with
    # "zero-size array to reduction operation fmax"
    proto = tmp_path / "p.toml"
    proto.write_text('[model]\neps = 0.03\n[ensemble]\ntraps_per_a0 = 7\ninitial = "loaded"\n'
                     'initial_force = 0.8\n[drive]\nkind = "force"\nrate = 1.3\nhold = 1.0\n'
                     'max_force = 0.55\n[output]\nevery_slip = 0.05\n')
    code, _, err = run(capsys, "simulate", str(proto), "--out", str(tmp_path / "out"))
    one_error_line(code, err, "drive.max_force = 0.55", "ensemble.initial_force = 0.8")
    assert not (tmp_path / "out").exists()


def test_a_memory_refusal_inside_a_fit_names_the_fits_own_option(
        monkeypatch: pytest.MonkeyPatch) -> None:
    # was: the simulator's hint, "raise every_slip ... lower traps_per_a0", keys fit does not
    # have, in fit.json's notes
    from dryfriction import TrapModel
    from dryfriction.fit import CVModel, cv_series
    from dryfriction.records.data import SeriesData

    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", "1MiB")
    t = np.linspace(0.0, 37.0, 60)
    data = SeriesData(t, np.where(t < 20.0, 1.3e-6, 1.1e-5), np.full(t.size, 0.61),
                      source="s.csv")
    with pytest.raises(ValueError) as exc:
        cv_series(CVModel(TrapModel(), traps_per_a0=3e4),
                  {"eps": 0.03, "t0": 0.7, "a0": 2.1e-6, "mu_el": 0.5}, data)
    msg = str(exc.value)
    assert msg.startswith("s.csv: a trap-model run") and "--traps-per-a0" in msg
    assert "every_slip" not in msg and "traps_per_a0 " not in msg


# ------------------------------------------------------------------------- rsf velocities
@pytest.mark.parametrize("argv, words", [
    # was: "segments[0].velocity = -1 m/s is out of range", a name the user never typed
    (["--v1", "-3.7e-6"], ["--v1", "-3.7e-06", "--stiffness inf --regularized"]),
    (["--v2", "-2.3e-5"], ["--v2", "-2.3e-05"]),
    (["--v1", "-3.7e-6", "--stiffness", "inf"], ["--v1", "--regularized"]),
    # was: "give v_init (> 0, m/s)", the library's parameter name
    (["--v1", "0"], ["--v-init", "--v1 is 0"]),
    (["--v1", "-3.7e-6", "--stiffness", "inf", "--regularized"], ["--v-init"]),
])
def test_rsf_velocities_name_the_option(capsys: pytest.CaptureFixture[str],
                                        tmp_path: Path, argv: list[str],
                                        words: list[str]) -> None:
    out = tmp_path / "out"
    code, _, err = run(capsys, "rsf", *argv, "--no-figure", "--out", str(out))
    one_error_line(code, err, *words)
    assert not out.exists()  # refused before any work


def test_rsf_sliding_back_runs_where_the_law_allows_it(capsys: pytest.CaptureFixture[str]):
    code, _, err = run(capsys, "rsf", "--v1", "-3.7e-6", "--stiffness", "inf", "--regularized",
                       "--v-init", "2.9e-6", "--t1", "1.5", "--t2", "0.7", "--no-figure")
    assert code == 0, err


@pytest.mark.parametrize("a0, t0, words", [
    # was: "--u = 0 is out of range", an option the user of --V never typed
    ("1e300", "1e-300", ["--a0", "--t0", "V* = a0/t0 = inf"]),
    ("3.3e-6", "1e300", ["--V 2.7e-06 m/s", "--a0 3.3e-06", "u = V t0/a0"]),
])
def test_steady_si_velocity_out_of_range_names_v(capsys: pytest.CaptureFixture[str],
                                                 a0: str, t0: str, words: list[str]) -> None:
    code, _, err = run(capsys, "steady", "--eps", "0.021", "--V", "2.7e-6", "--a0", a0,
                       "--t0", t0)
    one_error_line(code, err, *words)
