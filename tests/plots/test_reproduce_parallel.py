"""``reproduce`` draws its figures in a pool of forked processes on more than one core (issue 12),
serially on one: the same files either way, in the same order, each drawn once, and the pool
gone when the command returns."""

from __future__ import annotations

import multiprocessing
import os
from pathlib import Path

import pytest

import dryfriction.plots.report as figures
from dryfriction.plots.style import new_figure

pytestmark = pytest.mark.skipif("fork" not in multiprocessing.get_all_start_methods(),
                                reason="the parallel path needs fork")


def _cheap_plots(log: Path) -> list:  # type: ignore[type-arg]
    """Three cheap figures, each noting which process drew it (in ``log``)."""
    def make(k: int):  # type: ignore[no-untyped-def]
        def draw():  # type: ignore[no-untyped-def]
            with open(log, "a") as fh:
                fh.write(f"{k} {os.getpid()}\n")
            fig, ax = new_figure()
            ax.plot([0, 1, 2], [k, 2 * k, k * k], label=f"figure {k}")
            ax.set_title(f"figure {k}")
            return fig
        return draw
    return [(f"fig{k}.png", make(k)) for k in range(1, 4)]


def _reproduce(tmp_path: Path, cores: int, monkeypatch: pytest.MonkeyPatch
               ) -> tuple[dict[str, bytes], list[str], list[tuple[int, int]]]:
    log = tmp_path / f"drawn_{cores}.txt"
    monkeypatch.setattr(figures, "_plots", lambda: _cheap_plots(log))
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(cores)), raising=False)
    monkeypatch.setattr(figures, "compute_summary", lambda: {"C": 1.0})
    monkeypatch.setattr(figures, "report_html", lambda tmp, summary, images, panels: repr(
        [(k, v[0], v[1], len(v[2])) for k, v in images.items()]))
    steps: list[str] = []
    out = tmp_path / f"out_{cores}"
    figures.reproduce(out, progress=lambda done, total, what: steps.append(what))
    files = {p.name: p.read_bytes() for p in out.iterdir() if p.suffix in (".png", ".html")}
    drawn = [tuple(map(int, line.split())) for line in log.read_text().splitlines()]
    return files, steps, drawn  # type: ignore[return-value]


def test_parallel_figures_are_the_serial_ones(tmp_path: Path,
                                              monkeypatch: pytest.MonkeyPatch) -> None:
    serial, serial_steps, serial_drawn = _reproduce(tmp_path, 1, monkeypatch)
    parallel, parallel_steps, parallel_drawn = _reproduce(tmp_path, 2, monkeypatch)
    assert {pid for _, pid in serial_drawn} == {os.getpid()}  # one core: no fork
    assert sorted(k for k, _ in parallel_drawn) == [1, 2, 3]  # each figure drawn once...
    assert os.getpid() not in {pid for _, pid in parallel_drawn}  # ...by the pool
    assert parallel == serial  # byte for byte, report included (same images, same order)
    assert parallel_steps == serial_steps
    assert sorted(serial) == ["fig1.png", "fig2.png", "fig3.png", "report.html"]
    assert multiprocessing.active_children() == []  # the pool ended with the command


def test_a_failing_figure_in_the_pool_fails_the_command_whole(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    def boom():  # type: ignore[no-untyped-def]
        raise ValueError("figure 2 cannot be drawn")

    plots = _cheap_plots(tmp_path / "log.txt")
    plots[1] = ("fig2.png", boom)
    monkeypatch.setattr(figures, "_plots", lambda: plots)
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    monkeypatch.setattr(figures, "compute_summary", lambda: {"C": 1.0})
    with pytest.raises(ValueError, match="figure 2 cannot be drawn"):
        figures.reproduce(tmp_path / "out")
    assert not (tmp_path / "out").exists()
    assert multiprocessing.active_children() == []


def test_main_restores_the_signal_handlers() -> None:
    """main() in a process that goes on (a test, a notebook) leaves no handler behind: a test
    that called it left SIGTERM -> SystemExit in the test process, and the figure pool's
    workers forked later inherited it; CI then hung once in the pool's terminate (the workers
    now also reset SIGTERM themselves: plots.report._figure_worker)."""
    import signal

    from dryfriction.cli import main

    before = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    assert main(["--version"]) == 0
    assert (signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)) == before
