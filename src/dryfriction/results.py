"""One result schema for both simulators (the trap ensemble and rate-and-state).

Both :class:`dryfriction.ensemble.driving.SimulationResult` and
:class:`dryfriction.rsf.driving.RSFResult` offer

``columns()``
    The time series as ``{name: array}``, one entry per sample, always starting with the
    common columns :data:`COMMON_COLUMNS` (same names for the same quantities)::

        t    time                 x    slider position
        v    slider velocity      mu   friction coefficient

    followed by the simulator's own: ``theta`` (``theta2``), ``stress``, ``x_load``,
    ``v_load`` for rate-and-state; ``n_active``, ``mean_age``, ``x_pull``, ``f_applied``,
    ``births``, ``spinodal``, ``exits`` for the trap ensemble.

``summary()``
    A flat mapping made by :func:`summarize`, with the keys :data:`COMMON_SUMMARY_KEYS`:

    ==============  ==============================================================
    law             ``"cv"`` (trap model) or ``"rsf"`` (rate-and-state)
    partial         the run was interrupted (the samples stop early)
    samples         number of samples
    duration        ``t[-1] - t[0]``
    peak_mu         largest sampled friction; ``peak_t``, ``peak_x`` where it is
    final_mu        friction at the last sample
    mean_mu         time average of the friction (trapezoid rule)
    slip            ``x[-1] - x[0]``; ``path_length`` the sum of ``|dx|``
    v_max           largest sampled slider velocity
    units           ``{name: unit}`` for every column and every key above (``"1"``:
                    dimensionless, as the summary.json of ``simulate`` and ``rsf`` says it)
    ==============  ==============================================================

    and then the simulator's extras (solver statistics and the spring for rate-and-state;
    event counts, drive scalars and parameters for the trap ensemble). Times, lengths and
    velocities are in the simulator's units, named by ``units``: reduced (``t0``, ``a0``,
    ``a0/t0``) for the trap model, SI (s, m, m/s) for rate-and-state.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["COMMON_COLUMNS", "COMMON_SUMMARY_KEYS", "DIMENSIONLESS", "ImpossibleResultError",
           "check_physical", "dataset_records", "records", "records_dict", "summarize",
           "summary_units", "to_dataframe"]

DIMENSIONLESS = "1"
"""The unit of a dimensionless number (a friction coefficient, a count, a ratio): one
spelling for the Python results and every file written (:mod:`dryfriction.io.units`)."""

COMMON_COLUMNS: tuple[str, ...] = ("t", "x", "v", "mu")

COMMON_SUMMARY_KEYS: tuple[str, ...] = (
    "law", "partial", "samples", "duration", "peak_mu", "peak_t", "peak_x", "final_mu",
    "mean_mu", "slip", "path_length", "v_max", "units",
)


def summary_units(units: Mapping[str, str]) -> dict[str, str]:
    """The ``units`` of a summary: every column's (an empty unit, the older tables'
    dimensionless, as :data:`DIMENSIONLESS`) and the common keys' from their columns'
    (``duration`` and ``peak_t`` in ``t``'s unit, ``peak_mu`` in ``mu``'s, ...), as
    summary.json declares them."""
    u = {k: v or DIMENSIONLESS for k, v in units.items()}
    t, x, v, mu = (u.get(c, DIMENSIONLESS) for c in COMMON_COLUMNS)
    return {**u, "samples": DIMENSIONLESS, "duration": t, "peak_mu": mu, "peak_t": t,
            "peak_x": x, "final_mu": mu, "mean_mu": mu, "slip": x, "path_length": x,
            "v_max": v}


def summarize(
    law: str,
    t: ArrayLike,
    x: ArrayLike,
    v: ArrayLike,
    mu: ArrayLike,
    units: Mapping[str, str],
    *,
    partial: bool = False,
    extra: Mapping[str, Any] | None = None,
) -> dict[str, Any]:
    """The common summary of a time series (the keys :data:`COMMON_SUMMARY_KEYS`), then ``extra``.

    Parameters
    ----------
    law : str
        ``"cv"`` or ``"rsf"``.
    t, x, v, mu : array_like
        The common columns (same length, at least one sample).
    units : mapping
        Unit of every column.
    partial : bool
        Whether the run stopped early.
    extra : mapping, optional
        Simulator-specific entries; they may not redefine a common key.

    Returns
    -------
    dict
    """
    t, x, v, mu = (np.asarray(a, float) for a in (t, x, v, mu))
    if not len(t):
        raise ValueError("a result needs at least one sample")
    # NaN friction (e.g. an undefined sample) must not hide the peak of the others
    k = int(np.nanargmax(mu)) if np.any(np.isfinite(mu)) else 0
    span = float(t[-1] - t[0])
    mean = float(np.trapezoid(mu, t) / span) if span > 0 else float(np.mean(mu))
    out: dict[str, Any] = {
        "law": law,
        "partial": bool(partial),
        "samples": int(len(t)),
        "duration": span,
        "peak_mu": float(mu[k]),
        "peak_t": float(t[k]),
        "peak_x": float(x[k]),
        "final_mu": float(mu[-1]),
        "mean_mu": mean,
        "slip": float(x[-1] - x[0]),
        "path_length": float(np.sum(np.abs(np.diff(x)))),
        "v_max": float(np.nanmax(v)) if np.any(np.isfinite(v)) else float("nan"),
        "units": summary_units(units),
    }
    for key, value in (extra or {}).items():
        if key in out:
            raise ValueError(f"summary key {key!r} is common to every result: rename the extra")
        out[key] = value
    return out


class ImpossibleResultError(ValueError):
    """A run's result is outside what its physics allows (:func:`check_physical`): a numerical
    failure, never handed back as a result. A ``ValueError``, so the command line says it in
    one line (exit code 2) and a fit treats it as a failed evaluation."""


def check_physical(what: str, t: ArrayLike, x: ArrayLike, v: ArrayLike, mu: ArrayLike, *,
                   unit: str, forward: bool = False, tol: float = 0.0,
                   slip_max: float | None = None, slip_integral: float | None = None,
                   mu_min: float | None = None, mu_why: str | None = None) -> None:
    """Refuse a time series that breaks the bounds every run of either law obeys.

    The one check of both simulators (:func:`dryfriction.ensemble.driving.simulate`,
    :func:`dryfriction.rsf.driving.simulate`), so every command that runs one (``rsf``,
    ``simulate``, ``compare``, the fits' forward runs, sweeps) passes it before exit 0:

    * time and position finite, time non-decreasing; velocity and friction never infinite;
    * ``forward``: a slider whose velocity is positive by construction (the rate-and-state
      spring integrates ``ln V``) never moves backwards by more than ``tol``;
    * ``slip_max``: the slip is at most the load-point travel plus what the spring's stretch
      can give back (the caller's bound), within ``tol``;
    * ``slip_integral``: the slip equals the integral of the velocity (a second route to it),
      within ``tol``;
    * ``mu_min``: the friction never falls below the model's bound (0 for the regularised
      rate-and-state law, ``a asinh(...)`` of a positive velocity).

    Parameters
    ----------
    what : str
        The run, for the message.
    t, x, v, mu : array_like
        The common columns.
    unit : str
        Unit of ``x`` (``m`` or ``a0``).
    forward : bool
        The slider's velocity is positive throughout.
    tol : float
        Absolute tolerance on positions, in ``unit``: the integration's error bound.
    slip_max : float, optional
        Largest slip the drive allows, in ``unit``.
    slip_integral : float, optional
        ``int V dt`` over the run, in ``unit``, computed independently of ``x``.
    mu_min : float, optional
        Smallest friction the model can give.
    mu_why : str, optional
        Why friction below ``mu_min`` can happen with these inputs (a law used outside its
        domain, not a numerical failure): said instead of "a numerical failure".

    Raises
    ------
    ImpossibleResultError
        One line naming the bound, the value and where it was broken.
    """
    t, x, v, mu = (np.asarray(a, float) for a in (t, x, v, mu))

    def fail(msg: str, why: str | None = None) -> None:
        raise ImpossibleResultError(f"{what}: impossible result, {msg}: " + (
            why or "a numerical failure of these inputs (please report it)"))

    for name, arr, nan_ok in (("t", t, False), ("x", x, False), ("v", v, True),
                              ("mu", mu, True)):
        bad = np.isinf(arr) if nan_ok else ~np.isfinite(arr)
        if np.any(bad):
            i = int(np.argmax(bad))
            fail(f"{name} = {arr[i]:g} at sample {i}")
    if t.size > 1 and np.any(np.diff(t) < 0.0):
        i = int(np.argmax(np.diff(t) < 0.0)) + 1
        fail(f"time runs backwards at sample {i} (t = {t[i]:g})")
    if forward and x.size > 1:
        back = x - np.maximum.accumulate(x)
        if np.any(back < -tol):
            i = int(np.argmin(back))
            fail(f"the slider moved backwards by {-back[i]:.3g} {unit} (at t = {t[i]:g}) though "
                 "its velocity is positive throughout")
    if mu_min is not None and np.any(mu < mu_min):
        i = int(np.nanargmin(mu))
        fail(f"friction {mu[i]:.6g} at t = {t[i]:g} is below the model's bound {mu_min:g}",
             mu_why)
    slip = float(x[-1] - x[0])
    if slip_max is not None and slip > slip_max + tol:
        fail(f"slip {slip:.6g} {unit} is more than the load-point travel plus the spring's "
             f"stretch, {slip_max:.6g} {unit}")
    if slip_integral is not None and not abs(slip - slip_integral) <= tol:
        fail(f"slip {slip:.6g} {unit} is not the integral of the velocity, "
             f"{slip_integral:.6g} {unit}")


def records(columns: Mapping[str, ArrayLike] | Sequence[Mapping[str, Any]]) -> np.ndarray:
    """A NumPy structured array from ``{name: column}`` or from a sequence of rows.

    Parameters
    ----------
    columns : mapping or sequence of mappings
        Equal-length 1-D columns by name, or rows (``{name: scalar}``, every row with the same
        names in the same order). Floats become ``float64``, integers and booleans keep their
        kind, ``None`` among numbers becomes NaN, text is a fixed-width unicode field.

    Returns
    -------
    numpy.ndarray
        One record per sample (or row), fields in the order given.

    Raises
    ------
    ValueError
        When the columns differ in length or the rows in their names.
    """
    if not isinstance(columns, Mapping):
        rows = list(columns)
        names = list(rows[0]) if rows else []
        for i, row in enumerate(rows):
            if list(row) != names:
                raise ValueError(f"row {i} has fields {list(row)}, row 0 {names}")
        columns = {k: [row[k] for row in rows] for k in names}
    arrays = {k: _column(k, v) for k, v in columns.items()}
    lengths = {k: len(a) for k, a in arrays.items()}
    if len(set(lengths.values())) > 1:
        raise ValueError(f"columns differ in length: {lengths}")
    n = next(iter(lengths.values()), 0)
    out = np.empty(n, dtype=[(k, a.dtype) for k, a in arrays.items()])
    for k, a in arrays.items():
        out[k] = a
    return out


def _column(name: str, values: ArrayLike) -> np.ndarray:
    """One column as a 1-D array of a kind a structured array holds (``None`` -> NaN)."""
    raw = np.asarray(values)
    if raw.dtype == object:
        items = list(raw.ravel())
        if all(v is None or isinstance(v, int | float | np.number) for v in items):
            raw = np.array([np.nan if v is None else v for v in items], float)
        else:
            raw = np.array(["" if v is None else str(v) for v in items])
    if raw.ndim != 1:
        raise ValueError(f"column {name!r} has shape {raw.shape}: a record field must be 1-D")
    return raw.astype(np.float64) if raw.dtype.kind == "f" else raw


def to_dataframe(columns: Mapping[str, ArrayLike] | np.ndarray) -> Any:
    """A ``pandas.DataFrame`` of ``{name: column}`` or of a structured array.

    pandas is optional (not a dependency of dryfriction).

    Raises
    ------
    ImportError
        When pandas is not installed, with a message naming the alternatives.
    """
    try:
        import pandas as pd
    except ImportError as exc:
        raise ImportError("to_dataframe() needs pandas (pip install pandas); to_records() "
                          "gives the same table as a NumPy structured array") from exc
    return pd.DataFrame(columns if isinstance(columns, Mapping) else records_dict(columns))


def records_dict(rec: np.ndarray) -> dict[str, np.ndarray]:
    """``{field: column}`` of a structured array (columns are views, not copies)."""
    return {k: rec[k] for k in rec.dtype.names or ()}


def dataset_records(ds: Any) -> np.ndarray:
    """An :class:`xarray.Dataset` on a grid (a sweep's ``sweep.nc``) as one record per point.

    The coordinates of every dimension come first (the swept values), then every data variable
    that spans exactly the dataset's dimensions, in C order over the grid. Works without
    importing xarray here: any object with ``dims``, ``coords`` and ``data_vars`` of that shape.

    Returns
    -------
    numpy.ndarray
        Structured array of ``prod(shape)`` records.
    """
    dims = list(ds.dims)
    grids = np.meshgrid(*(np.asarray(ds.coords[d].values) for d in dims), indexing="ij")
    cols: dict[str, Any] = {d: g.ravel() for d, g in zip(dims, grids, strict=True)}
    for name, var in ds.data_vars.items():
        if list(var.dims) == dims:
            cols[str(name)] = np.asarray(var.values).ravel()
    return records(cols)
