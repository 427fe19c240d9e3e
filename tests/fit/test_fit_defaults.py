"""The defaults a user gets without saying (fit/): the record fit's trap model (module
docstring of fit/cvsteps.py: a fitted spring with a trend, sampled every 0.01 a0, 30
evaluations, steady tails skipped), the rate-and-state model's (kinematic, ageing, no trend,
steady start), and ``fit_steps_laws``' (the ageing law, the automatic initial state, a free
stiffness per step), each read from what the call does, not from the signature."""

from __future__ import annotations

import math

import numpy as np

from dryfriction.fit import lawchoice
from dryfriction.fit.cvsteps import RECORD_DIFF_STEP, RECORD_MAX_NFEV, record_cv_model
from dryfriction.fit.models import RSFModel
from dryfriction.records.data import SeriesData
from dryfriction.theory.model import TRAPS_PER_A0_COARSE, TrapModel


def test_record_cv_model_defaults() -> None:
    m = record_cv_model()
    assert m.trap == TrapModel()
    assert (m.stiffness, m.trend, m.sample_slip, m.steady_tail) == ("fit", True, 0.01, True)
    assert (m.v_ref, m.traps_per_a0) == (1e-6, TRAPS_PER_A0_COARSE)
    assert (m.max_nfev, RECORD_MAX_NFEV) == (30, 30)
    assert (m.diff_step, RECORD_DIFF_STEP) == (0.03, 0.03)
    assert m.progress is None


def test_rsf_model_defaults() -> None:
    assert RSFModel().options() == {"v0": None, "state_law": "ageing", "stiffness": math.inf,
                                    "damping": 0.0, "regularized": False, "trend": False}


def test_fit_steps_laws_defaults(monkeypatch) -> None:
    # mistakes: "auto" as the default law (five fits a step), a steady start by default, one
    # machine ("record") by default
    seen = []

    def run(record, windows, segments, stiffness, **kw):
        seen.append((stiffness, kw))
        return "result"

    free = []
    monkeypatch.setattr(lawchoice, "_run", run)
    monkeypatch.setattr(lawchoice, "_free_start", lambda *a: free.append(a[4:6]))
    t = 2.0 + 0.5 * np.arange(40)
    d = SeriesData(t, 1e-6 + 0.0 * t, 0.6 + 0.0 * t)
    assert lawchoice.fit_steps_laws(d, ["w"]) == "result"
    (stiffness, kw), = seen
    assert stiffness == "fit" and kw == {"law": "ageing", "initial": "steady"}
    assert free == [("fit", "ageing")]  # initial "auto": the flagged steps refitted free
