"""The workflows of the command line as library functions: each takes the same
options as its command, with the same defaults (:mod:`.options`), writes the same files, refuses
the same input in the same one line (``ValueError`` naming the option as typed), and returns a
result object; :mod:`dryfriction.cli` parses, calls one of them and prints.

* :func:`simulate` - a protocol file (``dryfriction simulate``);
* :func:`compare` - a trap-model protocol beside its rate-and-state twin (``compare``);
* :func:`reproduce` - the paper's figures, data, summary and report (``reproduce``);
* :func:`sweep`, :func:`phase_diagram` - a protocol's ``[sweep]`` grid on Dask (``sweep``,
  ``phase-diagram``);
* :func:`fit` - measured friction: the project's CSV files (:func:`fit_data`) or one laboratory
  record (:func:`fit_record`) (``fit``);
* :func:`rsf` - rate-and-state through a step, slide-hold-slide or stick-slip (``rsf``);
* :func:`record` - a laboratory record as read, its load program and steps (``record``);
* :func:`bifurcation` - the Hopf point of steady sliding by normal form (``bifurcation``);
* :func:`trap`, :func:`static`, :func:`steady`, :func:`stability` - the closed-form theory
  (the commands of the same names), returning a :class:`TableOutcome`.

Example::

    from dryfriction import app
    run = app.simulate("examples/rsf_velocity_step.toml", "out", figure=False)
    run.summary["mu_final"], run.files

The modules are named apart from the functions (``ratestate`` holds :func:`rsf`, ``reading``
:func:`record`, ``hopf`` :func:`bifurcation`): importing a submodule sets it as an attribute of
the package, which would hide a function of the same name.

Names are loaded on first use: ``import dryfriction.app`` imports nothing heavy.
"""

from __future__ import annotations

import importlib
from typing import Any

_WHERE = {"simulate": "runs", "compare": "runs", "reproduce": "runs", "RunOutcome": "outcome",
          "FitOutcome": "outcome", "fit": "fitting", "fit_data": "fitting",
          "fit_record": "records", "RecordFitOutcome": "outcome", "OPTIONS": "options",
          "Option": "options", "sweep": "sweeps", "phase_diagram": "sweeps",
          "SweepOutcome": "sweeps", "rsf": "ratestate", "trap": "theory", "static": "theory",
          "steady": "theory", "stability": "theory", "TableOutcome": "theory",
          "record": "reading", "RecordOutcome": "reading", "bifurcation": "hopf",
          "BifurcationOutcome": "hopf"}

__all__ = sorted(_WHERE)


def __getattr__(name: str) -> Any:
    if name in _WHERE:
        value = getattr(importlib.import_module(f"{__name__}.{_WHERE[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
