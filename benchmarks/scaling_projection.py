"""Efficiency at 16, 64 and 256 workers, projected from measured costs
(docs/performance.md, "Scaling on paper"):

    python benchmarks/scaling_projection.py [--parent-ms 0.5] [--save]

No machine with that many cores was lent; what a run on two cores
measures is each piece of the cost, and this script puts them together
in a discrete-event simulation of the run machinery:

* the parent hands out one task every ``--parent-ms`` of its own CPU
  (the measured per-task cost: the local pool's, or Dask's client and
  scheduler), and never more than ``window`` tasks are in flight a
  worker (the runner's window; the search submits whole batches);
* each worker runs its tasks one after the other; a task takes its
  measured duration;
* the efficiency is the work over W times the wall time.

The two workloads of the issue:

1. **A Hertz tolerance sweep of 1e5 designs at N = 16**: each design
   44 ms free (benchmarks/results/bench_chatter_sweep.md: 44.2 ms a
   design, CPU), cut into chunks by the sweep's own rule
   (:class:`contactsep.studies.chunks.Chunks`, fed the simulated chunk
   times), with and without a 20 lb preload (1.81 s a design);
2. **A 1,000-sample robust preload search**: a sequence of batches, each
   every sample at one to four preloads (the ceiling, the scan's batches
   of up to four, then one-preload bisection steps; 12 batches, as
   steel_relay's search), each run's time drawn from a log-normal with
   the measured spread of preloaded runs (median 1.5 s at N = 64, a
   factor 3 either way at one standard deviation), the batch handed out
   costliest first and waited for whole (the search needs every sample
   before it chooses the next preload).

The chunk size (sweep) and the batch shape (search) that keep each
workload at 90 % or above are printed beside.
"""

from __future__ import annotations

import argparse
import heapq
import math
import random
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

from contactsep.studies.chunks import Chunks  # noqa: E402

WORKERS = (16, 64, 256)
#: Measured a design (s): Hertz N = 16, free and at 20 lb.
DESIGN_S = {"free": 0.0442, "preloaded 20 lb": 1.806}
#: Robust search: batches (preloads each) of steel_relay's search shape.
SEARCH_BATCHES = (1, 4, 4, 4, 1, 1, 1, 1, 1, 1, 1, 1)
RUN_MEDIAN_S = 1.5
RUN_SIGMA = math.log(3.0)


def simulate(durations, workers: int, parent_s: float,
             window: int | None = None) -> float:
    """Wall time of ``durations`` (s, in hand-out order) on ``workers``,
    the parent spending ``parent_s`` a task and keeping at most
    ``window`` tasks a worker in flight (None: no limit)."""
    free = [0.0] * workers          # when each worker is next free
    heapq.heapify(free)
    in_flight: list[float] = []     # end times of the running tasks
    clock, end = 0.0, 0.0
    limit = None if window is None else window * workers
    for duration in durations:
        clock += parent_s           # the parent's own work on the task
        if limit is not None:
            while in_flight and len(in_flight) >= limit:
                clock = max(clock, heapq.heappop(in_flight))
        start = max(clock, heapq.heappop(free))
        finish = start + duration
        heapq.heappush(free, finish)
        heapq.heappush(in_flight, finish)
        end = max(end, finish)
    return end


def sweep_chunks(designs: int, design_s: float, workers: int,
                 chunk_size: int) -> list[float]:
    """The chunk durations the sweep's own sizing rule gives."""
    bounds = Chunks(designs, chunk_size, 16, workers=workers)
    out = []
    for first, last in bounds:
        seconds = (last - first) * design_s
        bounds.record(last - first, seconds)
        out.append(seconds)
    return out


def sweep_row(kind: str, workers: int, parent_s: float) -> tuple:
    durations = sweep_chunks(100_000, DESIGN_S[kind], workers, 100_000)
    wall = simulate(durations, workers, parent_s, window=4)
    work = sum(durations)
    return len(durations), work / (workers * wall)


def search_durations(samples: int, seed: int) -> list[list[float]]:
    rng = random.Random(seed)
    return [sorted((rng.lognormvariate(math.log(RUN_MEDIAN_S), RUN_SIGMA)
                    for _ in range(samples * preloads)), reverse=True)
            for preloads in SEARCH_BATCHES]


def search_row(workers: int, parent_s: float, samples: int = 1000,
               seed: int = 1) -> float:
    batches = search_durations(samples, seed)
    wall = sum(simulate(b, workers, parent_s) for b in batches)
    work = sum(sum(b) for b in batches)
    return work / (workers * wall)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--parent-ms", type=float, action="append",
                        help="the parent's CPU a task (ms; repeatable; "
                             "default 0.5 and 1.0)")
    parser.add_argument("--save", action="store_true",
                        help="also write benchmarks/results/"
                             "scaling_projection.md")
    args = parser.parse_args(argv)
    parents = args.parent_ms or [0.5, 1.0]
    lines = ["| workload | parent ms a task | tasks | "
             + " | ".join(f"{w} workers" for w in WORKERS) + " |",
             "|---|---:|---:|" + "---:|" * len(WORKERS)]
    for parent_ms in parents:
        parent_s = parent_ms / 1e3
        for kind in DESIGN_S:
            cells, count = [], 0
            for workers in WORKERS:
                count, efficiency = sweep_row(kind, workers, parent_s)
                cells.append(f"{100 * efficiency:.1f} %")
            lines.append(f"| 1e5-design Hertz N = 16 sweep, {kind} | "
                         f"{parent_ms:g} | {count:,} chunks | "
                         + " | ".join(cells) + " |")
        cells = [f"{100 * search_row(w, parent_s):.1f} %" for w in WORKERS]
        runs = 1000 * sum(SEARCH_BATCHES)
        lines.append(f"| 1,000-sample robust search, N = 64 | {parent_ms:g}"
                     f" | {runs:,} runs | " + " | ".join(cells) + " |")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    if args.save:
        command = " ".join(["python benchmarks/scaling_projection.py",
                            *(argv if argv is not None else sys.argv[1:])])
        (ROOT / "benchmarks" / "results" / "scaling_projection.md"
         ).write_text(f"<!-- {command} -->\n{text}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
