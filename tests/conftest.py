"""Shared test options: ``--runslow`` runs the larger variant of the convergence and coverage
studies, and the tests marked ``slow`` (each over ~3.5 s on CI's two cores: the studies, the
whole-process runs of a command, the fits of whole records).

Without it the parametrised studies run a smaller but meaningful version and the ``slow`` tests
are skipped, but for those also marked ``ci`` when ``--with-ci`` is given: ``make test`` (what
CI runs) passes it, so that CI runs one or more slow tests of each area (the README's commands,
the site in a browser, the refusal of huge runs, ...: ``pytest --co -q --slow-marked -m ci``
lists them) in the same session as the rest. ``--slow-marked`` runs
every ``slow`` test at the default sizes: the mutant runner (``tests/mutants.py``) names tests
of both kinds and must run each test it names, at the size the mutant list was checked with.
"""

from __future__ import annotations

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--runslow", action="store_true", default=False,
                     help="run the larger variant of the convergence and coverage studies")
    parser.addoption("--slow-marked", action="store_true", default=False,
                     help="run the tests marked slow too, at the default sizes")
    parser.addoption("--with-ci", action="store_true", default=False,
                     help="run the slow tests marked ci too (make test, CI)")


@pytest.fixture(scope="session")
def runslow(request: pytest.FixtureRequest) -> bool:
    """True when the larger parameter sets were asked for (``--runslow``)."""
    return bool(request.config.getoption("--runslow"))


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Skip the ``slow`` tests unless ``--runslow`` or ``--slow-marked`` is given, or the test
    is marked ``ci`` and ``--with-ci`` is."""
    if config.getoption("--runslow") or config.getoption("--slow-marked"):
        return
    with_ci = config.getoption("--with-ci")
    skip = pytest.mark.skip(reason="slow (over ~3.5 s): run with --runslow or --slow-marked")
    for item in items:
        if item.get_closest_marker("slow") is None:
            continue
        if not (with_ci and item.get_closest_marker("ci") is not None):
            item.add_marker(skip)
