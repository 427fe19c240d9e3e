"""Whether two versions of the detector give the same detections on the zoo, and how fast.

A speed change to :func:`dryfriction.records.lab.detect_program` must change no output. This
dumps every field of every detection (each :class:`~dryfriction.records.labsteps.Segment`'s
times, velocity, samples, confidence, normal, interval, flags and probability; the
fluctuations; resets, rate changes, gaps, normal-stress changes) of zoo records ``START`` to
``STOP - 1`` to a file, and compares two such files field by field: integers and flags
exactly, floats to a relative ``--rtol`` (default 0: bit for bit; NaN equals NaN).

The records are generated, written in their dialect and read back as ``bench_detect`` does;
``--cache DIR`` keeps the records read (pickled, one file per range) so that a second dump of
the same range skips the generation (the slow part: about 0.2 s a record). The CPU time of
:func:`detect_program` alone is printed per 1e6 rows, after one untimed detection (the compiled
kernel's loading), as ``bench_detect`` measures it.

Run::

    python -m benchmarks bench_detect_same dump START:STOP OUT.pkl [--cache DIR]
    python -m benchmarks bench_detect_same compare A.pkl B.pkl [--rtol R]
"""

from __future__ import annotations

import math
import os
import pickle
import sys
import tempfile
import time
from dataclasses import fields, replace
from pathlib import Path
from types import MappingProxyType

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import numpy as np  # noqa: E402

from dryfriction.records.lab import detect_program, read_record  # noqa: E402
from records_zoo import make_record, specs, write  # noqa: E402


def records(start: int, stop: int, cache: Path | None) -> list[tuple[int, object]]:
    """Zoo records ``start`` to ``stop - 1`` as read back from their files: ``(index,
    LabRecord)``; from ``cache`` where it holds them."""
    path = cache / f"zoo_{start}_{stop}.pkl" if cache is not None else None
    if path is not None and path.exists():
        with path.open("rb") as f:
            return [(i, replace(r, columns=MappingProxyType(r.columns),
                                units=MappingProxyType(r.units))) for i, r in pickle.load(f)]
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, prog, arts, dialect in specs(stop):
            if i < start:
                continue
            p = write(make_record(i, prog, arts, dialect), Path(tmp))
            out.append((i, read_record(p)))
            p.unlink()
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        part = path.with_suffix(".part")
        with part.open("wb") as f:  # a mappingproxy does not pickle: a dict, wrapped on load
            pickle.dump([(i, replace(r, columns=dict(r.columns), units=dict(r.units)))
                         for i, r in out], f)
        part.replace(path)
    return out


def flat(det: object) -> dict[str, object]:
    """Every field of a detection, as plain Python values (lists, floats, ints, bools)."""
    fl = det.fluctuations
    return {
        "segments": [[getattr(s, f.name) for f in fields(s)] for s in det.segments],
        "fluctuations": [fl.sigma, list(map(float, fl.scales)), list(map(float, fl.relative)),
                         list(map(float, fl.absolute)), fl.lag],
        "resets": list(det.resets), "rate_changes": list(det.rate_changes),
        "gaps": list(det.gaps), "normal_changes": list(det.normal_changes),
    }


def dump(start: int, stop: int, out: Path, cache: Path | None) -> None:
    """Detect the records and write their detections to ``out``; print the CPU per 1e6 rows."""
    recs = records(start, stop, cache)
    detect_program(recs[0][1])  # the compiled kernel loaded outside the timing
    dets, cpu, rows = {}, 0.0, 0
    for i, rec in recs:
        c0 = time.process_time()
        det = detect_program(rec)
        cpu += time.process_time() - c0
        rows += len(rec)
        dets[i] = flat(det)
    with out.open("wb") as f:
        pickle.dump(dets, f)
    print(f"records {start} to {stop - 1}: {len(recs)} records, {rows:,} rows, detection CPU "
          f"{cpu:.2f} s, {cpu / rows * 1e6:.3f} s per 1e6 rows")


def same(a: object, b: object, rtol: float) -> bool:
    """``a`` and ``b`` equal: containers item by item, floats to ``rtol`` (NaN equal to NaN)."""
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same(p, q, rtol) for p, q in zip(a, b, strict=True))
    if isinstance(a, (bool, np.bool_)) or isinstance(b, (bool, np.bool_)):
        return bool(a) == bool(b) and type(bool(a)) is type(bool(b))
    if isinstance(a, (float, np.floating)) and isinstance(b, (float, np.floating)):
        if math.isnan(a) or math.isnan(b):
            return math.isnan(a) and math.isnan(b)
        return a == b or abs(a - b) <= rtol * max(abs(a), abs(b))
    return a == b


def compare(pa: Path, pb: Path, rtol: float) -> int:
    """Print the records whose detections differ; return their number."""
    with pa.open("rb") as f:
        a = pickle.load(f)
    with pb.open("rb") as f:
        b = pickle.load(f)
    bad = 0
    if a.keys() != b.keys():
        print(f"different records: {sorted(a.keys() ^ b.keys())}")
        bad += 1
    for i in sorted(a.keys() & b.keys()):
        diff = [k for k in a[i] if not same(a[i][k], b[i][k], rtol)]
        if diff:
            bad += 1
            print(f"record {i}: differs in {', '.join(diff)}")
    print(f"{len(a.keys() & b.keys())} records compared (rtol {rtol:g}): {bad} differ")
    return bad


def main() -> None:
    args = [a for a in sys.argv[1:] if a != "bench_detect_same"]  # as ``-m benchmarks`` runs it
    opt: dict[str, str] = {}
    for name in ("--cache", "--rtol"):
        if name in args:
            k = args.index(name)
            opt[name] = args[k + 1]
            del args[k:k + 2]
    if args[:1] == ["dump"]:
        start, stop = (int(q) for q in args[1].split(":"))
        cache = Path(opt["--cache"]) if "--cache" in opt else None
        dump(start, stop, Path(args[2]), cache)
    elif args[:1] == ["compare"]:
        sys.exit(1 if compare(Path(args[1]), Path(args[2]), float(opt.get("--rtol", 0))) else 0)
    else:
        print(__doc__)
        sys.exit(2)


if __name__ == "__main__":
    main()
