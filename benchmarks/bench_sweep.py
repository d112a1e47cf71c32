"""A 1e6-design tolerance sweep (issue 12), side by side in one run.

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_sweep.py

Summary only vs also streaming a CSV, one process vs the local cores.
"""

from __future__ import annotations

import os
import tempfile
import time

from contactsep.studies import runner, sweep


def main() -> None:
    spec = sweep.make_spec(sample=["h2=normal(0.25,0.01)",
                                   "ys=uniform(0.45,0.55)"],
                           samples=1_000_000, seed=1)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for workers in (1, os.cpu_count() or 1):
            for csv in (False, True):
                writers = [runner.CsvWriter(os.path.join(tmp, "s.csv"),
                                            spec)] if csv else []
                start = time.perf_counter()
                runner.run_sweep(spec, writers=writers, threshold=0.12,
                                 workers=workers, progress=False)
                rows.append((workers, csv, time.perf_counter() - start))
    base = rows[0][2]
    print(f"{'workers':>7} {'csv':>5} {'seconds':>8} {'designs/s':>10} "
          f"{'ratio':>6}")
    for workers, csv, seconds in rows:
        print(f"{workers:7d} {str(csv):>5} {seconds:8.2f} "
              f"{spec.size / seconds:10.0f} {seconds / base:6.2f}")


if __name__ == "__main__":
    main()
