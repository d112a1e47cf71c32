"""The thesis experiment as Appendix G data sets (Chapters V and VI).

Geometry (Chapter V, "Description of the Model"): aluminium contacts 19 in
long, 2 in wide, 1/8 in thick; separators 2 1/2 in long, 1/2 in wide, of
thickness 0.125, 0.250, 0.350, 0.500 and 0.750 in.  Run conditions (Chapter
VI, Figures 20 and 23): initial static deflection 0.5 in, coefficient of
restitution 0.375.  The equivalent separator lengths are Table III's.
Material values are handbook aluminium; data/README.md gives the reasons
and the figures behind them.

Mode constants are computed by :mod:`contactsep.beams`, never copied
(:func:`~contactsep.restored.dataset.mode_constants`).

``python -m contactsep.restored.thesis_decks DIRECTORY`` writes the decks.
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from contactsep.restored import cards
from contactsep.restored.dataset import DataSet, mode_constants

# Chapter V: contacts 19 x 2 x 1/8 in, separators 2.5 x 0.5 in
CONTACT_LENGTH, CONTACT_WIDTH, CONTACT_THICKNESS = 19.0, 2.0, 0.125
SEPARATOR_LENGTH, SEPARATOR_WIDTH = 2.5, 0.5

#: Table III: separator thickness d (in) -> equivalent length L_c (in).
EQUIVALENT_LENGTHS = {
    0.125: 3.60,
    0.250: 3.60,
    0.350: 3.81,
    0.500: 4.07,
    0.750: 4.15,
}

#: Chapter VI, Figures 20 and 23: y_s = 0.5 in, e = 0.375.
STATIC_DEFLECTION = 0.5
RESTITUTION = 0.375

#: Handbook aluminium: E = 10.0e6 psi, 0.100 lb/in^3 = 172.8 lb/ft^3.
YOUNGS_MODULUS = 10.0e6
WEIGHT_DENSITY = 172.8

#: Time step (s) and separator position (in) of the runs.
TIME_STEP = 0.0005
SEPARATOR_POSITION = 0.0

#: The listing's DIMENSION (4).
MODES = 4


def thesis_data_set(separator_thickness: float, *,
                    equivalent_length: float | None = None,
                    static_deflection: float = STATIC_DEFLECTION,
                    restitution: float = RESTITUTION,
                    modes: int = MODES) -> DataSet:
    """The data set for one separator of the experiment.

    ``equivalent_length`` defaults to :func:`equivalent_length` of the
    thickness: Table III's L_c for the five separators, the stated rule
    between them.
    """
    if equivalent_length is None:
        equivalent_length = globals()["equivalent_length"](
            separator_thickness)
    return DataSet(
        xl=CONTACT_LENGTH, b=CONTACT_WIDTH, h=CONTACT_THICKNESS,
        rho=WEIGHT_DENSITY, ystat=static_deflection,
        xl2=SEPARATOR_LENGTH, b2=SEPARATOR_WIDTH, h2=separator_thickness,
        rho2=WEIGHT_DENSITY,
        xl3=CONTACT_LENGTH, b3=CONTACT_WIDTH, h3=CONTACT_THICKNESS,
        rho3=WEIGHT_DENSITY,
        delt=TIME_STEP, er=restitution, dely=SEPARATOR_POSITION,
        e=YOUNGS_MODULUS, xl2c=equivalent_length,
        **mode_constants(modes),
    )


def equivalent_length(separator_thickness: float) -> float:
    """L_c for a separator of thickness d (in).

    Table III's value where the thesis gives one (d = 0.125, 0.25, 0.35,
    0.5, 0.75 in).  Elsewhere a stated rule, not the thesis's: L_c is
    interpolated linearly in d between Table III's neighbours, and below
    0.125 in it is 3.60 in (the two thinnest separators share it: the
    correction vanishes for a thin separator).  Above 0.75 in the thesis
    gives nothing to interpolate from: ValueError.
    """
    d = float(separator_thickness)
    if d in EQUIVALENT_LENGTHS:
        return EQUIVALENT_LENGTHS[d]
    ds = sorted(EQUIVALENT_LENGTHS)
    if not 0 < d <= ds[-1]:
        raise ValueError(
            f"no equivalent length for a separator {d!r} in thick: Table "
            f"III covers 0 < d <= {ds[-1]} in; pass equivalent_length=")
    if d < ds[0]:
        return EQUIVALENT_LENGTHS[ds[0]]
    return float(np.interp(d, ds, [EQUIVALENT_LENGTHS[k] for k in ds]))


def deck_name(separator_thickness: float) -> str:
    """'thesis_d0125.dat' for the 0.125 in separator."""
    return f"thesis_d{round(separator_thickness * 1000):04d}.dat"


def write_thesis_decks(directory: str | os.PathLike) -> list[Path]:
    """Write one deck per separator and ``thesis_all.dat`` with all five;
    returns the paths written."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    data_sets = [thesis_data_set(d) for d in EQUIVALENT_LENGTHS]
    decks = {deck_name(d): [ds] for d, ds in zip(EQUIVALENT_LENGTHS, data_sets)}
    decks["thesis_all.dat"] = data_sets
    paths = []
    for name, content in decks.items():
        path = directory / name
        path.write_bytes(cards.format_deck(content).encode("ascii"))
        paths.append(path)
    return paths


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m contactsep.restored.thesis_decks DIRECTORY``: regenerate
    the decks."""
    parser = argparse.ArgumentParser(
        prog="python -m contactsep.restored.thesis_decks",
        description="Write the thesis decks (one per separator, and "
                    "thesis_all.dat) into DIRECTORY.")
    parser.add_argument("directory")
    args = parser.parse_args(argv)
    for path in write_thesis_decks(args.directory):
        print(path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
