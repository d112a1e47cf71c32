"""max y3 of eq. 23 as printed against the energy bound on it
(contactsep.model.energy.y3_energy_bound), N = 4, on each design of the
test suite's design family (tests/design_family.py, FAMILY and UNSEEN):
docs/model.md, "The energy bound on y3".  Run from the repository
root::

    python docs/studies/make_energy_bound.py > docs/studies/energy_bound.csv
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

from contactsep.model import evaluate
from contactsep.model.energy import y3_energy_bound

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from design_family import FAMILY, UNSEEN  # noqa: E402

COLUMNS = ("design", "ys_in", "y3_max_in", "bound_in", "bound_ratio",
           "above_bound")


def table() -> list[list]:
    """One row per design: its release ys, max y3 as printed, the
    bound, their ratio and whether it is above 1."""
    out = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # the bound's warning itself
        for name, design in {**FAMILY, **UNSEEN}.items():
            printed = design.replace(lower_response="as-printed")
            y3 = float(evaluate(printed).y3_max)
            bound = float(y3_energy_bound(printed))
            out.append([name, float(printed.ys), y3, bound, y3 / bound,
                        int(y3 > bound)])
    return out


def main(out=sys.stdout) -> None:
    out.write("# max y3 (eq. 23 as printed, N = 4) against the energy "
              "bound, the test suite's design family\n"
              "# python docs/studies/make_energy_bound.py > "
              "docs/studies/energy_bound.csv\n")
    out.write(",".join(COLUMNS) + "\n")
    for row in table():
        out.write(",".join(v if isinstance(v, str) else repr(v)
                           for v in row) + "\n")


if __name__ == "__main__":
    main()
