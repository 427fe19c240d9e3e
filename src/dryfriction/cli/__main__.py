"""``python -m dryfriction.cli``: the same as the ``dryfriction`` command."""

from . import main

code = main()
# Run with -m, CPython ends the process by SIGINT (status -2 to its parent, not main()'s 130)
# when a KeyboardInterrupt once passed through an exec() of source text, even one that main()
# caught later: a dataclass or a Numba wrapper being built when Ctrl-C came. The flag behind it
# (Modules/main.c, pymain_run_module) is cleared by the next exec of source text, and only the
# -m route reads it (the console script exits through SystemExit directly). Measured: 3 of 8
# interrupted `simulate` runs ended by SIGINT before this line, 0 of 8 after
# (tests/cli/test_signals.py::test_signals_into_the_trap_ensemble).
exec("")  # noqa: S102
raise SystemExit(code)
