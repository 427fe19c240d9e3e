"""Shared test options: ``--runslow`` runs the larger variant of the convergence and coverage
studies.

Nothing is skipped without it: the parametrised studies always run a smaller but meaningful
version.
"""

from __future__ import annotations

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--runslow", action="store_true", default=False,
                     help="run the larger variant of the convergence and coverage studies")


@pytest.fixture(scope="session")
def runslow(request: pytest.FixtureRequest) -> bool:
    """True when the larger parameter sets were asked for (``--runslow``)."""
    return bool(request.config.getoption("--runslow"))
