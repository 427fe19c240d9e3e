"""summary.json's slip and path_length (dryfriction.results.summarize) on a run that slides
back: the net slip x[-1] - x[0] and the sum of |dx|, computed here from the run's own samples
and from the program's legs. Written for the survivors of the second blind mutant review
(benchmarks/blind_mutants2.py: results_path_length_abs, |net slip| for the path)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.program import Segment
from dryfriction.rsf.driving import simulate
from dryfriction.rsf.law import RateState
from dryfriction.rsf.spring import RSFInitial, RSFOutput, SpringSlider


def test_path_length_counts_the_slip_back() -> None:
    """A rigid (kinematic) machine, 37 um forward at 2.3 um/s then 11 um back at 1.1 um/s:
    path 48 um, net slip 26 um (the regularised law runs backwards)."""
    fwd, back = 37e-6, 11e-6
    p = RateState(0.0113, 0.0157, 23e-6, 0.583, 1.3e-6, regularized=True)
    t_turn, t_end = fwd / 2.3e-6, fwd / 2.3e-6 + back / 1.1e-6
    te = np.union1d(np.linspace(0.0, t_end, 41), [t_turn])  # the turn is sampled
    res = simulate(p, SpringSlider([Segment(2.3e-6, slip=fwd), Segment(-1.1e-6, slip=back)]),
                   RSFInitial(v=2.3e-6), output=RSFOutput(t_eval=te, rtol=1e-9))
    s = res.summary()
    x = np.asarray(res.x)
    assert s["path_length"] == pytest.approx(float(np.sum(np.abs(np.diff(x)))), rel=1e-12)
    assert s["path_length"] == pytest.approx(fwd + back, rel=1e-6)
    assert s["slip"] == pytest.approx(fwd - back, rel=1e-6)
