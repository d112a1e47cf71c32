"""Scaling of the sweeps on 1, 2, 4, ... usable cores (issue 29), beside
a yardstick measured in the same run.

    OPENBLAS_NUM_THREADS=1 nice python benchmarks/bench_scaling.py \\
        [--eq23 DESIGNS] [--hertz DESIGNS] [--repeat R] [--no-dask] \
        [--preload [--preload-at K,K] [--preload-converged]]

The yardstick: an embarrassingly parallel NumPy kernel (numpy.sin on 1e6
elements, 60 times) in k processes at once; its speed-up k * t1 / tk is
what the machine gives k processes (memory bandwidth, turbo, other
users).  Each sweep: an eq. 23 tolerance sweep (`--sample
'd=normal(0.25,0.01)' --sample 'ys=uniform(0.45,0.55)' --threshold
0.115`, summary only) and a Hertz chatter sweep (N = 16, h2 varied), on
the local pool (``workers=k``; k = 1 runs in this process) and on a Dask
LocalCluster of k single-threaded worker processes.  Printed per row:
seconds, speed-up over one worker, efficiency = speed-up / the
yardstick's speed-up at k, Dask's throughput / the local pool's at the
same k, and the parent's CPU share = the parent's CPU seconds / (k x
wall seconds).  ``--preload``: the time of the preload chart (N = 4) on
1 and on all usable cores (``--preload-at K,K,...``: on those numbers
of workers instead; ``--preload-converged``: also the converged chart,
N = 32 checked at 2N, as ``contactsep study preload --converge``).  ``--repeat R``: each time the best of R
runs, the configurations taken in turn (on a shared machine the load
drifts between one configuration and the next).
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import resource
import sys
import time

import numpy as np

from contactsep.studies import runner, sweep


def _sin_kernel(_):
    x = np.linspace(0.0, 1.0, 1_000_000)
    for _ in range(60):
        np.sin(x)
    return None


def yardstick(k: int) -> float:
    """Seconds for k processes each running the kernel once, at once."""
    with multiprocessing.get_context("fork").Pool(k) as pool:
        pool.map(_sin_kernel, range(k))          # warm the processes
        start = time.perf_counter()
        pool.map(_sin_kernel, range(k), chunksize=1)
        return time.perf_counter() - start


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def timed_sweep(spec, threshold, k, dask, warm=None):
    """(seconds, parent CPU seconds) of one summary-only sweep; on Dask
    after ``warm``, a small sweep of the same model on the new cluster
    (its workers import the compiled modules once, as a long-lived
    cluster's have; the local pool's workers are forked from a parent
    that has them)."""
    if dask:
        import distributed
        with distributed.LocalCluster(
                n_workers=k, threads_per_worker=1, processes=True,
                dashboard_address=None) as cluster, \
                distributed.Client(cluster) as client:
            if warm is not None:
                runner.run_sweep(warm, scheduler=client, progress=False)
            cpu, start = _cpu(), time.perf_counter()
            runner.run_sweep(spec, threshold=threshold, scheduler=client,
                             progress=False)
            return time.perf_counter() - start, _cpu() - cpu
    cpu, start = _cpu(), time.perf_counter()
    runner.run_sweep(spec, threshold=threshold, workers=k, progress=False)
    return time.perf_counter() - start, _cpu() - cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--eq23", type=int, default=2_000_000,
                        help="designs of the eq. 23 sweep")
    parser.add_argument("--hertz", type=int, default=200,
                        help="designs of the Hertz N = 16 sweep")
    parser.add_argument("--repeat", type=int, default=1,
                        help="best of R runs of each configuration")
    parser.add_argument("--no-dask", action="store_true")
    parser.add_argument("--preload", action="store_true")
    parser.add_argument("--preload-at", default=None,
                        help="worker counts of the preload chart "
                             "(default: 1 and all usable cores)")
    parser.add_argument("--preload-converged", action="store_true",
                        help="also time the converged N = 32 chart")
    parser.add_argument("--no-sweeps", action="store_true",
                        help="only the yardstick and the preload chart")
    args = parser.parse_args()
    cores = runner.usable_cores()
    ks = [1]
    while ks[-1] * 2 <= cores:
        ks.append(ks[-1] * 2)
    if ks[-1] != cores:
        ks.append(cores)
    load = os.getloadavg()
    print(f"usable cores {cores}; load average {load[0]:.2f} "
          f"{load[1]:.2f} {load[2]:.2f} at the start")
    sticks = {k: yardstick(k) for k in ks}
    print(f"{'k':>3} {'yardstick s':>11} {'speed-up':>8}")
    for k in ks:
        print(f"{k:3d} {sticks[k]:11.2f} {k * sticks[1] / sticks[k]:8.2f}")
    sweeps = {
        "eq23": (sweep.make_spec(sample=["d=normal(0.25,0.01)",
                                         "ys=uniform(0.45,0.55)"],
                                 samples=args.eq23, seed=1), 0.115),
        "hertz": (sweep.make_spec(vary=[f"h2=0.1:0.8:{args.hertz}"],
                                  model="hertz", base={"n_modes": 16}),
                  None)}
    warm = {"eq23": sweep.make_spec(sample=["d=normal(0.25,0.01)"],
                                    samples=4 * max(ks)),
            "hertz": sweep.make_spec(vary=[f"h2=0.2:0.3:{2 * max(ks)}"],
                                     model="hertz", base={"n_modes": 16})}
    print(f"\n{'sweep':>6} {'engine':>6} {'k':>3} {'seconds':>8} "
          f"{'speed-up':>8} {'efficiency':>10} {'dask/local':>10} "
          f"{'parent %':>8}")
    engines = ("local",) + (() if args.no_dask else ("dask",))
    for name, (spec, threshold) in \
            ({} if args.no_sweeps else sweeps).items():
        runs = {}
        for _ in range(args.repeat):
            for engine in engines:
                for k in ks:
                    seconds, cpu = timed_sweep(spec, threshold, k,
                                               engine == "dask", warm[name])
                    # as it goes (stderr): a run cut short keeps its rows
                    print(f"{name} {engine} k = {k}: {seconds:.2f} s",
                          file=sys.stderr, flush=True)
                    if (engine, k) not in runs or \
                            seconds < runs[engine, k][0]:
                        runs[engine, k] = (seconds, cpu)
        for engine in engines:
            for k in ks:
                seconds, cpu = runs[engine, k]
                local = runs["local", k][0]
                speedup = runs["local", 1][0] / seconds
                efficiency = speedup / (k * sticks[1] / sticks[k])
                ratio = f"{local / seconds:10.2f}" \
                    if engine == "dask" else f"{'':>10}"
                # k = 1 on the local pool runs in the parent: no share
                share = f"{'-':>8}" if engine == "local" and k == 1 else \
                    f"{100 * cpu / (k * seconds):8.1f}"
                print(f"{name:>6} {engine:>6} {k:3d} {seconds:8.2f} "
                      f"{speedup:8.2f} {efficiency:10.2f} {ratio} "
                      f"{share}", flush=True)
    if args.preload:
        from contactsep.studies.preload import preload_chart
        at = (1, cores) if args.preload_at is None else \
            tuple(int(k) for k in args.preload_at.split(","))
        charts = [("N = 4", dict(n_modes=4))]
        if args.preload_converged:
            charts.append(("N = 32 converged", dict(converge=True)))
        for label, options in charts:
            for k in at:
                start = time.perf_counter()
                preload_chart(workers=k, **options)
                print(f"preload chart {label}, {k} workers: "
                      f"{time.perf_counter() - start:.1f} s", flush=True)
    load = os.getloadavg()
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} at the "
          f"end")


if __name__ == "__main__":
    main()
