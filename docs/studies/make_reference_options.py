"""docs/reference.md's table of the listing's options on the thesis decks,
printed as a CSV.

Run from the repository root::

    python docs/studies/make_reference_options.py > docs/studies/reference_options.csv

One row a thesis deck (data/decks/thesis_d*.dat, read as the restored
program reads it): the NumPy reference (contactsep.restored.reference)
with the listing's defaults and with the thesis's versions of its
options.  ``psi``: the impulse (lb s); ``v0``: the separator's mid-span
velocity after it (in/s); ``y3_extreme``: the lower contact's largest
displacement, at a root of the velocity; ``y3_grid_extreme``: the largest
sample of the history grid i*DELT; ``impulse_velocity``: the velocity
the impulse uses (in/s).  Signs are the listing's (downward negative).
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np

import contactsep
from contactsep.restored import reference

ROOT = Path(__file__).resolve().parents[2]
DECKS = sorted((ROOT / "data" / "decks").glob("thesis_d*.dat"))
COLUMNS = ("d_in", "psi_listing_lb_s", "psi_thesis_lb_s",
           "v0_listing_in_s", "y3_extreme_listing_in",
           "y3_extreme_thesis_equivalent_in", "y3_extreme_thesis_nominal_in",
           "t_impact_s", "extreme_time_s", "y3_grid_extreme_in",
           "grid_extreme_time_s", "impulse_velocity_listing_in_s",
           "impulse_velocity_thesis_in_s")


def deck_row(deck: Path) -> list[float]:
    """The row of one deck (its d from the deck's name: thesis_d0125)."""
    data_set = contactsep.replay(deck, precision="double")[0].inputs
    listing = reference.run(data_set)
    thesis = reference.run(data_set, impact_velocity="thesis")
    equivalent, nominal = (
        reference.run(data_set, impact_velocity="thesis",
                      separator_mass=mass)
        for mass in ("equivalent", "nominal"))
    k = int(np.argmax(np.abs(listing.history_ty3)))
    return [int(deck.stem.split("_d")[1]) / 1000, listing.ey, thesis.ey,
            listing.ty2dt, listing.extreme_ty3, equivalent.extreme_ty3,
            nominal.extreme_ty3, listing.t_impact, listing.extreme_time,
            listing.history_ty3[k], listing.history_t[k],
            listing.impulse_velocity, thesis.impulse_velocity]


def main() -> None:
    out = csv.writer(sys.stdout, lineterminator="\n")
    print("# The NumPy reference on the thesis decks: the listing's options "
          "and the thesis's")
    print("# python docs/studies/make_reference_options.py")
    out.writerow(COLUMNS)
    for deck in DECKS:
        out.writerow(f"{float(v):.12g}" for v in deck_row(deck))


if __name__ == "__main__":
    main()
