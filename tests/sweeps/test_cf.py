"""``sweep.nc`` is self-describing (CF): units and long names on every variable, the stick-slip
class with its names, the protocol text; and the ``sweep --linear`` example of
docs/howto/sweeps.md runs without an OverflowError or a RuntimeWarning."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.theory.model import TrapModel
from dryfriction.theory.stability import rightmost_root, steady_response
from sweep_protocols import spring_sweep

EXAMPLE = Path(__file__).parents[2] / "examples" / "phase_diagram.toml"

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


@pytest.mark.slow
def test_readme_linear_sweep_has_every_point_and_units(tmp_path, recwarn):
    # was: 2 of 9 points OverflowError (a Newton run of rightmost_root off to |lambda| ~ 1e200)
    # and NaN K_c there, with RuntimeWarnings on the terminal
    ds = _sweep(tmp_path, EXAMPLE, "--linear")
    assert ds.attrs["n_failed"] == 0 and not any(ds["error"].values.ravel())
    assert np.isfinite(ds["K_c"].values).all()
    # K_c depends on the velocity only (no mass, no damping here)
    assert (ds["K_c"].values == ds["K_c"].values[0]).all()
    assert ds["K_c"].attrs["units"] == "F_el/a0" and ds["omega_c"].attrs["units"] == "rad/t0"
    assert ds["drive.segments.0.velocity"].attrs["units"] == "a0/t0"
    # was: NaN at 3 of the 9 points (no root found from 24 starts); every point where the
    # linear problem is defined (all of them here) has a growth rate, and says what it is
    assert np.isfinite(ds["growth_rate"].values).all()
    kinds = dict(zip(ds["growth_rate_kind"].attrs["flag_values"],
                     ds["growth_rate_kind"].attrs["flag_meanings"].split(), strict=True))
    assert {kinds[int(k)] for k in ds["growth_rate_kind"].values.ravel()} <= {
        "rightmost_root", "delay_chain_limit"}


@pytest.mark.parametrize(("u", "K"), [(1.0, 0.05), (0.1, 0.1)])
def test_rightmost_root_survives_a_seed_that_runs_away(u, K):
    # the two points of the docs' sweep that raised; both stiffnesses are above K_c
    # (0.030 at u = 1, 0.056 at u = 0.1), so the root the other seeds find is stable
    resp = steady_response(u, TrapModel(eps=0.04))
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
        assert set(mod.SWEEP_VARIABLES) == {"K_c", "omega_c", "growth_rate", "growth_rate_kind",
                                            "linearly_stable"}


def _chi_zeros_in(resp, K: float, re_lo: float, re_hi: float, im_hi: float) -> int:
    """Zeros of ``chi = K + Z`` in the rectangle ``[re_lo, re_hi] x [-im_hi, im_hi]`` by the
    argument principle (the winding of chi along its edge): a count that does not depend on
    where a Newton search starts."""
    n = 6000
    edge = np.concatenate([
        re_lo + 1j * np.linspace(im_hi, -im_hi, n, endpoint=False),
        np.linspace(re_lo, re_hi, n, endpoint=False) - 1j * im_hi,
        re_hi + 1j * np.linspace(-im_hi, im_hi, n, endpoint=False),
        np.linspace(re_hi, re_lo, n, endpoint=False) + 1j * im_hi,
    ])
    chi = K + resp.Z(np.append(edge, edge[0]))
    turn = np.diff(np.unwrap(np.angle(chi)))
    assert np.abs(turn).max() < 1.0  # sampled finely enough for the count to hold
    return round(turn.sum() / (2 * np.pi))  # the edge runs counter-clockwise


def _chain_root(resp, K: float, k: int) -> complex:
    """The ``k``-th root of the delay chain by the test's own Newton from its asymptotics
    ``K + Z(inf) - E e^{-lambda tau_d} = 0``."""
    amp = resp.edge * resp.edge_delay / resp.H0
    z = complex(-(np.log(complex((K + resp.Z_inf) / amp)) + 2j * np.pi * k) / resp.tau_d)
    for _ in range(40):
        h = 1e-7 * abs(z)
        f = complex(K + resp.Z(z))
        z -= f * h / (complex(K + resp.Z(z + h)) - f)
    assert abs(K + resp.Z(z)) < 1e-10
    return z


@pytest.mark.slow
@pytest.mark.parametrize("u", [0.01, 0.1, 1.0])
def test_readme_linear_sweep_growth_rates_are_the_spectrum_supremum(u):
    """The 9 points of the ``sweep --linear`` of docs/howto/sweeps.md: each growth rate finite, of
    the sign of ``K_c - K``; no zero of chi to its right (argument principle, up to |lambda| tau_d =
    40), the rightmost root a zero of chi that the same count sees; never below a root of the chain
    far out (the supremum includes the chain), and equal to its limit where it says so. Catches a
    search that misses the low-frequency rightmost root (the old 24 starts gave -1.79/tau_d at u =
    0.1, K = 0.1 where a root sits at -1.62/tau_d) or returns NaN where the rightmost roots lie at
    |lambda| tau_d ~ 1000."""
    from dryfriction.analysis.linear import GROWTH_KINDS, growth_rate
    from dryfriction.theory.linear_stability import critical_stiffness

    resp = steady_response(u, TrapModel(eps=0.04))
    k_c = critical_stiffness(u, TrapModel(eps=0.04)).critical_stiffness
    tau = resp.tau_d
    for K in (0.025, 0.05, 0.1):
        rate, code, root = growth_rate(resp, K)
        kind = GROWTH_KINDS[code]
        assert np.isfinite(rate) and kind in ("rightmost_root", "delay_chain_limit"), (K, kind)
        assert np.sign(rate) == np.sign(k_c - K), (K, rate, k_c)
        assert _chi_zeros_in(resp, K, rate + 0.05 / tau, 40.0 / tau, 40.0 / tau) == 0, K
        far = _chain_root(resp, K, 20_000)
        assert far.real <= rate + 1e-3 / tau, (K, far, rate)
        if kind == "rightmost_root":
            assert root.real == rate and abs(K + resp.Z(root)) < 1e-8
            if abs(root.imag) < 39.0 / tau:  # the count sees it: it can tell a zero is there
                assert _chi_zeros_in(resp, K, rate - 0.05 / tau, 40.0 / tau, 40.0 / tau) >= 1
        else:
            assert rate - far.real < 0.01 / tau, (K, far, rate)
