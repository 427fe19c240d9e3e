"""Atomic writes: whole or nothing, ordinary permissions."""

import os
import stat

import pytest

from dryfriction.io import atomic_write_text, output_directory, write_csv


def test_permissions_follow_umask(tmp_path):
    old = os.umask(0o022)
    try:
        f = atomic_write_text(tmp_path / "a.txt", "x")
        assert stat.S_IMODE(f.stat().st_mode) == 0o644
        with output_directory(tmp_path / "res") as d:
            (d / "b.txt").write_text("y")
        assert stat.S_IMODE((tmp_path / "res").stat().st_mode) == 0o755
    finally:
        os.umask(old)


def test_output_directory_whole_or_nothing(tmp_path):
    out = tmp_path / "res"
    with output_directory(out) as d:
        (d / "one").write_text("1")
    with pytest.raises(RuntimeError), output_directory(out) as d:
        (d / "two").write_text("2")
        raise RuntimeError("boom")
    assert sorted(p.name for p in out.iterdir()) == ["one"]
    assert [p.name for p in tmp_path.iterdir()] == ["res"]  # no temporary leftovers


def test_csv_rejects_ragged_columns(tmp_path):
    with pytest.raises(ValueError, match="different lengths"):
        write_csv(tmp_path / "x.csv", {"a": [1.0, 2.0], "b": [1.0]})
    assert not (tmp_path / "x.csv").exists()


def test_ctrl_c_during_the_swap_is_delivered_after_it(tmp_path, monkeypatch):
    # a SIGINT arriving between "old results aside" and "new results in" is held back
    import signal

    import dryfriction.io as dio

    out = tmp_path / "res"
    with output_directory(out) as d:
        (d / "old").write_text("old")
    real_replace = os.replace
    calls = []

    def replace(a, b):
        calls.append(b)
        real_replace(a, b)
        if len(calls) == 1:  # just after moving the old results aside
            signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(dio.os, "replace", replace)
    with pytest.raises(KeyboardInterrupt), output_directory(out) as d:
        (d / "new").write_text("new")
    assert sorted(p.name for p in out.iterdir()) == ["new"]
