"""How busy W workers are in `contactsep preload`'s search, with and
without runs made ahead for idle workers
(docs/performance-parallel.md, "Workers kept busy by runs made ahead").

The simulations are the tests' planted ones (an event below a threshold
and in a window 1.5 % wide above it; tests/studies/preload/
test_runs_ahead.py), run in this process as a pool hands them out, so
that the figures are the search's shape, not the machine's: the share of
worker slots that hold a run, round by round (a batch of b runs takes
ceil(b / W) rounds), and the rounds a search waits for, on every design
of the family.  Without runs ahead the same search sends its batches as
asked (the one-worker search's batches, cut into rounds of W).

    python benchmarks/runs_ahead.py --save
"""

from __future__ import annotations

import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests"))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "studies", "preload"))

from design_family import FAMILY  # noqa: E402
from results import Report  # noqa: E402
from test_runs_ahead import busy_share, plant, searched, sent  # noqa: E402

WORKERS = (2, 4, 8, 16)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--save", action="store_true",
                        help="write benchmarks/results/runs_ahead.md")
    args = parser.parse_args(argv)
    pools = plant(setattr)
    say = Report()
    say("| design | W | busy without | busy with | rounds without | "
        "rounds with | runs asked | made ahead | of them used |")
    say("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name in sorted(FAMILY):
        _, alone = searched(FAMILY[name], 1)
        for workers in WORKERS:
            _, sims = searched(FAMILY[name], workers)
            batches = sent(pools[-1])
            rounds = sum(math.ceil(b / workers) for b in batches)
            plain = sum(math.ceil(b / workers) for b in alone.batches)
            say(f"| {name} | {workers} | "
                f"{busy_share(alone.batches, workers):.0%} | "
                f"{busy_share(batches, workers):.0%} | {plain} | {rounds} "
                f"| {sims.runs} | {sims.ahead.made} | {sims.ahead.used} |")
    if args.save:
        say.save("runs_ahead", "python benchmarks/runs_ahead.py --save")
    return 0


if __name__ == "__main__":
    sys.exit(main())
