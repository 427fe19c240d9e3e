"""The null distribution of a change's confidence ``z``: what sets ``detection.Z_MIN`` (issue 23).

No-step records of the artifact zoo (``tests/records_zoo.py``: program ``none``, the artifacts
of the zoo's records 0 to 149, each record's own seed; never the held-out records 150 to 449)
are written, read back and searched with a threshold of 2, far below any real one; the largest
``z`` of a change found on each (0 where none) is the null statistic: a threshold ``Z`` gives a
false change on the fraction of no-step records whose statistic reaches it. Prints its upper
quantiles and the false-change fraction at the chosen ``Z_MIN``.

Run: ``python -m benchmarks bench_detect_null [N]`` (the first N records, default 150).
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import numpy as np  # noqa: E402

from dryfriction.records.detection import Z_MIN  # noqa: E402
from dryfriction.records.lab import detect_program, read_record  # noqa: E402
from records_zoo import make_record, specs, write  # noqa: E402

Z_SEARCH = 2.0  # the threshold the null records are searched with


def null_statistics(n: int = 150) -> np.ndarray:
    """The largest ``z`` found on each of ``n`` no-step zoo records (0 where none)."""
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, _prog, arts, dialect in specs(n):
            rec = make_record(i, "none", arts, dialect)
            path = write(rec, Path(tmp))
            det = detect_program(read_record(path), z_min=Z_SEARCH)
            path.unlink()
            segs = det.segments
            z = [s.confidence for p, s in zip(segs, segs[1:], strict=False)
                 if s.velocity != p.velocity]
            out.append(max(z, default=0.0))
    return np.asarray(out)


def main() -> None:
    n = int(sys.argv[-1]) if len(sys.argv) > 1 and sys.argv[-1].isdigit() else 150
    z = null_statistics(n)
    print(f"no-step zoo records 0 to {n - 1}, searched at z >= {Z_SEARCH:g}: a change found on "
          f"{100 * np.mean(z > 0):.0f} %")
    print("largest z per record, quantiles 90 / 95 / 99 / max: "
          + " / ".join(f"{q:.2f}" for q in np.percentile(z, [90, 95, 99, 100])))
    print("largest ten: " + ", ".join(f"{q:.2f}" for q in np.sort(z)[::-1][:10]))
    print(f"at Z_MIN = {Z_MIN:g}: a false change on {100 * np.mean(z >= Z_MIN):.1f} % of "
          "no-step records")


if __name__ == "__main__":
    main()
