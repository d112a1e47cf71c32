"""Conclusion 8's convergence in N (docs/studies.md), printed as JSON.

Run from the repository root::

    python docs/studies/make_conclusion8_convergence.py > docs/studies/conclusion8_convergence.json

``share``: the first mode's share over the study's x3/L3 grid at each N,
its largest relative departure from the share at ``reference_n``, and
the smallest N from which every larger N checked departs by less than
``tolerance``.  ``counts`` (the study itself at each N): its count of maxima at x3/L3 = 0.5, 1 % prominence,
for N = 8, 16, 32, 64, and at x3/L3 = 0.67, the study's own prominence,
for N = 32 and 64 (a row's count is its own history's, on the time grid
of the first row's period; the first row stays x3/L3 = 0.5).
"""

from __future__ import annotations

import json

import numpy as np

from contactsep.model import evaluate, thesis_design
from contactsep.studies.thesis import mode_share

NS = (8, 16, 32, 64)
REFERENCE_N = 256
TOLERANCE = 1e-4


def first_mode_share(n_modes: int) -> np.ndarray:
    """The study's share over its x3/L3 grid, from eq. 23's c3_j (the
    study's formula, without its costly maxima count)."""
    base = thesis_design(n_modes=n_modes)
    c3 = np.nan_to_num(evaluate(base.replace(
        x3=mode_share.RATIOS * float(base.L3))).c3)
    return c3[:, 0] ** 2 / np.sum(c3 ** 2, axis=1)


def share() -> dict:
    limit = first_mode_share(REFERENCE_N)
    off = {n: float(np.max(np.abs(first_mode_share(n) / limit - 1)))
           for n in NS}
    converged = [n for n in NS if all(off[m] < TOLERANCE for m in NS
                                      if m >= n)]
    return {"reference_n": REFERENCE_N, "tolerance": TOLERANCE,
            "departure": {str(n): off[n] for n in NS},
            "converged_from_n": min(converged)}


def counts() -> dict:
    """The study at each N on two of its rows (module doc)."""
    ratios, prominence = mode_share.RATIOS, mode_share.PROMINENCE
    at = [int(np.argmin(np.abs(ratios - r))) for r in (0.5, 0.67)]
    assert at[0] == 0
    found = {}
    try:
        mode_share.RATIOS = ratios[at]
        for key, level, ns, row in (("one_percent", 0.01, NS, 0),
                                    ("study_prominence", prominence,
                                     (32, 64), 1)):
            mode_share.PROMINENCE = level
            found[key] = {
                "prominence": level, "r": float(ratios[at[row]]),
                "n_maxima": {str(n): int(mode_share.conclusion8(
                    n_modes=n)["n_maxima"][row]) for n in ns}}
    finally:
        mode_share.RATIOS, mode_share.PROMINENCE = ratios, prominence
    return found


def main() -> dict:
    return {"share": share(), "counts": counts()}


if __name__ == "__main__":
    print(json.dumps(main(), indent=2))
