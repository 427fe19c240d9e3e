"""fixE item 6 (a second new user's trial, problem 11): a unit is written one way whichever
way a user reads it. The Python ``summary()`` of a run declares a dimensionless number "1", as
summary.json does (it wrote "" where the command line wrote "1"), and the common keys' units
as summary.json's; an extended interface's ``work_load`` (and every energy, and ``load``) is in
the same unit in summary.json and load.csv (one said "F_el a0 per element", the other "F_el
a0": the chain's total in one element's F_el)."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.ensemble.interface_result import INTERFACE_UNITS, InterfaceResult
from dryfriction.ensemble.result import UNITS as CV_UNITS
from dryfriction.io.units import (
    DIMENSIONLESS,
    INTERFACE_LOAD_UNITS,
    INTERFACE_SUMMARY_UNITS,
    SUMMARY_UNITS,
    with_units,
)
from dryfriction.results import COMMON_SUMMARY_KEYS, summarize
from dryfriction.rsf.result import UNITS as RSF_UNITS


@pytest.mark.parametrize("law, units", [("cv", CV_UNITS), ("rsf", RSF_UNITS)])
def test_a_python_summary_declares_what_summary_json_declares(law: str, units: dict) -> None:
    """Mistake: the columns' table passed on as it is ('' for friction, no unit for
    final_mu)."""
    t = np.array([0.0, 1.5, 4.0])
    s = summarize(law, t, 2.0 * t, np.full(3, 2.0), np.array([0.6, 0.65, 0.62]), units)
    written = with_units(s, SUMMARY_UNITS[law])["units"]
    for key in (*COMMON_SUMMARY_KEYS[2:-1], *units):
        assert s["units"][key] == written[key], key
    assert s["units"]["mu"] == s["units"]["final_mu"] == DIMENSIONLESS == "1"
    assert "" not in s["units"].values()


def test_an_interface_s_energies_have_one_unit_in_summary_json_and_load_csv() -> None:
    t = np.linspace(0.0, 3.0, 4)
    z = np.zeros((4, 2))
    energy = {k: t.copy() for k in ("work_load", "elastic_energy", "kinetic_energy",
                                    "work_friction", "work_damping", "work_quasi_static")}
    r = InterfaceResult(t=t, x=np.array([0.5, 1.5]), slip=z, slip_rate=z, stress=z, load=t,
                        load_point=t, params={}, units=dict(INTERFACE_UNITS), energy=energy)
    summary = with_units(r.summary(), INTERFACE_SUMMARY_UNITS)["units"]  # summary.json's
    for key in (*energy, "load"):
        assert summary[key] == r.summary()["units"][key] == INTERFACE_LOAD_UNITS[key], key
    assert summary["work_load"] == "F_el a0"
