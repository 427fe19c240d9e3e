"""``sweep.nc`` is self-describing (CF): units and long names on every variable, the stick-slip
class with its names, the protocol text; and the README's ``sweep --linear`` example runs
without an OverflowError or a RuntimeWarning."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.theory.stability import rightmost_root, steady_response
from sweep_protocols import spring_sweep

EXAMPLE = Path(__file__).parents[1] / "examples" / "phase_diagram.toml"

STICK_SLIP = spring_sweep('"drive.stiffness" = [0.02, 0.5]\n', slip=16.0, every_slip=0.05,
                          transient=6.0, alpha=0.13,
                          header="# two springs — one soft, one stiff\n")


def _sweep(tmp_path: Path, protocol: Path, *extra: str) -> xr.Dataset:
    out = tmp_path / "out"
    r = CliRunner().invoke(app, ["sweep", str(protocol), "--out", str(out), "--workers", "1",
                                 *extra])
    assert r.exit_code == 0, r.output
    with xr.open_dataset(out / "sweep.nc") as ds:
        return ds.load()


def test_stick_slip_sweep_names_its_classes_and_units(tmp_path):
    proto = tmp_path / "p.toml"
    proto.write_text(STICK_SLIP, encoding="utf-8")
    ds = _sweep(tmp_path, proto)
    cls = ds["class"]
    # the codes of analysis.stickslip (module doc): steady 0, periodic 1, ..., undetermined -1
    meanings = cls.attrs["flag_meanings"].split()
    codes = [int(v) for v in np.asarray(cls.attrs["flag_values"])]
    assert dict(zip(codes, meanings, strict=True)) == {
        -1: "undetermined", 0: "steady", 1: "periodic", 2: "irregular", 3: "transient",
        4: "oscillation"}
    names = [meanings[codes.index(int(c))] for c in cls.values]
    assert names[1] == "steady"  # K = 0.5 is far above K_c
    assert ds["period"].attrs["units"] == "t0" and ds["slip_per_event"].attrs["units"] == "a0"
    assert ds["amplitude"].attrs["units"] == "1"
    assert ds["drive.stiffness"].attrs["units"] == "F_el/a0"
    for name in [*ds.data_vars, *ds.coords]:
        assert ds[name].attrs.get("long_name"), name
        assert name == "error" or "units" in ds[name].attrs, name
    assert ds.attrs["Conventions"] == "CF-1.8"
    assert ds.attrs["protocol"] == STICK_SLIP  # as written, non-ASCII dash included
    assert "stick_slip_summary" in ds.attrs["analysis"] and "p.toml" in ds.attrs["source"]


def test_readme_linear_sweep_has_every_point_and_units(tmp_path, recwarn):
    # was: 2 of 9 points OverflowError (a Newton run of rightmost_root off to |lambda| ~ 1e200)
    # and NaN K_c there, with RuntimeWarnings on the terminal
    ds = _sweep(tmp_path, EXAMPLE, "--linear")
    assert ds.attrs["n_failed"] == 0 and not any(ds["error"].values.ravel())
    assert np.isfinite(ds["K_c"].values).all()
    # K_c depends on the velocity only (no mass, no damping here)
    assert (ds["K_c"].values == ds["K_c"].values[0]).all()
    assert ds["K_c"].attrs["units"] == "F_el/a0" and ds["omega_c"].attrs["units"] == "1/t0"
    assert ds["drive.segments.0.velocity"].attrs["units"] == "a0/t0"


@pytest.mark.parametrize(("u", "K"), [(1.0, 0.05), (0.1, 0.1)])
def test_rightmost_root_survives_a_seed_that_runs_away(u, K):
    # the two points of the README sweep that raised; both stiffnesses are above K_c
    # (0.030 at u = 1, 0.056 at u = 0.1), so the root the other seeds find is stable
    resp = steady_response(u, 0.04)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no RuntimeWarning either
        root = rightmost_root(resp, K)
    assert np.isfinite(root) and root.real < 0


@pytest.mark.parametrize("name", ["linear", "stickslip"])
def test_every_runner_result_has_cf_attributes(name):
    # a result the runner returns but the table forgets would be a bare number in sweep.nc
    import importlib

    mod = importlib.import_module(f"dryfriction.analysis.{name}")
    for info in mod.SWEEP_VARIABLES.values():
        assert info["long_name"] and "units" in info
    if name == "stickslip":
        from dryfriction.analysis.stickslip import StickSlipStats

        fields = set(StickSlipStats.__dataclass_fields__) - {"code"} | {"class", "u", "stiffness"}
        assert set(mod.SWEEP_VARIABLES) == fields
    else:
        assert set(mod.SWEEP_VARIABLES) == {"K_c", "omega_c", "growth_rate", "linearly_stable"}
