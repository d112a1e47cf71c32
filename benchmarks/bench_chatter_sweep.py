"""Chatter sweeps and the preload chart (issue 16), side by side with
numpy.sin on 1e6 float64 elements, in one run:

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_chatter_sweep.py [chart]

The sweep: a 1,000-design tolerance study of the thesis rig, Hertz,
N = 16 (d ~ normal(0.25, 0.01) in, y_s ~ uniform(0.45, 0.55) in), with
a progress bar (tqdm on stderr), on 1 and on 2 worker processes; again
with a 20 lb preload (the lower contact pressed nearly the whole window:
the costly case, every step after the impact a fixed step).  Beside it
the same designs simulated one by one in this process (the sum of the
simulate() calls a sweep makes), which bounds what the sweep's own
machinery costs.  ``chart``: also `contactsep study preload` (Hertz,
N = 32) on 1 and 2 workers.
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np
from bench_chatter import best  # this folder: run as a script

from contactsep.chatter import simulate
from contactsep.model import thesis_design
from contactsep.studies import chatter_sweep, preload, runner, sweep


def spec(preload_lb=None):
    settings = {} if preload_lb is None else {"preload": preload_lb}
    return sweep.make_spec(sample=["d=normal(0.25,0.01)",
                                   "ys=uniform(0.45,0.55)"],
                           samples=1000, seed=1, base={"n_modes": 16},
                           model="hertz", settings=settings)


def one_by_one(s) -> float:
    """The sweep's simulate() calls, in this process, timed alone."""
    inputs = sweep.chunk_inputs(s, 0, s.size)
    total = 0.0
    for d, ys in zip(inputs["h2"], inputs["ys"]):
        design = thesis_design(d=float(d), ys=float(ys), n_modes=16)
        start = time.perf_counter()
        simulate(design, model="hertz", samples=1, single_impulse=False,
                 **{**chatter_sweep.DEFAULT_SETTINGS, **s.settings})
        total += time.perf_counter() - start
    return total


def main(argv) -> None:
    x = np.random.default_rng(0).random(1_000_000)
    sine = best(lambda: np.sin(x), 20)
    rows = []
    cores = os.cpu_count() or 1
    for label, load in (("no preload", None), ("preload 20 lb", 20.0)):
        s = spec(load)
        rows.append((f"{label}: simulate() one by one", one_by_one(s)))
        for workers in sorted({1, cores}):
            start = time.perf_counter()
            summary = runner.run_sweep(s, workers=workers, progress=True)
            rows.append((f"{label}: sweep, {workers} worker(s), progress "
                         f"bar (p_open {summary['p_open']:.3g})",
                         time.perf_counter() - start))
    if "chart" in argv:
        for workers in sorted({1, cores}):
            start = time.perf_counter()
            chart = preload.preload_chart(workers=workers)
            runs = next(n for n in chart.notes if "simulations" in n)
            rows.append((f"study preload, N = 32, {workers} worker(s), "
                         f"{runs}", time.perf_counter() - start))
    print(f"numpy.sin, 1e6 float64: {sine * 1e3:.2f} ms; {cores} cores\n")
    print("| run (1,000 designs, Hertz N = 16) | s | ms a design | "
          "x numpy.sin a design |")
    print("|---|---:|---:|---:|")
    for label, seconds in rows:
        per = seconds / (1000 if "chart" not in label else 1)
        print(f"| {label} | {seconds:.1f} | {per * 1e3:.1f} | "
              f"{per / sine:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
