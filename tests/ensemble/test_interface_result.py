"""The interface run's result object (ensemble/interface_result.py) on fields written by hand
(issue 25: a constant offset a difference cancels, a column's definition, max vs last): the
energy residual against its definition with stored energy at the start and with and without
the quasi-static term, and every summary entry."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.ensemble.interface_result import InterfaceResult


def _result(energy: dict) -> InterfaceResult:  # type: ignore[type-arg]
    t = np.array([0.0, 0.5, 1.25, 2.0])
    slip = np.array([[0.0, 0.0, 0.0], [0.1, 0.3, 0.05], [0.7, 0.2, 0.4], [0.6, 0.25, 0.5]])
    rate = np.array([[0.0, 0.0, 0.0], [0.2, 3.1, 0.1], [1.7, -0.4, 0.9], [0.3, 0.1, 0.2]])
    return InterfaceResult(t=t, x=np.arange(3) + 0.5, slip=slip, slip_rate=rate,
                           stress=np.ones((4, 3)), load=np.array([0.0, 1.2, 2.9, 1.1]),
                           load_point=np.array([0.0, 0.4, 0.9, 1.3]), params={"m": 1},
                           energy=energy, info={"steps": 40, "partial": True})


E = {"work_load": np.array([0.0, 0.5, -2.5, 1.75]),
     "elastic_energy": np.array([0.3, 0.45, 0.6, 0.7]),  # a start with stored energy
     "kinetic_energy": np.array([0.1, 0.05, 0.2, 0.0]),
     "work_friction": np.array([0.0, 0.1, 0.4, 0.8]),
     "work_damping": np.array([0.0, 0.01, 0.02, 0.03])}


def test_energy_residual_is_its_definition() -> None:
    stored = E["elastic_energy"] + E["kinetic_energy"]
    want = E["work_load"] - (stored - 0.4) - E["work_friction"] - E["work_damping"]
    np.testing.assert_allclose(_result(E).energy_residual(), want, rtol=1e-15, atol=1e-15)
    qs = np.array([0.0, 0.0, 0.15, 0.15])
    np.testing.assert_allclose(_result({**E, "work_quasi_static": qs}).energy_residual(),
                               want - qs, rtol=1e-15, atol=1e-15)


def test_summary_entries() -> None:
    r = _result(E)
    s = r.summary()
    res = r.energy_residual()
    assert (s["kind"], s["n_elements"], s["n_samples"], s["t_end"]) == ("interface", 3, 4, 2.0)
    assert s["max_slip"] == 0.7 and s["max_slip_rate"] == 3.1  # the largest, not the last
    assert s["final_load"] == 1.1
    assert s["energy_residual_max"] == pytest.approx(float(np.max(np.abs(res))), rel=1e-15)
    assert s["energy_work_load_max"] == 2.5  # |work| at its largest (a negative one)
    assert s["partial"] is True and s["info"] == {"steps": 40}
    assert r.n_elements == 3
    bare = _result({}).summary()
    assert bare["energy_residual_max"] == 0.0 and bare["energy_work_load_max"] == 0.0
