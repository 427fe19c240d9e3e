"""Measured friction data: CSV loaders and the data-set types the fitter works on.

Three kinds of data set, told apart by their columns (names are case-insensitive):

* **static** (static friction against waiting time): ``t_w, mu_s`` — the waiting (hold) time
  and the static friction coefficient ``F_s/W``;
* **steady** (steady sliding): ``V, mu_d`` — the sliding velocity and the steady dynamic
  friction coefficient ``F_d/W``;
* **series** (a transient: velocity steps, slide-hold-slide): ``t, v_load, mu`` — time, the
  load-point velocity and the friction coefficient.

Each may carry an uncertainty column ``sigma_<quantity>`` (``sigma_mu_s``, ``sigma_mu_d``,
``sigma_mu``): one standard deviation of the friction coefficient, ``> 0``. Other columns are
ignored. Lines starting with ``#`` are comments (the shipped synthetic data say so there);
blank lines are skipped; the first other line is the header.

**Separator**: commas; or semicolons with decimal commas (``t[s];v_load[um/s];mu`` then
``0,5;1;0,5998``), as a spreadsheet set to a European locale saves "CSV": the same columns
and checks (:func:`csv_separator`). A header line holding a ``;`` and no ``,`` is read that
way; a cell ``1.000,5`` (a thousands point) is refused as not a number.

**Units** go in the header after the name, in square brackets: ``t_w[min]``, ``V[um/s]``,
``t[ms]``. Without brackets the quantity is in SI (s, m/s). Accepted:

* times (``t_w``, ``t``): ``s``, ``ms``, ``us`` (or ``µs``), ``ns``, ``min``, ``h``, ``d``;
* velocities (``V``, ``v_load``): ``<length>/<time>`` with length ``m``, ``cm``, ``mm``,
  ``um`` (or ``µm``), ``nm`` and one of the times above, e.g. ``m/s``, ``um/s``, ``mm/min``;
* friction coefficients and their uncertainties: dimensionless, ``[]``, ``[1]`` or ``[-]``.

Everything is converted to SI on reading. Checks, each naming the file, the line and the
column: a missing column, a cell that is not a number, NaN or infinite values, a negative
waiting time, a non-positive sliding velocity (``V`` enters through ``ln V``), a negative load
velocity (holds, ``v_load = 0``, are allowed), times that do not increase, non-positive
uncertainties, rows with the wrong number of cells. All raise :class:`ValueError`; the CLI turns
them into one line and exit code 2.
"""

from __future__ import annotations

import csv
import math
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..io.textfile import check_text_file
from ..validation import Array

__all__ = [
    "StaticData",
    "SteadyData",
    "SeriesData",
    "Dataset",
    "read_csv",
    "csv_separator",
    "TIME_UNITS",
    "LENGTH_UNITS",
]


TIME_UNITS: dict[str, float] = {
    "s": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6, "ns": 1e-9, "min": 60.0, "h": 3600.0,
    "d": 86400.0,
}
"""Accepted time units and their value in seconds."""

LENGTH_UNITS: dict[str, float] = {
    "m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9,
}
"""Accepted length units (for velocities ``length/time``) and their value in metres."""

_DIMENSIONLESS = ("", "1", "-")


def _frozen_array(name: str, value: ArrayLike, source: str) -> Array:
    arr = np.array(value, dtype=float, copy=True).ravel()
    if not np.all(np.isfinite(arr)):
        i = int(np.flatnonzero(~np.isfinite(arr))[0])
        raise ValueError(f"{source}: {name}[{i}] = {arr[i]} is not a finite number")
    arr.setflags(write=False)
    return arr


def _check_lengths(source: str, **cols: Array | None) -> int:
    lengths = {k: len(v) for k, v in cols.items() if v is not None}
    if len(set(lengths.values())) > 1:
        raise ValueError(f"{source}: columns have different lengths {lengths}")
    n = next(iter(lengths.values()))
    if n == 0:
        raise ValueError(f"{source}: no data rows")
    return n


def _check_where(source: str, name: str, arr: Array, bad: NDArray[np.bool_], need: str) -> None:
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"{source}: {name}[{i}] = {arr[i]:g} is out of range: {need}")


def _sigma(source: str, name: str, sigma: ArrayLike | None) -> Array | None:
    if sigma is None:
        return None
    s = _frozen_array(name, sigma, source)
    _check_where(source, name, s, s <= 0.0, "uncertainties must be > 0")
    return s


@dataclass(frozen=True)
class StaticData:
    """Static friction against waiting time.

    Parameters
    ----------
    t_w : array_like
        Waiting (hold) times, s, ``>= 0``.
    mu_s : array_like
        Static friction coefficients ``F_s/W``.
    sigma : array_like, optional
        One-standard-deviation uncertainty of ``mu_s`` (``> 0``); ``None`` if not known.
    source : str
        Where the data came from (file name), used in messages.
    """

    t_w: Array
    mu_s: Array
    sigma: Array | None = None
    source: str = "<static data>"
    kind: ClassVar[str] = "static"
    x_name: ClassVar[str] = "t_w"
    y_name: ClassVar[str] = "mu_s"
    x_unit: ClassVar[str] = "s"

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "t_w", _frozen_array("t_w", self.t_w, self.source))
        set_(self, "mu_s", _frozen_array("mu_s", self.mu_s, self.source))
        set_(self, "sigma", _sigma(self.source, "sigma_mu_s", self.sigma))
        _check_lengths(self.source, t_w=self.t_w, mu_s=self.mu_s, sigma=self.sigma)
        _check_where(self.source, "t_w", self.t_w, self.t_w < 0.0, "waiting times must be >= 0")

    @property
    def x(self) -> Array:
        """The independent variable (``t_w``, s)."""
        return self.t_w

    @property
    def y(self) -> Array:
        """The measured friction coefficient."""
        return self.mu_s

    def __len__(self) -> int:
        return len(self.t_w)


@dataclass(frozen=True)
class SteadyData:
    """Steady dynamic friction against sliding velocity.

    Parameters
    ----------
    V : array_like
        Sliding velocities, m/s, ``> 0``.
    mu_d : array_like
        Steady friction coefficients ``F_d/W``.
    sigma : array_like, optional
        One-standard-deviation uncertainty of ``mu_d`` (``> 0``).
    source : str
        Where the data came from (file name).
    """

    V: Array
    mu_d: Array
    sigma: Array | None = None
    source: str = "<steady data>"
    kind: ClassVar[str] = "steady"
    x_name: ClassVar[str] = "V"
    y_name: ClassVar[str] = "mu_d"
    x_unit: ClassVar[str] = "m/s"

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "V", _frozen_array("V", self.V, self.source))
        set_(self, "mu_d", _frozen_array("mu_d", self.mu_d, self.source))
        set_(self, "sigma", _sigma(self.source, "sigma_mu_d", self.sigma))
        _check_lengths(self.source, V=self.V, mu_d=self.mu_d, sigma=self.sigma)
        _check_where(self.source, "V", self.V, self.V <= 0.0, "sliding velocities must be > 0")

    @property
    def x(self) -> Array:
        """The independent variable (``V``, m/s)."""
        return self.V

    @property
    def y(self) -> Array:
        return self.mu_d

    def __len__(self) -> int:
        return len(self.V)


@dataclass(frozen=True)
class SeriesData:
    """A friction transient: friction against time under a prescribed load-point velocity.

    Parameters
    ----------
    t : array_like
        Times, s, strictly increasing.
    v_load : array_like
        Load-point velocity at each time, m/s, ``>= 0`` (0: hold). It is read as piecewise
        constant and right-continuous: a new value holds from the first sample that shows it
        (see :meth:`segments`).
    mu : array_like
        Friction coefficient.
    sigma : array_like, optional
        One-standard-deviation uncertainty of ``mu`` (``> 0``).
    source : str
        Where the data came from (file name).
    """

    t: Array
    v_load: Array
    mu: Array
    sigma: Array | None = None
    source: str = "<series data>"
    kind: ClassVar[str] = "series"
    x_name: ClassVar[str] = "t"
    y_name: ClassVar[str] = "mu"
    x_unit: ClassVar[str] = "s"

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "t", _frozen_array("t", self.t, self.source))
        set_(self, "v_load", _frozen_array("v_load", self.v_load, self.source))
        set_(self, "mu", _frozen_array("mu", self.mu, self.source))
        set_(self, "sigma", _sigma(self.source, "sigma_mu", self.sigma))
        n = _check_lengths(self.source, t=self.t, v_load=self.v_load, mu=self.mu,
                           sigma=self.sigma)
        _check_where(self.source, "v_load", self.v_load, self.v_load < 0.0,
                     "load velocities must be >= 0")
        if n > 1:
            bad = np.concatenate([[False], np.diff(self.t) <= 0.0])
            _check_where(self.source, "t", self.t, bad, "times must increase strictly")
        if self.v_load[0] <= 0.0:
            raise ValueError(f"{self.source}: the series starts with v_load = 0: it must start "
                             "sliding (the fit starts from steady sliding at v_load[0])")

    @property
    def x(self) -> Array:
        """The independent variable (``t``, s)."""
        return self.t

    @property
    def y(self) -> Array:
        return self.mu

    def __len__(self) -> int:
        return len(self.t)

    def segments(self) -> tuple[Array, Array]:
        """The load program as constant-velocity stretches (ours).

        Returns ``(durations, velocities)``: a stretch starts at the first sample of each run of
        equal ``v_load`` and lasts until the first sample of the next run (the last one until
        the last sample; a single-sample final run is given the median sampling interval).
        Times are counted from ``t[0]``. A change of velocity is thus placed at the first
        sample showing it: record a sample at each change (a step between samples is only
        located to within one sampling interval, which biases a fit of the transient).
        """
        change = np.flatnonzero(np.diff(self.v_load) != 0.0) + 1
        starts = np.concatenate([[0], change])
        t_start = self.t[starts]
        t_end = np.concatenate([t_start[1:], [self.t[-1]]])
        dur = t_end - t_start
        if dur[-1] <= 0.0:
            dur[-1] = float(np.median(np.diff(self.t))) if len(self.t) > 1 else 1.0
        return dur, self.v_load[starts].copy()


Dataset = StaticData | SteadyData | SeriesData
"""Any of the three data-set types."""

# ----------------------------------------------------------------------------- CSV reading
_HEADER = re.compile(r"^\s*([^\[\]]*?)\s*(?:\[\s*([^\[\]]*?)\s*\])?\s*$")

# canonical column -> (kind of unit, accepted spellings of the name)
_COLUMNS: dict[str, tuple[str, tuple[str, ...]]] = {
    "t_w": ("time", ("t_w", "tw")),
    "mu_s": ("none", ("mu_s",)),
    "sigma_mu_s": ("none", ("sigma_mu_s",)),
    "V": ("velocity", ("v",)),
    "mu_d": ("none", ("mu_d",)),
    "sigma_mu_d": ("none", ("sigma_mu_d",)),
    "t": ("time", ("t",)),
    "v_load": ("velocity", ("v_load",)),
    "mu": ("none", ("mu",)),
    "sigma_mu": ("none", ("sigma_mu",)),
}
_KINDS: dict[str, tuple[str, ...]] = {
    "series": ("t", "v_load", "mu"),
    "static": ("t_w", "mu_s"),
    "steady": ("V", "mu_d"),
}
_SIGMA = {"static": "sigma_mu_s", "steady": "sigma_mu_d", "series": "sigma_mu"}


def _unit_factor(unit: str, kind: str, where: str) -> float:
    u = unit.strip()
    if kind == "none":
        if u in _DIMENSIONLESS:
            return 1.0
        raise ValueError(f"{where}: unit [{unit}] is not allowed: this column is dimensionless "
                         "(no unit, [], [1] or [-])")
    if u == "":
        return 1.0
    if kind == "time":
        if u in TIME_UNITS:
            return TIME_UNITS[u]
        raise ValueError(f"{where}: unknown time unit [{unit}]: allowed "
                         f"{', '.join(TIME_UNITS)}")
    parts = u.split("/")
    if len(parts) == 2 and parts[0].strip() in LENGTH_UNITS and parts[1].strip() in TIME_UNITS:
        return LENGTH_UNITS[parts[0].strip()] / TIME_UNITS[parts[1].strip()]
    raise ValueError(f"{where}: unknown velocity unit [{unit}]: allowed length/time with length "
                     f"{', '.join(LENGTH_UNITS)} and time {', '.join(TIME_UNITS)} (e.g. um/s)")


def _parse_header(cells: list[str], src: str, line: int) -> dict[str, tuple[int, float]]:
    """Map canonical column names to ``(index, SI factor)``."""
    found: dict[str, tuple[int, float]] = {}
    for j, cell in enumerate(cells):
        m = _HEADER.match(cell)
        where = f"{src}, line {line}, column {j + 1} ({cell.strip()!r})"
        if m is None:
            raise ValueError(f"{where}: cannot read the column name and unit")
        name, unit = m.group(1).strip().lower(), m.group(2)
        for canon, (ukind, spellings) in _COLUMNS.items():
            if name in spellings:
                if canon in found:
                    raise ValueError(f"{where}: column {canon} appears twice")
                factor = _unit_factor(unit or "", ukind, where)
                found[canon] = (j, factor)
                break
        # any other column is ignored, whatever its unit
    return found


def csv_separator(header: str) -> str:
    """The separator of a CSV file of ours, from its header line: ``";"`` (its numbers then
    carry decimal commas) where the line holds a ``;`` and no ``,``, else ``","``.

    Ours: a spreadsheet in a European locale saves "CSV" with semicolons because the comma is
    its decimal mark; a comma-separated header never holds a ``;`` (no name or unit of
    :mod:`dryfriction.records.data` has one)."""
    return ";" if ";" in header and "," not in header else ","


def read_csv(path: str | os.PathLike[str]) -> Dataset:
    """Read a friction data set from a CSV file (see the module docstring for the format).

    Parameters
    ----------
    path : str or path-like
        The CSV file.

    Returns
    -------
    StaticData, SteadyData or SeriesData
        Chosen by the columns present (``t, v_load, mu`` first, then ``t_w, mu_s``, then
        ``V, mu_d``); values in SI.

    Raises
    ------
    ValueError
        Naming the file, line and column of the first problem.
    """
    path = Path(path)
    src = str(path)
    check_text_file(path)  # gzip, UTF-16: named, not decoded
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError:
        raise ValueError(f"{src}: not a UTF-8 text file") from None
    header: list[str] | None = None
    header_line = 0
    rows: list[tuple[int, list[str]]] = []
    first = next((ln for ln in text.splitlines()
                  if ln.strip() and not ln.lstrip().startswith("#")), "")
    sep = csv_separator(first)
    for lineno, cells in enumerate(csv.reader(text.splitlines(), delimiter=sep), start=1):
        if not cells or all(c.strip() == "" for c in cells) or cells[0].lstrip().startswith("#"):
            continue
        if header is None:
            header, header_line = cells, lineno
        else:
            rows.append((lineno, cells))
    if header is None:
        raise ValueError(f"{src}: empty file: expected a header line with column names")
    cols = _parse_header(header, src, header_line)
    kind = next((k for k, need in _KINDS.items() if all(c in cols for c in need)), None)
    if kind is None:
        have = [c.strip() for c in header]
        wanted = "; ".join(", ".join(n) for n in _KINDS.values())
        raise ValueError(f"{src}, line {header_line}: missing columns: need one of "
                         f"({wanted}); found {', '.join(have)}")
    for other, need in _KINDS.items():
        if other != kind and all(c in cols for c in need):
            raise ValueError(f"{src}, line {header_line}: columns for both {kind} and {other} "
                             "data: one kind of data per file")
    if not rows:
        raise ValueError(f"{src}: no data rows after the header (line {header_line})")
    wanted_cols = list(_KINDS[kind]) + ([_SIGMA[kind]] if _SIGMA[kind] in cols else [])
    values: dict[str, list[float]] = {c: [] for c in wanted_cols}
    for lineno, cells in rows:
        if len(cells) != len(header):
            raise ValueError(f"{src}, line {lineno}: {len(cells)} cells, the header has "
                             f"{len(header)}")
        for c in wanted_cols:
            j, factor = cols[c]
            cell = cells[j].strip()
            where = f"{src}, line {lineno}, column {j + 1} ({c})"
            if cell == "":
                raise ValueError(f"{where}: empty cell")
            try:
                # decimal commas with semicolons (csv_separator); the cell is named as written
                x = float(cell.replace(",", ".") if sep == ";" else cell)
            except ValueError:
                raise ValueError(f"{where}: {cell!r} is not a number") from None
            if math.isnan(x):
                raise ValueError(f"{where}: NaN is not allowed")
            if not math.isfinite(x):
                raise ValueError(f"{where}: {cell!r} is not finite")
            if c == "t_w" and x < 0.0:
                raise ValueError(f"{where}: negative waiting time {cell}")
            if c == "V" and x <= 0.0:
                raise ValueError(f"{where}: sliding velocity {cell} must be > 0")
            if c == "v_load" and x < 0.0:
                raise ValueError(f"{where}: negative load velocity {cell}")
            if c.startswith("sigma") and x <= 0.0:
                raise ValueError(f"{where}: uncertainty {cell} must be > 0")
            if c == "t" and values["t"] and x * factor <= values["t"][-1]:
                raise ValueError(f"{where}: time {cell} does not increase")
            values[c].append(x * factor)
    sigma = values.get(_SIGMA[kind])
    if kind == "static":
        return StaticData(values["t_w"], values["mu_s"], sigma, src)
    if kind == "steady":
        return SteadyData(values["V"], values["mu_d"], sigma, src)
    return SeriesData(values["t"], values["v_load"], values["mu"], sigma, src)
