"""Does the robust preload converge in N where the nominal one cannot?
The robust answer (``contactsep preload --tolerance``) of the relays
whose nominal threshold is ill-conditioned, searched at N and 2N on the
same tolerance draws (docs/preload-family.md, "How well-posed the answer is";
issue 25):

    OPENBLAS_NUM_THREADS=1 nice python benchmarks/robust_convergence.py \\
        [--designs NAME,NAME] [--n-modes 32,64] [--ys-tolerance 0.02] \\
        [--samples 100] [--workers K] [--csv F] [--tested-csv F] \\
        [--journal DIR]

For every design of tests/design_family.py named and every N:
``contactsep.preload(design at N, tolerance=['ys=uniform(y_s (1 - t),
y_s (1 + t))'], samples=S, seed=0, verify=False, converge=False)``
(elastic Hertz, the static correction on, each run's own step and the
design's own window).  The draws are the same at every N (the seed and
the sweep's sampler), so the answers differ by N alone, not by the
samples.  ``--csv``: one row an answer (nominal and robust); and
``--tested-csv``: one row a preload the robust search tried (n, n_open,
n_failed).  Both are rewritten (whole, atomically) after every run, so a
killed run keeps those it finished; rows of designs not named are kept
from the files as found, and so are those of a named design at an N not
given (a design too slow for many samples can be run apart with fewer,
and a higher N added later: each row says its samples and N), and so
are the rows of a search with the robust band before commit 8260ec4
(``robust_band`` nominal_events: what the old band missed stays beside
the fixed band's fine_grid rows).  ``--journal DIR``: each search keeps
every finished simulation in DIR/DESIGN-N (``contactsep.preload(...,
journal=...)``), so that a search killed after hours and run again with
the same command simulates only what is missing; the directory goes once
its rows are written (with ``--check-preloads``, DIR/check: every
run's task names its design, N and preload, so one journal serves any
check).

``--check-preloads P,P,... --check-csv F``: no search; each sample's run
at each of those preloads (lb), at every N given: the counts that say
whether the p_open a search found at N holds at a higher N, where a
whole search there would cost hours.
"""

from __future__ import annotations

import argparse
import shutil
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from design_family import FAMILY  # noqa: E402
from preload_family import csv_rows  # noqa: E402

from contactsep import output  # noqa: E402
from contactsep.studies.preload.command import preload  # noqa: E402
from contactsep.studies.preload.chart import Simulations  # noqa: E402
from contactsep.studies.preload.robust import (  # noqa: E402
    parse_tolerances, sample_counts, tolerance_samples)
from contactsep.runs.journal import RunJournal  # noqa: E402

COLUMNS = ("design", "n_modes", "ys_in", "ys_tolerance", "samples",
           "min_preload_lb", "robust_min_preload_lb", "n", "n_open",
           "n_failed", "p_open_ci95_high", "robust_tested",
           "simulations", "wall_s", "robust_band")
#: How the robust search chose the preloads above its answer: rows
#: searched before commit 8260ec4 tried the nominal design's events only.
BAND_BEFORE_FIX = "nominal_events"
BAND = "fine_grid"
CHECK_COLUMNS = ("design", "n_modes", "ys_tolerance", "samples",
                 "preload_lb", "n", "n_open", "n_failed", "wall_s")
TESTED_COLUMNS = ("design", "n_modes", "preload_lb", "n", "n_open",
                  "n_failed", "robust_band")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--designs", default="steel_relay,becu_light")
    parser.add_argument("--n-modes", default="32,64")
    parser.add_argument("--ys-tolerance", type=float, default=0.02,
                        help="relative half-width of y_s's uniform "
                             "tolerance")
    parser.add_argument("--samples", type=int, default=100)
    parser.add_argument("--workers", type=int, default=None)
    parser.add_argument("--csv", default=None)
    parser.add_argument("--tested-csv", default=None)
    parser.add_argument("--journal", default=None,
                        help="directory that keeps each search's finished "
                             "simulations (DIR/DESIGN-N) until its rows "
                             "are written")
    parser.add_argument("--check-preloads", default=None)
    parser.add_argument("--check-csv", default=None)
    args = parser.parse_args()
    if args.check_preloads:
        check(args)
        return
    names = args.designs.split(",")
    n_list = [int(n) for n in args.n_modes.split(",")]
    rows = kept(args.csv, names, n_list)
    tested = kept(args.tested_csv, names, n_list)
    print("| design | N | nominal lb | robust lb | n_open/n | preloads "
          "tried | simulations | s |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name in names:
        for n_modes in n_list:
            design = FAMILY[name].replace(n_modes=n_modes)
            t = args.ys_tolerance
            tolerance = _tolerance(design, t)
            start = time.perf_counter()
            journal = None
            if args.journal:
                journal = Path(args.journal) / f"{name}-{n_modes}"
                journal.parent.mkdir(parents=True, exist_ok=True)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                answer = preload(design, tolerance=tolerance,
                                 samples=args.samples, seed=0,
                                 verify=False, converge=False,
                                 workers=args.workers, journal=journal)
            seconds = time.perf_counter() - start
            robust = answer.robust
            interval = robust.p_open_ci95
            rows.append({
                "design": name, "n_modes": n_modes, "ys_in": design.ys,
                "ys_tolerance": t, "samples": args.samples,
                "min_preload_lb": answer.min_preload_lb,
                "robust_min_preload_lb": robust.min_preload_lb,
                "n": robust.n, "n_open": robust.n_open,
                "n_failed": robust.n_failed,
                "p_open_ci95_high": interval[1] if interval else None,
                "robust_tested": len(robust.tested),
                "simulations": answer.simulations, "wall_s": seconds,
                "robust_band": BAND})
            tested += [{"design": name, "n_modes": n_modes,
                        "preload_lb": p, "n": n, "n_open": k,
                        "n_failed": f, "robust_band": BAND}
                       for p, n, k, f in robust.tested]
            print(f"| {name} | {n_modes} | {answer.min_preload_lb:.4g} | "
                  f"{robust.min_preload_lb:.4g} | {robust.n_open}/"
                  f"{robust.n} | {len(robust.tested)} | "
                  f"{answer.simulations} | {seconds:.0f} |", flush=True)
            if args.csv:
                write(args.csv, rows, COLUMNS, (
                    "# min_preload_lb: the nominal design's answer; "
                    "robust_min_preload_lb: the smallest preload with "
                    "p_open <= 0.01 over the samples; n, n_open, "
                    "n_failed, p_open_ci95_high (Wilson 95 %) at it; "
                    "robust_tested: preloads the robust search tried; "
                    "simulations: the nominal search's runs (the robust "
                    "search's are robust_tested x samples)",
                    "# units: in, lb, s; wall_s: wall time on two worker "
                    "processes (benchmarks/robust_convergence.py; a search "
                    "resumed from --journal: its last run's only)",
                    "# robust_band: fine_grid, every fine-grid preload "
                    "from the robust answer to 1.5 times it and the "
                    "nominal design's events to 2 times (since commit "
                    "8260ec4; since commit ae7bf1a from the top down, "
                    "stopping at the first failing batch of four: the "
                    "same answer, fewer preloads tried below it); "
                    "nominal_events, above its answer the "
                    "nominal design's events only (rows searched before "
                    "it; docs/preload.md, The robust answer at N and 2N)"))
            if args.tested_csv:
                write(args.tested_csv, tested, TESTED_COLUMNS, (
                    "# one row a preload the robust search tried: n "
                    "samples ran, n_open had a discontinuity event, "
                    "n_failed did not finish; robust_band: that "
                    "search's (the answers' file says what it means)",
                    "# units: lb (benchmarks/robust_convergence.py)"))
            if journal is not None and args.csv and args.tested_csv:
                shutil.rmtree(journal, ignore_errors=True)


def _tolerance(design, t) -> list[str]:
    return [f"ys=uniform({design.ys * (1 - t)!r},{design.ys * (1 + t)!r})"]


def check(args) -> None:
    """The samples' counts at the preloads given, no search."""
    names = args.designs.split(",")
    preloads = [float(p) for p in args.check_preloads.split(",")]
    n_list = [int(n) for n in args.n_modes.split(",")]
    rows = kept(args.check_csv, names, n_list, preloads)
    print("| design | N | preload lb | n_open/n | s |")
    print("|---|---:|---:|---:|---:|")
    journal = None
    if args.journal:
        Path(args.journal).mkdir(parents=True, exist_ok=True)
        journal = RunJournal(Path(args.journal) / "check", {
            "check": "benchmarks/robust_convergence.py --check-preloads"})
    with Simulations(args.workers, journal=journal) as sims:
        for name in names:
            for n_modes in n_list:
                design = FAMILY[name].replace(n_modes=n_modes)
                spec = parse_tolerances(
                    _tolerance(design, args.ys_tolerance), args.samples, 0)
                samples = tolerance_samples(design, {}, spec)
                for p in preloads:
                    start = time.perf_counter()
                    (n, n_open, n_failed), = sample_counts(
                        samples, "hertz", [p], sims)
                    seconds = time.perf_counter() - start
                    rows.append({"design": name, "n_modes": n_modes,
                                 "ys_tolerance": args.ys_tolerance,
                                 "samples": args.samples, "preload_lb": p,
                                 "n": n, "n_open": n_open,
                                 "n_failed": n_failed, "wall_s": seconds})
                    print(f"| {name} | {n_modes} | {p:.6g} | {n_open}/"
                          f"{n} | {seconds:.0f} |", flush=True)
                    if args.check_csv:
                        write(args.check_csv, rows, CHECK_COLUMNS, (
                            "# no search: n samples ran at preload_lb, "
                            "n_open had a discontinuity event, n_failed "
                            "did not finish",
                            "# units: lb, s; wall_s: wall time on two "
                            "worker processes "
                            "(benchmarks/robust_convergence.py "
                            "--check-preloads)"), first=CHECK,
                            exact=("preload_lb",))
    if journal is not None and args.check_csv:
        journal.remove()


def kept(path, names, n_modes, preloads=None) -> list[dict]:
    """The rows of ``path`` (if it exists) not of a named design at a
    named N (and, given ``preloads``, at one of those preloads; else
    searched with this band): those are the ones this run writes anew.
    A search's rows with the band before commit 8260ec4 are kept beside
    the new band's: they are what the old band missed."""
    if not path or not Path(path).exists():
        return []
    lines = [line for line in Path(path).read_text().splitlines()
             if not line.startswith("#")]
    columns = lines[0].split(",")
    rows = [dict(zip(columns, line.split(","))) for line in lines[1:]]
    if "robust_band" not in columns and preloads is None:
        for row in rows:
            row["robust_band"] = BAND_BEFORE_FIX
    rerun = {(name, str(n)) for name in names for n in n_modes}
    if preloads is not None:
        return [row for row in rows
                if (row["design"], row["n_modes"]) not in rerun or not any(
                    float(row["preload_lb"]) == p for p in preloads)]
    return [row for row in rows
            if (row["design"], row["n_modes"]) not in rerun
            or row["robust_band"] != BAND]


SEARCH = ("# contactsep.preload(design at N, tolerance=['ys=uniform("
          "y_s (1 - ys_tolerance), y_s (1 + ys_tolerance))'], "
          "samples=samples, seed=0, verify=False, converge=False) on "
          "the designs of tests/design_family.py (elastic Hertz, each "
          "run's own step, the design's own window, static correction "
          "on)")
CHECK = ("# the samples of contactsep.preload(design at N, tolerance=["
         "'ys=uniform(y_s (1 - ys_tolerance), y_s (1 + ys_tolerance))'], "
         "samples=samples, seed=0) on the designs of "
         "tests/design_family.py, each run at preload_lb (elastic Hertz, "
         "each run's own step, the design's own window, static "
         "correction on)")


def write(path, rows, columns, comments, first=SEARCH,
          exact=("ys_in",)) -> None:
    """The rows, '#' comments first (``exact`` columns with all their
    digits); replaced only when finished."""
    lines = [first, *comments, ",".join(columns)]
    lines += csv_rows(rows, columns, exact=exact)
    with output.open_output(path) as out:
        output.write_text(out, "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
