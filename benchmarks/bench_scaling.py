"""Scaling of the sweeps on 1, 2, 4, ... usable cores, beside a
yardstick measured in the same run: one script for a session lent a
many-core machine, done in about ``--minutes`` (default 8).

    OPENBLAS_NUM_THREADS=1 nice python benchmarks/bench_scaling.py \\
        [--minutes M] [--max-workers K] [--eq23 DESIGNS] \
        [--hertz DESIGNS] [--repeat R] [--no-dask] [--no-robust] \
        [--preload [--preload-at K,K] [--preload-converged]]

The budget: each sweep's cost a design is measured first on one worker
(a small calibration sweep), and its size (unless ``--eq23``/``--hertz``
give it) is then chosen so that its runs on every engine and worker
count, at the yardstick's speed-ups, take its share of ``--minutes``
(eq. 23 and Hertz 40 % each, the robust search the rest); the plan is
printed before the runs.  The robust search (unless ``--no-robust``): a
robust preload of the light beryllium-copper relay at N = 4 (fixed step
1e-8 s, window 5 ms, no static correction, ``--robust-samples`` draws of
y_s), on the local pool and on a Dask LocalCluster of the same worker
counts (2 and the most), so that Dask / local for a search is measured
beside the sweeps'.

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

from contactsep.runs.pool import usable_cores
from contactsep.studies.sweep import run as runner

from contactsep.studies.sweep import spec as sweep
#: search takes the rest).
SHARES = {"eq23": 0.4, "hertz": 0.4}
#: Designs of the calibration sweeps (eq. 23, Hertz N = 16).
CALIBRATION = {"eq23": 50_000, "hertz": 8}
#: Smallest sizes the budget may choose (a sweep shorter than its
#: start-up says nothing about scaling).
SMALLEST = {"eq23": 100_000, "hertz": 16}


def _sin_kernel(_):
    x = np.linspace(0.0, 1.0, 1_000_000)
    for _ in range(60):
        np.sin(x)


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


def sweep_specs(eq23: int, hertz: int) -> dict:
    """The two sweeps (spec, threshold) at the given sizes."""
    return {
        "eq23": (sweep.make_spec(sample=["d=normal(0.25,0.01)",
                                         "ys=uniform(0.45,0.55)"],
                                 samples=eq23, seed=1), 0.115),
        "hertz": (sweep.make_spec(vary=[f"h2=0.1:0.8:{hertz}"],
                                  model="hertz", base={"n_modes": 16}),
                  None)}


def planned_sizes(args, ks, sticks, engines) -> dict:
    """Each sweep's size: as given, or the budget's (module doc)."""
    given = {"eq23": args.eq23, "hertz": args.hertz}
    if all(v is not None for v in given.values()):
        return given
    # the sum over configurations of 1 / (the yardstick's speed-up)
    inverse = sum(sticks[k] / (k * sticks[1]) for k in ks) * \
        len(engines) * args.repeat
    calibration = sweep_specs(CALIBRATION["eq23"], CALIBRATION["hertz"])
    sizes = {}
    for name, size in given.items():
        if size is not None:
            sizes[name] = size
            continue
        spec, threshold = calibration[name]
        seconds, _ = timed_sweep(spec, threshold, 1, False)
        each = seconds / CALIBRATION[name]
        budget = SHARES[name] * 60.0 * args.minutes
        sizes[name] = max(SMALLEST[name], int(budget / (each * inverse)))
        print(f"{name}: {1e6 * each:.3g} us a design on one worker; "
              f"{sizes[name]:,} designs fit {budget:.0f} s", flush=True)
    return sizes


def timed_robust(k: int, samples: int, dask: bool, modes: int = 4):
    """(seconds, parent CPU seconds, answer's JSON) of the robust
    search (module doc) on k local workers or k Dask workers."""
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..",
                                    "tests"))
    from design_family import FAMILY

    import contactsep
    design = FAMILY["becu_light"].replace(n_modes=modes)
    options = {"tolerance": ["ys=uniform(0.029,0.031)"], "samples": samples,
                   "p_target": 0.6, "converge": False, "dt": 1e-8, "t_end": 0.005,
                   "static_correction": False}
    if modes != 4:
        # runs as long as a designer's: the design's own numerics
        for name in ("dt", "t_end", "static_correction"):
            options.pop(name)
    if dask:
        import distributed
        with distributed.LocalCluster(
                n_workers=k, threads_per_worker=1, processes=True,
                dashboard_address=None) as cluster, \
                distributed.Client(cluster) as client:
            # the workers import the compiled modules once, as a
            # long-lived cluster's have
            client.run(lambda: __import__("contactsep.chatter"))
            cpu, start = _cpu(), time.perf_counter()
            answer = contactsep.preload(design, workers=client, **options)
            return (time.perf_counter() - start, _cpu() - cpu,
                    answer.to_json_dict())
    cpu, start = _cpu(), time.perf_counter()
    answer = contactsep.preload(design, workers=k, **options)
    return time.perf_counter() - start, _cpu() - cpu, answer.to_json_dict()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--minutes", type=float, default=8.0,
                        help="the budget that sizes the sweeps")
    parser.add_argument("--max-workers", type=int, default=None,
                        help="most workers (default: the usable cores)")
    parser.add_argument("--eq23", type=int, default=None,
                        help="designs of the eq. 23 sweep (default: "
                             "the budget's)")
    parser.add_argument("--hertz", type=int, default=None,
                        help="designs of the Hertz N = 16 sweep "
                             "(default: the budget's)")
    parser.add_argument("--no-robust", action="store_true",
                        help="leave out the robust search")
    parser.add_argument("--robust-samples", type=int, default=12,
                        help="draws of the robust search")
    parser.add_argument("--robust-modes", type=int, default=4,
                        help="its modes (other than 4: the design's own "
                             "step, window and static correction)")
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
    start_all = time.perf_counter()
    cores = usable_cores()
    if args.max_workers is not None:
        cores = max(1, min(cores, args.max_workers))
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
    engines = ("local",) + (() if args.no_dask else ("dask",))
    sweeps = {} if args.no_sweeps else \
        sweep_specs(**planned_sizes(args, ks, sticks, engines))
    warm = {"eq23": sweep.make_spec(sample=["d=normal(0.25,0.01)"],
                                    samples=4 * max(ks)),
            "hertz": sweep.make_spec(vary=[f"h2=0.2:0.3:{2 * max(ks)}"],
                                     model="hertz", base={"n_modes": 16})}
    print(f"\n{'sweep':>6} {'engine':>6} {'k':>3} {'seconds':>8} "
          f"{'speed-up':>8} {'efficiency':>10} {'dask/local':>10} "
          f"{'parent %':>8}")
    for name, (spec, threshold) in \
            sweeps.items():
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
    if not args.no_robust:
        robust_at = sorted({min(2, cores), cores})
        print(f"\n{'search':>6} {'engine':>6} {'k':>3} {'seconds':>8} "
              f"{'dask/local':>10} {'parent %':>8} same answer")
        for k in robust_at:
            local = timed_robust(k, args.robust_samples, False,
                                 args.robust_modes)
            rows = [("local", local)]
            if not args.no_dask:
                rows.append(("dask", timed_robust(k, args.robust_samples,
                                                  True, args.robust_modes)))
            for engine, (seconds, cpu, answer) in rows:
                ratio = f"{local[0] / seconds:10.2f}" \
                    if engine == "dask" else f"{'':>10}"
                share = f"{'-':>8}" if engine == "local" and k == 1 else \
                    f"{100 * cpu / (k * seconds):8.1f}"
                same = "yes" if answer == local[2] else "NO"
                print(f"{'robust':>6} {engine:>6} {k:3d} {seconds:8.2f} "
                      f"{ratio} {share} {same}", flush=True)
    if args.preload:
        from contactsep.studies.preload.chart import preload_chart
        at = (1, cores) if args.preload_at is None else \
            tuple(int(k) for k in args.preload_at.split(","))
        charts = [("N = 4", {"n_modes": 4})]
        if args.preload_converged:
            charts.append(("N = 32 converged", {"converge": True}))
        for label, options in charts:
            for k in at:
                start = time.perf_counter()
                preload_chart(workers=k, **options)
                print(f"preload chart {label}, {k} workers: "
                      f"{time.perf_counter() - start:.1f} s", flush=True)
    load = os.getloadavg()
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} at the "
          f"end; {time.perf_counter() - start_all:.0f} s in all")


if __name__ == "__main__":
    main()
