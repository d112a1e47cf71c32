"""How close `contactsep preload`'s estimate of its time comes to the
time its runs take (docs/performance-contact.md, "The search's time,
estimated before it starts").

The command estimates a run as its window over its step, in steps, at
the measured cost a step of its probe (one run at no preload, made
first to check the design: contactsep.studies.preload.estimate).  Here,
on every family design at N = 16 and 32, the probe is run and timed as
the command times it, then the design is simulated at the ceiling (the
search's first run), at half of it and at a tenth of it, and each run's
seconds are divided by the estimate: 1 is exact, above 1 the estimate
is short.  Each ratio is the median of three repeats (a new probe each
time).

    python benchmarks/preload_estimate.py --save
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests"))

from design_family import FAMILY  # noqa: E402
from results import Report  # noqa: E402

from contactsep.chatter import simulate  # noqa: E402
from contactsep.chatter.stack import largest_preload  # noqa: E402
from contactsep.studies.preload.estimate import run_seconds  # noqa: E402

SHARES = (1.0, 0.5, 0.1)
REPEATS = 3


def _timed(design, preload):
    start = time.perf_counter()
    result = simulate(design, model="hertz", preload=preload, samples=1,
                      single_impulse=False)
    return result, time.perf_counter() - start


def ratios(design) -> list:
    """The medians over REPEATS of each SHARES run's seconds over the
    probe's estimate of a run."""
    ceiling = largest_preload(design)
    found = [[] for _ in SHARES]
    for _ in range(REPEATS):
        probe, seconds = _timed(design, 0.0)
        estimate = run_seconds(probe, seconds)
        for column, share in enumerate(SHARES):
            found[column].append(_timed(design, share * ceiling)[1]
                                 / estimate)
    return [statistics.median(column) for column in found]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--save", action="store_true",
                        help="write benchmarks/results/preload_estimate.md")
    args = parser.parse_args(argv)
    say = Report()
    say("| design | N | at the ceiling | at half of it | at a tenth |")
    say("|---|---:|---:|---:|---:|")
    for n_modes in (16, 32):
        for name in sorted(FAMILY):
            found = ratios(FAMILY[name].replace(n_modes=n_modes))
            say(f"| {name} | {n_modes} | "
                + " | ".join(f"{r:.2f}" for r in found) + " |")
    if args.save:
        say.save("preload_estimate",
                 "python benchmarks/preload_estimate.py --save")
    return 0


if __name__ == "__main__":
    sys.exit(main())
