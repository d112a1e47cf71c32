"""The parent's cost per task of a batch of simulations on Dask (the
preload searches and the studies: dask_map.run_tasks): N no-op tasks on
a LocalCluster of k single-threaded worker processes, the parent's CPU
seconds (time.process_time: every thread of this process, Dask's event
loop included) and wall seconds per task.

    python benchmarks/bench_dask_tasks.py [--tasks N] [--workers K]
        [--repeat R] [--cluster local|subprocess]

``--cluster local`` (the default): a LocalCluster(processes=True), whose
scheduler runs in this process, so that the parent's CPU counts the
scheduler's too; ``subprocess``: Dask's SubprocessCluster, the scheduler
in a process of its own as ``dask scheduler`` runs it, so that the
parent is the client alone (``contactsep preload --scheduler-file``).

Two ways, in turn on the same cluster: ``run_tasks`` (one client.map,
results fetched as they arrive) and ``one at a time``, the way it
replaced (one client.submit per task, and after each wait a scan of
every unfinished future), kept here as the yardstick.  Each the best of
R runs.  A no-op task measures the parent alone: a simulation's own
time is spent on the workers.
"""

from __future__ import annotations

import argparse
import time

from contactsep.studies import dask_map, dask_run


def noop(task):
    """A task that does nothing on the worker."""
    return task


def one_at_a_time(client, function, tasks: list) -> list:
    """run_tasks as it was: a submit per task (the costliest the highest
    priority), then for each task a wait and a gather of all the
    finished ones among those left."""
    count = len(tasks)
    futures = {i: client.submit(dask_map.on_worker, function, task,
                                pure=False, priority=count - i)
               for i, task in enumerate(tasks)}
    index = {future.key: i for i, future in futures.items()}
    out, have = [None] * count, set()
    for i in range(count):
        if i in have:
            continue
        out[i] = dask_run.wait(client, futures[i], dask_map._NoStop,
                               len(have))
        have.add(i)
        ready = dask_run.gather_finished(
            client, [f for j, f in futures.items() if j not in have])
        for key, result in ready.items():
            out[index[key]] = result
            have.add(index[key])
    return out


def measure(run, client, tasks: list) -> tuple[float, float]:
    """(parent CPU s, wall s) of one batch."""
    cpu, wall = time.process_time(), time.perf_counter()
    out = run(client, noop, tasks)
    cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    assert out == tasks
    return cpu, wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tasks", type=int, default=2000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--cluster", choices=("local", "subprocess"),
                        default="local")
    args = parser.parse_args()
    import distributed
    tasks = list(range(args.tasks))
    ways = {"run_tasks": dask_map.run_tasks, "one at a time": one_at_a_time}
    best = {name: (float("inf"), float("inf")) for name in ways}
    if args.cluster == "local":
        cluster = distributed.LocalCluster(
            n_workers=args.workers, threads_per_worker=1, processes=True,
            dashboard_address=None)
    else:
        from distributed.deploy.subprocess import SubprocessCluster
        cluster = SubprocessCluster(n_workers=args.workers,
                                    threads_per_worker=1,
                                    dashboard_address=None)
    with cluster, distributed.Client(cluster) as client:
        dask_map.run_tasks(client, noop, tasks[:20])        # warm
        for _ in range(args.repeat):
            for name, run in ways.items():
                cpu, wall = measure(run, client, tasks)
                best[name] = min(best[name][0], cpu), min(best[name][1],
                                                          wall)
    print(f"{args.tasks} no-op tasks, {args.workers} workers "
          f"({args.cluster} cluster), best of {args.repeat}:")
    for name, (cpu, wall) in best.items():
        print(f"  {name:14s} parent CPU {1e3 * cpu / args.tasks:.3f} ms a "
              f"task ({cpu:.2f} s), wall {1e3 * wall / args.tasks:.3f} ms "
              f"a task ({wall:.2f} s)")


if __name__ == "__main__":
    main()
