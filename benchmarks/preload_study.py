"""The preload chart's numbers checked (docs/preload-family.md, "The preload
chart"), on the local cores:

    OPENBLAS_NUM_THREADS=1 python benchmarks/preload_study.py [PART ...]

Parts (default: convergence, check, monotone):

* ``convergence``: the thesis rig's answer (Hertz, d = 0.25 in,
  y_s = 0.5 in), elastic, N = 16, 32, 64 at the default dt (5e-8 s)
  and at 2.5e-8 s: the chart's search, the designs of each batch run
  together (a few minutes on two cores).  ``convergence-full`` adds
  N = 8, 128, 256, dt = 1e-7 and 1.25e-8 s and Flores damping
  (e = 0.375) for N = 16 ... 128 (about half an hour).
* ``check``: each row of a chart (``--chart CSV``, default
  docs/studies/preload.csv) simulated 3 % above (no event expected) and
  3 % below (an event expected) its preload, at the row's own N and
  step.
* ``monotone``: each row of the chart scanned finely, 0.80-1.25 times
  its preload in 1 % steps (at the row's own N and step): where
  "closed" is not monotone.

(The chart's convergence in N, each row checked at twice its N and half
its step and searched again where it moves: ``contactsep study preload
--converge``, contactsep.studies.preload.converge, which replaced this
script's chart-bracket, chart-rows and chart-convergence parts.)
"""

from __future__ import annotations

import csv
import sys
import time

import numpy as np

import contactsep
from contactsep.studies.preload import chart as preload
from contactsep.studies.preload.runs import PreloadRun

CHART = "docs/studies/preload.csv"
#: The chart's numerics (preload_chart gives them explicitly: the thesis
#: rig's step and the listing's window, not each design's own).
CHART_SETTINGS = {"dt": 5e-8, "t_end": 0.06}


def row_settings(row):
    """A chart row's numerics: the chart's, at the row's own step (a
    converged chart's rows differ)."""
    return {**CHART_SETTINGS,
            "dt": float(row.get("dt_s") or CHART_SETTINGS["dt"])}


def read_chart(path):
    with open(path) as handle:
        return list(csv.DictReader(line for line in handle
                                   if not line.startswith("#")))


def run_all(tasks, workers=None):
    """(design, model, settings, preload) tasks on the local cores;
    returns the ChatterResults' (n_events, longest_open_s)."""
    from concurrent.futures import ProcessPoolExecutor
    with ProcessPoolExecutor(workers) as pool:
        return list(pool.map(_summary, tasks, chunksize=1))


def _summary(task):
    from contactsep.chatter import simulate
    design, model, settings, load = task
    r = simulate(design, model=model, preload=load, samples=1,
                 single_impulse=False, **settings)
    return r.n_events, r.longest_open_s


def convergence(full=False) -> None:
    """The thesis rig's answer at N = 16, 32, 64, each at the default dt
    and at half of it (``full``: also N = 8, 128, 256, dt down to
    1.25e-8 s and Flores damping: about half an hour on two cores)."""
    cases = [(n, dt, "none") for n in (16, 32, 64)
             for dt in (None, 2.5e-8)]
    if full:
        cases += [(n, None, "none") for n in (8, 128, 256)] + [
            (n, dt, "none") for n, dt in ((32, 1e-7), (32, 1.25e-8),
                                          (128, 2.5e-8))] + [
            (n, None, "flores") for n in (16, 32, 64, 128)] + [
            (32, 2.5e-8, "flores")]
    designs = [contactsep.thesis_design(d=0.25, ys=0.5, n_modes=n)
               for n, _, _ in cases]
    settings = [{"damping": damping, **CHART_SETTINGS,
                 **({} if dt is None else {"dt": dt})}
                for _, dt, damping in cases]
    start = time.perf_counter()
    with preload.Simulations() as sims:
        def has_event(tasks):
            return sims.events([PreloadRun(designs[row], "hertz",
                                           settings[row], p)
                                for row, p in tasks])
        found = preload.search(len(cases), has_event)
    print(f"thesis rig, Hertz, d = 0.25 in, y_s = 0.5 in "
          f"({sims.runs} simulations, {time.perf_counter() - start:.0f} s)")
    print("| damping | N | dt (s) | min preload (lb) | runs | closed below "
          "it (lb) |")
    print("|---|---|---|---:|---:|---|")
    for (n, dt, damping), result in zip(cases, found):
        below = result.closed_below
        text = f"{len(below)} from {min(below):.4g} to {max(below):.4g}" \
            if below else "-"
        print(f"| {damping} | {n} | {dt or 5e-8:g} | "
              f"{result.min_preload_lb:.4g} | {len(result.tested)} | "
              f"{text} |")


def check(path=CHART) -> None:
    rows = [r for r in read_chart(path)
            if np.isfinite(float(r["min_preload_lb"]))]
    tasks = []
    for r in rows:
        design = contactsep.thesis_design(d=float(r["d_in"]),
                                          ys=float(r["ys_in"]),
                                          n_modes=int(r["n_modes"]))
        for factor in (0.97, 1.03):
            tasks.append((design, r["model"], row_settings(r),
                          factor * float(r["min_preload_lb"])))
    out = run_all(tasks)
    print("| d (in) | y_s (in) | N | min preload (lb) | events at -3 % | "
          "longest (us) | events at +3 % | longest (us) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for k, r in enumerate(rows):
        (below, lb), (above, la) = out[2 * k], out[2 * k + 1]
        print(f"| {r['d_in']} | {r['ys_in']} | {r['n_modes']} | "
              f"{float(r['min_preload_lb']):.4g} | {below} | {lb * 1e6:.1f}"
              f" | {above} | {la * 1e6:.1f} |")


def monotone(path=CHART) -> None:
    """Every 1 % step from 0.80 to 1.25 times each answer, up to the
    largest preload the simulation takes."""
    from contactsep.chatter.stack import largest_preload
    rows = [r for r in read_chart(path)
            if np.isfinite(float(r["min_preload_lb"]))]
    factors = np.round(np.arange(0.80, 1.2501, 0.01), 2)
    tasks, where = [], []
    for k, r in enumerate(rows):
        design = contactsep.thesis_design(d=float(r["d_in"]),
                                          ys=float(r["ys_in"]),
                                          n_modes=int(r["n_modes"]))
        answer = float(r["min_preload_lb"])
        for f in factors:
            if f * answer <= largest_preload(design):
                tasks.append((design, r["model"], row_settings(r),
                              f * answer))
                where.append((k, f))
    out = run_all(tasks)
    print(f"factors {factors[0]:g}-{factors[-1]:g} of each row's preload "
          f"(up to the simulation's limit)")
    print("| d (in) | y_s (in) | min preload (lb) | closed below it "
          "(x answer) | events above it (x answer) | tested to (x) |")
    print("|---|---|---:|---|---|---:|")
    for k, r in enumerate(rows):
        part = [(f, n) for (row, f), (n, _) in zip(where, out) if row == k]
        closed = [f for f, n in part if n == 0 and f < 1]
        opened = [f for f, n in part if n > 0 and f >= 1]
        print(f"| {r['d_in']} | {r['ys_in']} | "
              f"{float(r['min_preload_lb']):.4g} | "
              f"{', '.join(f'{f:g}' for f in closed) or '-'} | "
              f"{', '.join(f'{f:g}' for f in opened) or '-'} | "
              f"{max(f for f, _ in part):g} |")


def main(argv) -> None:
    chart = CHART
    if "--chart" in argv:
        at = argv.index("--chart")
        chart = argv[at + 1]
        del argv[at:at + 2]
    parts = {"convergence": convergence,
             "convergence-full": lambda: convergence(full=True),
             "check": lambda: check(chart),
             "monotone": lambda: monotone(chart)}
    for name in argv or ["convergence", "check", "monotone"]:
        if name not in parts:
            raise SystemExit(f"unknown part {name!r}: one of "
                             f"{', '.join(parts)}")
        parts[name]()
        print()


if __name__ == "__main__":
    main(sys.argv[1:])
