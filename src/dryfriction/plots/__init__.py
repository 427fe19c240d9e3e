"""Every figure (matplotlib object API, no pyplot): the paper's figures (:mod:`.paper`), the
figures of runs and sweeps (:mod:`.runs`), the reproduce report (:mod:`.report`), in the one
style of :mod:`.style`. Nothing outside this package draws.

A command-line process (``dryfriction ...``, which sets ``DRYFRICTION_LEAN_MATPLOTLIB=1``)
imports matplotlib here without the property tables it writes into the docstring of every
artist class's ``set`` at import (``matplotlib.artist.kwdoc``: about 0.15 s, a sixth of the
figure's cost, for docstrings that process never shows). Elsewhere (a notebook, a script)
matplotlib is imported as usual.
"""

import os
import sys

LEAN_ENV = "DRYFRICTION_LEAN_MATPLOTLIB"
"""The environment variable that asks for the lean import (``"1"``)."""


def _import_matplotlib_lean() -> None:
    """Import the parts of matplotlib the figures use with ``kwdoc`` answering ``""`` (its
    only use is docstrings), then put it back for any artist class defined later."""
    import matplotlib.artist

    kwdoc = matplotlib.artist.kwdoc
    matplotlib.artist.kwdoc = lambda artist: ""
    try:
        import matplotlib.backends.backend_agg  # noqa: F401
        import matplotlib.figure  # noqa: F401
    finally:
        matplotlib.artist.kwdoc = kwdoc


if os.environ.get(LEAN_ENV) == "1" and "matplotlib.figure" not in sys.modules:
    _import_matplotlib_lean()
