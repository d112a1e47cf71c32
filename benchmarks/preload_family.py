"""The smallest preload of each design of the test family at the default
N, and how far it moves at twice the modes and half the step (issue 25,
items 2 and 5; docs/preload-family.md, "The preload command on the family"):

    OPENBLAS_NUM_THREADS=1 nice python benchmarks/preload_family.py \\
        [--designs NAME,NAME] [--workers K] [--json F] [--csv F]

For every design of tests/design_family.py (FAMILY; the thesis rigs'
rows are the preload chart's, docs/studies/preload.csv, checked there),
``contactsep.preload(design)`` as the command runs it: elastic Hertz,
N = DEFAULT_MODES, the design's own step and window, the static
correction on, its whole search, then the same search at 2N and half
the step (``verify``: ``min_preload_change``).  Prints one row a design:
the answer, the answer at 2N, dt/2, their relative change, then with
``converge=True`` the answer converged to 2 % (where the change exceeds
2 %, the answer at 2N checked at 4N and a quarter of the step or the
finest step the work budget takes, searched again there if it fails, up
to checks at N = 128), the N it was found
and checked at, the default answer's difference from it, the
simulations and the seconds.  ``--json`` writes the rows (strict JSON)
as they finish, ``--csv`` at the end (``--from-json F --csv G``: the
CSV of an earlier ``--json``, no runs).  Tens of minutes a relay on two
cores.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from design_family import FAMILY  # noqa: E402

from contactsep import output  # noqa: E402
from contactsep.studies.preload.command import preload  # noqa: E402
from contactsep.studies.preload.chart import DEFAULT_MODES  # noqa: E402

RELAYS = [name for name in FAMILY if not name.startswith("thesis")]


def finite(value):
    return value if isinstance(value, (int, float)) and \
        math.isfinite(value) else None


def error(answer) -> str:
    """(answer at N - converged answer) / converged answer."""
    a, c = answer.min_preload_lb, answer.converged_min_preload_lb
    if not (math.isfinite(a) and c is not None and math.isfinite(c)) \
            or c == 0:
        return "-"
    return f"{(a - c) / c:+.2%}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--designs", default=",".join(RELAYS))
    parser.add_argument("--workers", type=int, default=None)
    parser.add_argument("--json", default=None)
    parser.add_argument("--csv", default=None,
                        help="the rows as CSV ('#' comments first)")
    parser.add_argument("--from-json", default=None,
                        help="no runs: the CSV of an earlier --json")
    parser.add_argument("--search-at", type=int, default=None, metavar="N",
                        help="instead: each design's whole search at N "
                             "and half its own step there, or the finest "
                             "step the work budget takes (--csv: every "
                             "preload tried)")
    args = parser.parse_args()
    if args.search_at:
        search_at(args.designs.split(","), args.search_at, args.workers,
                  args.csv)
        return
    if args.from_json:
        with open(args.from_json) as rows:
            write_csv(json.load(rows), args.csv)
        return
    rows = []
    print("| design | N | dt s | min preload lb | at 2N, dt/2 lb | change "
          "| converged lb | at N | checked at N | held | error at N "
          "| simulations | s |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|")
    for name in args.designs.split(","):
        design = FAMILY[name].replace(n_modes=DEFAULT_MODES)
        start = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            answer = preload(design, workers=args.workers, converge=True)
        seconds = time.perf_counter() - start
        row = {"design": name, "n_modes": answer.n_modes,
               "dt_s": answer.dt_s,
               "min_preload_lb": finite(answer.min_preload_lb),
               "verify_min_preload_lb": finite(answer.verify_min_preload_lb),
               "min_preload_change": finite(answer.min_preload_change),
               "converged_min_preload_lb":
                   finite(answer.converged_min_preload_lb),
               "converged_n_modes": answer.converged_n_modes,
               "converged_dt_s": answer.converged_dt_s,
               "converged_check_n_modes": answer.converged_check_n_modes,
               "converged": answer.converged,
               "simulations": answer.simulations, "wall_s": seconds}
        rows.append(row)
        change = row["min_preload_change"]
        print(f"| {name} | {answer.n_modes} | {answer.dt_s:.3g} | "
              f"{answer.min_preload_lb:.4g} | "
              f"{answer.verify_min_preload_lb:.4g} | "
              f"{'-' if change is None else f'{change:+.2%}'} | "
              f"{answer.converged_min_preload_lb:.4g} | "
              f"{answer.converged_n_modes} | "
              f"{answer.converged_check_n_modes} | "
              f"{'yes' if answer.converged else 'no'} | "
              f"{error(answer)} | "
              f"{answer.simulations} | {seconds:.0f} |", flush=True)
        if args.json:
            with output.open_output(args.json) as out:
                output.write_json(out, rows, indent=1)
    if args.csv:
        write_csv(rows, args.csv)


def search_at(names, n_modes, workers, path) -> None:
    """The whole search (no verify) of each design at ``n_modes``: the
    check of a converged answer looks at 2 % either side only, the
    search at every 0.99 % to twice the answer."""
    from contactsep.chatter import simulate
    from contactsep.chatter.stack import smallest_dt
    for name in names:
        design = FAMILY[name].replace(n_modes=n_modes)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            probe = simulate(design, samples=1, single_impulse=False)
            dt = max(probe.dt / 2,
                     smallest_dt(n_modes, probe.t_end_s) * 1.0001)
            start = time.perf_counter()
            answer = preload(design, verify=False, dt=dt, workers=workers)
        seconds = time.perf_counter() - start
        print(f"{name}: N = {n_modes}, dt {dt:.6g} s: "
              f"{answer.min_preload_lb:.6g} lb, {answer.simulations} "
              f"simulations, {seconds:.0f} s", flush=True)
        if path:
            lines = [f"# {name} (tests/design_family.py) at N = {n_modes} "
                     f"and dt = {dt:.6g} s (half its own step there, or "
                     f"the work budget's finest step over its "
                     f"{probe.t_end_s:.3g} s window), elastic Hertz, "
                     f"static correction on: the whole preload search of "
                     f"contactsep.preload(design, verify=False, dt=...) "
                     f"(benchmarks/preload_family.py --designs {name} "
                     f"--search-at {n_modes})",
                     f"# answer: {answer.min_preload_lb:.6g} lb "
                     f"({answer.simulations} simulations); event: 1 where "
                     f"the circuit opened for at least "
                     f"{probe.min_open_s:g} s",
                     "preload_lb,event"]
            lines += [f"{p!r},{int(bool(e))}"
                      for p, e in sorted(answer.tested)]
            with output.open_output(path) as out:
                output.write_text(out, "\n".join(lines) + "\n")


COLUMNS = ("design", "n_modes", "dt_s", "min_preload_lb",
           "verify_min_preload_lb", "min_preload_change",
           "converged_min_preload_lb", "converged_n_modes", "converged_dt_s",
           "converged_check_n_modes", "converged", "simulations", "wall_s")


def write_csv(rows, path) -> None:
    """The rows, '#' comments first; replaced only when finished."""
    lines = ["# contactsep.preload(design, converge=True) on the designs of "
             "tests/design_family.py at N = DEFAULT_MODES (elastic Hertz, "
             "the design's own step and window, static correction on)",
             "# min_preload_change: the answer at 2N and half the step "
             "against the answer (a full second search)",
             "# converged_*: the answer converged to 2 % (where the change "
             "exceeds 2 %, the answer at 2N checked at 4N and a quarter of "
             "the step, or the finest step the work budget takes); "
             "converged 1: its check held",
             "# units: lb, s; wall_s: wall time on two worker processes",
             ",".join(COLUMNS)]
    lines += csv_rows(rows, COLUMNS)
    with output.open_output(path) as out:
        output.write_text(out, "\n".join(lines) + "\n")


def csv_rows(rows, columns, exact=()) -> list[str]:
    """One CSV line a row (dicts): '' for None, 0 or 1 for a bool, 'nan'
    for a number that is not finite, 6 significant digits for a float
    (all of them, repr, in the ``exact`` columns)."""
    def cell(column, value):
        if value is None:
            return ""
        if isinstance(value, bool):
            return str(int(value))
        if isinstance(value, float):
            if not math.isfinite(value):
                return "nan"
            return repr(value) if column in exact else f"{value:.6g}"
        return str(value)
    return [",".join(cell(column, row[column]) for column in columns)
            for row in rows]


if __name__ == "__main__":
    main()
