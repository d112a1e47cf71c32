"""A 1e6-design tolerance sweep (issue 12), side by side in one run.

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_sweep.py [--save]

Summary only vs also streaming a CSV, one process vs the local cores
(wall clock: the workers are other processes).  ``--save``: also into
benchmarks/results/bench_sweep.md, the run docs/performance.md quotes.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time

from results import Report  # this folder: run as a script

from contactsep.studies import runner, sweep


def main(save: bool = False) -> None:
    say = Report()
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
    say("| workers | CSV | seconds | designs/s | ratio |")
    say("|---|---|---|---|---|")
    for workers, csv, seconds in rows:
        say(f"| {workers} | {'yes' if csv else 'no'} | {seconds:.2f} | "
            f"{spec.size / seconds:,.0f} | {seconds / base:.2f} |")
    if save:
        say.save("bench_sweep", "OPENBLAS_NUM_THREADS=1 python "
                 "benchmarks/bench_sweep.py --save")


if __name__ == "__main__":
    main(save="--save" in sys.argv[1:])
