"""Argument checks shared by every public entry point.

Every check raises :class:`ValueError` naming the parameter, the offending value and the
allowed range, before any work starts. The CLI turns these into one line and exit code 2.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "Array",
    "check_alpha",
    "check_range",
    "check_scalar",
    "check_choice",
    "check_broadcast",
    "check_finite_result",
    "ALPHA_MIN",
    "EPS_MAX",
    "U_MIN",
    "U_MAX",
    "T_MAX",
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
