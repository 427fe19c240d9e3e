"""The run figures' drawn data and titles (plots/runs.py), each against its definition written
here, at generic values: the drive and machine said in the titles (spring, force ramp, loaded
start, plurals), the steady state ``mu_ss(V)`` drawn over a geometric grid, the spring-force
line only with damping or mass, the velocity panel's log/linear switch, the load point's slip,
the threshold star at its slip, the twin's parameters times ``mu_el``, the phase diagram's
markers at their (u, K) and its ``K_c(u)`` line."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

from dryfriction.analysis import stickslip
from dryfriction.analysis.rsf_view import Comparison
from dryfriction.plots import runs
from dryfriction.plots.runs import _describe_drive, _rsf_title, _trap_title


def test_drive_descriptions_spring_force_and_plurals() -> None:
    # mistakes: K and M swapped, the hold count off (a segment of velocity 0 is a hold, not
    # one given by its duration), the loaded start's force taken from the drive, "1 segments"
    segs = [{"velocity": 1e-3, "slip": 0.5}, {"velocity": 0.0, "duration": 30.0},
            {"velocity": 2e-3, "duration": 12.0}, {"velocity": 0.0, "duration": 7.0}]
    spring = {"kind": "spring", "stiffness": 0.037, "mass": 0.5, "damping": 0.25,
              "segments": segs}
    assert _describe_drive(spring, {"kind": "loaded", "force": 0.3}) == (
        r"spring $K$ = 0.037 $F_{el}/a_0$, $M$ = 0.5, $\eta$ = 0.25; 4 segments, 2 holds "
        "from rest under 0.3 $F_{el}$")
    one = {"kind": "velocity", "segments": [{"velocity": 0.3, "slip": 2.0}]}
    assert _describe_drive(one, {"kind": "steady", "velocity": 0.3}) == (
        "velocity program: 1 segment from steady sliding at u = 0.3")
    held = {"kind": "velocity", "segments": segs[:2]}
    assert _describe_drive(held, {"kind": "rest"}) == (
        "velocity program: 2 segments, 1 hold from rest")
    force = {"kind": "force", "hold": 250.0, "rate": 0.0625}
    assert _describe_drive(force, {"kind": "rest"}) == (
        r"force control from rest: hold 250 $t_0$, then a ramp of 0.0625 $F_{el}/t_0$")


def test_trap_title_reads_the_model_and_the_track() -> None:
    p = {"model": {"eps": 0.023, "alpha": 0.17, "creep": "eyring-nabarro"},
         "track": {"traps_per_a0": 250.0},
         "drive": {"kind": "force", "hold": 10.0, "rate": 0.5}, "initial": {"kind": "rest"}}
    title = _trap_title(SimpleNamespace(info={"parameters": p}, partial=False))
    assert title == ("trap model: $\\varepsilon$ = 0.023, $\\alpha$ = 0.17, eyring-nabarro "
                     "creep, 250 traps/$a_0$\nforce control from rest: hold 10 $t_0$, then a "
                     "ramp of 0.5 $F_{el}/t_0$")


def _rsf_result(**kw):
    t = np.linspace(3.0, 43.0, 401)  # a record whose time does not start at 0
    v = np.where(t < 13.0, 2e-6, 2e-5)
    v[200:230] = 0.0
    x = 4e-3 + np.concatenate([[0.0], np.cumsum(v[1:] * np.diff(t))])
    mu = 0.61 + 0.004 * np.log(np.maximum(v, 1e-9) / 2e-6)
    params = SimpleNamespace(state_law="slip", a=0.011, b=0.015, dc=2.5e-5, mu0=0.61, v0=2e-6,
                             steady_state_friction=lambda w: 0.61 - 0.004 * np.log(w / 2e-6))
    base = dict(t=t, x=x, v=v, mu=mu, stress=mu - 2e-3, load_velocity=1.5 * v, damping=0.0,
                mass=0.0, params=params, stiffness=None)
    base.update(kw)
    return SimpleNamespace(**base)


def test_rsf_titles_law_machine_damping_mass() -> None:
    # mistakes: "kinematic" for a finite spring, damping's unit for the mass, a zero mass shown
    r = _rsf_result(stiffness=2.0e4, damping=0.3)
    assert _rsf_title(r) == ("rate-and-state, slip law: a = 0.011, b = 0.015, $D_c$ = 2.5e-05 m\n"
                             "$\\mu_0$ = 0.61 at $V_0$ = 2e-06 m/s, spring k = 20000 1/m, "
                             "damping = 0.3 s/m")
    r = _rsf_result(stiffness=np.inf, mass=0.02)
    assert _rsf_title(r, "step").endswith("kinematic machine, mass = 0.02 s²/m")
    assert _rsf_title(r, "step").startswith("step: a = 0.011")


def test_friction_against_ln_v_draws_the_steady_state_on_a_geometric_grid() -> None:
    # the steady state mu_ss(V) on 200 points geometrically spaced from the lowest to the
    # highest positive slip rate (mistake: a linear grid, or from 0); the start marker at the
    # first sample that has a rate
    r = _rsf_result()
    _, axes = runs.rsf_timeseries_figure(r)
    ax = axes[3]
    ss = next(ln for ln in ax.lines if ln.get_label() == r"steady state $\mu_{ss}(V)$")
    grid = np.geomspace(2e-6, 2e-5, 200)
    np.testing.assert_allclose(ss.get_xdata(), grid, rtol=1e-12)
    np.testing.assert_allclose(ss.get_ydata(), 0.61 - 0.004 * np.log(grid / 2e-6), rtol=1e-12)
    start = next(ln for ln in ax.lines if ln.get_marker() == "o")
    assert list(start.get_xdata()) == [2e-6] and list(start.get_ydata()) == [r.mu[0]]
    run = ax.lines[0]
    assert np.isnan(run.get_xdata()[200:230]).all()  # a hold has no place on ln V


def test_rsf_timeseries_spring_force_only_with_damping_or_mass_and_load_velocity() -> None:
    # mistake: the spring-force line tied to the damping alone (with a mass the spring no
    # longer reads the friction either)
    for kw, drawn in (({}, False), ({"mass": 1e-3}, True), ({"damping": 0.2}, True)):
        _, axes = runs.rsf_timeseries_figure(_rsf_result(**kw))
        lines = [ln for ln in axes[0].lines if "spring force" in str(ln.get_label())]
        assert bool(lines) is drawn, kw
        if drawn:
            np.testing.assert_array_equal(lines[0].get_ydata(), _rsf_result().stress)
    r = _rsf_result()
    _, axes = runs.rsf_timeseries_figure(r)
    lv = next(ln for ln in axes[2].lines if ln.get_label() == "load velocity")
    want = np.where(r.load_velocity > 0, r.load_velocity, np.nan)
    np.testing.assert_array_equal(lv.get_ydata(), want)
    np.testing.assert_array_equal(axes[1].lines[0].get_xdata(), r.x - r.x[0])


def _trap(v, x_pull=None, **info):
    t = np.linspace(2.0, 12.0, 51)
    x = 0.7 + np.cumsum(np.concatenate([[0.0], np.abs(v[1:]) * np.diff(t)]))
    mu = 1.0 + 0.03 * np.sin(t)
    params = {"model": {"eps": 0.03, "alpha": 0.13, "creep": "log", "mu_el": 0.8},
              "track": {"traps_per_a0": 300.0},
              "drive": {"kind": "velocity", "segments": [{"velocity": 0.2, "slip": 1.0}]},
              "initial": {"kind": "steady", "velocity": 0.2}}
    return SimpleNamespace(t=t, x=x, v=v, mu=mu, partial=False,
                           x_pull=np.full(t.size, np.nan) if x_pull is None else x_pull,
                           info={"parameters": params, **info})


def test_timeseries_velocity_panel_log_beyond_thirty_linear_from_zero_below() -> None:
    # the velocity panel goes to a log axis when the rates span more than a factor 30; below
    # it stays linear from 0 to 1.1 times the largest rate (mistakes: the factor, the margin)
    t = np.linspace(2.0, 12.0, 51)
    wide = np.where(t < 7.0, 0.01, 0.31)  # a factor 31
    narrow = np.where(t < 7.0, 0.01, 0.29)  # a factor 29
    _, axes = runs.timeseries_figure(_trap(wide))
    assert axes[2].get_yscale() == "log"
    _, axes = runs.timeseries_figure(_trap(narrow))
    assert axes[2].get_yscale() == "linear"
    assert axes[2].get_ylim() == pytest.approx((0.0, 1.1 * 0.29), rel=1e-12)
    assert "$v$" in axes[2].get_ylabel() and "|v|" not in axes[2].get_ylabel()
    # the friction label carries mu_el = 0.8
    assert r"$\mu_{el}$ = 0.8" in axes[0].get_ylabel()
    back = np.where(t < 7.0, 0.2, -0.15)  # sliding back: the label says |v|
    _, axes = runs.timeseries_figure(_trap(back))
    assert "|v|" in axes[2].get_ylabel()


def test_timeseries_load_point_from_its_first_sample_and_threshold_at_its_slip() -> None:
    t = np.linspace(2.0, 12.0, 51)
    v = np.full(t.size, 0.2)
    x_pull = np.full(t.size, np.nan)
    x_pull[3:] = 5.0 + 0.25 * (t[3:] - t[3])  # the load point recorded from the 4th sample
    r = _trap(v, x_pull, threshold_mu=1.0234, threshold_t=6.3)
    _, axes = runs.timeseries_figure(r)
    lp = next(ln for ln in axes[3].lines if ln.get_label() == "load point")
    np.testing.assert_allclose(lp.get_ydata(), x_pull - 5.0, rtol=1e-14)
    slider = next(ln for ln in axes[3].lines if ln.get_label() == "slider")
    np.testing.assert_allclose(slider.get_ydata(), r.x - r.x[0], rtol=1e-14)
    # the star: at t = 6.3 on the time panel, at the slip reached at 6.3 on the slip panel
    star_t = next(ln for ln in axes[0].lines if ln.get_marker() == "*")
    star_x = next(ln for ln in axes[1].lines if ln.get_marker() == "*")
    assert list(star_t.get_xdata()) == [6.3]
    assert star_x.get_xdata()[0] == pytest.approx(float(np.interp(6.3, t, r.x - r.x[0])),
                                                  rel=1e-12)
    assert star_x.get_ydata()[0] == 1.0234
    assert any(tx.get_text() == "static threshold 1.023" for tx in axes[1].texts)


def test_comparison_title_scales_the_twin_by_mu_el_and_labels_the_unit() -> None:
    # the twin's a, b are per F_el; in friction units a = mu_el a_twin (mistake: unscaled)
    t = np.linspace(1.0, 21.0, 80)
    mu_trap = 0.7 * (1 + 0.02 * np.tanh(t - 5))
    twin = SimpleNamespace(state_law="slip", a=0.0031, b=0.0213, dc=1.7)
    c = Comparison(t, 0.1 * t + 2.0, mu_trap, mu_trap + 1e-3 * np.cos(t), twin, "standard", 0.7)
    fig, ax = runs.comparison_figure(c, "p.toml")
    title = fig.get_suptitle()
    assert f"a = {0.7 * 0.0031:.3g}, b = {0.7 * 0.0213:.3g}" in title
    assert "$D_c$ = 1.7 $a_0$" in title and f"rms misfit {c.misfit['rms']:.3g}" in title
    assert r"\mu_{el} F/F_{el}" in ax[2].get_ylabel()
    np.testing.assert_allclose(ax[1].lines[0].get_xdata(), 0.1 * (t - t[0]), rtol=0,
                               atol=1e-14)


def test_phase_diagram_markers_at_their_point_and_the_critical_line(monkeypatch) -> None:
    # a 2 x 3 sweep (not square: a transposed class array would misplace or fail), the K_c
    # line on 40 geometric velocities over the swept range (critical_line replaced by a
    # closed form here: what is tested is the drawing); K spanning more than 5 on a log axis
    monkeypatch.setattr(stickslip, "critical_line", lambda base, u: 0.3 * np.sqrt(u))
    K, V = [0.02, 0.15], [0.05, 0.2, 0.8]
    codes = np.array([[0.0, 1.0, 2.0], [np.nan, 3.0, 0.0]])
    ds = xr.Dataset({"class": (("k", "v"), codes)}, coords={"k": K, "v": V})
    base = {"model": {"eps": 0.035}, "drive": {"mass": 0.4, "damping": 0.06}}
    fig, ax = runs.phase_diagram_figure(ds, base, "k", "v")
    pts = {c.get_label(): sorted(map(tuple, np.asarray(c.get_offsets()).tolist()))
           for c in ax.collections}
    assert pts == {"steady": [(0.05, 0.02), (0.8, 0.15)], "periodic": [(0.2, 0.02)],
                   "irregular": [(0.8, 0.02)], "transient": [(0.2, 0.15)],
                   "failed": [(0.05, 0.15)]}
    line = ax.lines[0]
    np.testing.assert_allclose(line.get_xdata(), np.geomspace(0.05, 0.8, 40), rtol=1e-12)
    np.testing.assert_allclose(line.get_ydata(), 0.3 * np.sqrt(np.geomspace(0.05, 0.8, 40)),
                               rtol=1e-12)
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"  # K spans 7.5
    assert ax.get_title() == (r"stick-slip phase diagram, $\varepsilon$ = 0.035, $M$ = 0.4, "
                              r"$\eta$ = 0.06")
    # K spanning exactly 5: linear (the rule is "more than 5")
    ds5 = ds.assign_coords(k=[0.03, 0.15])
    assert runs.phase_diagram_figure(ds5, base, "k", "v")[1].get_yscale() == "linear"
