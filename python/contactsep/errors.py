"""The package's errors: a bad deck, and any other input it refuses.

Every message is one printable line; the command prints it as
``contactsep: error: <message>`` and exits with status 2.
"""

from __future__ import annotations


def location(data_set: int | None = None, card: int | None = None,
             columns: tuple[int, int] | None = None) -> str:
    """'data set 2, card 9, columns 16-30' (the parts that are known)."""
    parts = []
    if data_set is not None:
        parts.append(f"data set {data_set}")
    if card is not None:
        parts.append(f"card {card}")
    if columns is not None:
        first, last = columns
        parts.append(f"column {first}" if first == last
                     else f"columns {first}-{last}")
    return ", ".join(parts) if parts else "deck"


_CONTROL_NAMES = {0: "NUL", 7: "BEL", 8: "BS", 9: "TAB", 10: "LF", 11: "VT",
                  12: "FF", 13: "CR", 26: "SUB", 27: "ESC", 127: "DEL"}


def describe_byte(code: int) -> str:
    """'character 0x1B (ESC)': a byte (or character code) named without
    printing it, for messages that must stay one printable line."""
    name = _CONTROL_NAMES.get(code)
    return f"character 0x{code:02X}" + (f" ({name})" if name else "")


class DeckError(ValueError):
    """A deck that cannot be read or run, and where it went wrong.

    ``data_set`` is 1-based, ``card`` is the 1-based line number in the deck
    file, ``columns`` is (first, last), 1-based and inclusive; ``text`` is what
    was found there and ``expected`` what should have been.  Any of them may
    be None.  ``partial`` holds the results of the data sets before the bad
    one; ``listing_before`` the text the original program printed for them
    (``contactsep legacy``); ``listing`` what the restored core wrote for
    the bad one before it failed, if anything.

    Without ``message``, the message is built from the parts, e.g.
    "data set 2, card 9, columns 16-30: found 'ABC', expected a number
    (F15.9)".
    """

    def __init__(self, message: str | None = None, *,
                 data_set: int | None = None, card: int | None = None,
                 columns: tuple[int, int] | None = None,
                 text: str | None = None, expected: str | None = None,
                 partial: list | None = None,
                 listing: str | None = None,
                 listing_before: str = "") -> None:
        self.data_set = data_set
        self.card = card
        self.columns = tuple(columns) if columns is not None else None
        self.text = text
        self.expected = expected
        self.partial = list(partial) if partial is not None else []
        self.listing = listing
        self.listing_before = listing_before
        if message is None:
            problem = []
            if text is not None:
                problem.append(f"found {text!r}")
            if expected is not None:
                problem.append(f"expected {expected}")
            message = (location(data_set, card, self.columns) + ": "
                       + (", ".join(problem) or "bad deck"))
        super().__init__(message)


def printable(message: str) -> str:
    """One line: line ends and TABs become blanks, other control
    characters are named by their code."""
    out = []
    for char in message:
        if char in "\n\r\t\v\f":
            out.append(" ")
        elif char.isprintable():
            out.append(char)
        else:
            out.append(f"<0x{ord(char):02X}>")
    return "".join(out)


def shown(value) -> str:
    """repr(value) for a message, a long one cut (10**400 is 401
    digits): 'an integer of 401 digits'."""
    if isinstance(value, int) and abs(value) > 10**30:
        # (repr of an int past 4300 digits is itself an error)
        return f"an integer of about {int(value.bit_length() * 0.30103) + 1}" \
            f" digits"
    text = repr(value)
    return text if len(text) <= 40 else \
        text[:24] + f"... ({len(text)} characters)"


class InputError(ValueError):
    """Input the package refuses (a design, a study or sweep option, a
    simulation setting); the message is one printable line naming the
    field, what was found and what is expected (whatever the user typed
    in it: :func:`printable`).  Each layer raises it or a subclass of its
    own."""

    def __init__(self, message: str = "", *args) -> None:
        super().__init__(printable(str(message)), *args)


class ContactsepWarning(UserWarning):
    """A result that runs but may not mean what it seems (a unit trap, a
    deck beyond what its cards or the beam theory carry, an extreme at the
    end of the window).  Filter it with ``warnings.simplefilter``."""
