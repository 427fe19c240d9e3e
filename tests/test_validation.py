"""The checks every layer shares (dryfriction.validation): both edges of each documented range,
each unit of the size table against one written here, the defaults of the limits, the
thresholds of the words a refusal prints (issue 25: refusal boundaries, defaults, units)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dryfriction import validation as val

# the size units written out by hand (decimal K, M, G, T; binary KiB..TiB), case-insensitive
SIZES = {"3.5": 3.5, "3.5B": 3.5, "3.5k": 3.5e3, "3.5KB": 3.5e3, "3.5m": 3.5e6, "3.5MB": 3.5e6,
         "3.5G": 3.5e9, "3.5gb": 3.5e9, "3.5T": 3.5e12, "3.5TB": 3.5e12,
         "3.5KiB": 3.5 * 1024, "3.5mib": 3.5 * 1024**2, "3.5GiB": 3.5 * 1024**3,
         "3.5TiB": 3.5 * 1024**4, " 7 MiB ": 7 * 1024**2}


@pytest.mark.parametrize("text", sorted(SIZES))
def test_parse_bytes_against_a_hand_written_table(text: str) -> None:
    assert val.parse_bytes(text) == pytest.approx(SIZES[text], rel=1e-15)


def test_parse_bytes_names_the_variable_it_was_given() -> None:
    with pytest.raises(ValueError, match=r"^--limit = '3 PB' is not allowed: a positive size"):
        val.parse_bytes("3 PB", "--limit")


def test_format_bytes_at_each_unit_threshold() -> None:
    # mistake: a threshold one unit off (KiB shown for 1023 B), decimal for binary units
    assert val.format_bytes(1023) == "1023 B"
    assert val.format_bytes(1024) == "1.0 KiB"
    assert val.format_bytes(3 * 2**20 - 1) == "3.0 MiB"
    assert val.format_bytes(2**20 - 1) == "1024.0 KiB"
    assert val.format_bytes(2.5 * 2**30) == "2.5 GiB"
    assert val.format_bytes(6.5 * 2**40) == "6.5 TiB"
    assert val.format_bytes(2**50 - 1) == "1024.0 TiB"
    assert val.format_bytes(3 * 2**50) == "3.1e+03 TiB"
    assert val.format_bytes(math.inf) == "more than any machine has"
    assert val.format_bytes(math.nan) == "more than any machine has"


def test_memory_limit_default_fraction_and_fallback(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(val.MEMORY_ENV, raising=False)
    monkeypatch.setattr(val, "_available_memory", lambda: 3.0e9)
    assert val.MEMORY_FRACTION == 0.5
    assert val.memory_limit() == 1.5e9
    monkeypatch.setattr(val, "_available_memory", lambda: None)
    assert val.memory_limit() == 8.0 * 2**30  # the machine does not say: 8 GiB
    monkeypatch.setenv(val.MEMORY_ENV, "  250MiB ")
    assert val.memory_limit() == 250 * 2**20


def test_check_memory_accepts_the_limit_itself(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(val.MEMORY_ENV, "3000")
    val.check_memory("x", 3000.0, "h")  # equal: allowed
    for need in (3000.5, math.nan, math.inf):
        with pytest.raises(ValueError) as info:
            val.check_memory("every = 0.1 gives 7 samples", need, "raise every")
        msg = str(info.value)
        assert msg.startswith("every = 0.1 gives 7 samples (")
        assert "more than the limit 2.9 KiB: raise every or set DRYFRICTION_MEMORY_LIMIT" in msg


def test_time_limit_default_and_variable(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(val.TIME_ENV, raising=False)
    assert val.time_limit() == 3600.0 == val.TIME_LIMIT_S
    monkeypatch.setenv(val.TIME_ENV, " 7200.5 ")
    assert val.time_limit() == 7200.5
    for bad in ("0", "-3", "nan", "soon"):
        monkeypatch.setenv(val.TIME_ENV, bad)
        with pytest.raises(ValueError, match="DRYFRICTION_TIME_LIMIT = .* a positive number"):
            val.time_limit()


def test_check_time_edge_and_words(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(val.TIME_ENV, "5400")
    val.check_time("x", 5400.0, "h")  # equal: allowed
    cases = {5400.5: "1.5 h", 3 * 86400.0: "3 days", math.nan: "longer than any machine runs"}
    for s, words in cases.items():
        with pytest.raises(ValueError) as info:
            val.check_time("drive.mass = 1 gives 3e8 time steps", s, "a larger mass")
        assert str(info.value) == (f"drive.mass = 1 gives 3e8 time steps: about {words} of "
                                   "computing, more than the limit 1.5 h: a larger mass or set "
                                   "DRYFRICTION_TIME_LIMIT (seconds)")
    # the words' thresholds, through the same message (seconds, minutes, hours, days)
    monkeypatch.setenv(val.TIME_ENV, "1")
    for s, words in ((59.0, "59 s"), (60.0, "1 min"), (3599.0, "60 min"), (3600.0, "1 h"),
                     (86399.0, "24 h"), (86400.0, "1 days")):
        with pytest.raises(ValueError, match=f"about {words} of computing, more than the "
                                             "limit 1 s"):
            val.check_time("w", s, "h")


@pytest.mark.parametrize("lo_open, hi_open, text", [
    (False, False, "allowed finite and >= -2.5 and <= 4"),
    (True, False, "allowed finite and > -2.5 and <= 4"),
    (False, True, "allowed finite and >= -2.5 and < 4"),
    (True, True, "allowed finite and > -2.5 and < 4")])
def test_check_range_both_edges_open_and_closed(lo_open: bool, hi_open: bool, text: str) -> None:
    f = lambda v: val.check_range("k", v, -2.5, 4.0, lo_open=lo_open, hi_open=hi_open)  # noqa: E731
    np.testing.assert_array_equal(f([-2.4, 0.0, 3.9]), [-2.4, 0.0, 3.9])
    for edge, is_open in ((-2.5, lo_open), (4.0, hi_open)):
        if is_open:
            with pytest.raises(ValueError, match=f"^k = {edge:g} is out of range: {text}$"):
                f(edge)
        else:
            assert float(f(edge)) == edge
    with pytest.raises(ValueError, match="k = 5 is out of range"):  # the first bad element
        f([1.0, 5.0, -7.0])


@pytest.mark.parametrize("lo_open", [False, True])
@pytest.mark.parametrize("hi_open", [False, True])
def test_check_scalar_on_python_floats_is_check_range_on_arrays(lo_open: bool, hi_open: bool
                                                                ) -> None:
    """check_scalar takes a Python float in range without NumPy: the same value, or the same
    one-line refusal, as the array route, at both edges (open and closed), just inside and
    just outside them, at 0 and -0 below a bound of 0, and at inf and NaN; an unbounded side
    too."""
    lo, hi = -0.0371, 2.93e4
    cases = [lo, hi, math.nextafter(lo, 0.0), math.nextafter(hi, 0.0),
             math.nextafter(lo, -1.0), math.nextafter(hi, 1e9), 17.3, -5.5e-3, 4e4,
             math.inf, -math.inf, math.nan]
    for bounds in ((lo, hi), (None, hi), (lo, None), (0.0, None)):
        for v in cases + [0.0, -0.0]:
            want: object
            try:
                want = float(val.check_range("k", np.asarray(v), *bounds, lo_open=lo_open,
                                             hi_open=hi_open))
            except ValueError as e:
                want = str(e)
            try:
                got: object = val.check_scalar("k", v, *bounds, lo_open=lo_open,
                                               hi_open=hi_open)
                assert type(got) is float
            except ValueError as e:
                got = str(e)
            assert got == want, (bounds, v)


def test_check_range_unbounded_and_not_numbers() -> None:
    assert float(val.check_range("x", -1e300)) == -1e300
    for bad in (math.inf, -math.inf, math.nan):
        with pytest.raises(ValueError, match="out of range: allowed finite$"):
            val.check_range("x", bad)
    with pytest.raises(ValueError, match="x = 'abc' is not a real number"):
        val.check_range("x", "abc")
    with pytest.raises(ValueError, match="x must be a single number, got an array of shape"):
        val.check_scalar("x", [1.0, 2.0])
    assert isinstance(val.check_scalar("x", np.float32(2.5)), float)


def test_check_alpha_and_direct_edges() -> None:
    assert val.check_alpha(val.ALPHA_MIN) == val.ALPHA_MIN == 1e-6
    assert val.check_alpha(1.0 - 1e-12) == 1.0 - 1e-12
    for bad in (0.999e-6, 1.0):
        with pytest.raises(ValueError, match="alpha = "):
            val.check_alpha(bad)
    assert val.check_direct(0.0, val.U_MIN) == (0.0, 1e-30)
    assert val.check_direct(val.DIRECT_MAX, val.U_MAX) == (1.0, 1e30)
    with pytest.raises(ValueError, match="direct = "):
        val.check_direct(1.0 + 1e-9, 1.0)
    with pytest.raises(ValueError, match="direct = "):
        val.check_direct(-1e-12, 1.0)
    for v in (0.99e-30, 1.01e30):
        with pytest.raises(ValueError, match="v_ref = "):
            val.check_direct(0.5, v)


def test_check_figure_format_edges() -> None:
    assert val.check_figure_format("svg") == ("svg", None)
    assert val.check_figure_format("pdf", 50) == ("pdf", 50)
    assert val.check_figure_format("png", 1200.0) == ("png", 1200)
    for dpi in (49, 1201, 150.5):
        with pytest.raises(ValueError, match=r"^--dpi .* out of range: allowed a whole number "
                                             r"in \[50, 1200\]$"):
            val.check_figure_format("png", dpi)
    with pytest.raises(ValueError, match="--format 'jpg' is not allowed: choose one of png, "
                                         "pdf, svg"):
        val.check_figure_format("jpg")


def test_check_broadcast_and_finite_result_name_their_inputs() -> None:
    assert val.check_broadcast(T=np.ones((3, 1)), eps=np.ones(2)) == (3, 2)
    with pytest.raises(ValueError, match=r"^T has shape \(3,\), eps \(2,\) and u \(4,\): they "
                                         r"do not broadcast$"):
        val.check_broadcast(T=np.ones(3), eps=np.ones(2), u=np.ones(4))
    out = val.check_finite_result("mu", [1.0, 2.0], u=[3.0, 4.0])
    np.testing.assert_array_equal(out, [1.0, 2.0])
    # the inputs at the FIRST non-finite element, a scalar input broadcast
    with pytest.raises(ValueError, match=r"^mu is not finite at u = 0.25, T = 7: "):
        val.check_finite_result("mu", [1.0, np.nan, np.inf], u=[2.0, 0.25, 9.0], T=7.0)


def test_parameter_check_and_declared_default() -> None:
    p = val.Parameter("k", 2.0, 0.0, 5.0, lo_open=True)
    assert p.check(5.0) == 5.0
    with pytest.raises(ValueError, match="k = 0 is out of range: allowed finite and > 0"):
        p.check(0.0)
    with pytest.raises(ValueError, match="k = "):
        p.check(None)  # None only where None is the default
    opt = val.Parameter("dc2", None, 0.0, lo_open=True)
    assert opt.check(None) is None
    sw = val.Parameter("regularized", False, boolean=True)
    assert sw.check(np.bool_(True)) is True
    with pytest.raises(ValueError, match="regularized = 1 is not allowed: true or false"):
        sw.check(1)
    ch = val.Parameter("law", "ageing", choices=("ageing", "slip"))
    with pytest.raises(ValueError, match="law = 'prz' is not allowed: choose one of ageing, slip"):
        ch.check("prz")
    import dataclasses

    assert val.declared({"k": p}, "k").default == 2.0
    req = val.declared({"r": val.Parameter("r")}, "r")
    assert req.default is dataclasses.MISSING


def test_the_declared_limits_and_the_model_objects_that_read_them() -> None:
    """The limits as their docstrings state them (the model tables read them, so a table-driven
    test of the tables cannot see a limit that moved), each seen through a model object."""
    from dryfriction.rsf.law import RateState
    from dryfriction.theory.model import TrapModel

    assert (val.EPS_MAX, val.U_MIN, val.U_MAX, val.T_MAX, val.FRICTION_MAX) == (
        1.0, 1e-30, 1e30, 1e30, 10.0)
    assert TrapModel(eps=1.0).eps == 1.0 and TrapModel(mu_el=10.0).mu_el == 10.0
    assert TrapModel(v_ref=1e-30).v_ref == 1e-30 and TrapModel(v_ref=1e30).v_ref == 1e30
    for kw in ({"eps": 1.0 + 1e-9}, {"mu_el": 10.0 + 1e-9}, {"v_ref": 0.99e-30}):
        with pytest.raises(ValueError, match=f"^{next(iter(kw))} = "):
            TrapModel(**kw)
    assert RateState(0.01, 0.012, 1e-5, -10.0, 1e-6).mu0 == -10.0
    with pytest.raises(ValueError, match="^mu0 = "):
        RateState(0.01, 0.012, 1e-5, 10.0 + 1e-9, 1e-6)
