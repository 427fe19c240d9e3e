"""The quasi-static spring-slider sweep protocol the sweep, stick-slip and CF tests share
(trap model, eps = 0.04, 50 traps/a0, started in steady sliding at u = 0.1 on K = 0.05)."""

from __future__ import annotations


def spring_sweep(sweep: str = "", *, slip: float | str = 30.0, every_slip: float = 0.5,
                 transient: float = 10.0, alpha: float | None = None, header: str = "") -> str:
    """Protocol text ending with the ``[sweep]`` table header followed by ``sweep`` (its keys).

    ``slip`` may be a placeholder string that a test replaces; ``alpha`` adds the key to
    ``[model]``; ``header`` (comment lines) goes first."""
    alpha_line = "" if alpha is None else f"alpha = {alpha}\n"
    return (f"{header}[model]\n{alpha_line}eps = 0.04\n\n"
            "[ensemble]\ntraps_per_a0 = 50\ninitial = \"steady\"\ninitial_velocity = 0.1\n\n"
            "[drive]\nkind = \"spring\"\nstiffness = 0.05\nmass = 0.0\n"
            f"segments = [{{velocity = 0.1, slip = {slip}}}]\n\n"
            f"[output]\nevery_slip = {every_slip}\n\n"
            f"[stickslip]\ntransient = {transient}\n\n"
            f"[sweep]\n{sweep}")
