"""``python -m dryfriction.cli``: the same as the ``dryfriction`` command."""

from . import main

raise SystemExit(main())
