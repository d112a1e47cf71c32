"""The single numbers docs/studies.md, docs/sweeps.md and docs/model.md
quote from one computation each (not a study's table): the pages show
them with the ``datum`` role from the JSON this prints.  Run from the
repository root::

    python docs/studies/make_page_numbers.py > docs/studies/page_numbers.json
"""

from __future__ import annotations

import json
import sys

import numpy as np

from contactsep.model import evaluate, thesis_design

#: The rig's length (in) of the upper and lower contacts.
LENGTH = 19.0


def figure7() -> dict:
    """Figure 7's c3_j (eq. 23 as printed, N = 4) at x/L = 0.98 and
    0.78, how much weaker mode 2 is at 0.78, and mode 2's node."""
    from contactsep.studies.thesis.mode_share import second_mode_node
    c3 = evaluate(thesis_design(x3=np.array([0.98, 0.78]) * LENGTH,
                                lower_response="as-printed")).c3
    return {"c3_098_in": c3[0].tolist(), "c3_078_in": c3[1].tolist(),
            "mode2_weaker": float(c3[0, 1] / c3[1, 1]),
            "second_mode_node": second_mode_node()}


def conclusion8() -> dict:
    """The first mode's share of sum c3_j^2 at mode 2's node (the
    conclusion 8 study's N)."""
    from contactsep.studies.thesis.mode_share import MODES, second_mode_node
    c3 = evaluate(thesis_design(n_modes=MODES,
                                x3=second_mode_node() * LENGTH)).c3
    return {"share_at_node": float(c3[0] ** 2 / np.sum(c3 ** 2))}


def separator_constant() -> float:
    """(k1 L)^2 sqrt(E g/(12 gamma)) of the clamped-clamped aluminium
    separator (E = 1e7 psi, gamma = 0.1 lb/in^3): Table III's 1.3e6."""
    from contactsep.beams import eigenvalues
    from contactsep.constants import GRAVITY_IN_PER_S2
    k1 = eigenvalues("clamped-clamped", 1)[0]
    return float(k1 ** 2 * np.sqrt(10.0e6 * GRAVITY_IN_PER_S2
                                   / (12 * 0.100)))


def numbers() -> dict:
    from contactsep.chatter import DEFAULT_MODES
    from contactsep.chatter.stack import largest_preload
    impulse = evaluate(thesis_design(n_modes=4, d=0.25))
    window = evaluate(thesis_design(tau=1.0, lower_response="as-printed"))
    return {
        "figure7": figure7(),
        "conclusion8": conclusion8(),
        "separator_constant": separator_constant(),
        "largest_preload_lb": float(largest_preload(
            thesis_design(n_modes=DEFAULT_MODES))),
        # v0 M3/(psi L3) of the impulse form, thesis rig, N = 4
        "lower_response_factor": float(impulse.v0 * impulse.M3
                                       / (impulse.psi * LENGTH)),
        # max y3 at tau = 1 s, eq. 23 as printed, N = 4
        "one_second_y3_max_in": float(window.y3_max),
        # tau = 1e4 s in periods of the fastest of y3's 4 modes
        "long_window_periods": float(impulse.p3.max()) * 1e4 / (2 * np.pi),
    }


if __name__ == "__main__":
    json.dump(numbers(), sys.stdout, indent=1)
    sys.stdout.write("\n")
