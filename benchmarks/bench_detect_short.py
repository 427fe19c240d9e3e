"""What the search for short stops costs the detection (``records.detection.SHORT_SEARCH``).

The zoo's records (``tests/records_zoo.py``) are generated, written in their dialects and read
back as ``bench_detect`` does; each is then detected with the search on and off in turn (the
order alternating between two passes, so that a drift of the machine's speed falls on both),
and the CPU time of :func:`dryfriction.records.lab.detect_program` summed for each. Prints
both per 1e6 rows and their ratio, and the records whose program differs.

Run: ``python -m benchmarks bench_detect_short [START:STOP]`` (default 81000:81150).
"""

from __future__ import annotations

import os
import re
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import dryfriction.records.detection as detection  # noqa: E402
from dryfriction.records.lab import detect_program, read_record  # noqa: E402
from records_zoo import make_record, specs, write  # noqa: E402


def run(start: int, stop: int) -> dict[str, float]:
    """CPU seconds per 1e6 rows with the search on and off, and the records that differ."""
    labs = []
    rows = 0
    with tempfile.TemporaryDirectory() as tmp:
        # the compiled kernels loaded once, untimed
        detect_program(read_record(write(make_record(0, "up", (), "tab_um"), Path(tmp))))
        for i, prog, arts, dialect in specs(stop):
            if i < start:
                continue
            rec = make_record(i, prog, arts, dialect)
            labs.append((rec.name, read_record(write(rec, Path(tmp)))))
            rows += rec.rows
    cpu = {True: 0.0, False: 0.0}
    differ = set()
    before = detection.SHORT_SEARCH
    try:
        for order in ((True, False), (False, True)):
            for name, lab in labs:
                got = {}
                for on in order:
                    detection.SHORT_SEARCH = on
                    c0 = time.process_time()
                    got[on] = detect_program(lab).segments
                    cpu[on] += time.process_time() - c0
                if [(s.i_start, s.velocity) for s in got[True]] != [
                        (s.i_start, s.velocity) for s in got[False]]:
                    differ.add(name)
    finally:
        detection.SHORT_SEARCH = before
    return {"on": cpu[True] / 2 / rows * 1e6, "off": cpu[False] / 2 / rows * 1e6,
            "ratio": cpu[True] / cpu[False], "rows": rows, "differ": sorted(differ)}


def main() -> None:
    args = [a for a in sys.argv[1:] if re.fullmatch(r"\d+:\d+", a)]
    start, stop = (int(q) for q in args[-1].split(":")) if args else (81000, 81150)
    r = run(start, stop)
    print(f"zoo {start} to {stop - 1}: {r['rows']:,} rows")
    print(f"detection CPU with the short search {r['on']:.3f}, without {r['off']:.3f} s per "
          f"1e6 rows: ratio {r['ratio']:.3f}")
    print(f"records whose program differs: {len(r['differ'])} {' '.join(r['differ'])}")


if __name__ == "__main__":
    main()
