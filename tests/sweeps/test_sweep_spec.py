"""The sweep table (dryfriction.sweeps.sweep.parse_sweep) against its definition: the log and
lin axes' values, both ends of n's range, the grid's points in C order, overrides that leave
the base untouched (issue 25: a count off by one, a refusal boundary, a default)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.sweeps.sweep import MAX_AXIS, get_dotted, parse_sweep, set_dotted

BASE = {"model": {"eps": 0.04}, "drive": {"stiffness": 0.3,
                                          "segments": [{"velocity": 0.1, "slip": 2.0},
                                                       {"velocity": 0.4, "slip": 1.0}]}}


def _axis(spec):  # type: ignore[no-untyped-def]
    return parse_sweep({**BASE, "sweep": {"drive.stiffness": spec}}).axes[0].values


def test_log_and_lin_axes_are_their_definitions() -> None:
    got = _axis({"log": [2e-3, 0.5, 4]})
    want = 2e-3 * (0.5 / 2e-3) ** (np.arange(4) / 3)  # equal ratios, both ends included
    np.testing.assert_allclose(got, want, rtol=1e-14)
    assert got[0] == 2e-3 and got[-1] == pytest.approx(0.5, rel=1e-15)
    np.testing.assert_allclose(_axis({"lin": [-1.5, 2.0, 8]}), -1.5 + 0.5 * np.arange(8),
                               rtol=0, atol=1e-15)
    assert _axis({"lin": [0.7, 3.0, 1]}) == (0.7,)
    assert _axis({"log": [5.0, 0.05, 3]}) == pytest.approx((5.0, 0.5, 0.05), rel=1e-14)
    assert _axis([0.3, "x", 2]) == (0.3, "x", 2)  # a list is taken as it is
    assert len(_axis({"lin": [0.0, 1.0, MAX_AXIS]})) == MAX_AXIS == 1_000_000


@pytest.mark.parametrize("spec, msg", [
    ({"lin": [0.0, 1.0, 0]}, r"n = 0 must be an integer in \[1, 1000000\]"),
    ({"lin": [0.0, 1.0, MAX_AXIS + 1]}, "n = 1000001 must be an integer"),
    ({"lin": [0.0, 1.0, True]}, "n = True must be an integer"),
    ({"lin": [0.0, 1.0, 2.0]}, "n = 2.0 must be an integer"),
    ({"lin": [0.0, float("inf"), 2]}, "lin stop = inf is not allowed: a finite number"),
    ({"log": [False, 1.0, 2]}, "log start = False is not allowed"),
    ({"log": [1.0, -2.0, 3]}, "log range needs start, stop > 0"),
    ({"log": [1.0, 2.0]}, r"log needs \[start, stop, n\]"),
    ({"lin": [1.0, 2.0, 3], "log": [1.0, 2.0, 3]}, "values must be a list"),
])
def test_bad_axes_are_refused_naming_the_key(spec, msg) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(ValueError, match=f"^protocol: \\[sweep\\] 'drive.stiffness': {msg}"):
        _axis(spec)


def test_grid_points_in_c_order_and_overrides() -> None:
    spec = parse_sweep({**BASE, "sweep": {"drive.segments.1.velocity": [0.2, 0.5, 0.9],
                                          "model.eps": {"lin": [0.01, 0.03, 2]}}}, "p.toml")
    assert spec.shape == (3, 2) and spec.size == 6
    pts = list(spec.points())
    assert [i for i, _ in pts] == [(0, 0), (0, 1), (1, 0), (1, 1), (2, 0), (2, 1)]
    idx, over = pts[3]
    assert over == {"drive.segments.1.velocity": 0.5, "model.eps": 0.03}
    proto = spec.protocol(over)
    assert proto["drive"]["segments"][1]["velocity"] == 0.5
    assert proto["drive"]["segments"][0]["velocity"] == 0.1 and proto["model"]["eps"] == 0.03
    assert BASE["drive"]["segments"][1]["velocity"] == 0.4 and BASE["model"]["eps"] == 0.04
    assert "sweep" not in spec.base
    with pytest.raises(ValueError, match=r"^p\.toml: \[sweep\] keys 'drive.segments' and "
                                         r"'drive.segments.0.velocity' overlap"):
        parse_sweep({**BASE, "sweep": {"drive.segments": [[]],
                                       "drive.segments.0.velocity": [1.0]}}, "p.toml")


def test_dotted_keys() -> None:
    assert get_dotted(BASE, "drive.segments.1.slip") == 1.0
    for bad in ("drive.segments.2.slip", "drive.stiffness.x", "model.alpha"):
        with pytest.raises(KeyError):
            get_dotted(BASE, bad)
    new = set_dotted(BASE, "drive.segments.0.slip", 7.5)
    assert new["drive"]["segments"][0]["slip"] == 7.5
    assert BASE["drive"]["segments"][0]["slip"] == 2.0
    with pytest.raises(KeyError):
        set_dotted(BASE, "drive.mass", 1.0)  # a new key is no override
