"""Efficiency at 16, 64 and 256 workers, projected from measured costs
(docs/performance-parallel.md, "Scaling on paper"):

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
   (:class:`contactsep.runs.chunks.Chunks`, fed the simulated chunk
   times), with and without a 20 lb preload (1.81 s a design);
2. **A 1,000-sample robust preload search**: a sequence of batches, each
   every sample at one to four preloads (the ceiling, the scan's batches
   of four, then eight one-preload bisection steps, as steel_relay's
   search; or speculative steps of 3 or 7 preloads, which take 4 or 3
   batches for the same eight bits), each run's time drawn from a log-normal with
   the measured spread of preloaded runs (median 1.5 s at N = 64, a
   factor 3 either way at one standard deviation), the batch handed out
   costliest first and waited for whole (the search needs every sample
   before it chooses the next preload).

The search rows give the efficiency over every run made and, beside
it, the wall time relative to one preload a bisection step (what the
designer waits for).
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

from contactsep.runs.chunks import Chunks

WORKERS = (16, 64, 256)
#: Measured a design (s): Hertz N = 16, free and at 20 lb.
DESIGN_S = {"free": 0.0442, "preloaded 20 lb": 1.806}
#: Robust search: the bisection's steps after the ceiling and the scan
#: (steel_relay's search: 1 + 3 x 4 + 8 x 1 preloads).
BISECTION_BITS = 8
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
        if limit is not None:       # a full window: wait for a result
            while in_flight and len(in_flight) >= limit:
                clock = max(clock, heapq.heappop(in_flight))
        clock += parent_s           # the parent's own work on the task
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


def search_shape(candidates: int = 1) -> list[int]:
    """Preloads of each batch: the ceiling, the scan's three batches of
    four, then BISECTION_BITS of bisection, ``candidates`` preloads a
    step (a speculative step tries that many at once: it gains
    log2(candidates + 1) bits, so it takes fewer, wider batches)."""
    bits = math.log2(candidates + 1)
    steps = math.ceil(BISECTION_BITS / bits - 1e-9)
    return [1, 4, 4, 4] + [candidates] * steps


def search_durations(samples: int, seed: int,
                     candidates: int = 1) -> list[list[float]]:
    rng = random.Random(seed)
    return [sorted((rng.lognormvariate(math.log(RUN_MEDIAN_S), RUN_SIGMA)
                    for _ in range(samples * preloads)), reverse=True)
            for preloads in search_shape(candidates)]


def search_row(workers: int, parent_s: float, samples: int = 1000,
               seed: int = 1, candidates: int = 1) -> tuple:
    """(runs, efficiency, wall relative to one candidate a step) of the
    search; the efficiency counts every run made, the wall time is what
    the designer waits."""
    def wall_of(k):
        return sum(simulate(b, workers, parent_s)
                   for b in search_durations(samples, seed, k))
    batches = search_durations(samples, seed, candidates)
    wall = wall_of(candidates)
    work = sum(sum(b) for b in batches)
    runs = sum(len(b) for b in batches)
    return runs, work / (workers * wall), wall / wall_of(1)


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
        for candidates in (1, 3, 7):
            rows = [search_row(w, parent_s, candidates=candidates)
                    for w in WORKERS]
            cells = [f"{100 * e:.1f} % (wall x{r:.2f})" for _, e, r in rows]
            lines.append(f"| 1,000-sample robust search, N = 64, "
                         f"{candidates} preload(s) a bisection step | "
                         f"{parent_ms:g} | {rows[0][0]:,} runs | "
                         + " | ".join(cells) + " |")
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from results import Report
    say = Report()
    say("\n".join(lines))
    if args.save:
        say.save("scaling_projection", "python benchmarks/"
                 "scaling_projection.py " + " ".join(
                     sys.argv[1:] if argv is None else argv))
    return 0


if __name__ == "__main__":
    sys.exit(main())
