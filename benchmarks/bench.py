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

import numpy as np

from contactsep.restored import core, legacy, reference

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
    lean_calls(data_set, args.repeat)


def _best_us(case, repeat: int, number: int = 200) -> float:
    return min(timeit.repeat(case, number=number, repeat=repeat)) \
        / number * 1e6


def lean_calls(data_set, repeat: int) -> None:
    """Issue 10: solve(double) with and without the listing, against
    numpy.sin on 1,064 elements (the call's trig count; the arithmetic
    bound is 5-10 us).  benchmarks/bench_lean.py adds the call as it was
    before, built from its git revision, in the same run."""
    x = np.linspace(0.0, 100.0, 1064)
    now = _best_us(lambda: core.solve(data_set, "double"), repeat)
    lean = _best_us(lambda: core.solve(data_set, "double", listing=False),
                    repeat)
    sin = _best_us(lambda: np.sin(x), repeat, number=2000)
    print(f"{'solve(double), listing':<34} {now:9.1f} us")
    print(f"{'solve(double, listing=False)':<34} {lean:9.1f} us")
    print(f"{'numpy.sin, 1,064 elements':<34} {sin:9.1f} us")
    print(f"lean/sin = {lean / sin:.1f}x")


if __name__ == "__main__":
    main()
