"""Argument checks shared by every public entry point.

Every check raises :class:`ValueError` naming the parameter, the offending value and the
allowed range, before any work starts. The CLI turns these into one line and exit code 2.
"""

from __future__ import annotations

import dataclasses
import importlib.util
import math
import os
import re
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "Array",
    "check_alpha",
    "check_range",
    "check_scalar",
    "check_choice",
    "check_figure_format",
    "FIGURE_FORMATS",
    "DPI_RANGE",
    "check_broadcast",
    "check_finite_result",
    "check_memory",
    "check_time",
    "format_bytes",
    "memory_limit",
    "parse_bytes",
    "require_extra",
    "MissingExtraError",
    "MEMORY_ENV",
    "TIME_ENV",
    "TIME_LIMIT_S",
    "time_limit",
    "ALPHA_MIN",
    "EPS_MAX",
    "U_MIN",
    "U_MAX",
    "T_MAX",
    "FRICTION_MAX",
    "DIRECT_MAX",
    "check_direct",
    "Parameter",
    "REQUIRED",
    "declared",
]

Array = NDArray[np.float64]
"""The one alias for float arrays, used by every module's annotations."""

ALPHA_MIN: float = 1e-6
"""Smallest reduced trap stiffness accepted by the friction calculations: ``y_c ~ 1/(4 alpha)``
grows without bound as ``alpha -> 0`` and the force integrals overflow far below this."""

EPS_MAX: float = 1.0
"""Largest creep parameter ``eps = S/Y`` accepted: the activation stress ``S`` stays below the
hardness ``Y``. The paper's expansions need ``eps << 1``; the exact quadratures hold up to 1."""

U_MIN: float = 1e-30
"""Smallest reduced velocity ``u = V t0/a0`` accepted (``V = 1e-30 a0/t0``: far below any
experiment; the quadratures are checked against eq. 35 there)."""

U_MAX: float = 1e30
"""Largest reduced velocity accepted (``mu_d`` equals its limit 1 to rounding long before)."""

T_MAX: float = 1e30
"""Largest reduced waiting time ``t_w/t0`` accepted."""

FRICTION_MAX: float = 10.0
"""Largest friction coefficient ``F/W`` a run's inputs may set (ours): ``mu_el = F_el/W`` of
the trap model and ``|mu0|`` of rate-and-state. Measured coefficients of solids stay below
about 5 (clean metals in vacuum), and the fits bound ``mu_el`` to 10 already; beyond it a run
reports a friction no apparatus shows (``mu_el = 1e300`` gave
``mu_s = 1.3e300`` with exit 0)."""


def _fmt_range(lo: float | None, hi: float | None, lo_open: bool, hi_open: bool) -> str:
    parts = []
    if lo is not None:
        parts.append(f"{'>' if lo_open else '>='} {lo:g}")
    if hi is not None:
        parts.append(f"{'<' if hi_open else '<='} {hi:g}")
    return "finite and " + " and ".join(parts) if parts else "finite"


def check_range(
    name: str,
    value: ArrayLike,
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
) -> NDArray[np.float64]:
    """Return ``value`` as a float array after checking every element lies in the range.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : array_like
        Scalar or array of real numbers.
    lo, hi : float or None
        Bounds; ``None`` means unbounded on that side.
    lo_open, hi_open : bool
        Whether the bound itself is excluded.

    Raises
    ------
    ValueError
        If any element is non-finite, non-real or outside the range.
    """
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} is not a real number") from None
    bad = ~np.isfinite(arr)
    if lo is not None:
        bad |= (arr <= lo) if lo_open else (arr < lo)
    if hi is not None:
        bad |= (arr >= hi) if hi_open else (arr > hi)
    if np.any(bad):
        first = arr[bad].flat[0] if arr.ndim else float(arr)
        raise ValueError(
            f"{name} = {first:g} is out of range: allowed {_fmt_range(lo, hi, lo_open, hi_open)}"
        )
    return arr


def check_scalar(
    name: str,
    value: float,
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
) -> float:
    """Like :func:`check_range` for a single real number; returns a Python float."""
    if type(value) is float and math.isfinite(value) and (
            lo is None or (value > lo if lo_open else value >= lo)) and (
            hi is None or (value < hi if hi_open else value <= hi)):
        # a Python float in range, without NumPy (about 8 us a call otherwise; a fit's forward
        # runs check tens of thousands: every segment of a measured drive's programs); out of
        # range, or another type, it takes check_range's way, and its message
        return value
    arr = check_range(name, value, lo, hi, lo_open=lo_open, hi_open=hi_open)
    if arr.ndim != 0:
        raise ValueError(f"{name} must be a single number, got an array of shape {arr.shape}")
    out = float(arr)
    assert math.isfinite(out)
    return out


def check_choice(name: str, value: str, choices: tuple[str, ...]) -> str:
    """Check that ``value`` is one of ``choices``."""
    if value not in choices:
        raise ValueError(f"{name} = {value!r} is not allowed: choose one of {', '.join(choices)}")
    return value


FIGURE_FORMATS: tuple[str, ...] = ("png", "pdf", "svg")
"""File formats of the figures (``--format``); pdf and svg are vector graphics."""
DPI_RANGE: tuple[int, int] = (50, 1200)
"""Resolutions a figure may be rendered at (``--dpi``): 150 by default (screen, slides),
300-600 in print."""


def check_figure_format(fmt: str, dpi: float | None = None) -> tuple[str, int | None]:
    """``(fmt, dpi)`` checked, before any figure is drawn (no matplotlib needed): ``fmt`` one
    of :data:`FIGURE_FORMATS`, ``dpi`` a whole number in :data:`DPI_RANGE` or ``None`` (the
    figure style's default)."""
    if fmt not in FIGURE_FORMATS:
        raise ValueError(f"--format {fmt!r} is not allowed: choose one of "
                         f"{', '.join(FIGURE_FORMATS)}")
    if dpi is None:
        return fmt, None
    lo, hi = DPI_RANGE
    if not (lo <= dpi <= hi and float(dpi).is_integer()):
        raise ValueError(f"--dpi {dpi:g} is out of range: allowed a whole number in [{lo}, {hi}]")
    return fmt, int(dpi)


def check_broadcast(**arrays: ArrayLike) -> tuple[int, ...]:
    """Broadcast shape of the named arrays, or a ``ValueError`` naming them and their shapes.

    ``check_broadcast(T=T, eps=eps)`` raises ``T has shape (3,) and eps (2,): they do not
    broadcast`` instead of NumPy's anonymous message.
    """
    shapes = {k: np.shape(v) for k, v in arrays.items()}
    try:
        return tuple(np.broadcast_shapes(*shapes.values()))
    except ValueError:
        items = [f"{k} {s}" for k, s in shapes.items()]
        first, rest = items[0].replace(" ", " has shape ", 1), items[1:]
        listed = first if not rest else ", ".join([first, *rest[:-1]]) + " and " + rest[-1]
        raise ValueError(f"{listed}: they do not broadcast") from None


def check_finite_result(what: str, result: ArrayLike, **inputs: ArrayLike) -> NDArray[np.float64]:
    """Return ``result`` if every element is finite; otherwise a ``ValueError`` naming the inputs.

    The last line of defence behind the range checks: a computation never hands back NaN or
    infinity as if it were a number.
    """
    arr = np.asarray(result, float)
    bad = ~np.isfinite(arr)
    if np.any(bad):
        shape = arr.shape
        idx = np.unravel_index(int(np.argmax(bad)), shape) if shape else ()
        where = ", ".join(
            f"{k} = {float(np.broadcast_to(np.asarray(v, float), shape)[idx]):g}"
            for k, v in inputs.items()
        )
        raise ValueError(f"{what} is not finite at {where}: these inputs are beyond the range "
                         "where the numerics hold")
    return arr


def check_alpha(alpha: float) -> float:
    """Reduced trap stiffness of a pinning trap, ``ALPHA_MIN <= alpha < 1`` (``alpha >= 1``:
    no pinning, no friction)."""
    return check_scalar("alpha", alpha, ALPHA_MIN, 1.0, hi_open=True)


DIRECT_MAX: float = 1.0
"""Largest direct-effect coefficient ``A = kT/(sigma_s0 v*)`` accepted: measured values are of
order 0.01; ``A = 1`` already doubles the junction strength per e-fold of velocity, far beyond
the thermally activated (Eyring) regime the rheology describes."""


def check_direct(direct: float, v_ref: float) -> tuple[float, float]:
    """Direct-effect coefficient ``0 <= direct <= DIRECT_MAX`` and reference velocity
    ``U_MIN <= v_ref <= U_MAX`` (reduced ``a0/t0``), as floats."""
    return (check_scalar("direct", direct, 0.0, DIRECT_MAX),
            check_scalar("v_ref", v_ref, U_MIN, U_MAX))


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


REQUIRED: Any = _Required()
"""The default of a :class:`Parameter` that has none (the caller must give it)."""


@dataclass(frozen=True)
class Parameter:
    """One declared parameter of a model object: its default and its allowed values (issue
    26; the model objects read both from a table of these, in the manner of scikit-learn's
    declared parameter constraints).

    Parameters
    ----------
    name : str
        The name a user types (Python keyword; the CLI option is ``--name`` with ``-``).
    default : float, str, bool, None or REQUIRED
        The one default of the package; ``None`` for an optional part left out (then not
        checked); :data:`REQUIRED` when the caller must give it.
    lo, hi : float or None
        Bounds (``None``: unbounded); ``lo_open``/``hi_open`` exclude the bound itself.
    choices : tuple of str, optional
        For a named choice instead of a number.
    boolean : bool
        For a switch (``True``/``False``) instead of a number.
    meaning : str
        What the parameter is, with its unit.
    """

    name: str
    default: Any = REQUIRED
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    choices: tuple[str, ...] = ()
    boolean: bool = False
    meaning: str = ""

    def check(self, value: Any) -> Any:
        """``value`` checked (a float, the chosen name, a bool, or ``None`` where that is the
        default): a ``ValueError`` naming the parameter and the allowed values otherwise."""
        if value is None and self.default is None:
            return None
        if self.choices:
            return check_choice(self.name, value, self.choices)
        if self.boolean:
            if not isinstance(value, (bool, np.bool_)):
                raise ValueError(f"{self.name} = {value!r} is not allowed: true or false")
            return bool(value)
        return check_scalar(self.name, value, self.lo, self.hi,
                            lo_open=self.lo_open, hi_open=self.hi_open)


def declared(table: dict[str, Parameter], name: str) -> Any:
    """A dataclass field whose default is ``table[name].default`` (none when required)."""
    d = table[name].default
    return dataclasses.field() if d is REQUIRED else dataclasses.field(default=d)


# ---------------------------------------------------------------- memory budget

MEMORY_ENV = "DRYFRICTION_MEMORY_LIMIT"
"""Environment variable overriding the memory limit of one run (``"8GiB"``, ``"500MB"``,
``"1e9"`` bytes)."""

MEMORY_FRACTION = 0.5
"""Default limit: this fraction of the memory the machine has available (other processes, and
the copies a run makes when it writes its results, need the rest)."""

_UNITS = {"": 1, "B": 1, "K": 1e3, "KB": 1e3, "M": 1e6, "MB": 1e6, "G": 1e9, "GB": 1e9,
          "T": 1e12, "TB": 1e12, "KIB": 2**10, "MIB": 2**20, "GIB": 2**30, "TIB": 2**40}


def parse_bytes(text: str, name: str = MEMORY_ENV) -> float:
    """A size such as ``"8GiB"``, ``"512 MB"`` or ``"1e9"`` (bytes) as a number of bytes.

    Raises
    ------
    ValueError
        Naming ``name`` unless the text is a positive finite number with a known unit.
    """
    m = re.fullmatch(r"\s*([0-9.eE+-]+)\s*([A-Za-z]*)\s*", text)
    value = math.nan
    if m and m.group(2).upper() in _UNITS:
        try:
            value = float(m.group(1)) * _UNITS[m.group(2).upper()]
        except ValueError:
            value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name} = {text!r} is not allowed: a positive size such as 8GiB, "
                         "512MB or 1e9 (bytes)")
    return value


def format_bytes(n: float) -> str:
    """``2.9 TiB``-style size of ``n`` bytes (binary units)."""
    if not math.isfinite(n):
        return "more than any machine has"
    if n >= 2**50:
        return f"{n / 2**40:.1e} TiB"
    for unit, size in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if n >= size:
            return f"{n / size:.1f} {unit}"
    return f"{n:.0f} B"


def _available_memory() -> float | None:
    """Bytes of memory available to a new allocation (``MemAvailable``), else physical memory."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024.0
    except (OSError, ValueError, IndexError):
        pass
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (AttributeError, ValueError, OSError):
        return None


def memory_limit() -> float:
    """Bytes one run may plan to hold: :data:`MEMORY_ENV` if set, else :data:`MEMORY_FRACTION`
    of the available memory (8 GiB where the machine does not say)."""
    text = os.environ.get(MEMORY_ENV, "").strip()
    if text:
        return parse_bytes(text)
    avail = _available_memory()
    return MEMORY_FRACTION * avail if avail else 8.0 * 2**30


def check_memory(what: str, need: float, hint: str) -> None:
    """Refuse a run whose estimate ``need`` (bytes) is over :func:`memory_limit`.

    The message reads ``{what} ({size}), more than the limit {limit}: {hint} or set
    DRYFRICTION_MEMORY_LIMIT``; ``what`` names the key and what it gives, ``hint`` the key to
    change.
    """
    limit = memory_limit()
    if not need <= limit:  # NaN (an estimate that overflowed) is refused too
        raise ValueError(f"{what} ({format_bytes(need)}), more than the limit "
                         f"{format_bytes(limit)}: {hint} or set {MEMORY_ENV}")


# ---------------------------------------------------------------- time budget (issue 24)

TIME_ENV = "DRYFRICTION_TIME_LIMIT"
"""Environment variable overriding the longest estimated run, in seconds (``"7200"``)."""

TIME_LIMIT_S = 3600.0
"""Default longest run, seconds of CPU on the development machine, estimated before any work
(ours): past an hour a run is refused rather than left to look hung; a longer one is asked for
with :data:`TIME_ENV`. The estimates are lower bounds (the work no run can avoid), so a run
is never refused for a cost it would not have."""


def time_limit() -> float:
    """Seconds one run may plan to take: :data:`TIME_ENV` if set, else :data:`TIME_LIMIT_S`."""
    text = os.environ.get(TIME_ENV, "").strip()
    if not text:
        return TIME_LIMIT_S
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not value > 0.0:
        raise ValueError(f"{TIME_ENV} = {text!r} is not allowed: a positive number of seconds")
    return value


def _format_seconds(s: float) -> str:
    if not math.isfinite(s):
        return "longer than any machine runs"
    if s >= 86400.0:
        return f"{s / 86400.0:.2g} days"
    if s >= 3600.0:
        return f"{s / 3600.0:.2g} h"
    return f"{s / 60.0:.2g} min" if s >= 60.0 else f"{s:.2g} s"


def check_time(what: str, seconds: float, hint: str) -> None:
    """Refuse a run whose estimated time ``seconds`` is over :func:`time_limit`.

    The message reads ``{what}: about {time} of computing, more than the limit {limit}: {hint}
    or set DRYFRICTION_TIME_LIMIT`` (one line); ``what`` names the key and what it gives.
    """
    limit = time_limit()
    if not seconds <= limit:  # NaN (an estimate that overflowed) is refused too
        raise ValueError(f"{what}: about {_format_seconds(seconds)} of computing, more than "
                         f"the limit {_format_seconds(limit)}: {hint} or set {TIME_ENV} "
                         "(seconds)")


class MissingExtraError(ImportError, ValueError):
    """An optional dependency group (``pip install 'dryfriction[NAME]'``) is not installed.

    Also a :class:`ValueError`, so the CLI reports it in one line (exit code 2) like bad input.
    """


def require_extra(extra: str, modules: tuple[str, ...], purpose: str) -> None:
    """Raise :class:`MissingExtraError` naming the extra to install when any of ``modules``
    (top-level import names) is missing. Looks the modules up without importing them.

    Parameters
    ----------
    extra : str
        Name of the optional dependency group in ``pyproject.toml`` (e.g. ``"sweep"``).
    modules : tuple of str
        Top-level modules the feature imports.
    purpose : str
        What needs them, for the message ("a sweep").
    """
    missing = []
    for name in modules:
        try:
            found = importlib.util.find_spec(name) is not None
        except (ImportError, ValueError):  # a broken or half-removed install counts as missing
            found = False
        if not found:
            missing.append(name)
    if missing:
        raise MissingExtraError(
            f"{purpose} needs the optional packages {', '.join(missing)}: "
            f"pip install 'dryfriction[{extra}]'")
