"""A 1e6-design tolerance sweep (issue 12), side by side in one run.

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_sweep.py [--cpu] [--save]

Summary only vs also streaming a CSV, one process vs the local cores
(wall clock: the workers are other processes).  ``--cpu``: one worker
only (the sweep runs in this process), timed by this process's CPU
time, with a Parquet row beside the CSV one: what a loaded shared
machine can still measure side by side (the wall clock of several
processes there says more about the others' runs than about the
sweep).  ``--save``: also into benchmarks/results/bench_sweep.md, the
run docs/performance.md quotes.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time

from results import Report  # this folder: run as a script

from contactsep.studies.sweep import run as runner

from contactsep.studies.sweep import spec as sweep
from contactsep.studies.sweep.writers import CsvWriter, ParquetWriter
def main(save: bool = False, cpu: bool = False) -> None:
    say = Report()
    spec = sweep.make_spec(sample=["h2=normal(0.25,0.01)",
                                   "ys=uniform(0.45,0.55)"],
                           samples=1_000_000, seed=1)
    clock = time.process_time if cpu else time.perf_counter
    outputs = ("no", "CSV", "Parquet") if cpu else ("no", "CSV")
    counts = (1,) if cpu else (1, os.cpu_count() or 1)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for workers in counts:
            for output in outputs:
                writers = {
                    "no": list,
                    "CSV": lambda: [CsvWriter(
                        os.path.join(tmp, "s.csv"), spec)],
                    "Parquet": lambda: [ParquetWriter(
                        os.path.join(tmp, "s.parquet"), spec)],
                }[output]()
                start = clock()
                runner.run_sweep(spec, writers=writers, threshold=0.12,
                                 workers=workers, progress=False)
                rows.append((workers, output, clock() - start))
    base = rows[0][2]
    say(f"clock: {'process CPU time' if cpu else 'wall clock'}")
    say()
    say("| workers | output | seconds | designs/s | ratio |")
    say("|---|---|---:|---:|---:|")
    for workers, output, seconds in rows:
        say(f"| {workers} | {output} | {seconds:.2f} | "
            f"{spec.size / seconds:,.0f} | {seconds / base:.2f} |")
    if save:
        say.save("bench_sweep", "OPENBLAS_NUM_THREADS=1 python "
                 "benchmarks/bench_sweep.py " + ("--cpu " if cpu else "")
                 + "--save")


if __name__ == "__main__":
    main(save="--save" in sys.argv[1:], cpu="--cpu" in sys.argv[1:])
