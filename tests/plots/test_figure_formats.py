"""``--format png|pdf|svg`` and ``--dpi`` on the commands that draw: the file has the format's
signature and the asked resolution, and a bad value is one line before any work."""

from __future__ import annotations

import io
import struct
from pathlib import Path

import pytest
from typer.testing import CliRunner

from dryfriction.cli import app
from dryfriction.plots import report
from dryfriction.plots.style import RUN_WIDTH, new_figure, save_figure
from dryfriction.validation import check_figure_format

PROTOCOL = """\
[model]
alpha = 0.13
eps = 0.04
[ensemble]
traps_per_a0 = 50
initial = "steady"
initial_velocity = 1.0
[drive]
kind = "velocity"
segments = [{velocity = 1.0, slip = 0.5}, {velocity = 0.0, duration = 10.0},
            {velocity = 1.0, slip = 0.5}]
[output]
every_slip = 0.01
"""

MAGIC = {"png": b"\x89PNG\r\n\x1a\n", "pdf": b"%PDF-", "svg": b"<?xml"}


def _png_size(data: bytes) -> tuple[int, int]:
    return struct.unpack(">II", data[16:24])


@pytest.fixture
def protocol(tmp_path: Path) -> Path:
    p = tmp_path / "p.toml"
    p.write_text(PROTOCOL)
    return p


@pytest.mark.slow
@pytest.mark.parametrize("fmt", ["png", "pdf", "svg"])
def test_simulate_writes_its_figure_in_the_asked_format(tmp_path, protocol, fmt):
    out = tmp_path / "run"
    r = CliRunner().invoke(app, ["simulate", str(protocol), "--out", str(out), "--format", fmt])
    assert r.exit_code == 0, r.output
    figs = sorted(p.name for p in out.glob("timeseries.*") if p.suffix != ".csv")
    assert figs == [f"timeseries.{fmt}"]
    assert (out / f"timeseries.{fmt}").read_bytes().startswith(MAGIC[fmt])


def test_dpi_sets_the_png_resolution(tmp_path, protocol):
    out = tmp_path / "run"
    r = CliRunner().invoke(app, ["simulate", str(protocol), "--out", str(out), "--dpi", "300"])
    assert r.exit_code == 0, r.output
    width, _ = _png_size((out / "timeseries.png").read_bytes())
    # the figure is RUN_WIDTH + 3.5 inches wide (two columns)
    assert width == round((RUN_WIDTH + 3.5) * 300)


@pytest.mark.parametrize(("command", "args"), [
    ("simulate", ["--out", "{out}"]),
    ("compare", ["--out", "{out}"]),
    ("reproduce", ["--out", "{out}"]),
    ("rsf", ["--out", "{out}"]),
])
@pytest.mark.parametrize(("option", "value", "word"), [
    ("--format", "jpg", "--format 'jpg' is not allowed: choose one of png, pdf, svg"),
    ("--dpi", "10", "--dpi 10 is out of range"),
    ("--dpi", "5000", "--dpi 5000 is out of range"),
])
def test_bad_format_or_dpi_is_one_line_and_nothing_written(tmp_path, protocol, command, args,
                                                          option, value, word):
    out = tmp_path / "o"
    argv = [command] + ([str(protocol)] if command in ("simulate", "compare") else [])
    argv += [a.format(out=out) for a in args] + [option, value]
    r = CliRunner().invoke(app, argv)
    assert r.exit_code == 2, r.output
    lines = r.output.strip().splitlines()
    assert len(lines) == 1 and word in lines[0], r.output
    assert not out.exists()


def test_fit_and_phase_diagram_take_the_options_too():
    for command in ("fit", "phase-diagram"):
        text = CliRunner().invoke(app, [command, "--help"]).stdout
        assert "--format" in text and "--dpi" in text, command


def test_check_figure_format_defaults_and_limits():
    assert check_figure_format("svg") == ("svg", None)
    assert check_figure_format("png", 300.0) == ("png", 300)
    with pytest.raises(ValueError, match="whole number"):
        check_figure_format("png", 150.5)


def test_vector_files_are_the_same_bytes_when_drawn_twice():
    # no creation date inside: a re-run that changed nothing writes the same file
    def draw(fmt: str) -> bytes:
        fig, ax = new_figure()
        ax.plot([0, 1], [1, 0])
        buf = io.BytesIO()
        save_figure(fig, buf, fmt)
        return buf.getvalue()

    for fmt in ("pdf", "svg"):
        assert draw(fmt) == draw(fmt)


def test_report_embeds_svg_as_svg_and_pdf_as_png(tmp_path):
    summary = report.compute_summary()
    names = (*report.FIGURE_FILES, *report.EXTRA_FILES)
    svg = {n: (n.replace(".png", ".svg"), "image/svg+xml", b"<?xml") for n in names}
    page = report.report_html(tmp_path, summary, {"version": "x", "commit": "", "date": "d"},
                              images=svg)
    assert page.count('src="data:image/svg+xml;base64,') == len(names)
    assert 'alt="fig6.svg"' in page


def test_png_files_at_the_packages_compression_by_either_writer():
    """save_figure and save_png write the same PNG bytes, at PNG_COMPRESSION (a figure written
    by Pillow at that zlib level, not at its default of 6), and decode to the same pixels as
    at level 6 (lossless)."""
    import numpy as np
    from matplotlib.image import imread

    from dryfriction.plots.style import DPI, PNG_COMPRESSION, save_png

    fig, ax = new_figure()
    ax.plot([0.3, 1.7, 2.2], [1.1, -0.4, 0.9], marker="o")
    a, b, ref = io.BytesIO(), io.BytesIO(), io.BytesIO()
    save_figure(fig, a, "png")
    save_png(fig, b)
    fig.savefig(ref, format="png", dpi=DPI, pil_kwargs={"compress_level": PNG_COMPRESSION})
    assert a.getvalue() == b.getvalue() == ref.getvalue()
    six = io.BytesIO()
    fig.savefig(six, format="png", dpi=DPI)
    assert six.getvalue() != a.getvalue()  # another level, other bytes
    a.seek(0)
    six.seek(0)
    assert np.array_equal(imread(a), imread(six))
