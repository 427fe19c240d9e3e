"""Laboratory records: header dialects, units, the column map, every refusal by file, line and
column; the load program detected from a noisy displacement; the steps cut from it."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from dryfriction.records.lab import (
    LabRecord,
    detect_segments,
    load_velocity_series,
    parse_column_map,
    parse_segments,
    read_record,
    segments_table,
    slice_steps,
)

# shipped with its licence and citation (examples/data/lab/README.md)
SHARED = (Path(__file__).resolve().parents[2] / "examples" / "data" / "lab"
          / "sepiolite_velstep_0.2-2um_s.txt")


def write(tmp_path: Path, text: str, name: str = "rec.txt") -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def table(header: str, rows: list[list[float]], sep: str = "\t") -> str:
    return header + "\n" + "".join(sep.join(f"{v:.9g}" for v in r) + "\n" for r in rows)


def ramp(n: int = 12) -> list[list[float]]:
    """t, displacement, friction, normal: simple increasing rows."""
    return [[0.5 * i, 2.0 * i, 0.6 + 0.001 * i, 10.0] for i in range(n)]


# ----------------------------------------------------------------------------- reading
def test_shared_record_reads_in_si() -> None:
    r = read_record(SHARED)
    # examples/data/lab/README.md and docs/tutorials/lab-record.md: 23,790 rows, one header
    assert len(r) == 23790 and r.first_line == 2
    assert dict(r.columns) == {"time": "Time(s)", "disp": "Displ(microns)", "mu": "Friction",
                               "normal": "EffectiveNormalstress(MPa)"}
    # first data line: 8105.381000 1554.674000 0.536278 29.999476
    assert r.time[0] == 8105.381
    assert r.load_point[0] == pytest.approx(1554.674e-6, rel=1e-12)
    assert r.friction[0] == 0.536278
    assert r.normal_stress[0] == pytest.approx(29.999476e6, rel=1e-12)
    assert r.normal_unit == "Pa" and r.load_velocity is None
    assert r.time[-1] - r.time[0] == pytest.approx(3226, abs=1)  # the same: 3,226 s
    assert r.load_point[-1] - r.load_point[0] == pytest.approx(2.4e-3, rel=0.03)  # 2.4 mm


def test_comma_dialect_friction_from_shear_over_normal(tmp_path: Path) -> None:
    rows = [[10.0 + i, 1.5 + 0.001 * i, 6.0, 10.0 + (i == 3)] for i in range(12)]
    r = read_record(write(tmp_path, table("time[s],LP_disp[mm],Shear_stress[MPa],"
                                          "Normal_stress[MPa]", rows, ","), "a.csv"))
    assert r.load_point[0] == pytest.approx(1.5e-3, rel=1e-12)  # mm -> m
    assert r.friction[0] == pytest.approx(0.6) and r.friction[3] == pytest.approx(6 / 11)
    assert r.normal_stress[3] == pytest.approx(11e6) and r.normal_unit == "Pa"
    assert r.columns["shear"] == "Shear_stress[MPa]" and "mu" not in r.columns


def test_tab_dialect_disp_um_time_ms(tmp_path: Path) -> None:
    rows = [[500.0 * i, 2.0 * i, 0.55] for i in range(12)]
    r = read_record(write(tmp_path, table("Time(ms)\tDisp(um)\tFriction", rows)))
    assert r.time[1] == pytest.approx(0.5) and r.load_point[1] == pytest.approx(2e-6)
    assert r.normal_stress is None and r.normal_unit == ""
    # trailing empty columns on every line; the effective normal stress wins over the total
    text = "Time(s)\tNormal_stress(MPa)\tDisp(um)\tEffective_normal_stress(MPa)\tmu\t\t\n"
    text += "".join(f"{i}\t50\t{i}\t30\t0.6\t\t\n" for i in range(12))
    r = read_record(write(tmp_path, text, "trailing.txt"))
    assert r.columns["normal"] == "Effective_normal_stress(MPa)"
    assert r.normal_stress[0] == pytest.approx(30e6) and len(r) == 12


@pytest.mark.parametrize("header, column, value, expect", [
    ("Time(min)", "time", 2.0, 120.0),
    ("Time(h)", "time", 1.5, 5400.0),
    ("Disp(nm)", "load_point", 250.0, 250e-9),
    ("Disp(microns)", "load_point", 3.0, 3e-6),
    ("Disp(µm)", "load_point", 3.0, 3e-6),
    ("Disp[m]", "load_point", 3.0, 3.0),
    ("lp_velocity(um/s)", "load_velocity", 10.0, 1e-5),
    ("Normal_stress(kPa)", "normal_stress", 5.0, 5e3),
    ("Normal_force(kN)", "normal_stress", 5.0, 5e3),
])
def test_units_convert_to_si(tmp_path: Path, header: str, column: str, value: float,
                             expect: float) -> None:
    names = {"time": "Time(s)", "load_point": "Disp(um)", "load_velocity": "Disp(um)",
             "normal_stress": "Normal_stress(MPa)"}
    names[column] = header
    cols = [names["time"], names["load_point"] if column != "load_velocity" else header,
            "mu", names["normal_stress"]]
    rows = [[1.0 + i, 1.0, 0.5, 1.0] for i in range(12)]
    for r in rows:
        r[{"time": 0, "load_point": 1, "load_velocity": 1, "normal_stress": 3}[column]] = value
    if column == "time":
        rows = [[value * (i + 1), 1.0, 0.5, 1.0] for i in range(12)]
    rec = read_record(write(tmp_path, table("\t".join(cols), rows)))
    got = getattr(rec, column)[0]
    assert got == pytest.approx(expect, rel=1e-12)
    if "force" in header:
        assert rec.normal_unit == "N"


def test_spaces_units_row_comments_and_trailing_columns(tmp_path: Path) -> None:
    text = ("# exp 7, gouge\n\nTime (s)   Shear_stress (MPa)   LP_disp   Normal_stress (MPa)\n"
            "s   -   mm   -\n")
    text += "".join(f"{i:.1f}   {3.0 + 0.1 * i:.2f}   {0.01 * i:.3f}   5.00   \n"
                    for i in range(12))
    r = read_record(write(tmp_path, text))
    assert r.first_line == 5
    assert r.load_point[3] == pytest.approx(0.03e-3)  # mm from the units row
    assert r.friction[2] == pytest.approx(3.2 / 5.0)
    # semicolons with decimal commas, a comment and blank line among the data
    rows = "".join(f"{i},5;{i * 2},0;0,5{i % 10}\n" + ("# paused\n\n" if i == 4 else "")
                   for i in range(12))
    r = read_record(write(tmp_path, "t[s];displacement[um];mu;\n" + rows, "b.txt"))
    assert r.time[1] == 1.5 and r.load_point[2] == pytest.approx(4e-6)
    assert r.friction[3] == pytest.approx(0.53) and len(r) == 12


def test_column_map_overrides_and_gives_units(tmp_path: Path) -> None:
    assert parse_column_map("time=Zeit, disp=Weg:mm,friction=Reibung") == {
        "time": "Zeit", "disp": "Weg:mm", "mu": "Reibung"}
    rows = [[i, 0.1 * i, 0.01 * i, 0.4] for i in range(12)]
    p = write(tmp_path, table("Zeit\tWeg\tHor_disp(um)\tReibung", rows))
    r = read_record(p, parse_column_map("time=Zeit,disp=Weg:mm,mu=REIBUNG"))
    assert r.load_point[5] == pytest.approx(0.5e-3)  # the map's unit: mm
    assert r.columns["disp"] == "Weg" and r.units["disp"] == "mm"
    # two displacement-like names: the guess refuses, the map chooses
    p2 = write(tmp_path, table("Time(s)\tDisp(um)\tShear_disp(um)\tmu", rows), "c.txt")
    with pytest.raises(ValueError, match=r"could each be.*--columns disp="):
        read_record(p2)
    r2 = read_record(p2, {"disp": "Shear_disp"})
    assert r2.load_point[5] == pytest.approx(0.01 * 5 * 1e-6)
    for bad, msg in [("disp", "expected key=name"), ("speed=V", "unknown key"),
                     ("t=a,time=b", "given twice")]:
        with pytest.raises(ValueError, match=msg):
            parse_column_map(bad)
    with pytest.raises(ValueError, match=r"c\.txt, line 1: --columns mu=Reib.*found"):
        read_record(p2, {"mu": "Reib"})


# ----------------------------------------------------------------------------- refusals
GOOD = "Time(s)\tDispl(microns)\tFriction\n" + "".join(
    f"{i}\t{2 * i}\t0.6\n" for i in range(12))


@pytest.mark.parametrize("text, where, what", [
    ("Time(s)\tLoad(kN)\tFriction\n" + "1\t2\t3\n" * 12, "line 1",
     r"no load-point displacement.*'Load\(kN\)'.*--columns disp="),
    # the unit is refused before the data are read (the bad cells below are never reached)
    ("Time(s)\tDispl(furlongs)\tFriction\n" + "1\tx\t3\n" * 12, "line 1, column 2",
     r"unknown unit \(furlongs\).*accepted.*mm"),
    ("Time(fortnights)\tDispl(um)\tFriction\n" + "1\t2\t3\n" * 12, "line 1, column 1",
     r"unknown unit.*accepted.*min"),
    (GOOD.replace("5\t10\t0.6", "5\t1O\t0.6"), "line 7, column 2", r"'1O' is not a number"),
    ("# c\n" + GOOD.replace("\n5\t10\t", "\n\n# gap\n5\t1O\t"), "line 10, column 2",
     r"'1O' is not a number"),
    # a missing value in 1 of 12 rows is more than MISSING_MAX to drop (test_missing_values)
    (GOOD.replace("5\t10\t0.6", "5\t10\tnan"), "line 7, column 3",
     r"1 of 12 data rows have a missing value.*more than 5 %"),
    (GOOD.replace("5\t10\t0.6", "4\t10\t0.6"), "line 7, column 1",
     r"time 4 does not increase \(previous 4\)"),
    (GOOD.replace("5\t10\t0.6", "5\t\t0.6"), "line 7, column 2",
     r"1 of 12 data rows have a missing value \(empty, NaN\)"),
    ("Time(s)\tDispl(um)\tFriction\n" + "1\t2\t0.6\n2\t3\t0.6\n", "line 3",
     r"only 2 data rows"),
    ("Time(s)\tDispl(um)\tShear(MPa)\tNormal(kN)\n" + "".join(f"{i}\t1\t2\t3\n"
                                                               for i in range(12)),
     "line 1", r"stress.*force|force.*stress"),
])
def test_every_refusal_names_file_line_and_column(tmp_path: Path, text: str, where: str,
                                                  what: str) -> None:
    p = write(tmp_path, text, "bad_rec.txt")
    with pytest.raises(ValueError, match=what) as exc:
        read_record(p)
    msg = str(exc.value)
    assert msg.startswith(f"{p}, {where}"), msg
    assert "\n" not in msg


def test_line_numbers_count_comments_and_blank_lines(tmp_path: Path) -> None:
    text = "# header comment\nTime(s)\tDispl(um)\tFriction\n" + "".join(
        f"{i}\t{i}\t0.6\n" + ("\n# note\n" if i == 2 else "") for i in range(12))
    text = text.replace("7\t7\t0.6", "7\t7\tinf")  # data row 8: file line 2 + 8 + 2 = 12
    p = write(tmp_path, text)
    with pytest.raises(ValueError, match=r"line 12, column 3 \(Friction\): inf"):
        read_record(p)


def test_memory_estimate_refuses_before_reading(tmp_path: Path,
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", "1KB")
    with pytest.raises(ValueError, match=r"rec\.txt.*more than the limit.*split the file"):
        read_record(write(tmp_path, GOOD))


def test_hundred_thousand_rows_read_exactly(tmp_path: Path) -> None:
    rng = np.random.default_rng(3)
    n = 100_000
    t = 7.0 + np.cumsum(rng.uniform(0.01, 0.02, n))
    x = np.round(1e3 + 0.3 * t + rng.normal(0, 0.2, n), 3)
    mu = np.round(0.6 + rng.normal(0, 1e-3, n), 6)
    body = np.column_stack([np.round(t, 4), x, mu])
    p = tmp_path / "big.txt"
    with open(p, "w") as fh:
        fh.write("Time(s)\tDispl(microns)\tFriction\n")
        np.savetxt(fh, body, fmt=["%.4f", "%.3f", "%.6f"], delimiter="\t")
    r = read_record(p)
    assert len(r) == n
    assert np.array_equal(r.time, np.round(t, 4))
    assert np.allclose(r.load_point, x * 1e-6, rtol=1e-15, atol=0)
    assert np.array_equal(r.friction, mu)


# ----------------------------------------------------------------------------- load program
def synthetic(program: list[tuple[float, float]], t_end: float, *, noise: float = 0.3e-6,
              dt: tuple[float, float] = (0.1, 0.1), t_rate: float | None = None,
              t0: float = 500.0, seed: int = 0) -> LabRecord:
    """A record of a known program: (start, velocity) pairs, times from 0; sampling dt[0]
    before ``t_rate`` and dt[1] after; Gaussian noise then 0.1 um quantisation."""
    rng = np.random.default_rng(seed)
    tr = t_end if t_rate is None else t_rate
    t = np.concatenate([np.arange(0.0, tr, dt[0]), np.arange(tr, t_end, dt[1])])
    starts = np.array([s for s, _ in program] + [np.inf])
    vel = np.array([v for _, v in program])
    x = np.zeros_like(t)
    for s, e, v in zip(starts[:-1], starts[1:], vel, strict=True):
        x += v * np.clip(t - s, 0.0, e - s)
    x = np.round((1e-3 + x + rng.normal(0.0, noise, t.size)) / 1e-7) * 1e-7
    mu = 0.6 + 1e-3 * rng.normal(size=t.size)
    return LabRecord("synthetic.txt", t + t0, x, None, mu, None, "", {}, 2)


def check_program(segs: tuple, program: list[tuple[float, float]], t0: float, dt: float,
                  samples: int = 5, rel: float = 0.03) -> None:
    assert len(segs) == len(program), segments_table(segs)
    for s, (start, v) in zip(segs, program, strict=True):
        assert abs(s.t_start - (t0 + start)) <= samples * dt, segments_table(segs)
        if v == 0.0:
            assert s.velocity == 0.0
        else:
            assert s.velocity == pytest.approx(v, rel=rel), segments_table(segs)


def test_detects_velocity_steps_through_noise_and_a_sampling_rate_change() -> None:
    prog = [(0.0, 1e-6), (300.0, 1e-5), (420.0, 1e-6), (700.0, 3e-6), (900.0, 1e-6)]
    rec = synthetic(prog, 1100.0, dt=(0.1, 0.4), t_rate=600.0, seed=1)
    segs = detect_segments(rec)
    check_program(segs, prog, 500.0, 0.4)
    # contiguous, covering every sample, and v_load per sample follows
    assert segs[0].i_start == 0 and segs[-1].i_end == len(rec)
    assert all(a.i_end == b.i_start for a, b in zip(segs, segs[1:], strict=False))
    v = load_velocity_series(rec, segs)
    assert v[0] == segs[0].velocity and v[-1] == segs[-1].velocity
    assert v[segs[2].i_start] == segs[2].velocity != v[segs[2].i_start - 1]
    # the two 1 um/s stretches get one plateau value
    assert segs[0].velocity == segs[2].velocity == segs[4].velocity


def test_slow_wobble_makes_no_false_steps_and_keeps_the_hold() -> None:
    # a load point that wobbles 0.3 um with a 20 s period (a motor's gear), sampled 10x
    # faster from 650 s: short stretches' slopes scatter, yet they are neither steps nor moves
    prog = [(0.0, 1e-6), (300.0, 1e-5), (420.0, 1e-6), (700.0, 3e-6), (900.0, 0.0),
            (1000.0, 1e-6)]
    rec = synthetic(prog, 1300.0, noise=0.5e-6, dt=(0.1, 0.01), t_rate=650.0, seed=3)
    x = np.asarray(rec.load_point) + 0.3e-6 * np.sin(2 * np.pi * rec.time / 20.0)
    wobbly = LabRecord("w.txt", rec.time, x, None, rec.friction, None, "", {}, 2)
    check_program(detect_segments(wobbly), prog, 500.0, 0.1)


def test_wide_range_of_velocities_slowest_is_not_a_hold() -> None:
    # 0.1 and 300 um/s in one record (factor 3000), then a real hold
    prog = [(0.0, 3e-4), (50.0, 1e-7), (550.0, 3e-4), (600.0, 0.0), (700.0, 1e-7)]
    rec = synthetic(prog, 1200.0, noise=0.3e-6, seed=8)
    check_program(detect_segments(rec), prog, 500.0, 0.1)


def test_detects_holds_and_slices_slide_hold_slide() -> None:
    prog = [(0.0, 1e-5), (100.0, 0.0), (130.0, 1e-5), (230.0, 0.0), (530.0, 1e-5),
            (640.0, 3e-5)]
    rec = synthetic(prog, 720.0, noise=0.2e-6, seed=2)
    segs = detect_segments(rec)
    check_program(segs, prog, 500.0, 0.1)
    steps = slice_steps(rec, segs)
    assert [w.kind for w in steps] == ["shs", "shs", "step"]
    assert [w.hold for w in steps[:2]] == pytest.approx([30.0, 300.0], abs=0.5)
    assert steps[2].v_before == pytest.approx(1e-5, rel=0.03)
    assert steps[2].v_after == pytest.approx(3e-5, rel=0.03)
    for w, s in zip(steps, (segs[1], segs[3], segs[5]), strict=True):
        assert w.t_change == s.t_start
        # 50 um of sliding at 10 um/s before the change (5 s), unless half the stretch is less
        lead = s.t_start - rec.time[w.i_start]
        assert lead == pytest.approx(min(5.0, 0.5 * (segs[segs.index(s) - 1].duration)),
                                     abs=0.11)
    assert steps[0].i_end == segs[2].i_end and steps[2].i_end == len(rec)
    assert [w.index for w in steps] == [0, 1, 2]


def test_velocity_column_gives_the_program_too() -> None:
    t = np.arange(0.0, 400.0, 0.2)
    v = np.where(t < 150.0, 2e-6, 2e-5) + np.random.default_rng(4).normal(0, 2e-7, t.size)
    rec = LabRecord("v.txt", t, None, v, np.full(t.size, 0.6), None, "", {}, 2)
    check_program(detect_segments(rec), [(0.0, 2e-6), (150.0, 2e-5)], 0.0, 0.2)


def test_no_step_is_refused_naming_the_file() -> None:
    rec = synthetic([(0.0, 1e-6)], 300.0, seed=5)
    segs = detect_segments(rec)
    assert len(segs) == 1 and segs[0].velocity == pytest.approx(1e-6, rel=0.03)
    with pytest.raises(ValueError, match=r"^synthetic\.txt: no velocity step or hold"):
        slice_steps(rec, segs)


def test_segments_given_by_hand() -> None:
    rec = synthetic([(0.0, 2e-7), (1200.0, 2e-6)], 2000.0, t0=8000.0, seed=6)
    segs = parse_segments("0:2e-7, 1200:2e-6", rec)
    assert [s.velocity for s in segs] == [2e-7, 2e-6]
    assert segs[1].t_start == 9200.0 and segs[0].t_end == 9200.0
    assert rec.time[segs[1].i_start] >= 9200.0 > rec.time[segs[1].i_start - 1]
    assert segs[1].i_end == len(rec)
    text = segments_table(segs)
    assert "(s)" in text and "(m/s)" in text and len(text.splitlines()) == 4  # + legend
    for bad, msg in [("5:2e-7", "must start at 0"), ("0:2e-7,1200", "start:velocity"),
                     ("0:2e-7,9200:1e-6", "outside synthetic.txt"),
                     ("0:1e-6,300:0,200:1e-6", "must increase"), ("0:x", "start:velocity")]:
        with pytest.raises(ValueError, match=msg):
            parse_segments(bad, rec)


def test_the_segments_form_is_the_shortest_decimal_that_reads_back() -> None:
    # the mistakes: a start printed with its float noise (a new user was given 139.99998 for
    # a record whose clock ran in minutes), and a start rounded to the nearest decimal (140
    # would select the next sample)
    from dryfriction.records.labsteps import make_segments, segments_spec

    rng = np.random.default_rng(38)
    for trial in range(40):
        # a clock in minutes written with 7 decimals, a first sample off 0, a jittered rate
        dt = rng.choice([0.05, 0.02, 0.1, 1.0 / 3.0]) * (1 + 0.01 * rng.standard_normal(900))
        t = np.round((417.3 + np.cumsum(dt)) / 60.0, 7) * 60.0
        idx = sorted(rng.choice(np.arange(5, 895), 3, replace=False).tolist())
        vel = [2.3e-6, 7.1e-6, 0.0, 1.9e-6]
        segs = make_segments(t, [0, *idx, t.size], vel)
        rec = LabRecord("m.txt", t, np.zeros(t.size), None, np.full(t.size, 0.6), None, "",
                        {}, 2)
        spec = segments_spec(segs, float(t[0]), t)
        back = parse_segments(spec, rec)
        assert [g.i_start for g in back] == [g.i_start for g in segs], (trial, spec)
        for item, g in zip(spec.split(",")[1:], segs[1:], strict=True):
            start = item.split(":")[0]
            x, prev = t[g.i_start] - t[0], t[g.i_start - 1] - t[0]
            assert prev < float(start) <= x
            # shortest: one decimal fewer falls at or before the sample before
            d = len(start.partition(".")[2])
            if d:
                assert np.floor(x * 10 ** (d - 1)) / 10 ** (d - 1) <= prev
    # the user's case: a sample 2e-5 s before 140 s, its predecessor 0.05 s earlier
    t = np.append(np.arange(0.0, 139.96, 0.05), [139.99998, 140.04998, 140.09998])
    segs = make_segments(t, [0, t.size - 3, t.size], [1e-6, 1e-5])
    assert segments_spec(segs, 0.0, t) == "0:1e-06,139.99:1e-05"
    assert segments_spec(segs, 0.0) == "0:1e-06,139.99998:1e-05"  # without the clock


def test_shared_record_program_and_step() -> None:
    r = read_record(SHARED)
    segs = detect_segments(r)
    v = [s.velocity for s in segs]
    # a 0.2 -> 2 um/s record: the velocities alternate between those two values
    assert len(v) >= 2
    assert all(x == pytest.approx(2e-7, rel=0.03) for x in v[0::2])
    assert all(x == pytest.approx(2e-6, rel=0.03) for x in v[1::2])
    # the step: 50-s slopes change between 2200 s and 2250 s after the start
    assert 2200.0 < segs[1].t_start - r.time[0] < 2250.0
    steps = slice_steps(r, segs)
    assert len(steps) == len(segs) - 1 and steps[0].kind == "step"
    w = steps[0]
    assert w.v_before < w.v_after and w.i_start < segs[1].i_start < w.i_end
    assert r.time[segs[1].i_start] - r.time[w.i_start] == pytest.approx(250.0, abs=1.0)


# ----------------------------------------------------------------------------- command line
def test_record_command_shows_columns_program_and_steps(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from dryfriction.cli import app

    rec = synthetic([(0.0, 1e-6), (200.0, 1e-5)], 400.0, seed=7)
    rows = np.column_stack([rec.time, rec.load_point * 1e3, rec.friction])
    p = write(tmp_path, table("time[s],LP_disp[mm],mu", rows.tolist(), ","), "r.csv")
    runner = CliRunner()
    r = runner.invoke(app, ["record", str(p)])
    assert r.exit_code == 0, r.output
    assert "LP_disp[mm]" in r.output and "velocity (m/s)" in r.output
    assert "step" in r.output.split("steps:")[1]
    # the steps' line in the units its head names (um/s): 1 -> 10 um/s
    head, line = r.output.split("steps:")[1].strip().splitlines()[:2]
    assert "v_before (um/s)" in head and "v_after (um/s)" in head
    cells = line.split()
    assert float(cells[3]) == pytest.approx(1.0, rel=0.02)
    assert float(cells[4]) == pytest.approx(10.0, rel=0.02)
    r = runner.invoke(app, ["record", str(p), "--segments", "0:1e-6,200:1e-5", "--json"])
    assert r.exit_code == 0, r.output
    rep = json.loads(r.output)
    assert [s["velocity"] for s in rep["segments"]] == [1e-6, 1e-5]
    assert rep["steps"][0]["t_change"] == pytest.approx(700.0)
    r = runner.invoke(app, ["record", str(p), "--columns", "disp=nope"])
    assert r.exit_code == 2 and "r.csv, line 1" in r.output and "nope" in r.output


def test_segments_table_gives_the_normal_column_in_its_own_unit(tmp_path: Path) -> None:
    """The mistake this is for: the table divided every normal value by 1e6 and said
    "MPa (force: kN)", so a record with a normal force of 4.2 kN printed 0.0042 (in MN). The
    table and segments.csv must give the same number in the same unit."""
    from dryfriction.records.labsteps import Segment, write_segments_csv

    for unit, value, shown, name in (("Pa", 13.7e6, "13.7", "normal (MPa)"),
                                     ("N", 4.2e3, "4.2", "normal (kN)")):
        segs = (Segment(3.5, 80.25, 2.5e-6, 0, 700, 40.0, value),)
        text = segments_table(segs, unit)
        header, row = text.splitlines()[:2]
        assert name in header and row.split()[-1] == shown, text
        write_segments_csv(tmp_path / f"s{unit}.csv", segs, 3.5, unit)
        csv_lines = (tmp_path / f"s{unit}.csv").read_text().splitlines()
        assert csv_lines[1].endswith(f"[{name[8:-1]}]")
        assert float(csv_lines[2].split(",")[-1]) == pytest.approx(float(shown))
