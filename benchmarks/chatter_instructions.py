"""The adaptive steppers' work in instructions, for callgrind: a count
that, unlike the shared machine's clock, shows a change of 1 %:

    valgrind --tool=callgrind \\
        --toggle-collect='__chatter_adaptive_MOD_adaptive' \\
        python benchmarks/chatter_instructions.py hertz

Runs the thesis rig at N = 16 twice, summary only (``samples=1``,
``single_impulse=False``), with the given law (hertz or newton); the
toggle counts only the compiled stepper (``adaptive`` and what it
calls).  ``callgrind_annotate --threshold=100`` gives the count by
procedure; compare the sums without malloc, free and memset, whose
counts vary with the heap's state from run to run (2.5-7.4 million in
the same Hertz run of ~177 million; the rest repeats to ~20
instructions).
"""

from __future__ import annotations

import sys

import contactsep
from contactsep import chatter

RUNS = 2


def main() -> None:
    law = sys.argv[1] if len(sys.argv) > 1 else "hertz"
    rig = contactsep.thesis_design(n_modes=16)
    for _ in range(RUNS):
        chatter.simulate(rig, model=law, samples=1, single_impulse=False)


if __name__ == "__main__":
    main()
