"""The extended interface's inputs (ensemble/interface.py): the defaults and the accepted side
of every bound whose refused side tests/ensemble/test_interface.py checks, and the refused side
of the rest (issue 25: >= moved to >, a default changed, a bound that differs by loading)."""

from __future__ import annotations

import pytest

from dryfriction.ensemble import interface as itf
from dryfriction.ensemble.drives import MASS_MIN, STIFFNESS_MAX
from dryfriction.ensemble.interface import InterfaceDrive, InterfaceModel
from dryfriction.program import Segment, VelocityProgram
from dryfriction.theory.model import TrapModel

PROG = VelocityProgram([Segment(0.1, slip=1.0)])


def test_model_defaults_and_accepted_edges() -> None:
    m = InterfaceModel(TrapModel(), 3, 1.0, 1.0)
    assert (m.damping, m.disorder, m.normal_spread, m.density_spread, m.quasi_static_rate) == (
        0.0, "independent", 0.0, 0.0, 0.0)
    assert itf.MAX_ELEMENTS == 2**20
    assert InterfaceModel(TrapModel(), 1, 0.0, MASS_MIN).n_elements == 1  # no coupling: allowed
    edge = InterfaceModel(TrapModel(), itf.MAX_ELEMENTS, STIFFNESS_MAX, 2.0,
                          normal_spread=0.999, density_spread=0.999, quasi_static_rate=1e30)
    assert edge.n_elements == 2**20 and edge.coupling == STIFFNESS_MAX
    for kw, name in (({"normal_spread": 1.0}, "normal_spread"),
                     ({"density_spread": 1.0}, "density_spread"),
                     ({"quasi_static_rate": -1e-9}, "quasi_static_rate"),
                     ({"damping": -1e-9}, "damping"), ({"disorder": "random"}, "disorder")):
        with pytest.raises(ValueError, match=f"^{name} = "):
            InterfaceModel(TrapModel(), 3, 1.0, 1.0, **kw)  # type: ignore[arg-type]
    for n in (itf.MAX_ELEMENTS + 1, True):
        with pytest.raises(ValueError, match=r"n_elements = .* allowed an integer 1 to 1048576"):
            InterfaceModel(TrapModel(), n, 1.0, 1.0)
    with pytest.raises(ValueError, match="^mass = "):
        InterfaceModel(TrapModel(), 3, 1.0, 0.99 * MASS_MIN)
    with pytest.raises(ValueError, match="^coupling = "):
        InterfaceModel(TrapModel(), 3, STIFFNESS_MAX * 1.001, 1.0)


def test_drive_bounds_differ_by_loading() -> None:
    """Uniform loading needs a plate spring > 0 and no edge spring; side loading an edge spring
    > 0 and a plate spring >= 0 (0: a free top)."""
    assert InterfaceDrive("side", 0.0, PROG, edge_stiffness=0.4).stiffness == 0.0
    assert InterfaceDrive("uniform", STIFFNESS_MAX, PROG).edge_stiffness == 0.0
    with pytest.raises(ValueError, match="^stiffness = 0 is out of range"):
        InterfaceDrive("uniform", 0.0, PROG)
    with pytest.raises(ValueError, match="^edge_stiffness = 0 is out of range"):
        InterfaceDrive("side", 0.3, PROG, edge_stiffness=0.0)
    with pytest.raises(ValueError, match="^loading = 'top' is not allowed"):
        InterfaceDrive("top", 0.3, PROG)
    d = InterfaceDrive("side", 0.3, [Segment(-0.2, slip=0.5)], edge_stiffness=0.4)  # type: ignore[arg-type]
    assert isinstance(d.program, VelocityProgram)
