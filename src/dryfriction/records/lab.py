"""Laboratory friction records as they come from the apparatus: reading, load program, steps.

A record is a text table (or a spreadsheet ``.xlsx`` or MATLAB ``.mat`` file, read as one:
:mod:`.labforms`) with one header line of column names, units in parentheses or square
brackets after the name (``Time(s)``, ``Displ(microns)``, ``Shear_stress[MPa]``), separated by
tabs, commas, semicolons or spaces (sniffed). Lines starting with ``#`` and blank lines are
skipped; a units row under the header (``s  um  -  MPa``) and trailing empty columns are
tolerated; a preamble above the header without ``#`` is skipped and said (:func:`_find_header`,
``LabRecord.notes``), and a row with a missing value (:data:`MISSING`) in a needed column is
dropped and counted, up to :data:`MISSING_MAX` of the rows. Columns are recognised by name,
case-insensitively (the *role* in brackets is the key of the column map):

* time (``time``): ``t``, ``Time``, ``time[s]``, ``elapsed_time``;
* load-point displacement (``disp``): ``Displ``, ``Disp``, ``LP_disp``, ``load_point``,
  ``displacement`` (a name with ``lp`` or ``load point`` wins over other displacements);
* load-point velocity (``velocity``), when the file gives it instead of a displacement:
  ``lp_velocity``, ``v_load``, ``velocity``;
* friction (``mu``): ``Friction``, ``mu``, ``cof``, ``friction_coefficient``;
* shear and normal stress or force (``shear``, ``normal``): ``Shear_stress``, ``tau``,
  ``Normal_stress``, ``EffectiveNormalstress``, ``sigma_n`` (an *effective* normal stress wins).
  Friction is shear over normal when there is no friction column (both stresses or both forces).

Units (SI without one): time ``s, ms, us, min, h``; length ``m, cm, mm, um, µm, micron(s), nm``;
velocity ``length/time`` (``um/s``); stress ``Pa, kPa, MPa, GPa``; force ``N, kN, MN``; friction
dimensionless (none, ``-`` or ``1``). The column map ``time=Time,disp=LP_disp:mm,...`` (CLI
``--columns``) names any column the guesses miss, with an optional unit after ``:``.

The load program is found from the displacement (:func:`detect_segments`) or given
(:func:`parse_segments`), and a multi-step record is cut into its velocity steps and
slide-hold-slide cycles (:func:`slice_steps`). Every refusal is a :class:`ValueError` naming the
file, the line (1-based) and the column.
"""

from __future__ import annotations

import io
import os
import re
from collections.abc import Callable, Mapping
from dataclasses import replace
from pathlib import Path
from types import MappingProxyType

import numpy as np

from ..io.textfile import HEAD_BYTES, check_text
from ..validation import FRICTION_MAX, Array, check_memory
from .artifacts import moves_backwards
from .data import LENGTH_UNITS, TIME_UNITS
from .detection import (
    Detection,
    backwards_message,
    detect_program,
    detect_segments,
    held_back_message,
    no_change_message,
)
from .labforms import FORMS, MATRIX_NOTE, PREAMBLE_MAX, read_table
from .labsteps import (
    SEGMENTS_SYNTAX,
    Segment,
    StepWindow,
    load_velocity_series,
    normal_change_text,
    normal_change_values,
    parse_segments,
    segments_spec,
    segments_table,
    slice_steps,
    write_segments_csv,
)
from .record import LabRecord

__all__ = [
    "LabRecord",
    "Segment",
    "StepWindow",
    "ROLES",
    "MIN_ROWS",
    "MISSING",
    "MISSING_MAX",
    "read_record",
    "apparatus_note",
    "assumed_units",
    "note_text",
    "APPARATUS_V_TYPICAL",
    "APPARATUS_X_TYPICAL",
    "FRICTION_MAX",
    "parse_column_map",
    "Detection",
    "detect_program",
    "detect_segments",
    "backwards_message",
    "held_back_message",
    "moves_backwards",
    "no_change_message",
    "parse_segments",
    "segments_table",
    "segments_spec",
    "write_segments_csv",
    "SEGMENTS_SYNTAX",
    "load_velocity_series",
    "slice_steps",
    "normal_change_values",
    "normal_change_text",
]

MIN_ROWS = 10
# FRICTION_MAX (validation): the largest |friction| a record may hold, as a run's inputs;
# measured coefficients lie between 0 and about 1.5, and a cell of 1e300 is a typo that,
# read as friction, overflowed the fit (rms = inf)
APPARATUS_V_MAX = 1e-2
"""Load velocity (m/s) above which a record is flagged as implausible for a friction
apparatus (ours: rotary shear reaches ~1 m/s, but a velocity-step record of 0.2 m/s is far
more often micrometres read as metres)."""
APPARATUS_X_MAX = 1.0
"""Load-point displacement span (m) above which a record is flagged likewise."""
"""Fewest data rows a record may have (fewer cannot show a transient)."""
APPARATUS_V_TYPICAL = (1e-9, 1e-3)
"""Load velocities (m/s) of the apparatus whose velocity-step records this package reads
(ours): servo-controlled biaxial (double-direct shear) and triaxial machines step between
about 0.01 um/s and 1 mm/s (1 nm/s: the slowest creep and hold tests). A record read with a
column *without a unit* is checked against this range and :data:`APPARATUS_X_TYPICAL`: where
its SI reading falls outside, the reading is flagged louder (a warning naming the unit that
would fit). Rotary-shear machines go beyond both (to m/s and metres): their records give the
unit (``--columns disp=NAME:m``), which silences it; a missing unit is never refused."""
APPARATUS_X_TYPICAL = 0.05
"""Load-point displacement span (m) of those apparatus (ours: a biaxial layer travels a few
cm at most, a triaxial saw-cut a few mm)."""
_SI_UNIT = {"time": "s", "disp": "m", "velocity": "m/s"}
_SI_WORD = {"time": "seconds", "disp": "metres", "velocity": "m/s"}

ROLES: dict[str, str] = {
    "time": "time",
    "disp": "load-point displacement",
    "velocity": "load-point velocity",
    "mu": "friction",
    "shear": "shear stress or force",
    "normal": "normal stress or force",
}
"""The column-map keys and what each column holds."""

_ALIASES = {"t": "time", "displacement": "disp", "lp": "disp", "load_point": "disp",
            "v": "velocity", "vel": "velocity", "v_load": "velocity", "friction": "mu",
            "tau": "shear", "sigma_n": "normal", "sn": "normal"}

_TIME = {**TIME_UNITS, "sec": 1.0, "hr": 3600.0}
_LENGTH = {**LENGTH_UNITS, "μm": 1e-6, "micron": 1e-6, "microns": 1e-6}
_STRESS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9}
_FORCE = {"N": 1.0, "kN": 1e3, "MN": 1e6}
_NONE = ("", "-", "1")


# ------------------------------------------------------------------------------ header
_CELL = re.compile(r"^(.*?)\s*[\(\[]\s*([^\(\)\[\]]*?)\s*[\)\]]\s*$")


def _split_cell(cell: str) -> tuple[str, str | None]:
    """``'Time (s)'`` -> ``('Time', 's')``; ``'Friction'`` -> ``('Friction', None)``."""
    m = _CELL.match(cell.strip())
    return (m.group(1).strip(), m.group(2)) if m else (cell.strip(), None)


def _key(name: str) -> str:
    k = name.lower().replace("µ", "mu").replace("μ", "mu")
    return re.sub(r"[^a-z0-9]", "", k)


def _guess_role(name: str) -> tuple[str | None, bool]:
    """(role, preferred) guessed from a column name (without its unit)."""
    k = _key(name)
    if re.fullmatch(r"t|times?\d*|timesec|elapsedtime|timeelapsed|runtime|testtime", k):
        return "time", False
    if re.search(r"vel|speed", k) or k in ("v", "vlp", "vload", "lpv"):
        return "velocity", "lp" in k or "loadpoint" in k
    if re.search(r"disp|loadpoint", k) or k in ("lp", "lpd", "x"):
        if re.search(r"vert|norm|thick|dil", k):
            return None, False
        return "disp", k.startswith("lp") or "loadpoint" in k
    if "fric" in k or k in ("mu", "cof", "coefficientoffriction"):
        return "mu", False
    if re.search(r"strain|rate|disp", k):
        return None, False
    if "shear" in k or k in ("tau", "ss"):
        return "shear", False
    if "normal" in k or k in ("sn", "sigman", "sigmaneff", "effsigman"):
        return "normal", "eff" in k
    return None, False


def _lookup(unit: str, table: Mapping[str, float]) -> float | None:
    if unit in table:
        return table[unit]
    folded = [k for k in table if k.casefold() == unit.casefold()]
    return table[folded[0]] if len(folded) == 1 else None


def _unit(role: str, unit: str, where: str) -> tuple[float, str]:
    """SI factor and kind (``time, length, velocity, stress, force, none``) of a unit."""
    u = unit.strip()
    if role == "mu":
        if u in _NONE:
            return 1.0, "none"
        raise ValueError(f"{where}: unit ({unit}) is not allowed: friction is dimensionless "
                         "(no unit, - or 1)")
    if u == "":
        return 1.0, {"time": "time", "disp": "length", "velocity": "velocity"}.get(role, "")
    tables: dict[str, dict[str, tuple[Mapping[str, float], str]]] = {
        "time": {"time": (_TIME, "time")},
        "disp": {"length": (_LENGTH, "length")},
        "shear": {"stress": (_STRESS, "stress"), "force": (_FORCE, "force")},
        "normal": {"stress": (_STRESS, "stress"), "force": (_FORCE, "force")},
    }
    if role == "velocity":
        num, _, den = u.partition("/")
        f_len, f_time = _lookup(num.strip(), _LENGTH), _lookup(den.strip(), _TIME)
        if f_len is not None and f_time is not None:
            return f_len / f_time, "velocity"
        raise ValueError(f"{where}: unknown velocity unit ({unit}): accepted length/time with "
                         f"length {', '.join(_LENGTH)} and time {', '.join(_TIME)} (e.g. um/s)")
    for table, kind in tables[role].values():
        f = _lookup(u, table)
        if f is not None:
            return f, kind
    accepted = ", ".join(k for table, _ in tables[role].values() for k in table)
    raise ValueError(f"{where}: unknown unit ({unit}) for the {ROLES[role]}: accepted "
                     f"{accepted}")


def parse_column_map(text: str) -> dict[str, str]:
    """Parse the CLI column map ``time=Time,disp=LP_disp:mm,mu=Friction``.

    Keys are the roles of :data:`ROLES` (``time, disp, velocity, mu, shear, normal``; also
    ``t, displacement, v, friction, tau, sigma_n``); a value is a header name, matched
    case-insensitively with or without its unit, optionally followed by ``:unit`` for a header
    that has none.

    Returns
    -------
    dict
        Role -> ``"name"`` or ``"name:unit"``.

    Raises
    ------
    ValueError
        For an item that is not ``key=name``, an unknown key, or a key given twice.
    """
    out: dict[str, str] = {}
    for item in (s.strip() for s in text.split(",")):
        if not item:
            continue
        key, sep, value = item.partition("=")
        key = key.strip().lower()
        key = _ALIASES.get(key, key)
        if not sep or not value.strip():
            raise ValueError(f"--columns {item!r}: expected key=name, e.g. disp=LP_disp:mm")
        if key not in ROLES:
            raise ValueError(f"--columns {item!r}: unknown key {key!r}: allowed "
                             f"{', '.join(ROLES)}")
        if key in out:
            raise ValueError(f"--columns: {key} is given twice")
        out[key] = value.strip()
    return out


# ------------------------------------------------------------------------------ reading
def _sniff(header: str, sample: str) -> str | None:
    """The delimiter of the data lines (``None``: runs of spaces)."""
    for d in ("\t", ";", ","):
        if d in sample and (d in header or d != ","):
            return d
    return None


def _cells(line: str, delim: str | None) -> list[str]:
    cells = line.split(delim) if delim else line.split()
    while cells and not cells[-1].strip():
        cells.pop()  # trailing empty columns
    return cells


def _is_number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def _header_cells(line: str, delim: str | None) -> list[str]:
    cells = _cells(line, delim)
    if delim is None:  # ``Shear_stress (MPa)``: a lone unit belongs to the name before it
        merged: list[str] = []
        for c in cells:
            if merged and re.fullmatch(r"[\(\[].*[\)\]]", c):
                merged[-1] += " " + c
            else:
                merged.append(c)
        cells = merged
    return cells


MISSING = ("", "nan", "na", "n/a", "#n/a", "null", "none")
"""Cells read as a missing value (case-insensitive): empty, NaN and the spreadsheets' marks.
A row with one in a needed column is dropped and counted (:data:`MISSING_MAX`)."""
MISSING_MAX = 0.05
"""Largest fraction of a record's rows that may be dropped for a missing value in a needed
column (ours: a few dropouts of a logger are common; more is a column that was not recorded
throughout, which dropping would hide): above it the record is refused."""


# PREAMBLE_MAX (most lines above a header skipped as a preamble) is labforms': a spreadsheet's
# header is found by the same rule (labforms._header_index), and labforms cannot import this


def _is_missing(cell: str) -> bool:
    return cell.strip().lower() in MISSING


def _numeric_line(s: str) -> bool:
    """A data row: at least two cells, all numbers or missing marks, at least one a number."""
    cells = [c for c in re.split(r"[\t;, ]+", s.strip()) if c]
    return (len(cells) >= 2 and all(_is_number(c) or _is_missing(c) for c in cells)
            and any(_is_number(c) and not _is_missing(c) for c in cells))


def _unit_cell(cell: str) -> bool:
    u = cell.strip().strip("()[]").strip()
    if u in _NONE:
        return True
    num, sep, den = u.partition("/")
    if sep:
        return (_lookup(num.strip(), _LENGTH) is not None
                and _lookup(den.strip(), _TIME) is not None)
    return any(_lookup(u, table) is not None for table in (_TIME, _LENGTH, _STRESS, _FORCE))


def _find_header(head: list[str], columns: Mapping[str, str] | None
                 ) -> tuple[str | None, int, str | None, int, tuple[str, int] | None,
                            list[tuple[int, str]]]:
    """``(header, its line, first data line, its line, units row, preamble)`` of a text record.

    The header is, of the lines above the first two that read as numbers (comment and blank
    lines aside), the first with the most column names the reader recognises (or the column
    map names); without any, the last of them (above a units row, ``s um - MPa``). A line
    right under it with no number, or only units, is a units row; the data start under
    those. The lines above the header are a preamble (an instrument's ``Experiment p4966``,
    ``Sample rate: 50 Hz`` without ``#``): skipped, and returned to be reported. Lines are
    1-based, as an editor counts.
    """
    lines = [(n, ln) for n, ln in enumerate(head, start=1)
             if ln.strip() and not ln.strip().startswith("#")]
    if not lines:
        return None, 0, None, 0, None, []
    cache: dict[int, bool] = {}

    def numeric(k: int) -> bool:  # on demand: a file of text cells is not scanned twice
        if k not in cache:
            cache[k] = _numeric_line(lines[k][1])
        return cache[k]

    # the preamble is looked for in the first PREAMBLE_MAX lines (a file whose rows hold a
    # text cell has no line of numbers: its lines are not each scored as a header)
    top = min(len(lines), PREAMBLE_MAX + 2)
    start = next((k for k in range(top) if numeric(k) and (k + 1 == len(lines)
                                                           or numeric(k + 1))), len(lines))
    named = {(v.rpartition(":")[0] if ":" in v else v).strip().lower()
             for v in (columns or {}).values()}
    sample_line = lines[start][1] if start < len(lines) else lines[-1][1]

    def cells(line: str) -> list[str]:
        return _header_cells(line, _sniff(line, sample_line))

    def names(line: str) -> int:
        parts = [_split_cell(c)[0] for c in cells(line)]
        return sum(_guess_role(c)[0] is not None or c.lower() in named for c in parts)

    def units_only(line: str) -> bool:
        return bool(cells(line)) and all(_unit_cell(c) for c in cells(line))

    cands = list(range(min(max(start, 1), PREAMBLE_MAX + 1)))
    score = [names(lines[k][1]) for k in cands]
    if max(score) > 0:
        h = score.index(max(score))
    elif start < len(lines):  # no name recognised: the line above the data (and units)
        h = start - 1
        if h >= 1 and units_only(lines[h][1]):
            h -= 1
    else:
        h = 0
    units_row = None
    k = h + 1
    if k < len(lines) and not numeric(k) and (units_only(lines[k][1]) or not any(
            _is_number(c) for c in re.split(r"[\t;, ]+", lines[k][1].strip()))):
        units_row, k = (lines[k][1], lines[k][0]), k + 1
    sample = lines[k] if k < len(lines) else (0, None)
    return lines[h][1], lines[h][0], sample[1], sample[0], units_row, lines[:h]


def _decode(raw: bytes) -> str:
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        return raw.decode("latin-1")  # older instruments write µ as one byte


def _assign(
    src: str, hline: int, names: list[str], columns: Mapping[str, str] | None
) -> tuple[dict[str, int], dict[str, str | None]]:
    """Column index and unit override of each role, from the map then from the names."""
    idx: dict[str, int] = {}
    forced: dict[str, str | None] = {}
    found = ", ".join(repr(n) for n in names)
    for role, spec in (columns or {}).items():
        role = _ALIASES.get(role, role)
        if role not in ROLES:
            raise ValueError(f"{src}: column map key {role!r} is unknown: allowed "
                             f"{', '.join(ROLES)}")
        name, unit = spec, None
        if ":" in spec:
            name, _, unit = spec.rpartition(":")
        hits = [j for j, n in enumerate(names)
                if name.strip().lower() in (n.strip().lower(), _split_cell(n)[0].lower())]
        if not hits:
            raise ValueError(f"{src}, line {hline}: --columns {role}={spec}: no column "
                             f"{name!r}; found {found}")
        idx[role], forced[role] = hits[0], unit
    guesses: dict[str, list[tuple[int, bool]]] = {}
    for j, n in enumerate(names):
        role, preferred = _guess_role(_split_cell(n)[0])
        if role is not None and j not in idx.values():
            guesses.setdefault(role, []).append((j, preferred))
    for role, cands in guesses.items():
        if role in idx:
            continue
        best = [c for c in cands if c[1]] or cands
        if len(best) > 1:
            which = " and ".join(f"{names[j]!r} (column {j + 1})" for j, _ in best)
            raise ValueError(f"{src}, line {hline}: {which} could each be the {ROLES[role]}: "
                             f"choose one with --columns {role}=NAME")
        idx[role] = best[0][0]
    if "time" not in idx:
        raise ValueError(f"{src}, line {hline}: no time column: found {found}; name it with "
                         "--columns time=NAME")
    if "disp" not in idx and "velocity" not in idx:
        raise ValueError(f"{src}, line {hline}: no load-point displacement (or velocity) column: "
                         f"found {found}; name it with --columns disp=NAME (or velocity=NAME)")
    if "mu" not in idx and not ("shear" in idx and "normal" in idx):
        missing = "normal" if "shear" in idx else "shear"
        raise ValueError(f"{src}, line {hline}: no friction column (nor shear and normal "
                         f"stress: no {ROLES[missing]} column): found {found}; name it with "
                         f"--columns mu=NAME (or shear=NAME,normal=NAME)")
    return idx, forced


def assumed_units(record: LabRecord) -> dict[str, str]:
    """The SI unit the reader assumed for each of the record's time, displacement and velocity
    columns that has no unit in the file (``{"disp": "m"}``); ``{}`` when every one has its
    own. Friction is dimensionless; stresses and forces enter only as their ratio."""
    return {role: _SI_UNIT[role] for role in ("time", "disp", "velocity")
            if role in record.columns and not record.units.get(role, "")}


def _speeds(v: float, span: float) -> str:
    """``up to 10 um/s over 0.94 mm``: a velocity and a span in the units a lab uses."""
    def length(x: float, per: str = "") -> str:
        for unit, f in (("m", 1.0), ("mm", 1e-3), ("um", 1e-6), ("nm", 1e-9)):
            if x >= f or unit == "nm":
                return f"{x / f:.3g} {unit}{per}"
        return ""  # pragma: no cover

    return f"up to {length(v, '/s')} over {length(span)}"


def apparatus_note(record: LabRecord, velocities: Array | list[float],
                   given: bool = False) -> str | None:
    """One line on the units of the record's time, displacement and velocity columns, where the
    user reads it (``record``, ``fit`` and their JSON): ``None`` when every one has its unit
    and the numbers are plausible.

    * A column without a unit is read as SI: the line (``note: ...``) names it, the unit
      assumed and the ``--columns ROLE=NAME:UNIT`` entry that changes it. Where that reading
      makes the load velocities leave :data:`APPARATUS_V_TYPICAL` or the displacement span
      exceed :data:`APPARATUS_X_TYPICAL`, it is louder (``warning: ...``) and names the units
      that would bring the record into that range (millimetres or micrometres read as metres,
      minutes read as seconds are the usual causes).
    * A unit written, but load velocities above :data:`APPARATUS_V_MAX` or a displacement
      span above :data:`APPARATUS_X_MAX`: asks whether the unit is right, or (a program given
      in other units than m/s) reminds that ``--segments`` is in m/s.

    Parameters
    ----------
    record : LabRecord
    velocities : array
        The load program's velocities, m/s.
    given : bool
        The program was given (``--segments``, in m/s) rather than detected.
    """
    v = float(np.max(np.abs(velocities))) if len(velocities) else 0.0
    x = record.load_point
    span = float(np.ptp(x)) if x is not None and len(x) else 0.0
    role = "disp" if x is not None else "velocity"
    header, unit = record.columns.get(role, role), record.units.get(role, "")
    assumed = assumed_units(record)
    odd = v > APPARATUS_V_MAX or span > APPARATUS_X_MAX
    if given and odd and span <= APPARATUS_X_MAX:  # the program's m/s, not a column's unit
        return (f"note: {record.source}: load velocities up to {v:.3g} m/s are odd for a "
                "friction apparatus; --segments takes velocities in m/s (2e-7 for 0.2 um/s)")
    if assumed:
        return _assumed_note(record, assumed, v, span, role, given)
    if not odd:
        return None
    return (f"note: {record.source}: load velocities up to {v:.3g} m/s and {span:.3g} m of "
            f"displacement are odd for a friction apparatus; column {header!r} has the unit "
            f"{unit!r}: is it right?")


def _assumed_note(record: LabRecord, assumed: dict[str, str], v: float, span: float,
                  role: str, given: bool) -> str:
    """:func:`apparatus_note` for a record with columns read as SI for want of a unit."""
    cols = record.columns
    said = " and ".join(f"{cols[r]!r}" + (" is read" if k == 0 else "") + f" in {_SI_WORD[r]}"
                        for k, r in enumerate(assumed))
    entry = "--columns " + ",".join(f"{r}={cols[r]}:UNIT" for r in assumed)
    lo, hi = APPARATUS_V_TYPICAL
    head = f"{record.source}: no unit in the header, so {said} (SI): load velocities "
    if lo <= v <= hi and span <= APPARATUS_X_TYPICAL or v == 0.0 and span == 0.0:
        return f"note: {head}{_speeds(v, span)}; if a unit is another, give {entry}"
    # the SI reading is out of the apparatus' range: which unit would bring it in
    fits = []
    for u, f in (("mm", 1e-3), ("um", 1e-6)):
        if role not in assumed:
            break
        w = v if given else v * f  # a given program's velocities are its own m/s
        if (given or lo <= w <= hi) and span * f <= APPARATUS_X_TYPICAL:
            unit = u + ("/s" if role == "velocity" else "")
            fits.append(f"--columns {role}={cols[role]}:{unit} gives {_speeds(w, span * f)}")
    if "time" in assumed:  # a clock in ms (too slow) or in minutes or hours (too fast)
        for u, f in (("ms", 1e3), ("min", 1 / 60.0), ("h", 1 / 3600.0)):
            if not fits and lo <= v * f <= hi and span <= APPARATUS_X_TYPICAL:
                fits.append(f"--columns time={cols['time']}:{u} gives {_speeds(v * f, span)}")
    hint = "; ".join(fits) + "; " if fits else ""
    return (f"warning: {head}{_speeds(v, span)}, outside what biaxial and triaxial friction "
            f"apparatus do ({lo:g} to {hi:g} m/s over at most {APPARATUS_X_TYPICAL:g} m): the "
            f"unit is most likely not SI; {hint}give the unit with {entry} (SI written out, "
            "e.g. :m, keeps this reading and silences this line)")


def note_text(line: str) -> str:
    """An :func:`apparatus_note` line without its ``note:`` or ``warning:`` prefix and the
    space after it (as the JSON reports keep it)."""
    return re.sub(r"^(note|warning): ", "", line)


def read_record(
    path: str | os.PathLike[str], columns: Mapping[str, str] | None = None
) -> LabRecord:
    """Read a laboratory friction record (see the module docstring for the format).

    Parameters
    ----------
    path : str or path-like
        The text file.
    columns : mapping, optional
        Role -> header name (``"LP_disp"`` or ``"LP_disp:mm"``), overriding the guesses; the
        form :func:`parse_column_map` returns.

    Returns
    -------
    LabRecord
        Values in SI units.

    Raises
    ------
    ValueError
        A missing or ambiguous column, an unknown unit, a cell that is not a finite number,
        time that does not increase strictly, fewer than :data:`MIN_ROWS` rows, or a file too
        large for the memory limit: one line naming the file, the line and the column.
    OSError
        If the file cannot be read.
    """
    path = Path(path)
    src = str(path)
    if path.suffix.lower() in FORMS:  # a spreadsheet or a MATLAB file (.labforms)
        return _read_form(path, columns)
    size = path.stat().st_size
    with open(path, "rb") as fh:
        chunk = fh.read(1 << 20)
    check_text(chunk[:HEAD_BYTES], src)  # gzip, UTF-16: named, not read as Latin-1
    head = _decode(chunk).splitlines()
    if len(chunk) == 1 << 20 and len(head) > 1:
        head.pop()  # may be cut short
    header, hline, sample, sline, units_row, preamble = _find_header(head, columns)
    if header is None:
        raise ValueError(f"{src}: no header line with column names")
    if sample is None:
        raise ValueError(f"{src}: no data rows after the header (line {hline}): at least "
                         f"{MIN_ROWS} needed")
    delim = _sniff(header, sample)
    names = _header_cells(header, delim)
    width = len(_cells(sample, delim))
    if width > len(names):
        raise ValueError(f"{src}, line {sline}: {width} cells, the header (line {hline}) names "
                         f"{len(names)}: separate the columns with tabs or commas"
                         + (f", or, if line {hline} is not the header, name the header's "
                            "columns with --columns" if hline != sline - 1 else ""))
    row_units = _header_cells(units_row[0], delim) if units_row else []
    notes = []
    if preamble:  # one line: what was skipped, so that a wrong guess shows
        shown = ", ".join(repr(ln.strip()[:40]) for _, ln in preamble[:3])
        more = f" and {len(preamble) - 3} more" if len(preamble) > 3 else ""
        notes.append(f"{src}: {len(preamble)} line(s) above the header (line {hline}) skipped "
                     f"as a preamble: {shown}{more}")

    def load(usecols: list[int], roles: list[str]) -> tuple[Array, Callable[[int], int]]:
        need = size + size / max(len(sample), 8) * (120 + 24 * len(usecols))
        check_memory(f"{src}: reading this {size / 1e6:.0f} MB record needs", need,
                     "split the file")
        decimal_comma = delim != "," and bool(re.search(r"\d,\d", sample))
        with open(path, "rb") as fh:
            raw = fh.read()
        if decimal_comma:
            raw = raw.replace(b",", b".")
        data = _parse(raw, sline - 1, delim, usecols, src, names, roles)
        return data, _line_mapper(raw, sline, len(data))

    return _finish(src, names, columns, hline, sline, row_units, load, notes)


def _finish(src: str, names: list[str], columns: Mapping[str, str] | None, hline: int,
            sline: int, row_units: list[str],
            load: Callable[[list[int], list[str]], tuple[Array, Callable[[int], int]]],
            notes: list[str] | None = None) -> LabRecord:
    """The columns assigned and their units checked, then the data ``load``-ed (the used
    columns and a row -> file line map), checked and turned into a :class:`LabRecord`. A row
    with a missing value (NaN) in a used column is dropped and counted in the record's
    ``notes``, up to :data:`MISSING_MAX` of the rows; more is refused."""
    notes = list(notes or [])
    idx, forced = _assign(src, hline, names, columns)
    roles = list(idx)
    factors: dict[str, float] = {}
    kinds: dict[str, str] = {}
    units: dict[str, str] = {}
    for role in roles:  # every unit is checked before the data are read
        j = idx[role]
        unit = forced.get(role)
        if unit is None:
            unit = _split_cell(names[j])[1]
        if unit is None and j < len(row_units):
            unit = row_units[j].strip().strip("()[]")
        where = f"{src}, line {hline}, column {j + 1} ({names[j].strip()})"
        factors[role], kinds[role] = _unit(role, unit or "", where)
        units[role] = unit or ""
    if "mu" not in idx and kinds["shear"] != kinds["normal"]:
        # a column without a unit has no kind: say so (the line read "is a  and", outside24)
        said = {r: f"a {kinds[r]}" if kinds[r] else "without a unit" for r in ("shear", "normal")}
        raise ValueError(f"{src}, line {hline}: shear column {names[idx['shear']]!r} is "
                         f"{said['shear']} and normal column {names[idx['normal']]!r} "
                         f"{said['normal']}: friction needs two stresses or two forces (a "
                         "unit with --columns, e.g. shear=NAME:MPa)")
    usecols = [idx[r] for r in roles]
    data, line_of = load(usecols, roles)
    data, line_of = _drop_missing(src, data, line_of, [names[idx[r]].strip() for r in roles],
                                  usecols, notes)
    vals: dict[str, Array] = {}
    for k, role in enumerate(roles):
        j, col = idx[role], data[:, k]
        bad = ~np.isfinite(col)
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(f"{src}, line {line_of(i)}, column {j + 1} ({names[j].strip()}): "
                             f"{col[i]} is not a finite number")
        vals[role] = col * factors[role] if factors[role] != 1.0 else col.copy()
    if len(data) < MIN_ROWS:
        raise ValueError(f"{src}, line {line_of(len(data) - 1)}: only {len(data)} data rows: "
                         f"at least {MIN_ROWS} needed")
    t = vals["time"]
    dec = np.flatnonzero(np.diff(t) <= 0.0)
    if dec.size:
        i, j, k = int(dec[0]) + 1, idx["time"], roles.index("time")
        raise ValueError(f"{src}, line {line_of(i)}, column {j + 1} ({names[j].strip()}): "
                         f"time {data[i, k]:g} does not increase (previous {data[i - 1, k]:g})")
    if "mu" in vals:
        friction = vals["mu"]
    else:
        zero = np.flatnonzero(vals["normal"] == 0.0)
        if zero.size:
            j = idx["normal"]
            raise ValueError(f"{src}, line {line_of(int(zero[0]))}, column {j + 1} "
                             f"({names[j].strip()}): normal stress 0: friction is undefined")
        friction = vals["shear"] / vals["normal"]
    far = np.flatnonzero(~(np.abs(friction) <= FRICTION_MAX))
    if far.size:
        i = int(far[0])
        j = idx["mu" if "mu" in vals else "shear"]
        raise ValueError(f"{src}, line {line_of(i)}, column {j + 1} ({names[j].strip()}): "
                         f"friction {friction[i]:g} is out of range: allowed |friction| <= "
                         f"{FRICTION_MAX:g} (a friction coefficient)")
    normal = vals.get("normal")
    normal_unit = "" if normal is None else ("N" if kinds["normal"] == "force" else "Pa")
    role = "disp" if "disp" in vals else "velocity"
    flipped = role in vals and moves_backwards(t, vals[role], role == "velocity")
    if flipped:
        vals[role] = -vals[role]
        notes.append(f"the load point's {'displacement' if role == 'disp' else 'velocity'} "
                     f"column ({names[idx[role]].strip()}) decreases as the load point "
                     "advances (its net motion is backwards): read with its sign changed, "
                     "so that the load program moves forward")
    for a in (t, friction, normal, vals.get("disp"), vals.get("velocity")):
        if a is not None:
            a.setflags(write=False)
    return LabRecord(
        source=src, time=t, load_point=vals.get("disp"), load_velocity=vals.get("velocity"),
        friction=friction, normal_stress=normal, normal_unit=normal_unit,
        columns=MappingProxyType({r: names[idx[r]].strip() for r in roles}),
        first_line=sline, units=MappingProxyType(units), notes=tuple(notes),
        sign_changed=flipped)


def _drop_missing(src: str, data: Array, line_of: Callable[[int], int], names: list[str],
                  usecols: list[int], notes: list[str]
                  ) -> tuple[Array, Callable[[int], int]]:
    """``data`` without its rows that hold a missing value (NaN: an empty cell, ``NaN``,
    ``#N/A``) in a used column, and the row -> file line map of the rows kept; one line added
    to ``notes`` (how many, the first lines). Never filled. More than :data:`MISSING_MAX` of
    the rows: refused in one line (how many, where)."""
    miss = np.isnan(data)
    rows = np.flatnonzero(miss.any(axis=1))
    if rows.size == 0:
        return data, line_of
    per = miss.sum(axis=0)
    where = ", ".join(f"{n!r} (column {j + 1}) {int(c)}" for n, j, c in
                      zip(names, usecols, per, strict=True) if c)
    first = ", ".join(str(line_of(int(i))) for i in rows[:5]) + (" ..." if rows.size > 5 else "")
    if rows.size > MISSING_MAX * len(data):
        i, k = int(rows[0]), int(np.argmax(miss[rows[0]]))
        raise ValueError(f"{src}, line {line_of(i)}, column {usecols[k] + 1} ({names[k]}): "
                         f"{rows.size} of {len(data)} data rows have a missing value (empty, "
                         f"NaN) in a needed column ({where}; lines {first}): more than "
                         f"{100 * MISSING_MAX:g} % to drop: fill or remove them")
    keep = np.flatnonzero(~miss.any(axis=1))
    notes.append(f"{src}: {rows.size} of {len(data)} data rows dropped for a missing value "
                 f"(empty, NaN) in a needed column ({where}; lines {first})")
    return data[keep], lambda i: line_of(int(keep[min(i, len(keep) - 1)]))


def _read_form(path: Path, columns: Mapping[str, str] | None) -> LabRecord:
    """:func:`read_record` for a ``.xlsx`` or ``.mat`` file: its table read as a text one."""
    notes: list[str] = []
    named = {(v.rpartition(":")[0] if ":" in v else v).strip().lower()
             for v in (columns or {}).values()}

    def is_name(cell: str) -> bool:  # as _find_header scores a text record's lines
        name = _split_cell(cell)[0]
        return _guess_role(name)[0] is not None or name.lower() in named

    names, table, hline, sline, row_units, word = read_table(path, is_name, notes)

    def load(usecols: list[int], roles: list[str]) -> tuple[Array, Callable[[int], int]]:
        return table[:, usecols], lambda i: sline + i

    try:
        rec = _finish(str(path), names, columns, hline, sline, row_units, load, notes)
    except ValueError as exc:  # the same refusal, in the file's own words for a row
        msg = str(exc).replace(", line 0", "") if hline == 0 else str(exc)
        split = [n for n in notes if MATRIX_NOTE in n]
        if split and "--columns" in msg and not columns:  # no name to guess: map them all
            m = re.search(r"(\S+)_1 \.\. ", split[0])
            stem = m.group(1) if m else "data"
            msg += (f" (a matrix's columns have no names: map each, e.g. --columns "
                    f"time={stem}_1,disp={stem}_2:UNIT,mu={stem}_3, or shear=...,normal=... "
                    "for friction from stresses)")
        raise ValueError(msg.replace(", line ", f", {word} ").replace(
            "; lines ", f"; {word}s ")) from None
    # a cell that is not a number is NaN in a form's table: a missing value, by its row
    return replace(rec, notes=tuple(n.replace("; lines ", f"; {word}s ") for n in rec.notes))


def _parse(raw: bytes, skip: int, delim: str | None, usecols: list[int], src: str,
           names: list[str], roles: list[str]) -> Array:
    """The used columns of the data lines as one float array (rows, len(usecols))."""
    kw = dict(delimiter=delim, usecols=usecols, comments="#", ndmin=2, encoding="latin-1")
    try:
        return np.loadtxt(io.BytesIO(raw), skiprows=skip, **kw)  # type: ignore[call-overload]
    except ValueError:
        pass
    # slow path, only for an unusual file: drop blank and comment lines, find the bad cell
    lines = raw.decode("latin-1").splitlines()[skip:]
    keep = [(n, ln) for n, ln in enumerate(lines, start=skip + 1)
            if ln.strip() and not ln.lstrip().startswith("#")]
    try:
        return np.loadtxt([ln for _, ln in keep], **kw)  # type: ignore[call-overload]
    except ValueError:
        pass
    # cell by cell: a missing value (empty, NaN, #N/A: MISSING) is NaN, for _finish to drop
    out = np.empty((len(keep), len(usecols)))
    for r, (n, ln) in enumerate(keep):
        body = re.sub(r"#n/a", "NaN", ln, flags=re.IGNORECASE).split("#", 1)[0]
        cells = body.split(delim) if delim else body.split()  # empty cells kept
        for k, (j, role) in enumerate(zip(usecols, roles, strict=True)):
            where = f"{src}, line {n}, column {j + 1} ({names[j].strip()})"
            if j >= len(cells):
                raise ValueError(f"{where}: missing: the line has {len(_cells(body, delim))} "
                                 f"cells, the header {len(names)}")
            cell = cells[j]
            if _is_missing(cell):
                out[r, k] = np.nan
            elif _is_number(cell):
                out[r, k] = float(cell)
            else:
                raise ValueError(f"{where}: {cell.strip()!r} is not a number ({ROLES[role]})")
    return out


def _line_mapper(raw: bytes, first: int, rows: int):  # type: ignore[no-untyped-def]
    """Row index -> file line; scans the file only when blank or comment lines intervene."""
    tail = raw.rstrip(b"\r\n \t")
    n_lines = tail.count(b"\n") + 1 if tail else 0
    if n_lines - (first - 1) == rows:
        return lambda i: first + i
    numbers: list[int] = []

    def line_of(i: int) -> int:
        if not numbers:
            for n, ln in enumerate(raw.decode("latin-1").splitlines(), start=1):
                s = ln.strip()
                if n >= first and s and not s.startswith("#"):
                    numbers.append(n)
        return numbers[min(i, len(numbers) - 1)]

    return line_of

