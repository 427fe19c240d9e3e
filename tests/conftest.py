"""Shared test options: ``--runslow`` runs the larger variant of the convergence studies.

Nothing is skipped without it: the parametrised studies run a smaller but meaningful version.
"""

from __future__ import annotations

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--runslow", action="store_true", default=False,
                     help="run the larger variant of the convergence studies")


@pytest.fixture(scope="session")
def runslow(request: pytest.FixtureRequest) -> bool:
    return bool(request.config.getoption("--runslow"))
