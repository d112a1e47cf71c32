"""Chatter sweeps and the preload chart (issue 16), side by side with
numpy.sin on 1e6 float64 elements, in one run:

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_chatter_sweep.py [chart]
        [--cpu] [--designs N] [--save]

The sweep: a 1,000-design tolerance study of the thesis rig, Hertz,
N = 16 (d ~ normal(0.25, 0.01) in, y_s ~ uniform(0.45, 0.55) in), with
a progress bar (tqdm on stderr), on 1 and on 2 worker processes; again
with a 20 lb preload (the lower contact pressed nearly the whole window:
the costly case, every step after the impact a fixed step).  Beside it
the same designs simulated one by one in this process (the sum of the
simulate() calls a sweep makes), which bounds what the sweep's own
machinery costs.  ``chart``: also `contactsep study preload` (Hertz,
N = 32) on 1 and 2 workers.  ``--cpu``: one worker only (the sweep runs
in this process), timed by CPU time (the process's and its finished
children's: a long simulation runs in a forked child), what a loaded
shared machine can still measure side by side; ``--designs N``: N
designs instead of 1,000; ``--save``: also into
benchmarks/results/bench_chatter_sweep.md, the run docs/performance.md
quotes.
"""

from __future__ import annotations

import os
import sys
import time

import bench_chatter  # this folder: run as a script
import numpy as np
from bench_chatter import best
from results import Report

from contactsep.chatter import simulate
from contactsep.model import thesis_design
from contactsep.studies.preload import chart as preload
from contactsep.studies.sweep import chatter as chatter_sweep
from contactsep.studies.sweep import run as runner
from contactsep.studies.sweep import spec as sweep
def spec(preload_lb=None, designs=1000):
    settings = {} if preload_lb is None else {"preload": preload_lb}
    return sweep.make_spec(sample=["d=normal(0.25,0.01)",
                                   "ys=uniform(0.45,0.55)"],
                           samples=designs, seed=1, base={"n_modes": 16},
                           model="hertz", settings=settings)


def one_by_one(s) -> float:
    """The sweep's simulate() calls, in this process, timed alone."""
    inputs = sweep.chunk_inputs(s, 0, s.size)
    total = 0.0
    for d, ys in zip(inputs["h2"], inputs["ys"]):
        design = thesis_design(d=float(d), ys=float(ys), n_modes=16)
        start = bench_chatter.clock()
        simulate(design, model="hertz", samples=1, single_impulse=False,
                 **{**chatter_sweep.DEFAULT_SETTINGS, **s.settings})
        total += bench_chatter.clock() - start
    return total


def main(argv) -> None:
    cpu = "--cpu" in argv
    designs = int(argv[argv.index("--designs") + 1]) \
        if "--designs" in argv else 1000
    bench_chatter.clock = bench_chatter.cpu_time if cpu else time.perf_counter
    clock = bench_chatter.clock
    say = Report()
    x = np.random.default_rng(0).random(1_000_000)
    sine = best(lambda: np.sin(x), 20)
    rows = []
    cores = os.cpu_count() or 1
    counts = [1] if cpu else sorted({1, cores})
    for label, load in (("no preload", None), ("preload 20 lb", 20.0)):
        s = spec(load, designs)
        rows.append((f"{label}: simulate() one by one", one_by_one(s)))
        for workers in counts:
            start = clock()
            summary = runner.run_sweep(s, workers=workers, progress=True)
            rows.append(((f"{label}: sweep, {workers} worker(s), progress "
                         f"bar (p_open {summary['p_open']:.3g})"),
                         clock() - start))
    if "chart" in argv:
        for workers in counts:
            start = clock()
            chart = preload.preload_chart(workers=workers)
            runs = next(n for n in chart.notes if "simulations" in n)
            rows.append(((f"study preload, N = 32, {workers} worker(s), "
                         f"{runs}"), clock() - start))
    say(f"clock: {'process CPU time' if cpu else 'wall'}")
    say(f"numpy.sin, 1e6 float64: {sine * 1e3:.2f} ms; {cores} cores")
    say()
    say(f"| run ({designs:,} designs, Hertz N = 16) | s | ms a design | "
        "x numpy.sin a design |")
    say("|---|---:|---:|---:|")
    for label, seconds in rows:
        per = seconds / (designs if "chart" not in label else 1)
        say(f"| {label} | {seconds:.1f} | {per * 1e3:.1f} | "
            f"{per / sine:.2f} |")
    if "--save" in argv:
        say.save("bench_chatter_sweep", "OPENBLAS_NUM_THREADS=1 python "
                 "benchmarks/bench_chatter_sweep.py " + " ".join(argv))


if __name__ == "__main__":
    main(sys.argv[1:])
