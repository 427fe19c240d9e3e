"""The ``rsf`` workflow: rate-and-state friction (SI units) through a velocity step,
slide-hold-slide or stick-slip on a spring (:func:`rsf`). Moved here from the command line."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from .options import OPTIONS
from .outcome import RunOutcome
from .runs import Draw, Report, draw_here
from .theory import LOAD_MAX

__all__ = ["rsf", "rsf_figure"]

_O = {k: o.default for k, o in OPTIONS["rsf"].items()}


def rsf_figure(result: Any, title: str) -> tuple[Any, Any]:
    """:func:`dryfriction.plots.runs.rsf_figure` (the ``rsf`` workflow's figure), imported
    when called (a painter receives the function by module and name)."""
    from ..plots.runs import rsf_figure as build

    return build(result, title)


def rsf(*, case: str = _O["case"], a: float = _O["a"], b: float = _O["b"],
        dc: float = _O["dc"], mu0: float = _O["mu0"], v0: float = _O["v0"],
        state_law: str = _O["state_law"], regularized: bool = _O["regularized"],
        stiffness: float = _O["stiffness"], damping: float = _O["damping"],
        mass: float = _O["mass"], v1: float = _O["v1"], v2: float = _O["v2"],
        t1: float = _O["t1"], t2: float | None = _O["t2"], hold: float = _O["hold"],
        v_init: float | None = _O["v_init"], rtol: float = _O["rtol"],
        out: str | Path | None = None, force: bool = _O["force"], fmt: str = _O["fmt"],
        dpi: int | None = _O["dpi"], figure: bool = _O["figure"],
        report: Report | None = None, draw: Draw | None = None,
        on_start: Callable[[], None] | None = None) -> RunOutcome:
    """Rate-and-state friction through a velocity step (``case="step"``: ``v1`` for ``t1``,
    then ``v2`` for ``t2``), slide-hold-slide (``"shs"``: ``v1``, a hold of ``hold`` s, ``v1``
    again) or stick-slip (``v1`` for ``t1``), on a spring of ``stiffness`` (1/m per unit
    normal force) with radiation damping and mass (``dryfriction rsf``;
    :func:`dryfriction.rsf.driving.simulate`). SI units throughout.

    Every check runs before any work, each refusal naming the option as typed. With ``out``,
    series.csv, summary.json and rsf.{fmt} are written there (whole or not at all).

    Returns
    -------
    RunOutcome
        ``summary``: the run's summary with ``case`` and ``wall_s``; ``units`` ``"SI"``;
        ``notes``: a slide-hold-slide that ended before the reload's peak; ``out`` ``None``
        (and ``files`` empty) without ``out``.
    """
    from ..io.files import check_output_dir, output_directory, write_csv, write_json
    from ..io.units import SUMMARY_UNITS, with_units
    from ..program import Segment
    from ..rsf.driving import RSFInitial, RSFOutput, SolverError, SpringSlider, simulate
    from ..rsf.law import V_MAX, V_MIN, RateState
    from ..rsf.spring import RTOL_RANGE, T_MAX
    from ..validation import check_choice, check_figure_format, check_scalar

    check_choice("case", case, ("step", "shs", "stick-slip"))
    fmt, dpi = check_figure_format(fmt, dpi)
    if t2 is None:
        t2 = reload_time(a, b, dc, v1, hold, stiffness) if case == "shs" else 30.0
    # durations and velocities a run can reach in floating point (a 1e308 s first segment
    # would leave the later ones at t = inf, silently dropped)
    for name, value in (("--t1", t1), ("--t2", t2), ("--hold-time", hold)):
        check_scalar(name, value, 0.0, T_MAX, lo_open=True)
    for name, value in (("--v1", v1), ("--v2", v2)):
        check_scalar(name, value, -V_MAX, V_MAX)
        if value != 0.0 and abs(value) < V_MIN:  # named as typed, not as segments[0]
            raise ValueError(f"{name} {value:g} is out of range: allowed 0 (a hold) or "
                             f"{V_MIN:g} <= |{name[2:]}| <= {V_MAX:g} m/s")
        if value < 0.0 and not (math.isinf(stiffness) and regularized):
            # the spring driver integrates ln V and the standard law needs V > 0: the
            # driver's own check would name segments[i], which the user never typed
            raise ValueError(f"{name} {value:g} is out of range: allowed 0 to {V_MAX:g} m/s "
                             "(sliding back needs --stiffness inf --regularized)")
    if v_init is not None:
        check_scalar("--v-init", v_init, 0.0, V_MAX, lo_open=True)
    elif v1 <= 0.0:  # the library would ask for v_init, a name the user never typed
        raise ValueError(f"--v-init is needed when --v1 is {v1:g} m/s: the initial slip "
                         f"velocity, > 0 and <= {V_MAX:g} m/s (the state starts steady for it)")
    check_scalar("--damping", damping, 0.0, LOAD_MAX)
    check_scalar("--mass", mass, 0.0, LOAD_MAX)
    # the solver's own range (rsf.spring.RTOL_RANGE), named as typed: "0 < rtol <= 0.1" here
    # once let 0.05 through to a second refusal with another range
    check_scalar("--rtol", rtol, *RTOL_RANGE)
    params = RateState(a, b, dc, mu0, v0, state_law=state_law,  # type: ignore[arg-type]
                       regularized=regularized)
    if case == "step":
        segs = [Segment(v1, t1), Segment(v2, t2)]
    elif case == "shs":
        segs = [Segment(v1, t1), Segment(0.0, hold), Segment(v1, t2)]
    else:
        segs = [Segment(v1, t1)]
        if v_init is None:
            v_init = 1.01 * v1
    drive = SpringSlider(segs, stiffness, damping, mass)  # every check before any work
    init, output = RSFInitial(v=v_init), RSFOutput(rtol=rtol)
    drive.check_model(params)
    init.resolve(params, drive)
    if out is not None:
        check_output_dir(out, force=force, command="rsf")
    if on_start is not None:
        on_start()
    start = time.perf_counter()
    try:
        res = simulate(params, drive, init, output)
    except SolverError as exc:
        raise ValueError(str(exc)) from None
    context = {"case": case, "wall_s": time.perf_counter() - start}
    summary = with_units({**res.summary(), **context}, SUMMARY_UNITS["rsf"])
    files: list[str] = []
    if out is not None:
        with output_directory(out, command="rsf", force=force, report=report) as tmp:
            write_csv(tmp / "series.csv", res.columns(), summary["units"])
            write_json(tmp / "summary.json", summary)
            files = ["series.csv", "summary.json"]
            if figure:
                (draw or draw_here)(rsf_figure, res, f"{case}, {state_law} law",
                                    path=tmp / f"rsf.{fmt}", fmt=fmt, dpi=dpi)
                files.append(f"rsf.{fmt}")
    notes = []
    if case == "shs" and _peak_at_end(res, t1 + hold):
        notes.append(f"note: the reload had not reached its peak when the run ended (t2 = "
                     f"{t2:g} s): raise --t2")
    return RunOutcome(Path(out) if out is not None else None, files,  # type: ignore[arg-type]
                      summary, res, notes, units="SI")


def reload_time(a: float, b: float, dc: float, v: float, hold: float,
                stiffness: float) -> float:
    """Duration (s) of the reload of a slide-hold-slide at load velocity ``v`` that passes the
    peak: the spring takes up the friction the contact healed during the hold (about
    ``b ln(1 + hold v/dc)`` plus the direct effect ``a``, over ``stiffness``), then the slider
    slides ``10 dc`` (the evolution back to steady state). At least 30 s. (Ours: an
    estimate, checked after the run by :func:`_peak_at_end`.)"""
    from ..rsf.spring import T_MAX

    if not (a > 0 and dc > 0 and v != 0 and math.isfinite(a + b + dc + v + hold)):
        return 30.0  # the law's own checks reject these, with their own message
    speed = abs(v)
    heal = max(b, 0.0) * math.log1p(hold * speed / dc) + 2.0 * a
    load = heal / (stiffness * speed) if math.isfinite(stiffness) and stiffness > 0 else 0.0
    return max(30.0, min(load + 10.0 * dc / speed, T_MAX))


def _peak_at_end(res: Any, reload_start: float) -> bool:
    """Whether the friction of the reload (after ``reload_start``) is still at its maximum at
    the last sample: the run ended before the peak."""
    import numpy as np

    sel = np.asarray(res.t) >= reload_start
    mu = np.asarray(res.mu)[sel]
    return bool(mu.size > 1 and int(np.argmax(mu)) == mu.size - 1)
