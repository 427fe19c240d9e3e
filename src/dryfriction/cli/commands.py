"""The app with every command registered: importing the command modules adds their commands
to :data:`.common.app`. Kept apart from :mod:`dryfriction.cli` so that the console script can
start its painter (:mod:`.painter`) before Typer, Rich and the commands are imported."""

# importing them registers their commands
from . import bifurcation, examples, fitting, model, record, runs, sweeps  # noqa: F401
from .common import app

__all__ = ["app"]
