"""Stick-slip measures against their definitions on a signal built to know them (issue 25:
an estimator never checked against its definition hides an off-by-one).

:func:`~dryfriction.analysis.stickslip.analyse` reports the time-weighted fraction of the
window the slider sticks (``v < stick_fraction u``), each sample standing for the step that
ends at it. On irregular sampling the sample that starts a step and the one that ends it
weigh differently, which is what the test uses: a sawtooth load, a velocity that is slow on
the ramps and fast in the drops, sampled at jittered times.
"""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.analysis.stickslip import analyse


def _sawtooth(seed: int) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(seed)
    dt = rng.uniform(0.013, 0.11, 4000)  # jittered, 1:8
    t = np.concatenate(([0.0], np.cumsum(dt)))
    u = 0.37
    period = 23.0
    phase = (t % period) / period
    slow = phase < 0.83  # sticking on the ramp, slipping in the last 17 %
    v = np.where(slow, 0.04 * u, 9.0 * u)
    x = np.concatenate(([0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))))
    load = np.where(slow, 0.6 + 0.05 * phase / 0.83, 0.65 - 0.05 * (phase - 0.83) / 0.17)
    return t, x, v, load, u


@pytest.mark.parametrize("seed", [3, 17])
def test_stick_fraction_is_its_definition(seed: int) -> None:
    t, x, v, load, u = _sawtooth(seed)
    got = analyse(t, x, v, load, u=u, floor=1e-3)
    slow = v < 0.5 * u
    want = float(np.sum(np.diff(t)[slow[1:]]) / (t[-1] - t[0]))  # step ending at a slow one
    assert got.stick_fraction == pytest.approx(want, rel=1e-12)
    assert got.stick_fraction == pytest.approx(0.83, abs=0.02)  # and the built-in truth
    assert got.events >= 8


def _ramps(drops: list[float], periods: list[float], slips: list[float], n: int = 40,
           dt_slip: float = 0.01) -> tuple[np.ndarray, ...]:
    """Ramps up by each drop in ``periods[k] - dt_slip`` (slider still), then the drop in one
    sample (the slider slips ``slips[k]``), then a last ramp up by 0.1 that confirms the last
    trough; built from the definitions."""
    t, y, x, v = [0.0], [1.0], [0.0], [0.0]
    for d, p, s in zip(drops, periods, slips, strict=True):
        tt = t[-1] + np.linspace(0.0, p - dt_slip, n)[1:]
        t += list(tt)
        y += list(1.0 + d * np.linspace(0.0, 1.0, n)[1:])
        x += [x[-1]] * (n - 1)
        v += [0.0] * (n - 1)
        t.append(t[-1] + dt_slip)
        y.append(1.0)
        x.append(x[-1] + s)
        v.append(s / dt_slip)
    t += list(t[-1] + np.linspace(0.0, 2.0, n)[1:])
    y += list(1.0 + 0.1 * np.linspace(0.0, 1.0, n)[1:])
    x += [x[-1]] * (n - 1)
    v += [0.0] * (n - 1)
    return tuple(map(np.asarray, (t, x, v, y)))


def test_every_measure_against_its_definition_on_known_events() -> None:
    """Unequal drops, periods and slips: range, threshold, drop and period means and their
    coefficients of variation (population std over mean), slip per event, stick time and
    mean force, each recomputed here from the events put in (mistakes: the sample std, the
    range of the drops, the threshold without its floor, the mean force as the sample mean)."""
    drops = [0.2, 0.3, 0.25, 0.2, 0.3, 0.25, 0.22]
    periods = [5.0, 7.0, 6.0, 5.5, 7.5, 6.0, 6.5]
    slips = [0.4, 0.7, 0.5, 0.45, 0.8, 0.55, 0.6]
    t, x, v, y = _ramps(drops, periods, slips)
    u = 0.083
    st = analyse(t, x, v, y, u=u, floor=1e-3, rel_threshold=0.3)
    peaks_t = np.cumsum(periods) - 0.01  # each peak is the last sample before its drop
    per = np.diff(peaks_t)
    d = np.asarray(drops)
    assert st.events == 7
    assert st.range == pytest.approx(0.3, rel=1e-12)
    assert st.threshold == pytest.approx(0.3 * 0.3, rel=1e-12)
    assert st.amplitude == pytest.approx(d.mean(), rel=1e-12)
    assert st.amplitude_cv == pytest.approx(d.std() / d.mean(), rel=1e-12)
    assert st.period == pytest.approx(per.mean(), rel=1e-12)
    assert st.period_cv == pytest.approx(per.std() / per.mean(), rel=1e-12)
    assert st.slip_per_event == pytest.approx(np.mean(slips), rel=1e-12)
    stick = float(np.sum(np.diff(t)[v[1:] < 0.5 * u]) / (t[-1] - t[0]))
    assert st.stick_fraction == pytest.approx(stick, rel=1e-12)
    assert st.stick_time == pytest.approx(stick * per.mean(), rel=1e-12)
    assert st.mean_force == pytest.approx(np.trapezoid(y, t) / (t[-1] - t[0]), rel=1e-12)
    assert st.kind == "irregular"  # cv of the periods 0.14 > 0.1
    # the floor wins when it is above rel_threshold * range
    assert analyse(t, x, v, y, u=u, floor=0.15).threshold == 0.15


@pytest.mark.parametrize("growth, kind", [(0.29, "transient"), (0.235, "periodic")])
def test_transient_is_a_drift_of_the_drops_beyond_30_percent(growth: float, kind: str) -> None:
    """Drops growing by ``exp(growth)`` over the run (regular periods): beyond ln 1.3 = 0.262
    the run is a transient, below it periodic (the fitted drift of ln drop, both sides)."""
    k = 12
    drops = list(0.2 * np.exp(growth * np.arange(k) / (k - 1)))
    t, x, v, y = _ramps(drops, [6.0] * k, [0.5] * k)
    st = analyse(t, x, v, y, u=0.083, floor=1e-3, rel_threshold=0.3)
    assert st.events == k and st.kind == kind


def test_summarise_reads_a_spring_run_after_half_its_travel() -> None:
    """summarise: the spring force ``mu_el K (X_pull - X)``, the transient at half the
    load-point travel by default (an explicit one up to, not including, the travel), ``u`` the
    last segment's velocity; each number against analyse called on the same samples."""
    from types import SimpleNamespace

    from dryfriction.analysis.stickslip import summarise
    from dryfriction.ensemble.drives import SpringDrive
    from dryfriction.ensemble.population import Track, TrapModel
    from dryfriction.program import Segment, VelocityProgram

    t, x, _, _ = _ramps([0.2, 0.3, 0.25, 0.2, 0.3, 0.25, 0.22],
                        [5.0, 7.0, 6.0, 5.5, 7.5, 6.0, 6.5], [0.4] * 7)
    u, k, mu_el = 0.083, 0.7, 0.45
    drive = SpringDrive(stiffness=k, mass=0.0, program=VelocityProgram(
        [Segment(0.02, duration=1.0), Segment(u, duration=float(t[-1]) - 1.0)]))
    x_pull = 0.3 + u * t
    res = SimpleNamespace(t=t, x=x, v=np.gradient(x, t), x_pull=x_pull)
    model = TrapModel(eps=0.04, mu_el=mu_el)
    got = summarise(res, drive, model, Track(50.0), floor=2e-3)  # type: ignore[arg-type]
    travel = x_pull - x_pull[0]
    t_half = float(np.interp(0.5 * travel[-1], travel, t))
    want = analyse(t, x, res.v, mu_el * k * (x_pull - x), u=u, t_start=t_half, floor=2e-3)
    assert got == {**want.to_dict(), "u": u, "stiffness": k}
    summarise(res, drive, model, Track(50.0), transient=0.9 * float(travel[-1]),  # type: ignore[arg-type]
              floor=2e-3)
    with pytest.raises(ValueError, match=r"^stickslip\.transient = .* a0 is not allowed: less "
                                         "than the load-point travel"):
        summarise(res, drive, model, Track(50.0), transient=float(travel[-1]), floor=2e-3)  # type: ignore[arg-type]
