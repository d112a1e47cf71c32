"""Speed of each implementation on the thesis decks (not run by the tests).

    python benchmarks/bench.py [--repeat N]

Prints the best wall time of N runs for: one data set through the restored
core (single and double) and through the NumPy reference, a whole deck
replayed, and the original program on the same deck (a subprocess each run).
"""

from __future__ import annotations

import argparse
import timeit
from pathlib import Path

from contactsep import core, legacy, reference

DECKS = Path(__file__).resolve().parent.parent / "data" / "decks"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=20)
    args = parser.parse_args()
    deck = DECKS / "thesis_all.dat"
    data_set = core.replay(DECKS / "thesis_d0250.dat", "double")[0].inputs
    cases = {
        "solve, single (1 data set)": lambda: core.solve(data_set, "single"),
        "solve, double (1 data set)": lambda: core.solve(data_set, "double"),
        "reference.run (1 data set)": lambda: reference.run(data_set),
        "replay thesis_all (5 sets)": lambda: core.replay(deck),
        "legacy thesis_all (5 sets)": lambda: legacy.run(deck),
    }
    for name, case in cases.items():
        number = 10 if "legacy" not in name else 1
        best = min(timeit.repeat(case, number=number, repeat=args.repeat))
        print(f"{name:<30} {best / number * 1e3:9.3f} ms")


if __name__ == "__main__":
    main()
