"""The sweep commands' lines built directly (issue 25): the command that resumes a sweep (the
same options, shell-quoted, the default connect timeout left out, the flags only when set)
and the one line for failed points (all of them, or how many of how many, the first error)."""

from __future__ import annotations

import shlex
from types import SimpleNamespace

import numpy as np
import pytest
import typer

from dryfriction.cli import sweeps as cli_sweeps


def test_the_resume_command_repeats_the_options_given() -> None:
    line = cli_sweeps._resume_command("sweep", "my protocol.toml", "out dir", None, 3, True,
                                      False, 10.0)
    assert shlex.split(line) == ["dryfriction", "sweep", "my protocol.toml", "--out", "out dir",
                                 "--workers", "3", "--yes"]
    line = cli_sweeps._resume_command("phase-diagram", "p.toml", "o", "tcp://h:8786", None,
                                      False, True, 2.5)
    assert shlex.split(line) == ["dryfriction", "phase-diagram", "p.toml", "--out", "o",
                                 "--scheduler", "tcp://h:8786", "--connect-timeout", "2.5",
                                 "--linear"]


class _Dataset:
    def __init__(self, err: np.ndarray) -> None:
        self.attrs = {"n_failed": int(sum(bool(e) for e in err.ravel()))}
        self._err = SimpleNamespace(values=err, size=err.size)

    def __getitem__(self, name: str) -> SimpleNamespace:
        assert name == "error"
        return self._err


def test_failed_points_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    cli_sweeps._fail_if_points_failed(_Dataset(np.array([["", ""], ["", ""]], object)), "o")
    with pytest.raises(typer.Exit) as exc:
        cli_sweeps._fail_if_points_failed(
            _Dataset(np.array([["", "K < 0"], ["", "too long"]], object)), "o")
    assert exc.value.exit_code == 1
    err = " ".join(capsys.readouterr().err.split())
    assert "2 of 4 points failed (first: K < 0)" in err and "o/sweep.nc" in err
    with pytest.raises(typer.Exit):
        cli_sweeps._fail_if_points_failed(
            _Dataset(np.array([["a", "b"], ["c", "d"]], object)), "o")
    assert "all 4 points failed (first: a)" in " ".join(capsys.readouterr().err.split())
