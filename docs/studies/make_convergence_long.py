"""The convergence table beyond the study's N <= 50 (docs/model.md):
t1, V, psi, v0, max y3 and t_max of the thesis design (eq. 23 as
printed, the convergence study's design) at N = 4 and 100 ... 1600, the
compiled kernel.  Run from the repository root::

    python docs/studies/make_convergence_long.py > docs/studies/convergence_long.csv
"""

from __future__ import annotations

import sys

import numpy as np

from contactsep.model import evaluate
from contactsep.studies.study import thesis_study_design

#: The table's N: the listing's 4 (the errors' reference) and 100-1600.
MODES = (4, 100, 200, 400, 800, 1600)
COLUMNS = ("N", "t1_s", "v_impact_in_s", "psi_lb_s", "v0_in_s",
           "y3_max_in", "t_max_s")


def table() -> list[list[float]]:
    """One row per N: the COLUMNS' values."""
    n = np.array(MODES)
    ev = evaluate(thesis_study_design(n_modes=n))
    columns = (n, ev.t1, ev.v_impact, ev.psi, ev.v0, ev.y3_max, ev.t_max)
    return [[c[i].item() for c in columns] for i in range(len(n))]


def main(out=sys.stdout) -> None:
    out.write("# The convergence table beyond N = 50 (docs/model.md)\n"
              "# python docs/studies/make_convergence_long.py > "
              "docs/studies/convergence_long.csv\n"
              "# model: eq. 23 as printed (contactsep.model), the thesis "
              "design of contactsep study convergence\n")
    out.write(",".join(COLUMNS) + "\n")
    for row in table():
        out.write(",".join(repr(v) for v in row) + "\n")


if __name__ == "__main__":
    main()
