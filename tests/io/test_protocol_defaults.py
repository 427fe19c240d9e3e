"""A protocol's optional keys left out (issue 25: a default changed, nothing checks it): the
parsed objects hold the module docstring's defaults, which are the model's declared ones
(theory.model.TRAP_PARAMETERS), for the trap model, a force drive, a spring drive and
rate-and-state (whose start defaults to the first segment's velocity)."""

from __future__ import annotations

from typing import Any

import pytest

from dryfriction.io.protocol import protocol_from_dict
from dryfriction.theory.model import TRAP_PARAMETERS

ENSEMBLE = {"traps_per_a0": 20, "initial": "rest"}


def test_the_trap_models_defaults_are_its_declared_ones() -> None:
    p = protocol_from_dict({"model": {"eps": 0.037}, "ensemble": ENSEMBLE,
                            "drive": {"kind": "force", "rate": 0.3},
                            "output": {"every": 0.5}}, "p")
    m = p.model
    assert (m.alpha, m.creep, m.mu_el, m.direct, m.v_ref) == (0.13, "log", 1.0, 0.0, 1.0)
    for name in ("alpha", "creep", "mu_el", "direct", "v_ref"):
        assert getattr(m, name) == TRAP_PARAMETERS[name].default, name
    assert p.track.layout == "regular"
    assert (p.drive.hold, p.drive.max_force) == (0.0, 10.0)


def test_a_spring_drives_damping_and_the_rsf_start() -> None:
    spring: dict[str, Any] = {"kind": "spring", "stiffness": 0.05, "mass": 0.2,
                              "segments": [{"velocity": 0.3, "slip": 1.0}]}
    p = protocol_from_dict({"model": {"eps": 0.037}, "ensemble": ENSEMBLE, "drive": spring,
                            "output": {"every_slip": 0.05}}, "p")
    assert p.drive.damping == 0.0 and p.drive.mass == 0.2
    rsf = protocol_from_dict({"model": {"law": "rsf", "a": 0.006, "b": 0.009, "dc": 2e-6,
                                        "mu0": 0.57, "v0": 1.3e-6},
                              "drive": {"kind": "spring", "stiffness": 3e3,
                                        "segments": [{"velocity": 2.9e-6, "duration": 3.0},
                                                     {"velocity": 0.8e-6, "duration": 2.0}]}},
                             "p")
    assert rsf.output.rtol == pytest.approx(1e-7) and rsf.output.every is None
    assert rsf.drive.damping == 0.0 and rsf.drive.mass == 0.0
    assert rsf.run().v[0] == pytest.approx(2.9e-6, rel=1e-9)  # started at the first velocity
