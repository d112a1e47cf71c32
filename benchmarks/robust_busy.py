"""How busy W workers are in `contactsep preload --tolerance`'s robust
search (docs/performance-parallel.md, "Workers kept busy by runs made
ahead").

The samples are the tests' planted ones (an event below 10 lb per inch
of separator; tests/planted_preload.py) with a 2 % tolerance on the
separator's thickness, p_target 0.01, so that the figures are the
search's shape, not the machine's: the share of worker slots that hold
a run, round by round (a batch of b runs takes ceil(b / W) rounds), on
every design of the family at 400 and 1,000 samples.

    python benchmarks/robust_busy.py --save
"""

from __future__ import annotations

import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests"))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "studies", "preload"))

import planted_preload  # noqa: E402
from design_family import FAMILY  # noqa: E402
from results import Report  # noqa: E402
from test_robust_busy import robust_batches  # noqa: E402
from test_runs_ahead import busy_share  # noqa: E402

from contactsep.studies.preload import robust  # noqa: E402

WORKERS = (8, 16, 64, 256)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--save", action="store_true",
                        help="write benchmarks/results/robust_busy.md")
    args = parser.parse_args(argv)
    robust.simulate_design = planted_preload.fake_sample
    say = Report()
    say("| design | samples | batches | runs | "
        + " | ".join(f"busy at W = {w}" for w in WORKERS) + " |")
    say("|---|---:|---:|---:|" + "---:|" * len(WORKERS))
    for name in sorted(FAMILY):
        for samples in (400, 1000):
            batches = robust_batches(FAMILY[name], samples)
            say(f"| {name} | {samples} | {len(batches)} | {sum(batches)} | "
                + " | ".join(f"{busy_share(batches, w):.0%}"
                             for w in WORKERS) + " |")
    if args.save:
        say.save("robust_busy", "python benchmarks/robust_busy.py --save")
    return 0


if __name__ == "__main__":
    sys.exit(main())
