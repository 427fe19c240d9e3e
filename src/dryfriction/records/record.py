"""A laboratory friction record in SI units: the type every reader returns and every step of
the record's analysis takes (:mod:`.lab` reads it, :mod:`.detection` finds its load program,
:mod:`.labsteps` slices it).

It has a module of its own because the reader and the slicer both need it: in ``lab.py`` it
made ``lab`` and ``labsteps`` import each other.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from ..validation import Array

__all__ = ["LabRecord"]


@dataclass(frozen=True)
class LabRecord:
    """A laboratory friction record in SI units.

    Attributes
    ----------
    source : str
        The file it was read from (used in messages).
    time : Array
        Time, s, strictly increasing; the file's own clock (it may start at any value).
    load_point : Array or None
        Load-point displacement, m (``None`` when the file gives a velocity instead).
    load_velocity : Array or None
        Load-point velocity, m/s, when the file has a velocity column.
    friction : Array
        Friction coefficient (the file's, or shear over normal stress).
    normal_stress : Array or None
        Normal stress, Pa, or normal force, N, as the file gives it (see ``normal_unit``).
    normal_unit : str
        ``"Pa"``, ``"N"``, or ``""`` when there is no normal column.
    columns : Mapping[str, str]
        Role (``time, disp, velocity, mu, shear, normal``) -> header cell as found.
    first_line : int
        File line (1-based) of the first data row.
    units : Mapping[str, str]
        Role -> unit as written in the file (``""``: none, read as SI).
    notes : tuple of str
        One line for each thing the reader did that the user should know: a preamble above
        the header skipped, rows with a missing value dropped (how many, where).
    sign_changed : bool
        True when the load point's column was read with its sign changed (its net motion in
        the file is backwards; one of ``notes`` says so): ``record.png`` says it too.
    """

    source: str
    time: Array
    load_point: Array | None
    load_velocity: Array | None
    friction: Array
    normal_stress: Array | None
    normal_unit: str
    columns: Mapping[str, str]
    first_line: int
    units: Mapping[str, str] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    sign_changed: bool = False

    def __len__(self) -> int:
        return len(self.time)
