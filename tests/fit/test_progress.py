"""Progress of long jobs (issue 15): the fit's evaluation count and estimate, the CLI's lines
on standard error with an estimate of the time left, standard output left clean."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from dryfriction.cli import app, common
from dryfriction.fit import CVModel, fit
from dryfriction.records.data import SeriesData

runner = CliRunner()


def _toy_series(values, data):  # type: ignore[no-untyped-def]
    """A cheap stand-in for the trap-model series: the steady level at each load velocity,
    counting its calls (each one is an evaluation of the model)."""
    _toy_series.calls += 1  # type: ignore[attr-defined]
    u = data.v_load * values["t0"] / values["a0"]
    return values["mu_el"] * (1.0 - values["eps"] * np.log(u))


def _series(n: int = 60, seed: int = 0) -> SeriesData:
    true = {"eps": 0.03, "t0": 0.01, "a0": 1e-6, "mu_el": 0.5}
    t = np.linspace(0.0, 1.0, n)
    v = np.where(t < 0.5, 1e-4, 1e-3)
    _toy_series.calls = 0  # type: ignore[attr-defined]
    mu = _toy_series(true, SeriesData(t, v, np.zeros(n)))
    rng = np.random.default_rng(seed)
    return SeriesData(t, v, mu + rng.normal(0.0, 1e-3, n))


def test_fit_progress_counts_every_evaluation_and_ends_at_its_estimate() -> None:
    """``done`` is the number of model evaluations (one per call, none skipped or counted
    twice), never beyond the estimated total; the stages are named; the last report is
    ``done == total``. Catches a tracker that counts solves instead of evaluations, an
    estimate below the work already done, or a missing final report."""
    d = _series()
    calls: list[tuple[int, int, str]] = []
    _toy_series.calls = 0  # type: ignore[attr-defined]
    r = fit(d, CVModel(series=_toy_series), fix={"a0": 1e-6}, profile=True,
            progress=lambda n, tot, what: calls.append((n, tot, what)))
    assert r.success
    done = [c[0] for c in calls]
    assert done[:-1] == list(range(1, len(done)))  # one report per evaluation, then the end
    assert done[-1] == _toy_series.calls  # type: ignore[attr-defined]
    assert all(n <= tot for n, tot, _ in calls)
    assert calls[-1][:2] == (done[-1], done[-1])
    whats = {w for _, _, w in calls}
    assert any(w.startswith("start 1 of") for w in whats)
    assert {f"profile of {k} ({i + 1} of 3)" for i, k in enumerate(r.free)} <= whats


def test_fit_progress_counts_the_separate_fits_of_a_joint_fit() -> None:
    """The consistency test fits each data set alone: their evaluations continue the count,
    one each (a nested fit's final report is no evaluation), under the data set's name."""
    from dryfriction.records.data import read_csv

    calls = [0]

    class Counting(CVModel):
        def predict(self, *args, **kwargs):  # type: ignore[no-untyped-def]
            # at the data (residuals), not at the three points of the derived slopes
            calls[0] += len(args) + len(kwargs) == 2
            return super().predict(*args, **kwargs)

    data = Path(__file__).parents[2] / "examples" / "data"
    ds = [read_csv(data / "synthetic_static_paper.csv"),
          read_csv(data / "synthetic_steady_paper.csv")]
    seen: list[tuple[int, int, str]] = []
    fit(ds, Counting(), profile=False, progress=lambda n, tot, w: seen.append((n, tot, w)))
    done = [c[0] for c in seen]
    # one prediction per data set and evaluation of the joint fit, one per separate one
    assert done[:-1] == list(range(1, len(done)))
    alone = sum(1 for _, _, w in seen[:-1] if w.endswith(" alone"))
    assert calls[0] == 2 * (done[-1] - alone) + alone
    assert {w for _, _, w in seen if w.endswith(" alone")} == {
        "synthetic_static_paper.csv alone", "synthetic_steady_paper.csv alone"}


def test_fit_progress_estimate_is_close_once_a_profile_has_run() -> None:
    """After the first profile walk the estimated total is within a factor 2 of the real one
    (the remaining profiles cost about as much): an estimate that ignored the profiles (the
    starts' count only) would be several times too small."""
    d = _series(seed=1)
    calls: list[tuple[int, int, str]] = []
    r = fit(d, CVModel(series=_toy_series), fix={"a0": 1e-6}, profile=True,
            progress=lambda n, tot, what: calls.append((n, tot, what)))
    real = calls[-1][0]
    second = next(tot for _, tot, w in calls if w.startswith(f"profile of {r.free[1]}"))
    assert real / 2 <= second <= 2 * real, (second, real)


@pytest.mark.slow
def test_cli_fit_prints_progress_with_time_left_on_stderr_and_clean_json(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The joint trap-model fit of docs/tutorials/lab-record.md (no terminal: plain lines) says what
    it is doing, how many evaluations of about how many, and the time left, on standard error only:
    standard output is the --json report and nothing else. (A time-series fit takes minutes; the
    lines come from the same code, here every update instead of one per PROGRESS_EVERY_S.)"""
    monkeypatch.setattr(common, "PROGRESS_EVERY_S", 0.0)
    data = Path(__file__).parents[2] / "examples" / "data"
    r = runner.invoke(app, ["fit", str(data / "synthetic_static_paper.csv"),
                            str(data / "synthetic_steady_paper.csv"), "--model", "cv",
                            "--out", str(tmp_path / "o"), "--no-compare", "--json",
                            "--no-figure"])
    assert r.exit_code == 0, r.output
    report = json.loads(r.stdout)  # nothing but the JSON on standard output
    assert report["model"] == "cv"
    lines = [ln for ln in r.stderr.splitlines() if ln.startswith("fit: ")]
    assert len(lines) >= 20, r.stderr
    assert all("evaluations" in ln and "elapsed" in ln for ln in lines)
    assert any("cv start 1 of" in ln for ln in lines), lines
    assert any("cv profile of t0" in ln for ln in lines), lines
    assert any("s left" in ln for ln in lines), lines


def test_progress_is_silent_for_a_quick_job_without_a_terminal(
        monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    """Without a terminal, nothing before PROGRESS_EVERY_S: a quick job's stderr stays empty
    (a helper that printed every update would flood a log)."""
    monkeypatch.setattr(common, "PROGRESS_EVERY_S", 3600.0)
    with common.progress_bar("job", 10, "steps") as update:
        for i in range(10):
            update(i + 1)
    captured = capsys.readouterr()
    assert captured.err == "" and captured.out == ""


def test_progress_bar_draws_on_a_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    """On a terminal the Rich bar is drawn: it was given the lazy console stand-in, which is
    no context manager, and every command's bar raised TypeError (seen running compare under
    a terminal)."""
    import io

    buf = io.StringIO()
    monkeypatch.setattr(common, "err", common._Console(file=buf, force_terminal=True,
                                                       width=100))
    with common.progress_bar("job", 10, "steps", delay=0.0) as update:
        for i in range(10):
            update(i + 1, what="stage")
    assert "job: stage" in buf.getvalue()
