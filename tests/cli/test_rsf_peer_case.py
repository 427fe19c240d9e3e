"""The ``rsf`` command's default run is rsfmodel's standard velocity step, and gives its
numbers (issue 25: a wrong default is a mistake no other test pins).

rsfmodel (Leeman & May; ``../shared/peers/README.md``) runs a = 0.005, b = 0.01, Dc = 10 um,
k = 1e-3 /um, 1 -> 10 um/s at t = 10 s, 40 s, ageing law, mu0 = 0.6 at V0 = 1 um/s, and
reports steady friction 0.588487 after the step and a peak of 0.60784 (its own solver,
measured there, never imported here). The steady value is also the closed form
``mu0 + (a - b) ln(V2/V0)`` = 0.6 - 0.005 ln 10. A default moved (V0, the step's time or
velocities, the stiffness, the law) changes one of the three numbers.
"""

from __future__ import annotations

import json
import math

import pytest
from typer.testing import CliRunner

from dryfriction.cli import app


def test_default_rsf_run_is_rsfmodels_velocity_step() -> None:
    r = CliRunner().invoke(app, ["rsf", "--json", "--no-figure"])
    assert r.exit_code == 0, r.output
    s = json.loads(r.stdout)
    assert s["duration"] == 40.0
    assert s["final_mu"] == pytest.approx(0.6 - 0.005 * math.log(10.0), abs=1e-6)
    assert abs(s["final_mu"] - 0.588487) < 2e-6  # rsfmodel's, to its printed digits
    assert abs(s["peak_mu"] - 0.60784) < 1e-5
    assert 10.0 < s["peak_t"] < 12.0
