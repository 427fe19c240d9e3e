"""app.fit's dispatch called directly (issue 25), the two fits replaced by recorders (what is
checked is the routing, before any work): a record goes to the record fit with its own
defaults (rsf, its one machine, a trend), the project's CSV files to the data fit with theirs
(cv); each option of the other kind of input refused in one line naming the flag."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

import dryfriction.app.fitting as fitting
import dryfriction.app.records as records
from dryfriction import app

ROOT = Path(__file__).resolve().parents[2]
CSV = ROOT / "examples" / "data" / "synthetic_static_paper.csv"


@pytest.fixture
def calls(monkeypatch: pytest.MonkeyPatch) -> list[tuple[str, Any, dict[str, Any]]]:
    seen: list[tuple[str, Any, dict[str, Any]]] = []
    monkeypatch.setattr(records, "fit_record",
                        lambda path, out, **kw: seen.append(("record", path, kw)))
    monkeypatch.setattr(fitting, "fit_data",
                        lambda paths, out, **kw: seen.append(("data", paths, kw)))
    return seen


def _record(tmp_path: Path) -> Path:
    p = tmp_path / "r.txt"
    p.write_text("Time (s)\tLP_disp (um)\tFriction\n" +
                 "".join(f"{0.1 * i:.1f}\t{0.3 * i:.2f}\t0.6\n" for i in range(30)))
    return p


def test_a_record_goes_to_the_record_fit_with_its_defaults(tmp_path: Path, calls) -> None:  # type: ignore[no-untyped-def]
    rec = _record(tmp_path)
    app.fit(rec, tmp_path / "o")
    kind, path, kw = calls[-1]
    assert kind == "record" and path == rec
    assert kw["model"] == "rsf" and kw["stiffness"] == "record" and kw["trend"] is True
    assert kw["law"] == "ageing" and kw["initial"] == "auto" and kw["drive"] == "measured"
    assert kw["errors"] == "hac" and kw["run_cv"] is False and kw["joint"] is False
    app.fit(rec, tmp_path / "o", stiffness="2.5e4", trend=False, state_law="auto")
    kw = calls[-1][2]
    assert kw["stiffness"] == 2.5e4 and kw["trend"] is False and kw["law"] == "auto"


def test_csv_files_go_to_the_data_fit_with_theirs(tmp_path: Path, calls) -> None:  # type: ignore[no-untyped-def]
    app.fit([CSV], tmp_path / "o", alpha=0.21)
    kind, paths, kw = calls[-1]
    assert kind == "data" and paths == [CSV]
    assert kw["model"] == "cv" and kw["alpha"] == 0.21
    assert not set(kw) & {"columns", "segments", "joint", "run_cv", "errors", "drive",
                          "initial_state"}


@pytest.mark.parametrize("name, value, flag", [
    ("columns", "time=t_w", "--columns"), ("segments", "0:1e-6", "--segments"),
    ("joint", True, "--joint"), ("run_cv", True, "--run-cv"), ("errors", "white", "--errors"),
    ("drive", "program", "--drive"), ("initial_state", "free", "--initial-state"),
])
def test_a_records_option_is_refused_for_csv_files(tmp_path: Path, calls, name: str,  # type: ignore[no-untyped-def]
                                                   value: Any, flag: str) -> None:
    with pytest.raises(ValueError, match=f"^{flag} is for a laboratory record, not the "
                                         "project's CSV files$"):
        app.fit(CSV, tmp_path / "o", **{name: value})
    assert calls == [] and not (tmp_path / "o").exists()


@pytest.mark.parametrize("name, value, flag", [("fix", ["a=0.01"], "--fix"),
                                               ("v0", 1e-6, "--v0")])
def test_a_csv_option_is_refused_for_a_record(tmp_path: Path, calls, name: str, value: Any,  # type: ignore[no-untyped-def]
                                              flag: str) -> None:
    with pytest.raises(ValueError, match=f"^{flag} is for the project's CSV files, not a "
                                         "laboratory record"):
        app.fit(_record(tmp_path), tmp_path / "o", **{name: value})
    assert calls == []
    with pytest.raises(TypeError, match="unknown option"):
        app.fit(CSV, tmp_path / "o", stifness=1.0)


class _Stop(Exception):
    pass


@pytest.mark.parametrize("given, expect", [(None, float("inf")), ("fit", "fit"),
                                           ("3.3e4", 3.3e4)])
def test_csv_series_fit_machine_defaults_to_kinematic(tmp_path: Path, given: Any,
                                                       expect: Any,
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    # mistake (blind set 5, app_csv_stiffness_default_fit): without --stiffness the project's
    # CSV fits fit a machine stiffness (a spring) instead of the kinematic machine (inf) the
    # help promises; the fit itself is replaced by a recorder of what it was asked
    import dryfriction.fit as fit_pkg

    seen: dict[str, Any] = {}

    def record_call(datasets: Any, model: Any, **kw: Any) -> None:
        seen.update(kw)
        raise _Stop

    monkeypatch.setattr(fit_pkg, "fit", record_call)
    opts = {} if given is None else {"stiffness": given}
    series = ROOT / "examples" / "data" / "synthetic_velocity_step_rsf.csv"  # a machine's data
    with pytest.raises(_Stop):
        fitting.fit_data([series], tmp_path / "o", model="rsf", **opts)
    assert seen["stiffness"] == expect
