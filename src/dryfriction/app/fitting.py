"""``fit``: measured friction against the trap model (cv) or rate-and-state (rsf).
:func:`fit` reads what it is given: the project's CSV files (:func:`fit_data`) or one
laboratory record (:func:`dryfriction.app.records.fit_record`)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from .checks import check_fit_applies, check_fit_options, check_record_applies
from .options import CSV_TRAPS_PER_A0, OPTIONS
from .outcome import FitOutcome, RecordFitOutcome

__all__ = ["fit", "fit_data", "check_fit_options", "parse_stiffness", "is_project_csv",
           "Progress", "as_typed"]

Progress = Callable[..., None]
"""``progress(done, total, what)``."""

_FIT = OPTIONS["fit"]
_D = {k: o.default for k, o in _FIT.items()}
_PROJECT_COLUMNS = ({"t_w", "mu_s"}, {"v", "mu_d"}, {"t", "v_load", "mu"})
# the record's options, and the value that means "not given" (refused for CSV files)
_RECORD_ONLY = ("columns", "segments", "joint", "run_cv", "errors", "drive", "initial_state")


def is_project_csv(path: str | Path) -> bool:
    """Whether ``path`` is in the project's own CSV format (:mod:`dryfriction.records.data`): its
    first line that is not a comment or blank is a header (comma- or semicolon-separated,
    :func:`dryfriction.records.data.csv_separator`) holding the columns of one data kind.
    Anything else is read as a laboratory record."""
    import re

    from ..io.textfile import check_text_file
    from ..records.data import csv_separator
    from ..records.labforms import FORMS

    if Path(path).suffix.lower() in FORMS:  # a .xlsx or .mat is a record, as `record` reads it
        return False
    check_text_file(path)  # a compressed or UTF-16 file is named here, whatever it holds
    s = _header_line(path)
    names = {re.sub(r"\[.*?\]", "", c).strip().lower() for c in s.split(csv_separator(s))}
    return bool(s) and any(cols <= names for cols in _PROJECT_COLUMNS)


def _header_line(path: str | Path) -> str:
    """The first line of a text file that is not blank or a comment ("" if none)."""
    with open(path, encoding="utf-8", errors="replace") as fh:
        for line in fh:
            s = line.strip()
            if s and not s.startswith("#"):
                return s
    return ""


def _check_files(paths: Sequence[Path]) -> None:
    """Refuse, in one line naming the files, a file given twice (its rows would count twice
    and narrow every interval) and a laboratory record given with other files (a record is
    fitted alone, :func:`dryfriction.app.records.fit_record`)."""
    from ..records.lab import read_record
    from ..records.labforms import FORMS

    seen: dict[Path, Path] = {}
    for p in paths:
        key = p.resolve()  # the same file by another spelling (./a.csv, a link) too
        if key in seen:
            same = f"{p}" if str(seen[key]) == str(p) else f"{seen[key]} and {p}"
            raise ValueError(f"{same}: the same file is given more than once: each file is "
                             "fitted once (its rows would count twice); give it once")
        seen[key] = p
    if len(paths) < 2:
        return
    for p in paths:
        if not p.is_file() or is_project_csv(p):
            continue
        if p.suffix.lower() not in FORMS:
            try:  # a text file of neither kind is refused by the CSV reader, in its words
                read_record(p)
            except ValueError:
                continue
        others = ", ".join(str(q) for q in paths if q is not p)
        raise ValueError(f"{p} is a laboratory record, and a record is fitted alone "
                         f"(dryfriction fit {p} --out DIR); the project's CSV files "
                         f"({others}) are fitted together, without it")


def parse_stiffness(text: str | float) -> float | str:
    """``--stiffness``: ``fit``, ``slope``, ``record`` (a record's one machine) or a number
    (1/m, ``> 0``; ``inf`` kinematic)."""
    t = str(text).strip().lower()
    if t in ("fit", "slope", "record"):
        return t
    try:
        k = float(t)
    except ValueError:
        raise ValueError(f"--stiffness {text!r} is not allowed: fit, slope, record or a number "
                         "(1/m, > 0; inf for the kinematic machine)") from None
    if not k > 0:
        raise ValueError(f"--stiffness {text!r} is out of range: allowed > 0 (1/m), fit, "
                         "slope or record")
    return k


def _csv_stiffness(value: Any) -> float | str:
    """``--stiffness`` for the project's CSV files (``record`` is for a laboratory record)."""
    k = parse_stiffness("inf" if value is None else value)
    if k == "record":
        raise ValueError("--stiffness record is for a laboratory record (its steps' one "
                         "machine), not the project's CSV files: fit, slope or a number (1/m)")
    return k


def as_typed(message: str) -> str:
    """A fit's refusal in the command line's words: the library names a fixed value as the
    Python caller gave it (``fix['t0'] [s] = -1 is out of range``), the command line user
    typed ``--fix t0=-1`` (``--fix t0 [s] = -1 is out of range``)."""
    import re

    return re.sub(r"^fix\['(\w+)'\]", r"--fix \1", message)


def parse_fix(items: Sequence[str] | dict[str, float] | None) -> dict[str, float]:
    """``--fix name=value`` (repeatable) as ``{name: value}``; a dict is taken as it is."""
    if isinstance(items, dict):
        return {str(k): float(v) for k, v in items.items()}
    fixed: dict[str, float] = {}
    for item in items or []:
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise ValueError(f"--fix {item!r}: expected name=value, e.g. --fix t0=0.01")
        try:
            fixed[name.strip()] = float(value)
        except ValueError:
            raise ValueError(f"--fix {item!r}: {value!r} is not a number") from None
    return fixed


def fit(data: Sequence[str | Path] | str | Path, out: str | Path, *,
        progress: Progress | None = None, report: Callable[[str], None] | None = None,
        on_start: Callable[[], None] | None = None, bar: Any = None,
        on_program: Callable[[list[Any], Any], None] | None = None,
        **options: Any) -> FitOutcome | RecordFitOutcome:
    """Fit measured friction and write fit.json (and its figures) into ``out``
    (``dryfriction fit``).

    One file that is not in the project's CSV format is a laboratory record
    (:func:`dryfriction.app.records.fit_record`: fit.json, steps.csv, the figures); otherwise
    the CSV files are fitted together (:func:`fit_data`). Every option is checked, in the
    name the command line gives it, before any work.

    Parameters
    ----------
    data : path or list of paths
        CSV files (t_w,mu_s; V,mu_d; t,v_load,mu: units in the header) or one record.
    out : path
        Results folder: new, empty, or written by this program before.
    progress : callable, optional
        ``progress(done, total, what)``.
    report : callable, optional
        ``report(line)``: what was done to files already in ``out``, and notes said before
        the fit (a record's units).
    on_start : callable, optional
        Called after every check, before the work.
    bar, on_program : callable, optional
        A record's progress bars and its load program: see
        :func:`dryfriction.app.records.fit_record`.
    **options
        The options of :data:`dryfriction.app.options.OPTIONS` ``["fit"]`` (``model``,
        ``alpha``, ``state_law``, ...), with its defaults.

    Returns
    -------
    FitOutcome or RecordFitOutcome
    """
    from ..fit.loadpoint import check_drive
    from ..io.files import check_output_dir
    from ..validation import check_choice, check_figure_format

    unknown = set(options) - set(_FIT)
    if unknown:
        raise TypeError(f"fit() got unknown option(s) {', '.join(sorted(unknown))}")
    o = {**_D, **options}
    paths = [Path(data)] if isinstance(data, (str, Path)) else [Path(p) for p in data]
    if o["model"] is not None:
        check_choice("--model", o["model"], ("cv", "rsf"))
    check_drive(o["drive"])
    o["fmt"], o["dpi"] = check_figure_format(o["fmt"], o["dpi"])
    check_fit_options(alpha=o["alpha"], creep=o["creep"], v0=o["v0"], state_law=o["state_law"],
                      errors=o["errors"], traps_per_a0=o["traps_per_a0"], direct=o["direct"],
                      v_ref=o["v_ref"])
    _check_files(paths)
    record = len(paths) == 1 and not is_project_csv(paths[0])
    if o["model"] is None:  # chosen by the input (OPTIONS["fit"]["model"])
        o["model"] = "rsf" if record else "cv"
    if record:
        # the mirror of the CSV files' refusal of the record's options below: a record's fit
        # reads neither, and an option silently ignored looks obeyed (outside24: --fix a=nan
        # and --fix zz=1 fitted the record free, exit 0)
        for flag, given in (("--fix", o["fix"] or None), ("--v0", o["v0"])):
            if given is not None:
                raise ValueError(f"{flag} is for the project's CSV files, not a laboratory "
                                 "record (its steps are fitted free; --stiffness K holds "
                                 "the machine)")
        check_record_applies(o, _D)  # the trap model's options without --run-cv (fixE)
    check_output_dir(out, force=o["force"], command="fit")
    if record:
        from .records import fit_record

        rec_opts = {k: o[k] for k in ("model", "columns", "segments", "joint", "run_cv",
                                      "alpha", "creep", "errors", "direct", "v_ref",
                                      "traps_per_a0", "drive", "profile", "force", "fmt",
                                      "dpi", "figure")}
        return fit_record(paths[0], out, stiffness=parse_stiffness(
            "record" if o["stiffness"] is None else o["stiffness"]),
            trend=True if o["trend"] is None else o["trend"], law=o["state_law"],
            initial=o["initial_state"], bar=bar, report=report, on_start=on_start,
            on_program=on_program, **rec_opts)
    for name in _RECORD_ONLY:  # in the order the command line has always named them
        if name == "initial_state" and o["state_law"] == "auto":
            raise ValueError("--state-law auto is for a laboratory record, not the project's "
                             "CSV files")
        if o[name] != _D[name]:
            flag = _FIT[name].flag
            raise ValueError(f"{flag} is for a laboratory record, not the project's CSV files")
    return fit_data(paths, out, progress=progress, report=report, on_start=on_start,
                    **{k: v for k, v in o.items() if k not in _RECORD_ONLY})


def fit_data(paths: Sequence[str | Path], out: str | Path, *,
             progress: Progress | None = None, report: Callable[[str], None] | None = None,
             on_start: Callable[[], None] | None = None, **options: Any) -> FitOutcome:
    """Fit the project's CSV files together (static, steady or time series) and write
    fit.json and fit.{fmt} (``dryfriction fit DATA.csv ...``): the fit
    (:func:`dryfriction.fit.fit`) with profile intervals unless ``profile=False``, and, with
    ``compare`` (default), the other model fitted to the same data and both compared
    (:func:`dryfriction.fit.compare_models`; a comparison that cannot run says why in
    fit.json).

    Parameters
    ----------
    paths : list of paths
        The CSV files.
    out : path
        Results folder.
    progress, report, on_start : as :func:`fit`.
    **options
        As :func:`fit`, less the record's own.

    Returns
    -------
    FitOutcome
        ``success`` False: the fit did not converge (the command exits 1).
    """
    from ..fit import CVModel, compare_models
    from ..fit import fit as run_fit
    from ..io.files import check_output_dir, output_directory, write_json
    from ..io.units import DIMENSIONLESS, FIT_UNITS, with_units
    from ..records.data import csv_separator, read_csv
    from ..theory.model import TrapModel
    from ..validation import check_figure_format

    o = {**{k: v for k, v in _D.items() if k not in _RECORD_ONLY}, **options}
    o["fmt"], o["dpi"] = check_figure_format(o["fmt"], o["dpi"])
    paths = [Path(p) for p in paths]
    fixed = parse_fix(o["fix"])
    stiffness = _csv_stiffness(o["stiffness"])
    check_output_dir(out, force=o["force"], command="fit")
    datasets = [read_csv(p) for p in paths]
    # an option these data or models do not use, refused by name before the fit (fixE)
    check_fit_applies(o, _D, {d.kind for d in datasets}, [str(p) for p in paths])
    for p in paths:  # the reading chosen, said: a ';' file might have been meant otherwise
        if report is not None and csv_separator(_header_line(p)) == ";":
            report(f"note: {p}: read as the project's CSV with ';' separators and decimal "
                   "commas")
    if on_start is not None:
        on_start()
    model = o["model"]
    opts: dict[str, Any] = dict(alpha=o["alpha"], creep=o["creep"], v0=o["v0"],
                                state_law=o["state_law"], stiffness=stiffness,
                                regularized=o["regularized"], trend=bool(o["trend"]))
    chosen: Any = (CVModel(TrapModel(o["alpha"], creep=o["creep"], direct=o["direct"]),
                           traps_per_a0=CSV_TRAPS_PER_A0
                           if o["traps_per_a0"] is None else o["traps_per_a0"],
                           v_ref=o["v_ref"]) if model == "cv" else model)
    done = [0]

    def fit_progress(n: int, total: int, what: str) -> None:
        done[0] = n
        if progress is not None:
            progress(n, total, f"{model} {what}")

    try:
        result = run_fit(datasets, chosen, fix=fixed,
                         profile=True if o["profile"] is None else o["profile"],
                         progress=fit_progress, **opts)
    except NotImplementedError as exc:
        raise ValueError(str(exc)) from None
    except ValueError as exc:  # fix['t0'] is --fix t0 here (the options' names)
        raise ValueError(as_typed(str(exc))) from None
    report_ = result.to_dict()
    if o["compare"]:
        other = "rsf" if model == "cv" else "cv"
        before = done[0]

        def compare_progress(n: int, total: int, what: str) -> None:
            # the count goes on; the total grows by the comparison's, unknown before
            if progress is not None:
                progress(before + n, before + total, f"{other} comparison {what}")

        try:
            alt = run_fit(datasets, other, profile=False, consistency=False, **opts,
                          progress=compare_progress)
            report_["comparison"] = compare_models([result, alt])
        except (ValueError, NotImplementedError) as exc:
            report_["comparison"] = {"not_run": f"{other}: {exc}"}
    # every number's unit (dryfriction.io.units): the fixed table, the model's parameters
    report_ = with_units(report_, FIT_UNITS,
                         {p.name: p.unit or DIMENSIONLESS for p in result.parameters})
    files = ["fit.json"]
    with output_directory(out, command="fit", force=o["force"], inputs=paths,
                          report=report) as tmp:
        write_json(tmp / "fit.json", report_)
        if o["figure"]:
            from ..plots.fits import plot_fit
            from ..plots.style import save_figure

            fig, _ = plot_fit(result, datasets)
            save_figure(fig, tmp / f"fit.{o['fmt']}", o["fmt"], o["dpi"])
            files.append(f"fit.{o['fmt']}")
    return FitOutcome(Path(out), files, report_, result, datasets)
