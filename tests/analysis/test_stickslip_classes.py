"""``analysis.stickslip.analyse``: each class on both sides of its threshold with the default
keywords (issue 25, strengthen7B).

A load built from its definition: ramps up by a drop in a period, then the drop in one sample.
The defaults under test (module doc): ``stick_fraction = 0.5`` (sticking is ``v < 0.5 u``:
ramps at 0.45 u stick, at 0.55 u they do not: ``periodic`` against ``oscillation``),
``cv_periodic = 0.1`` (periods of coefficient of variation 0.09 against 0.11: ``periodic``
against ``irregular``), three events at least (two: ``undetermined``), and ``steady`` when
the range is below the floor (its value itself is not steady).
"""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.analysis.stickslip import analyse

U = 0.083


def _ramps(periods: list[float], ramp_v: float, drop: float = 0.23, n: int = 40,
           dt_slip: float = 0.01) -> tuple[np.ndarray, ...]:
    """Ramps up by ``drop`` in ``period - dt_slip`` with the slider at ``ramp_v``, then the drop
    in one sample (the slider slips 0.5 a0 in it); a last ramp confirms the last trough."""
    t, y, x, v = [0.0], [1.0], [0.0], [ramp_v]
    for p in [*periods, 2.0]:
        tt = t[-1] + np.linspace(0.0, p - dt_slip, n)[1:]
        x += list(x[-1] + ramp_v * (tt - t[-1]))
        t += list(tt)
        y += list(1.0 + drop * np.linspace(0.0, 1.0, n)[1:])
        v += [ramp_v] * (n - 1)
        if p == 2.0:
            break
        t.append(t[-1] + dt_slip)
        y.append(1.0)
        x.append(x[-1] + 0.5)
        v.append(0.5 / dt_slip)
    return tuple(map(np.asarray, (t, x, v, y)))


def _periods(cv: float, k: int = 10) -> list[float]:
    """``k`` periods about 6.1 whose population coefficient of variation is ``cv``."""
    z = np.resize([1.0, -1.0], k)
    return list(6.1 * (1.0 + cv * z))


@pytest.mark.parametrize("ramp_v, kind", [(0.45 * U, "periodic"), (0.55 * U, "oscillation")])
def test_sticking_is_below_half_the_pulling_velocity(ramp_v: float, kind: str) -> None:
    t, x, v, y = _ramps(_periods(0.0), ramp_v)
    st = analyse(t, x, v, y, u=U)
    assert st.events == 10 and st.kind == kind
    assert (st.stick_fraction > 0.9) == (kind == "periodic")


@pytest.mark.parametrize("cv, kind", [(0.09, "periodic"), (0.11, "irregular")])
def test_periodic_below_a_tenth_of_variation(cv: float, kind: str) -> None:
    t, x, v, y = _ramps(_periods(cv), 0.1 * U)
    st = analyse(t, x, v, y, u=U)
    # the peaks' spacings: the periods shifted by one, the first period's end the first peak
    assert st.period_cv == pytest.approx(cv, rel=0.05)
    assert st.kind == kind


@pytest.mark.parametrize("k, kind", [(2, "undetermined"), (3, "periodic")])
def test_three_events_at_least(k: int, kind: str) -> None:
    t, x, v, y = _ramps([6.1] * k, 0.1 * U)
    st = analyse(t, x, v, y, u=U)
    assert st.events == k and st.kind == kind


def test_steady_below_the_floor_and_not_at_it() -> None:
    t, x, v, y = _ramps([6.1] * 5, 0.1 * U)
    rng = float(y.max() - y.min())
    assert analyse(t, x, v, y, u=U, floor=rng * (1 + 1e-9)).kind == "steady"
    assert analyse(t, x, v, y, u=U, floor=rng).kind != "steady"
