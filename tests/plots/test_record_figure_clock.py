"""record.png on a record whose clock does not start at 0 (plots/record.py): the measured
velocity and the drawn load program on one time axis, from the first
sample. Each test names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import numpy as np
from matplotlib.colors import to_rgba

from dryfriction.plots.record import plot_record
from dryfriction.records.lab import parse_segments, read_record

PROGRAM = "0:1.3e-06,12.5:4.1e-06,21:0,26.5:6e-07"


def test_program_and_velocity_from_the_first_sample(tmp_path) -> None:  # type: ignore[no-untyped-def]
    # mistake (blind set 6, plot_record_program_no_t0): the program's segments drawn at record
    # time while the velocity and the shading are drawn from the first sample, so on a record
    # starting at t = 1734.2 s the red lines sit 1734 s to the right, off the panel
    t = 1734.2 + 0.05 * np.arange(800)
    rel = t - t[0]
    v = np.select([rel < 12.5, rel < 21.0, rel < 26.5], [1.3e-6, 4.1e-6, 0.0], 6e-7)
    x = np.concatenate([[0.0], np.cumsum(v[:-1] * 0.05)])
    path = tmp_path / "clock.txt"
    path.write_text("Time(s)\tDispl(um)\tFriction\n" + "".join(
        f"{a:.4f}\t{b * 1e6:.9f}\t{0.61 + 1e-3 * np.sin(a):.6f}\n" for a, b in zip(t, x,
                                                                                 strict=True)))
    rec = read_record(path)
    segs = parse_segments(PROGRAM, rec)
    fig, info = plot_record(rec, segs, None, given=True)
    ax = fig.axes[info.panels.index("velocity")]
    red = [ln for ln in ax.get_lines()
           if ln.get_xdata().size == 2 and to_rgba(ln.get_color()) == to_rgba("C3")]
    assert len(red) == len(segs)
    for ln, s in zip(red, segs, strict=True):
        np.testing.assert_allclose(ln.get_xdata(), [s.t_start - t[0], s.t_end - t[0]],
                                   atol=1e-9)
        np.testing.assert_allclose(ln.get_ydata(), [s.velocity * 1e6] * 2, rtol=1e-12)
    # the measured velocity on the same axis: within the record's span from 0
    grey = max(ax.get_lines(), key=lambda ln: np.asarray(ln.get_xdata()).size)
    xs = np.asarray(grey.get_xdata())
    assert xs.min() >= 0.0 and xs.max() <= rel[-1] + 1e-9
    fig.clf()
