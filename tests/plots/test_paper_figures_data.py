"""The paper's Fig. 4 and 6 and the three extra panels (plots/paper.py) read back from their
artists, each curve against the library function of that curve by another route (one model
per eps; ``dieterich_constant_local`` per eps, not the sweep over eps), at non-default
arguments (eps 0.03, alpha 0.11): mistakes in a curve's argument (C u for C/u, the load
dropped, Eyring-Nabarro for log), its grid, or a number written in a label or title."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.plots import paper
from dryfriction.theory.dieterich import (
    dieterich_constant_asymptotic,
    dieterich_constant_local,
)
from dryfriction.theory.model import TrapModel
from dryfriction.theory.static import static_friction
from dryfriction.theory.steady import steady_death_point, steady_friction, steady_profile
from dryfriction.theory.trap import Trap

A, E = 0.11, 0.03


def _by_label(ax):
    return {ln.get_label(): ln for ln in ax.get_lines()}


def test_fig6_each_constant_s_curve_at_t_c_over_u() -> None:
    _, ax = paper.fig6_dieterich(eps=E, alpha=A, C_values=(1.5, 3.5), C_paper=2.45,
                                 u_range=(0.02, 50.0), n=21)
    u = np.logspace(np.log10(0.02), np.log10(50.0), 21)
    m = TrapModel(A, E)
    lines = _by_label(ax)
    np.testing.assert_allclose(lines[r"$\mu_d(u)$"].get_xdata(), u, rtol=1e-12)
    np.testing.assert_allclose(lines[r"$\mu_d(u)$"].get_ydata(), steady_friction(m, u),
                               rtol=1e-12)
    for C in (1.5, 3.5):
        y = lines[rf"$\mu_s(C/u)$, $C$ = {C:g}"].get_ydata()
        np.testing.assert_allclose(y, static_friction(m, C / u), rtol=1e-12)
    np.testing.assert_allclose(lines[r"$C$ = 2.45 (paper)"].get_ydata(),
                               static_friction(m, 2.45 / u), rtol=1e-12)
    c_inf = dieterich_constant_asymptotic(m)
    np.testing.assert_allclose(lines[rf"$C_\infty$ = {c_inf:.4f} (ours, asymptotic)"]
                               .get_ydata(), static_friction(m, c_inf / u), rtol=1e-12)
    # the least-squares constant as its label gives it (4 decimals; recomputing it here would
    # double the test's time): its curve at T = C_LS/u
    (ls,) = [k for k in lines if k.startswith("$C_{LS}$ = ")]
    c_ls = float(ls.split("= ")[1].split(" ")[0])
    assert 1.0 < c_ls < 10.0
    np.testing.assert_allclose(lines[ls].get_ydata(), static_friction(m, c_ls / u), rtol=1e-4)


def test_fig4_profile_to_the_death_point_and_mu_d_in_the_title() -> None:
    _, ax = paper.fig4_steady_pinning_curve(u=0.3, eps=E, alpha=A)
    m = TrapModel(A, E)
    p_d = float(steady_death_point(m, 0.3))
    lines = _by_label(ax)
    aged = lines["dynamically aged, occupied (+) states"]
    y = np.linspace(-1.0, p_d, 1200)
    np.testing.assert_allclose(aged.get_xdata(), y, rtol=1e-12)
    np.testing.assert_allclose(aged.get_ydata(), steady_profile(m, y, 0.3), rtol=1e-12)
    elastic = lines[r"elastic curve ($\varepsilon$ = 0)"]
    assert elastic.get_xdata()[-1] == pytest.approx(Trap(A).y_c, rel=1e-12)
    dot = next(ln for ln in ax.get_lines() if ln.get_marker() == "o")
    assert list(dot.get_xdata()) == [p_d]
    assert ax.get_title().endswith(f"$\\mu_d$ = {float(steady_friction(m, 0.3)):.4f}")
    assert rf"$u$ = 0.3, $\varepsilon$ = {E:g}" in ax.get_title()
    assert any(f"{p_d:.4f}" in t.get_text() for t in ax.texts)


def test_extra_loaded_creep_and_local_constant_curves() -> None:
    T = np.logspace(-1.0, 1.0, 11)
    _, ax = paper.extra_loaded_static(eps=E, alpha=A, loads=(0.0, 0.3), T_range=(0.1, 10.0),
                                      n=11)
    lines = _by_label(ax)
    np.testing.assert_allclose(lines[r"$f_w$ = 0 $F_{el}$ (at rest, paper)"].get_ydata(),
                               static_friction(TrapModel(A, E), T), rtol=1e-12)
    np.testing.assert_allclose(lines[r"$f_w$ = 0.3 $F_{el}$"].get_ydata(),
                               static_friction(TrapModel(A, E), T, load=0.3), rtol=1e-12)
    _, ax = paper.extra_creep_laws(alpha=A, eps_values=(E,), x_range=(0.1, 10.0), n=11)
    ls = [ln for ln in ax.get_lines() if np.asarray(ln.get_xdata()).size == 11]
    log, en = TrapModel(A, E, "log"), TrapModel(A, E, "eyring-nabarro")
    want = [static_friction(log, T), static_friction(en, T), steady_friction(log, T),
            steady_friction(en, T)]
    assert len(ls) == 4
    for ln, w in zip(ls, want, strict=True):
        np.testing.assert_allclose(ln.get_ydata(), w, rtol=1e-12)
    assert [ln.get_linestyle() for ln in ls] == ["-", "--", "-", "--"]
    u = np.logspace(-1.0, 1.0, 7)
    _, ax = paper.extra_local_dieterich_constant(eps_values=(0.02, E), alpha=A,
                                                 u_range=(0.1, 10.0), n=7)
    curves = [ln for ln in ax.get_lines() if np.asarray(ln.get_xdata()).size == 7]
    for ln, e in zip(curves, (0.02, E), strict=True):
        np.testing.assert_allclose(ln.get_ydata(), dieterich_constant_local(TrapModel(A, e), u),
                                   rtol=1e-8)
    c_inf = dieterich_constant_asymptotic(TrapModel(A))
    flat = {ln.get_label(): ln.get_ydata()[0] for ln in ax.get_lines()
            if np.asarray(ln.get_xdata()).size == 2}
    assert flat[rf"$C_\infty$ = {c_inf:.4f} (ours)"] == pytest.approx(c_inf, rel=1e-12)
    assert flat[r"2.45 $\approx 1 + y_c$ (paper)"] == 2.45
