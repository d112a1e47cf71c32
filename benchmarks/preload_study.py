"""The preload chart's numbers checked (docs/chatter.md, "The preload
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
  its preload in 1 % steps: where "closed" is not monotone.
* ``chart-bracket [--chart CSV]`` (not in the default parts): each
  answer of a chart at twice its N and half its step, 2 % below (an
  event expected) and 2 % above (none): the chart's rows converged to
  2 % (28 simulations; minutes).
* ``chart-rows --rows d:ys,...`` (not in the default parts): the
  chart's search at 2N and half the step for the rows given (those
  chart-bracket could not hold), each answer's change.
* ``chart-convergence [--modes N]`` (not in the default parts): the
  whole chart at N (default 32) and at 2N, half the step, with each
  row's change: the chart's convergence table (an hour or more on two
  cores at N = 32; run it with the static correction in).
"""

from __future__ import annotations

import csv
import sys
import time

import numpy as np

import contactsep
from contactsep.studies import preload

CHART = "docs/studies/preload.csv"
#: The chart's numerics (preload_chart gives them explicitly: the thesis
#: rig's step and the listing's window, not each design's own).
CHART_SETTINGS = {"dt": 5e-8, "t_end": 0.06}


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
            return sims.events([(designs[row], "hertz", settings[row], p)
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
        # each row at its own N and step (a converged chart's)
        settings = {**CHART_SETTINGS,
                    "dt": float(r.get("dt_s") or CHART_SETTINGS["dt"])}
        for factor in (0.97, 1.03):
            tasks.append((design, r["model"], settings,
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
    from contactsep.chatter.simulate import largest_preload
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
                tasks.append((design, r["model"], CHART_SETTINGS, f * answer))
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


def chart_convergence(n_modes=32) -> None:
    """The whole chart at N and again at 2N and half the step (each row
    its own search, as contactsep preload's min_preload_change): the
    convergence table of the chart, each row's change flagged above 2 %.
    With the static correction (issue 25) the chart converged to 2 % a
    row is the N at which no row is flagged."""
    from contactsep.chatter.simulate import DEFAULT_DT
    step = DEFAULT_DT["hertz"]      # the chart's own (preload_chart)
    start = time.perf_counter()
    coarse = preload.preload_chart(n_modes=n_modes)
    middle = time.perf_counter()
    fine = preload.preload_chart(n_modes=2 * n_modes, dt=step / 2)
    print(f"The preload chart at N = {n_modes}, dt {step:g} s "
          f"({middle - start:.0f} s) and at N = {2 * n_modes}, dt "
          f"{step / 2:g} s ({time.perf_counter() - middle:.0f} s)\n")
    print(f"| d (in) | y_s (in) | N = {n_modes} (lb) | N = {2 * n_modes}, "
          f"dt/2 (lb) | change | within 2 % |")
    print("|---|---|---:|---:|---:|---|")
    for d, ys, a, b in zip(coarse["d_in"], coarse["ys_in"],
                           coarse["min_preload_lb"], fine["min_preload_lb"]):
        change = (b - a) / a if a > 0 else float("nan")
        print(f"| {d:g} | {ys:g} | {a:.4g} | {b:.4g} | {change:+.1%} | "
              f"{'yes' if abs(change) <= 0.02 else 'NO'} |")


def chart_bracket(path=CHART, margin=0.02) -> None:
    """Each answer of a chart (``--chart CSV``, at N) checked at 2N and
    half the chart's step: ``margin`` (2 %) below it an event expected,
    ``margin`` above none.  Both hold: at 2N, dt/2 the threshold lies
    within the margin of the chart's answer (a window of events, or of
    closed preloads, narrower than the margin aside): the row is
    converged to the margin.  A row closed at -margin too (a closed
    window of the rattle) is scanned between, 0.25 % apart, and below
    to -5 %: an event there still puts the threshold within the
    margin.  28 simulations and 10 a closed row, not a second chart."""
    rows = [r for r in read_chart(path)
            if r["min_preload_lb"] not in ("nan", "")]
    n = 2 * int(rows[0]["n_modes"])
    settings = {"dt": CHART_SETTINGS["dt"] / 2,
                "t_end": CHART_SETTINGS["t_end"], "damping": "none"}
    tasks = []
    for r in rows:
        design = contactsep.thesis_design(d=float(r["d_in"]),
                                          ys=float(r["ys_in"]), n_modes=n)
        answer = float(r["min_preload_lb"])
        tasks += [(design, r["model"], settings, answer * (1 - margin)),
                  (design, r["model"], settings, answer * (1 + margin))]
    start = time.perf_counter()
    found = run_all(tasks)
    # a row closed at -margin too (the rattle's closed windows): the
    # preloads between, 0.25 % apart, and below it to -5 %
    steps = [1 - margin * k / 8 for k in range(1, 8)] + [
        0.97, 0.96, 0.95]
    closed = [k for k in range(len(rows)) if found[2 * k][0] == 0]
    scan = run_all([(tasks[2 * k][0], rows[k]["model"], settings,
                     float(rows[k]["min_preload_lb"]) * f)
                    for k in closed for f in steps])
    highest = {}
    for i, k in enumerate(closed):
        events = [f for j, f in enumerate(steps)
                  if scan[i * len(steps) + j][0] > 0]
        highest[k] = max(events) if events else None
    print(f"The chart {path} (N = {rows[0]['n_modes']}) at N = {n}, dt "
          f"{settings['dt']:g} s, {margin:.0%} either side of each answer "
          f"({time.perf_counter() - start:.0f} s)\n")
    print(f"| d (in) | y_s (in) | answer (lb) | events at -{margin:.0%} | "
          f"events at +{margin:.0%} | longest opening at +{margin:.0%} "
          f"(s) | highest event below | within {margin:.0%} |")
    print("|---|---|---:|---:|---:|---:|---|---|")
    for k, r in enumerate(rows):
        (below, _), (above, longest) = found[2 * k], found[2 * k + 1]
        top = 1 - margin if below else highest.get(k)
        held = top is not None and top >= 1 - margin - 1e-12 \
            and above == 0
        where = "none to -5 %" if top is None else f"{top:.4f} x"
        print(f"| {float(r['d_in']):g} | {float(r['ys_in']):g} | "
              f"{float(r['min_preload_lb']):.4g} | {below} | {above} | "
              f"{longest:.3g} | {where} | {'yes' if held else 'NO'} |")


def chart_rows(path=CHART, rows="") -> None:
    """The chart's search itself, at 2N and half the chart's step, for
    the rows ``--rows d:ys,d:ys`` (those chart-bracket could not hold
    to 2 %): each row's answer at 2N, dt/2 and its change from the
    chart's (a few hundred simulations a row)."""
    chart = {(float(r["d_in"]), float(r["ys_in"])): r
             for r in read_chart(path)}
    keys = [tuple(float(v) for v in item.split(":"))
            for item in rows.split(",") if item]
    n = 2 * int(next(iter(chart.values()))["n_modes"])
    settings = {"dt": CHART_SETTINGS["dt"] / 2,
                "t_end": CHART_SETTINGS["t_end"], "damping": "none"}
    designs = [contactsep.thesis_design(d=d, ys=ys, n_modes=n)
               for d, ys in keys]
    start = time.perf_counter()
    with preload.Simulations() as sims:
        found = preload.min_preloads(designs, "hertz", settings,
                                     simulations=sims)
    print(f"The chart's search at N = {n}, dt {settings['dt']:g} s "
          f"({sims.runs} simulations, {time.perf_counter() - start:.0f} s)"
          f"\n")
    print(f"| d (in) | y_s (in) | chart (lb) | N = {n}, dt/2 (lb) | change "
          f"| closed below it at N = {n} (lb) |")
    print("|---|---|---:|---:|---:|---|")
    for (d, ys), result in zip(keys, found):
        answer = float(chart[(d, ys)]["min_preload_lb"])
        below = result.closed_below
        text = f"{len(below)} from {min(below):.4g} to {max(below):.4g}" \
            if below else "-"
        print(f"| {d:g} | {ys:g} | {answer:.4g} | "
              f"{result.min_preload_lb:.4g} | "
              f"{result.min_preload_lb / answer - 1:+.1%} | {text} |")


def main(argv) -> None:
    chart = CHART
    if "--chart" in argv:
        at = argv.index("--chart")
        chart = argv[at + 1]
        del argv[at:at + 2]
    n_modes = 32
    if "--modes" in argv:
        at = argv.index("--modes")
        n_modes = int(argv[at + 1])
        del argv[at:at + 2]
    rows = ""
    if "--rows" in argv:
        at = argv.index("--rows")
        rows = argv[at + 1]
        del argv[at:at + 2]
    parts = {"chart-convergence": lambda: chart_convergence(n_modes),
             "chart-rows": lambda: chart_rows(chart, rows),
             "convergence": convergence,
             "convergence-full": lambda: convergence(full=True),
             "check": lambda: check(chart),
             "chart-bracket": lambda: chart_bracket(chart),
             "monotone": lambda: monotone(chart)}
    for name in argv or ["convergence", "check", "monotone"]:
        if name not in parts:
            raise SystemExit(f"unknown part {name!r}: one of "
                             f"{', '.join(parts)}")
        parts[name]()
        print()


if __name__ == "__main__":
    main(sys.argv[1:])
