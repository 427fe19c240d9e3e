"""Sweeps of extended-interface protocols (:mod:`dryfriction.analysis.interface_sweep`, the
``dryfriction sweep`` command on an ``[interface]`` protocol): every point's catalogue
statistics against the same protocol simulated alone, and the refusals before any worker.

Each test names the plausible mistakes it is for (seen failing with each applied, then
reverted).
"""

from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from dryfriction.analysis.interface_sweep import (
    SWEEP_VARIABLES,
    catalogue_options,
    catalogue_summary,
    interface_point,
)

pytest.importorskip("distributed")

# four side-loaded blocks, generic parameters (no unit factor 1), about 0.5 s of one core each
BASE = """
[model]
alpha = 0.12
eps = 0.045

[ensemble]
traps_per_a0 = 40
layout = "random"
seed = 7
initial = "rest"

[interface]
n_elements = 4
coupling = COUPLING
mass = 1.1
damping = 0.03
normal_spread = 0.1

[drive]
kind = "side"
edge_stiffness = 0.6
stiffness = 0.0
segments = [{velocity = 0.0, duration = 50.0}, {velocity = 0.023, duration = 1450.0}]

[output]
every = 0.7
"""
COUPLINGS = (1.7, 2.9)
SWEEP = '\n[sweep]\n"interface.coupling" = [1.7, 2.9]\n'


def _write(tmp_path: Path, text: str, name: str = "p.toml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def _sweep_file(tmp_path: Path, catalogue: str = "", sweep: str = SWEEP) -> Path:
    return _write(tmp_path, BASE.replace("COUPLING", "1.0") + catalogue + sweep)


def _direct(tmp_path: Path, coupling: float) -> tuple[dict, dict, dict]:
    """The point simulated alone by ``dryfriction simulate`` (its own catalogue, the route
    users take): events.csv as columns, summary.json, the fields."""
    from dryfriction.app.runs import simulate

    p = _write(tmp_path, BASE.replace("COUPLING", repr(coupling)), f"direct_{coupling}.toml")
    out = tmp_path / f"direct_{coupling}"
    simulate(p, out, figure=False)
    lines = (out / "events.csv").read_text().splitlines()
    header = [h.split("[")[0] for h in lines[0].split(",")]
    rows = [list(map(float, line.split(","))) for line in lines[1:] if line]
    cols = {h: np.array([r[k] for r in rows]) for k, h in enumerate(header)}
    fields = dict(np.load(out / "fields.npz"))
    return cols, json.loads((out / "summary.json").read_text()), fields


@pytest.mark.slow
def test_sweep_values_equal_the_same_point_run_directly(tmp_path: Path) -> None:
    """``dryfriction sweep`` on an interface protocol: every stored statistic equals what the
    same point gives simulated alone (events.csv, summary.json and the fields of ``dryfriction
    simulate``), with the unit declared in sweep.nc; a second call resumes (same numbers).
    Mistakes caught: the swept value not reaching the run (the base protocol run at every
    point); spanning counted as the arrested events; the mean slip as the mean moment; the
    friction's time average without the trapezoid weights; the precursors under the default
    edge_gap of 0 instead of simulate's 1; events before ``after`` kept."""
    import xarray as xr

    from dryfriction.app.sweeps import sweep

    out = tmp_path / "sweep"
    res = sweep(_sweep_file(tmp_path), out, workers=1)
    assert res.failed == 0 and res.size == 2
    ds = xr.open_dataset(out / "sweep.nc")
    for name, info in SWEEP_VARIABLES.items():
        assert ds[name].attrs["units"] == info["units"], name
    assert ds["interface.coupling"].attrs["units"] == "F_el/a0"
    seen = set()
    for coupling in COUPLINGS:
        got = {k: float(ds[k].sel({"interface.coupling": coupling})) for k in SWEEP_VARIABLES}
        cols, summary, fields = _direct(tmp_path, coupling)
        n = cols["event"].size if cols else 0
        assert n >= 3, "the test needs events"  # the point is not empty
        assert got["events"] == n
        assert got["spanning"] == cols["spanning"].sum()
        assert got["arrested"] == n - cols["spanning"].sum()
        assert got["mean_slip"] == pytest.approx(cols["mean_slip"].mean(), rel=1e-12)
        assert got["max_extent"] == pytest.approx(cols["extent"].max(), rel=1e-12)
        assert got["mean_extent"] == pytest.approx(cols["extent"].mean(), rel=1e-12)
        assert got["threshold"] == pytest.approx(cols["threshold"][0], rel=1e-12)
        alpha = summary["fronts"]["moment_exponent"]["alpha"]
        assert got["moment_alpha"] == pytest.approx(alpha, rel=1e-12)
        pre = summary["fronts"]["precursors"]
        assert got["precursors"] == pre["n"]
        if pre["rho"] is not None and math.isfinite(pre["rho"]):
            assert got["precursor_rho"] == pytest.approx(pre["rho"], rel=1e-12)
        # the time average of the elements' mean friction: the trapezoid written out on the
        # samples (not uniform: the hold's 50 t0 is no multiple of every = 0.7)
        f = fields["stress"].mean(axis=1)
        t = fields["t"]
        area = sum(0.5 * (f[j] + f[j + 1]) * (t[j + 1] - t[j]) for j in range(t.size - 1))
        assert got["mean_friction"] == pytest.approx(area / (t[-1] - t[0]), rel=1e-9)
        mu_load = fields["load"].max() / 4  # mu_el = 1, 4 blocks
        assert got["max_load_ratio"] == pytest.approx(mu_load, rel=1e-12)
        seen.add((got["events"], got["mean_slip"]))
    assert len(seen) == 2, "the two points gave the same catalogue: the swept key was lost"
    # resumed: the same call reads the stored points (none computed or written again)
    stored = {p.name: p.stat().st_mtime_ns for p in (out / "points").iterdir()}
    assert len(stored) == 2
    again = sweep(_sweep_file(tmp_path), out, workers=1)
    assert again.dataset["events"].values.tolist() == ds["events"].values.tolist()
    assert {p.name: p.stat().st_mtime_ns for p in (out / "points").iterdir()} == stored


@pytest.mark.slow
def test_catalogue_after_leaves_the_early_events_out(tmp_path: Path) -> None:
    """``catalogue.after``: the events that start before it are left out of every count, the
    mean friction averaged from it on (the cut inside an event, which is then left out).
    Mistakes caught: ``after`` ignored; compared with the events' end instead of their
    start."""
    from dryfriction.io.protocol import parse_protocol

    proto = parse_protocol(BASE.replace("COUPLING", "2.9"))
    res = proto.run()
    everything = catalogue_summary(res)
    cols, _, _ = _direct(tmp_path, 2.9)
    k = int(np.argmax(cols["duration"]))  # within the longest event: after its start
    cut = float(cols["t_start"][k] + 0.5 * cols["duration"][k])
    assert cols["t_start"][k] < cut < cols["t_end"][k]
    later = catalogue_summary(res, after=cut)
    assert later["events"] == np.sum(cols["t_start"] >= cut) < everything["events"]
    assert later["mean_slip"] == pytest.approx(
        cols["mean_slip"][cols["t_start"] >= cut].mean(), rel=1e-12)
    keep = res.t >= cut
    f = res.stress[keep].mean(axis=1)
    assert later["mean_friction"] == pytest.approx(
        float(np.trapezoid(f, res.t[keep]) / (res.t[keep][-1] - res.t[keep][0])), rel=1e-12)


def _cli(args: list[str], monkeypatch: pytest.MonkeyPatch):
    """The command in-process, with any start of a Dask cluster or worker made to fail."""
    from typer.testing import CliRunner

    import dryfriction.sweeps.sweep as sweep_mod
    from dryfriction.cli import app

    def no_worker(*a, **k):
        raise AssertionError("a worker was started")

    monkeypatch.setattr(sweep_mod, "start_client", no_worker)
    return CliRunner().invoke(app, args)


@pytest.mark.parametrize("catalogue, sweep, message", [
    ("", '\n[sweep]\n"interface.n_elements" = [4, 0]\n',
     "n_elements = 0 is out of range: allowed an integer 1 to"),
    ("", '\n[sweep]\n"interface.coupling" = [1.7, -2.0]\n', "coupling = -2 is out of range"),
    ("", '\n[sweep]\n"ensemble.traps_per_a0" = [40, 4e7]\n', "traps_per_a0 = 4e+07 places"),
    ("", '\n[sweep]\n"output.every" = [0.7, 1e-6]\n', "every = 1e-06 with n_elements = 4"),
    ("\n[catalogue]\nmin_elements = 0\n", SWEEP, "catalogue.min_elements = 0 is out of range"),
    ("\n[catalogue]\nthreshold = -0.1\n", SWEEP, "catalogue.threshold = -0.1 is out of range"),
    ("\n[catalogue]\nafter = 1500.0\n", SWEEP, "catalogue.after = 1500 t0 is out of range"),
    ("\n[catalogue]\nwindow = 3\n", SWEEP, "unknown key(s) catalogue.window"),
    ("", '\n[sweep]\n"catalogue.edge_gap" = [1, 2.5]\n', "does not exist"),
])
def test_bad_point_refused_in_one_line_before_any_worker(tmp_path: Path,
                                                         monkeypatch: pytest.MonkeyPatch,
                                                         catalogue: str, sweep: str,
                                                         message: str) -> None:
    """A grid with one impossible point: one line naming the parameter (the interface's own
    refusal, its memory / sample estimate, a bad ``[catalogue]`` value), exit 2, no worker
    started, no folder made. Mistakes caught: the points checked as spring protocols (every
    interface sweep refused); only the base protocol checked, not every point; the
    ``[catalogue]`` table not checked before the workers."""
    if "does not exist" in message:  # a swept [catalogue] key: needs the table in the base
        catalogue, message = "\n[catalogue]\nedge_gap = 1\n", "catalogue.edge_gap = 2.5"
    p = _sweep_file(tmp_path, catalogue, sweep)
    r = _cli(["sweep", str(p), "--out", str(tmp_path / "o")], monkeypatch)
    assert r.exit_code == 2, r.output
    assert message in r.output.replace("\n", " "), r.output
    assert len(r.output.strip().splitlines()) == 1, r.output
    assert not (tmp_path / "o").exists()


def test_linear_and_phase_diagram_refuse_an_interface(tmp_path: Path,
                                                      monkeypatch: pytest.MonkeyPatch) -> None:
    """``--linear`` and ``phase-diagram`` are the spring slider's: one line each, before any
    worker. Mistake caught: ``--linear`` silently ignored (the catalogue run instead)."""
    p = _sweep_file(tmp_path)
    for args, word in ((["sweep", str(p), "--linear"], "--linear"),
                       (["phase-diagram", str(p)], "phase diagram")):
        r = _cli([*args, "--out", str(tmp_path / "o")], monkeypatch)
        assert r.exit_code == 2 and word in r.output, r.output
        assert len(r.output.strip().splitlines()) == 1, r.output
    assert not (tmp_path / "o").exists()


def test_catalogue_options_and_point_checks() -> None:
    """The ``[catalogue]`` table's ranges at their edges, and the example sweep's points all
    accepted. Mistakes caught: ``min_elements`` 1.5 read as 1; ``edge_gap = 0`` refused;
    ``after`` equal to the drive's duration accepted (no sample left)."""
    assert catalogue_options({"min_elements": 1, "edge_gap": 0, "after": 0.0}) == {
        "min_elements": 1, "edge_gap": 0, "after": 0.0}
    for table in ({"min_elements": 1.5}, {"edge_gap": -1}, {"threshold": 0.0},
                  {"after": True}, {"threshold": math.inf}):
        with pytest.raises(ValueError, match=f"catalogue.{next(iter(table))}"):
            catalogue_options(table)
    doc = tomllib.loads(BASE.replace("COUPLING", "1.5"))
    with pytest.raises(ValueError, match="catalogue.after = 1500 t0"):
        interface_point({**doc, "catalogue": {"after": 1500.0}})
    interface_point({**doc, "catalogue": {"after": 1499.0}})
    example = Path(__file__).resolve().parents[2] / "examples" / "interface_sweep.toml"
    from dryfriction.sweeps.sweep import parse_sweep

    spec = parse_sweep(tomllib.loads(example.read_text()))
    for _, ov in spec.points():
        interface_point(spec.protocol(ov))
