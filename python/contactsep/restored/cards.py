"""Appendix G card decks: a pure-Python reader and writer.

The listing reads every card with FORMAT 10 = (7F15.9), except card 5 with
FORMAT 15 = (E15.9,I2); the card layout is in :mod:`contactsep.restored.dataset`.

Reading follows Fortran formatted input (F editing, Fortran 2018 13.7.2.3.2):

* a card is a line ended by LF; a trailing CR is dropped (CRLF decks);
  a line shorter than 80 columns is a card with blanks in the rest;
  columns a FORMAT does not read (76-80, and past the last field) are
  ignored, as the program ignores them;
* every field is 15 columns; an all-blank field is zero; leading blanks,
  and blanks after a leading sign or an exponent letter ('- 1.5E 3'), never
  count; other blanks are removed (``blank="null"``, BN, gfortran's
  default) or read as zeros (``blank="zero"``, BZ, as on the old card
  readers, including the blanks that pad a short line);
* a number is an optional sign, digits with an optional decimal point and
  an optional exponent (E or D with an optionally signed integer, or a
  signed integer alone: '1.5+3'); without a decimal point the last 9 digits
  are decimals ('19' is 19e-9);
* I2 (N on card 5) is an optionally signed integer, by the same blank rule.

Stricter than gfortran, which reads these as a value: a field without a
mantissa digit ('+', '.', 'E5'), an exponent without digits ('1.5E+'),
the exponent letter Q, a comma (gfortran ends the field there),
INF and NaN (rejected as non-finite).  As in gfortran, a decimal exponent
beyond 9999 in magnitude is an error (under BZ, a left-justified '1.0E-7'
has exponent -7000000000: an error, not a silent 0).  The tests record
each case.

Rejected with :class:`~contactsep.errors.DeckError`, which names the data
set, card (line number), columns, text and what was expected: such fields,
a TAB or any character outside printable ASCII, a card longer than 80
columns, N < 1, a deck ending inside a data set, and an empty deck.
Trailing blank lines at the end of the file are ignored.

Writing gives what gfortran writes with these FORMATs: F15.9 as '%15.9f',
E15.9 as '0.100000000E+08', I2 right-justified, LF line ends.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Iterable

from contactsep.errors import DeckError, describe_byte, location
from contactsep.restored.dataset import (
    FIXED_CARDS,
    MODE_GROUPS,
    SCALAR_CARDS,
    DataSet,
)

#: Columns of a punched card.
CARD_COLUMNS = 80
#: Width of an F15.9 or E15.9 field.
FIELD_WIDTH = 15
#: Decimals of F15.9 and E15.9, also the implied decimals of input.
DECIMALS = 9
#: The blank rules: "null" (BN) and "zero" (BZ).
BLANK_MODES = ("null", "zero")

# card 5: E in columns 1-15, N in columns 16-17
_N_COLUMNS = (FIELD_WIDTH + 1, FIELD_WIDTH + 2)

# sign, digits, point, digits, exponent (E/D with optional sign, or a sign)
_NUMBER = re.compile(
    r"([+-]?)([0-9]*)(?:\.([0-9]*))?(?:[EeDd]([+-]?[0-9]+)|([+-][0-9]+))?")
_INTEGER = re.compile(r"[+-]?[0-9]+")
# blanks that never count: after a leading sign, after an exponent letter
_IGNORED_BLANKS = re.compile(r"(^[+-]|[EeDd]) +")
# gfortran rejects a decimal exponent this large (after implied decimals)
_MAX_EXPONENT = 9999
# what gfortran reads as infinity or NaN
_NON_FINITE = re.compile(r"[+-]?(inf|infinity|nan(\(.*\))?)", re.IGNORECASE)


def _check_blank(blank: str) -> None:
    if blank not in BLANK_MODES:
        raise ValueError(f"blank must be one of {BLANK_MODES}, got {blank!r}")


def _apply_blank_rule(field: str, blank: str) -> str:
    """The field with leading blanks, blanks after a leading sign and blanks
    after an exponent letter (the standard's "E followed by zero or more
    blanks") dropped, and the other blanks removed (BN) or made zeros (BZ)."""
    body = _IGNORED_BLANKS.sub(r"\1", field.lstrip(" "))
    return body.replace(" ", "" if blank == "null" else "0")


def parse_real(field: str, decimals: int = DECIMALS, blank: str = "null",
               descriptor: str = "F15.9") -> float:
    """The value of one F (or E) input field, with ``decimals`` implied.

    Raises :class:`DeckError` (without location) for a field that is not a
    finite number; ``descriptor`` names the edit descriptor in its message.
    """
    _check_blank(blank)
    body = _apply_blank_rule(field, blank)
    if not body:
        return 0.0
    match = _NUMBER.fullmatch(body)
    if match is None or not (match[2] or match[3]):
        if _NON_FINITE.fullmatch(field.strip(" ")):
            raise DeckError(text=field.strip(" "),
                            expected=f"a finite number ({descriptor})")
        raise DeckError(text=field.strip(" "),
                        expected=f"a number ({descriptor})")
    sign, whole, fraction, exponent_e, exponent_sign = match.groups()
    exponent = int(exponent_e or exponent_sign or 0)
    if fraction is None:
        # no decimal point: the last `decimals` digits are decimals
        exponent -= decimals
        fraction = ""
    if abs(exponent) > _MAX_EXPONENT:
        # as gfortran; under BZ this is a left-justified exponent ('1.0E-7 ')
        rule = "ignored" if blank == "null" else "read as zeros"
        raise DeckError(text=field.strip(" "),
                        expected=f"an exponent below 10000 ({descriptor}, "
                                 f"blanks {rule})")
    # float() of the decimal string rounds correctly, like gfortran's strtod
    value = float(f"{sign}{whole or '0'}.{fraction or '0'}e{exponent}")
    if not math.isfinite(value):
        raise DeckError(text=field.strip(" "),
                        expected=f"a finite number ({descriptor})")
    return value


def parse_integer(field: str, blank: str = "null",
                  descriptor: str = "I2") -> int:
    """The value of one I input field; raises :class:`DeckError`."""
    _check_blank(blank)
    body = _apply_blank_rule(field, blank)
    if not body:
        return 0
    if _INTEGER.fullmatch(body) is None:
        raise DeckError(text=field.strip(" "),
                        expected=f"an integer ({descriptor})")
    return int(body)


def _deck_text(source) -> str:
    """Deck text from a path (os.PathLike), bytes, or the text itself."""
    if isinstance(source, os.PathLike):
        with open(source, "rb") as handle:
            source = handle.read()
    if isinstance(source, (bytes, bytearray)):
        # one character per byte, so columns count bytes as gfortran does;
        # anything outside printable ASCII is then rejected card by card
        return bytes(source).decode("latin-1")
    if isinstance(source, str):
        if "\n" not in source and os.path.isfile(source):
            # a str is deck text; reading a file name as cards would only
            # give a puzzling error at card 1
            raise TypeError(f"{source!r} names a file: pass "
                            f"pathlib.Path({source!r}) to read it")
        return source
    raise TypeError("a deck is a str (its text), bytes or an os.PathLike path")


def _card_images(text: str) -> list[str]:
    """The deck's lines: LF-separated, a trailing CR dropped, trailing
    blank lines removed."""
    lines = text.split("\n")
    if lines[-1] == "":
        lines.pop()
    lines = [line[:-1] if line.endswith("\r") else line for line in lines]
    while lines and not lines[-1].strip(" "):
        lines.pop()
    return lines


def _check_card(line: str, data_set: int, card: int) -> None:
    for column, char in enumerate(line, start=1):
        if " " <= char <= "~":
            continue
        if char == "\t":
            found = "a TAB (character 0x09)"
            expected = "a blank (a TAB has no fixed column on a card)"
        elif char == "\r":
            found = "a CR (character 0x0D) not followed by LF"
            expected = ("a printable ASCII character (a card ends at LF or "
                        "CR LF)")
        else:
            found = describe_byte(ord(char))
            expected = ("a printable ASCII character (a card ends at LF or "
                        "CR LF)")
        # the character is named, never echoed (issue 9)
        raise DeckError(f"{location(data_set, card, (column, column))}: "
                        f"found {found}, expected {expected}",
                        data_set=data_set, card=card,
                        columns=(column, column), text=char,
                        expected=expected)
    if len(line) > CARD_COLUMNS:
        raise DeckError(data_set=data_set, card=card,
                        columns=(CARD_COLUMNS + 1, len(line)),
                        text=line[CARD_COLUMNS:],
                        expected="nothing past column 80: a card has 80 columns")


def _located(error: DeckError, data_set: int, card: int,
             columns: tuple[int, int]) -> DeckError:
    return DeckError(data_set=data_set, card=card, columns=columns,
                     text=error.text, expected=error.expected)


class _DataSetReader:
    """Reads the cards of one data set, starting at line ``first``."""

    def __init__(self, lines: list[str], first: int, index: int, blank: str):
        self.lines, self.first, self.index, self.blank = lines, first, index, blank
        self.n: int | None = None

    def card(self, number: int) -> tuple[str, int]:
        """Card ``number`` (1-based within the set), padded to 80 columns,
        and its line number in the deck."""
        line_index = self.first + number - 1
        if line_index >= len(self.lines):
            found = len(self.lines) - self.first
            if self.n is None:
                expected = "6 + 3N cards (N is on card 5)"
            else:
                expected = f"6 + 3N = {FIXED_CARDS + 3 * self.n} cards"
            raise DeckError(
                f"{location(self.index)}: expected {expected}, found {found} "
                f"(the deck ends at card {len(self.lines)})",
                data_set=self.index, expected=expected)
        line = self.lines[line_index]
        _check_card(line, self.index, line_index + 1)
        return line.ljust(CARD_COLUMNS), line_index + 1

    def real(self, image: str, card: int, field: int,
             descriptor: str = "F15.9") -> float:
        first = FIELD_WIDTH * field
        columns = (first + 1, first + FIELD_WIDTH)
        try:
            return parse_real(image[first:first + FIELD_WIDTH], DECIMALS,
                              self.blank, descriptor)
        except DeckError as error:
            raise _located(error, self.index, card, columns) from None

    def integer(self, image: str, card: int) -> int:
        first, last = _N_COLUMNS
        try:
            return parse_integer(image[first - 1:last], self.blank, "I2")
        except DeckError as error:
            raise _located(error, self.index, card, _N_COLUMNS) from None

    def read(self) -> tuple[DataSet, int]:
        """The data set, and the line index after its last card."""
        values: dict = {}
        for number, names in SCALAR_CARDS:
            image, card = self.card(number)
            if names == ("e", "n"):
                values["e"] = self.real(image, card, 0, "E15.9")
                n = self.integer(image, card)
                if n < 1:
                    raise DeckError(
                        data_set=self.index, card=card, columns=_N_COLUMNS,
                        text=image[_N_COLUMNS[0] - 1:_N_COLUMNS[1]],
                        expected="N >= 1 (I2)")
                self.n = values["n"] = n
            else:
                for field, name in enumerate(names):
                    values[name] = self.real(image, card, field)
        n = self.n
        for group_index, group in enumerate(MODE_GROUPS):
            columns = {name: [] for name in group}
            for mode in range(n):
                image, card = self.card(FIXED_CARDS + 1 + group_index * n + mode)
                for field, name in enumerate(group):
                    columns[name].append(self.real(image, card, field))
            values.update(columns)
        return DataSet(**values), self.first + FIXED_CARDS + 3 * n


def read_deck(source, blank: str = "null") -> list[DataSet]:
    """Every data set of a deck: ``source`` is a path (os.PathLike), bytes,
    or the deck's text as a str.

    Raises :class:`DeckError` at the first bad card, with the data sets read
    before it in ``error.partial``.
    """
    _check_blank(blank)
    lines = _card_images(_deck_text(source))
    if not lines:
        raise DeckError("deck: expected at least one data set of 6 + 3N "
                        "cards, found no cards",
                        expected="at least one data set of 6 + 3N cards")
    data_sets: list[DataSet] = []
    first = 0
    while first < len(lines):
        reader = _DataSetReader(lines, first, len(data_sets) + 1, blank)
        try:
            data_set, first = reader.read()
        except DeckError as error:
            error.partial = list(data_sets)
            raise
        data_sets.append(data_set)
    return data_sets


def format_f(value: float) -> str:
    """``value`` as gfortran writes it with F15.9.

    Raises ValueError where gfortran would write asterisks (the value needs
    more than 15 columns) or for a non-finite value.
    """
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{value!r} is not finite")
    text = f"{value:{FIELD_WIDTH}.{DECIMALS}f}"
    if len(text) > FIELD_WIDTH:
        raise ValueError(f"{value!r} does not fit F15.9 (gfortran writes "
                         f"asterisks)")
    return text


def format_e(value: float) -> str:
    """``value`` as gfortran writes it with E15.9, e.g. '0.100000000E+08'
    and '-.100000000E+08'; exponents beyond 99 drop the E ('0.1...+101')."""
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{value!r} is not finite")
    if value == 0.0:
        digits, exponent = "0" * DECIMALS, 0
    else:
        significand, power = f"{abs(value):.{DECIMALS - 1}e}".split("e")
        digits, exponent = significand.replace(".", ""), int(power) + 1
    lead = "-." if math.copysign(1.0, value) < 0 else "0."
    tail = (f"E{exponent:+03d}" if abs(exponent) <= 99
            else f"{exponent:+04d}")
    return lead + digits + tail


def format_i2(value: int) -> str:
    """N as I2; ValueError outside 1..99 (N >= 1 and two columns)."""
    if isinstance(value, bool) or not 1 <= value <= 99:
        raise ValueError(f"N = {value!r} must be 1..99 to fit I2")
    return f"{int(value):2d}"


def format_deck(data_sets: Iterable[DataSet]) -> str:
    """The card images of ``data_sets``, back to back, LF line ends."""
    cards: list[str] = []
    for data_set in data_sets:
        for _, names in SCALAR_CARDS:
            if names == ("e", "n"):
                cards.append(format_e(data_set.e) + format_i2(data_set.n))
            else:
                cards.append("".join(format_f(getattr(data_set, name))
                                     for name in names))
        for group in MODE_GROUPS:
            for mode in range(data_set.n):
                cards.append("".join(format_f(getattr(data_set, name)[mode])
                                     for name in group))
    return "".join(card + "\n" for card in cards)
