"""How well-posed is the smallest preload?  Each design's whole search
repeated on copies of it whose release deflection y_s differs by parts
per billion or per million (docs/preload-family.md, "How well-posed the
answer is"; issue 25):

    OPENBLAS_NUM_THREADS=1 nice python benchmarks/preload_conditioning.py \\
        [--designs NAME,NAME] [--perturbations 0,1e-9,...] \\
        [--dt S --t-end S] [--workers K] [--csv F]

For every design of tests/design_family.py and every relative change r
of ``--perturbations``: ``contactsep.preload(design with y_s (1 + r),
verify=False, converge=False)`` at N = DEFAULT_MODES, the design's own
step and window (elastic Hertz, the static correction on), or the step
and window given (``--dt 5e-8 --t-end 0.06``: the preload chart's, on
the thesis rigs, whose own 0.295 s window has events up to the largest
preload the simulation takes).  A change of
1e-9 in y_s is far below any tolerance a part is made to and below the
effect of halving the step or doubling N; where it moves the answer by
more than the 2 % the convergence checks ask for, the answer has no
value to converge to at 2 %, whatever the numerics.  Prints one row a
run; ``--csv`` is rewritten (whole, atomically) after every design, so a
killed run keeps the designs it finished.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from design_family import FAMILY  # noqa: E402
from preload_family import csv_rows  # noqa: E402

from contactsep import output  # noqa: E402
from contactsep.studies.preload.command import preload  # noqa: E402
from contactsep.studies.preload.chart import DEFAULT_MODES  # noqa: E402

PERTURBATIONS = (0.0, 1e-9, -1e-9, 1e-6, -1e-6)
COLUMNS = ("design", "n_modes", "dt_s", "ys_in", "ys_change",
           "min_preload_lb", "change_from_unperturbed",
           "highest_event_lb", "simulations", "wall_s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--designs", default=",".join(FAMILY))
    parser.add_argument("--perturbations",
                        default=",".join(repr(p) for p in PERTURBATIONS),
                        help="relative changes of y_s; the first is the "
                             "reference of change_from_unperturbed")
    parser.add_argument("--dt", type=float, default=None)
    parser.add_argument("--t-end", type=float, default=None)
    parser.add_argument("--workers", type=int, default=None)
    parser.add_argument("--csv", default=None)
    args = parser.parse_args()
    changes = [float(p) for p in args.perturbations.split(",")]
    settings = {name: value for name, value in (("dt", args.dt),
                                                ("t_end", args.t_end))
                if value is not None}
    rows = []
    print("| design | N | dt s | y_s change | min preload lb | change "
          "| highest event lb | simulations | s |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name in args.designs.split(","):
        base = FAMILY[name].replace(n_modes=DEFAULT_MODES)
        reference = None
        for change in changes:
            design = base.replace(ys=base.ys * (1.0 + change))
            start = time.perf_counter()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                answer = preload(design, verify=False, converge=False,
                                 workers=args.workers, **settings)
            seconds = time.perf_counter() - start
            found = answer.min_preload_lb
            if reference is None:
                reference = found
            moved = (found - reference) / reference \
                if math.isfinite(found) and reference else math.nan
            events = [p for p, event in answer.tested
                      if event and p > 0]
            highest = max(events) if events else math.nan
            row = {"design": name, "n_modes": answer.n_modes,
                   "dt_s": answer.dt_s, "ys_in": design.ys,
                   "ys_change": change, "min_preload_lb": found,
                   "change_from_unperturbed": moved,
                   "highest_event_lb": highest,
                   "simulations": answer.simulations, "wall_s": seconds}
            rows.append(row)
            print(f"| {name} | {answer.n_modes} | {answer.dt_s:.3g} | "
                  f"{change:g} | {found:.4g} | {moved:+.2%} | "
                  f"{highest:.4g} | {answer.simulations} | "
                  f"{seconds:.0f} |", flush=True)
        if args.csv:
            write_csv(rows, args.csv, settings)


def write_csv(rows, path, settings) -> None:
    """The rows, '#' comments first; replaced only when finished."""
    given = ", ".join(f"{k} = {v:g} s" for k, v in settings.items())
    lines = ["# contactsep.preload(design with y_s (1 + ys_change), "
             "verify=False, converge=False) on the designs of "
             "tests/design_family.py at N = DEFAULT_MODES (elastic Hertz, "
             + (given if given else "the design's own step and window")
             + ", static correction on)",
             "# change_from_unperturbed: (min_preload_lb - the design's "
             "own answer) / the design's own answer; highest_event_lb: the "
             "largest preload tried with a discontinuity event",
             "# units: in, lb, s; wall_s: wall time on two worker "
             "processes (benchmarks/preload_conditioning.py)",
             ",".join(COLUMNS)]
    lines += csv_rows(rows, COLUMNS, exact=("ys_in",))
    with output.open_output(path) as out:
        output.write_text(out, "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
