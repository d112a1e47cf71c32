"""How far the listing's impact sum is from the exact one, over the
thesis decks: the worst |ratio - 1| of the reference's two closed forms
of the initial amplitudes (the deck's 9-decimal mode function against
the exact one; independent of the model).  docs/model.md, "The listing
as a special case", quotes it.  Run from the repository root:

    python docs/studies/make_listing_difference.py > docs/studies/listing_difference.json
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

import contactsep
from contactsep.restored import reference

#: The thesis decks (data/decks, the tests' conftest.DECK_DIR).
DECKS = Path(__file__).resolve().parents[2] / "data" / "decks"


def difference() -> dict:
    worst, decks = 0.0, sorted(DECKS.glob("*.dat"))
    for deck in decks:
        for run in contactsep.replay(deck, precision="double"):
            ds = run.inputs
            p = reference.frequencies(ds)[0]
            ratio = np.sum(p * ds.c * reference.initial_amplitudes(
                ds, "closed-form")) / np.sum(
                p * ds.c * reference.initial_amplitudes(ds, "exact-mode"))
            worst = max(worst, float(abs(ratio - 1)))
    return {"decks": len(decks), "worst_ratio_minus_1": worst}


if __name__ == "__main__":
    print(json.dumps(difference(), indent=1))
