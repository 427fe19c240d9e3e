"""The detector's compiled and shortened paths give NumPy's numbers to the last bit.

A speed change to the detector must change no detection (``benchmarks/bench_detect_same.py``
compares whole detections on the zoo): each faster form here is compared, bit for bit, with
the NumPy form it replaced, on records with the artifacts that make the edge cases (gaps,
rate changes, quantised and repeated values, NaN, even and odd counts). Mistakes each test
catches: a pairwise sum in the wrong order (the last bits of every stretch's line), a window
counted from the wrong start, the local rate after an increment taken one window early, the
wrong middle value of an even count, the quantile's weight from the wrong end.
"""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.records import artifacts, detection
from dryfriction.records.hinge_kernel import (
    pairwise_sum,
    reset_increments,
    row_medians,
    stretch_residuals,
    window_pairs,
)
from dryfriction.records.placement import _cov_int
from dryfriction.records.segmentation import line_fit, median, quantile


def _record(seed: int, n: int = 3000) -> tuple[np.ndarray, np.ndarray]:
    """Times with a 10-fold rate change and a gap, and a wandering, quantised displacement."""
    rng = np.random.default_rng(seed)
    dt = np.where(np.arange(n) < n // 2, 0.1, 1.0) * rng.uniform(0.7, 1.3, n)
    dt[n // 3] = 40.0  # a gap
    t = 1e4 + np.cumsum(dt)
    x = 2e-7 * t + 1e-8 * np.cumsum(rng.standard_normal(n)) + 1e-8 * rng.standard_normal(n)
    return t, np.round(x / 2e-8) * 2e-8


def _window_slopes_numpy(t, x, width, offset):
    """The NumPy form :func:`detection._window_pairs` replaced (bincount per window)."""
    w = np.floor((t - offset) / width).astype(np.int64)
    w0 = int(w[0])
    w -= w0
    tt = t - (offset + (w + w0) * width)
    nw = int(w[-1]) + 1
    n = np.bincount(w, minlength=nw).astype(float)
    st, sx = np.bincount(w, tt, nw), np.bincount(w, x, nw)
    stt, stx = np.bincount(w, tt * tt, nw), np.bincount(w, tt * x, nw)
    with np.errstate(divide="ignore", invalid="ignore"):
        var_t = stt / n - (st / n) ** 2
        slope = (stx / n - st * sx / n**2) / var_t
    ok = (n >= 3) & (var_t >= width**2 / 48.0) & np.isfinite(slope)
    return slope, n * var_t, ok, w, n


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_window_pairs_are_the_bincount_forms_to_the_last_bit(seed: int) -> None:
    t, x = _record(seed)
    speed = np.where(np.arange(t.size) < 1000, 2e-7, 5e-8)
    sigma = 1e-8
    for width in (0.7, 3.0, 50.0, 400.0):
        for off in (0.0, 0.5 * width, 0.25 * width):
            s, sxx, ok, w, cnt = _window_slopes_numpy(t, x, width, float(t[0]) - off)
            u = np.bincount(w, speed, len(s)) / np.maximum(cnt, 1)
            pair = ok[1:] & ok[:-1]
            with np.errstate(divide="ignore", invalid="ignore"):
                w2 = 0.5 * sigma**2 * (1.0 / sxx[1:] + 1.0 / sxx[:-1])
            y_ref = (0.5 * (s[1:] - s[:-1]) ** 2 - w2)[pair]
            u_ref = (0.5 * (u[1:] + u[:-1]))[pair]
            y, uu = window_pairs(t, x, speed, width, float(t[0]) - off, 0.5 * sigma**2,
                                 width**2 / 48.0)
            assert np.array_equal(y, y_ref) and np.array_equal(uu, u_ref)


def _fluctuations_both(t: np.ndarray, x: np.ndarray, bounds: list[int], v: np.ndarray,
                       monkeypatch: pytest.MonkeyPatch) -> tuple:
    """``measure_fluctuations`` with its loop over the durations compiled and as NumPy."""
    got = []
    for compiled in (True, False):
        monkeypatch.setattr(detection, "COMPILED_SCALES", compiled)
        fl = detection.measure_fluctuations(t, x, 1.3e-8, bounds, v)
        got.append(fl)
    return tuple(got)


@pytest.mark.parametrize("seed", range(4))
def test_fluctuation_scales_compiled_are_the_numpy_loop(seed: int,
                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    """The compiled loop over the durations (COMPILED_SCALES) gives the NumPy loop's r(T), a(T)
    and durations to the last bit: on a record with a rate change, a gap and a quantum; on a
    slide-hold-slide that is mostly hold (at the long durations too few pairs move: r(T) is
    the shorter duration's); and with MOVING_Z 0. Mistakes: the faster half by an unstable
    sort (ties split otherwise), the third and fourth offsets always or never taken, too few
    moving pairs read as no relative wander, the absolute wander from the faster half."""
    t, x = _record(seed)
    rng = np.random.default_rng(seed)
    inner = sorted(rng.choice(np.arange(50, t.size - 50), 3, replace=False).tolist())
    bounds = [0, *inner, t.size]
    v = np.array([2e-7, 0.0, 6e-7, 1.1e-7])
    a, b = _fluctuations_both(t, x, bounds, v, monkeypatch)
    # a slide-hold-slide, mostly hold: 30 s at 1.7 um/s, 1900 s held, 30 s at 1.7 um/s
    th = np.arange(0.0, 1960.0, 0.2)
    vh = np.where((th < 30.0) | (th > 1930.0), 1.7e-6, 0.0)
    xh = np.concatenate([[0.0], np.cumsum(vh[:-1] * 0.2)])
    xh = xh + 3e-8 * np.sin(th / 7.0 + seed) + 1e-8 * rng.standard_normal(th.size)
    bh = [0, 150, 9650, th.size]
    c, d = _fluctuations_both(th, xh, bh, np.array([1.7e-6, 0.0, 1.7e-6]), monkeypatch)
    monkeypatch.setattr(detection, "MOVING_Z", 0.0)
    e, f = _fluctuations_both(t, x, bounds, v, monkeypatch)
    for p, q in ((a, b), (c, d), (e, f)):
        assert p.scales.size >= 5
        assert np.array_equal(p.scales, q.scales)
        assert np.array_equal(p.relative, q.relative)
        assert np.array_equal(p.absolute, q.absolute)
    assert c.relative.max() > 0.0 and np.unique(c.relative).size > 1


def test_fluctuations_of_equal_times_are_none_measured(monkeypatch: pytest.MonkeyPatch
                                                      ) -> None:
    """Times all equal (a caller's arrays; a LabRecord's increase): no wander measured, at
    once, by both loops. Mistake, seen failing in an independent review: the durations
    doubled from 0 without end (the compiled loop's list grew until the memory ran out, the
    NumPy loop hung)."""
    rng = np.random.default_rng(2)
    x = np.cumsum(rng.normal(0.0, 1e-8, 2000))
    for compiled in (True, False):
        monkeypatch.setattr(detection, "COMPILED_SCALES", compiled)
        fl = detection.measure_fluctuations(np.full(2000, 5.0), x, 1e-8, [0, 700, 2000],
                                            np.array([1e-6, 3e-6]))
        assert fl.scales.size == 1 and not fl.relative.any() and not fl.absolute.any()


@pytest.mark.parametrize("seed", [0, 1])
def test_stretch_residuals_are_line_fits_to_the_last_bit(seed: int) -> None:
    t, x = _record(seed)
    rng = np.random.default_rng(seed)
    inner = np.sort(rng.choice(np.arange(1, t.size), 40, replace=False))
    bounds = np.concatenate([[0], inner, [t.size]])
    v = rng.standard_normal(bounds.size - 1) * 1e-7
    res_ref, speed_ref = np.empty(t.size), np.empty(t.size)
    for (a, b), vv in zip(zip(bounds[:-1], bounds[1:], strict=True), v, strict=True):
        slope, mean, _ = line_fit(t[a:b], x[a:b])
        res_ref[a:b] = x[a:b] - mean - slope * (t[a:b] - t[a:b].mean())
        speed_ref[a:b] = abs(vv)
    res, speed = stretch_residuals(t, x, bounds.astype(np.int64), v)
    assert np.array_equal(res, res_ref) and np.array_equal(speed, speed_ref)


def test_pairwise_sum_is_numpys_sum_to_the_last_bit() -> None:
    rng = np.random.default_rng(5)
    for n in [*range(1, 300), 1000, 4099, 20011]:
        a = rng.standard_normal(n + 7) * 1e3 + 1e6
        lo = int(rng.integers(0, 7))
        assert pairwise_sum(a, lo, n) == np.sum(a[lo:lo + n])


@pytest.mark.parametrize("seed", range(6))
def test_find_resets_compiled_is_the_numpy_form(seed: int, monkeypatch) -> None:
    t, x = _record(seed)
    rng = np.random.default_rng(seed)
    for k in rng.integers(10, t.size - 10, 3):  # transducer re-zeroed three times
        x[k:] -= rng.uniform(-3e-6, 3e-6)
    if seed % 2:
        x[100:130] = x[100]  # a stuck transducer: zero increments
    got = {}
    for compiled in (True, False):
        monkeypatch.setattr(artifacts, "COMPILED_RESETS", compiled)
        got[compiled] = artifacts.find_resets(t, x)
    assert got[True][1] == got[False][1] and len(got[True][1]) >= 3
    assert np.array_equal(got[True][0], got[False][0])


@pytest.mark.parametrize("seed", range(3))
def test_reset_increments_are_the_numpy_forms_to_the_last_bit(seed: int) -> None:
    t, x = _record(seed)
    d, dt = np.diff(x), np.diff(t)
    rate = d / dt
    vb, va = artifacts._local_rate(rate, "before"), artifacts._local_rate(rate, "after")
    vb = np.where(np.isfinite(vb), vb, va)
    va = np.where(np.isfinite(va), va, vb)
    e = d - vb * dt
    got = reset_increments(t, x)
    for a, b in zip(got[:6], (d, dt, np.minimum(vb, va) * dt, np.maximum(vb, va) * dt,
                              e[np.isfinite(e)], (rate - vb)[np.isfinite(rate - vb)]),
                    strict=True):
        assert np.array_equal(a, b)
    assert got[6] == np.abs(d[d != 0.0]).min()


def test_row_medians_are_numpys_to_the_last_bit() -> None:
    rng = np.random.default_rng(7)
    for k in (1, 2, 5, 10, 16, 17, 32):
        a = np.round(rng.standard_normal((500, k)) * 3) / 3  # repeated values
        a[3, 0] = np.nan
        assert np.array_equal(row_medians(a), np.median(a, axis=1), equal_nan=True)


def test_median_and_quantile_are_numpys_to_the_last_bit() -> None:
    rng = np.random.default_rng(8)
    for n in [*range(1, 40), 999, 1000, 20000]:
        a = np.round(rng.standard_normal(n) * 5) / 7
        for arr in (a, np.abs(a)):
            assert median(arr) == np.median(arr)
            for q in (0.0, 0.01, 0.5, 0.9, 0.99, 1.0):
                assert quantile(arr, q) == np.quantile(arr, q)
    a[5] = np.nan
    assert np.isnan(median(a)) and np.isnan(quantile(a, 0.99))


def test_ou_covariance_in_place_is_the_formula() -> None:
    rng = np.random.default_rng(9)
    tb = np.sort(rng.uniform(0.0, 200.0, 256))
    tg, t0, tau = 90.0, float(tb[0]), 7.3
    e1, s2 = np.minimum(tb, tg), np.maximum(tb, tg)

    def g(y):
        a = np.abs(y)
        return tau * a + tau * tau * np.expm1(-a / tau)

    for p, q, r, w in ((t0, e1[:, None], t0, e1[None, :]), (t0, e1[:, None], tg, s2[None, :]),
                       (tg, s2[:, None], tg, s2[None, :])):
        ref = g(q - r) - g(p - r) - g(q - w) + g(p - w)
        assert np.array_equal(_cov_int(p, q, r, w, tau), ref)
