"""``reproduce``'s summary and report page, every number recomputed here from its definition by
another route (per-eps models instead of the ``*_over_eps`` sweeps, the grid written out), and
the page's table read cell by cell from a summary of generic made-up numbers (so that a row
showing the wrong key, a swapped column or a wrong percentage cannot hide behind equal values).
"""

from __future__ import annotations

import copy
import re

import numpy as np
import pytest

from dryfriction import __version__
from dryfriction.plots import report
from dryfriction.theory.creep import radius
from dryfriction.theory.model import TrapModel
from dryfriction.theory.static import fresh_force, loaded_edge, static_friction
from dryfriction.theory.steady import steady_friction

ALPHA = 0.13
EPS = (0.01, 0.02, 0.03, 0.04, 0.05)
U = np.logspace(-2.0, 2.0, 201)  # the figures' grid, written out: 0.01 ... 100, 201 points
BUILD = {"version": __version__, "commit": "", "date": "2026-01-02 03:04 UTC"}


@pytest.fixture(scope="module")
def s():
    return report.compute_summary()


def test_grid_and_eps_of_the_data_files() -> None:
    # mistake: a grid of 200 points, or one decade short, changes every CSV row
    np.testing.assert_array_equal(report.GRID, U)
    assert list(report.EPS) == list(EPS)


def test_end_points_per_eps_from_one_model_per_eps(s) -> None:
    # mistakes: the T = 100 column taken for T = 0.01 (or the last row for the first), mu_s and
    # mu_d swapped; each value by the single-eps route (one TrapModel per eps)
    assert s["eps_values"] == list(EPS)
    for k, e in enumerate(EPS):
        m = TrapModel(ALPHA, e)
        assert s["mu_s_at_T_0.01"][k] == pytest.approx(float(static_friction(m, 0.01)), rel=1e-12)
        assert s["mu_s_at_T_100"][k] == pytest.approx(float(static_friction(m, 100.0)), rel=1e-12)
        assert s["mu_d_at_u_0.01"][k] == pytest.approx(float(steady_friction(m, 0.01)), rel=1e-12)
        assert s["mu_d_at_u_100"][k] == pytest.approx(float(steady_friction(m, 100.0)), rel=1e-12)
    # absolute levels: static friction grows with eps at T = 100, steady friction falls at u = 0.01
    assert np.all(np.diff(s["mu_s_at_T_100"]) > 0) and np.all(np.diff(s["mu_d_at_u_0.01"]) > 0)


def test_dieterich_residuals_and_gap_by_their_definition(s) -> None:
    # max over the grid of |mu_d(u) - mu_s(C/u)| for each C; the paper's curve against the
    # asymptotic one. Mistakes: C * u for C / u, the residual of one C under another's name
    m = TrapModel(ALPHA, 0.04)
    mu_d = steady_friction(m, U)
    cs = {"C_asymptotic": s["dieterich_C_asymptotic"],
          "C_least_squares": s["dieterich_C_least_squares"], "C_paper": 2.45}
    assert s["dieterich_C_paper"] == 2.45
    for name, c in cs.items():
        want = float(np.max(np.abs(mu_d - static_friction(m, c / U))))
        assert s["dieterich_max_residual"][name] == pytest.approx(want, rel=1e-10), name
    gap = float(np.max(np.abs(static_friction(m, 2.45 / U) - static_friction(m, cs["C_asymptotic"]
                                                                              / U))))
    assert s["dieterich_paper_vs_asymptotic_max_gap"] == pytest.approx(gap, rel=1e-10)
    assert s["dieterich_C_least_squares_range"] == {"u_min": 0.01, "u_max": 100.0, "n": 81}
    assert s["dieterich_eps"] == 0.04
    assert s["one_plus_y_c"] == pytest.approx(1.0 + (1 - ALPHA) ** 2 / (4 * ALPHA), rel=1e-14)


def test_fig4_friction_and_creep_differences_by_their_definition(s) -> None:
    assert s["fig4"]["u"] == 0.1 and s["fig4"]["eps"] == 0.04
    assert s["fig4"]["mu_d"] == pytest.approx(
        float(steady_friction(TrapModel(ALPHA, 0.04), 0.1)), rel=1e-12)
    # the exact Eyring-Nabarro law against the log law, over every eps and the whole grid
    # (mistakes: the eps = 0.01 row taken for the whole range, or the last row for eps = 0.01)
    dr = [np.abs(radius(U, e, "eyring-nabarro") - radius(U, e, "log")) for e in EPS]
    ds = [np.abs(static_friction(TrapModel(ALPHA, e, creep="eyring-nabarro"), U)
                 - static_friction(TrapModel(ALPHA, e), U)) for e in EPS]
    dd = [np.abs(steady_friction(TrapModel(ALPHA, e, creep="eyring-nabarro"), U)
                 - steady_friction(TrapModel(ALPHA, e), U)) for e in EPS]
    cd = s["creep_law_difference"]
    assert cd["max_abs_radius_ratio"] == pytest.approx(max(map(np.max, dr)), rel=1e-9)
    assert cd["max_abs_mu_s"] == pytest.approx(max(map(np.max, ds)), rel=1e-9)
    assert cd["max_abs_mu_d"] == pytest.approx(max(map(np.max, dd)), rel=1e-9)
    assert cd["max_abs_mu_s_eps_0.01"] == pytest.approx(float(np.max(ds[0])), rel=1e-9)
    assert cd["max_abs_mu_d_eps_0.01"] == pytest.approx(float(np.max(dd[0])), rel=1e-9)


def test_loaded_protocol_edge_carries_the_load(s) -> None:
    # the edge d_w is the root of fresh_force(d_w) = f_w (a fresh contact carrying the load);
    # mistake: the edge of another load, or of a model at another eps
    for d, f_w in zip(s["loaded_protocol"], (0.0, 0.25, 0.5), strict=True):
        assert d["load"] == f_w and d["eps"] == 0.04
        assert d["edge_d_w"] == pytest.approx(loaded_edge(TrapModel(ALPHA), f_w), rel=1e-12)
        assert float(fresh_force(TrapModel(ALPHA), d["edge_d_w"])) == pytest.approx(f_w,
                                                                                  abs=1e-9)


# ------------------------------------------------------------------ the page, cell by cell


def _forged(s):
    """The summary with generic, pairwise different numbers where the page reads them."""
    f = copy.deepcopy(s)
    f["dieterich_C_asymptotic"] = 2.7  # 10.2 % above the paper's 2.45
    f["static_slope_per_eps"] = 1.17
    f["dynamic_slope_per_eps"] = -1.43
    f["mu_d_at_u_100"] = [1.00011, 1.00022, 1.00033, 1.00044, 1.00055]
    f["mu_d_at_u_0.01"] = [1.1, 1.2, 1.3, 1.4, 1.5]
    f["mu_s_at_T_0.01"] = [1.00061, 1.00072, 1.00083, 1.00094, 1.00105]
    f["mu_s_at_T_100"] = [1.2, 1.3, 1.4, 1.5, 1.6]
    f["dieterich_max_residual"] = {"C_asymptotic": 0.0123, "C_least_squares": 0.0456,
                                   "C_paper": 0.0789}
    f["dieterich_C_local"] = {"0.01": 17.25, "0.1": 7.5, "1": 4.25, "10": 3.125, "100": 2.875}
    f["creep_law_difference"] = {**f["creep_law_difference"], "max_abs_mu_s": 0.004321,
                                 "max_abs_mu_d": 0.005432, "max_abs_mu_d_eps_0.01": 0.000654,
                                 "max_abs_mu_s_eps_0.01": 0.000765}
    f["loaded_protocol"] = [
        {"load": 0.0, "edge_d_w": -0.11111, "eps": 0.04, "mu_s_T_1": 1.02222,
         "mu_s_T_100": 1.13333, "secant_slope_per_eps_T_1_to_100": 1.4444},
        {"load": 0.25, "edge_d_w": -0.22222, "eps": 0.04, "mu_s_T_1": 1.05555,
         "mu_s_T_100": 1.16666, "secant_slope_per_eps_T_1_to_100": 1.7777},
    ]
    return f


@pytest.fixture(scope="module")
def forged(s, tmp_path_factory):
    folder = tmp_path_factory.mktemp("figs")
    for name in (*report.FIGURE_FILES, *report.EXTRA_FILES):
        (folder / name).write_bytes(b"\x89PNG\r\n\x1a\n")
    f = _forged(s)
    return f, report.report_html(folder, f, BUILD)


def _key_rows(page):
    rows = re.findall(r"<tr><td>(.*?)</td><td class=num>(.*?)</td><td>(.*?)</td>"
                      r"<td class=note>(.*?)</td></tr>", page, re.S)
    return {q: (o, p, n) for q, o, p, n in rows}


def test_key_table_rows_show_their_own_numbers(forged) -> None:
    # mistakes: the u = 100 row showing the u = 0.01 values, T = 0.01 showing T = 100, the
    # residual of another C, the EN differences of one eps for the other
    f, page = forged
    rows = _key_rows(page)
    assert rows["μ_d(u = 100)"][0] == "1.00011, 1.00022, 1.00033, 1.00044, 1.00055"
    assert rows["μ_s(T = 0.01)"][0] == "1.00061, 1.00072, 1.00083, 1.00094, 1.00105"
    ls = rows["Dieterich C, least squares (u 0.01–100, ε = 0.04)"]
    assert ls[2] == "max |μ_d − μ_s(C/u)| = 0.0456"
    asym = rows["Dieterich C, asymptotic (u → ∞)"]
    assert asym[0] == "2.7"
    # (2.7 / 2.45 - 1) = 10.204 %: one decimal
    assert "differs by 10.2 % from the paper" in asym[2]
    assert f"1 + y_c = {f['one_plus_y_c']:.4f}" in asym[2]
    assert rows["local C(u), ε = 0.04"][0] == ("u=0.01:&nbsp;17.250, u=0.1:&nbsp;7.500, "
                                                "u=1:&nbsp;4.250, u=10:&nbsp;3.125, "
                                                "u=100:&nbsp;2.875")
    assert rows["max |μ_s(EN) − μ_s(log)|"][0] == "0.004321"
    en_d = rows["max |μ_d(EN) − μ_d(log)|"]
    assert en_d[0] == "0.005432" and en_d[2] == "at ε = 0.01 only 0.0007"
    assert rows["(1/ε) dμ_s/d ln(1+T) (first order)"][0] == "1.17"
    assert rows["(1/ε) dμ_d/d ln u (u ≪ 1)"][0] == "-1.43"


def test_claims_quote_the_ratio_of_the_slopes_and_the_local_constants(forged) -> None:
    # ratio = static / |dynamic| = 1.17 / 1.43 = 0.818 (mistake: the signed ratio, -0.818)
    _, page = forged
    assert "1.1700\nε per unit ln t_w against 1.4300 ε per unit ln(1/V), ratio\n0.818." in page
    assert "falls from\n17.25 at u = 0.01 to 2.875 at\nu = 100" in page
    assert "C_∞ = 2.7000, about\n10.2 % larger" in page
    assert "residuals up to\n0.046." in page


def test_loaded_table_columns_in_their_header_order(forged) -> None:
    # header: f_w, d_w, mu_s(T=1), mu_s(T=100), slope/eps (mistake: two columns swapped)
    f, page = forged
    head = re.search(r"<tr><th>f_w \[F_el\]</th>(.*?)</tr>", page, re.S).group(0)
    assert re.findall(r"<th>(.*?)</th>", head) == ["f_w [F_el]", "edge d_w [a0]", "μ_s(T=1)",
                                                   "μ_s(T=100)", "slope/ε"]
    cells = [re.findall(r"<td class=num>(.*?)</td>", r) for r in re.findall(
        r"<tr>(<td class=num>[^\n]*?)</tr>", page.split(head)[1].split("</table>")[0])]
    assert cells == [["0", "-0.11111", "1.02222", "1.13333", "1.4444"],
                     ["0.25", "-0.22222", "1.05555", "1.16666", "1.7777"]]


def test_panel_cuts_just_right_of_each_panel() -> None:
    # three panels side by side at 60 dpi: each cut 0.1 in right of a panel's frame, or at the
    # next panel's left edge if that is nearer (mistakes: the pad in pixels, cut at the frame
    # itself, the last panel dropped, the panels named from 1)
    import io

    from PIL import Image

    from dryfriction.plots.style import new_figure

    fig, _ = new_figure((9.0, 2.5), 1, 3)
    fig.canvas.draw()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=60)
    width = Image.open(io.BytesIO(buf.getvalue())).size[0]
    boxes = sorted((ax.get_position() for ax in fig.axes), key=lambda b: b.x0)
    cuts = [0] + [round(width * min(b.x1 + 0.1 / 9.0, nxt.x0))
                  for b, nxt in zip(boxes[:-1], boxes[1:], strict=True)] + [width]
    got = report.panel_pngs(fig, buf.getvalue(), "f.png", 60)
    assert [g[0] for g in got] == ["f.png (a)", "f.png (b)", "f.png (c)"]
    widths = [Image.open(io.BytesIO(g[2])).size[0] for g in got]
    assert widths == [b - a for a, b in zip(cuts[:-1], cuts[1:], strict=True)]
    assert all(b.x1 + 0.1 / 9.0 < nxt.x0 for b, nxt in zip(boxes[:-1], boxes[1:], strict=True))
