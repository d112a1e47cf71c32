"""Read the listing the Appendix G program prints back into numbers.

Every WRITE uses FORMAT 10, ``(7F15.9)``, so each printed line is a row of
15-column fields; a value too wide for F15.9 prints as 15 asterisks and is
read back as NaN.  The sections of one data set follow the program's WRITE
statements in order, and their lengths are fixed by N, which the parser
takes from the number of modal-table lines (the only 5-field lines after the
first).  The parser is used to read the original program's output, which
has no other interface (``contactsep compare``), and by the tests.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

FIELD_WIDTH = 15


class ListingFormatError(ValueError):
    """The text does not have the shape of an Appendix G listing."""


def fields(line: str) -> np.ndarray:
    """The F15.9 fields of one printed line as float64 (asterisks -> NaN)."""
    line = line.rstrip("\r\n")
    if not line or len(line) % FIELD_WIDTH:
        raise ListingFormatError(
            f"a listing line is a row of {FIELD_WIDTH}-column fields: "
            f"{line!r}")
    values = []
    for start in range(0, len(line), FIELD_WIDTH):
        text = line[start:start + FIELD_WIDTH]
        values.append(float("nan") if "*" in text else float(text))
    return np.array(values)


@dataclass(frozen=True)
class DataSetListing:
    """The sections of one data set's listing, as printed (float64)."""

    separator_card: np.ndarray   # XL2, B2, H2, RHO2
    modal_table: np.ndarray      # N rows: V, C, ALPHA, P, APE
    trace: np.ndarray            # rows: T, TY, TYDTL
    end_of_search: float         # ED = 9.999
    impact: np.ndarray           # T, EY, CT, CT2, CT3
    coefficients: np.ndarray     # N rows: A1, B1
    tip: np.ndarray              # T, TY, TYDTL, ACT
    ty2dt: float
    history: np.ndarray          # rows: T, TY3
    separator_modes: np.ndarray  # N rows: V2, C2, ALPH2, P2
    lower_modes: np.ndarray      # N rows: V3, C3, ALPH3, P3
    masses: np.ndarray           # WM, WM2, WM3, XL2C
    ratios: np.ndarray           # GR, BETA, MR1, MR3
    #: The lines of text this data set occupies.
    text: str

    @property
    def n(self) -> int:
        return len(self.modal_table)


def _rows(rows: list[np.ndarray], width: int) -> np.ndarray:
    if not rows:
        return np.empty((0, width))
    return np.vstack(rows)


def parse(text: str) -> list[DataSetListing]:
    """Split a listing into data sets and read every section."""
    lines = text.splitlines(keepends=True)
    rows = [fields(line) for line in lines]
    sets: list[DataSetListing] = []
    i = 0

    def take(width: int, what: str) -> np.ndarray:
        nonlocal i
        if i >= len(rows) or rows[i].size != width:
            found = "end of listing" if i >= len(rows) else \
                f"{rows[i].size} fields on line {i + 1}"
            raise ListingFormatError(
                f"expected {what} ({width} fields), found {found}")
        i += 1
        return rows[i - 1]

    def run(width: int) -> list[np.ndarray]:
        nonlocal i
        found = []
        while i < len(rows) and rows[i].size == width:
            found.append(rows[i])
            i += 1
        return found

    while i < len(rows):
        start = i
        separator_card = take(4, "the separator card echo")
        modal = run(5)
        n = len(modal)
        if n == 0:
            raise ListingFormatError(f"no modal table after line {start + 1}")
        trace = run(3)
        end_of_search = take(1, "the end-of-search mark 9.999")[0]
        impact = take(5, "T, EY, CT, CT2, CT3")
        coefficients = [take(2, "A1, B1") for _ in range(n)]
        tip = take(4, "T, TY, TYDTL, ACT after impact")
        ty2dt = take(1, "TY2DT")[0]
        history = run(2)
        separator_modes = [take(4, "V2, C2, ALPH2, P2") for _ in range(n)]
        lower_modes = [take(4, "V3, C3, ALPH3, P3") for _ in range(n)]
        masses = take(4, "WM, WM2, WM3, XL2C")
        ratios = take(4, "GR, BETA, MR1, MR3")
        sets.append(DataSetListing(
            separator_card=separator_card, modal_table=_rows(modal, 5),
            trace=_rows(trace, 3), end_of_search=float(end_of_search),
            impact=impact, coefficients=_rows(coefficients, 2), tip=tip,
            ty2dt=float(ty2dt), history=_rows(history, 2),
            separator_modes=_rows(separator_modes, 4),
            lower_modes=_rows(lower_modes, 4), masses=masses, ratios=ratios,
            text="".join(lines[start:i])))
    return sets
