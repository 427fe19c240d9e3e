"""Shared pytest options: ``--runslow`` runs the larger parameter sets of the convergence and
coverage studies (the smaller sets always run)."""

from __future__ import annotations

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--runslow", action="store_true", default=False,
                     help="run the larger (slow) parameter sets of the statistical studies")


@pytest.fixture
def runslow(request: pytest.FixtureRequest) -> bool:
    """True when the larger parameter sets were asked for (``--runslow``)."""
    return bool(request.config.getoption("--runslow"))
