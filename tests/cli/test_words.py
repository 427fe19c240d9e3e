"""The command line's words: help that keeps its bracketed units, whole tables with units in the
headers, SI options of ``static`` and ``steady``, and ``stability`` refusing an ill-posed case."""

from __future__ import annotations

import json
import re

import pytest
from typer.testing import CliRunner

from dryfriction.cli import app

runner = CliRunner()


def invoke(*args: str):
    return runner.invoke(app, list(args))


@pytest.mark.parametrize(("command", "words"), [
    ("fit", ["V[um/s]"]),
    ("sweep", ["[sweep]", "{log = [a, b, n]}"]),
    ("steady", ["V [m/s]", "[a0/t0]", "a0 [m]", "t0 [s]"]),
    ("static", ["t_w [s]", "[t0]", "[F_el]"]),
    ("stability", ["[F_el t0^2/a0]", "[F_el t0/a0]"]),
])
def test_help_keeps_bracketed_words(command, words):
    # Rich help took "[...]" as markup and printed nothing in its place
    r = invoke(command, "--help")
    assert r.exit_code == 0, r.output
    text = " ".join(r.stdout.split())  # the help is re-wrapped to the terminal's width
    for w in words:
        assert w in text, (w, r.stdout)


def test_flags_are_not_shown_as_taking_a_value():
    r = invoke("steady", "--help")
    assert "<bool>" not in r.stdout
    assert re.search(r"^\s*--json\s+Machine", r.stdout, re.M), r.stdout


def test_stability_table_is_whole_at_80_columns_with_units():
    # CliRunner's output is no terminal: Rich's width is 80, where the table was cut to
    # "0.072482…" and the headers to "forward_…"
    r = invoke("stability", "--eps", "0.04", "--u", "0.01", "0.1", "--M", "10",
               "--eta", "0.1")
    assert r.exit_code == 0, r.output
    assert "…" not in r.stdout
    for header in ("u[a0/t0]", "K_c[F_el/a0]", "omega_c[rad/t0]", "dmu_d_du[F_el t0/a0]"):
        assert header in r.stdout
    as_json = json.loads(invoke("stability", "--eps", "0.04", "--u", "0.01", "0.1", "--M",
                                "10", "--eta", "0.1", "--json").stdout)
    for k in as_json["K_c"]:
        assert f"{k:.10g}" in r.stdout  # every digit printed


def test_theory_tables_say_the_units_of_their_inputs_and_their_notes():
    # a new user read "a0 = 1e-06, t0 = 0.01" without units, and a negative K_c_rsf without
    # a word on it
    r = invoke("steady", "--eps", "0.07", "--V", "3e-6", "--a0", "2e-6", "--t0", "0.04")
    assert r.exit_code == 0, r.output
    assert "a0 = 2e-06 m, t0 = 0.04 s" in r.stdout and "eps = 0.07," in r.stdout
    r = invoke("stability", "--eps", "0.083", "--u", "1.7", "--direct", "0.27")
    assert r.exit_code == 0, r.output
    assert "mass = 0.0 F_el t0^2/a0" in r.stdout
    assert "\nnote: K_c_rsf = 0 where the rate-and-state twin is stable at every " in r.stdout
    assert "u = 1.7 a0/t0: b - a - eta u = " in r.stdout
    assert json.loads(invoke("stability", "--eps", "0.083", "--u", "1.7", "--direct", "0.27",
                             "--json").stdout)["notes"][0].startswith("K_c_rsf = 0")


def test_stability_with_mass_and_no_damping_is_refused_as_ill_posed():
    r = invoke("stability", "--eps", "0.04", "--u", "0.1", "--M", "10")
    assert r.exit_code == 2
    assert "ill posed" in r.output and "--eta" in r.output and "K_c" in r.output
    assert invoke("stability", "--eps", "0.04", "--u", "0.1", "--M", "10", "--eta",
                  "0.1").exit_code == 0


def _json(*args: str) -> dict:
    r = invoke(*args, "--json")
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def test_static_in_seconds_is_the_reduced_result_at_t_w_over_t0_times_mu_el():
    # T = t_w/t0 = 1000 and 10000; F/W = mu_el F/F_el: a swapped or missing scale fails
    si = _json("static", "--eps", "0.04", "--t-w", "10", "100", "--t0", "0.01", "--mu-el", "0.4")
    red = _json("static", "--eps", "0.04", "--T", "1000", "10000")
    assert si["t_w"] == [10.0, 100.0] and si["t0"] == 0.01 and si["mu_el"] == 0.4
    assert si["mu_s"] == pytest.approx([0.4 * m for m in red["mu_s"]], rel=1e-12)
    plain = _json("static", "--eps", "0.04", "--t-w", "10", "--t0", "0.01")  # friction in F_el
    assert plain["mu_s"] == pytest.approx(red["mu_s"][:1], rel=1e-12)


def test_steady_in_m_per_s_is_the_reduced_result_at_v_t0_over_a0():
    # u = V t0/a0 = 1e-5 * 0.01 / 1e-6 = 0.1 and 1
    si = _json("steady", "--eps", "0.04", "--V", "1e-5", "1e-4", "--a0", "1e-6", "--t0", "0.01",
               "--mu-el", "0.5")
    red = _json("steady", "--eps", "0.04", "--u", "0.1", "1")
    assert si["mu_d"] == pytest.approx([0.5 * m for m in red["mu_d"]], rel=1e-12)
    r = invoke("steady", "--eps", "0.04", "--V", "1e-5", "--a0", "1e-6", "--t0", "0.01")
    assert "V[m/s]" in r.stdout and "mu_d[F_el]" in r.stdout
    r = invoke("steady", "--eps", "0.04", "--V", "1e-5", "--a0", "1e-6", "--t0", "0.01",
               "--mu-el", "0.5")
    assert "mu_d[F/W]" in r.stdout


@pytest.mark.parametrize(("args", "word"), [
    (["static", "--eps", "0.04", "--T", "1", "--t-w", "1", "--t0", "1"], "both"),
    (["static", "--eps", "0.04"], "neither"),
    (["static", "--eps", "0.04", "--t-w", "1"], "--t0"),
    (["static", "--eps", "0.04", "--T", "1", "--t0", "1"], "--t0"),
    (["static", "--eps", "0.04", "--T", "1", "--mu-el", "0.4"], "--mu-el"),
    (["static", "--eps", "0.04", "--t-w", "1", "--t0", "1", "--a0", "1"], "--a0"),
    (["static", "--eps", "0.04", "--t-w", "1", "--t0", "-1"], "t0"),
    (["steady", "--eps", "0.04", "--V", "1e-6", "--t0", "0.01"], "--a0"),
    (["steady", "--eps", "0.04", "--V", "-1e-6", "--t0", "0.01", "--a0", "1e-6"], "V"),
    (["steady", "--eps", "0.04", "--u", "1", "--a0", "1e-6"], "--a0"),
])
def test_si_option_mistakes_are_one_line(args, word):
    r = invoke(*args)
    assert r.exit_code == 2, r.output
    lines = r.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and word in lines[0], r.output
