"""Where a Dask sweep's time goes (issue 29, item 1): the eq. 23
tolerance sweep on the local pool and on a Dask LocalCluster of k
single-threaded workers, with Dask's task stream of the second.

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_dask_timeline.py \\
        [--workers K] [--designs N] [--chunk-size C]

Printed: the local pool's seconds; Dask's seconds, its chunks, the sum
of their compute times, the workers' utilisation (that sum / (k x
wall)), the median and longest chunk, how long before the first chunk
started and after the last ended; per worker, the chunks it ran and the
gaps between one chunk's end and its next one's start.  Utilisation
well under 1 with short chunks and long gaps means the workers waited
for the parent (its fetches, its submissions); a compute sum well above
the local pool's CPU time means the chunks themselves ran slower.
"""

from __future__ import annotations

import argparse
import collections
import statistics
import time

from contactsep.studies.sweep import run as runner

from contactsep.studies.sweep import spec as sweep
def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--designs", type=int, default=2_000_000)
    parser.add_argument("--chunk-size", type=int, default=None)
    args = parser.parse_args()
    import distributed
    k, cs = args.workers, args.chunk_size
    spec = sweep.make_spec(sample=["d=normal(0.25,0.01)",
                                   "ys=uniform(0.45,0.55)"],
                           samples=args.designs, seed=1)
    warm = sweep.make_spec(sample=["d=normal(0.25,0.01)"], samples=4 * k)
    start = time.perf_counter()
    runner.run_sweep(spec, threshold=0.115, workers=k, progress=False,
                     chunk_size=cs)
    print(f"local pool, {k} workers: {time.perf_counter() - start:.2f} s",
          flush=True)
    with distributed.LocalCluster(n_workers=k, threads_per_worker=1,
                                  processes=True, dashboard_address=None
                                  ) as cluster, \
            distributed.Client(cluster) as client:
        runner.run_sweep(warm, scheduler=client, progress=False)
        with distributed.get_task_stream(client) as stream:
            t0 = time.time()
            runner.run_sweep(spec, threshold=0.115, scheduler=client,
                             progress=False, chunk_size=cs)
            t1 = time.time()
    tasks = [t for t in stream.data if t["key"].startswith("chunk_result")]
    spans = [(s["start"], s["stop"], t["worker"]) for t in tasks
             for s in t["startstops"] if s["action"] == "compute"]
    compute = [b - a for a, b, _ in spans]
    wall = t1 - t0
    print(f"dask, {k} workers: {wall:.2f} s, {len(tasks)} chunks, compute "
          f"{sum(compute):.2f} s, utilisation "
          f"{sum(compute) / (k * wall):.2f}, chunk median "
          f"{statistics.median(compute):.3f} s, longest "
          f"{max(compute):.3f} s, first start after "
          f"{min(a for a, _, _ in spans) - t0:.2f} s, last end "
          f"{t1 - max(b for _, b, _ in spans):.2f} s before the sweep's")
    by_worker = collections.defaultdict(list)
    for a, b, worker in spans:
        by_worker[worker].append((a, b))
    gaps = []
    for runs in by_worker.values():
        runs.sort()
        gaps += [runs[i + 1][0] - runs[i][1] for i in range(len(runs) - 1)]
    print(f"chunks a worker {sorted(len(r) for r in by_worker.values())}; "
          f"gaps between a worker's chunks: median "
          f"{statistics.median(gaps):.3f} s, mean "
          f"{statistics.mean(gaps):.3f} s, longest {max(gaps):.3f} s")


if __name__ == "__main__":
    main()
