"""The restored Fortran core (fortran/restored/*.f90), called through f2py.

Two extension modules are built from one generic source: ``_core_single``
(the listing's REAL, float32) and ``_core_double`` (float64).  This module is
the thin layer between them and Python: it reads decks with the core's own
card reader, runs data sets, and turns status codes into
:class:`~contactsep.errors.DeckError`.
"""

from __future__ import annotations

import importlib
import io
import math
import os
import threading
from collections import deque
from dataclasses import dataclass
from pathlib import Path
from typing import BinaryIO, Iterator, Union

import numpy as np

from contactsep.constants import LISTING_TAU_S
from contactsep.errors import DeckError, describe_byte, location
from contactsep.restored import cards, checks
from contactsep.restored import status as status_codes
from contactsep.restored.dataset import (
    FIXED_CARDS,
    MODE_GROUPS,
    SCALAR_CARDS,
    DataSet,
)
from contactsep.restored.result import Result

PRECISIONS = ("single", "double")
BLANK_MODES = cards.BLANK_MODES

#: Scalar inputs in the order of the core's ``scalars`` array (card order).
SCALAR_NAMES = tuple(
    name for _, names in SCALAR_CARDS for name in names if name != "n")
#: Mode inputs in the order of the columns of the core's ``modes`` array.
MODE_NAMES = tuple(name for group in MODE_GROUPS for name in group)

#: The listing's fixed end of the lower-contact history (TAU = 0.060 s).
TAU = LISTING_TAU_S
#: Most impact-search lines the core may print before it gives up: as many
#: as the history may have, so any DELT the history allows can also reach
#: an impact up to 0.06 s away.
MAX_SEARCH_LINES = 1_000_000
#: The core keeps one run's tables and listing until they are taken.
_KEPT = threading.Lock()
#: Most lower-contact history lines (T = 0, DELT, ... < TAU) the core will
#: produce: DELT must be at least TAU / 1e6 = 6e-8 s.
MAX_HISTORY_LINES = 1_000_000
_FIELD = 15
#: Solver failures and the card field that decides them (status codes of
#: fortran/restored/status.f90): (card within the data set, columns).
_SOLVER_FIELDS = {
    # DELY: the release point is not above it
    status_codes.RELEASE_NOT_ABOVE: (4, (31, 45)),
    # DELT: the search step no longer moves T
    status_codes.SEARCH_STALLED: (4, (1, 15)),
    # N: the modal sums overflow
    status_codes.SEARCH_NOT_FINITE: (5, (16, 17)),
    # DELT or DELY: no impact within the search bound
    status_codes.TRACE_FULL: (4, (1, 45)),
    # DELT: the history step no longer moves T
    status_codes.HISTORY_STALLED: (4, (1, 15)),
    # DELT: the history needs too many lines
    status_codes.HISTORY_FULL: (4, (1, 15)),
}


def _api(precision: str):
    if precision not in PRECISIONS:
        raise ValueError(
            f"precision must be one of {PRECISIONS}, not {precision!r}")
    module = importlib.import_module(f"contactsep.restored._core_{precision}")
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
    #: Its card images as read (one line each, LF-ended, a CR before the
    #: LF dropped): what ``contactsep legacy`` feeds the original program.
    cards: str = ""


def read_text(path: str | os.PathLike) -> str:
    """The deck file as text, one character per byte (card images are
    ASCII; any other byte is kept so the reader can point at it).  The
    whole file is held: :func:`iter_deck` and :func:`iter_replay` take the
    path itself and read it a card at a time."""
    with open(path, "rb") as handle:
        return handle.read().decode("latin-1")


#: The most modes card 5's I2 field can give, and so the most cards a data
#: set can have: 6 + 3 * 99 = 303.
MAX_MODES = 99
MAX_CARDS = 6 + 3 * MAX_MODES
_MAX_CARDS = MAX_CARDS
#: Columns past the card's 80 a line is read for before it is refused:
#: enough to show what is there (the rest of the line is never read).
_PAST_CARD = 40
_LINE_READ = cards.CARD_COLUMNS + _PAST_CARD + 1
#: A deck: its text (str or bytes), a path (os.PathLike) or a binary file.
Deck = Union[str, bytes, "os.PathLike[str]", BinaryIO]


def check_line(raw: bytes, complete: bool = True) -> tuple[int, int, str]:
    """What is wrong with one line of a deck (its LF removed, at most
    ``_LINE_READ`` bytes; ``complete`` False when the line goes on):
    (first column, last column, what was found and expected), or
    (0, 0, "") for a good card.  A character outside printable ASCII is
    named by its code, never echoed; a TAB and a stray CR get their own
    words; then a line past column 80 is refused, quoting (printable)
    what is there."""
    for column, code in enumerate(raw, start=1):
        if 32 <= code <= 126:
            continue
        if code == 9:
            found = ("found a TAB (character 0x09), expected a blank "
                     "(a TAB has no fixed column on a card)")
        elif code == 13:
            found = ("found a CR (character 0x0D) not followed by "
                     "LF, expected a printable ASCII character (a card "
                     "ends at LF or CR LF)")
        else:
            found = (f"found {describe_byte(code)}, expected a printable "
                     f"ASCII character (a card ends at LF or CR LF)")
        return column, column, found
    width = cards.CARD_COLUMNS
    if len(raw) > width:
        shown = raw[width:width + _PAST_CARD].decode("ascii")
        more = "..." if not complete or len(raw) > width + _PAST_CARD else ""
        last = len(raw) if complete else width + 1
        return (width + 1, last,
                f"found '{shown}{more}'"
                f"{'' if complete else ' (the line goes on)'}, expected "
                f"nothing past column 80 (a card has 80 columns)")
    return 0, 0, ""


class _CardLines:
    """The lines of a deck, read one at a time (never more than
    ``_LINE_READ`` bytes of one) and checked as they come.

    ``next()`` gives a good line as text without its LF (and one CR
    before it), or None at the end of the deck or at the first bad line,
    whose place and message are then in ``bad`` (line, first column, last
    column, message without the data set); nothing after it is read."""

    def __init__(self, stream: BinaryIO) -> None:
        self._stream = stream
        self.count = 0
        self.bad: tuple[int, int, int, str] | None = None

    def next(self) -> str | None:
        if self.bad is not None:
            return None
        raw = self._stream.readline(_LINE_READ)
        if not raw:
            return None
        self.count += 1
        complete = raw.endswith(b"\n") or len(raw) < _LINE_READ
        if raw.endswith(b"\n"):
            raw = raw[:-1]
        if complete and raw.endswith(b"\r"):
            raw = raw[:-1]
        first, last, found = check_line(raw, complete)
        if found:
            self.bad = (self.count, first, last, found)
            return None
        return raw.decode("ascii")


def _bad_line_error(index: int, bad: tuple[int, int, int, str]) -> DeckError:
    card, first, last, found = bad
    return DeckError(f"{location(index, card, (first, last))}: {found}",
                     data_set=index, card=card, columns=(first, last))


class _open_deck:
    """Context manager: a binary stream over any :data:`Deck`."""

    def __init__(self, source: Deck) -> None:
        self._source, self._owned = source, None

    def __enter__(self) -> BinaryIO:
        source = self._source
        if isinstance(source, str):
            source = source.encode("latin-1")
        if isinstance(source, (bytes, bytearray, memoryview)):
            return io.BytesIO(bytes(source))
        if isinstance(source, os.PathLike):
            self._owned = open(source, "rb")
            return self._owned
        if hasattr(source, "readline"):
            return source
        raise TypeError("a deck is its text (str or bytes), a path "
                        "(os.PathLike) or a binary file")

    def __exit__(self, *exc) -> None:
        if self._owned is not None:
            self._owned.close()


def iter_deck(source: Deck, *, precision: str = "single",
              blank: str = "null") -> Iterator[DeckSet]:
    """Read data sets from a deck with the core's card reader.

    ``source`` is the deck's text (str, or bytes), a path (os.PathLike:
    a str is always text) or a binary file.  Values are read in the
    working precision of ``precision``, exactly as the original program
    reads them.  Raises :class:`DeckError` at the first bad card; data
    sets before it have already been yielded.

    The deck is read a line at a time and at most one data set ahead
    (6 + 3 * 99 = 303 cards), so memory is bounded by one data set
    whatever the deck's size, and input that never ends is refused: a
    line at its column 81 (only 40 columns past the card are read, to
    show them), a character outside printable ASCII when it is read,
    more than 303 blank lines where a data set should start.  The core is
    handed one data set's worth of cards at a time.
    """
    if blank not in BLANK_MODES:
        raise ValueError(f"blank must be one of {BLANK_MODES}, not {blank!r}")
    api = _api(precision)
    with _open_deck(source) as stream:
        yield from _read_sets(_CardLines(stream), api, blank)


def _read_sets(lines: _CardLines, api, blank: str) -> Iterator[DeckSet]:
    pending: deque[str] = deque()   # good lines read, not yet used
    first, index = 0, 0             # first: 0-based line of the data set

    def fill(count: int) -> None:
        while len(pending) < count:
            line = lines.next()
            if line is None:
                return
            pending.append(line)

    while True:
        index += 1
        # blank lines where a data set starts: the end of the deck, or
        # cards of zeros (an error at card 1); never more than a data set
        # of them, so blank lines that never end are refused
        blanks = 0
        while True:
            fill(blanks + 1)
            if blanks == len(pending) or pending[blanks].strip(" "):
                break
            blanks += 1
            if blanks > MAX_CARDS:
                raise DeckError(
                    f"data set {index}, cards {first + 1}-{first + blanks}: "
                    f"found {blanks} blank lines and the deck goes on, "
                    f"expected a data set (at most 6 + 3 * {MAX_MODES} = "
                    f"{MAX_CARDS} cards) or the end of the deck",
                    data_set=index)
        if blanks == len(pending):
            if lines.bad is not None:
                raise _bad_line_error(index, lines.bad)
            if index == 1:
                raise DeckError("the deck holds no data set "
                                "(expected 6 + 3N cards)", data_set=None)
            return
        # cards 1-6, then as many as card 5's N asks for: never a line
        # past the data set is read before it is run (a deck on a pipe)
        size = FIXED_CARDS
        while True:
            fill(size)
            window = "".join(pending[i] + "\n"
                             for i in range(min(len(pending), size)))
            try:
                item = _read_window(api, window, first + 1, index, blank)
                break
            except _Truncated as error:
                if error.n > 0 and size == FIXED_CARDS and \
                        len(pending) >= size:
                    size = FIXED_CARDS + 3 * min(error.n, MAX_MODES)
                    continue
                if lines.bad is not None:
                    raise _bad_line_error(index, lines.bad) from None
                raise error.deck_error from None
        used = item.last_card - first
        yield DeckSet(item.index, item.first_card, item.last_card,
                      item.data_set, "".join(
                          pending[i] + "\n" for i in range(used)))
        next_card = item.last_card + 1
        for _ in range(next_card - 1 - first):
            pending.popleft()
        first = next_card - 1


class _Truncated(Exception):
    """The cards ended inside the data set (the window or the deck)."""

    def __init__(self, deck_error: DeckError, n: int) -> None:
        self.deck_error, self.n = deck_error, n


def _read_window(api, window: str, first_card: int, index: int,
                 blank: str) -> DeckSet:
    """Read the data set at the start of ``window`` (cards from line
    ``first_card`` of the deck on) with the core's reader."""
    (scalars, n, modes, next_card, status, message, card, first_col,
     last_col) = api.read_data_set(
         text=window.encode("ascii"), first_line=first_card,
         first_card=first_card, blank_zero=int(blank == "zero"),
         max_modes=MAX_MODES)
    if status != status_codes.OK:
        text = _text(message)
        if status == status_codes.CARD_NOT_NUMERIC and card and first_col:
            line = window.split("\n")[card - first_card]
            text = _exponent_message(text, line, (first_col, last_col),
                                     blank)
        error = DeckError(
            f"data set {index}, {text}" if card else
            f"data set {index}: {text}", data_set=index,
            card=card or None,
            columns=(first_col, last_col) if first_col else None)
        if status == status_codes.DECK_TRUNCATED:
            raise _Truncated(error, int(n))
        raise error
    values = dict(zip(SCALAR_NAMES, (float(x) for x in scalars)))
    for column, name in enumerate(MODE_NAMES):
        values[name] = np.array(modes[:n, column], dtype=np.float64)
    return DeckSet(index, first_card, next_card - 1,
                   DataSet(n=int(n), **values))


def reread(item: DeckSet, precision: str, *, blank: str = "null") -> DeckSet:
    """The data set ``item`` read again from its cards in ``precision``
    (errors name the same data set, cards and columns)."""
    try:
        return _read_window(_api(precision), item.cards, item.first_card,
                            item.index, blank)
    except _Truncated as error:
        raise error.deck_error from None


def _exponent_message(message: str, line: str, columns: tuple[int, int],
                      blank: str) -> str:
    """The core's 'expected a number' for a field gfortran refuses only for
    its exponent beyond 9999 says so, as the deck format's docs do."""
    field = line.ljust(cards.CARD_COLUMNS)[columns[0] - 1:columns[1]]
    try:
        cards.parse_real(field, blank=blank)
    except DeckError as error:
        if error.expected and error.expected.startswith("an exponent"):
            return message.replace("expected a number (",
                                   "expected a number with an exponent "
                                   "below 10000 (", 1)
    return message


def history_length(delt: float, precision: str = "double",
                   tau: float = TAU) -> int:
    """Room for the history loop T = 0, DELT, ... < tau.

    T is accumulated in the working precision, and each T + DELT can fall
    short of the exact sum by half an ulp of T <= tau, i.e. by less than
    tau * eps; so the loop runs at most tau / (DELT - tau * eps) times.
    Never more than twice MAX_HISTORY_LINES: the core refuses a DELT that
    needs more than MAX_HISTORY_LINES before it uses the room.
    """
    eps = float(np.finfo(np.float32 if precision == "single"
                         else np.float64).eps)
    step = delt - tau * eps
    if not (step > 0 and math.isfinite(tau) and tau > 0):
        return 2 * MAX_HISTORY_LINES
    return int(min(math.ceil(tau / step), 2 * MAX_HISTORY_LINES)) + 2


def listing_capacity(n: int, history: int, search: int) -> int:
    """Bytes the listing of one data set can take with ``search`` search
    lines: each WRITE's fields of 15 columns and a newline, by section."""
    line = lambda fields: fields * _FIELD + 1
    return (line(4) + n * line(5) + search * line(3) + line(1)
            + line(5) + n * line(2) + line(4) + line(1)
            + history * line(2) + 2 * n * line(4) + 2 * line(4))


def solve(data_set: DataSet, precision: str = "single", *,
          data_set_index: int | None = None,
          first_card: int | None = None, listing: bool = True,
          tau: float = TAU) -> Result:
    """Run one data set through the restored core.

    This is the call a designer makes in a loop: no deck file is involved.
    Inputs are rounded to the build's precision on the way in.  Values
    outside their ranges, a release point not above the separator or an
    impact that never comes raise :class:`DeckError`; ``data_set_index``
    and ``first_card`` (the data set's place in a deck) locate it.
    ``listing=False`` skips formatting the listing text (``Result.listing``
    is then ``""``); every number is the same.  ``tau`` (s) ends the
    lower contact's history (the listing's TAU = 0.060 s; the listing
    with another ``tau`` is not the original program's); at most
    1,000,000 history lines (tau / DELT).
    """
    api = _api(precision)
    dtype = np.float32 if precision == "single" else np.float64
    scalars = np.array([getattr(data_set, name) for name in SCALAR_NAMES],
                       dtype=dtype)
    modes = np.asfortranarray(
        np.column_stack([getattr(data_set, name) for name in MODE_NAMES]),
        dtype=dtype)
    n = data_set.n
    max_history = history_length(data_set.delt, precision, tau)
    with _KEPT:
        (p, ape, impact, a1, b1, tip, ty2dt, p2, p3, closing, n_trace,
         n_history, listing_length, status, message) = api.solve(
             scalars=scalars, n=n, modes=modes, t_end=tau,
             max_trace=MAX_SEARCH_LINES, max_history=max_history,
             max_listing=listing_capacity(n, max_history,
                                          MAX_SEARCH_LINES),
             with_listing=int(bool(listing)))
        (trace_t, trace_ty, trace_tydtl, history_t,
         history_ty3) = api.take_tables(n_trace, n_history)
        text = ""
        if listing:
            codes = api.take_listing(listing_length)
            # decoded from the array's buffer (one copy), then dropped
            text = str(codes.data, "ascii")
            del codes
    if status != status_codes.OK:
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
        p=p, ape=ape,
        trace_t=trace_t, trace_ty=trace_ty, trace_tydtl=trace_tydtl,
        t_impact=float(impact[0]), ey=float(impact[1]),
        ct=float(impact[2]), ct2=float(impact[3]), ct3=float(impact[4]),
        a1=a1, b1=b1,
        tip_ty=float(tip[1]), tip_tydtl=float(tip[2]), tip_act=float(tip[3]),
        ty2dt=float(ty2dt),
        history_t=history_t, history_ty3=history_ty3,
        p2=p2, p3=p3,
        wm=float(closing[0]), wm2=float(closing[1]), wm3=float(closing[2]),
        gr=float(closing[4]), beta=float(closing[5]),
        mr1=float(closing[6]), mr3=float(closing[7]),
        listing=text, tau=float(tau))
    checks.warn(checks.input_messages(data_set)
                + checks.result_messages(result))
    return result


def iter_replay(source: Deck, precision: str = "single", *,
                blank: str = "null") -> Iterator[Result]:
    """Run the data sets of a deck one after another (a generator: the
    deck is read a data set at a time, so its size does not matter);
    ``source`` as for :func:`iter_deck`; see :func:`replay`."""
    for item in iter_deck(source, precision=precision, blank=blank):
        yield solve(item.data_set, precision, data_set_index=item.index,
                    first_card=item.first_card)


def replay_text(text: Deck, precision: str = "single", *,
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
    return replay_text(Path(path), precision, blank=blank)
