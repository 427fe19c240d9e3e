"""Every number a user keeps carries its unit: each CSV column of every writer has a header
``name[unit]`` (or is a label declared so), each JSON number a unit in the document's
``units`` object or its own ``unit`` (dryfriction.io.units). sweep.nc's ``units`` attributes:
tests/sweeps/test_cf.py. The results folder's manifest (dryfriction.json: hashes, times) and a
sweep's resume records (points/*.json, read back by the sweep only) are bookkeeping, not
results."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.io import units as U
from dryfriction.io.files import write_csv
from lab_synth import Truth, synth_record, write_lab_file
from output_units import check_folder

EXAMPLES = Path(__file__).parents[2] / "examples"
def _run(*args: str) -> None:
    r = CliRunner().invoke(app, list(args))
    assert r.exit_code == 0, r.output


@pytest.fixture(scope="module")
def record(tmp_path_factory: pytest.TempPathFactory) -> Path:
    t, _, mu, x = synth_record(Truth(), [1.3e-6, 4.1e-6], duration_slip=300e-6)
    return write_lab_file(tmp_path_factory.mktemp("rec") / "rec.txt", t, x, mu)


SHS = EXAMPLES / "slide_hold_slide.toml"


@pytest.mark.parametrize("args", [
    ("simulate", str(EXAMPLES / "velocity_step.toml"), "--no-figure"),
    ("simulate", str(EXAMPLES / "rsf_velocity_step.toml"), "--no-figure"),
    ("rsf", "--no-figure"),
    ("rsf", "--case", "shs", "--no-figure"),
    ("bifurcation", str(EXAMPLES / "rsf_stick_slip.toml"), "--velocities", "1e-6,3e-6",
     "--no-figure"),
    ("fit", str(EXAMPLES / "data" / "synthetic_velocity_step_rsf.csv"), "--model", "rsf",
     "--no-figure", "--no-compare", "--no-profile"),
    ("fit", str(EXAMPLES / "data" / "synthetic_static_paper.csv"),
     str(EXAMPLES / "data" / "synthetic_steady_paper.csv"), "--no-figure", "--no-profile"),
    # the force and spring drives' own summary keys (threshold, slips: found without units)
    ("simulate", str(EXAMPLES / "static_threshold_loaded.toml"), "--no-figure"),
    ("simulate", str(EXAMPLES / "spring_stick_slip.toml"), "--no-figure"),
], ids=["simulate-cv", "simulate-rsf", "rsf-step", "rsf-shs", "bifurcation", "fit-csv",
        "fit-csv-cv", "simulate-force", "simulate-spring"])
def test_every_column_has_a_unit(tmp_path: Path, args: tuple[str, ...]) -> None:
    out = tmp_path / "out"
    _run(*args, "--out", str(out))
    assert check_folder(out) == []


def test_trap_bifurcation_has_units(tmp_path: Path) -> None:
    """The trap-model route of ``bifurcation`` (reduced units: io.units.TRAP_BIFURCATION_UNITS)."""
    proto = tmp_path / "trap.toml"
    proto.write_text((EXAMPLES / "spring_inertial.toml").read_text().replace(
        "eps = 0.04", "eps = 0.04\ndirect = 0.02"))
    out = tmp_path / "out"
    _run("bifurcation", str(proto), "--velocities", "0.04", "--no-figure", "--out", str(out))
    assert check_folder(out) == []
    assert "[a0/t0]" in (out / "bifurcation.csv").read_text()


def test_snapshots_have_units(tmp_path: Path) -> None:
    out = tmp_path / "out"
    _run("simulate", str(SHS), "--out", str(out), "--no-figure")
    assert any(p.name.startswith("snapshot_") for p in out.iterdir())
    assert check_folder(out) == []


@pytest.mark.slow
def test_record_fit_chooses_rsf_and_has_units(tmp_path: Path, record: Path) -> None:
    out = tmp_path / "out"
    # no --model: a record is fitted with rate-and-state (the default cv was refused: exit 2)
    r = CliRunner().invoke(app, ["fit", str(record), "--out", str(out)])
    assert r.exit_code == 0, r.output
    # the table: units in its headers, mu0, which machine parameters were fitted, the law
    for word in ("dc[m]", "stiffness[1/m]", "mu0[1]", "fitted", "k, trend", "ageing",
                 "v0 = v_before"):
        assert word in r.stdout, word
    assert {"steps.csv", "segments.csv", "fit.json"} <= {p.name for p in out.iterdir()}
    assert check_folder(out) == []
    rows = U.read_rows(out / "steps.csv")
    head = (out / "steps.csv").read_text().splitlines()[0].split(",")
    assert {"dc[m]", "stiffness[1/m]", "trend[1/m]", "t_change[s]", "a[1]"} <= set(head)
    assert float(rows[0]["dc"]) == pytest.approx(20e-6, rel=0.1)


def test_compare_has_units_and_reports_progress(tmp_path: Path) -> None:
    from dryfriction.app.runs import compare

    out = tmp_path / "out"
    calls: list[tuple[float, float, str]] = []
    compare(EXAMPLES / "velocity_step.toml", out, figure=False,
            progress=lambda d, n, w: calls.append((d, n, w)))
    assert check_folder(out) == []
    # progress through the trap model's run, then the twin's stage (compare took 6-14 s silent)
    done = [c[0] for c in calls]
    assert done == sorted(done) and all(c[1] == 100.0 for c in calls)
    assert calls[0][2] == "trap model" and calls[-1] == (100.0, 100.0, "done")
    assert any(w.startswith("rate-and-state twin, start") for _, _, w in calls)
    assert len(calls) > 20
    doc = json.loads((out / "compare.json").read_text())
    assert doc["units"]["dc_a0"] == "a0" and doc["unit_system"].startswith("reduced")


def test_the_check_catches_a_column_without_unit(tmp_path: Path) -> None:
    # the check itself can fail: a bare quantity, an empty unit, an undeclared JSON number
    (tmp_path / "a.csv").write_text("t[s],dc,kind,mu[]\n1,2,step,3\n")
    (tmp_path / "b.json").write_text('{"units": {"t": "s"}, "t": 1, "peak_x": 2, '
                                     '"p": {"value": 1, "unit": "m"}}')
    assert check_folder(tmp_path) == ["a.csv: dc", "a.csv: mu[]", "b.json: peak_x"]


def test_a_writer_refuses_a_column_without_unit(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="no unit declared for the column.*dc"):
        write_csv(tmp_path / "x.csv", {"t": [1.0], "dc": [2.0]}, {"t": "s"})
    assert not (tmp_path / "x.csv").exists()


def test_headers_read_back_new_and_old(tmp_path: Path) -> None:
    write_csv(tmp_path / "new.csv", {"t": [1.5], "mu": [0.6], "kind": ["step"]},
              {"t": "s", "mu": "", "kind": None})
    assert (tmp_path / "new.csv").read_text().splitlines()[0] == "t[s],mu[1],kind"
    (tmp_path / "old.csv").write_text("# a comment\nt,mu,kind\n1.5,0.6,step\n")
    assert U.read_rows(tmp_path / "new.csv") == U.read_rows(tmp_path / "old.csv") == [
        {"t": "1.5", "mu": "0.6", "kind": "step"}]


def test_fit_figure_title_gives_units() -> None:
    # the title printed bare numbers (a0 = 8.266e-07): each value now carries its unit
    from dryfriction.fit import fit
    from dryfriction.plots.fits import plot_fit
    from dryfriction.records.data import read_csv

    data = read_csv(EXAMPLES / "data" / "synthetic_velocity_step_rsf.csv")
    result = fit([data], "rsf", profile=False, consistency=False)
    fig, _ = plot_fit(result, [data])
    title = fig._suptitle.get_text()
    dc = next(p for p in result.parameters if p.name == "dc")
    assert f"dc = {dc.value:.4g} m" in title, title


@pytest.mark.parametrize("args", [
    ("trap",),
    ("static", "--eps", "0.04", "--T", "1", "10", "--direct", "0.01", "--pull-velocity", "1"),
    ("static", "--eps", "0.04", "--t-w", "1", "--t0", "0.1", "--mu-el", "0.5", "--load", "0.3"),
    ("steady", "--eps", "0.04", "--V", "1e-6", "--a0", "1e-6", "--t0", "1"),
    ("stability", "--eps", "0.04", "--u", "0.1", "--M", "1", "--eta", "1", "--direct", "0.01"),
    ("rsf",),
], ids=["trap", "static", "static-si", "steady-si", "stability", "rsf"])
def test_printed_json_has_units(args: tuple[str, ...]) -> None:
    # --json on standard output is JSON a user keeps too (it had no units object)
    r = CliRunner().invoke(app, [*args, "--json"])
    assert r.exit_code == 0, r.output
    assert U.undeclared(json.loads(r.stdout)) == []


def test_record_json_has_units(record: Path) -> None:
    r = CliRunner().invoke(app, ["record", str(record), "--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert U.undeclared(doc) == [] and doc["units"]["t_change"] == "s"
