"""fixE item 4 (a second new user's trial, problem 18): the fit's refusals of fixed and start
values name what the caller typed, ``fix['t0']`` or ``start['eps']`` in Python and ``--fix
t0`` on the command line, with the allowed range; a start outside the fit's range (it was
clipped onto the bound in silence: ``start={"eps": 5}`` ran) or given for a fixed parameter
is refused in one line, before any work."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dryfriction.cli import main
from dryfriction.fit import fit
from dryfriction.records.data import StaticData, SteadyData

TW = np.geomspace(2.0, 3e4, 9)


def _static() -> StaticData:
    return StaticData(TW, 0.61 + 0.0047 * np.log(TW / 3.0), None, "static.csv")


def _steady() -> SteadyData:
    v = np.geomspace(1e-7, 1e-4, 8)
    return SteadyData(v, 0.62 - 0.003 * np.log(v / 1e-6), None, "steady.csv")


@pytest.mark.parametrize("kwargs, words", [
    ({"fix": {"eps": 5.0}}, "fix['eps'] = 5 is out of range: allowed finite and > 1e-06 and "
     "<= 1"),
    ({"fix": {"t0": -1.0}}, "fix['t0'] [s] = -1 is out of range: allowed finite and > 1e-12 "
     "and <= 1e+09"),
    ({"start": {"eps": 5.0}}, "start['eps'] = 5 is out of range: allowed finite and >= 1e-06 "
     "and <= 1"),
    ({"start": {"t0": -1.0}}, "start['t0'] [s] = -1 is out of range: allowed finite and >= "
     "1e-12 and <= 1e+09"),
    ({"start": {"mu_el": float("nan")}}, "start['mu_el'] = nan is out of range: allowed "
     "finite and >= 0.001 and <= 10"),
    ({"start": {"zz": 1.0}}, "start['zz'] names an unknown parameter for model cv with "
     "static data: the parameters are eps, t0, mu_el"),
    ({"fix": {"t0": 2.0}, "start": {"t0": 3.0}}, "start['t0'] is given for a parameter fix "
     "holds at 2 s: drop one of them"),
])
def test_python_refusals_name_the_keyword_and_the_range(kwargs: dict, words: str,
                                                          monkeypatch: pytest.MonkeyPatch
                                                          ) -> None:
    """Mistakes: the command line's --fix in Python (the user's report), a start clipped in
    silence, a fixed eps = 5 refused by the model as 'eps = 5' during the fit."""
    import dryfriction.fit.engine as engine

    def no_work(*a: object, **k: object) -> None:
        raise AssertionError("the fit started before the refusal")

    monkeypatch.setattr(engine, "_best_of_starts", no_work)
    with pytest.raises(ValueError) as exc:
        fit(_static(), "cv", profile=False, **kwargs)
    assert str(exc.value) == words
    assert "--" not in str(exc.value)


def test_a_start_on_its_bound_and_inside_is_taken() -> None:
    # the range is closed for a start (the search may start on its bound)
    r = fit(_steady(), "rsf", v0=1e-6, start={"a_minus_b": -0.003, "mu0": 5.0},
            profile=False)
    assert r.success and r["a_minus_b"].value == pytest.approx(-0.003, abs=1e-4)


def test_the_command_line_says_its_option(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    # mistake: the library's fix['t0'] shown to a command-line user, who typed --fix t0=-1
    data = tmp_path / "s.csv"
    data.write_text("t_w[s],mu_s\n" + "".join(f"{a:g},{0.61 + 0.0047 * np.log(a / 3.0):.6f}\n"
                                              for a in TW))
    capsys.readouterr()
    for item, words in (("t0=-1", "error: --fix t0 [s] = -1 is out of range: allowed finite "
                                  "and > 1e-12 and <= 1e+09"),
                        ("eps=5", "error: --fix eps = 5 is out of range"),
                        ("zz=1", "error: --fix zz names an unknown parameter")):
        assert main(["fit", str(data), "--out", str(tmp_path / "o"), "--fix", item]) == 2
        err = capsys.readouterr().err
        assert err.startswith(words) and "fix[" not in err, err
        assert not (tmp_path / "o").exists()
