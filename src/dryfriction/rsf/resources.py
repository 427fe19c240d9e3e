"""How much memory a rate-and-state run will hold, estimated before any work.

The solver (:func:`~dryfriction.rsf.driving.simulate`) records every accepted step, at most
``max_steps`` plus one per segment, in buffers that double when full: at the moment of a
doubling the old and the new buffer coexist, three times the steps' own size. Each step stores
its time, segment and the state and derivative vectors (``ny <= 4`` floats each). The output
(every step, or the ``every``/``t_eval`` times) then becomes about a dozen float arrays
(interpolation temporaries and the result's columns). All arithmetic is in floats: an absurd
input gives ``inf``, never an ``OverflowError``.

Time: the step budget ``max_steps`` bounds a run's work before it starts (a compiled
step costs about 1 us: the default 1e6 steps are about a second), and this memory check
bounds ``max_steps``; a run that needs more steps stops with ``SolverError`` naming
``max_steps``, it never runs on silently.
"""

from __future__ import annotations

import math

from ..validation import check_memory
from .law import RateState
from .spring import RSFOutput, SpringSlider

__all__ = ["BYTES_PER_OUTPUT", "check_rsf_run", "estimate_rsf"]

BYTES_PER_OUTPUT = 16 * 8.0
"""Bytes per output time: the interpolation temporaries and the result's columns."""


def estimate_rsf(params: RateState, drive: SpringSlider, output: RSFOutput
                 ) -> tuple[float, float, float]:
    """``(steps, outputs, bytes)``: the most solver steps recorded, the output times, and the
    peak bytes they hold."""
    ny = params.n_state + (0 if drive.kinematic else 1) + (1 if drive.mass > 0.0 else 0)
    prog = drive.program
    steps = float(output.max_steps) + len(prog.segments)
    if output.t_eval is not None:
        outputs = float(len(output.t_eval))
    elif output.every is not None:
        outputs = prog.total_time / output.every + len(prog.segments) + 1.0
    else:
        outputs = steps
    step_bytes = 3.0 * (16.0 + 16.0 * ny)
    return steps, outputs, steps * step_bytes + outputs * BYTES_PER_OUTPUT


def check_rsf_run(params: RateState, drive: SpringSlider, output: RSFOutput, *,
                  qualified: bool = False) -> float:
    """Refuse a run whose estimate is over :func:`dryfriction.validation.memory_limit`.

    Parameters
    ----------
    qualified : bool
        Name ``every`` as a protocol file spells it (``output.every``).

    Returns
    -------
    float
        The estimate, bytes.

    Raises
    ------
    ValueError
        One line with the estimate, the limit and the key to change.
    """
    steps, outputs, need = estimate_rsf(params, drive, output)
    every = ("output." if qualified else "") + "every"
    if output.every is not None and not outputs <= steps:
        what = f"{every} = {output.every:g} gives {outputs:.1e} samples"
        hint = f"raise {every} (or shorten the drive)"
    elif output.t_eval is not None and not outputs <= steps:
        what = f"t_eval gives {outputs:.1e} samples"
        hint = "ask for fewer t_eval"
    else:
        what = f"max_steps = {output.max_steps} lets the solver record {steps:.1e} steps"
        hint = (f"give {every}" if qualified else f"lower max_steps, give {every}") \
            if output.every is None and output.t_eval is None else "lower max_steps"
    if math.isnan(need):
        need = math.inf
    check_memory(what, need, hint)
    return need
