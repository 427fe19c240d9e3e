"""The ``bifurcation`` workflow: the nature of the onset of stick-slip by normal form
(:func:`bifurcation`, :mod:`dryfriction.analysis.hopf_table`). Moved here from the command
line."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .options import OPTIONS

__all__ = ["bifurcation", "BifurcationOutcome"]

_O = {k: o.default for k, o in OPTIONS["bifurcation"].items()}


@dataclass
class BifurcationOutcome:
    """The Hopf point of steady sliding at each velocity (``dryfriction bifurcation``).

    Attributes
    ----------
    out : Path
        The results folder.
    files : list of str
        bifurcation.csv, bifurcation.json (and bifurcation.png with the figure).
    report : dict
        What bifurcation.json holds: ``rows`` (one per velocity: ``K_c``, the frequency, the
        first Lyapunov coefficient ``l1`` and the nature), ``units``, ``law``, ``protocol``.
    """

    out: Path
    files: list[str]
    report: dict[str, Any]


def bifurcation(protocol: str | Path, velocities: str | list[float], out: str | Path, *,
                check: bool = _O["check"], figure: bool = _O["figure"],
                force: bool = _O["force"],
                report: Callable[[str], None] | None = None,
                progress: Callable[[int, int], None] | None = None) -> BifurcationOutcome:
    """Critical stiffness, frequency and first Lyapunov coefficient ``l1`` of steady sliding
    at each load velocity of a protocol: the Hopf bifurcation's nature (supercritical
    ``l1 < 0``, subcritical ``l1 > 0``, degenerate ``l1 = 0``). Rate-and-state (m/s, SI):
    :func:`dryfriction.analysis.hopf_table.bifurcation_table`; the trap model (reduced units
    ``a0``, ``t0``, ``F_el``): :func:`dryfriction.analysis.hopf_table.trap_bifurcation_table`.

    Parameters
    ----------
    protocol : path
        A rate-and-state protocol (``model.law = "rsf"``: its law, damping and mass are used)
        or a trap-model one (``model.law = "cv"`` with ``0 < direct``, ``alpha < 0.1716``: its
        model, and a spring drive's mass and damping, else 0).
    velocities : str or list of float
        Load velocities, m/s for rate-and-state, ``a0/t0`` for the trap model:
        ``"1e-6,1e-5"`` as ``--velocities`` takes them, or a list.
    out : path
        Folder for bifurcation.csv, bifurcation.json and bifurcation.png (whole or not at
        all).
    check : bool
        Check each nature by direct simulation (at most ``MAX_CHECKED`` velocities):
        rate-and-state by its solver; the trap model by its ensemble on the protocol's track
        (refused in one line, before any simulation, when the estimated cost is over
        :data:`~dryfriction.analysis.hopf_table.TRAP_CHECK_CPU_MAX`).
    figure, force, report : as :func:`dryfriction.app.simulate`.
    progress : callable, optional
        ``progress(done, total)`` after each velocity.
    """
    from ..analysis.hopf_table import (
        MAX_CHECKED,
        MAX_TRAP_VELOCITIES,
        bifurcation_table,
        check_trap,
        parse_velocities,
        trap_bifurcation_table,
    )
    from ..io.files import check_output_dir, output_directory, write_csv, write_json
    from ..io.protocol import Protocol, RSFProtocol, load_protocol
    from ..io.units import BIFURCATION_UNITS, TRAP_BIFURCATION_UNITS, with_units
    from ..validation import U_MAX

    if not isinstance(velocities, str):
        velocities = ",".join(repr(float(v)) for v in velocities)
    n_given = len(velocities.split(","))  # before reading the protocol, as before the trap route
    if check and n_given > MAX_CHECKED:
        raise ValueError(f"--velocities: {n_given} values with --check: allowed at most "
                         f"{MAX_CHECKED}")
    proto = load_protocol(protocol)
    if isinstance(proto, Protocol):  # the trap model: reduced units
        vs = parse_velocities(velocities, U_MAX, "a0/t0 (reduced, for a trap-model protocol)",
                              MAX_TRAP_VELOCITIES)
        mass = float(getattr(proto.drive, "mass", 0.0))  # a spring drive's; else none
        damping = float(getattr(proto.drive, "damping", 0.0))
        try:
            check_trap(proto.model, mass, damping)
        except ValueError as exc:
            raise ValueError(f"{protocol}: {exc}") from None
        check_output_dir(out, force=force, command="bifurcation")
        rep = trap_bifurcation_table(proto.model, vs, mass, damping, progress=progress,
                                     track=proto.track if check else None)
        rep = with_units({**rep, "protocol": str(protocol)}, TRAP_BIFURCATION_UNITS)
    elif isinstance(proto, RSFProtocol):
        vs = parse_velocities(velocities)
        check_output_dir(out, force=force, command="bifurcation")
        rep = bifurcation_table(proto, vs, check, progress=progress)
        rep = with_units({**rep, "protocol": str(protocol)}, BIFURCATION_UNITS)
    else:
        raise ValueError(f"{protocol}: an [interface] protocol is not allowed here: allowed a "
                         "rate-and-state (law = 'rsf') or a single-slider trap-model protocol")
    rows = rep["rows"]
    files = ["bifurcation.csv", "bifurcation.json"]
    with output_directory(out, command="bifurcation", force=force, inputs=[protocol],
                          report=report) as tmp:
        write_csv(tmp / "bifurcation.csv", {k: [r[k] for r in rows] for k in rows[0]},
                  rep["units"])
        write_json(tmp / "bifurcation.json", rep)
        if figure:
            from ..plots.hopf import plot_bifurcation
            from ..plots.style import save_figure

            what = "trap model" if rep["law"] == "trap" else f"{rep['law']} law"
            fig, _ = plot_bifurcation(rep, f"{what}, {protocol}")
            save_figure(fig, tmp / "bifurcation.png", "png")
            files.append("bifurcation.png")
    return BifurcationOutcome(Path(out), files, rep)
