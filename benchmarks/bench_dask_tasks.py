"""The parent's cost per task of a batch of simulations on Dask (the
preload searches and the studies: dask_map.run_tasks): N no-op tasks on
a cluster of k single-threaded worker processes, the parent's CPU
seconds (time.process_time: every thread of this process, Dask's event
loop included) and wall seconds per task.

    python benchmarks/bench_dask_tasks.py [--tasks N,N] [--workers K]
        [--repeat R] [--cluster local,subprocess] [--save]

Clusters: ``local``, a LocalCluster(processes=True), whose scheduler
runs in this process, so that the parent's CPU counts the scheduler's
too; ``subprocess``, Dask's SubprocessCluster, the scheduler in a
process of its own as ``dask scheduler`` runs it, so that the parent is
the client alone (``contactsep preload --scheduler-file``).  Two ways,
in turn on each cluster: ``run_tasks`` (one client.map, results fetched
as they arrive) and ``one at a time``, the way it replaced (one
client.submit per task, and after each wait a scan of every unfinished
future), kept here as the yardstick; and ``dask floor``, Dask's own
least cost (one map, one wait, one gather: no result before the last).
Each the best of R runs.  A no-op
task measures the parent alone: a simulation's own time is spent on the
workers.  ``--save``: the table into
benchmarks/results/bench_dask_tasks.md.
"""

from __future__ import annotations

import argparse
import os
import sys
import time

from contactsep.runs import dask_map, dask_run


def on_worker(function, task):
    """``function(task)`` on a Dask worker, with glibc's own heap
    thresholds, as a one-run pack does (dask_packs.run_pack): the
    yardsticks' task."""
    dask_run.heap_as_glibc_default()
    return function(task)


def noop(task):
    """A task that does nothing on the worker."""
    return task


def one_at_a_time(client, function, tasks: list) -> list:
    """run_tasks as it was: a submit per task (the costliest the highest
    priority), then for each task a wait and a gather of all the
    finished ones among those left."""
    count = len(tasks)
    futures = {i: client.submit(on_worker, function, task,
                                pure=False, priority=count - i)
               for i, task in enumerate(tasks)}
    index = {future.key: i for i, future in futures.items()}
    out, have = [None] * count, set()
    for i in range(count):
        if i in have:
            continue
        out[i] = futures[i].result()
        have.add(i)
        # a gather of all the finished ones among those left (the
        # scan of every pending future the one Dask loop does without)
        ready = [f for j, f in futures.items()
                 if j not in have and f.status == "finished"]
        for future, result in zip(ready, client.gather(ready)):
            out[index[future.key]] = result
            have.add(index[future.key])
    return out


def dask_floor(client, function, tasks: list) -> list:
    """Dask's own least cost of a batch: one map, one wait for all, one
    gather (no result before the last: no journal could keep them)."""
    import distributed
    futures = client.map(on_worker, [function] * len(tasks), tasks,
                         pure=False)
    distributed.wait(futures)
    return client.gather(futures)


def measure(run, client, tasks: list) -> tuple[float, float]:
    """(parent CPU s, wall s) of one batch."""
    cpu, wall = time.process_time(), time.perf_counter()
    out = run(client, noop, tasks)
    cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    assert out == tasks
    return cpu, wall


def cluster(kind: str, workers: int):
    """A cluster of ``workers`` single-threaded worker processes."""
    import distributed
    if kind == "local":
        return distributed.LocalCluster(
            n_workers=workers, threads_per_worker=1, processes=True,
            dashboard_address=None)
    from distributed.deploy.subprocess import SubprocessCluster
    return SubprocessCluster(n_workers=workers, threads_per_worker=1,
                             dashboard_address=None)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tasks", default="2000",
                        help="tasks in a batch (comma-separated: each)")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--cluster", default="local,subprocess",
                        help="local, subprocess or both (comma-separated)")
    parser.add_argument("--save", action="store_true",
                        help="also into benchmarks/results/"
                             "bench_dask_tasks.md")
    args = parser.parse_args()
    import distributed
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from results import Report
    say = Report()
    sizes = [int(size) for size in args.tasks.split(",")]
    ways = {"run_tasks": dask_map.run_tasks, "one at a time": one_at_a_time,
            "dask floor": dask_floor}
    say(f"No-op tasks, {args.workers} single-threaded workers, best of "
        f"{args.repeat}:")
    say()
    say("| cluster | tasks | way | parent CPU (ms a task) | wall (ms a "
        "task) |")
    say("|---|---:|---|---:|---:|")
    for kind in args.cluster.split(","):
        with cluster(kind, args.workers) as running, \
                distributed.Client(running) as client:
            dask_map.run_tasks(client, noop, list(range(20)))   # warm
            for size in sizes:
                tasks = list(range(size))
                best = {name: (float("inf"), float("inf")) for name in ways}
                for _ in range(args.repeat):
                    for name, run in ways.items():
                        cpu, wall = measure(run, client, tasks)
                        best[name] = (min(best[name][0], cpu),
                                      min(best[name][1], wall))
                for name, (cpu, wall) in best.items():
                    say(f"| {kind} | {size} | {name} | "
                        f"{1e3 * cpu / size:.3f} | {1e3 * wall / size:.3f} "
                        f"|")
    if args.save:
        say.save("bench_dask_tasks", "python benchmarks/bench_dask_tasks.py "
                 + " ".join(sys.argv[1:]))


if __name__ == "__main__":
    main()
