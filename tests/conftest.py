"""Shared test options: ``--runslow`` runs the larger variant of the convergence and coverage
studies, and the tests marked ``slow`` (each over ~20 s).

Without it the parametrised studies run a smaller but meaningful version and the ``slow`` tests
are skipped; ``make test`` then runs a selected ``slow`` subset with ``--runslow -m slow``
(see the Makefile), so CI exercises them too.
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


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Skip the ``slow`` tests unless ``--runslow`` is given."""
    if config.getoption("--runslow"):
        return
    skip = pytest.mark.skip(reason="slow (over ~20 s): run with --runslow")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)
