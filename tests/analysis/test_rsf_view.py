"""The trap model seen through rate-and-state: robust physical conclusions, each checked by a
route independent of the fit (eq. 34, the linear response, the trap geometry)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from dryfriction.analysis.rsf_view import rsf_twin_series, transient_shape, trap_model_as_rsf
from dryfriction.io.files import to_jsonable
from dryfriction.program import Segment, VelocityProgram
from dryfriction.rsf.law import RateState
from dryfriction.theory.creep import radius
from dryfriction.theory.linear_stability import effective_rsf
from dryfriction.theory.model import TrapModel
from dryfriction.theory.steady import steady_friction
from dryfriction.theory.trap import Trap

EPS, ALPHA, U0 = 0.04, 0.13, 0.1


@pytest.fixture(scope="module")
def view():  # type: ignore[no-untyped-def]
    return trap_model_as_rsf(TrapModel(alpha=ALPHA, eps=EPS), u0=U0)


@pytest.mark.slow
def test_the_ensemble_is_accurate_enough(view) -> None:  # type: ignore[no-untyped-def]
    """Steady levels of the runs against eq. 34 (closed-form quadrature) to 1e-3."""
    model = TrapModel(alpha=ALPHA, eps=EPS)
    for entry in view.steps.values():
        assert entry["mu_before"] == pytest.approx(float(steady_friction(model, U0)), abs=1e-3)
        assert entry["mu_end"] == pytest.approx(float(steady_friction(model, entry["u_after"])),
                                                abs=1e-3)


@pytest.mark.slow
def test_velocity_weakening_and_the_steady_slope(view) -> None:  # type: ignore[no-untyped-def]
    """b > a > 0 and a - b equals the steady slope of eq. 34 over the steps (chord of the
    exact steady friction), to 10 % (the fit also weighs the transients)."""
    chord = (float(steady_friction(TrapModel(alpha=ALPHA, eps=EPS), 10 * U0))
             - float(steady_friction(TrapModel(alpha=ALPHA, eps=EPS),
                                     U0 / 10))) / (2 * math.log(10.0))
    for key in ("ageing", "slip", "ageing_with_holds"):
        tw = view.twins[key]
        assert tw.b > tw.a > 0.0
        assert tw.a - tw.b == pytest.approx(chord, rel=0.1)


def test_no_direct_effect(view) -> None:  # type: ignore[no-untyped-def]
    """The ensemble's friction is continuous in slip: the first 0.02 a0 after the step
    u0 -> 10 u0 changes it by far less than the linear prediction's direct effect a ln 10,
    and the fitted a is a small fraction of b (the linear theory's a/b is 0.25 here)."""
    lin = effective_rsf(U0, TrapModel(alpha=ALPHA, eps=EPS))
    up = view.steps[f"step {U0:g} -> {10 * U0:g}"]
    assert abs(up["jump_first_sample"]) < 0.1 * lin["a"] * math.log(10.0)
    for key in ("ageing", "slip", "ageing_with_holds"):
        assert view.twins[key].a < 0.1 * view.twins[key].b
    assert view.linear["forward_shift_stiffness"] < 0.0  # softening forward response


def test_b_scales_with_eps_between_the_linear_bounds(view) -> None:  # type: ignore[no-untyped-def]
    """b = c eps with c between (b - a)/eps and b/eps of the linear prediction
    (effective_rsf): with a -> 0 the fit puts all of the steady weakening into b, and the
    linear theory's b is the largest evolution effect the slow response allows."""
    lin = effective_rsf(U0, TrapModel(alpha=ALPHA, eps=EPS))
    lo, hi = 0.95 * (lin["b"] - lin["a"]) / EPS, lin["b"] / EPS
    assert 1.3 < lo < hi < 2.2  # stated range at eps = 0.04, u0 = 0.1
    for key in ("ageing", "slip", "ageing_with_holds"):
        assert lo < view.twins[key].b / EPS < hi


def test_dc_is_of_order_a0_and_the_memory_is_finite(view) -> None:  # type: ignore[no-untyped-def]
    """Dc between a quarter and a half of the trap's life in slip, (1 + y_c) a0; the transient
    ends after 1 + p_d, with p_d = y_c a_r(age) between y_c and y_c a_r(max age)."""
    yc = Trap(ALPHA).y_c
    for key in ("ageing", "slip", "ageing_with_holds"):
        assert 0.25 * (1 + yc) < view.twins[key].dc < 0.5 * (1 + yc)
    lin = effective_rsf(U0, TrapModel(alpha=ALPHA, eps=EPS))
    assert 0.25 * (1 + yc) < lin["dc"] < 0.5 * (1 + yc)
    for entry in view.steps.values():
        u_min = min(U0, entry["u_after"])
        r_max = float(radius(3.0 * (1 + yc) / u_min, EPS))  # oldest age met, bounded
        shape = entry["shape_trap"]
        assert 0.9 * (1 + yc) < shape["x99"] < 1 + yc * r_max
        assert shape["x99_over_x90"] < 1.6  # an exponential gives 2
        for law in ("ageing", "slip"):  # the fitted twins keep the exponential tail
            assert entry[f"shape_rsf_{law}"]["x99"] > shape["x99"]


def test_rsf_describes_the_steps_to_a_few_percent_with_a_systematic_misfit(
        view) -> None:  # type: ignore[no-untyped-def]
    for key in ("ageing", "slip"):
        tw = view.twins[key]
        for name, entry in view.steps.items():
            change = abs(entry["mu_end"] - entry["mu_before"])
            assert 0.01 * change < tw.rms[name] < 0.15 * change
        assert any("systematic misfit" in n for n in tw.notes)  # runs test


def test_healing_needs_the_ageing_law(view) -> None:  # type: ignore[no-untyped-def]
    """Peaks grow with log hold time at about b (Beeler et al. 1994); the slip law predicts
    no healing at rest and misses them by far more than the ageing law."""
    peaks = np.array(view.shs["peak_mu"])
    assert np.all(np.diff(peaks) > 0)
    assert view.shs["healing_rate_dmu_dlnt"] == pytest.approx(view.twins["ageing"].b, rel=0.25)
    assert view.shs["rms_slip"] > 5 * view.shs["rms_ageing_with_holds"]


def test_to_dict_is_json(view) -> None:  # type: ignore[no-untyped-def]
    d = json.loads(json.dumps(to_jsonable(view.to_dict())))
    assert set(d["fits"]) == {"ageing", "slip", "ageing_with_holds"}
    assert d["fits"]["ageing"]["dc_a0"] == view.twins["ageing"].dc
    assert len(view.findings) >= 5


def test_twin_series_holds_follow_the_state_laws() -> None:
    """Kinematic reload after a hold: the first friction equals the closed-form peak of
    hold_peak_friction (ageing law) and mu_ss (slip law)."""
    prog = VelocityProgram([Segment(1.0, 2.0), Segment(0.0, 50.0), Segment(1.0, 5.0)])
    t = np.array([1.0, 10.0, 52.0, 57.0])
    for law in ("ageing", "slip"):
        p = RateState(0.01, 0.02, 0.5, 1.0, 1.0, state_law=law)  # type: ignore[arg-type]
        f = rsf_twin_series(p, prog, t)
        assert f[0] == pytest.approx(1.0, abs=1e-9) and math.isnan(f[1])
        assert f[2] == pytest.approx(float(p.hold_peak_friction(50.0, 1.0)), abs=1e-7)


def test_transient_shape_of_an_exponential() -> None:
    x = np.linspace(0.0, 30.0, 30001)
    mu = np.where(x < 1.0, 0.0, 1.0 - np.exp(-(x - 1.0)))
    s = transient_shape(x, mu, 1.0)
    assert s["x50"] == pytest.approx(math.log(2.0), rel=1e-4)
    assert s["x90_over_x50"] == pytest.approx(math.log(10.0) / math.log(2.0), rel=1e-3)
    assert s["x99_over_x90"] == pytest.approx(2.0, rel=1e-3)


def test_compare_calibrates_the_protocols_whole_model(tmp_path, monkeypatch) -> None:
    # mistake caught: the standard calibration rebuilding an athermal model from eps, alpha and
    # creep (the old form's call), so a protocol's direct effect was dropped
    from dryfriction.analysis import rsf_view
    from dryfriction.io.protocol import load_protocol

    f = tmp_path / "hold.toml"
    f.write_text("[model]\neps = 0.03\nalpha = 0.11\ncreep = \"eyring-nabarro\"\n"
                 "direct = 0.02\nv_ref = 0.4\nmu_el = 0.5\n"
                 "[ensemble]\ntraps_per_a0 = 20\ninitial = \"steady\"\n"
                 "initial_velocity = 0.2\n[drive]\nkind = \"velocity\"\n"
                 "segments = [{velocity = 0.0, duration = 1.0}, {velocity = 0.2, slip = 0.2}]\n"
                 "[output]\nevery_slip = 0.05\n")
    proto = load_protocol(f)
    seen = []

    def stop(model, u0, *args, **kwargs):
        seen.append((model, u0))
        raise RuntimeError("stop")

    monkeypatch.setattr(rsf_view, "trap_model_as_rsf", stop)
    with pytest.raises(RuntimeError, match="stop"):
        rsf_view.compare_protocol(proto)
    assert seen == [(proto.model, 0.2)]
    assert proto.model == TrapModel(0.11, 0.03, "eyring-nabarro", 0.5, 0.02, 0.4)
