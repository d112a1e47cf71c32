"""The restored Fortran core (fortran/*.f90), called through f2py.

Two extension modules are built from one generic source: ``_core_single``
(the listing's REAL, float32) and ``_core_double`` (float64).  This module is
the thin layer between them and Python: it reads decks with the core's own
card reader, runs data sets, and turns status codes into
:class:`~contactsep.errors.DeckError`.
"""

from __future__ import annotations

import importlib
import math
import os
from dataclasses import dataclass
from typing import Iterator

import numpy as np

from contactsep import cards
from contactsep import checks
from contactsep.dataset import MODE_GROUPS, SCALAR_CARDS, DataSet
from contactsep.errors import DeckError, location
from contactsep.result import Result

PRECISIONS = ("single", "double")
BLANK_MODES = cards.BLANK_MODES

#: Scalar inputs in the order of the core's ``scalars`` array (card order).
SCALAR_NAMES = tuple(
    name for _, names in SCALAR_CARDS for name in names if name != "n")
#: Mode inputs in the order of the columns of the core's ``modes`` array.
MODE_NAMES = tuple(name for group in MODE_GROUPS for name in group)

#: The listing's fixed end of the lower-contact history (TAU = 0.060 s).
TAU = 0.060
#: Most impact-search lines the core may print before it gives up: as many
#: as the history may have, so any DELT the history allows can also reach
#: an impact up to 0.06 s away.
MAX_SEARCH_LINES = 1_000_000
#: Room for search lines on a first try: f2py zero-fills every output
#: array, so room costs time even unused (12 ms per call for a million
#: lines); a search that needs more is run again with MAX_SEARCH_LINES.
_FIRST_SEARCH_LINES = 512
_STATUS_SEARCH_FULL = 23
#: Most lower-contact history lines (T = 0, DELT, ... < TAU) the core will
#: produce: DELT must be at least TAU / 1e6 = 6e-8 s.
MAX_HISTORY_LINES = 1_000_000
_FIELD = 15
_STATUS_END_OF_DECK = 1
#: Solver failures and the card field that decides them (status codes of
#: fortran/status.f90): (card within the data set, columns).
_SOLVER_FIELDS = {
    20: (4, (31, 45)),   # DELY: the release point is not above it
    21: (4, (1, 15)),    # DELT: the search step no longer moves T
    22: (5, (16, 17)),   # N: the modal sums overflow
    23: (4, (1, 45)),    # DELT or DELY: no impact within the search bound
    24: (4, (1, 15)),    # DELT: the history step no longer moves T
    25: (4, (1, 15)),    # DELT: the history needs too many lines
}


def _api(precision: str):
    if precision not in PRECISIONS:
        raise ValueError(
            f"precision must be one of {PRECISIONS}, not {precision!r}")
    module = importlib.import_module(f"contactsep._core_{precision}")
    return module.contactsep_api


def _text(message: bytes | str) -> str:
    if isinstance(message, bytes):
        message = message.decode("ascii", "replace")
    return message.strip()


@dataclass(frozen=True)
class DeckSet:
    """One data set as read from a deck, with where it stands in the file."""

    #: 1-based position of the data set in the deck.
    index: int
    #: 1-based line numbers of its first and last card.
    first_card: int
    last_card: int
    data_set: DataSet


def read_text(path: str | os.PathLike) -> str:
    """The deck file as text, one character per byte (card images are
    ASCII; any other byte is kept so the reader can point at it)."""
    with open(path, "rb") as handle:
        return handle.read().decode("latin-1")


#: The most modes card 5's I2 field can give, and so the most cards a data
#: set can have.
MAX_MODES = 99
_MAX_CARDS = 6 + 3 * MAX_MODES
_STATUS_TRUNCATED = 14


def _card_lines(text: str) -> list[str]:
    """The deck's lines (cards), as the core counts them: ended by LF."""
    lines = text.split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    return lines


def iter_deck(text: str, *, precision: str = "single",
              blank: str = "null") -> Iterator[DeckSet]:
    """Read data sets from deck ``text`` with the core's card reader.

    Values are read in the working precision of ``precision``, exactly as the
    original program reads them.  Raises :class:`DeckError` at the first bad
    card; data sets before it have already been yielded.

    The core is handed one data set's worth of cards at a time (at most
    6 + 3 * 99), so reading is linear in the size of the deck, as bytes,
    so that any byte reaches the core's check for printable ASCII.  f2py
    passes text as a C string, which would end at a NUL byte: the core is
    given only the lines before the first NUL, and the NUL is reported here
    when reading reaches it.
    """
    if blank not in BLANK_MODES:
        raise ValueError(f"blank must be one of {BLANK_MODES}, not {blank!r}")
    api = _api(precision)
    lines = _card_lines(text)
    usable = len(lines)
    nul = text.find("\x00")
    if nul >= 0:
        usable = text.count("\n", 0, nul)
        nul_card = usable + 1
        nul_column = nul - (text.rfind("\n", 0, nul) + 1) + 1
    # next_content[i]: first line at or after i that is not blank
    next_content = [usable] * (usable + 1)
    for i in range(usable - 1, -1, -1):
        next_content[i] = i if lines[i].strip() else next_content[i + 1]

    first, index = 0, 0          # first: 0-based line of the data set
    while True:
        index += 1
        if next_content[min(first, usable)] >= usable:
            if nul >= 0:
                raise _nul_error(index, nul_card, nul_column)
            if index == 1:
                raise DeckError("the deck holds no data set "
                                "(expected 6 + 3N cards)", data_set=None)
            return
        # blank lines are cards of zeros, so a window that starts with
        # them still reaches the next card with something on it
        stop = min(usable, max(first + _MAX_CARDS, next_content[first] + 1))
        window = "".join(line + "\n" for line in lines[first:stop])
        (scalars, n, modes, next_card, status, message, card, first_col,
         last_col) = api.read_data_set(
             text=window.encode("latin-1"), first_line=first + 1,
             first_card=first + 1, blank_zero=int(blank == "zero"),
             max_modes=MAX_MODES)
        if status == _STATUS_TRUNCATED and nul >= 0:
            raise _nul_error(index, nul_card, nul_column)
        if status != 0:
            raise DeckError(
                f"data set {index}, {_text(message)}" if card else
                f"data set {index}: {_text(message)}", data_set=index,
                card=card or None,
                columns=(first_col, last_col) if first_col else None)
        values = dict(zip(SCALAR_NAMES, (float(x) for x in scalars)))
        for column, name in enumerate(MODE_NAMES):
            values[name] = np.array(modes[:n, column], dtype=np.float64)
        yield DeckSet(index, first + 1, next_card - 1,
                      DataSet(n=int(n), **values))
        first = next_card - 1


def _nul_error(index: int, card: int, column: int) -> DeckError:
    return DeckError(
        f"data set {index}, card {card}, column {column}: found the "
        f"character of code 0 (NUL), expected a printable ASCII character",
        data_set=index, card=card, columns=(column, column))


def history_length(delt: float, precision: str = "double") -> int:
    """Room for the history loop T = 0, DELT, ... < TAU.

    T is accumulated in the working precision, and each T + DELT can fall
    short of the exact sum by half an ulp of T <= TAU, i.e. by less than
    TAU * eps; so the loop runs at most TAU / (DELT - TAU * eps) times.
    Never more than twice MAX_HISTORY_LINES: the core refuses a DELT that
    needs more than MAX_HISTORY_LINES before it uses the room.
    """
    eps = float(np.finfo(np.float32 if precision == "single"
                         else np.float64).eps)
    step = delt - TAU * eps
    if not step > 0:
        return 2 * MAX_HISTORY_LINES
    return int(min(math.ceil(TAU / step), 2 * MAX_HISTORY_LINES)) + 2


def listing_capacity(n: int, history: int, search: int) -> int:
    """Bytes the listing of one data set can take with ``search`` search
    lines: each WRITE's fields of 15 columns and a newline, by section."""
    line = lambda fields: fields * _FIELD + 1
    return (line(4) + n * line(5) + search * line(3) + line(1)
            + line(5) + n * line(2) + line(4) + line(1)
            + history * line(2) + 2 * n * line(4) + 2 * line(4))


def solve(data_set: DataSet, precision: str = "single", *,
          data_set_index: int | None = None,
          first_card: int | None = None, listing: bool = True) -> Result:
    """Run one data set through the restored core.

    This is the call a designer makes in a loop: no deck file is involved.
    Inputs are rounded to the build's precision on the way in.  Values
    outside their ranges, a release point not above the separator or an
    impact that never comes raise :class:`DeckError`; ``data_set_index``
    and ``first_card`` (the data set's place in a deck) locate it.
    ``listing=False`` skips formatting the listing text (``Result.listing``
    is then ``""``); every number is the same.
    """
    api = _api(precision)
    dtype = np.float32 if precision == "single" else np.float64
    scalars = np.array([getattr(data_set, name) for name in SCALAR_NAMES],
                       dtype=dtype)
    modes = np.asfortranarray(
        np.column_stack([getattr(data_set, name) for name in MODE_NAMES]),
        dtype=dtype)
    n = data_set.n
    max_history = history_length(data_set.delt, precision)
    with_listing = listing
    for search in (_FIRST_SEARCH_LINES, MAX_SEARCH_LINES):
        (p, ape, trace, n_trace, impact, a1, b1, tip, ty2dt, history,
         n_history, p2, p3, closing, listing, listing_length, status,
         message) = api.solve(
             scalars=scalars, n=n, modes=modes, max_trace=search,
             max_history=max_history,
             max_listing=listing_capacity(n, max_history, search)
             if with_listing else 1,
             with_listing=int(bool(with_listing)))
        if status != _STATUS_SEARCH_FULL:
            break
    text = listing[:listing_length].tobytes().decode("ascii")
    if status != 0:
        card = columns = None
        if first_card is not None and status in _SOLVER_FIELDS:
            offset, columns = _SOLVER_FIELDS[status]
            card = first_card + offset - 1
        where = location(data_set_index, card, columns) + ": " \
            if data_set_index is not None else ""
        raise DeckError(f"{where}{_text(message)}",
                        data_set=data_set_index, card=card, columns=columns,
                        listing=text)
    result = Result(
        inputs=data_set, precision=precision,
        p=p.copy(), ape=ape.copy(),
        trace_t=trace[:n_trace, 0].copy(),
        trace_ty=trace[:n_trace, 1].copy(),
        trace_tydtl=trace[:n_trace, 2].copy(),
        t_impact=float(impact[0]), ey=float(impact[1]),
        ct=float(impact[2]), ct2=float(impact[3]), ct3=float(impact[4]),
        a1=a1.copy(), b1=b1.copy(),
        tip_ty=float(tip[1]), tip_tydtl=float(tip[2]), tip_act=float(tip[3]),
        ty2dt=float(ty2dt),
        history_t=history[:n_history, 0].copy(),
        history_ty3=history[:n_history, 1].copy(),
        p2=p2.copy(), p3=p3.copy(),
        wm=float(closing[0]), wm2=float(closing[1]), wm3=float(closing[2]),
        gr=float(closing[4]), beta=float(closing[5]),
        mr1=float(closing[6]), mr3=float(closing[7]),
        listing=text)
    checks.warn(checks.input_messages(data_set)
                + checks.result_messages(result))
    return result


def iter_replay(text: str, precision: str = "single", *,
                blank: str = "null") -> Iterator[Result]:
    """Run the data sets of deck ``text`` one after another (a generator,
    so a long deck need not be held in memory); see :func:`replay`."""
    for item in iter_deck(text, precision=precision, blank=blank):
        yield solve(item.data_set, precision, data_set_index=item.index,
                    first_card=item.first_card)


def replay_text(text: str, precision: str = "single", *,
                blank: str = "null") -> list[Result]:
    """Run every data set of deck ``text``; see :func:`replay`."""
    results: list[Result] = []
    try:
        for result in iter_replay(text, precision, blank=blank):
            results.append(result)
    except DeckError as error:
        error.partial = results
        raise
    return results


def replay(path: str | os.PathLike, precision: str = "single", *,
           blank: str = "null") -> list[Result]:
    """Replay an original card deck: one :class:`Result` per data set.

    ``"".join(r.listing for r in results)`` is what the original program
    prints for the deck.  On a bad data set :class:`DeckError` is raised with
    the results of the data sets before it in ``error.partial``.
    """
    return replay_text(read_text(path), precision, blank=blank)
