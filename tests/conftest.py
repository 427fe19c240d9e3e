"""Shared test options: ``--runslow`` runs the larger variant of the convergence and coverage
studies, and the tests marked ``slow`` (each over ~5 s on CI's two cores: the studies, the
whole-process runs of a command, the fits of whole records).

Without it the parametrised studies run a smaller but meaningful version and the ``slow`` tests
are skipped; ``make test`` then runs a selected ``slow`` subset with ``--runslow -m slow``
(see the Makefile), so CI exercises some of them too. ``--slow-marked`` runs the ``slow`` tests
at the default sizes: the mutant runner (``tests/mutants.py``) names tests of both kinds and must
run each test it names, at the size the mutant list was checked with.
"""

from __future__ import annotations

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--runslow", action="store_true", default=False,
                     help="run the larger variant of the convergence and coverage studies")
    parser.addoption("--slow-marked", action="store_true", default=False,
                     help="run the tests marked slow too, at the default sizes")


@pytest.fixture(scope="session")
def runslow(request: pytest.FixtureRequest) -> bool:
    """True when the larger parameter sets were asked for (``--runslow``)."""
    return bool(request.config.getoption("--runslow"))


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Skip the ``slow`` tests unless ``--runslow`` is given."""
    if config.getoption("--runslow") or config.getoption("--slow-marked"):
        return
    skip = pytest.mark.skip(reason="slow (over ~5 s): run with --runslow or --slow-marked")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)
